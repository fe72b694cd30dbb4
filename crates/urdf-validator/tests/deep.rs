//! `--deep`: the MuJoCo pass on example-robot-data's panda, UR5, Talos (reduced) and PR2 against the
//! Pinocchio golden torques, an analytic mimic robot, a cart whose centre of mass hangs past its wheels
//! (an automatic pass whose drop test fails), and the report without MuJoCo.
//!
//! MuJoCo comes from the test venv (`scripts/setup-test-env.sh` installs `mujoco`; `scripts/test.sh`
//! exports `URDF_VALIDATOR_PYTHON=.venv/bin/python`). Without it these tests skip, except under
//! `CI=true`, where they fail.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::path::Path;

use serde_json::Value;
use urdf_validator::analysis::classify::RobotType;
use urdf_validator::analysis::deep::DeepOptions;
use urdf_validator::diagnostics::{Confidence, Status};
use urdf_validator::model::{JointId, Model};
use urdf_validator::report::Report;
use urdf_validator::urdf::parse::parse_urdf;
use urdf_validator::Options;

fn deep_options(python: &Path, requested: bool) -> Options {
    Options {
        deep: DeepOptions {
            requested,
            python: Some(python.to_path_buf()),
            ..DeepOptions::default()
        },
        workspace: urdf_validator::analysis::workspace::WorkspaceOptions {
            samples: 500,
            ..Default::default()
        },
        ..Options::default()
    }
}

fn validate(path: &Path, options: &Options) -> Report {
    urdf_validator::validate(path, options).unwrap().report
}

fn validate_text(text: &str, options: &Options) -> Report {
    let path = std::env::temp_dir().join("urdf-validator-deep-test.urdf");
    urdf_validator::validate_text(text.to_string(), &path, options)
        .unwrap()
        .report
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * a.abs().max(b.abs()).max(1e-3)
}

/// Pinocchio's torques (raw, per joint) at one golden configuration, folded like statics (followers into
/// their leader), and that configuration as `--joint-angles` (independent joints).
fn pinocchio_folded(corpus: &Path, golden: &str, label: &str) -> (Model, Vec<Option<f64>>, String) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/pinocchio");
    let golden: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join(golden)).unwrap()).unwrap();
    let source = golden["source"].as_str().unwrap();
    let urdf = corpus.join(source);
    let (robot, _) = parse_urdf(&std::fs::read_to_string(&urdf).unwrap(), &urdf).unwrap();
    let (model, _) = Model::build(&robot);
    let configuration = golden["configurations"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["label"] == label)
        .unwrap();
    let angles: Vec<String> = configuration["q"]
        .as_object()
        .unwrap()
        .iter()
        .filter(|(name, _)| {
            model
                .joint(name)
                .is_some_and(|j| model.mimic[j.0].is_none())
        })
        .map(|(name, value)| format!("{name}={}", value.as_f64().unwrap()))
        .collect();
    let mut folded: Vec<Option<f64>> = vec![None; robot.joints.len()];
    for (name, value) in configuration["gravity_torque"].as_object().unwrap() {
        let j = model.joint(name).unwrap();
        folded[j.0] = value.as_f64();
    }
    let raw = folded.clone();
    for (j, value) in raw.iter().enumerate() {
        if model.mimic[j].is_some() {
            let (leader, factor) =
                urdf_validator::analysis::statics::gravity::independent_leader(&model, JointId(j));
            if let (Some(l), Some(v)) = (folded[leader.0], value) {
                folded[leader.0] = Some(l + factor * v);
            }
        }
    }
    (model, folded, angles.join(","))
}

/// Every compared joint: MuJoCo within 1e-6 of statics and of Pinocchio (at Pinocchio's zero pose and at
/// its first random configuration, given as `--pose custom`); the drop test reported. The zero pose's report
/// is returned.
fn check_robot(python: &Path, corpus: &Path, file: &str, golden: &str) -> Report {
    let mut report = None;
    for label in ["random_0", "zero"] {
        report = Some(check_at(python, corpus, file, golden, label));
    }
    report.unwrap()
}

