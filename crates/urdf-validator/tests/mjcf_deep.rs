//! `--deep` on MJCF: MuJoCo loads the user's file itself (includes, defaults, `ref`, ball joints), its
//! gravity forces and centre of mass compared with ours (gymnasium's ant, Menagerie's go2 and iiwa14, a
//! model of its own), the drop test on the model's own ground; an MJCF MuJoCo refuses; and the file
//! withheld from MuJoCo under `--untrusted`.
//!
//! MuJoCo comes from the test venv (`URDF_VALIDATOR_PYTHON`), gymnasium's ant from the wheel
//! `scripts/setup-test-env.sh` unpacks (`URDF_VALIDATOR_GYMNASIUM_CORPUS`). Without them these tests skip,
//! except under `CI=true`, where they fail.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};

use urdf_validator::analysis::deep::DeepOptions;
use urdf_validator::diagnostics::Status;
use urdf_validator::input::sandbox::Sandbox;
use urdf_validator::report::Report;
use urdf_validator::Options;

/// A scratch folder removed at the end of the test.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!(
            "urdf-validator-mjcf-deep-{name}-{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    fn file(&self, name: &str, text: &str) -> PathBuf {
        let path = self.0.join(name);
        std::fs::write(&path, text).unwrap();
        path
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn deep_options(python: &Path) -> Options {
    let mut options = Options {
        deep: DeepOptions {
            requested: true,
            python: Some(python.to_path_buf()),
            ..DeepOptions::default()
        },
        ..Options::default()
    };
    options.workspace.samples = 200;
    options
}

fn validate(path: &Path, options: &Options) -> Report {
    urdf_validator::validate(path, options).unwrap().report
}

fn ant() -> Option<PathBuf> {
    let dir = common::data_dir(
        "URDF_VALIDATOR_GYMNASIUM_CORPUS",
        Some(common::repo_root().join("target/gymnasium/gymnasium/envs/mujoco/assets")),
        "gymnasium's MuJoCo models (gymnasium==1.2.2 wheel)",
    )?;
    Some(dir.join("ant.xml"))
}

#[test]
fn the_ant_stands_on_its_own_floor_and_agrees_with_mujoco() {
    let (Some(python), Some(ant)) = (common::mujoco_python(), ant()) else {
        return;
    };
    let report = validate(&ant, &deep_options(&python));
    let deep = report.deep.expect("a deep section");
    assert_eq!(deep.simulator_version.as_deref(), Some("4.0.0"));
    assert_eq!(deep.agreement, Some(true), "{:#?}", deep.joints);
    assert_eq!(deep.joints.len(), 8, "the ant's eight hinges");
    assert!(deep.com_abs_diff.unwrap() < 1e-9);
    // Nothing of a URDF import (fused links, dropped visuals, mimic, efforts, hulls) is said of MJCF.
    assert!(
        deep.simulator_changes.is_empty(),
        "{:#?}",
        deep.simulator_changes
    );
    let drop = deep.drop_test.unwrap();
    assert_eq!(drop.base, "free");
    assert_eq!(drop.status, Status::Pass, "{:?}", drop.reason);
    // The four unnamed foot bodies, named as the reader names them, rest on the model's floor.
    assert_eq!(drop.ground_links.len(), 4, "{:?}", drop.ground_links);
    assert!(drop.ground_links.iter().all(|l| l.starts_with("body#")));
    assert!(drop.fallen_onto.is_empty());
}

#[test]
fn menagerie_go2_and_iiwa_agree_with_mujoco() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/menagerie");
    for (file, joints, base) in [
        ("unitree_go2/go2.xml", 12, "free"),
        ("kuka_iiwa_14/iiwa14.xml", 7, "fixed"),
    ] {
        let report = validate(&data.join(file), &deep_options(&python));
        let deep = report.deep.expect("a deep section");
        assert_eq!(deep.agreement, Some(true), "{file}: {:#?}", deep.joints);
        assert_eq!(deep.joints.len(), joints, "{file}");
        assert!(
            deep.simulator_changes.is_empty(),
            "{file}: {:#?}",
            deep.simulator_changes
        );
        let drop = deep.drop_test.unwrap();
        assert_eq!(drop.base, base, "{file}");
        // (go2 at qpos0 has its calves outside their range: MuJoCo's limits push it over; a verdict.)
        assert_ne!(drop.status, Status::Unknown, "{file}: {:?}", drop.reason);
    }
}

