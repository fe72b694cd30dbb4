//! `urdf_validate diff OLD NEW`: what changed between two descriptions or reports.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

use serde_json::Value;

fn temp_dir() -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "urdf_validate_diff_{}_{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::SeqCst)
    ));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn diff(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .arg("diff")
        .args(args)
        .args(["--no-config", "--samples", "500"])
        .current_dir(dir)
        .output()
        .expect("runs")
}

fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

#[test]
fn heavier_forearms_show_in_torques_mass_and_com() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let pr2 = robots.join("pr2/pr2_description/robots/pr2.urdf");
    let text = std::fs::read_to_string(&pr2).expect("PR2 URDF");
    // Both forearm links declare 2.57968 kg: make them 5 kg.
    let forearm = r#"<mass value="2.57968"/>"#;
    assert_eq!(
        text.matches(forearm).count(),
        2,
        "PR2's forearm masses moved"
    );
    let dir = temp_dir();
    std::fs::write(
        dir.join("pr2_heavy.urdf"),
        text.replace(forearm, r#"<mass value="5.0"/>"#),
    )
    .unwrap();
    let package_path = robots.join("pr2").display().to_string();
    let pr2 = pr2.display().to_string();
    let output = diff(
        &dir,
        &[
            &pr2,
            "pr2_heavy.urdf",
            "--package-path",
            &package_path,
            "--format",
            "json",
        ],
    );
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    let json: Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let mass = |side: &str| json["total_mass"][side].as_f64().unwrap();
    assert!(
        (mass("new") - mass("old") - 2.0 * (5.0 - 2.57968)).abs() < 1e-6,
        "{json}"
    );
    assert_ne!(json["com"]["old"], json["com"]["new"]);
    let links: Vec<&str> = json["link_masses"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["name"].as_str().unwrap())
        .collect();
    assert_eq!(links, ["r_forearm_link", "l_forearm_link"]);
    let joint = |name: &str| {
        json["joints"]
            .as_array()
            .unwrap()
            .iter()
            .find(|j| j["joint"] == name)
            .unwrap_or_else(|| panic!("{name} not among the changed joints: {json}"))
            .clone()
    };
    for name in [
        "r_shoulder_lift_joint",
        "l_shoulder_lift_joint",
        "r_elbow_flex_joint",
        "l_elbow_flex_joint",
    ] {
        let j = joint(name);
        let torque = |side: &str| j[side]["torque"].as_f64().unwrap().abs();
        assert!(torque("new") > torque("old") + 1.0, "{name}: {j}");
        assert!(
            j["new"]["margin"].as_f64() < j["old"]["margin"].as_f64(),
            "{name}: {j}"
        );
    }

    let output = diff(
        &dir,
        &[
            &pr2,
            "pr2_heavy.urdf",
            "--package-path",
            &package_path,
            "--format",
            "markdown",
        ],
    );
    let markdown = stdout(&output);
    assert!(
        markdown.contains("| r_elbow_flex_joint | -11.40 N·m / 30"),
        "{markdown}"
    );
    assert!(
        markdown.contains("| link r_forearm_link (kg) | 2.580 | 5.000 | +2.420 |"),
        "{markdown}"
    );
    let output = diff(
        &dir,
        &[&pr2, "pr2_heavy.urdf", "--package-path", &package_path],
    );
    let text = stdout(&output);
    assert!(
        text.contains("[Gravity torques (joints that changed)]"),
        "{text}"
    );
    assert!(text.contains("total mass (kg)"), "{text}");
    // The shoulders fail on both sides; each side says the effort that would pass.
    assert!(text.contains("FAIL (needs ≥ 74.26)"), "{text}");
    assert!(text.contains("FAIL (needs ≥ 95.20)"), "{text}");
}

/// A one-joint arm whose shoulder declares effort `effort` (it needs about 5.9 N·m).
fn arm(effort: &str) -> String {
    format!(
        r#"<robot name="arm">
  <link name="base"><inertial><mass value="5"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="{effort}" velocity="1"/>
  </joint>
  <link name="upper"><inertial><origin xyz="0.3 0 0"/><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.05"/></inertial></link>
</robot>
"#
    )
}

#[test]
fn the_exit_code_says_whether_new_is_worse() {
    let dir = temp_dir();
    std::fs::write(dir.join("strong.urdf"), arm("50")).unwrap();
    std::fs::write(dir.join("weak.urdf"), arm("3")).unwrap();
    let worse = diff(&dir, &["strong.urdf", "weak.urdf"]);
    assert_eq!(worse.status.code(), Some(1), "{worse:?}");
    let text = stdout(&worse);
    assert!(text.contains("WORSE"), "{text}");
    assert!(text.contains("added  U701  FAIL"), "{text}");
    let better = diff(&dir, &["weak.urdf", "strong.urdf"]);
    assert_eq!(better.status.code(), Some(0), "{better:?}");
    assert!(stdout(&better).contains("removed  U701"));
    // A report JSON stands for its robot.
    let output = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(["strong.urdf", "--quiet", "--no-config", "--samples", "500"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    let from_report = diff(
        &dir,
        &["strong_validation.json", "weak.urdf", "--format", "json"],
    );
    assert_eq!(from_report.status.code(), Some(1), "{from_report:?}");
    let json: Value = serde_json::from_slice(&from_report.stdout).unwrap();
    assert_eq!(json["findings_added"][0]["rule"], "U701");
    assert_eq!(json["findings_removed"], Value::Array(Vec::new()));
    // Unreadable input, wrong format, one input: exit 2 with one line.
    for args in [
        &["strong.urdf", "missing.urdf"][..],
        &["strong.urdf", "weak.urdf", "--format", "sarif"],
        &["strong.urdf"],
    ] {
        let output = diff(&dir, args);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {output:?}");
        let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    }
}

#[test]
fn a_configured_baseline_hides_findings_on_neither_side() {
    // The baseline names weak.urdf (NEW): applied, it would hide NEW's U701 but not OLD's copy of it, and
    // the U701 would look fixed.
    let dir = temp_dir();
    std::fs::write(dir.join("weak.urdf"), arm("3")).unwrap();
    std::fs::write(dir.join("weak_base.urdf"), arm("3")).unwrap();
    let written = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(["weak.urdf", "--quiet", "--no-write", "--samples", "500"])
        .args(["--write-baseline", "baseline.json"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(written.status.code(), Some(0), "{written:?}");
    std::fs::write(
        dir.join("urdf-validate.toml"),
        "baseline = \"baseline.json\"\n",
    )
    .unwrap();
    let same = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(["diff", "weak_base.urdf", "weak.urdf", "--format", "json"])
        .args(["--samples", "500"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(same.status.code(), Some(0), "{same:?}");
    let json: Value = serde_json::from_slice(&same.stdout).unwrap();
    assert_eq!(
        json["findings_removed"],
        Value::Array(Vec::new()),
        "{json:#}"
    );
    assert_eq!(json["findings_added"], Value::Array(Vec::new()), "{json:#}");

    // A report written with --baseline leaves findings out: refused with one line.
    let output = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(["weak.urdf", "--quiet", "--samples", "500"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    let refused = diff(&dir, &["weak_validation.json", "weak.urdf"]);
    assert_eq!(refused.status.code(), Some(2), "{refused:?}");
    let stderr = String::from_utf8_lossy(&refused.stderr).into_owned();
    assert!(stderr.contains("written with --baseline"), "{stderr}");
}