fn check_at(python: &Path, corpus: &Path, file: &str, golden: &str, label: &str) -> Report {
    let (model, pinocchio, angles) = pinocchio_folded(corpus, golden, label);
    let mut options = deep_options(python, true);
    options.statics.pose.kind = urdf_validator::analysis::pose::PoseKind::Custom;
    options.statics.pose.joint_angles = Some(angles);
    let report = validate(&corpus.join(file), &options);
    let deep = report.deep.as_ref().expect("a deep section");
    assert_ne!(deep.status, Status::Unknown, "{file}: {:?}", deep.reason);
    assert!(
        deep.joints.iter().all(|j| j.agrees),
        "{file}: {:#?}",
        deep.joints
    );
    assert!(!deep.joints.is_empty(), "{file}: no joint compared");
    for joint in &deep.joints {
        let mujoco = joint.mujoco_torque.unwrap();
        assert!(
            close(mujoco, joint.our_torque),
            "{file} {}: MuJoCo {mujoco}, statics {}",
            joint.name,
            joint.our_torque
        );
        let id = model.joint(&joint.name).unwrap();
        let theirs = pinocchio[id.0].unwrap();
        assert!(
            close(mujoco, theirs),
            "{file} [{label}] {}: MuJoCo {mujoco}, Pinocchio {theirs}",
            joint.name
        );
    }
    let statics = report.statics.as_ref().unwrap();
    // The centre of mass agrees unless MuJoCo changed a mass (UR5's 'world' link: see below).
    let mass_changed = deep.simulator_changes.iter().any(|c| c.kind == "mass");
    assert_eq!(deep.agreement, Some(!mass_changed), "{file}");
    let com = if mass_changed {
        Confidence::Estimated
    } else {
        Confidence::Simulated
    };
    assert_eq!(statics.com_confidence, com, "{file}");
    assert!(statics
        .joints
        .iter()
        .filter(|j| j.mimics.is_none() && j.required_torque_gravity.is_some())
        .all(|j| j.torque_confidence == Confidence::Simulated));
    let drop = deep.drop_test.as_ref().expect("a drop test");
    assert_eq!(drop.simulated_s, 2.0, "{file}");
    assert!(
        drop.max_tilt_deg.is_some() && drop.com_drift_m.is_some(),
        "{file}"
    );
    report
}

#[test]
fn panda_ur5_talos_and_pr2_agree_with_pinocchio_and_get_a_drop_test() {
    let (Some(python), Some(corpus)) = (common::mujoco_python(), common::corpus()) else {
        return;
    };
    let panda = check_robot(
        &python,
        &corpus,
        "panda_description/urdf/panda.urdf",
        "panda_description__urdf__panda.json",
    );
    let deep = panda.deep.unwrap();
    assert!(
        deep.simulator_changes.iter().any(|c| c.kind == "mimic"),
        "the finger mimic becomes an equality"
    );
    // (Pinocchio's zero pose puts panda_joint4 outside its limits: MuJoCo's limit pushes it back.)

    let ur5 = check_robot(
        &python,
        &corpus,
        "ur_description/urdf/ur5_robot.urdf",
        "ur_description__urdf__ur5_robot.json",
    );
    let deep = ur5.deep.unwrap();
    // A link named 'world' is MuJoCo's world body: base_link is fused into it and its 4 kg dropped.
    assert!(
        deep.simulator_changes
            .iter()
            .any(|c| c.kind == "mass" && c.element == "world" && c.message.contains("4.000000 kg")),
        "{:#?}",
        deep.simulator_changes
    );
    let drop = deep.drop_test.unwrap();
    assert_eq!(drop.base, "fixed");
    assert_eq!(drop.status, Status::Pass);

    let talos = check_robot(
        &python,
        &corpus,
        "talos_data/robots/talos_reduced.urdf",
        "talos_data__robots__talos_reduced.json",
    );
    assert_eq!(talos.deep.unwrap().drop_test.unwrap().base, "free");

    let pr2 = check_robot(
        &python,
        &corpus,
        "pr2_description/urdf/pr2.urdf",
        "pr2_description__urdf__pr2.json",
    );
    let deep = pr2.deep.as_ref().unwrap();
    let refused: Vec<&str> = deep
        .simulator_changes
        .iter()
        .filter(|c| c.kind == "refused")
        .map(|c| c.element.as_str())
        .collect();
    assert!(refused.contains(&"sensor_mount_link"), "{refused:?}");
    let finding = pr2
        .findings
        .iter()
        .find(|f| f.rule == "U741" && f.message.contains("sensor_mount_link"))
        .expect("a U741 finding for sensor_mount_link");
    assert!(finding.line.is_some() && finding.message.contains("A + B >= C"));
    assert!(deep.simulator_changes.iter().any(|c| c.kind == "fused"));
    // The shoulder-lift motors are too weak for the arms (statics FAILs them): they sag in MuJoCo too.
    let drop = deep.drop_test.as_ref().unwrap();
    assert_eq!(drop.status, Status::Fail);
    let sagging: Vec<&str> = drop
        .joints_sagging
        .iter()
        .map(|j| j.name.as_str())
        .collect();
    assert!(
        sagging.contains(&"r_shoulder_lift_joint") && sagging.contains(&"l_shoulder_lift_joint")
    );
    // Its fingertips end on the ground below those shoulders: their sag, not a fall.
    assert!(drop.fallen_onto.is_empty(), "{drop:?}");
    assert!(!pr2.findings.iter().any(|f| f.rule == "U745"));
}

