//! `--fix`, `--unsafe-fixes` and `--diff` on files as users write them: a URDF with one finding of each
//! fixable kind, a xacro file whose flagged value is a literal in a macro body (edited there) or comes from a
//! property (not editable here: the finding says where it comes from), and the reference robots.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("urdf_validate_fix_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(args)
        .args(["--samples", "500", "--no-write"])
        .env("NO_COLOR", "1")
        .output()
        .expect("runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Whitespace before `<?xml` (U012, safe), inverted limits (U304, unsafe), a non-unit axis (U310, safe),
/// limits on a continuous joint (U308, safe) and an effort below the gravity torque (U701, unsafe).
const EVERY_KIND: &str = r#"  
<?xml version="1.0"?>
<robot name="r">
  <link name="base"><inertial><mass value="5"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/><origin xyz="0 0 0.5"/>
    <axis xyz="0 2 0"/><limit lower="1" upper="-1" effort="1" velocity="1"/></joint>
  <link name="a"><inertial><origin xyz="0.5 0 0"/><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="j2" type="continuous"><parent link="a"/><child link="b"/><origin xyz="1 0 0"/>
    <axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="10" velocity="1"/></joint>
  <link name="b"><inertial><mass value="0.1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>
</robot>
"#;

fn rules_of(report: &Value, fixable: bool) -> Vec<String> {
    let mut rules: Vec<String> = report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| {
            !fixable
                || f["fix"]["edits"]
                    .as_array()
                    .is_some_and(|edits| !edits.is_empty())
        })
        .map(|f| f["rule"].as_str().unwrap().to_string())
        .collect();
    rules.sort();
    rules.dedup();
    rules
}

fn json_report(path: &Path) -> Value {
    let output = run(&[path.to_str().unwrap(), "--format", "json"]);
    serde_json::from_slice(&output.stdout).expect("a JSON report")
}

#[test]
fn every_fixable_kind_is_reported_with_its_fix_and_marked_in_the_text() {
    let dir = scratch("kinds");
    let file = dir.join("r.urdf");
    std::fs::write(&file, EVERY_KIND).unwrap();
    let report = json_report(&file);
    assert_eq!(
        rules_of(&report, true),
        ["U012", "U304", "U308", "U310", "U701"]
    );
    let axis = report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["rule"] == "U310")
        .unwrap();
    assert_eq!(axis["fix"]["applicability"], "safe");
    let edit = &axis["fix"]["edits"][0];
    assert_eq!(edit["replacement"], "0 1 0");
    assert_eq!(edit["line"], 6);
    assert_eq!(
        &EVERY_KIND
            [edit["start"].as_u64().unwrap() as usize..edit["end"].as_u64().unwrap() as usize],
        "0 2 0"
    );
    let output = run(&[file.to_str().unwrap()]);
    let stdout = text(&output.stdout);
    assert!(
        stdout.contains("[*] Joint 'j1' axis has length 2.0000"),
        "{stdout}"
    );
    assert!(
        stdout.contains("[FIX]  [*] 3 fixable with --fix (2 more with --unsafe-fixes)"),
        "{stdout}"
    );
}

#[test]
fn diff_prints_the_fixes_and_writes_nothing() {
    let dir = scratch("diff");
    let file = dir.join("r.urdf");
    std::fs::write(&file, EVERY_KIND).unwrap();
    let output = run(&[file.to_str().unwrap(), "--diff"]);
    assert_eq!(output.status.code(), Some(1), "{}", text(&output.stderr));
    let diff = text(&output.stdout);
    assert!(diff.contains("-    <axis xyz=\"0 2 0\"/>"), "{diff}");
    assert!(diff.contains("+    <axis xyz=\"0 1 0\"/>"), "{diff}");
    assert!(
        diff.contains("+    <axis xyz=\"1 0 0\"/><limit effort=\"10\" velocity=\"1\"/></joint>"),
        "{diff}"
    );
    // Unsafe fixes only with --unsafe-fixes.
    assert!(!diff.contains("effort=\"16.19\""), "{diff}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), EVERY_KIND);
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        1,
        "no report written"
    );
    let unsafe_diff = text(&run(&[file.to_str().unwrap(), "--diff", "--unsafe-fixes"]).stdout);
    assert!(
        unsafe_diff.contains("<limit lower=\"-1\" upper=\"1\" effort=\"16.19\" velocity=\"1\"/>"),
        "{unsafe_diff}"
    );
}