#[test]
fn the_drop_test_uses_the_models_own_tilted_floor() {
    let (Some(python), Some(ant)) = (common::mujoco_python(), ant()) else {
        return;
    };
    // The same ant on its floor tilted by 30°: with a flat floor of its own it would stand (test above).
    let text = std::fs::read_to_string(&ant).unwrap();
    let tilted = text.replacen(
        "name=\"floor\" pos=\"0 0 0\"",
        "name=\"floor\" pos=\"0 0 0\" euler=\"30 0 0\"",
        1,
    );
    assert_ne!(tilted, text, "ant.xml's floor is where the test expects it");
    let dir = Scratch::new("tilted");
    let path = dir.file("ant_tilted.xml", &tilted);
    let report = validate(&path, &deep_options(&python));
    let drop = report.deep.unwrap().drop_test.unwrap();
    assert!(
        drop.max_tilt_deg.unwrap() > 20.0,
        "the ant lies on the 30° slope: {drop:#?}"
    );
}

#[test]
fn an_included_model_with_ball_joints_and_ref_agrees_at_a_turned_pose() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let dir = Scratch::new("ball");
    // MuJoCo reads the include, the class defaults and `ref` itself; the ball joint's three hinges are
    // compared at a pose where all three are turned.
    dir.file(
        "arm.xml",
        r#"<mujoco>
  <worldbody>
    <body name="upper" pos="0 0 1">
      <joint name="shoulder" type="ball"/>
      <geom class="limb" fromto="0 0 0 0.3 0.1 -0.4"/>
      <body name="lower" pos="0.3 0.1 -0.4">
        <joint name="elbow" axis="0 1 0" ref="20" range="-90 90"/>
        <geom class="limb" fromto="0 0 0 0.2 -0.1 -0.3" mass="1.5"/>
      </body>
    </body>
  </worldbody>
</mujoco>"#,
    );
    let path = dir.file(
        "model.xml",
        r#"<mujoco>
  <default><default class="limb"><geom type="capsule" size="0.04"/></default></default>
  <include file="arm.xml"/>
  <actuator><motor joint="elbow" gear="50" ctrlrange="-1 1"/></actuator>
</mujoco>"#,
    );
    let mut options = deep_options(&python);
    options.statics.pose.kind = urdf_validator::analysis::pose::PoseKind::Custom;
    options.statics.pose.joint_angles =
        Some("shoulder_x=0.4,shoulder_y=-0.7,shoulder_z=1.1,elbow=0.5".to_string());
    let report = validate(&path, &options);
    let deep = report.deep.expect("a deep section");
    assert_ne!(deep.status, Status::Unknown, "{:?}", deep.reason);
    for name in ["shoulder_x", "shoulder_y", "shoulder_z", "elbow"] {
        let joint = deep
            .joints
            .iter()
            .find(|j| j.name == name)
            .unwrap_or_else(|| panic!("{name} compared: {:#?}", deep.joints));
        assert!(joint.agrees, "{joint:#?}");
        assert!(joint.our_torque.abs() > 0.1, "a real torque: {joint:#?}");
    }
    assert_eq!(deep.agreement, Some(true));
}

#[test]
fn an_mjcf_mujoco_refuses_is_a_finding_and_the_rest_of_the_report_runs() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let dir = Scratch::new("refused");
    // The weld's body names a body that does not exist: MuJoCo refuses the model; our reader only reports
    // the weld as a loop (U038), so the refusal is MuJoCo's own.
    let path = dir.file(
        "m.xml",
        r#"<mujoco>
  <worldbody>
    <body name="link" pos="0 0 1">
      <joint name="hinge" axis="0 1 0"/>
      <geom type="box" size="0.1 0.1 0.1" pos="0.2 0 0"/>
    </body>
  </worldbody>
  <equality><weld body1="link" body2="nowhere"/></equality>
  <actuator><motor joint="hinge" ctrlrange="-1 1" gear="10"/></actuator>
</mujoco>"#,
    );
    let report = validate(&path, &deep_options(&python));
    let deep = report.deep.expect("a deep section");
    assert_eq!(deep.status, Status::Fail);
    assert!(
        deep.reason.as_deref().unwrap().contains("nowhere"),
        "MuJoCo's own message: {:?}",
        deep.reason
    );
    assert!(report.findings.iter().any(|f| f.rule == "U740"));
    assert!(report.statics.is_some(), "statics still ran");
}

#[test]
fn under_untrusted_the_file_is_not_handed_to_mujoco() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let dir = Scratch::new("untrusted");
    let path = dir.file(
        "m.xml",
        r#"<mujoco><worldbody><body><joint/><geom size="0.1" pos="0.1 0 0"/></body></worldbody></mujoco>"#,
    );
    let options = Options {
        sandbox: Sandbox::untrusted(Vec::new(), Vec::new()),
        ..deep_options(&python)
    };
    let report = validate(&path, &options);
    let deep = report
        .deep
        .expect("a deep section saying why it did not run");
    assert_eq!(deep.status, Status::Unknown);
    assert!(
        deep.reason.as_deref().unwrap().contains("--untrusted"),
        "{:?}",
        deep.reason
    );
    assert!(report.findings.iter().any(|f| f.rule == "U790"));
}
