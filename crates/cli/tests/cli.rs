//! End-to-end tests of the `urdf_validate` binary: exit codes, files written, error lines, colour.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn temp_dir() -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "urdf_validate_cli_{}_{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::SeqCst)
    ));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(args)
        .env_remove("NO_COLOR")
        .env_remove("CLICOLOR_FORCE")
        .output()
        .expect("runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

const GOOD: &str = r#"<robot name="good">
  <link name="base"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <link name="arm">
    <inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
  </link>
</robot>
"#;

const WARNING: &str = r#"<robot name="warn">
  <link name="base"/>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
  <link name="arm"/>
</robot>
"#;

fn write(dir: &Path, name: &str, content: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, content).expect("write");
    path
}

#[test]
fn example_robot_passes() {
    let out = temp_dir();
    let example = repo_root().join("examples/robots/mobile_manipulator.urdf");
    let result = run(&[
        example.to_str().unwrap(),
        "--output-dir",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        result.status.code(),
        Some(0),
        "{}{}",
        text(&result.stdout),
        text(&result.stderr)
    );
    assert!(out.join("mobile_manipulator_validation.json").is_file());
}

#[test]
fn exit_codes_follow_the_status_and_a_batch_takes_the_worst() {
    let dir = temp_dir();
    let good = write(&dir, "good.urdf", GOOD);
    let warn = write(&dir, "warn.urdf", WARNING);
    assert_eq!(
        run(&[good.to_str().unwrap(), "--no-write"]).status.code(),
        Some(0)
    );
    assert_eq!(
        run(&[warn.to_str().unwrap(), "--no-write"]).status.code(),
        Some(1)
    );
    let batch = run(&[dir.to_str().unwrap(), "--no-write"]);
    assert_eq!(batch.status.code(), Some(1));
    let stdout = text(&batch.stdout);
    assert!(stdout.contains("Summary: 2 file(s)"), "{stdout}");
    assert!(stdout.contains("1 PASS · 1 WARN"), "{stdout}");
}

#[test]
fn report_is_written_beside_the_input_as_strict_json() {
    let dir = temp_dir();
    let good = write(&dir, "good.urdf", GOOD);
    let result = run(&[good.to_str().unwrap()]);
    assert_eq!(result.status.code(), Some(0));
    let report_path = dir.join("good_validation.json");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report_path).expect("report written"))
            .expect("JSON");
    assert_eq!(report["robot_name"], "good");
    assert_eq!(report["overall_status"], "PASS");
    assert!(text(&result.stdout).contains(&format!("Full report: {}", report_path.display())));
}

#[test]
fn json_format_prints_the_report_on_stdout() {
    let dir = temp_dir();
    let warn = write(&dir, "warn.urdf", WARNING);
    let result = run(&[warn.to_str().unwrap(), "--format", "json", "--no-write"]);
    let report: serde_json::Value = serde_json::from_slice(&result.stdout).expect("stdout is JSON");
    assert_eq!(report["overall_status"], "WARN");
    let finding = &report["findings"].as_array().expect("findings")[0];
    assert_eq!(finding["rule"], "U201");
    assert_eq!(finding["line"], 4);
}

#[test]
fn malformed_xml_exits_2_with_one_located_line() {
    let dir = temp_dir();
    let broken = write(
        &dir,
        "broken.urdf",
        "<robot name=\"x\">\n  <link name=\"a\">\n</robot>\n",
    );
    let result = run(&[broken.to_str().unwrap()]);
    assert_eq!(result.status.code(), Some(2));
    let stderr = text(&result.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("broken.urdf:3:"), "{stderr}");
    assert!(stderr.contains("expected"), "{stderr}");
    assert!(!stderr.contains("panicked"));
    assert!(!dir.join("broken_validation.json").exists());
}

