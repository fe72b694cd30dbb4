//! One triggering and one clean document per rule of the registry, plus the behaviours around them
//! (frames, statuses, confidence, malformed input, non-finite numbers, loops, mimics, references, meshes).
//!
//! Every document is an inline raw string whose first line is line 1; expected positions are 1-based
//! (line, column) of the span start, and each expectation names the text found there so that a miscounted
//! expectation fails as a test bug rather than as a library bug.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::fs;
use std::path::{Path, PathBuf};

use urdf_validator::diagnostics::finding::Severity;
use urdf_validator::diagnostics::rules;
use urdf_validator::diagnostics::Section;
use urdf_validator::input::LoadError;
use urdf_validator::report::{ConfidenceLevel, FindingReport, Report, Status};
use urdf_validator::Error;
use urdf_validator::{validate, validate_text, Options, Validation};

// -------------------------------------------------------------------------------------------------
// Helpers
// -------------------------------------------------------------------------------------------------

const FILE: &str = "t.urdf";

fn run_at(urdf: &str, path: &Path) -> Validation {
    validate_text(urdf.to_string(), path, &Options::default()).unwrap_or_else(|e| {
        panic!("expected a parsed document, got LoadError: {e}\n--- input ---\n{urdf}")
    })
}

fn run(urdf: &str) -> Validation {
    run_at(urdf, Path::new(FILE))
}

fn report(urdf: &str) -> Report {
    run(urdf).report
}

fn findings(urdf: &str) -> Vec<FindingReport> {
    report(urdf).findings
}

fn with_code<'a>(findings: &'a [FindingReport], code: &str) -> Vec<&'a FindingReport> {
    findings.iter().filter(|f| f.rule == code).collect()
}

fn lines_of(findings: &[FindingReport], code: &str) -> Vec<u32> {
    with_code(findings, code)
        .iter()
        .map(|f| f.line.unwrap_or(0))
        .collect()
}

fn positions_of(findings: &[FindingReport], code: &str) -> Vec<(u32, u32)> {
    with_code(findings, code)
        .iter()
        .map(|f| (f.line.unwrap_or(0), f.column.unwrap_or(0)))
        .collect()
}

fn the_one<'a>(findings: &'a [FindingReport], code: &str) -> &'a FindingReport {
    let hits = with_code(findings, code);
    assert_eq!(
        hits.len(),
        1,
        "{code}: expected exactly one finding\n{}",
        describe(findings)
    );
    hits[0]
}

/// All findings, one per line, for failure messages.
fn describe(findings: &[FindingReport]) -> String {
    let mut out = String::from("findings:\n");
    for f in findings {
        out.push_str(&format!(
            "  {} {:?} {}:{} {} (help: {:?})\n",
            f.rule,
            f.severity,
            f.line.unwrap_or(0),
            f.column.unwrap_or(0),
            f.message,
            f.help
        ));
    }
    out
}

/// The text of `urdf` from 1-based (line, column), columns counted in characters.
fn text_at(urdf: &str, line: u32, column: u32) -> String {
    urdf.split('\n')
        .nth(line as usize - 1)
        .map(|l| l.chars().skip(column as usize - 1).collect())
        .unwrap_or_default()
}

/// `code` fires exactly once, at (line, column), where the source reads `token`; name, severity and file
/// agree with the registry.
fn assert_fires(code: &str, urdf: &str, line: u32, column: u32, token: &str) {
    let rule = rules::find(code).unwrap_or_else(|| panic!("{code} is not in the registry"));
    assert!(
        text_at(urdf, line, column).starts_with(token),
        "test bug for {code}: the text at {line}:{column} is {:?}, not {token:?}",
        text_at(urdf, line, column)
    );
    let all = findings(urdf);
    assert_eq!(
        positions_of(&all, code),
        vec![(line, column)],
        "{code} ({}) should fire once at {line}:{column} ({token:?})\n{}",
        rule.name,
        describe(&all)
    );
    let hit = the_one(&all, code);
    assert_eq!(hit.name, rule.name, "{code}: rule name");
    assert_eq!(hit.severity, rule.severity, "{code}: severity");
    assert_eq!(hit.file.as_deref(), Some(FILE), "{code}: file");
    assert!(!hit.message.is_empty(), "{code}: empty message");
}

/// `code` does not fire on `urdf` (which must still parse).
fn assert_absent(code: &str, urdf: &str) {
    let all = findings(urdf);
    assert!(
        lines_of(&all, code).is_empty(),
        "{code} fired on the clean document\n{}",
        describe(&all)
    );
}

/// A chain of `n` bare links joined by fixed joints.
fn chain_of_links(n: usize) -> String {
    let mut out = String::from("<robot name=\"big\">\n");
    for i in 0..n {
        out.push_str(&format!("  <link name=\"l{i}\"/>\n"));
    }
    for i in 1..n {
        out.push_str(&format!(
            "  <joint name=\"j{i}\" type=\"fixed\">\n    <parent link=\"l{}\"/>\n    <child link=\"l{i}\"/>\n  </joint>\n",
            i - 1
        ));
    }
    out.push_str("</robot>\n");
    out
}

/// A fresh directory under the system temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("urdf-validator-rules-{}-{tag}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("create temp dir");
        TempDir(dir)
    }

    fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

/// The process-independent LoadError checks: an XML error whose Display is `t.urdf:LINE:COL: ...`.
fn assert_xml_load_error(input: &str) {
    let error = match validate_text(input.to_string(), Path::new(FILE), &Options::default()) {
        Err(e) => e,
        Ok(v) => panic!(
            "{input:?} should not parse\n{}",
            describe(&v.report.findings)
        ),
    };
    let shown = error.to_string();
    let Error::Load(LoadError::Xml { line, column, .. }) = &error else {
        panic!("{input:?}: expected LoadError::Xml, got {error:?}");
    };
    assert!(*line >= 1 && *column >= 1, "{input:?}: {shown}");
    let rest = shown
        .strip_prefix("t.urdf:")
        .unwrap_or_else(|| panic!("{input:?}: Display lacks 't.urdf:': {shown}"));
    let mut parts = rest.splitn(3, ':');
    let shown_line: u32 = parts
        .next()
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{input:?}: no line in {shown}"));
    let shown_column: u32 = parts
        .next()
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{input:?}: no column in {shown}"));
    assert_eq!((shown_line, shown_column), (*line, *column), "{shown}");
    assert!(!shown.contains('\n'), "one line: {shown}");
}

// -------------------------------------------------------------------------------------------------
// One triggering and one clean document per rule
// -------------------------------------------------------------------------------------------------

/// `mod $module { fires, clean }`: `fires` asserts the code fires once at (line, column) over `token`,
/// `clean` asserts it is absent from the near-identical fixed document.
macro_rules! rule_case {
    (
        $module:ident, $code:literal,
        fires: $fires:expr,
        at: ($line:expr, $column:expr, $token:expr),
        clean: $clean:expr $(,)?
    ) => {
        mod $module {
            use super::*;

            pub const CODE: &str = $code;

            #[test]
            fn fires() {
                assert_fires(CODE, &$fires, $line, $column, $token);
            }

            #[test]
            fn clean() {
                assert_absent(CODE, &$clean);
            }
        }
    };
}

/// Every rule with a case below; the guard test checks it against the registry.
const COVERED: &[&str] = &[
    u001_not_a_robot::CODE,
    u002_missing_attribute::CODE,
    u003_invalid_number::CODE,
    u004_non_finite_value::CODE,
    u005_unknown_element::CODE,
    u006_unknown_attribute::CODE,
    u007_unknown_joint_type::CODE,
    u008_missing_geometry::CODE,
    u009_no_links::CODE,
    u101_duplicate_name::CODE,
    u102_undefined_link::CODE,
    u103_kinematic_loop::CODE,
    u104_multiple_roots::CODE,
    u105_too_many_links::CODE,
    u201_missing_inertial::CODE,
    u202_negative_mass::CODE,
    u203_zero_mass::CODE,
    u204_zero_inertia::CODE,
    u205_inertia_not_positive_definite::CODE,
    u206_inertia_triangle_inequality::CODE,
    u207_massless_geometry::CODE,
    u208_inertia_far_from_geometry::CODE,
    u209_inertia_outside_geometry::CODE,
    u210_implausible_density::CODE,
    u301_missing_limit::CODE,
    u302_incomplete_limit::CODE,
    u303_missing_effort_velocity::CODE,
    u304_inverted_limits::CODE,
    u305_empty_joint_range::CODE,
    u306_non_positive_effort::CODE,
    u307_non_positive_velocity::CODE,
    u308_continuous_joint_limits::CODE,
    u309_zero_axis::CODE,
    u310_non_unit_axis::CODE,
    u311_mimic_undefined_joint::CODE,
    u312_mimic_cycle::CODE,
    u313_floating_joint::CODE,
    u401_transmission_undefined_joint::CODE,
    u402_gazebo_undefined_reference::CODE,
    u403_ros2_control_undefined_joint::CODE,
    u404_undefined_material::CODE,
    u501_mesh_not_found::CODE,
    u502_visual_without_collision::CODE,
    u503_invalid_geometry_size::CODE,
    u504_mesh_in_millimetres::CODE,
    u505_mesh_unreadable::CODE,
    u601_links_in_contact_at_reference::CODE,
    u011_unsupported_urdf_version::CODE,
    u012_late_xml_declaration::CODE,
    u014_unbound_namespace_prefix::CODE,
    "U010", // needs a xacro file: xacro_warnings_are_u010_at_the_xacro_tag below
    "U602", // needs an SRDF file: a_broken_or_stale_srdf_is_u602_and_the_rest_runs below
    // Verdict rules: tests/verdicts.rs (statics, stability, requested checks) and tests/workspace.rs
    // (task, orientation, self-collision), each firing with its position and absent on a sound robot.
    "U701",
    "U702",
    "U703",
    "U710",
    "U711",
    "U720",
    "U721",
    "U722",
    "U723",
    "U724",
    "U730",
    // tests/classification.rs: a y-up quadruped (fires at the root link) and the same robot turned z-up
    // in the file (absent).
    "U731",
    // The MuJoCo pass: tests/deep.rs (they need MuJoCo from the test venv).
    "U740",
    "U741",
    "U742",
    "U743",
    "U744",
    "U745",
    "U746",
    "U747",
    "U748",
    // U750–U761: tests/simulators.rs (the `--simulator` load profiles).
    "U750",
    "U751",
    "U752",
    "U753",
    "U754",
    "U755",
    "U756",
    "U757",
    "U758",
    "U759",
    "U760",
    "U761",
    // tests/symmetry.rs: a lopsided cart and its true twin.
    "U770",
    "U790",
    // U020–U029: tests/sdf.rs (SDFormat input; each at its line, and sdformat's invalid files).
    "U020",
    "U021",
    "U022",
    "U023",
    "U024",
    "U025",
    "U026",
    "U027",
    "U028",
    "U029",
    // U030–U033: tests/mjcf.rs (MJCF input: each at its line, includes, hostile values).
    "U030",
    "U031",
    "U032",
    "U033",
    // U034–U037: tests/mjcf.rs (the MJCF-only actuator and inertia rules: each at its line, and absent
    // on the repaired model).
    "U034",
    "U035",
    "U036",
    "U037",
    // U038: tests/mjcf.rs (connect and weld equalities close loops).
    "U038",
    // U039: tests/mjcf.rs (a keyframe past a joint's range or an actuator's ctrlrange).
    "U039",
    // U040: tests/mjcf.rs (statics follow the model's gravity).
    "U040",
    // U041, U043: tests/mjcf.rs (a ctrlrange past the joint's range, by 1 % or more and by less, not at
    // rounding).
    "U041",
    "U043",
    // U042 and U603 (MJCF): tests/mjcf_mujoco_agreement.rs (each case against MuJoCo's contact list);
    // U603 on URDF: tests/stability.rs (a link below the declared ground).
    "U042",
    "U603",
    // Untrusted mode's refusals: u013_access_refused below; crates/cli/tests/security.rs runs 33 hostile inputs.
    "U013",
    // Suppressions (tests/suppressions.rs and crates/cli/tests/config.rs cover the configuration side).
    u801_unused_suppression::CODE,
    u802_unknown_rule_code::CODE,
];

