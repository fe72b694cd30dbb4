//! Source mapping: every output start tag, attribute and text maps back to where it was written, with the
//! macro calls and includes that produced it.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::{Path, PathBuf};

use xacro::{expand_file, Expansion, FrameKind, Options, Piece};

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/source_map/robot.urdf.xacro")
}

/// `file-name:line:col` of the origin of output byte `at`, and its stack as `kind name file:line`.
fn describe(x: &Expansion, at: usize) -> (String, Vec<String>) {
    let origin = x
        .map
        .origin(at)
        .unwrap_or_else(|| panic!("no origin at {at}"));
    let file = &x.sources[origin.file];
    let (line, col) = file.line_col(origin.span.start);
    let name = file
        .path
        .file_name()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned();
    let stack = x
        .map
        .stack(origin)
        .map(|f| {
            let src = &x.sources[f.file];
            let (l, _) = src.line_col(f.span.start);
            let kind = match f.kind {
                FrameKind::Macro => "macro",
                FrameKind::Include => "include",
            };
            let short = Path::new(&f.name)
                .file_name()
                .map_or(f.name.clone(), |n| n.to_string_lossy().into_owned());
            format!(
                "{kind} {short} {}:{l}",
                src.path.file_name().unwrap_or_default().to_string_lossy()
            )
        })
        .collect();
    (format!("{name}:{line}:{col}"), stack)
}

fn offset_of(x: &Expansion, needle: &str) -> usize {
    x.xml
        .find(needle)
        .unwrap_or_else(|| panic!("{needle:?} not in output:\n{}", x.xml))
}

#[test]
fn attribute_inside_a_macro_maps_to_the_macro_body_with_the_call_site() {
    let x = expand_file(&fixture(), &Options::default()).expect("expands");
    // The broken inertia value, written literally in the macro body (line 8).
    let at = offset_of(&x, "ixx=\"-1\"") + "ixx=\"".len();
    assert_eq!(x.map.entry_at(at).map(|e| e.piece), Some(Piece::AttrValue));
    let (loc, stack) = describe(&x, at);
    assert_eq!(loc, "robot.urdf.xacro:8:23");
    assert_eq!(stack, ["macro heavy_link robot.urdf.xacro:12"]);
    // The attribute name maps too.
    let (loc, _) = describe(&x, offset_of(&x, "ixx=\"-1\""));
    assert_eq!(loc, "robot.urdf.xacro:8:18");
    // An attribute computed from a parameter maps to the expression in the body.
    let (loc, stack) = describe(
        &x,
        offset_of(&x, "<mass value=\"2\"") + "<mass value=\"".len(),
    );
    assert_eq!(loc, "robot.urdf.xacro:7:22");
    assert_eq!(stack, ["macro heavy_link robot.urdf.xacro:12"]);
    // The start tag of an element from the macro.
    let (loc, _) = describe(&x, offset_of(&x, "<inertia "));
    assert_eq!(loc, "robot.urdf.xacro:8:9");
}

#[test]
fn includes_and_blocks_map_to_where_they_were_written() {
    let x = expand_file(&fixture(), &Options::default()).expect("expands");
    let (loc, stack) = describe(&x, offset_of(&x, "<from_include"));
    assert_eq!(loc, "parts.xacro:8:3");
    assert_eq!(stack, ["include parts.xacro robot.urdf.xacro:3"]);
    // The macro's own element comes from the included file, instantiated by the call in the entry file.
    let (loc, stack) = describe(&x, offset_of(&x, "<wrapper"));
    assert_eq!(loc, "parts.xacro:4:5");
    assert_eq!(stack, ["macro part_with_block robot.urdf.xacro:13"]);
    // The block is where the caller wrote it, in the caller's context (top level).
    let at = offset_of(&x, "written at the call site");
    let (loc, stack) = describe(&x, at);
    assert_eq!(loc, "robot.urdf.xacro:14:26");
    assert!(stack.is_empty(), "{stack:?}");
    let (loc, stack) = describe(&x, offset_of(&x, "<plain"));
    assert_eq!(loc, "robot.urdf.xacro:16:3");
    assert!(stack.is_empty());
    // Indentation and end tags map to nothing.
    assert!(x.map.origin(offset_of(&x, "</robot>")).is_none());
}

#[test]
fn line_col_is_one_based_and_counts_characters() {
    let f = xacro::SourceFile::new("x".into(), "ab\nçd\n".into());
    assert_eq!(f.line_col(0), (1, 1));
    assert_eq!(f.line_col(3), (2, 1));
    assert_eq!(f.line_col(5), (2, 2));
    assert_eq!(f.line_col(100), (3, 1));
}

#[test]
fn every_output_start_tag_is_mapped() {
    let x = expand_file(&fixture(), &Options::default()).expect("expands");
    let doc = roxmltree::Document::parse(&x.xml).expect("output parses");
    for node in doc.descendants().filter(|n| n.is_element()) {
        let origin = x.map.origin(node.range().start);
        assert!(origin.is_some(), "unmapped <{}>", node.tag_name().name());
        for a in node.attributes() {
            let o = x
                .map
                .origin(a.range_value().start)
                .expect("attribute value mapped");
            let src = &x.sources[o.file].text[o.span.clone()];
            assert!(!src.is_empty());
        }
    }
}
