//! `--write-baseline` and `--baseline`: adopting the validator on a robot that already has findings.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

use serde_json::Value;

fn temp_dir() -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "urdf_validate_baseline_{}_{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::SeqCst)
    ));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(args)
        .args(["--no-config", "--color", "never", "--samples", "200"])
        .current_dir(dir)
        .output()
        .expect("runs")
}

/// The JSON report printed by a `--format json --no-write` run.
fn report(dir: &Path, args: &[&str]) -> (u8, Value) {
    let mut all = vec!["--format", "json", "--no-write"];
    all.extend_from_slice(args);
    let output = run(dir, &all);
    let json = serde_json::from_slice(&output.stdout).unwrap_or_else(|e| {
        panic!(
            "{e}: {}{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        )
    });
    (output.status.code().expect("exit code") as u8, json)
}

/// A two-joint arm: `shoulder` too weak for its arm at the zero pose (U701 FAIL) with effort
/// `shoulder`, `elbow` with effort `elbow`; `base` has an inertia violating the triangle inequality
/// (U206 WARN). `padding` goes before the first link (line shifts).
fn arm(shoulder: &str, elbow: &str, padding: &str) -> String {
    format!(
        r#"<robot name="arm">{padding}
  <link name="base">
    <inertial><mass value="5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.1"/></inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="{shoulder}" velocity="1"/>
  </joint>
  <link name="upper">
    <inertial><origin xyz="0.25 0 0"/><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.05"/></inertial>
  </link>
  <joint name="elbow" type="revolute">
    <parent link="upper"/><child link="fore"/>
    <origin xyz="0.5 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="{elbow}" velocity="1"/>
  </joint>
  <link name="fore">
    <inertial><origin xyz="0.2 0 0"/><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial>
  </link>
</robot>
"#
    )
}

fn rules(report: &Value) -> Vec<String> {
    report["findings"]
        .as_array()
        .expect("findings")
        .iter()
        .map(|f| format!("{} {}", f["rule"].as_str().unwrap(), f["message"]))
        .collect()
}

#[test]
fn a_baseline_hides_todays_findings_and_only_new_ones_count() {
    let dir = temp_dir();
    std::fs::write(dir.join("arm.urdf"), arm("5", "10", "")).unwrap();
    let (code, before) = report(&dir, &["arm.urdf"]);
    assert_eq!(code, 2, "{:?}", rules(&before));
    let known = before["findings"].as_array().unwrap().len();
    assert!(known >= 2, "{:?}", rules(&before));

    // Writing the baseline: exit 0, a stable, sorted file.
    let output = run(
        &dir,
        &[
            "arm.urdf",
            "--no-write",
            "--write-baseline",
            "baseline.json",
        ],
    );
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    let written = std::fs::read_to_string(dir.join("baseline.json")).unwrap();
    let file: Value = serde_json::from_str(&written).unwrap();
    assert_eq!(file["urdf_validate_baseline"], 1);
    assert_eq!(file["robots"][0]["file"], "arm.urdf");
    assert!(
        written.contains(r#""element": "robot[@name='arm']/joint[@name='shoulder']/limit""#),
        "{written}"
    );
    run(
        &dir,
        &["arm.urdf", "--no-write", "--write-baseline", "again.json"],
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("again.json")).unwrap(),
        written
    );

    // The next run: nothing new, exit 0, the known findings counted.
    let (code, after) = report(&dir, &["arm.urdf", "--baseline", "baseline.json"]);
    assert_eq!(code, 0, "{:?}", rules(&after));
    assert_eq!(after["overall_status"], "PASS");
    assert_eq!(after["findings"], Value::Array(Vec::new()));
    assert_eq!(after["baseline"]["matched"], known);
    assert_eq!(after["baseline"]["new"], 0);
    assert_eq!(after["baseline"]["stale"], Value::Array(Vec::new()));
    let text = run(
        &dir,
        &["arm.urdf", "--no-write", "--baseline", "baseline.json"],
    );
    let text = String::from_utf8_lossy(&text.stdout).into_owned();
    assert!(
        text.contains(&format!(
            "[BASELINE]  {known} known finding(s) hidden (baseline.json), 0 new"
        )),
        "{text}"
    );

    // Line shifts (blank lines, a comment) and a torque that moved a little change nothing.
    let shifted = arm("5.5", "10", "\n\n  <!-- moved down -->\n\n");
    std::fs::write(dir.join("arm.urdf"), shifted).unwrap();
    let (code, after) = report(&dir, &["arm.urdf", "--baseline", "baseline.json"]);
    assert_eq!(code, 0, "{:?}", rules(&after));

    // A new weakness: only it is reported, and it sets the exit code.
    std::fs::write(dir.join("arm.urdf"), arm("5.5", "1", "\n")).unwrap();
    let (code, after) = report(&dir, &["arm.urdf", "--baseline", "baseline.json"]);
    assert_eq!(code, 2);
    let new = rules(&after);
    assert_eq!(new.len(), 1, "{new:?}");
    assert!(
        new[0].starts_with("U701") && new[0].contains("'elbow'"),
        "{new:?}"
    );
    assert_eq!(after["baseline"]["new"], 1);

    // A problem fixed: its entry is stale.
    std::fs::write(dir.join("arm.urdf"), arm("50", "10", "")).unwrap();
    let (code, after) = report(&dir, &["arm.urdf", "--baseline", "baseline.json"]);
    assert_eq!(code, 0, "{:?}", rules(&after));
    let stale = after["baseline"]["stale"].as_array().unwrap();
    assert_eq!(stale.len(), 1, "{stale:?}");
    assert_eq!(stale[0]["rule"], "U701");
    assert!(stale[0]["key"].as_str().unwrap().contains("'shoulder'"));
    let text = run(
        &dir,
        &["arm.urdf", "--no-write", "--baseline", "baseline.json"],
    );
    let text = String::from_utf8_lossy(&text.stdout).into_owned();
    assert!(
        text.contains("1 stale — rewrite with --write-baseline"),
        "{text}"
    );
}

#[test]
fn an_earlier_report_serves_as_a_baseline() {
    let dir = temp_dir();
    std::fs::write(dir.join("arm.urdf"), arm("5", "10", "")).unwrap();
    let output = run(&dir, &["arm.urdf", "--quiet"]);
    assert_eq!(output.status.code(), Some(2));
    // A report written before findings carried their element: matched on rule and message alone.
    let mut old: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("arm_validation.json")).unwrap())
            .unwrap();
    for finding in old["findings"].as_array_mut().unwrap() {
        finding.as_object_mut().unwrap().remove("element");
    }
    std::fs::write(dir.join("old.json"), old.to_string()).unwrap();
    for baseline in ["arm_validation.json", "old.json"] {
        std::fs::write(dir.join("arm.urdf"), arm("5", "10", "\n\n")).unwrap();
        let (code, after) = report(&dir, &["arm.urdf", "--baseline", baseline]);
        assert_eq!(code, 0, "{baseline}: {:?}", rules(&after));
        std::fs::write(dir.join("arm.urdf"), arm("5", "1", "")).unwrap();
        let (code, after) = report(&dir, &["arm.urdf", "--baseline", baseline]);
        assert_eq!(code, 2, "{baseline}");
        let new = rules(&after);
        assert!(
            new.len() == 1 && new[0].contains("'elbow'"),
            "{baseline}: {new:?}"
        );
    }
}