#[test]
fn every_rule_in_the_registry_has_a_case() {
    let missing: Vec<&str> = rules::ALL
        .iter()
        .map(|r| r.code)
        .filter(|code| !COVERED.contains(code))
        .collect();
    assert!(
        missing.is_empty(),
        "rules without a trigger/clean case in tests/rules.rs: {missing:?}"
    );
    for code in COVERED {
        assert!(
            rules::find(code).is_some(),
            "{code} is listed in COVERED but not in rules::ALL"
        );
    }
    let mut sorted = COVERED.to_vec();
    sorted.dedup();
    assert_eq!(sorted.len(), COVERED.len(), "COVERED lists a code twice");
}

rule_case! {
    u001_not_a_robot, "U001",
    fires: include_str!("data/rule-examples/u001/fail.urdf"),
    at: (2, 1, "<scene"),
    clean: include_str!("data/rule-examples/u001/pass.urdf"),
}

rule_case! {
    u002_missing_attribute, "U002",
    fires: include_str!("data/rule-examples/u002/fail.urdf"),
    at: (5, 9, "<box/>"),
    clean: include_str!("data/rule-examples/u002/pass.urdf"),
}

rule_case! {
    u003_invalid_number, "U003",
    fires: include_str!("data/rule-examples/u003/fail.urdf"),
    at: (5, 20, "1 1\""),
    clean: include_str!("data/rule-examples/u003/pass.urdf"),
}

rule_case! {
    u004_non_finite_value, "U004",
    fires: include_str!("data/rule-examples/u004/fail.urdf"),
    at: (4, 20, "nan\""),
    clean: include_str!("data/rule-examples/u004/pass.urdf"),
}

rule_case! {
    u005_unknown_element, "U005",
    fires: include_str!("data/rule-examples/u005/fail.urdf"),
    at: (3, 5, "<inertia"),
    clean: include_str!("data/rule-examples/u005/pass.urdf"),
}

rule_case! {
    u006_unknown_attribute, "U006",
    fires: include_str!("data/rule-examples/u006/fail.urdf"),
    at: (2, 21, "mass=\"1\""),
    clean: include_str!("data/rule-examples/u006/pass.urdf"),
}

rule_case! {
    u007_unknown_joint_type, "U007",
    fires: include_str!("data/rule-examples/u007/fail.urdf"),
    at: (4, 25, "hinge\""),
    clean: include_str!("data/rule-examples/u007/pass.urdf"),
}

rule_case! {
    u008_missing_geometry, "U008",
    fires: include_str!("data/rule-examples/u008/fail.urdf"),
    at: (3, 5, "<visual>"),
    clean: include_str!("data/rule-examples/u008/pass.urdf"),
}

rule_case! {
    u009_no_links, "U009",
    fires: include_str!("data/rule-examples/u009/fail.urdf"),
    // A finding about the whole robot points at its name, not at the whole element.
    at: (2, 14, "empty"),
    clean: include_str!("data/rule-examples/u009/pass.urdf"),
}

rule_case! {
    u101_duplicate_name, "U101",
    fires: include_str!("data/rule-examples/u101/fail.urdf"),
    at: (3, 15, "a\""),
    clean: include_str!("data/rule-examples/u101/pass.urdf"),
}

rule_case! {
    u102_undefined_link, "U102",
    fires: include_str!("data/rule-examples/u102/fail.urdf"),
    at: (6, 18, "arm_lnk\""),
    clean: include_str!("data/rule-examples/u102/pass.urdf"),
}

rule_case! {
    u103_kinematic_loop, "U103",
    fires: include_str!("data/rule-examples/u103/fail.urdf"),
    at: (9, 3, "<joint name=\"j2\""),
    clean: include_str!("data/rule-examples/u103/pass.urdf"),
}

rule_case! {
    u104_multiple_roots, "U104",
    fires: include_str!("data/rule-examples/u104/fail.urdf"),
    at: (4, 15, "orphan\""),
    clean: include_str!("data/rule-examples/u104/pass.urdf"),
}

rule_case! {
    u105_too_many_links, "U105",
    fires: chain_of_links(51),
    at: (1, 14, "big\""),
    clean: chain_of_links(50),
}

rule_case! {
    u201_missing_inertial, "U201",
    fires: include_str!("data/rule-examples/u201/fail.urdf"),
    at: (3, 3, "<link name=\"arm\""),
    clean: include_str!("data/rule-examples/u201/pass.urdf"),
}

rule_case! {
    u202_negative_mass, "U202",
    fires: include_str!("data/rule-examples/u202/fail.urdf"),
    at: (4, 20, "-1\""),
    clean: include_str!("data/rule-examples/u202/pass.urdf"),
}

rule_case! {
    u203_zero_mass, "U203",
    fires: include_str!("data/rule-examples/u203/fail.urdf"),
    at: (5, 20, "0\""),
    clean: include_str!("data/rule-examples/u203/pass.urdf"),
}

rule_case! {
    u204_zero_inertia, "U204",
    fires: include_str!("data/rule-examples/u204/fail.urdf"),
    at: (6, 7, "<inertia"),
    clean: include_str!("data/rule-examples/u204/pass.urdf"),
}

rule_case! {
    u205_inertia_not_positive_definite, "U205",
    fires: include_str!("data/rule-examples/u205/fail.urdf"),
    at: (6, 7, "<inertia"),
    clean: include_str!("data/rule-examples/u205/pass.urdf"),
}

rule_case! {
    // A placeholder 1e-3 on an 8 kg cube: 53× below the geometry's.
    u208_inertia_far_from_geometry, "U208",
    fires: include_str!("data/rule-examples/u208/fail.urdf"),
    at: (6, 7, "<inertia"),
    // 2.5× off: within the factor 3.
    clean: include_str!("data/rule-examples/u208/pass.urdf"),
}

rule_case! {
    // 1 kg·m² on 8 kg in a 0.2 m box: the second moment along x would be 0.5 kg·m², and no body of 8 kg
    // inside [-0.1, 0.1] centred at 0 has more than 8 × 0.1² = 0.08.
    u209_inertia_outside_geometry, "U209",
    fires: include_str!("data/rule-examples/u209/fail.urdf"),
    at: (6, 7, "<inertia"),
    // 0.15: more than 3× the cube's (U208), still possible inside the box (all mass on the faces).
    clean: include_str!("data/rule-examples/u209/pass.urdf"),
}

rule_case! {
    // 8,000 kg in 8 dm³: 1,000,000 kg/m³ (grams written as kilograms); 8 kg is 1,000 kg/m³.
    u210_implausible_density, "U210",
    fires: include_str!("data/rule-examples/u210/fail.urdf"),
    at: (5, 20, "8000\""),
    clean: include_str!("data/rule-examples/u210/pass.urdf"),
}

rule_case! {
    u206_inertia_triangle_inequality, "U206",
    fires: include_str!("data/rule-examples/u206/fail.urdf"),
    at: (6, 7, "<inertia"),
    // 1 + 1 = 2: a thin plate, exactly on the boundary.
    clean: include_str!("data/rule-examples/u206/pass.urdf"),
}

rule_case! {
    u207_massless_geometry, "U207",
    fires: include_str!("data/rule-examples/u207/fail.urdf"),
    at: (2, 3, "<link name=\"base\""),
    clean: include_str!("data/rule-examples/u207/pass.urdf"),
}

rule_case! {
    u301_missing_limit, "U301",
    fires: include_str!("data/rule-examples/u301/fail.urdf"),
    at: (4, 3, "<joint name=\"j\""),
    clean: include_str!("data/rule-examples/u301/pass.urdf"),
}

rule_case! {
    u302_incomplete_limit, "U302",
    fires: include_str!("data/rule-examples/u302/fail.urdf"),
    at: (8, 5, "<limit"),
    clean: include_str!("data/rule-examples/u302/pass.urdf"),
}

rule_case! {
    u303_missing_effort_velocity, "U303",
    fires: include_str!("data/rule-examples/u303/fail.urdf"),
    at: (4, 3, "<joint name=\"j\""),
    clean: include_str!("data/rule-examples/u303/pass.urdf"),
}

rule_case! {
    u304_inverted_limits, "U304",
    fires: include_str!("data/rule-examples/u304/fail.urdf"),
    at: (8, 19, "1\" upper"),
    clean: include_str!("data/rule-examples/u304/pass.urdf"),
}

rule_case! {
    u305_empty_joint_range, "U305",
    fires: include_str!("data/rule-examples/u305/fail.urdf"),
    at: (8, 19, "0.5\" upper"),
    clean: include_str!("data/rule-examples/u305/pass.urdf"),
}

rule_case! {
    u306_non_positive_effort, "U306",
    fires: include_str!("data/rule-examples/u306/fail.urdf"),
    at: (8, 41, "0\" velocity"),
    clean: include_str!("data/rule-examples/u306/pass.urdf"),
}

rule_case! {
    u307_non_positive_velocity, "U307",
    fires: include_str!("data/rule-examples/u307/fail.urdf"),
    at: (8, 55, "0\"/>"),
    clean: include_str!("data/rule-examples/u307/pass.urdf"),
}

rule_case! {
    u308_continuous_joint_limits, "U308",
    fires: include_str!("data/rule-examples/u308/fail.urdf"),
    at: (8, 19, "-1\" upper"),
    clean: include_str!("data/rule-examples/u308/pass.urdf"),
}

rule_case! {
    u309_zero_axis, "U309",
    fires: include_str!("data/rule-examples/u309/fail.urdf"),
    at: (7, 16, "0 0 0\""),
    clean: include_str!("data/rule-examples/u309/pass.urdf"),
}

rule_case! {
    u310_non_unit_axis, "U310",
    fires: include_str!("data/rule-examples/u310/fail.urdf"),
    at: (7, 16, "0 0 2\""),
    clean: include_str!("data/rule-examples/u310/pass.urdf"),
}

rule_case! {
    u311_mimic_undefined_joint, "U311",
    fires: include_str!("data/rule-examples/u311/fail.urdf"),
    at: (14, 19, "leadr\""),
    clean: include_str!("data/rule-examples/u311/pass.urdf"),
}

rule_case! {
    u312_mimic_cycle, "U312",
    fires: include_str!("data/rule-examples/u312/fail.urdf"),
    at: (14, 5, "<mimic"),
    clean: include_str!("data/rule-examples/u312/pass.urdf"),
}

rule_case! {
    u313_floating_joint, "U313",
    fires: include_str!("data/rule-examples/u313/fail.urdf"),
    at: (4, 25, "floating\""),
    clean: include_str!("data/rule-examples/u313/pass.urdf"),
}

rule_case! {
    u401_transmission_undefined_joint, "U401",
    fires: include_str!("data/rule-examples/u401/fail.urdf"),
    at: (10, 18, "k\""),
    clean: include_str!("data/rule-examples/u401/pass.urdf"),
}

rule_case! {
    u402_gazebo_undefined_reference, "U402",
    fires: include_str!("data/rule-examples/u402/fail.urdf"),
    at: (3, 22, "bsae\""),
    clean: include_str!("data/rule-examples/u402/pass.urdf"),
}

rule_case! {
    u403_ros2_control_undefined_joint, "U403",
    fires: include_str!("data/rule-examples/u403/fail.urdf"),
    at: (12, 18, "k\""),
    clean: include_str!("data/rule-examples/u403/pass.urdf"),
}

rule_case! {
    u404_undefined_material, "U404",
    fires: include_str!("data/rule-examples/u404/fail.urdf"),
    at: (7, 7, "<material name=\"steel\""),
    clean: include_str!("data/rule-examples/u404/pass.urdf"),
}

/// Written out by hand: the clean document needs a mesh file next to it.
mod u501_mesh_not_found {
    use super::*;

    pub const CODE: &str = "U501";

    const FIRES: &str = r#"<robot name="r">
  <link name="base">
    <collision>
      <geometry>
        <mesh filename="package://nopkg/m.stl"/>
      </geometry>
    </collision>
  </link>
</robot>
"#;

    const CLEAN: &str = r#"<robot name="r">
  <link name="base">
    <collision>
      <geometry>
        <mesh filename="m.stl"/>
      </geometry>
    </collision>
  </link>
</robot>
"#;

