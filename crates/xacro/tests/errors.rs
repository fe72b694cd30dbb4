//! Errors: the class, a file:line:col location and the include / macro stack, for every error fixture.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::{Path, PathBuf};

use xacro::{expand_file, ErrorKind, Options};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

fn options() -> Options {
    Options {
        env: Some(std::sync::Arc::new(|_: &str| None)),
        ..Options::default()
    }
}

#[test]
fn error_fixtures_have_class_and_location() {
    use ErrorKind::*;
    // (fixture, class, line, column, text the message must contain)
    let cases: &[(&str, ErrorKind, usize, usize, &str)] = &[
        (
            "error_undefined_property.xacro",
            UndefinedProperty,
            5,
            18,
            "did you mean 'wheel_radius'?",
        ),
        (
            "error_undefined_arg.xacro",
            UndefinedArgument,
            4,
            15,
            "did you mean 'use_gpu'?",
        ),
        (
            "error_unknown_macro.xacro",
            UnknownMacro,
            4,
            3,
            "did you mean 'wheel'?",
        ),
        (
            "error_missing_param.xacro",
            MissingParameter,
            4,
            3,
            "[radius]",
        ),
        (
            "error_unknown_param.xacro",
            UnknownParameter,
            4,
            28,
            "\"radius\"",
        ),
        (
            "error_missing_include.xacro",
            IncludeNotFound,
            3,
            28,
            "inc/missing_file.xacro",
        ),
        ("error_bad_condition.xacro", BadCondition, 3, 20, "maybe"),
        ("error_invalid_xml.xacro", XmlParse, 4, 1, ""),
        (
            "error_not_enough_blocks.xacro",
            Block,
            4,
            3,
            "Not enough blocks",
        ),
        (
            "error_unused_block.xacro",
            Block,
            4,
            18,
            "Unused block \"two\"",
        ),
        (
            "error_package_not_found.xacro",
            PackageNotFound,
            3,
            28,
            "no_such_package_xyz",
        ),
        (
            "error_circular.xacro",
            CircularProperty,
            3,
            35,
            "a -> b -> a",
        ),
        ("error_dunder.xacro", InvalidName, 3, 15, "__import__"),
        (
            "error_unknown_substitution.xacro",
            Substitution,
            3,
            15,
            "bogus",
        ),
        (
            "error_env_unset.xacro",
            Substitution,
            3,
            15,
            "XACRO_SURELY_UNSET_VARIABLE",
        ),
        (
            "error_missing_attribute.xacro",
            MissingAttribute,
            3,
            3,
            "default",
        ),
        ("error_undefined_block.xacro", Block, 3, 3, "nothing"),
        (
            "error_zero_division.xacro",
            Expression,
            4,
            21,
            "ZeroDivisionError",
        ),
        ("error_recursion.xacro", Limit, 3, 55, "runaway"),
        (
            "error_include_cycle.xacro",
            IncludeCycle,
            3,
            3,
            "cycle_a.xacro",
        ),
        ("error_fatal.xacro", Fatal, 3, 15, "stop here"),
    ];
    let mut failures = Vec::new();
    for (name, kind, line, col, text) in cases {
        let e = match expand_file(&fixture(name), &options()) {
            Ok(_) => {
                failures.push(format!("{name}: expanded without error"));
                continue;
            }
            Err(e) => e,
        };
        let loc = e.location.clone();
        let got = loc.as_ref().map(|l| (l.line, l.col));
        let file_ok = loc
            .as_ref()
            .is_some_and(|l| l.path.to_string_lossy().contains("fixtures"));
        if e.kind != *kind || got != Some((*line, *col)) || !file_ok || !e.message.contains(text) {
            failures.push(format!("{name}: expected {kind:?} at {line}:{col} containing {text:?}, got {:?} at {got:?}: {e}", e.kind));
        }
        let shown = e.to_string();
        assert!(shown.starts_with(&format!(
            "{}:",
            loc.map(|l| l.path.display().to_string())
                .unwrap_or_default()
        )));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn errors_inside_macros_and_includes_show_the_stack() {
    let e = expand_file(&fixture("error_missing_param.xacro"), &options()).unwrap_err();
    assert!(e.stack.is_empty(), "the call itself is at the top level");
    let e = expand_file(&fixture("error_include_cycle.xacro"), &options()).unwrap_err();
    let shown = e.to_string();
    assert!(shown.contains("included at"), "{shown}");
    assert!(e.stack.len() >= 2, "{shown}");
    let e = expand_file(&fixture("error_recursion.xacro"), &options()).unwrap_err();
    assert!(
        e.to_string()
            .lines()
            .nth(1)
            .is_some_and(|l| l.starts_with("  in macro 'forever' called at ")),
        "{e}"
    );
}

#[test]
fn invalid_xml_in_an_included_file_is_located_there_with_the_include() {
    let e = expand_file(&fixture("error_included_invalid_xml.xacro"), &options()).unwrap_err();
    assert_eq!(e.kind, ErrorKind::XmlParse);
    let loc = e.location.clone().expect("located");
    assert!(loc.path.ends_with("inc/broken.xacro"), "{e}");
    assert_eq!((loc.line, loc.col), (5, 3), "{e}");
    assert_eq!(e.stack.len(), 1, "{e}");
    assert_eq!((e.stack[0].location.line, e.stack[0].location.col), (3, 3));
    assert!(e.to_string().contains("included at"), "{e}");
}

#[test]
fn dirname_is_the_directory_of_the_current_file() {
    let dir = fixture("inc");
    let text = "<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\"><d v=\"$(dirname)\"/></robot>";
    let x =
        xacro::expand_str(text, &dir.join("virtual.xacro"), &Options::default()).expect("expands");
    assert!(
        x.xml.contains(&format!(
            "v=\"{}\"",
            std::path::absolute(&dir).unwrap().display()
        )),
        "{}",
        x.xml
    );
}