/// Two links on one axis, the second following the first ×2: τ1 = −29.43, τ2 = −4.905, folded
/// τ1 + 2 τ2 = −39.24 N·m at the zero pose.
const MIMIC_ARM: &str = r#"<robot name="mimic_arm">
  <link name="base"><inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="upper"><inertial><origin xyz="0.5 0 0"/><mass value="1"/><inertia ixx="0.01" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.5 0 0"/><geometry><box size="1 0.05 0.05"/></geometry></collision></link>
  <link name="lower"><inertial><origin xyz="0.25 0 0"/><mass value="2"/><inertia ixx="0.01" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.05 0.05"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 0.5"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="100" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/><origin xyz="1 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="100" velocity="1"/><mimic joint="shoulder" multiplier="2"/></joint>
</robot>"#;

#[test]
fn a_mimic_leader_agrees_once_its_follower_is_folded_in() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let mut options = deep_options(&python, true);
    options.overrides.robot_type = Some(RobotType::ArmOnly);
    let report = validate_text(MIMIC_ARM, &options);
    let deep = report.deep.unwrap();
    assert_eq!(deep.agreement, Some(true), "{:#?}", deep.joints);
    assert_eq!(deep.joints.len(), 1, "the follower is folded, not compared");
    let shoulder = &deep.joints[0];
    assert_eq!(shoulder.name, "shoulder");
    assert!(
        close(shoulder.mujoco_torque.unwrap(), -39.24),
        "{shoulder:?}"
    );
    assert!(close(shoulder.our_torque, -39.24));
    assert!(deep
        .simulator_changes
        .iter()
        .any(|c| c.kind == "mimic" && c.element == "elbow"));
}

/// A cart on four wheels carrying a 20 kg weight on a mast 45 cm ahead of its front axle.
const TIPPING_CART: &str = r#"<robot name="tipping_cart">
  <link name="base_link"><inertial><mass value="4"/><inertia ixx="0.05" iyy="0.06" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.05"/></geometry></collision></link>
  <link name="mast"><inertial><origin xyz="0.4 0 0.6"/><mass value="20"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.4 0 0.6"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="mast_joint" type="fixed"><parent link="base_link"/><child link="mast"/><origin xyz="0.2 0 0"/></joint>
  WHEELS
</robot>"#;

fn wheel(name: &str, x: f64, y: f64) -> String {
    format!(
        r#"<link name="{name}_wheel"><inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.03"/></geometry></collision></link>
  <joint name="{name}_wheel_joint" type="continuous"><parent link="base_link"/><child link="{name}_wheel"/>
    <origin xyz="{x} {y} -0.025"/><axis xyz="0 1 0"/><limit effort="20" velocity="10"/></joint>"#
    )
}

#[test]
fn a_cart_whose_com_hangs_past_its_wheels_gets_an_automatic_deep_pass_that_fails() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let wheels: String = [
        ("fl", 0.15, 0.17),
        ("fr", 0.15, -0.17),
        ("bl", -0.15, 0.17),
        ("br", -0.15, -0.17),
    ]
    .iter()
    .map(|(n, x, y)| wheel(n, *x, *y))
    .collect();
    let text = TIPPING_CART.replace("WHEELS", &wheels);
    let report = validate_text(&text, &deep_options(&python, false));
    let stability = report.stability.as_ref().unwrap();
    assert!(stability.margin_mm.unwrap() < 0.0, "{stability:?}");
    let deep = report.deep.as_ref().expect("an automatic deep pass");
    assert_eq!(deep.trigger, "automatic");
    let drop = deep.drop_test.as_ref().unwrap();
    assert_eq!(drop.status, Status::Fail, "{drop:?}");
    assert!(drop.final_tilt_deg.unwrap() > 15.0, "{drop:?}");
    assert!(report.findings.iter().any(|f| f.rule == "U745"));
    assert!(report.findings.iter().any(|f| f.rule == "U748"));
}