#[test]
fn one_baseline_covers_a_batch() {
    let dir = temp_dir();
    for robot in ["a", "b"] {
        std::fs::create_dir_all(dir.join(robot)).unwrap();
        std::fs::write(dir.join(robot).join("arm.urdf"), arm("5", "10", "")).unwrap();
    }
    std::fs::write(dir.join("b/arm.urdf"), arm("50", "1", "")).unwrap();
    let output = run(
        &dir,
        &[
            "a",
            "b",
            "--no-write",
            "--quiet",
            "--write-baseline",
            "ci/baseline.json",
        ],
    );
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    let written = std::fs::read_to_string(dir.join("ci/baseline.json")).unwrap();
    assert!(written.contains(r#""file": "../a/arm.urdf""#), "{written}");
    assert!(written.contains(r#""file": "../b/arm.urdf""#), "{written}");
    let output = run(
        &dir,
        &[
            "a",
            "b",
            "--no-write",
            "--quiet",
            "--baseline",
            "ci/baseline.json",
        ],
    );
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    // Both robots are named `arm`: each file keeps its own findings (a's shoulder is not b's).
    std::fs::write(dir.join("b/arm.urdf"), arm("5", "1", "")).unwrap();
    let (code, after) = report(&dir, &["a", "b", "--baseline", "ci/baseline.json"]);
    assert_eq!(code, 2);
    let reports = after.as_array().expect("one report per file");
    assert_eq!(reports[0]["findings"], Value::Array(Vec::new()));
    let new = rules(&reports[1]);
    assert!(new.len() == 1 && new[0].contains("'shoulder'"), "{new:?}");
    // A robot the baseline does not hold, of the same name: all its findings are new.
    std::fs::create_dir_all(dir.join("c")).unwrap();
    std::fs::write(dir.join("c/arm.urdf"), arm("5", "10", "")).unwrap();
    let (code, after) = report(&dir, &["c/arm.urdf", "--baseline", "ci/baseline.json"]);
    assert_eq!(code, 2);
    assert_eq!(after["baseline"]["matched"], 0, "{after}");
    // A robot file that moved is still found by its robot name.
    std::fs::rename(dir.join("a"), dir.join("moved")).unwrap();
    let (code, after) = report(&dir, &["moved/arm.urdf", "--baseline", "ci/baseline.json"]);
    assert_eq!(code, 0, "{after}");
}

#[test]
fn a_malformed_baseline_is_one_line_naming_the_file() {
    let dir = temp_dir();
    std::fs::write(dir.join("arm.urdf"), arm("5", "10", "")).unwrap();
    std::fs::write(dir.join("broken.json"), "{\"robots\": ").unwrap();
    let output = run(
        &dir,
        &["arm.urdf", "--no-write", "--baseline", "broken.json"],
    );
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: baseline broken.json: not JSON"),
        "{stderr}"
    );
    let output = run(
        &dir,
        &["arm.urdf", "--no-write", "--baseline", "missing.json"],
    );
    assert_eq!(output.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&output.stderr).contains("baseline missing.json: cannot read it")
    );
}

#[test]
fn the_configuration_names_the_baseline() {
    let dir = temp_dir();
    std::fs::write(dir.join("arm.urdf"), arm("5", "10", "")).unwrap();
    run(
        &dir,
        &["arm.urdf", "--no-write", "--write-baseline", "known.json"],
    );
    std::fs::write(
        dir.join("urdf-validate.toml"),
        "baseline = \"known.json\"\n",
    )
    .unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args([
            "arm.urdf",
            "--no-write",
            "--samples",
            "200",
            "--color",
            "never",
        ])
        .current_dir(&dir)
        .output()
        .expect("runs");
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    assert!(String::from_utf8_lossy(&output.stdout).contains("[BASELINE]"));
}

#[test]
fn xacro_findings_keep_their_fingerprints_across_included_files() {
    let dir = temp_dir();
    let parts = |padding: &str| {
        format!(
            r#"<robot xmlns:xacro="http://www.ros.org/wiki/xacro">{padding}
  <xacro:macro name="segment" params="name parent effort">
    <joint name="${{name}}_joint" type="revolute">
      <parent link="${{parent}}"/><child link="${{name}}"/><axis xyz="0 1 0"/>
      <limit lower="-1" upper="1" effort="${{effort}}" velocity="1"/>
    </joint>
    <link name="${{name}}"><inertial><origin xyz="0.3 0 0"/><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.05"/></inertial></link>
  </xacro:macro>
</robot>
"#
        )
    };
    let robot = |calls: &str| {
        format!(
            r#"<robot name="two" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <link name="base"><inertial><mass value="50"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <xacro:segment name="left" parent="base" effort="2"/>
  <xacro:segment name="right" parent="base" effort="2"/>{calls}
</robot>
"#
        )
    };
    std::fs::write(dir.join("parts.xacro"), parts("")).unwrap();
    std::fs::write(dir.join("two.urdf.xacro"), robot("")).unwrap();
    let (code, before) = report(&dir, &["two.urdf.xacro"]);
    assert_eq!(code, 2, "{:?}", rules(&before));
    // Both weak joints are written in the same line of parts.xacro: their elements tell them apart.
    let output = run(
        &dir,
        &["two.urdf.xacro", "--no-write", "--write-baseline", "b.json"],
    );
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    let written = std::fs::read_to_string(dir.join("b.json")).unwrap();
    assert!(
        written.contains("joint[@name='left_joint']/limit"),
        "{written}"
    );
    assert!(
        written.contains("joint[@name='right_joint']/limit"),
        "{written}"
    );
    // Lines shift in the included file: nothing new.
    std::fs::write(dir.join("parts.xacro"), parts("\n\n  <!-- notes -->\n")).unwrap();
    let (code, after) = report(&dir, &["two.urdf.xacro", "--baseline", "b.json"]);
    assert_eq!(code, 0, "{:?}", rules(&after));
    // A third weak segment from the same macro line: only it is new.
    let third = r#"
  <xacro:segment name="middle" parent="base" effort="2"/>"#;
    std::fs::write(dir.join("two.urdf.xacro"), robot(third)).unwrap();
    let (code, after) = report(&dir, &["two.urdf.xacro", "--baseline", "b.json"]);
    assert_eq!(code, 2);
    let new = rules(&after);
    assert!(
        new.len() == 1 && new[0].contains("'middle_joint'"),
        "{new:?}"
    );
}