    #[test]
    fn fires() {
        assert_fires(CODE, FIRES, 5, 25, "package://nopkg/m.stl\"");
    }

    #[test]
    fn clean() {
        let dir = TempDir::new("u501-clean");
        fs::write(dir.path().join("m.stl"), b"solid m\nendsolid m\n").unwrap();
        let validation = run_at(CLEAN, &dir.path().join("robot.urdf"));
        let all = validation.report.findings;
        assert!(
            lines_of(&all, CODE).is_empty(),
            "{CODE} fired although m.stl exists next to the URDF\n{}",
            describe(&all)
        );
    }
}

rule_case! {
    u502_visual_without_collision, "U502",
    fires: include_str!("data/rule-examples/u502/fail.urdf"),
    at: (2, 3, "<link name=\"base\""),
    clean: include_str!("data/rule-examples/u502/pass.urdf"),
}

rule_case! {
    u503_invalid_geometry_size, "U503",
    fires: include_str!("data/rule-examples/u503/fail.urdf"),
    at: (5, 9, "<box size=\"1 0 1\""),
    clean: include_str!("data/rule-examples/u503/pass.urdf"),
}

/// A unit cube as ASCII STL, `size` units across.
fn cube_stl(size: f64) -> String {
    let mut out = String::from("solid cube\n");
    let corners = |i: usize| {
        [
            (i & 1) as f64 * size,
            ((i >> 1) & 1) as f64 * size,
            ((i >> 2) & 1) as f64 * size,
        ]
    };
    for [a, b, c] in [
        [0, 1, 3],
        [0, 3, 2],
        [4, 6, 7],
        [4, 7, 5],
        [0, 4, 5],
        [0, 5, 1],
        [2, 3, 7],
        [2, 7, 6],
        [0, 2, 6],
        [0, 6, 4],
        [1, 5, 7],
        [1, 7, 3],
    ] {
        out.push_str("facet normal 0 0 0\nouter loop\n");
        for v in [a, b, c].map(corners) {
            out.push_str(&format!("vertex {} {} {}\n", v[0], v[1], v[2]));
        }
        out.push_str("endloop\nendfacet\n");
    }
    out + "endsolid cube\n"
}

/// A link carrying `part.stl` at the end of a 0.1 m joint.
const PART_ROBOT: &str = r#"<robot name="r">
  <link name="base"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="part"/><origin xyz="0.1 0 0"/></joint>
  <link name="part">
    <collision>
      <geometry>
        <mesh filename="part.stl"/>
      </geometry>
    </collision>
  </link>
</robot>
"#;

/// Written out by hand: the mesh file must exist next to the URDF.
mod u504_mesh_in_millimetres {
    use super::*;

    pub const CODE: &str = "U504";

    fn findings_with_part(tag: &str, stl: &str, urdf: &str) -> Vec<FindingReport> {
        let dir = TempDir::new(tag);
        fs::write(dir.path().join("part.stl"), stl).unwrap();
        run_at(urdf, &dir.path().join("robot.urdf")).report.findings
    }

    #[test]
    fn fires() {
        // A 100 mm part exported in millimetres: 100 "metres" next to a 0.1 m joint.
        let all = findings_with_part("u504-fires", &cube_stl(100.0), PART_ROBOT);
        assert_eq!(
            positions_of(&all, CODE),
            vec![(7, 25)],
            "{}",
            describe(&all)
        );
        assert!(text_at(PART_ROBOT, 7, 25).starts_with("part.stl"));
        let hit = the_one(&all, CODE);
        assert_eq!(hit.severity, Severity::Warn);
        assert!(
            hit.help.as_deref().unwrap_or("").contains("0.001"),
            "{:?}",
            hit.help
        );
    }

    #[test]
    fn clean() {
        let scaled = PART_ROBOT.replace(
            r#"filename="part.stl""#,
            r#"filename="part.stl" scale="0.001 0.001 0.001""#,
        );
        let all = findings_with_part("u504-clean", &cube_stl(100.0), &scaled);
        assert!(lines_of(&all, CODE).is_empty(), "{}", describe(&all));
        let metres = findings_with_part("u504-metres", &cube_stl(0.1), PART_ROBOT);
        assert!(lines_of(&metres, CODE).is_empty(), "{}", describe(&metres));
    }

    /// A single link has nothing to compare its mesh with: a 2 m table is a table.
    #[test]
    fn never_on_a_single_link_object() {
        let table = r#"<robot name="table">
  <link name="top">
    <visual><geometry><mesh filename="part.stl"/></geometry></visual>
  </link>
</robot>
"#;
        let all = findings_with_part("u504-object", &cube_stl(2.0), table);
        assert!(lines_of(&all, CODE).is_empty(), "{}", describe(&all));
    }

    /// A 1.5 m rail on a link whose joints sit at its own frame, on a robot 0.8 m across: the mesh is
    /// large next to its link's joints but not next to the robot (the old per-link comparison fired).
    #[test]
    fn not_on_a_metre_scale_mesh_of_a_robot_its_size() {
        let rail = |scale: &str| {
            format!(
                r#"<robot name="gantry">
  <link name="base"/>
  <joint name="mount" type="fixed"><parent link="base"/><child link="rail"/></joint>
  <link name="rail">
    <visual><geometry><mesh filename="part.stl" scale="{scale}"/></geometry></visual>
  </link>
  <joint name="slide" type="prismatic"><parent link="rail"/><child link="carriage"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="1.4" effort="100" velocity="1"/></joint>
  <link name="carriage"/>
  <joint name="drop" type="fixed"><parent link="carriage"/><child link="tool"/><origin xyz="0.6 0 -0.5"/></joint>
  <link name="tool"/>
</robot>
"#
            )
        };
        let metres = findings_with_part("u504-rail", &cube_stl(1.5), &rail("1 1 1"));
        assert!(lines_of(&metres, CODE).is_empty(), "{}", describe(&metres));
        // The same rail exported in millimetres: 1500 m next to a 0.78 m robot.
        let millimetres = findings_with_part("u504-rail-mm", &cube_stl(1500.0), &rail("1 1 1"));
        assert_eq!(
            lines_of(&millimetres, CODE),
            [5],
            "{}",
            describe(&millimetres)
        );
    }
}

/// Written out by hand: the mesh file must exist next to the URDF.
mod u505_mesh_unreadable {
    use super::*;

    pub const CODE: &str = "U505";

    #[test]
    fn fires() {
        let dir = TempDir::new("u505-fires");
        fs::write(
            dir.path().join("part.stl"),
            "solid broken\nfacet normal 0 0 0\nouter loop\nvertex 1 x 2\n",
        )
        .unwrap();
        let all = run_at(PART_ROBOT, &dir.path().join("robot.urdf"))
            .report
            .findings;
        assert_eq!(
            positions_of(&all, CODE),
            vec![(7, 25)],
            "{}",
            describe(&all)
        );
        let hit = the_one(&all, CODE);
        assert!(
            hit.message.contains("part.stl") && hit.message.contains("line 4"),
            "{}",
            hit.message
        );
    }

    #[test]
    fn clean() {
        let dir = TempDir::new("u505-clean");
        fs::write(dir.path().join("part.stl"), cube_stl(0.1)).unwrap();
        let all = run_at(PART_ROBOT, &dir.path().join("robot.urdf"))
            .report
            .findings;
        assert!(lines_of(&all, CODE).is_empty(), "{}", describe(&all));
    }
}

// -------------------------------------------------------------------------------------------------
// Frames and missing inertials
// -------------------------------------------------------------------------------------------------

/// A complete, finding-free arm: base and arm with mass, inertia and collision, a limited revolute joint.
const CLEAN_ARM: &str = r#"<robot name="arm">
  <link name="base">
    <inertial>
      <mass value="5"/>
      <inertia ixx="0.021" ixy="0" ixz="0" iyy="0.021" iyz="0" izz="0.033"/>
    </inertial>
    <collision>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
    </collision>
  </link>
  <link name="arm">
    <inertial>
      <origin xyz="0 0 0.25"/>
      <mass value="1"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.001"/>
    </inertial>
    <collision>
      <origin xyz="0 0 0.25"/>
      <geometry><cylinder radius="0.03" length="0.5"/></geometry>
    </collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="arm"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="20" velocity="2"/>
  </joint>
</robot>
"#;

#[test]
fn the_clean_arm_has_no_findings_and_passes() {
    let r = report(CLEAN_ARM);
    assert!(r.findings.is_empty(), "{}", describe(&r.findings));
    assert_eq!(r.overall_status, Status::Pass);
    assert_eq!(r.confidence_level, ConfidenceLevel::High);
    assert_eq!(r.robot_name, "arm");
    assert_eq!(r.urdf_path, FILE);
}

#[test]
fn a_pure_frame_link_is_not_missing_inertial_and_counts_as_a_frame() {
    let urdf = r#"<robot name="r">
  <link name="base">
    <inertial>
      <mass value="1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
  </link>
  <link name="tool0"/>
  <joint name="flange" type="fixed">
    <parent link="base"/>
    <child link="tool0"/>
  </joint>
</robot>
"#;
    let r = report(urdf);
    assert!(
        lines_of(&r.findings, "U201").is_empty(),
        "{}",
        describe(&r.findings)
    );
    assert!(
        lines_of(&r.findings, "U207").is_empty(),
        "{}",
        describe(&r.findings)
    );
    assert_eq!(r.physics.links, 2);
    assert_eq!(r.physics.frames, 1, "tool0 is a frame: {:?}", r.physics);
    assert_eq!(r.physics.mass_missing, 0, "{:?}", r.physics);
    assert_eq!(r.physics.mass_exact, 1, "{:?}", r.physics);
    let tool0 = r.links.iter().find(|l| l.name == "tool0").unwrap();
    assert!(tool0.frame);
    assert!(!r.links.iter().find(|l| l.name == "base").unwrap().frame);
    // Frames do not drag the confidence down.
    assert_eq!(r.confidence_level, ConfidenceLevel::High);
}

#[test]
fn a_link_without_inertial_on_a_revolute_joint_is_u201_warn() {
    let urdf = r#"<robot name="r">
  <link name="base"/>
  <link name="arm"/>
  <joint name="j" type="revolute">
    <parent link="base"/>
    <child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>
"#;
    let r = report(urdf);
    let hit = the_one(&r.findings, "U201");
    assert_eq!(hit.severity, Severity::Warn);
    assert_eq!(hit.line, Some(3));
    assert!(hit.message.contains("'arm'"), "{}", hit.message);
    // A moving bare link is a body with missing mass, not a frame.
    assert_eq!(
        r.physics.frames, 1,
        "only the root is a frame: {:?}",
        r.physics
    );
    assert_eq!(r.physics.mass_missing, 1, "{:?}", r.physics);
    assert!(!r.links.iter().find(|l| l.name == "arm").unwrap().frame);
    assert_eq!(r.overall_status, Status::Warn);
}

#[test]
fn zero_mass_and_zero_inertia_on_a_fixed_link_are_not_flagged() {
    let urdf = r#"<robot name="r">
  <link name="base">
    <inertial>
      <mass value="0"/>
      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>
    </inertial>
  </link>
</robot>
"#;
    let f = findings(urdf);
    assert!(lines_of(&f, "U203").is_empty(), "{}", describe(&f));
    assert!(lines_of(&f, "U204").is_empty(), "{}", describe(&f));
    assert!(lines_of(&f, "U205").is_empty(), "{}", describe(&f));
}

// -------------------------------------------------------------------------------------------------
// Statuses, exit codes and confidence
// -------------------------------------------------------------------------------------------------

