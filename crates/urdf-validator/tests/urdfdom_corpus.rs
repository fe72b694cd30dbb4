//! urdfdom's own parser tests as a corpus: every document urdfdom loads, we read without a CRITICAL finding;
//! every document it refuses, we refuse (a CRITICAL finding, or a load error). The files and their source are
//! in `tests/data/urdfdom/` (see `SOURCES.md` there); the few cases where we disagree on purpose say why.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::{Path, PathBuf};

use urdf_validator::diagnostics::finding::Severity;
use urdf_validator::report::FindingReport;
use urdf_validator::{validate, validate_text, Options};

/// What urdfdom does with a document.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Urdfdom {
    /// `parseURDF` returns a model.
    Loads,
    /// `parseURDF` returns null.
    Refuses,
}
use Urdfdom::{Loads, Refuses};

/// One case: where it comes from, what urdfdom does, and — when we deliberately differ — the rule we fire
/// instead and why.
struct Case {
    name: &'static str,
    urdfdom: Urdfdom,
    disagreement: Option<Disagreement>,
}

struct Disagreement {
    /// The rule whose CRITICAL finding makes us refuse what urdfdom loads.
    rule: &'static str,
    why: &'static str,
}

/// Links with two parent joints: urdfdom's `ModelInterface::initTree` overwrites a link's parent joint
/// without complaint (the last joint in name order wins), so the tree it builds drops joint `j1`.
const TWO_PARENTS: &str = "the three urdf_unit_test documents join l1 to l2 by two joints (j1 and j2); \
urdfdom's initTree keeps the last one silently and loads a tree without j1, KDL and robot_state_publisher \
then publish one of the two frames; a link with two parent joints is a loop, which we refuse (U103)";

fn case(name: &'static str, urdfdom: Urdfdom) -> Case {
    Case {
        name,
        urdfdom,
        disagreement: None,
    }
}

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/urdfdom")
}

/// Our verdict: `Err(reason)` when we refuse (a load error or a CRITICAL finding), else the findings.
fn verdict(result: Result<Vec<FindingReport>, String>) -> Result<Vec<FindingReport>, Vec<String>> {
    match result {
        Err(load_error) => Err(vec![format!("load error: {load_error}")]),
        Ok(findings) => {
            let critical: Vec<String> = findings
                .iter()
                .filter(|f| f.severity == Severity::Critical)
                .map(|f| format!("{} {}", f.rule, f.message))
                .collect();
            if critical.is_empty() {
                Ok(findings)
            } else {
                Err(critical)
            }
        }
    }
}

fn check(case: &Case, result: Result<Vec<FindingReport>, String>, failures: &mut Vec<String>) {
    let ours = verdict(result);
    match (&case.disagreement, case.urdfdom, &ours) {
        (None, Loads, Ok(_)) | (None, Refuses, Err(_)) => {}
        (None, Loads, Err(critical)) => failures.push(format!(
            "{}: urdfdom loads it, we refuse it: {critical:?}",
            case.name
        )),
        (None, Refuses, Ok(findings)) => failures.push(format!(
            "{}: urdfdom refuses it, we give no CRITICAL: {:?}",
            case.name,
            findings
                .iter()
                .map(|f| format!("{} {}", f.rule, f.message))
                .collect::<Vec<_>>()
        )),
        (Some(d), _, Err(critical)) if critical.iter().any(|c| c.starts_with(d.rule)) => {
            assert!(!d.why.is_empty());
        }
        (Some(d), _, _) => failures.push(format!(
            "{}: recorded as a deliberate disagreement ({}: {}) but we now give {ours:?}; update the table",
            case.name,
            d.rule,
            d.why
        )),
    }
}

fn run_file(path: &Path) -> Result<Vec<FindingReport>, String> {
    validate(path, &Options::default())
        .map(|v| v.report.findings)
        .map_err(|e| e.to_string())
}

fn run_text(text: &str) -> Result<Vec<FindingReport>, String> {
    validate_text(
        text.to_string(),
        Path::new("inline.urdf"),
        &Options::default(),
    )
    .map(|v| v.report.findings)
    .map_err(|e| e.to_string())
}