#[test]
fn missing_and_binary_inputs_exit_2_without_panicking() {
    let dir = temp_dir();
    let junk = dir.join("junk.urdf");
    std::fs::write(&junk, [0xff_u8, 0xfe, 0x00, 0x12]).expect("write");
    for input in [dir.join("absent.urdf"), junk] {
        let result = run(&[input.to_str().unwrap(), "--no-write"]);
        assert_eq!(result.status.code(), Some(2));
        let stderr = text(&result.stderr);
        assert!(
            stderr.contains(input.file_name().unwrap().to_str().unwrap()),
            "{stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn explain_prints_the_rule_doc() {
    let result = run(&["--explain", "U205"]);
    assert_eq!(result.status.code(), Some(0));
    let stdout = text(&result.stdout);
    assert!(
        stdout.contains("inertia-not-positive-definite") && stdout.contains("How to fix"),
        "{stdout}"
    );
    let by_name = run(&["--explain", "missing-inertial"]);
    assert!(text(&by_name.stdout).starts_with("U201"));
    let unknown = run(&["--explain", "U2O5"]);
    assert_eq!(unknown.status.code(), Some(2));
    assert!(text(&unknown.stderr).contains("did you mean"));
}

#[test]
fn colour_only_when_asked_or_on_a_terminal() {
    let dir = temp_dir();
    let warn = write(&dir, "warn.urdf", WARNING);
    let piped = run(&[warn.to_str().unwrap(), "--no-write"]);
    assert!(
        !text(&piped.stdout).contains('\x1b'),
        "piped output must be plain"
    );
    let forced = run(&[warn.to_str().unwrap(), "--no-write", "--color", "always"]);
    assert!(text(&forced.stdout).contains('\x1b'));
    let never = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args([warn.to_str().unwrap(), "--no-write"])
        .env("NO_COLOR", "1")
        .env("CLICOLOR_FORCE", "1")
        .output()
        .expect("runs");
    assert!(
        !text(&never.stdout).contains('\x1b'),
        "NO_COLOR wins over CLICOLOR_FORCE"
    );
}

#[test]
fn warnings_show_a_source_snippet() {
    let dir = temp_dir();
    let warn = write(&dir, "warn.urdf", WARNING);
    let stdout = text(&run(&[warn.to_str().unwrap(), "--no-write"]).stdout);
    assert!(
        stdout.contains(&format!("--> {}:4:3", warn.display())),
        "{stdout}"
    );
    assert!(stdout.contains("4 |   <link name=\"arm\"/>"), "{stdout}");
}

#[test]
fn same_stem_in_one_output_dir_does_not_overwrite() {
    let (a, b, out) = (temp_dir(), temp_dir(), temp_dir());
    let first = write(&a, "robot.urdf", GOOD);
    let second = write(&b, "robot.urdf", WARNING);
    run(&[
        first.to_str().unwrap(),
        second.to_str().unwrap(),
        "--output-dir",
        out.to_str().unwrap(),
    ]);
    assert!(out.join("robot_validation.json").is_file());
    assert!(out.join("robot_2_validation.json").is_file());
}

#[test]
fn unknown_joint_in_joint_angles_exits_2_with_a_suggestion() {
    let dir = temp_dir();
    let good = write(&dir, "good.urdf", GOOD);
    let result = run(&[
        good.to_str().unwrap(),
        "--no-write",
        "--pose",
        "custom",
        "--joint-angles",
        "jj=0.3",
    ]);
    assert_eq!(result.status.code(), Some(2));
    let stderr = text(&result.stderr);
    assert!(
        stderr.contains("unknown joint 'jj'") && stderr.contains("did you mean 'j'"),
        "{stderr}"
    );
}

#[test]
fn statics_flags_reach_the_report() {
    let dir = temp_dir();
    let good = write(&dir, "good.urdf", GOOD);
    let result = run(&[
        good.to_str().unwrap(),
        "--no-write",
        "--format",
        "json",
        "--pose",
        "worst",
        "--samples",
        "200",
        "--seed",
        "3",
        "--payload-mass",
        "0.5",
    ]);
    let report: serde_json::Value = serde_json::from_slice(&result.stdout).expect("JSON");
    let statics = &report["statics"];
    assert_eq!(statics["pose"], "worst");
    assert_eq!(statics["samples"], 200);
    assert_eq!(statics["seed"], 3);
    assert_eq!(statics["payload_mass"], 0.5);
    assert_eq!(statics["payload_link"], "arm");
    let text_out = text(&run(&[good.to_str().unwrap(), "--no-write", "--pose", "limits"]).stdout);
    assert!(
        text_out.contains("[STATICS]  joints: PASS") && text_out.contains("(pose: limits)"),
        "{text_out}"
    );
}

const XACRO_LIBRARY: &str = r#"<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm_link" params="name mass">
    <link name="${name}">
      <inertial><mass value="${mass}"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    </link>
  </xacro:macro>
</robot>
"#;

const XACRO_ROBOT: &str = r#"<robot name="xr" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="mass" default="1"/>
  <xacro:include filename="lib.xacro"/>
  <link name="base"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <xacro:arm_link name="arm" mass="$(arg mass)"/>
</robot>
"#;

#[test]
fn xacro_arguments_reach_the_expansion() {
    let dir = temp_dir();
    write(&dir, "lib.xacro", XACRO_LIBRARY);
    let robot = write(&dir, "xr.urdf.xacro", XACRO_ROBOT);
    let robot = robot.to_str().unwrap();
    let mass = |args: &[&str]| -> f64 {
        let mut all = vec![robot, "--no-write", "--format", "json"];
        all.extend_from_slice(args);
        let out = run(&all);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
        let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
        report["statics"]["total_mass"].as_f64().expect("a mass")
    };
    assert_eq!(mass(&[]), 1.0);
    assert_eq!(mass(&["mass:=2.5"]), 2.5);
    assert_eq!(mass(&["--xacro-arg", "mass=4"]), 4.0);
    assert_eq!(mass(&["--xacro-arg", "mass:=5"]), 5.0, "xacro's spelling");
    let bad = run(&[robot, "--no-write", "--xacro-arg", "ma:ss=1"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        text(&bad.stderr).contains("'ma:ss=1'"),
        "{}",
        text(&bad.stderr)
    );
}

#[test]
fn expand_only_prints_the_urdf() {
    let dir = temp_dir();
    write(&dir, "lib.xacro", XACRO_LIBRARY);
    let robot = write(&dir, "xr.urdf.xacro", XACRO_ROBOT);
    let out = run(&[robot.to_str().unwrap(), "--expand-only", "mass:=3"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let urdf = text(&out.stdout);
    assert!(urdf.starts_with("<?xml"), "{urdf}");
    assert!(urdf.contains(r#"<mass value="3"/>"#), "{urdf}");
    assert!(!urdf.contains("xacro:"), "{urdf}");
    // An undefined argument is an error naming the file and line.
    let bad = write(
        &dir,
        "bad.urdf.xacro",
        r#"<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="$(arg nope)"/></robot>"#,
    );
    let out = run(&[bad.to_str().unwrap(), "--expand-only"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("bad.urdf.xacro:1:"),
        "{}",
        text(&out.stderr)
    );
}

#[test]
fn a_directory_includes_robot_xacros_but_not_macro_libraries() {
    let dir = temp_dir();
    write(&dir, "lib.xacro", XACRO_LIBRARY);
    write(&dir, "xr.urdf.xacro", XACRO_ROBOT);
    // A library of materials is not a robot either.
    write(
        &dir,
        "materials.xacro",
        r#"<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><material name="red"><color rgba="1 0 0 1"/></material></robot>"#,
    );
    let out = run(&[dir.to_str().unwrap(), "--no-write", "--format", "json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let reports: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let paths: Vec<&str> = match &reports {
        serde_json::Value::Array(items) => items
            .iter()
            .map(|r| r["urdf_path"].as_str().unwrap())
            .collect(),
        single => vec![single["urdf_path"].as_str().unwrap()],
    };
    assert_eq!(paths.len(), 1, "{paths:?}");
    assert!(paths[0].ends_with("xr.urdf.xacro"));
}

#[test]
fn json_is_an_object_for_one_named_file_only() {
    let dir = temp_dir();
    let good = write(&dir, "good.urdf", GOOD);
    let out = run(&[good.to_str().unwrap(), "--no-write", "--format", "json"]);
    assert!(text(&out.stdout).trim_start().starts_with('{'));
    // A directory holding one file still gives an array, so scripts do not break when a file is added.
    let out = run(&[dir.to_str().unwrap(), "--no-write", "--format", "json"]);
    assert!(
        text(&out.stdout).trim_start().starts_with('['),
        "{}",
        text(&out.stdout)
    );
    // A named file that cannot be loaded prints no JSON (the error is on stderr, exit 2).
    let bad = write(&dir, "bad.urdf", "<robot");
    let out = run(&[bad.to_str().unwrap(), "--no-write", "--format", "json"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stdout).trim().is_empty(), "{}", text(&out.stdout));
    assert!(text(&out.stderr).contains("bad.urdf"));
}

#[test]
fn expand_only_takes_one_xacro_file() {
    let dir = temp_dir();
    write(&dir, "lib.xacro", XACRO_LIBRARY);
    let robot = write(&dir, "xr.urdf.xacro", XACRO_ROBOT);
    let out = run(&[dir.to_str().unwrap(), "--expand-only"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("one xacro file"),
        "{}",
        text(&out.stderr)
    );
    let robot = robot.to_str().unwrap();
    let out = run(&[robot, robot, "--expand-only"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn a_misspelled_xacro_argument_is_warned_with_the_close_name() {
    let dir = temp_dir();
    let robot = write(
        &dir,
        "flag.urdf.xacro",
        r#"<robot name="flag" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="flag" default="default"/>
  <link name="base_$(arg flag)"/>
</robot>"#,
    );
    for args in [
        vec![robot.to_str().unwrap(), "flg:=given", "--no-write"],
        vec![
            robot.to_str().unwrap(),
            "--xacro-arg",
            "flg=given",
            "--no-write",
        ],
    ] {
        let out = text(&run(&args).stdout);
        assert!(out.contains("argument 'flg' was given"), "{out}");
        assert!(out.contains("did you mean 'flag'?"), "{out}");
    }
    let out = text(&run(&[robot.to_str().unwrap(), "flag:=given", "--no-write"]).stdout);
    assert!(!out.contains("was given"), "{out}");
}

#[test]
fn several_arms_can_be_declared_in_pairs() {
    let example = repo_root().join("examples/robots/mobile_manipulator.urdf");
    let example = example.to_str().unwrap();
    let mut args = vec![
        example,
        "--no-write",
        "--format",
        "json",
        "--samples",
        "500",
    ];
    args.extend([
        "--arm-root",
        "arm_mount_link",
        "--arm-tip",
        "tool0",
        "--arm-root",
        "shoulder_link",
        "--arm-tip",
        "wrist_2_link",
    ]);
    let out = run(&args);
    assert!(
        out.status.code().is_some_and(|c| c <= 2),
        "{}",
        text(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let tips: Vec<&str> = report["workspace"]["arms"]
        .as_array()
        .expect("arms")
        .iter()
        .map(|arm| arm["tip_link"].as_str().unwrap())
        .collect();
    assert_eq!(tips, ["tool0", "wrist_2_link"]);
    // Roots and tips go in pairs.
    let unpaired = run(&[
        example,
        "--no-write",
        "--arm-root",
        "arm_mount_link",
        "--arm-root",
        "shoulder_link",
        "--arm-tip",
        "tool0",
    ]);
    assert_eq!(unpaired.status.code(), Some(2));
    assert!(
        text(&unpaired.stderr).contains("2 --arm-root but 1 --arm-tip"),
        "{}",
        text(&unpaired.stderr)
    );
}

#[test]
fn simulator_gazebo_reports_what_sdformat_does_to_the_mobile_manipulator() {
    let robot = repo_root().join("examples/robots/mobile_manipulator.urdf");
    let out = run(&[
        "--format",
        "json",
        "--no-write",
        "--simulator",
        "gazebo",
        robot.to_str().unwrap(),
    ]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a JSON report");
    let lumped: Vec<(u64, String)> = report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["rule"].as_str().is_some_and(|r| r.starts_with("U75")))
        .map(|f| {
            assert_eq!(f["rule"], "U750", "{f}");
            (
                f["line"].as_u64().unwrap(),
                f["message"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    let lines: Vec<u64> = lumped.iter().map(|(line, _)| *line).collect();
    // The six fixed joints; every massless frame is lumped into a link with mass, so none is dropped (U751).
    assert_eq!(lines, [51, 141, 168, 196, 205, 423], "{lumped:?}");
    assert!(
        lumped[0]
            .1
            .contains("link 'base_link' is merged into 'base_footprint'"),
        "{lumped:?}"
    );
    assert!(
        lumped[5]
            .1
            .contains("link 'tool0' is merged into 'wrist_3_link'"),
        "{lumped:?}"
    );
}

#[test]
fn simulator_names_are_checked_and_comma_lists_accepted() {
    let robot = repo_root().join("examples/robots/mobile_manipulator.urdf");
    let out = run(&[
        "--no-write",
        "--simulator",
        "webots",
        robot.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(
        err.contains("invalid value 'webots' for '--simulator <NAME>'"),
        "{err}"
    );
    assert!(
        err.contains("mujoco, gazebo, pybullet, drake, isaac"),
        "{err}"
    );
    let out = run(&[
        "--format",
        "json",
        "--no-write",
        "--simulator",
        "mujoco,drake",
        "--simulator",
        "pybullet",
        robot.to_str().unwrap(),
    ]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a JSON report");
    let rules: Vec<&str> = report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|f| f["rule"].as_str())
        .collect();
    for code in ["U754", "U757", "U758"] {
        assert!(rules.contains(&code), "{code} missing: {rules:?}");
    }
}

#[test]
fn sdf_files_run_end_to_end_and_directories_pick_them_up() {
    let sdf = repo_root().join("crates/urdf-validator/tests/data/sdf/nested_arm.sdf");
    let result = run(&[sdf.to_str().unwrap(), "--no-write", "--samples", "500"]);
    assert_eq!(result.status.code(), Some(0), "{}", text(&result.stdout));
    assert!(text(&result.stdout).contains("[STATICS]"));
    let dir = temp_dir();
    let weak = r#"<?xml version="1.0"?>
<sdf version="1.9">
  <model name="weak">
    <link name="base"/>
    <joint name="fix" type="fixed"><parent>world</parent><child>base</child></joint>
    <link name="arm"><inertial><pose>0.5 0 0 0 0 0</pose><mass>4</mass></inertial></link>
    <joint name="shoulder" type="revolute">
      <parent>base</parent><child>arm</child>
      <axis><xyz>0 1 0</xyz><limit><lower>-1</lower><upper>1</upper>
        <effort>2</effort><velocity>1</velocity></limit></axis>
    </joint>
  </model>
</sdf>
"#;
    write(&dir, "weak.sdf", weak);
    write(
        &dir,
        "empty.world",
        "<sdf version=\"1.9\"><world name=\"w\"/></sdf>\n",
    );
    let result = run(&[dir.to_str().unwrap(), "--no-write", "--samples", "500"]);
    let stdout = text(&result.stdout);
    assert_eq!(result.status.code(), Some(2), "{stdout}");
    // The undersized joint is found at its <effort> line; the world is validated too.
    assert!(stdout.contains("weak.sdf:10:9  U701"), "{stdout}");
    assert!(stdout.contains("empty.world"), "{stdout}");
    assert!(stdout.contains("U020"), "{stdout}");
}

#[test]
fn mjcf_files_run_end_to_end_and_directories_pick_up_only_mujoco_xml() {
    let dir = temp_dir();
    let arm = r#"<mujoco model="arm">
  <compiler angle="degree"/>
  <include file="parts/defaults.xml"/>
  <worldbody>
    <body name="upper" pos="0 0 1">
      <joint name="shoulder" axis="0 1 0" range="-90 90"/>
      <geom class="link" fromto="0 0 0 0.5 0 0"/>
    </body>
  </worldbody>
</mujoco>
"#;
    write(&dir, "arm.xml", arm);
    std::fs::create_dir_all(dir.join("parts")).unwrap();
    write(
        &dir,
        "parts/defaults.xml",
        "<mujoco><default><default class=\"link\"><geom type=\"capsule\" size=\"0.05\" mass=\"2\"/></default></default></mujoco>\n",
    );
    write(
        &dir,
        "notes.xml",
        "<notes><note>not a model</note></notes>\n",
    );
    let arm_path = dir.join("arm.xml");
    let result = run(&[arm_path.to_str().unwrap(), "--no-write", "--format", "json"]);
    let report: serde_json::Value = serde_json::from_slice(&result.stdout).unwrap();
    // 2 kg at 0.25 m from the shoulder: 4.905 N·m, read through the include and the default class.
    let mass = report["statics"]["total_mass"].as_f64().unwrap();
    assert!((mass - 2.0).abs() < 1e-12, "{report}");
    let torque = report["statics"]["joints"][0]["required_torque_gravity"]
        .as_f64()
        .unwrap();
    assert!((torque.abs() - 2.0 * 9.81 * 0.25).abs() < 1e-9, "{report}");
    let result = run(&[dir.to_str().unwrap(), "--no-write", "--samples", "500"]);
    let stdout = text(&result.stdout);
    assert!(stdout.contains("arm.xml"), "{stdout}");
    assert!(stdout.contains("defaults.xml"), "{stdout}");
    assert!(!stdout.contains("notes.xml"), "{stdout}");
}

#[test]
fn pose_key_takes_an_mjcf_keyframe_and_an_unknown_one_exits_2_listing_the_keys() {
    let dir = temp_dir();
    let model = write(
        &dir,
        "arm.xml",
        r#"<mujoco><worldbody><body name="arm"><joint name="j" axis="0 1 0"/>
<geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.02" mass="1"/></body></worldbody>
<keyframe><key name="up" qpos="1.25"/><key name="flat" qpos="0"/></keyframe></mujoco>"#,
    );
    let path = model.to_str().unwrap();
    let result = run(&[path, "--no-write", "--format", "json", "--pose", "key:up"]);
    let report: serde_json::Value = serde_json::from_slice(&result.stdout).expect("JSON");
    assert_eq!(report["statics"]["pose"], "key:up");
    assert!((report["statics"]["configuration"]["j"].as_f64().unwrap() - 1.25).abs() < 1e-12);
    let result = run(&[path, "--no-write", "--pose", "key:down"]);
    assert_eq!(result.status.code(), Some(2));
    let stderr = text(&result.stderr);
    assert!(
        stderr.contains("no keyframe 'down' (its keys: up, flat)"),
        "{stderr}"
    );
    let good = write(&dir, "good.urdf", GOOD);
    let result = run(&[good.to_str().unwrap(), "--no-write", "--pose", "key:up"]);
    assert_eq!(result.status.code(), Some(2));
    assert!(text(&result.stderr).contains("keyframes are MJCF's"));
    let result = run(&[path, "--no-write", "--pose", "key:"]);
    assert_eq!(result.status.code(), Some(2));
    assert!(text(&result.stderr).contains("key:NAME"));
}