#[test]
fn fix_applies_safe_fixes_then_unsafe_ones_and_is_idempotent() {
    let dir = scratch("apply");
    let file = dir.join("r.urdf");
    std::fs::write(&file, EVERY_KIND).unwrap();
    let output = run(&[file.to_str().unwrap(), "--fix"]);
    assert!(
        text(&output.stderr)
            .contains("fixed 3 finding(s) in 1 file(s) (2 more with --unsafe-fixes)"),
        "{}",
        text(&output.stderr)
    );
    let after_safe = json_report(&file);
    assert_eq!(rules_of(&after_safe, true), ["U304", "U701"]);
    let output = run(&[file.to_str().unwrap(), "--fix", "--unsafe-fixes"]);
    // What is left is reported from the file as written: nothing.
    assert_eq!(output.status.code(), Some(0), "{}", text(&output.stdout));
    assert!(rules_of(&json_report(&file), false).is_empty());
    let again = run(&[file.to_str().unwrap(), "--diff", "--unsafe-fixes"]);
    assert_eq!(again.status.code(), Some(0));
    assert!(again.stdout.is_empty());
    let fixed = std::fs::read_to_string(&file).unwrap();
    assert!(fixed.starts_with("<?xml"), "{fixed}");
    assert!(roxmltree::Document::parse(&fixed).is_ok());
}

const XACRO: &str = r#"<?xml version="1.0"?>
<robot name="x" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="ax" value="0 0 3"/>
  <xacro:macro name="seg" params="n parent">
    <joint name="j${n}" type="revolute"><parent link="${parent}"/><child link="l${n}"/><origin xyz="0 0 0.1"/>
      <axis xyz="0 2 0"/><limit lower="-1" upper="1" effort="100" velocity="1"/></joint>
    <link name="l${n}"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  </xacro:macro>
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <xacro:seg n="1" parent="base"/>
  <xacro:seg n="2" parent="l1"/>
  <joint name="k" type="revolute"><parent link="l2"/><child link="t"/><axis xyz="${ax}"/><limit lower="-1" upper="1" effort="100" velocity="1"/></joint>
  <link name="t"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="m" type="revolute"><parent link="t"/><child link="u"/><axis xyz="0 ${2*1.5} 0"/><limit lower="-1" upper="1" effort="100" velocity="1"/></joint>
  <link name="u"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
</robot>
"#;

#[test]
fn xacro_literals_and_properties_are_fixed_in_the_source_and_computed_values_say_where_they_come_from(
) {
    let dir = scratch("xacro");
    let file = dir.join("x.urdf.xacro");
    std::fs::write(&file, XACRO).unwrap();
    let report = json_report(&file);
    let axes: Vec<&Value> = report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["rule"] == "U310")
        .collect();
    assert_eq!(axes.len(), 4);
    let axis_of = |joint: &str| {
        *axes
            .iter()
            .find(|f| {
                f["message"]
                    .as_str()
                    .unwrap()
                    .contains(&format!("'{joint}'"))
            })
            .unwrap()
    };
    // `${ax}`: the property's one literal definition is edited, and the fix says so.
    let property = axis_of("k");
    assert_eq!(property["fix"]["edits"][0]["line"], 3, "{property}");
    let description = property["fix"]["description"].as_str().unwrap();
    assert!(
        description.contains("edits the definition of property 'ax' at"),
        "{description}"
    );
    // An expression: not applicable, saying what computes it and where.
    let computed = axis_of("m");
    assert_eq!(computed["fix"]["edits"], Value::Array(Vec::new()));
    let why = computed["fix"]["not_applicable"].as_str().unwrap();
    assert!(
        why.contains("computed from `0 ${2*1.5} 0`") && why.contains("x.urdf.xacro:14:"),
        "{why}"
    );
    let output = run(&[file.to_str().unwrap(), "--fix"]);
    assert!(
        text(&output.stderr).contains("fixed 2 finding(s) in 1 file(s)"),
        "{}",
        text(&output.stderr)
    );
    // The macro's literal is one edit for both joints, not a conflict between them.
    assert!(
        !text(&output.stderr).contains("overlaps"),
        "{}",
        text(&output.stderr)
    );
    let fixed = std::fs::read_to_string(&file).unwrap();
    assert_eq!(
        fixed,
        XACRO
            .replace("<axis xyz=\"0 2 0\"/>", "<axis xyz=\"0 1 0\"/>")
            .replace("value=\"0 0 3\"", "value=\"0 0 1\"")
    );
    // The macro's two joints are fixed by the one edit, k by its property; m is left to the user.
    assert_eq!(rules_of(&json_report(&file), true), Vec::<String>::new());
    assert_eq!(rules_of(&json_report(&file), false), ["U310"]);
}