/// Issue 26 item 2 (`tests/data/deep/boom_cart.urdf`): statics says the cart tips over (U710); in MuJoCo it
/// pitches forward onto the weight under its boom and rests there about 12° from upright, below the 15°
/// tilt rule. Resting on a link that is not a support contact is a fall: U745 at the boom, the drop test
/// FAILs, and it agrees with statics.
#[test]
fn a_cart_that_falls_onto_its_boom_fails_the_drop_test_naming_the_boom() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/deep/boom_cart.urdf");
    let report = validate(&path, &deep_options(&python, false));
    assert!(report.findings.iter().any(|f| f.rule == "U710"));
    let deep = report.deep.as_ref().expect("an automatic deep pass");
    let drop = deep.drop_test.as_ref().unwrap();
    let tilt = drop.final_tilt_deg.unwrap();
    assert!(
        tilt > 5.0 && tilt < 15.0,
        "the tilt rule alone would pass it: {drop:?}"
    );
    assert_eq!(drop.status, Status::Fail, "{drop:?}");
    assert_eq!(drop.fallen_onto, ["boom"], "{drop:?}");
    assert!(drop.ground_links.contains(&"boom".to_string()));
    for support in ["left_wheel", "right_wheel", "caster"] {
        assert!(
            drop.support_links.contains(&support.to_string()),
            "{drop:?}"
        );
    }
    let finding = report
        .findings
        .iter()
        .find(|f| f.rule == "U745")
        .expect("a U745 finding");
    assert!(finding.message.contains("'boom'"), "{}", finding.message);
    assert_eq!(finding.line, Some(28), "at the boom's <link>");
    assert_eq!(drop.agrees_with_stability, Some(true));
    assert!(drop.stability_disagreement.is_none());
    // The trace: from the release to the end, at most 200 samples, ending at the final tilt.
    let trace = &drop.tilt_trace;
    assert!(trace.len() > 100 && trace.len() <= 200, "{}", trace.len());
    assert_eq!(trace[0][0], 0.0);
    assert_eq!(trace.last().unwrap()[0], 2.0);
    assert!((trace.last().unwrap()[1] - tilt).abs() < 1e-3);
    assert!(trace.windows(2).all(|w| w[0][0] < w[1][0]));
}

/// The four-wheeled tipping cart with a bumper under its mast, touching the ground, while `--contact-links`
/// names the wheels only: statics says the cart tips over (U710), MuJoCo keeps it up on the bumper (a link
/// touching the ground at the release is a support). The drop test passes and the deep section says that
/// the two disagree.
#[test]
fn when_statics_and_the_drop_test_disagree_the_deep_section_says_so() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let names = ["fl", "fr", "bl", "br"];
    let wheels: String = names
        .iter()
        .zip([(0.15, 0.17), (0.15, -0.17), (-0.15, 0.17), (-0.15, -0.17)])
        .map(|(n, (x, y))| wheel(n, x, y))
        .collect();
    let bumper = r#"<link name="bumper"><inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.3 0.05"/></geometry></collision></link>
  <joint name="bumper_joint" type="fixed"><parent link="base_link"/><child link="bumper"/><origin xyz="0.65 0 -0.05"/></joint>"#;
    let text = TIPPING_CART.replace("WHEELS", &format!("{wheels}\n  {bumper}"));
    let mut options = deep_options(&python, true);
    options.overrides.contact_links = Some(names.iter().map(|n| format!("{n}_wheel")).collect());
    let path = std::env::temp_dir().join("urdf-validator-deep-bumper-cart.urdf");
    let validation = urdf_validator::validate_text(text, &path, &options).unwrap();
    let report = &validation.report;
    let stability = report.stability.as_ref().unwrap();
    assert_eq!(stability.status, Status::Fail, "{stability:?}");
    let drop = report.deep.as_ref().unwrap().drop_test.as_ref().unwrap();
    assert_eq!(drop.status, Status::Pass, "{drop:?}");
    assert!(
        drop.ground_links.contains(&"bumper".to_string()),
        "{drop:?}"
    );
    assert!(drop.fallen_onto.is_empty(), "{drop:?}");
    assert_eq!(drop.agrees_with_stability, Some(false));
    let sentence = drop.stability_disagreement.as_deref().unwrap();
    assert!(
        sentence
            .starts_with("Statics and the drop test disagree: statics finds the centre of mass")
            && sentence.contains("outside the support polygon (the robot tips over to the front)")
            && sentence.contains("in MuJoCo the robot stays on its support contacts"),
        "{sentence}"
    );
    let text = urdf_validator::render::text::render_text(
        &validation,
        &urdf_validator::render::text::TextOptions::default(),
    );
    assert!(text.contains(sentence), "{text}");
}

