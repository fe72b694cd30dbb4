//! `--override KEY=VALUE` and `--override-file`: the robot evaluated with values changed, the file untouched,
//! the report listing what was overridden; a name the robot does not have is a usage error naming the
//! closest ones.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::PathBuf;
use std::process::{Command, Output};

use serde_json::Value;

/// A 2 kg arm link 0.5 m out on a joint declaring 1 N·m: undersized (needs 9.81 N·m).
const ARM: &str = r#"<robot name="r">
  <link name="base"><inertial><mass value="5"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.5"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="arm"><inertial><origin xyz="0.5 0 0"/><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
</robot>
"#;

fn robot(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "urdf_validate_overrides_{}_{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("arm.urdf");
    std::fs::write(&path, ARM).unwrap();
    path
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(args)
        .args(["--no-write", "--samples", "200"])
        .env("NO_COLOR", "1")
        .output()
        .expect("runs")
}

fn shoulder_margin(report: &Value) -> f64 {
    report["statics"]["joints"]
        .as_array()
        .unwrap()
        .iter()
        .find(|j| j["name"] == "shoulder")
        .unwrap()["margin"]
        .as_f64()
        .unwrap()
}

#[test]
fn an_effort_override_changes_the_verdict_and_is_listed() {
    let file = robot("effort");
    let before: Value =
        serde_json::from_slice(&run(&[file.to_str().unwrap(), "--format", "json"]).stdout).unwrap();
    assert_eq!(before["overall_status"], "FAIL");
    assert!(before.get("overrides").is_none());
    let output = run(&[
        file.to_str().unwrap(),
        "--format",
        "json",
        "--override",
        "joint.shoulder.effort=80",
    ]);
    let after: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(after["overall_status"], "PASS", "{after}");
    assert!((shoulder_margin(&after) - 80.0 / (2.0 * 9.81 * 0.5)).abs() < 1e-6);
    let listed = &after["overrides"][0];
    assert_eq!(
        (&listed["key"], &listed["value"], &listed["was"]),
        (&"joint.shoulder.effort".into(), &"80".into(), &"1".into()),
        "{after}"
    );
    // The edit that would write it (--fix --from-overrides): the effort value, 80.
    let edit = &listed["fix"]["edits"][0];
    let start = edit["start"].as_u64().unwrap() as usize;
    assert_eq!(&ARM[start..edit["end"].as_u64().unwrap() as usize], "1");
    assert_eq!(edit["replacement"], "80");
    assert_eq!(
        std::fs::read_to_string(&file).unwrap(),
        ARM,
        "the file is untouched"
    );
    let text = String::from_utf8_lossy(
        &run(&[
            file.to_str().unwrap(),
            "--override",
            "joint.shoulder.effort=80",
        ])
        .stdout,
    )
    .into_owned();
    assert!(
        text.contains("[OVERRIDES]  evaluated with joint.shoulder.effort = 80 (file: 1); the file is unchanged"),
        "{text}"
    );
}

#[test]
fn mass_com_and_payload_overrides_move_the_gravity_torque() {
    let file = robot("mass");
    let output = run(&[
        file.to_str().unwrap(),
        "--format",
        "json",
        "--override",
        "joint.shoulder.effort=100",
        "--override",
        "link.arm.mass=4",
        "--override",
        "link.arm.com=0.25,0,0",
    ]);
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    // 4 kg at 0.25 m: the same 9.81 N·m as 2 kg at 0.5 m.
    assert!(
        (shoulder_margin(&report) - 100.0 / 9.81).abs() < 1e-6,
        "{report}"
    );
    let dir = file.parent().unwrap();
    let overrides = dir.join("overrides.toml");
    std::fs::write(
        &overrides,
        "[joint.shoulder]\neffort = 100\n[payload]\nmass = 1\n",
    )
    .unwrap();
    let output = run(&[
        file.to_str().unwrap(),
        "--format",
        "json",
        "--override-file",
        overrides.to_str().unwrap(),
        "--payload-link",
        "arm",
    ]);
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    // The payload's mass is the statics' (held at the arm link's origin, on the joint axis).
    assert_eq!(report["overrides"][1]["key"], "payload.mass", "{report}");
    assert_eq!(report["statics"]["payload_mass"], 1.0, "{report}");
}