#[test]
fn a_file_outside_the_inputs_package_is_edited_only_with_unsafe_fixes() {
    let dir = scratch("outside");
    let package = dir.join("robot_description");
    std::fs::create_dir_all(package.join("urdf")).unwrap();
    std::fs::write(
        package.join("package.xml"),
        "<package><name>robot_description</name></package>",
    )
    .unwrap();
    let shared = dir.join("shared_macros");
    std::fs::create_dir_all(&shared).unwrap();
    let macros = XACRO
        .lines()
        .filter(|l| {
            !(l.contains("<link name=\"base\"")
                || l.contains("xacro:seg n=")
                || l.contains("name=\"k\"")
                || l.contains("name=\"t\""))
        })
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(shared.join("seg.xacro"), &macros).unwrap();
    let robot = package.join("urdf/robot.urdf.xacro");
    std::fs::write(
        &robot,
        r#"<robot name="x" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="../../shared_macros/seg.xacro"/>
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <xacro:seg n="1" parent="base"/>
</robot>
"#,
    )
    .unwrap();
    let output = run(&[robot.to_str().unwrap(), "--fix"]);
    let stderr = text(&output.stderr);
    assert!(
        stderr.contains("is outside the input's package"),
        "{stderr}"
    );
    assert_eq!(
        std::fs::read_to_string(shared.join("seg.xacro")).unwrap(),
        macros
    );
    let output = run(&[robot.to_str().unwrap(), "--fix", "--unsafe-fixes"]);
    assert!(
        text(&output.stderr).contains("fixed 1 finding(s)"),
        "{}",
        text(&output.stderr)
    );
    assert!(std::fs::read_to_string(shared.join("seg.xacro"))
        .unwrap()
        .contains("<axis xyz=\"0 1 0\"/>"));
}

/// On the reference robots (read-only here): every fix of `--diff --unsafe-fixes` gives text that parses,
/// and validating that text finds no fixable finding of the kinds applied, except effort fixes a
/// macro shares between joints that need different values (the first wins; noted on stderr).
#[test]
fn the_reference_robots_fixes_give_valid_files() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let output = run(&[robots.to_str().unwrap(), "--diff", "--unsafe-fixes"]);
    assert_eq!(output.status.code(), Some(1), "{}", text(&output.stderr));
    let diff = text(&output.stdout);
    assert!(diff.contains("+++ "), "{diff}");
    assert!(!text(&output.stderr).contains("would not be well-formed XML"));
}

/// Copy the folder `from` into `to`, recursively.
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// The findings of `rule` about `link` in a JSON report.
fn findings_about<'a>(report: &'a Value, rule: &str, link: &str) -> Vec<&'a Value> {
    let quoted = format!("Link '{link}'");
    report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["rule"] == rule && f["message"].as_str().unwrap().contains(&quoted))
        .collect()
}