#[test]
fn a_critical_finding_fails_with_exit_code_2() {
    let urdf = CLEAN_ARM.replace(r#"<mass value="1"/>"#, r#"<mass value="-1"/>"#);
    let r = report(&urdf);
    assert!(
        r.findings.iter().any(|f| f.severity == Severity::Critical),
        "{}",
        describe(&r.findings)
    );
    assert_eq!(r.schema.status, Status::Fail);
    assert_eq!(r.overall_status, Status::Fail);
    assert_eq!(r.overall_status.exit_code(), 2);
    assert!(
        r.critical_issues
            .iter()
            .any(|m| m.contains("negative mass")),
        "{:?}",
        r.critical_issues
    );
    assert_eq!(r.critical_issues, r.schema.critical_issues);
}

#[test]
fn only_warn_findings_warn_with_exit_code_1() {
    let urdf = CLEAN_ARM.replace(r#"<axis xyz="0 1 0"/>"#, r#"<axis xyz="0 2 0"/>"#);
    let r = report(&urdf);
    assert!(!r.findings.is_empty());
    assert!(
        r.findings.iter().all(|f| f.severity == Severity::Warn),
        "{}",
        describe(&r.findings)
    );
    assert_eq!(r.schema.status, Status::Warn);
    assert_eq!(r.overall_status, Status::Warn);
    assert_eq!(r.overall_status.exit_code(), 1);
    assert!(r.critical_issues.is_empty());
    assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
}

#[test]
fn only_info_findings_pass_with_exit_code_0() {
    let urdf = CLEAN_ARM.replace(r#"<link name="arm">"#, r#"<link name="arm" colour="red">"#);
    let r = report(&urdf);
    assert!(!r.findings.is_empty());
    assert!(
        r.findings.iter().all(|f| f.severity == Severity::Info),
        "{}",
        describe(&r.findings)
    );
    assert_eq!(r.schema.status, Status::Pass);
    assert_eq!(r.overall_status, Status::Pass);
    assert_eq!(r.overall_status.exit_code(), 0);
    assert!(r.critical_issues.is_empty() && r.warnings.is_empty());
    assert_eq!(r.schema.infos.len(), 1, "{:?}", r.schema.infos);
}

#[test]
fn exit_codes_of_every_status() {
    assert_eq!(Status::Pass.exit_code(), 0);
    assert_eq!(Status::NotApplicable.exit_code(), 0);
    assert_eq!(Status::Warn.exit_code(), 1);
    assert_eq!(Status::Fail.exit_code(), 2);
    assert_eq!(Status::Unknown.exit_code(), 2);
}

#[test]
fn confidence_is_high_when_every_body_declares_mass_and_inertia() {
    let r = report(CLEAN_ARM);
    assert_eq!(r.confidence_level, ConfidenceLevel::High, "{:?}", r.physics);
    assert_eq!(r.physics.mass_exact, 2);
    assert_eq!(r.physics.inertia_exact, 2);
}

#[test]
fn confidence_is_medium_when_half_the_bodies_declare_a_mass() {
    // base declares mass and inertia; arm (moving) declares nothing.
    let urdf = r#"<robot name="r">
  <link name="base">
    <inertial>
      <mass value="1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
  </link>
  <link name="arm"/>
  <joint name="j" type="revolute">
    <parent link="base"/>
    <child link="arm"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>
"#;
    let r = report(urdf);
    assert_eq!(r.physics.mass_exact, 1, "{:?}", r.physics);
    assert_eq!(r.physics.mass_missing, 1, "{:?}", r.physics);
    assert_eq!(r.confidence_level, ConfidenceLevel::Medium);

    // Every body has a mass but one lacks its inertia tensor: not HIGH either.
    let no_tensor = r#"<robot name="r">
  <link name="base">
    <inertial>
      <mass value="1"/>
    </inertial>
  </link>
</robot>
"#;
    let r = report(no_tensor);
    assert_eq!(r.physics.inertia_missing, 1, "{:?}", r.physics);
    assert_eq!(r.confidence_level, ConfidenceLevel::Medium);
}

#[test]
fn confidence_is_low_when_most_bodies_lack_a_mass() {
    let urdf = r#"<robot name="r">
  <link name="base">
    <inertial>
      <mass value="1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
  </link>
  <link name="a"/>
  <link name="b"/>
  <joint name="ja" type="continuous">
    <parent link="base"/>
    <child link="a"/>
  </joint>
  <joint name="jb" type="continuous">
    <parent link="a"/>
    <child link="b"/>
  </joint>
</robot>
"#;
    let r = report(urdf);
    assert_eq!(r.physics.mass_exact, 1, "{:?}", r.physics);
    assert_eq!(r.physics.mass_missing, 2, "{:?}", r.physics);
    assert_eq!(r.confidence_level, ConfidenceLevel::Low);

    // Nothing but frames: no physics data at all.
    let r = report("<robot name=\"r\"><link name=\"world\"/></robot>");
    assert_eq!(r.physics.frames, 1);
    assert_eq!(r.confidence_level, ConfidenceLevel::Low);
}

// -------------------------------------------------------------------------------------------------
// Malformed input
// -------------------------------------------------------------------------------------------------

#[test]
fn not_xml_is_a_load_error_with_a_position() {
    assert_xml_load_error("<robot");
}

#[test]
fn an_empty_document_is_a_load_error_with_a_position() {
    assert_xml_load_error("");
    assert_xml_load_error("   \n  ");
}

#[test]
fn binary_junk_is_a_load_error_with_a_position() {
    let bytes: Vec<u8> = (0u32..512)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
        .collect();
    assert_xml_load_error(&String::from_utf8_lossy(&bytes));
    assert_xml_load_error("\u{0}\u{1}\u{2}PK\u{3}\u{4}\u{fffd}\u{fffd}");
    assert_xml_load_error("<robot name=\"r\">\u{0}</robot>");
}

#[test]
fn an_error_on_a_later_line_reports_that_line() {
    let error = validate_text(
        "<robot name=\"r\">\n  <link name=\"a\">\n</robot>\n".to_string(),
        Path::new(FILE),
        &Options::default(),
    )
    .expect_err("mismatched tags");
    let Error::Load(LoadError::Xml { line, .. }) = error else {
        panic!("{error:?}")
    };
    assert_eq!(line, 3, "{error}");
}

#[test]
fn a_root_that_is_no_description_is_u001_not_an_error() {
    let urdf = r#"<scene model="m"><worldbody><body name="b"/></worldbody></scene>"#;
    let r = report(urdf);
    let hit = the_one(&r.findings, "U001");
    assert_eq!(hit.severity, Severity::Critical);
    assert!(hit.message.contains("<scene>"), "{}", hit.message);
    assert_eq!((hit.line, hit.column), (Some(1), Some(1)));
    // Nothing else is checked on a document that is not a robot.
    assert_eq!(r.findings.len(), 1, "{}", describe(&r.findings));
    assert_eq!(r.overall_status.exit_code(), 2);
}

#[test]
fn an_mjcf_root_is_read_as_mjcf_not_u001() {
    let r = report(
        r#"<mujoco model="m"><worldbody><body name="b"><geom size="0.1"/></body></worldbody></mujoco>"#,
    );
    assert!(
        with_code(&r.findings, "U001").is_empty(),
        "{}",
        describe(&r.findings)
    );
    // A sphere of 0.1 m at MuJoCo's default density, 1000 kg/m³.
    let mass = r.statics.as_ref().and_then(|s| s.total_mass).unwrap();
    assert!(
        (mass - 4.0 / 3.0 * std::f64::consts::PI).abs() < 1e-12,
        "{mass}"
    );
}

#[test]
fn an_entity_expansion_bomb_is_a_load_error() {
    let mut text =
        String::from("<?xml version=\"1.0\"?>\n<!DOCTYPE robot [\n<!ENTITY l0 \"lol\">\n");
    for i in 1..10 {
        let p = i - 1;
        text.push_str(&format!(
            "<!ENTITY l{i} \"{}\">\n",
            format!("&l{p};").repeat(10)
        ));
    }
    text.push_str("]>\n<robot name=\"&l9;\"><link name=\"a\"/></robot>\n");
    assert_xml_load_error(&text);
}

#[test]
fn a_value_from_a_dtd_entity_points_at_the_reference() {
    let urdf = r#"<!DOCTYPE robot [<!ENTITY m "-1">]>
<robot name="r">
  <link name="a">
    <inertial>
      <mass value="&m;"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
  </link>
</robot>
"#;
    let f = findings(urdf);
    assert_eq!(positions_of(&f, "U202"), vec![(5, 20)], "{}", describe(&f));
    assert!(text_at(urdf, 5, 20).starts_with("&m;"));
}

#[test]
fn deeply_nested_unknown_elements_do_not_overflow() {
    let depth = 20_000;
    let urdf = format!(
        "<robot name=\"r\"><link name=\"a\"/>{}{}</robot>",
        "<a>".repeat(depth),
        "</a>".repeat(depth)
    );
    let f = findings(&urdf);
    assert_eq!(lines_of(&f, "U005"), vec![1], "{}", describe(&f));
    let urdf = format!(
        "<robot name=\"r\"><link name=\"a\">{}{}</link></robot>",
        "<visual>".repeat(depth),
        "</visual>".repeat(depth)
    );
    let _ = findings(&urdf);
}

#[test]
fn files_that_cannot_be_read_are_load_errors() {
    let dir = TempDir::new("unreadable");
    let binary = dir.path().join("t.urdf");
    fs::write(&binary, [0xff, 0xfe, 0x00, 0x3c, 0x80, 0x81]).unwrap();
    let error = validate(&binary, &Options::default()).expect_err("not UTF-8");
    assert!(
        matches!(error, Error::Load(LoadError::NotUtf8 { .. })),
        "{error:?}"
    );
    assert!(error.to_string().contains("t.urdf:"), "{error}");

    let absent = dir.path().join("absent.urdf");
    let error = validate(&absent, &Options::default()).expect_err("missing file");
    assert!(
        matches!(error, Error::Load(LoadError::Io { .. })),
        "{error:?}"
    );
    assert!(error.to_string().contains("absent.urdf:"), "{error}");
}

/// A document touching every parser path, to be cut and mutated.
const EVERYTHING: &str = r#"<?xml version="1.0"?>
<robot name="all" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <material name="grey"><color rgba="0.5 0.5 0.5 1"/><texture/></material>
  <link name="base">
    <inertial>
      <origin xyz="0 0 0.1" rpy="0 0 0"/>
      <mass value="2"/>
      <inertia ixx="1" ixy="0.1" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <visual name="v">
      <origin xyz="0 0 0"/>
      <geometry><mesh filename="package://nopkg/m.stl" scale="1 1 1"/></geometry>
      <material name="grey"/>
    </visual>
    <collision><geometry><cylinder radius="0.1" length="0.2"/></geometry></collision>
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
  <link name="arm"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
  <link name="finger"/>
  <joint name="j" type="revolute">
    <origin xyz="0 0 1" rpy="0 0 1.57"/>
    <parent link="base"/>
    <child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
    <dynamics damping="0.1" friction="0"/>
    <safety_controller soft_lower_limit="-0.9" soft_upper_limit="0.9" k_position="10" k_velocity="1"/>
    <calibration rising="0"/>
  </joint>
  <joint name="f" type="prismatic">
    <parent link="arm"/>
    <child link="finger"/>
    <limit lower="0" upper="0.1" effort="1" velocity="1"/>
    <mimic joint="j" multiplier="0.1" offset="0"/>
  </joint>
  <transmission name="t"><type>x</type><joint name="j"/><actuator name="m"/></transmission>
  <gazebo reference="arm"><mu1>1</mu1></gazebo>
  <ros2_control name="hw" type="system"><joint name="j"/></ros2_control>
  <xacro:property name="p" value="1"/>
</robot>
"#;

#[test]
fn every_prefix_of_a_document_loads_or_errors_without_panicking() {
    assert!(validate_text(EVERYTHING.to_string(), Path::new(FILE), &Options::default()).is_ok());
    for (cut, _) in EVERYTHING.char_indices() {
        let _ = validate_text(
            EVERYTHING[..cut].to_string(),
            Path::new(FILE),
            &Options::default(),
        );
    }
}

#[test]
fn mutated_documents_never_panic() {
    const JUNK: [&str; 12] = [
        "<",
        ">",
        "\"",
        "=",
        "nan",
        "-inf",
        "1e400",
        "",
        "/",
        "é",
        "<link name=\"base\"/>",
        "0",
    ];
    let chars: Vec<(usize, char)> = EVERYTHING.char_indices().collect();
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for _ in 0..3000 {
        let at = chars[(next() % chars.len() as u64) as usize].0;
        let len = (next() % 6) as usize;
        let end = EVERYTHING[at..]
            .char_indices()
            .map(|(i, _)| at + i)
            .find(|&i| i >= at + len)
            .unwrap_or(EVERYTHING.len());
        let junk = JUNK[(next() % JUNK.len() as u64) as usize];
        let text = format!("{}{junk}{}", &EVERYTHING[..at], &EVERYTHING[end..]);
        if let Ok(v) = validate_text(text, Path::new(FILE), &Options::default()) {
            serde_json::to_string(&v.report).expect("a report always serialises");
        }
    }
}

// -------------------------------------------------------------------------------------------------
// Real-world shapes that must parse quietly
// -------------------------------------------------------------------------------------------------

#[test]
fn a_texture_without_filename_parses_without_a_finding() {
    // icub and romeo write `<texture/>` without a filename.
    let urdf = r#"<robot name="r">
  <material name="skin">
    <color rgba="1 1 1 1"/>
    <texture/>
  </material>
  <link name="base">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.17" ixy="0" ixz="0" iyy="0.17" iyz="0" izz="0.17"/>
    </inertial>
    <visual>
      <geometry><box size="1 1 1"/></geometry>
      <material name="cover"><texture/></material>
    </visual>
    <collision>
      <geometry><box size="1 1 1"/></geometry>
    </collision>
  </link>
</robot>
"#;
    let f = findings(urdf);
    assert!(f.is_empty(), "{}", describe(&f));
}

const OLD_TRANSMISSION_ROBOT: &str = r#"<robot name="r">
  <link name="base"/>
  <link name="arm">
    <inertial>
      <mass value="1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
  </link>
  <joint name="j" type="continuous">
    <parent link="base"/>
    <child link="arm"/>
    <limit effort="10" velocity="1"/>
  </joint>
  <transmission type="pr2_mechanism_model/SimpleTransmission"><joint name="j"/><actuator name="a"/><mechanicalReduction>1</mechanicalReduction></transmission>
</robot>
"#;

#[test]
fn an_old_style_transmission_without_type_element_parses() {
    let f = findings(OLD_TRANSMISSION_ROBOT);
    assert!(f.is_empty(), "{}", describe(&f));
}

#[test]
fn an_old_style_transmission_naming_a_missing_joint_is_u401() {
    let urdf = OLD_TRANSMISSION_ROBOT.replace(r#"<joint name="j"/>"#, r#"<joint name="jj"/>"#);
    let f = findings(&urdf);
    let hit = the_one(&f, "U401");
    assert_eq!(hit.severity, Severity::Warn);
    // `  <transmission type="pr2_mechanism_model/SimpleTransmission"><joint name="` is 75 characters.
    assert_eq!(
        (hit.line, hit.column),
        (Some(14), Some(76)),
        "{}",
        describe(&f)
    );
    assert!(text_at(&urdf, 14, 76).starts_with("jj\""));
    assert!(hit.message.contains("'jj'"), "{}", hit.message);
    assert_eq!(hit.help.as_deref(), Some("did you mean 'j'?"));
    assert_eq!(f.len(), 1, "{}", describe(&f));
}

#[test]
fn pr2_style_named_joints_in_a_transmission_are_checked() {
    let urdf = OLD_TRANSMISSION_ROBOT.replace(
        r#"<joint name="j"/>"#,
        r#"<flexJoint name="j"/><rollJoint name="roll"/>"#,
    );
    let f = findings(&urdf);
    let hit = the_one(&f, "U401");
    assert!(hit.message.contains("'roll'"), "{}", hit.message);
}

// -------------------------------------------------------------------------------------------------
// NaN and infinity
// -------------------------------------------------------------------------------------------------

const NON_FINITE: &str = r#"<robot name="r">
  <link name="base">
    <inertial>
      <mass value="nan"/>
      <inertia ixx="inf" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
  </link>
</robot>
"#;

/// The report serialises to JSON without NaN/Infinity tokens and re-parses.
fn assert_json_is_clean(report: &Report) {
    let json = serde_json::to_string(report).expect("serialise");
    assert!(!json.contains("NaN"), "{json}");
    assert!(!json.contains("Infinity"), "{json}");
    let value: serde_json::Value = serde_json::from_str(&json).expect("re-parse");
    assert!(value.get("findings").is_some_and(|f| f.is_array()));
}

#[test]
fn nan_and_inf_are_u004_at_the_value_column() {
    let r = report(NON_FINITE);
    assert_eq!(
        positions_of(&r.findings, "U004"),
        vec![(4, 20), (5, 21)],
        "{}",
        describe(&r.findings)
    );
    assert!(text_at(NON_FINITE, 4, 20).starts_with("nan\""));
    assert!(text_at(NON_FINITE, 5, 21).starts_with("inf\""));
    assert!(r
        .findings
        .iter()
        .all(|f| f.rule != "U004" || f.severity == Severity::Critical));
    // Neither the mass nor the tensor is usable.
    let base = &r.links[0];
    assert_eq!(base.mass, None);
    assert_eq!(base.inertia_tensor, None);
    assert_eq!(r.physics.mass_missing, 1, "{:?}", r.physics);
    // No inertia rule runs on a non-finite tensor.
    for code in ["U204", "U205", "U206"] {
        assert!(
            lines_of(&r.findings, code).is_empty(),
            "{code}\n{}",
            describe(&r.findings)
        );
    }
}

#[test]
fn non_finite_reports_serialise_to_valid_json() {
    assert_json_is_clean(&report(NON_FINITE));
}

#[test]
fn non_finite_values_everywhere_never_panic_and_serialise() {
    let urdf = r#"<robot name="r">
  <link name="base">
    <inertial>
      <origin xyz="nan inf -inf" rpy="nan 0 0"/>
      <mass value="-inf"/>
      <inertia ixx="nan" ixy="inf" ixz="-inf" iyy="nan" iyz="1e400" izz="-1e400"/>
    </inertial>
    <visual>
      <origin xyz="inf 0 0"/>
      <geometry><box size="nan inf -inf"/></geometry>
      <material name="m"><color rgba="nan 0 0 1"/></material>
    </visual>
    <collision>
      <geometry><mesh filename="m.stl" scale="inf nan 1"/></geometry>
    </collision>
    <collision>
      <geometry><cylinder radius="inf" length="nan"/></geometry>
    </collision>
    <collision>
      <geometry><sphere radius="-inf"/></geometry>
    </collision>
  </link>
  <link name="arm">
    <inertial>
      <mass value="1e308"/>
      <inertia ixx="1e308" ixy="1e308" ixz="1e308" iyy="1e308" iyz="1e308" izz="1e308"/>
    </inertial>
  </link>
  <link name="tip">
    <inertial>
      <mass value="1"/>
      <inertia ixx="1e-320" ixy="0" ixz="0" iyy="1e-320" iyz="0" izz="1e-320"/>
    </inertial>
  </link>
  <joint name="j" type="revolute">
    <origin xyz="nan 0 0" rpy="0 inf 0"/>
    <parent link="base"/>
    <child link="arm"/>
    <axis xyz="nan 0 1"/>
    <limit lower="nan" upper="inf" effort="-inf" velocity="nan"/>
    <dynamics damping="inf" friction="nan"/>
  </joint>
  <joint name="k" type="prismatic">
    <parent link="arm"/>
    <child link="tip"/>
    <axis xyz="1e200 1e200 0"/>
    <limit lower="-inf" upper="-inf" effort="inf" velocity="inf"/>
    <mimic joint="j" multiplier="nan" offset="inf"/>
  </joint>
</robot>
"#;
    let r = report(urdf);
    assert!(
        lines_of(&r.findings, "U004").len() >= 10,
        "{}",
        describe(&r.findings)
    );
    assert_json_is_clean(&r);
}

// -------------------------------------------------------------------------------------------------
// Kinematic loops
// -------------------------------------------------------------------------------------------------

#[test]
fn a_link_with_two_parents_is_a_loop() {
    let urdf = r#"<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <joint name="j1" type="fixed">
    <parent link="a"/>
    <child link="b"/>
  </joint>
  <joint name="j2" type="fixed">
    <parent link="a"/>
    <child link="b"/>
  </joint>
</robot>
"#;
    let f = findings(urdf);
    let hit = the_one(&f, "U103");
    assert_eq!(hit.line, Some(8));
    assert!(
        hit.message.contains("'b'") && hit.message.contains("'j1'") && hit.message.contains("'j2'"),
        "{}",
        hit.message
    );
}

#[test]
fn a_two_cycle_without_any_root_is_a_loop_and_does_not_panic() {
    let urdf = r#"<robot name="r">
  <link name="A"/>
  <link name="B"/>
  <joint name="ab" type="fixed">
    <parent link="A"/>
    <child link="B"/>
  </joint>
  <joint name="ba" type="fixed">
    <parent link="B"/>
    <child link="A"/>
  </joint>
</robot>
"#;
    let r = report(urdf);
    let hit = the_one(&r.findings, "U103");
    assert!(
        hit.message.contains('A') && hit.message.contains('B'),
        "{}",
        hit.message
    );
    assert!(
        matches!(hit.line, Some(4) | Some(8)),
        "the finding points at a joint of the cycle\n{}",
        describe(&r.findings)
    );
    assert!(lines_of(&r.findings, "U104").is_empty());
    assert_eq!(r.overall_status, Status::Fail);
    assert_json_is_clean(&r);
}

#[test]
fn a_cycle_with_a_branch_hanging_below_it_is_reported_once() {
    let urdf = r#"<robot name="r">
  <link name="A"/>
  <link name="B"/>
  <link name="C"/>
  <joint name="ab" type="fixed"><parent link="A"/><child link="B"/></joint>
  <joint name="ba" type="fixed"><parent link="B"/><child link="A"/></joint>
  <joint name="bc" type="fixed"><parent link="B"/><child link="C"/></joint>
</robot>
"#;
    let f = findings(urdf);
    let hit = the_one(&f, "U103");
    assert!(
        !hit.message.contains('C'),
        "C is not on the cycle: {}",
        hit.message
    );
}

#[test]
fn a_joint_whose_parent_is_its_child_is_a_loop() {
    let urdf = r#"<robot name="r">
  <link name="a"/>
  <joint name="self" type="fixed">
    <parent link="a"/>
    <child link="a"/>
  </joint>
</robot>
"#;
    let f = findings(urdf);
    let hit = the_one(&f, "U103");
    assert_eq!((hit.line, hit.column), (Some(3), Some(3)));
    assert!(hit.message.contains("'self'"), "{}", hit.message);
    assert!(lines_of(&f, "U104").is_empty(), "{}", describe(&f));
}

// -------------------------------------------------------------------------------------------------
// Mimic joints
// -------------------------------------------------------------------------------------------------

/// Two revolute joints: `follower`'s `<mimic>` is on line 14 and names `follower_mimics`; line 9, inside
/// `shoulder_pan`, holds `leader_mimic` (empty, or a `<mimic>` of its own).
fn mimic_robot(follower_mimics: &str, leader_mimic: &str) -> String {
    format!(
        r#"<robot name="r">
  <link name="base"/>
  <link name="a"/>
  <link name="b"/>
  <joint name="shoulder_pan" type="revolute">
    <parent link="base"/>
    <child link="a"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
    {leader_mimic}
  </joint>
  <joint name="follower" type="revolute">
    <parent link="a"/>
    <child link="b"/>
    <mimic joint="{follower_mimics}" multiplier="-1"/>
    <limit lower="-1" upper="1" effort="0" velocity="0"/>
  </joint>
</robot>
"#
    )
}

#[test]
fn a_mimic_of_a_missing_joint_suggests_the_close_name() {
    let urdf = mimic_robot("shoulder_pn", "");
    let f = findings(&urdf);
    let hit = the_one(&f, "U311");
    assert_eq!(hit.severity, Severity::Critical);
    assert_eq!((hit.line, hit.column), (Some(14), Some(19)));
    assert!(text_at(&urdf, 14, 19).starts_with("shoulder_pn\""));
    assert_eq!(hit.help.as_deref(), Some("did you mean 'shoulder_pan'?"));
}

#[test]
fn a_mimic_of_a_missing_joint_with_nothing_close_says_so() {
    let f = findings(&mimic_robot("gripper_finger_joint", ""));
    let hit = the_one(&f, "U311");
    assert_eq!(hit.help.as_deref(), Some("no similarly named item exists"));
}

#[test]
fn a_self_mimic_is_a_cycle() {
    let f = findings(&mimic_robot("follower", ""));
    let hit = the_one(&f, "U312");
    assert_eq!((hit.line, hit.column), (Some(14), Some(5)));
    assert!(
        hit.message.contains("follower → follower"),
        "{}",
        hit.message
    );
    assert!(lines_of(&f, "U311").is_empty(), "{}", describe(&f));
}

#[test]
fn a_two_joint_mimic_cycle_is_reported_once() {
    let urdf = mimic_robot("shoulder_pan", r#"<mimic joint="follower"/>"#);
    let f = findings(&urdf);
    let hit = the_one(&f, "U312");
    assert_eq!(hit.line, Some(9), "{}", describe(&f));
    assert!(
        hit.message.contains("shoulder_pan") && hit.message.contains("follower"),
        "{}",
        hit.message
    );
}

#[test]
fn a_valid_mimic_gives_nothing_and_exempts_the_follower_from_effort_and_velocity() {
    let f = findings(&mimic_robot("shoulder_pan", ""));
    for code in ["U311", "U312", "U306", "U307"] {
        assert!(lines_of(&f, code).is_empty(), "{code}\n{}", describe(&f));
    }
}

// -------------------------------------------------------------------------------------------------
// Roots, unknown elements, references
// -------------------------------------------------------------------------------------------------

#[test]
fn multiple_roots_name_the_disconnected_root() {
    let urdf = r#"<robot name="r">
  <link name="base"/>
  <link name="arm"/>
  <link name="camera_mount"/>
  <joint name="j" type="fixed">
    <parent link="base"/>
    <child link="arm"/>
  </joint>
</robot>
"#;
    let f = findings(urdf);
    let hit = the_one(&f, "U104");
    assert_eq!(hit.severity, Severity::Critical);
    assert!(hit.message.contains("'camera_mount'"), "{}", hit.message);
    assert!(hit.message.contains("'base'"), "{}", hit.message);
    assert_eq!((hit.line, hit.column), (Some(4), Some(15)));
    assert!(hit.help.as_deref().unwrap_or("").contains("joint"));
}

#[test]
fn the_larger_tree_is_the_root_whatever_the_document_order() {
    let urdf = r#"<robot name="r">
  <link name="stray"/>
  <link name="base"/>
  <link name="arm"/>
  <joint name="j" type="fixed">
    <parent link="base"/>
    <child link="arm"/>
  </joint>
</robot>
"#;
    let f = findings(urdf);
    let hit = the_one(&f, "U104");
    assert!(hit.message.starts_with("Link 'stray'"), "{}", hit.message);
    assert_eq!(hit.line, Some(2));
}

#[test]
fn an_undefined_link_suggests_the_close_name() {
    let urdf = r#"<robot name="r">
  <link name="base_link"/>
  <link name="arm_link"/>
  <joint name="j" type="fixed">
    <parent link="base_link"/>
    <child link="arm_lnk"/>
  </joint>
</robot>
"#;
    let f = findings(urdf);
    let hit = the_one(&f, "U102");
    assert_eq!(hit.help.as_deref(), Some("did you mean 'arm_link'?"));
    assert!(
        hit.message.contains("child link 'arm_lnk'"),
        "{}",
        hit.message
    );
}

#[test]
fn unknown_elements_and_attributes_are_info() {
    let urdf = r#"<robot name="r">
  <link name="base">
    <colision/>
  </link>
  <joint name="j" type="fixed" efort="1">
    <parent link="base"/>
    <child link="tip"/>
  </joint>
  <link name="tip"/>
</robot>
"#;
    let r = report(urdf);
    let element = the_one(&r.findings, "U005");
    assert_eq!(element.severity, Severity::Info);
    assert_eq!((element.line, element.column), (Some(3), Some(5)));
    assert!(
        element.message.contains("<colision>"),
        "{}",
        element.message
    );
    let attribute = the_one(&r.findings, "U006");
    assert_eq!(attribute.severity, Severity::Info);
    assert_eq!((attribute.line, attribute.column), (Some(5), Some(32)));
    assert!(text_at(urdf, 5, 32).starts_with("efort"));
    assert!(
        attribute.message.contains("'efort'"),
        "{}",
        attribute.message
    );
    assert_eq!(r.schema.status, Status::Pass, "{}", describe(&r.findings));
}

#[test]
fn an_unexpanded_xacro_property_is_u005_with_xacro_help() {
    let urdf = r#"<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="length" value="0.5"/>
  <link name="base"/>
</robot>
"#;
    let f = findings(urdf);
    let hit = the_one(&f, "U005");
    assert_eq!(hit.severity, Severity::Info);
    assert_eq!((hit.line, hit.column), (Some(2), Some(3)));
    assert!(hit.message.contains("xacro:property"), "{}", hit.message);
    assert!(
        hit.help.as_deref().unwrap_or("").contains("xacro"),
        "{:?}",
        hit.help
    );
}

#[test]
fn other_namespaced_extensions_are_not_unknown() {
    let urdf = r#"<robot name="r" xmlns:drake="http://drake.mit.edu">
  <drake:collision_filter_group name="g"/>
  <link name="base" drake:thing="1"/>
</robot>
"#;
    // Schema findings only: a robot without geometry has no contacts, so stability says it cannot run.
    let f: Vec<FindingReport> = findings(urdf)
        .into_iter()
        .filter(|f| f.section == Section::Schema)
        .collect();
    assert!(f.is_empty(), "{}", describe(&f));
}

#[test]
fn a_gazebo_reference_may_name_a_joint_and_robot_level_gazebo_needs_none() {
    let urdf = r#"<robot name="r">
  <link name="base"/>
  <link name="arm"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>
  <gazebo reference="j"><disableFixedJointLumping>true</disableFixedJointLumping></gazebo>
  <gazebo><plugin name="p" filename="libp.so"/></gazebo>
</robot>
"#;
    let f = findings(urdf);
    assert!(lines_of(&f, "U402").is_empty(), "{}", describe(&f));
}

#[test]
fn a_visual_material_with_its_own_colour_needs_no_definition() {
    let urdf = r#"<robot name="r">
  <link name="base">
    <visual>
      <geometry><box size="1 1 1"/></geometry>
      <material name="red"><color rgba="1 0 0 1"/></material>
    </visual>
  </link>
</robot>
"#;
    let f = findings(urdf);
    assert!(lines_of(&f, "U404").is_empty(), "{}", describe(&f));
}

/// urdfdom adds a material defined inside a visual to the model's materials, so a later visual may refer to
/// it by name alone; the rule's own definition is "defined nowhere".
#[test]
fn a_material_defined_in_an_earlier_visual_is_defined() {
    let urdf = r#"<robot name="r">
  <link name="a">
    <visual>
      <geometry><box size="1 1 1"/></geometry>
      <material name="red"><color rgba="1 0 0 1"/></material>
    </visual>
  </link>
  <link name="b">
    <visual>
      <geometry><box size="1 1 1"/></geometry>
      <material name="red"/>
    </visual>
  </link>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"#;
    let f = findings(urdf);
    assert!(lines_of(&f, "U404").is_empty(), "{}", describe(&f));
}

// -------------------------------------------------------------------------------------------------
// Limits and geometry details
// -------------------------------------------------------------------------------------------------

#[test]
fn a_limit_without_lower_and_upper_is_an_empty_range_defaulting_to_zero() {
    let urdf = r#"<robot name="r">
  <link name="base"/>
  <link name="arm"/>
  <joint name="j" type="revolute">
    <parent link="base"/>
    <child link="arm"/>
    <limit effort="10" velocity="1"/>
  </joint>
</robot>
"#;
    let f = findings(urdf);
    let hit = the_one(&f, "U305");
    assert_eq!((hit.line, hit.column), (Some(7), Some(5)));
    assert!(hit.message.contains("both default to 0"), "{}", hit.message);
}

#[test]
fn a_limit_without_effort_and_velocity_gives_two_u302() {
    let urdf = r#"<robot name="r">
  <link name="base"/>
  <link name="arm"/>
  <joint name="j" type="prismatic">
    <parent link="base"/>
    <child link="arm"/>
    <limit lower="0" upper="1"/>
  </joint>
</robot>
"#;
    let f = findings(urdf);
    assert_eq!(lines_of(&f, "U302"), vec![7, 7], "{}", describe(&f));
    let messages: Vec<&str> = with_code(&f, "U302")
        .iter()
        .map(|h| h.message.as_str())
        .collect();
    assert!(messages[0].contains("'effort'") && messages[1].contains("'velocity'"));
}

#[test]
fn a_non_unit_axis_suggests_the_normalised_axis() {
    let urdf = CLEAN_ARM.replace(r#"<axis xyz="0 1 0"/>"#, r#"<axis xyz="0 3 4"/>"#);
    let f = findings(&urdf);
    let hit = the_one(&f, "U310");
    assert!(hit.message.contains("5.0000"), "{}", hit.message);
    assert_eq!(
        hit.help.as_deref(),
        Some(r#"use xyz="0.000000 0.600000 0.800000""#)
    );
}

#[test]
fn a_planar_joint_is_u313() {
    let urdf = r#"<robot name="r">
  <link name="ground"/>
  <link name="puck"/>
  <joint name="slide" type="planar">
    <parent link="ground"/>
    <child link="puck"/>
    <axis xyz="0 0 1"/>
  </joint>
</robot>
"#;
    let f = findings(urdf);
    let hit = the_one(&f, "U313");
    assert_eq!((hit.line, hit.column), (Some(4), Some(29)));
    assert!(text_at(urdf, 4, 29).starts_with("planar"));
}

#[test]
fn degenerate_spheres_cylinders_and_mesh_scales_are_u503() {
    let urdf = r#"<robot name="r">
  <link name="base">
    <collision><geometry><sphere radius="0"/></geometry></collision>
    <collision><geometry><cylinder radius="0.1" length="-1"/></geometry></collision>
    <collision><geometry><mesh filename="package://nopkg/a.stl" scale="1 0 1"/></geometry></collision>
  </link>
</robot>
"#;
    let f = findings(urdf);
    assert_eq!(lines_of(&f, "U503"), vec![3, 4, 5], "{}", describe(&f));
    assert_eq!(positions_of(&f, "U503")[0], (3, 26));
    assert!(text_at(urdf, 3, 26).starts_with("<sphere"));
}

/// The rule's documentation: "Negative mesh scales, the usual way to mirror a part, are accepted."
#[test]
fn a_mirrored_mesh_is_not_u503() {
    let urdf = r#"<robot name="r">
  <link name="base">
    <collision><geometry><mesh filename="package://nopkg/b.stl" scale="-1 1 1"/></geometry></collision>
  </link>
</robot>
"#;
    let f = findings(urdf);
    assert!(lines_of(&f, "U503").is_empty(), "{}", describe(&f));
}

#[test]
fn columns_count_characters_not_bytes() {
    // "ä" is two bytes in UTF-8 but one column.
    let urdf = "<robot name=\"r\">\n  <link name=\"ä\"/><link name=\"ä\"/>\n</robot>\n";
    let f = findings(urdf);
    assert_eq!(positions_of(&f, "U101"), vec![(2, 31)], "{}", describe(&f));
    assert!(text_at(urdf, 2, 31).starts_with("ä\""));
}

#[test]
fn crlf_line_endings_keep_lines_and_columns() {
    let urdf = "<robot name=\"r\">\r\n  <link name=\"base\">\r\n    <collision>\r\n      <geometry>\r\n        <box size=\"1 1\"/>\r\n      </geometry>\r\n    </collision>\r\n  </link>\r\n</robot>\r\n";
    let f = findings(urdf);
    assert_eq!(positions_of(&f, "U003"), vec![(5, 20)], "{}", describe(&f));
}

// -------------------------------------------------------------------------------------------------
// Mesh resolution
// -------------------------------------------------------------------------------------------------

fn mesh_robot(filename: &str) -> String {
    format!(
        r#"<robot name="r">
  <link name="base">
    <collision>
      <geometry>
        <mesh filename="{filename}"/>
      </geometry>
    </collision>
  </link>
</robot>
"#
    )
}

#[test]
fn a_mesh_in_an_unknown_package_is_u501_info() {
    let urdf = mesh_robot("package://nopkg/m.stl");
    let r = report(&urdf);
    let hit = the_one(&r.findings, "U501");
    assert_eq!(hit.severity, Severity::Info);
    assert_eq!((hit.line, hit.column), (Some(5), Some(25)));
    assert!(
        hit.message.contains("package://nopkg/m.stl"),
        "{}",
        hit.message
    );
    assert!(
        hit.help.as_deref().unwrap_or("").contains("--package-path"),
        "{:?}",
        hit.help
    );
    assert_eq!(
        r.schema.status,
        Status::Pass,
        "INFO findings do not change the status"
    );
}

#[test]
fn a_relative_mesh_next_to_the_file_resolves() {
    let dir = TempDir::new("relative-mesh");
    fs::write(dir.path().join("m.stl"), b"solid m\nendsolid m\n").unwrap();
    fs::create_dir_all(dir.path().join("meshes")).unwrap();
    fs::write(dir.path().join("meshes/n.stl"), b"solid n\nendsolid n\n").unwrap();
    let urdf = mesh_robot("m.stl").replace(
        "</collision>",
        "</collision>\n    <collision><geometry><mesh filename=\"meshes/n.stl\"/></geometry></collision>",
    );
    let path = dir.path().join("robot.urdf");
    fs::write(&path, &urdf).unwrap();
    let validation = validate(&path, &Options::default()).expect("loads");
    let f = &validation.report.findings;
    assert!(lines_of(f, "U501").is_empty(), "{}", describe(f));
    assert_eq!(
        validation.report.urdf_path,
        path.display().to_string(),
        "the report names the file as given"
    );

    // The same file with a mesh that is not there: the finding says where it looked.
    let missing = mesh_robot("gone.stl");
    fs::write(&path, &missing).unwrap();
    let validation = validate(&path, &Options::default()).expect("loads");
    let hit = the_one(&validation.report.findings, "U501");
    assert_eq!(
        hit.file.as_deref(),
        Some(path.display().to_string().as_str())
    );
    assert!(
        hit.help
            .as_deref()
            .unwrap_or("")
            .contains(&dir.path().join("gone.stl").display().to_string()),
        "{:?}",
        hit.help
    );
}

#[test]
fn a_package_mesh_resolves_by_walking_up_to_a_package_xml() {
    let dir = TempDir::new("package-walk-up");
    let package = dir.path().join("my_robot");
    fs::create_dir_all(package.join("urdf")).unwrap();
    fs::create_dir_all(package.join("meshes")).unwrap();
    fs::write(
        package.join("package.xml"),
        "<package><name>my_robot</name></package>",
    )
    .unwrap();
    fs::write(package.join("meshes/m.stl"), b"solid m\nendsolid m\n").unwrap();
    let path = package.join("urdf/robot.urdf");
    fs::write(&path, mesh_robot("package://my_robot/meshes/m.stl")).unwrap();
    let validation = validate(&path, &Options::default()).expect("loads");
    let f = &validation.report.findings;
    assert!(lines_of(f, "U501").is_empty(), "{}", describe(f));
}

#[test]
fn an_http_mesh_is_u501_about_the_scheme() {
    let urdf = mesh_robot("http://x/m.stl");
    let f = findings(&urdf);
    let hit = the_one(&f, "U501");
    assert_eq!(hit.severity, Severity::Info);
    assert_eq!((hit.line, hit.column), (Some(5), Some(25)));
    assert!(
        hit.message.contains("scheme") && hit.message.contains("'http'"),
        "{}",
        hit.message
    );
}

#[test]
fn an_absolute_file_uri_with_escapes_resolves() {
    let dir = TempDir::new("file-uri");
    fs::write(dir.path().join("my mesh.stl"), b"solid m\nendsolid m\n").unwrap();
    let uri = format!("file://{}", dir.path().join("my%20mesh.stl").display());
    let f = findings(&mesh_robot(&uri));
    assert!(lines_of(&f, "U501").is_empty(), "{uri}\n{}", describe(&f));
}

#[test]
fn an_explicit_package_path_resolves_package_uris() {
    let dir = TempDir::new("package-path");
    fs::create_dir_all(dir.path().join("pkg/meshes")).unwrap();
    fs::write(
        dir.path().join("pkg/meshes/m.stl"),
        b"solid m\nendsolid m\n",
    )
    .unwrap();
    let options = Options {
        resolver: urdf_validator::input::resolve::PackageResolver::new(
            vec![dir.path().to_path_buf()],
            None,
            None,
        ),
        ..Options::default()
    };
    let urdf = mesh_robot("package://pkg/meshes/m.stl");
    let v = validate_text(urdf.clone(), Path::new(FILE), &options).expect("loads");
    let f = &v.report.findings;
    assert!(lines_of(f, "U501").is_empty(), "{}", describe(f));
    // Without the path, the same file is not found.
    assert_eq!(lines_of(&findings(&urdf), "U501"), vec![5]);
}

#[test]
fn unresolvable_uris_are_u501_saying_why() {
    for (uri, why) in [
        ("https://example.com/m.stl", "'https'"),
        ("model://robot", "does not name a file"),
        ("package://pkg", "names no file"),
        (
            "package:///m.stl",
            "empty package name; ROS's resource_retriever refuses it",
        ),
        ("", "empty"),
    ] {
        let f = findings(&mesh_robot(uri));
        let hit = the_one(&f, "U501");
        assert!(hit.message.contains(why), "{uri:?}: {}", hit.message);
    }
}

#[test]
fn a_misspelt_gazebo_reference_suggests_the_link() {
    let urdf = r#"<robot name="r">
  <link name="base"/>
  <gazebo reference="bsae"/>
</robot>
"#;
    let f = findings(urdf);
    let hit = the_one(&f, "U402");
    assert_eq!(hit.help.as_deref(), Some("did you mean 'base'?"));
}

/// Editors do not count a UTF-8 byte-order mark as a column.
#[test]
fn a_byte_order_mark_does_not_shift_line_one_columns() {
    let urdf = "\u{feff}<robot name=\"r\" x=\"1\">\n  <link name=\"a\"/>\n</robot>\n";
    let f = findings(urdf);
    assert_eq!(positions_of(&f, "U006"), vec![(1, 17)], "{}", describe(&f));
}

#[test]
fn a_byte_order_mark_parses() {
    let urdf = "\u{feff}<?xml version=\"1.0\"?>\n<robot name=\"r\" x=\"1\">\n  <link name=\"a\"/>\n</robot>\n";
    let f = findings(urdf);
    assert_eq!(positions_of(&f, "U006"), vec![(2, 17)], "{}", describe(&f));
}

#[test]
fn non_finite_limits_are_reported_once_by_the_parser() {
    let found = findings(
        r#"<robot name="r">
  <link name="a"/>
  <link name="b"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-inf" upper="-inf" effort="-inf" velocity="1"/></joint>
</robot>
"#,
    );
    assert_eq!(
        lines_of(&found, "U004"),
        vec![5, 5, 5],
        "{}",
        describe(&found)
    );
    for code in ["U304", "U305", "U306"] {
        assert!(
            with_code(&found, code).is_empty(),
            "{code} duplicates U004: {}",
            describe(&found)
        );
    }
}

#[test]
fn huge_eigenvalues_print_in_scientific_notation() {
    let found = findings(
        r#"<robot name="r">
  <link name="a"/>
  <link name="b"><inertial><mass value="1"/><inertia ixx="1e300" ixy="0" ixz="0" iyy="-1e300" iyz="0" izz="1e300"/></inertial></link>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint>
</robot>
"#,
    );
    let finding = the_one(&found, "U205");
    assert!(finding.message.len() < 200, "{}", finding.message);
    assert!(finding.message.contains("e300"), "{}", finding.message);
}

/// A three-joint arm over a base plate; link `l2`'s ball sits `z2` below its frame (its frame is 0.7 m up).
fn arm_over_plate(z2: f64) -> String {
    let joint = |name: &str, parent: &str, child: &str, z: f64, axis: &str| {
        format!(
            r#"  <joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/><origin xyz="0 0 {z}"/><axis xyz="{axis}"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>"#
        )
    };
    let inertial = r#"<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>"#;
    [
        r#"<robot name="r">"#.to_string(),
        format!(r#"  <link name="base">{inertial}<collision><origin xyz="0 0 0.05"/><geometry><box size="1 1 0.1"/></geometry></collision></link>"#),
        joint("j1", "base", "l1", 0.5, "0 0 1"),
        format!(r#"  <link name="l1">{inertial}<collision><geometry><sphere radius="0.05"/></geometry></collision></link>"#),
        joint("j2", "l1", "l2", 0.2, "0 1 0"),
        format!(r#"  <link name="l2">{inertial}<collision><origin xyz="0 0 {z2}"/><geometry><sphere radius="0.05"/></geometry></collision></link>"#),
        joint("j3", "l2", "l3", 0.2, "0 1 0"),
        format!(r#"  <link name="l3">{inertial}<collision><geometry><sphere radius="0.05"/></geometry></collision></link>"#),
        "</robot>\n".to_string(),
    ]
    .join("\n")
}

// The ball of l2 reaches 0.7 − 0.66 − 0.05 = −0.01 m: into the plate (top at 0.1 m) at the zero pose.
rule_case! {
    u601_links_in_contact_at_reference, "U601",
    fires: arm_over_plate(-0.66),
    at: (6, 124, "<collision><origin xyz=\"0 0 -0.66\"/>"),
    clean: arm_over_plate(-0.3),
}

#[test]
fn xacro_warnings_are_u010_at_the_xacro_tag() {
    let dir = std::env::temp_dir().join(format!("urdf_validator_u010_{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    let path = dir.join("w.urdf.xacro");
    fs::write(
        &path,
        r#"<robot name="w" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="a" value="1" bogus="x"/>
  <link name="l${a}"/>
</robot>"#,
    )
    .unwrap();
    let report = validate(&path, &Options::default()).unwrap().report;
    let hit = the_one(&report.findings, "U010");
    assert!(hit.message.contains("bogus"), "{}", hit.message);
    assert_eq!((hit.line, hit.column), (Some(2), Some(3)));
    // The whole tag: `<xacro:property name="a" value="1" bogus="x"/>` ends at column 49.
    assert_eq!((hit.end_line, hit.end_column), (Some(2), Some(49)));
    assert!(hit.file.as_deref().unwrap().ends_with("w.urdf.xacro"));
    fs::write(
        &path,
        r#"<robot name="w" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="a" value="1"/>
  <link name="l${a}"/>
</robot>"#,
    )
    .unwrap();
    let report = validate(&path, &Options::default()).unwrap().report;
    assert!(with_code(&report.findings, "U010").is_empty());
}

#[test]
fn a_broken_or_stale_srdf_is_u602_and_the_rest_runs() {
    let dir = std::env::temp_dir().join(format!("urdf_validator_u602_{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    let urdf = dir.join("arm.urdf");
    fs::write(&urdf, arm_over_plate(-0.3)).unwrap();
    let srdf = dir.join("arm.srdf");
    let run = || {
        validate(&urdf, &Options::default())
            .expect("validates")
            .report
    };
    // No SRDF: nothing to say.
    assert!(with_code(&run().findings, "U602").is_empty());
    // Truncated: reported, and the workspace still runs.
    fs::write(&srdf, "<robot name=\"r\"><disable_collisions link1=").unwrap();
    let report = run();
    let hit = the_one(&report.findings, "U602");
    assert!(hit.message.contains("arm.srdf"), "{}", hit.message);
    assert!(report.workspace.unwrap().max_reach.is_some());
    // A pair naming a link the robot does not have.
    fs::write(
        &srdf,
        r#"<robot name="r"><disable_collisions link1="base" link2="elbow" reason="Never"/></robot>"#,
    )
    .unwrap();
    let hit_message = the_one(&run().findings, "U602").message.clone();
    assert!(hit_message.contains("elbow"), "{hit_message}");
    // An SRDF of a larger model names many absent links: one finding for the file, not one per name.
    let absent: String = (0..40)
        .map(|i| format!(r#"<disable_collisions link1="base" link2="gone{i}"/>"#))
        .collect();
    fs::write(&srdf, format!(r#"<robot name="r">{absent}</robot>"#)).unwrap();
    let hit_message = the_one(&run().findings, "U602").message.clone();
    assert!(
        hit_message.contains("40 mentions of links the robot does not have")
            && hit_message.contains("'gone2'; …) — those entries are ignored"),
        "{hit_message}"
    );
    // A valid one is used quietly.
    fs::write(
        &srdf,
        r#"<robot name="r"><disable_collisions link1="base" link2="l3" reason="Never"/></robot>"#,
    )
    .unwrap();
    let report = run();
    assert!(with_code(&report.findings, "U602").is_empty());
    assert_eq!(report.workspace.unwrap().self_collision_srdf_disabled, 1);
    // Without `<stem>.srdf`, MoveIt's `<robot name>.srdf` is found.
    fs::rename(&srdf, dir.join("r.srdf")).unwrap();
    let report = run();
    assert_eq!(report.workspace.unwrap().self_collision_srdf_disabled, 1);
    // An explicit --srdf that does not exist is a usage error.
    let options = Options {
        statics: urdf_validator::analysis::statics::StaticsOptions {
            pose: urdf_validator::analysis::pose::PoseOptions {
                srdf: Some(dir.join("missing.srdf")),
                ..Default::default()
            },
            ..Default::default()
        },
        ..Options::default()
    };
    let error = validate(&urdf, &options).expect_err("missing --srdf");
    assert!(error.to_string().contains("missing.srdf"), "{error}");
}

// -------------------------------------------------------------------------------------------------
// URDF versions (urdfdom's URDFVersion) and the XML declaration
// -------------------------------------------------------------------------------------------------

rule_case! {
    u011_unsupported_urdf_version, "U011",
    fires: include_str!("data/rule-examples/u011/fail.urdf"),
    at: (1, 26, "2.0"),
    clean: include_str!("data/rule-examples/u011/pass.urdf"),
}

rule_case! {
    u012_late_xml_declaration, "U012",
    fires: include_str!("data/rule-examples/u012/fail.urdf"),
    at: (3, 1, "<?xml"),
    clean: include_str!("data/rule-examples/u012/pass.urdf"),
}

rule_case! {
    u014_unbound_namespace_prefix, "U014",
    fires: include_str!("data/rule-examples/u014/fail.urdf"),
    at: (3, 12, "sensor:camera"),
    clean: include_str!("data/rule-examples/u014/pass.urdf"),
}

/// Untrusted mode refuses a mesh outside its roots at the filename that asked, naming the path as written;
/// trusted mode (the default) reads it as before.
#[test]
fn u013_access_refused() {
    let root = std::env::temp_dir().join(format!("u013-{}", std::process::id()));
    fs::create_dir_all(&root).unwrap();
    let urdf = "<robot name=\"r\">\n  <link name=\"base\">\n    <visual><geometry><mesh filename=\"file:///etc/hostname\"/></geometry></visual>\n  </link>\n</robot>\n";
    let untrusted = Options {
        sandbox: urdf_validator::input::sandbox::Sandbox::untrusted([root.clone()], Vec::new()),
        ..Options::default()
    };
    let report = validate_text(urdf.to_string(), &root.join("r.urdf"), &untrusted)
        .unwrap()
        .report;
    let refused = &report.findings;
    assert_eq!(
        positions_of(refused, "U013"),
        vec![(3, 39)],
        "{}",
        describe(refused)
    );
    assert!(text_at(urdf, 3, 39).starts_with("file:///etc/hostname\""));
    let finding = the_one(refused, "U013");
    assert_eq!(finding.severity, Severity::Warn);
    assert!(
        finding.message.contains("file:///etc/hostname"),
        "{}",
        finding.message
    );
    let trusted = validate_text(urdf.to_string(), &root.join("r.urdf"), &Options::default())
        .unwrap()
        .report;
    assert_eq!(
        positions_of(&trusted.findings, "U013"),
        Vec::<(u32, u32)>::new()
    );
}

#[test]
fn blank_lines_before_the_xml_declaration_keep_every_position() {
    // Blank lines, spaces and a tab before the declaration, which itself spans two lines and holds a
    // non-ASCII character: every later finding must still point at its own line and column.
    let urdf = "\n \t\n<?xml version=\"1.0\"\n   encoding=\"UTF-8\" standalone=\"yes\"?>\n<!-- Ünïcode -->\n<robot name=\"r\">\n  <link name=\"base\">\n    <bogus/>\n  </link>\n  <joint name=\"j\" type=\"hinge\"/>\n</robot>\n";
    let all = findings(urdf);
    assert_eq!(
        positions_of(&all, "U012"),
        vec![(3, 1)],
        "{}",
        describe(&all)
    );
    assert_eq!(the_one(&all, "U012").severity, Severity::Warn);
    assert_eq!(
        positions_of(&all, "U005"),
        vec![(8, 5)],
        "{}",
        describe(&all)
    );
    assert_eq!(text_at(urdf, 8, 5), "<bogus/>");
    assert_eq!(
        positions_of(&all, "U007"),
        vec![(10, 25)],
        "{}",
        describe(&all)
    );
    assert!(text_at(urdf, 10, 25).starts_with("hinge"));
    // Without a declaration, leading whitespace was always fine and is not U012.
    assert_absent(
        "U012",
        "\n\n<robot name=\"r\">\n  <link name=\"base\"/>\n</robot>\n",
    );
    // `<?xml-stylesheet ...?>` is a processing instruction, legal after whitespace: no U012.
    assert_absent(
        "U012",
        "\n<?xml-stylesheet href=\"a.css\"?>\n<robot name=\"r\">\n  <link name=\"base\"/>\n</robot>\n",
    );
    // Something other than whitespace before the declaration stays an XML error, as in TinyXML2.
    assert_xml_load_error("<!-- c -->\n<?xml version=\"1.0\"?>\n<robot name=\"r\"/>\n");
}

#[test]
fn urdf_version_is_read_as_urdfdom_reads_it() {
    let doc = |version: &str| {
        format!("<robot name=\"r\" version=\"{version}\">\n  <link name=\"base\"/>\n</robot>\n")
    };
    for (version, why) in [
        ("foo", "The version attribute should be in the form 'x.y'"),
        ("1", "The version attribute should be in the form 'x.y'"),
        ("1.0.0", "The version attribute should be in the form 'x.y'"),
        (".1", "One of the fields of the version attribute is blank"),
        ("-1.0", "Version number must be positive"),
        ("a.c", "Version attribute is not an integer"),
        ("1.0~pre6", "Extra characters after the version number"),
        ("2.0", "URDF version 2.0 is not one urdfdom reads"),
    ] {
        let all = findings(&doc(version));
        let hit = the_one(&all, "U011");
        assert!(hit.message.contains(why), "{version}: {}", hit.message);
        assert_eq!(hit.severity, Severity::Critical);
    }
    for version in ["1.0", "1.1", "1.2", "01.00", " 1.1"] {
        assert_absent("U011", &doc(version));
    }
    // No attribute: 1.0.
    assert_absent(
        "U011",
        "<robot name=\"r\">\n  <link name=\"base\"/>\n</robot>\n",
    );
}

/// A link with one visual whose `<origin>` carries `origin` and whose geometry is `shape`.
fn versioned(version: &str, origin: &str, shape: &str) -> String {
    format!(
        "<robot name=\"r\"{version}>\n  <link name=\"base\">\n    <visual>\n      <origin {origin}/>\n      <geometry>{shape}</geometry>\n    </visual>\n  </link>\n</robot>\n"
    )
}

#[test]
fn quat_xyzw_follows_the_declared_version() {
    let quat = r#"quat_xyzw="0 0 0.7071 0.7071""#;
    let sphere = r#"<sphere radius="0.1"/>"#;
    // 1.0 (declared or by default): urdfdom ignores quat_xyzw with a warning; we say so (U006), not U011.
    for version in ["", r#" version="1.0""#] {
        let all = findings(&versioned(version, quat, sphere));
        assert_eq!(
            positions_of(&all, "U006"),
            vec![(4, 15)],
            "{}",
            describe(&all)
        );
        assert!(the_one(&all, "U006").message.contains("ignores"));
        assert!(with_code(&all, "U011").is_empty(), "{}", describe(&all));
    }
    // 1.1: read, no finding.
    let all = findings(&versioned(r#" version="1.1""#, quat, sphere));
    assert!(with_code(&all, "U006").is_empty(), "{}", describe(&all));
    assert!(with_code(&all, "U011").is_empty(), "{}", describe(&all));
    // 1.1 with rpy too: urdfdom refuses the file.
    let urdf = versioned(
        r#" version="1.1""#,
        &format!(r#"rpy="0 0 0" {quat}"#),
        sphere,
    );
    let all = findings(&urdf);
    assert_eq!(
        positions_of(&all, "U011"),
        vec![(4, 27)],
        "{}",
        describe(&all)
    );
    assert!(text_at(&urdf, 4, 27).starts_with("quat_xyzw"));
    // Not four numbers: urdfdom's Vector4 refuses it.
    let all = findings(&versioned(
        r#" version="1.1""#,
        r#"quat_xyzw="0 0 1""#,
        sphere,
    ));
    assert_eq!(with_code(&all, "U003").len(), 1, "{}", describe(&all));
}

#[test]
fn a_capsule_needs_version_1_1() {
    let capsule = r#"<capsule radius="0.1" length="0.5"/>"#;
    for version in ["", r#" version="1.0""#] {
        let urdf = versioned(version, r#"xyz="0 0 0""#, capsule);
        let all = findings(&urdf);
        let at = positions_of(&all, "U011");
        assert_eq!(at.len(), 1, "{}", describe(&all));
        assert!(text_at(&urdf, at[0].0, at[0].1).starts_with("<capsule"));
    }
    assert_absent(
        "U011",
        &versioned(r#" version="1.1""#, r#"xyz="0 0 0""#, capsule),
    );
    assert_absent(
        "U011",
        &versioned(r#" version="1.2""#, r#"xyz="0 0 0""#, capsule),
    );
}

rule_case! {
    u801_unused_suppression, "U801",
    fires: include_str!("data/rule-examples/u801/fail.urdf"),
    at: (2, 30, "U105"),
    clean: include_str!("data/rule-examples/u801/pass.urdf"),
}

rule_case! {
    u802_unknown_rule_code, "U802",
    fires: include_str!("data/rule-examples/u802/fail.urdf"),
    at: (2, 30, "U1O5"),
    clean: include_str!("data/rule-examples/u802/pass.urdf"),
}

/// A finding about the whole robot spans the robot's name, so an editor underlines one word of the
/// `<robot>` tag (it underlined the whole file, and topped every code-action menu in it).
#[test]
fn robot_wide_findings_span_the_name_not_the_file() {
    let text = chain_of_links(51);
    let report = validate_text(text, Path::new(FILE), &Options::default())
        .unwrap()
        .report;
    let hit = the_one(&report.findings, "U105");
    assert_eq!((hit.line, hit.column), (Some(1), Some(14)));
    assert_eq!(
        (hit.end_line, hit.end_column),
        (Some(1), Some(17)),
        "\"big\", end exclusive"
    );
}

/// A root element never closed (`</robot>` deleted) is reported where the end tag is missing, at the end
/// of the file; roxmltree points at 1:1.
#[test]
fn an_unclosed_root_is_reported_at_the_end_of_the_file() {
    let error = validate_text(
        "<robot name=\"r\">\n  <link name=\"a\"/>\n\n".to_string(),
        Path::new(FILE),
        &Options::default(),
    )
    .expect_err("unclosed root");
    let Error::Load(LoadError::Xml {
        line,
        column,
        message,
        ..
    }) = &error
    else {
        panic!("{error:?}")
    };
    assert_eq!((*line, *column), (2, 19), "{error}");
    assert!(message.contains("never closed"), "{message}");
}