#[test]
fn unknown_names_and_bad_values_are_usage_errors() {
    let file = robot("errors");
    let output = run(&[
        file.to_str().unwrap(),
        "--override",
        "joint.shouldr.effort=80",
    ]);
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("the robot has no joint 'shouldr' (did you mean 'shoulder'?)"),
        "{stderr}"
    );
    for bad in [
        "joint.shoulder.torque=1",
        "link.arm.mass=-2",
        "link.arm.com=1,2",
        "joint.shoulder.effort",
    ] {
        let output = run(&[file.to_str().unwrap(), "--override", bad]);
        assert_eq!(output.status.code(), Some(2), "{bad}");
        assert!(
            String::from_utf8_lossy(&output.stderr).contains("override '"),
            "{bad}"
        );
    }
    let output = run(&[
        file.to_str().unwrap(),
        "--override",
        "joint.shoulder.effort=8",
        "--fix",
    ]);
    assert_eq!(
        output.status.code(),
        Some(2),
        "--fix with --override is refused"
    );
}

#[test]
fn from_overrides_writes_the_values_into_the_file() {
    let file = robot("from_overrides");
    let path = file.to_str().unwrap();
    let overrides = [
        "--override",
        "joint.shoulder.effort=20",
        "--override",
        "joint.shoulder.upper=1.5",
        "--override",
        "link.arm.mass=1.5",
        "--override",
        "link.arm.com=0.25,0,0.125",
        // No <origin> in base's <inertial>: nothing to hold it, reported and left out.
        "--override",
        "link.base.com=0,0,0.1",
    ];
    let evaluated: Value = serde_json::from_slice(
        &run(&[&[path, "--format", "json"][..], &overrides[..]].concat()).stdout,
    )
    .unwrap();
    assert_eq!(
        evaluated["overrides"][0]["fix"]["applicability"], "unsafe",
        "{evaluated}"
    );
    assert!(
        evaluated["overrides"][4].get("fix").is_none(),
        "{evaluated}"
    );

    // --diff shows the edits and writes nothing.
    let diff = run(&[&[path, "--diff", "--from-overrides"][..], &overrides[..]].concat());
    assert_eq!(diff.status.code(), Some(1));
    let shown = String::from_utf8_lossy(&diff.stdout);
    assert!(shown.contains(r#"+    <axis xyz="0 1 0"/><limit lower="-1" upper="1.5" effort="20" velocity="1"/></joint>"#), "{shown}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), ARM);

    let fixed = run(&[&[path, "--fix", "--from-overrides"][..], &overrides[..]].concat());
    let stderr = String::from_utf8_lossy(&fixed.stderr);
    assert!(
        stderr.contains("override link.base.com: the file declares no attribute to hold it"),
        "{stderr}"
    );
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(
        text.contains(r#"<limit lower="-1" upper="1.5" effort="20" velocity="1"/>"#),
        "{text}"
    );
    assert!(
        text.contains(r#"<origin xyz="0.25 0 0.125"/><mass value="1.5"/>"#),
        "{text}"
    );
    assert!(!text.contains("0 0 0.1"), "{text}");
    // The file alone now gives what the overrides gave (but base's COM, which was not written).
    let after: Value = serde_json::from_slice(&run(&[path, "--format", "json"]).stdout).unwrap();
    let with_written: Value = serde_json::from_slice(
        &run(&[&[path, "--format", "json"][..], &overrides[..8]].concat()).stdout,
    )
    .unwrap();
    assert_eq!(shoulder_margin(&after), shoulder_margin(&with_written));
    assert!(after.get("overrides").is_none());
}

#[test]
fn from_overrides_needs_fix_or_diff_and_an_override() {
    let file = robot("from_overrides_usage");
    let path = file.to_str().unwrap();
    for (args, said) in [
        (
            &[
                path,
                "--from-overrides",
                "--override",
                "joint.shoulder.effort=8",
            ][..],
            "give it with --fix or --diff",
        ),
        (
            &[path, "--fix", "--from-overrides"][..],
            "no --override or --override-file to write",
        ),
        (
            &[path, "--diff", "--override", "joint.shoulder.effort=8"][..],
            "add --from-overrides to write the overrides into the file",
        ),
    ] {
        let output = run(args);
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains(said), "{args:?}: {stderr}");
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap(), ARM);
}