/// PR2's `sensor_mount_link` (example-robot-data) breaks A + B ≥ C (0.001 + 0.001 < 0.01): the unsafe fix
/// writes the inertia of its 1 cm visual box at the declared 0.05 kg (m s²/6 = 8.33333e-7), the finding is
/// gone and the file parses; the caster wheels' U209 (0.0124 kg·m² on a 0.44 kg, 16 cm wheel) is fixed too.
#[test]
fn pr2_sensor_mount_link_gets_its_geometrys_inertia() {
    let Some(corpus) = common::corpus() else {
        return;
    };
    let dir = scratch("pr2");
    let file = dir.join("pr2.urdf");
    std::fs::copy(corpus.join("pr2_description/urdf/pr2.urdf"), &file).unwrap();
    let before = json_report(&file);
    assert_eq!(
        findings_about(&before, "U206", "sensor_mount_link").len(),
        1
    );
    let fix = &findings_about(&before, "U206", "sensor_mount_link")[0]["fix"];
    assert_eq!(fix["applicability"], "unsafe", "{fix}");
    let output = run(&[file.to_str().unwrap(), "--fix", "--unsafe-fixes"]);
    assert!(output.status.code().is_some(), "{}", text(&output.stderr));
    let fixed = std::fs::read_to_string(&file).unwrap();
    assert!(roxmltree::Document::parse(&fixed).is_ok());
    assert!(
        fixed.contains(r#"<inertia ixx="8.33333e-7" ixy="0" ixz="0" iyy="8.33333e-7" iyz="0" izz="8.33333e-7"/>"#),
        "{fixed}"
    );
    let after = json_report(&file);
    for rule in ["U204", "U205", "U206", "U208", "U209"] {
        let left: Vec<&Value> = after["findings"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|f| f["rule"] == rule)
            .collect();
        assert!(left.is_empty(), "{rule} left after the fix: {left:?}");
    }
}

/// Spot (../shared/robots) has moving links without `<inertial>` (U201): the unsafe fix inserts one guessed
/// from the link's collision meshes at 1000 kg/m³, the findings are gone and the file parses.
#[test]
fn spot_links_without_inertial_get_a_guessed_one() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let dir = scratch("spot");
    copy_tree(&robots.join("spot/spot_description"), &dir);
    let file = dir.join("model.urdf");
    let before = json_report(&file);
    let missing: Vec<&Value> = before["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["rule"] == "U201")
        .collect();
    // Links without geometry have nothing to guess from: no fix.
    let fixable: Vec<&&Value> = missing.iter().filter(|f| !f["fix"].is_null()).collect();
    assert!(!fixable.is_empty(), "{missing:?}");
    for finding in &fixable {
        let description = finding["fix"]["description"].as_str().unwrap();
        assert!(
            description.contains("guessed") && description.contains("1000 kg/m³"),
            "{description}"
        );
    }
    run(&[file.to_str().unwrap(), "--fix", "--unsafe-fixes"]);
    let fixed = std::fs::read_to_string(&file).unwrap();
    assert!(roxmltree::Document::parse(&fixed).is_ok());
    let after = json_report(&file);
    let left = after["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["rule"] == "U201")
        .count();
    assert_eq!(left, missing.len() - fixable.len());
    assert!(
        rules_of(&after, true)
            .iter()
            .all(|r| !["U201", "U208", "U209"].contains(&r.as_str())),
        "{:?}",
        rules_of(&after, true)
    );
}

/// A moving 1 m × 0.1 m × 0.1 m box link without `<inertial>` (U201: guessed at 1000 kg/m³, 10 kg) on a
/// joint declaring 1 N·m: only once the inertial is written does the joint need more effort (U701).
const CHAINED: &str = r#"<?xml version="1.0"?>
<robot name="r">
  <link name="base"><inertial><mass value="5"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.5"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="arm">
    <collision><origin xyz="0.5 0 0"/><geometry><box size="1 0.1 0.1"/></geometry></collision>
  </link>
</robot>
"#;

#[test]
fn fix_passes_again_when_a_fix_calls_for_another() {
    let dir = scratch("chained");
    let path = dir.join("arm.urdf");
    std::fs::write(&path, CHAINED).unwrap();
    let file = path.to_str().unwrap();
    assert_eq!(rules_of(&json_report(&path), true), vec!["U201"]);
    let fixed = run(&[file, "--fix", "--unsafe-fixes"]);
    let stderr = text(&fixed.stderr);
    assert!(
        stderr.contains("fixed 2 finding(s) in 1 file(s) in 2 passes"),
        "{stderr}"
    );
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("<mass value=\"10\"/>"), "{text}");
    // 10 kg, 0.5 m out: 49.05 N·m, declared 1.5× that.
    assert!(text.contains("effort=\"73.58\""), "{text}");
    assert!(rules_of(&json_report(&path), true).is_empty());
}