/// The documents of `urdf_unit_test.cpp` and `urdf_version_test.cpp`, copied as files.
#[test]
fn urdfdom_test_documents() {
    let two_parents = |name| Case {
        name,
        urdfdom: Loads,
        disagreement: Some(Disagreement {
            rule: "U103",
            why: TWO_PARENTS,
        }),
    };
    let cases = [
        // urdf_unit_test.cpp: each goes on to read the model, so urdfdom loads it.
        two_parents("parse_joint_doubles"),
        two_parents("parse_link_doubles"),
        two_parents("parse_color_doubles"),
        // urdf_version_test.cpp
        case("test_version_wrong_type", Refuses), // version="foo"
        case("test_version_unsupported_version", Refuses), // version="2"
        case("test_version_not_specified", Loads),
        case("test_version_one_int", Refuses), // version="1"
        case("test_version_one_float", Loads), // version="1.0"
    ];
    let mut failures = Vec::new();
    for case in &cases {
        let path = data_dir().join(format!("{}.urdf", case.name));
        assert!(path.is_file(), "{} is missing", path.display());
        check(case, run_file(&path), &mut failures);
    }
    // Every copied document has a case.
    let mut listed: Vec<String> = std::fs::read_dir(data_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "urdf"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    listed.sort();
    let mut named: Vec<String> = cases.iter().map(|c| c.name.to_string()).collect();
    named.sort();
    assert_eq!(
        listed, named,
        "a .urdf in tests/data/urdfdom without a case"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `urdf_version_test.cpp`'s `URDF_VERSION_CLASS` strings, each put on a robot with one link: urdfdom refuses
/// every string its `URDFVersion` constructor throws on, and every version other than 1.0 / 1.1 / 1.2.
#[test]
fn urdfdom_version_strings() {
    let cases = [
        ("1.0", Loads),        // test_correct_string
        ("1.0.0", Refuses),    // test_too_many_dots
        ("1.", Refuses),       // test_not_enough_numbers
        (".1", Refuses),       // test_no_major_number
        ("-1.0", Refuses),     // test_negative_major_number
        ("1.-1", Refuses),     // test_negative_minor_number
        ("abc", Refuses),      // test_no_numbers
        ("a.c", Refuses),      // test_dots_no_numbers
        ("1.c", Refuses),      // test_dots_one_number
        ("1.0~pre6", Refuses), // test_trailing_junk
        // Read off URDFVersion / parseURDF rather than a gtest: strtol skips leading whitespace and takes a
        // sign, 1.1 (urdfdom 5.1) and 1.2 (urdfdom 6.0) are read, others are not.
        (" 1.0", Loads),
        ("+1.00", Loads),
        ("1.-0", Loads),
        ("1.1", Loads),
        ("1.2", Loads),
        ("1.3", Refuses),
        ("2.0", Refuses),
        ("0.9", Refuses),
        ("1.0 ", Refuses),
        ("", Refuses),
    ];
    let mut failures = Vec::new();
    for (version, urdfdom) in cases {
        let text = format!(
            "<robot name=\"test\" version=\"{version}\">\n  <link name=\"l1\"/>\n</robot>\n"
        );
        let name = Box::leak(format!("version {version:?}").into_boxed_str());
        let result = run_text(&text);
        if urdfdom == Refuses {
            // The refusal is U011 at the attribute, not some other rule.
            if let Ok(findings) = &result {
                if !findings
                    .iter()
                    .any(|f| f.rule == "U011" && f.line == Some(1) && f.column == Some(29))
                {
                    failures.push(format!("{name}: no U011 at 1:29"));
                }
            }
        }
        check(&case(name, urdfdom), result, &mut failures);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The URDF 1.1 cases urdfdom 5.1 added after the copied commit (`urdf_schema_quaternion_test.cpp`,
/// `urdf_schema_capsule_geometry_test.cpp`), rewritten from their names and log in ros/urdfdom#238.
#[test]
fn urdfdom_1_1_cases() {
    let robot = |version: &str, origin: &str, shape: &str| {
        format!(
            "<robot name=\"test\"{version}>\n  <link name=\"link1\">\n    <visual>\n      <origin {origin}/>\n      <geometry>{shape}</geometry>\n    </visual>\n  </link>\n</robot>\n"
        )
    };
    let v10 = " version=\"1.0\"";
    let v11 = " version=\"1.1\"";
    let sphere = "<sphere radius=\"1\"/>";
    let capsule = "<capsule radius=\"0.5\" length=\"2\"/>";
    let rpy = "rpy=\"0 0 1.5707963267948966\"";
    let quat = "quat_xyzw=\"0 0 0.7071067811865476 0.7071067811865476\"";
    let both = format!("{rpy} {quat}");
    let cases = [
        ("parse_rot_rpy_version_1_0", robot(v10, rpy, sphere), Loads),
        // "Ignoring quat_xyzw attribute requiring URDF version 1.1 since specified version is 1.0."
        (
            "parse_rot_quat_ignored_version_1_0",
            robot(v10, quat, sphere),
            Loads,
        ),
        (
            "parse_rot_quat_version_1_1",
            robot(v11, quat, sphere),
            Loads,
        ),
        (
            "parse_rot_both_quat_ignored_version_1_0",
            robot(v10, &both, sphere),
            Loads,
        ),
        // "Both rpy and quat_xyzw orientations are defined. Use either one or the other."
        (
            "parse_rot_both_version_1_1",
            robot(v11, &both, sphere),
            Refuses,
        ),
        ("parse_rot_quat_no_version", robot("", quat, sphere), Loads),
        (
            "parse_capsule_geometry_version_1_1",
            robot(v11, rpy, capsule),
            Loads,
        ),
        // "Ignoring capsule ... since specified version is 1.0." then "Could not parse visual element".
        (
            "parse_capsule_geometry_ignored_version_1_0",
            robot(v10, rpy, capsule),
            Refuses,
        ),
        (
            "parse_capsule_geometry_no_version",
            robot("", rpy, capsule),
            Refuses,
        ),
        // Vector4::init: exactly four numbers.
        (
            "parse_rot_quat_three_numbers_version_1_1",
            robot(v11, "quat_xyzw=\"0 0 1\"", sphere),
            Refuses,
        ),
        // Rotation::normalize: a zero quaternion is the identity, not an error.
        (
            "parse_rot_quat_zero_version_1_1",
            robot(v11, "quat_xyzw=\"0 0 0 0\"", sphere),
            Loads,
        ),
    ];
    let mut failures = Vec::new();
    for (name, text, urdfdom) in &cases {
        check(&case(name, *urdfdom), run_text(text), &mut failures);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