/// The boom cart with visuals only: MuJoCo drops URDF visuals, so nothing of it lands and it falls through
/// the floor. Before, that was a PASS ("stays up", 0° tilt); now the drop test cannot judge it: UNKNOWN
/// with a U747 saying why, and no claim about statics.
#[test]
fn a_robot_without_collision_geometry_gets_no_drop_test_verdict() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/deep/boom_cart.urdf");
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("<collision>", "<visual>")
        .replace("</collision>", "</visual>");
    let report = validate_text(&text, &deep_options(&python, true));
    let drop = report.deep.as_ref().unwrap().drop_test.as_ref().unwrap();
    assert_eq!(drop.status, Status::Unknown, "{drop:?}");
    assert!(drop.ground_links.is_empty() && drop.fallen_onto.is_empty());
    assert_eq!(drop.agrees_with_stability, None);
    assert!(
        report
            .findings
            .iter()
            .any(|f| f.rule == "U747" && f.message.contains("falls through the floor")),
        "{:#?}",
        report.findings
    );
    assert!(!report.findings.iter().any(|f| f.rule == "U745"));
}

#[test]
fn without_mujoco_the_message_says_how_to_install_it_and_the_rest_runs() {
    // A Python without site-packages cannot import mujoco; an interpreter that does not exist, neither.
    let dir = std::env::temp_dir().join(format!("urdf-validator-no-mujoco-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let wrapper = dir.join("python-without-site");
    std::fs::write(&wrapper, "#!/bin/sh\nexec python3 -S \"$@\"\n").unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&wrapper, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    for python in [wrapper.clone(), dir.join("no-such-python")] {
        let report = validate_text(MIMIC_ARM, &deep_options(&python, true));
        let finding = report
            .findings
            .iter()
            .find(|f| f.rule == "U790")
            .unwrap_or_else(|| panic!("{}: no U790 in {:#?}", python.display(), report.findings));
        assert!(
            finding
                .message
                .contains("pip install \"urdf-validator[mujoco]\"")
                && finding.message.contains("MuJoCo was not found"),
            "{}",
            finding.message
        );
        assert!(!finding.message.contains("Traceback"));
        assert_eq!(report.overall_status, Status::Unknown);
        let deep = report.deep.as_ref().unwrap();
        assert_eq!(deep.status, Status::Unknown);
        assert!(
            report.statics.as_ref().unwrap().total_mass.is_some(),
            "statics still ran"
        );
        assert!(report.workspace.is_some());
    }
    // Not asked for and the robot stands: nothing runs, nothing is said.
    let report = validate_text(MIMIC_ARM, &deep_options(&wrapper, false));
    assert!(report.deep.is_none());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A link without `<inertial>` but with a collision box gets mass from MuJoCo (U743); a floating joint
/// below the root is one MuJoCo refuses outright (U740, quoting MuJoCo), and the static report stays whole.
#[test]
fn what_mujoco_changes_or_cannot_load_is_reported_at_the_element() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let mut options = deep_options(&python, true);
    options.overrides.robot_type = Some(RobotType::ArmOnly);
    let with_box = MIMIC_ARM.replace(
        "</robot>",
        r#"<link name="camera"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="camera_joint" type="fixed"><parent link="lower"/><child link="camera"/><origin xyz="0.5 0 0"/></joint>
</robot>"#,
    );
    let report = validate_text(&with_box, &options);
    let deep = report.deep.as_ref().unwrap();
    assert!(
        deep.simulator_changes
            .iter()
            .any(|c| c.kind == "mass" && c.message.contains("'camera'")),
        "{:#?}",
        deep.simulator_changes
    );
    assert!(report.findings.iter().any(|f| f.rule == "U743"));
    assert!(
        !report.findings.iter().any(|f| f.rule == "U744"),
        "explained, not a disagreement"
    );

    let floating = MIMIC_ARM.replace(
        r#"<joint name="elbow" type="revolute">"#,
        r#"<joint name="elbow" type="floating">"#,
    );
    let report = validate_text(&floating, &options);
    let finding = report
        .findings
        .iter()
        .find(|f| f.rule == "U740")
        .unwrap_or_else(|| panic!("{:#?}", report.findings));
    assert!(
        finding
            .message
            .starts_with("MuJoCo cannot load this robot: "),
        "{}",
        finding.message
    );
    assert!(finding.line.is_some());
    assert_eq!(report.deep.as_ref().unwrap().status, Status::Fail);
    assert!(report.statics.is_some() && report.workspace.is_some());
}
