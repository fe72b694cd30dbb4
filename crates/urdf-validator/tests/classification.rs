//! Robot types of every example-robot-data robot and of the reference robots, and stability on them.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use urdf_validator::analysis::classify::RobotType;
use urdf_validator::analysis::pose::{PoseKind, PoseOptions};
use urdf_validator::analysis::statics::StaticsOptions;
use urdf_validator::analysis::workspace::WorkspaceOptions;
use urdf_validator::analysis::Overrides;
use urdf_validator::report::{Report, Status};
use urdf_validator::{validate, Options};

/// The expected type of every corpus URDF (path below the corpus's `robots/` folder). Reasons for the
/// less obvious ones: alex_* are upper bodies on a fixed pelvis; alexander's lower body and bolt are legs
/// without arms; allegro hands, finger_edu, TwoDofs and the pendulums are fixed-base mechanisms; borinot,
/// hextilt and hector are drones; centauro walks on four legs (with wheels as feet); the corpus pr2 welds its
/// wheels with fixed joints but is still wheeled; the human model lies on its side (found by leg names);
/// ur3.urdf is an empty stub.
const EXPECTED: &[(&str, RobotType)] = &[
    ("a1_description/urdf/a1.urdf", RobotType::Quadruped),
    (
        "alex_description/urdf/alex_nub_hands.urdf",
        RobotType::ArmOnly,
    ),
    (
        "alex_description/urdf/alex_psyonic_hands.urdf",
        RobotType::ArmOnly,
    ),
    (
        "alex_description/urdf/alex_sake_hands.urdf",
        RobotType::ArmOnly,
    ),
    (
        "alexander_description/urdf/alexander_v1.lowerBodyOnly.urdf",
        RobotType::Legged,
    ),
    (
        "allegro_hand_description/urdf/allegro_left_hand.urdf",
        RobotType::ArmOnly,
    ),
    (
        "allegro_hand_description/urdf/allegro_right_hand.urdf",
        RobotType::ArmOnly,
    ),
    (
        "anymal_b_simple_description/robots/anymal-kinova.urdf",
        RobotType::Quadruped,
    ),
    (
        "anymal_b_simple_description/robots/anymal.urdf",
        RobotType::Quadruped,
    ),
    (
        "anymal_c_simple_description/urdf/anymal.urdf",
        RobotType::Quadruped,
    ),
    (
        "asr_twodof_description/urdf/TwoDofs.urdf",
        RobotType::ArmOnly,
    ),
    ("b1_description/urdf/b1-z1.urdf", RobotType::Quadruped),
    ("b1_description/urdf/b1.urdf", RobotType::Quadruped),
    ("baxter_description/urdf/baxter.urdf", RobotType::ArmOnly),
    ("bolt_description/robots/bolt.urdf", RobotType::Legged),
    (
        "borinot_description/urdf/borinot_flying_arm_2.urdf",
        RobotType::Aerial,
    ),
    (
        "centauro_description/urdf/centauro.urdf",
        RobotType::Quadruped,
    ),
    (
        "double_pendulum_description/urdf/double_pendulum.urdf",
        RobotType::ArmOnly,
    ),
    (
        "double_pendulum_description/urdf/double_pendulum_continuous.urdf",
        RobotType::ArmOnly,
    ),
    (
        "double_pendulum_description/urdf/double_pendulum_simple.urdf",
        RobotType::ArmOnly,
    ),
    (
        "finger_edu_description/robots/finger_edu.urdf",
        RobotType::ArmOnly,
    ),
    (
        "g1_description/urdf/g1_29dof_rev_1_0.urdf",
        RobotType::Humanoid,
    ),
    (
        "g1_description/urdf/g1_29dof_with_hand_rev_1_0.urdf",
        RobotType::Humanoid,
    ),
    ("go1_description/urdf/go1.urdf", RobotType::Quadruped),
    ("go2_description/urdf/go2.urdf", RobotType::Quadruped),
    (
        "hector_description/robots/quadrotor_base.urdf",
        RobotType::Aerial,
    ),
    (
        "hextilt_description/urdf/hextilt_flying_arm_5.urdf",
        RobotType::Aerial,
    ),
    ("human_description/robots/human.urdf", RobotType::Humanoid),
    (
        "hyq_description/robots/hyq_no_sensors.urdf",
        RobotType::Quadruped,
    ),
    ("icub_description/robots/icub.urdf", RobotType::Humanoid),
    (
        "icub_description/robots/icub_reduced.urdf",
        RobotType::Humanoid,
    ),
    ("iris_description/robots/iris.urdf", RobotType::Aerial),
    (
        "iris_description/robots/iris_simple.urdf",
        RobotType::Aerial,
    ),
    ("kinova_description/robots/kinova.urdf", RobotType::ArmOnly),
    (
        "laikago_description/urdf/laikago.urdf",
        RobotType::Quadruped,
    ),
    ("panda_description/urdf/panda.urdf", RobotType::ArmOnly),
    (
        "panda_description/urdf/panda_collision.urdf",
        RobotType::ArmOnly,
    ),
    ("pr2_description/urdf/pr2.urdf", RobotType::Wheeled),
    (
        "quadruped_description/urdf/quadruped.urdf",
        RobotType::Quadruped,
    ),
    ("romeo_description/urdf/romeo.urdf", RobotType::Humanoid),
    (
        "romeo_description/urdf/romeo_laas_small.urdf",
        RobotType::Humanoid,
    ),
    (
        "romeo_description/urdf/romeo_small.urdf",
        RobotType::Humanoid,
    ),
    (
        "simple_humanoid_description/urdf/simple_humanoid.urdf",
        RobotType::Humanoid,
    ),
    (
        "simple_humanoid_description/urdf/simple_humanoid_classical.urdf",
        RobotType::Humanoid,
    ),
    ("so_arm_description/urdf/so100.urdf", RobotType::ArmOnly),
    ("so_arm_description/urdf/so101.urdf", RobotType::ArmOnly),
    ("solo_description/robots/solo.urdf", RobotType::Quadruped),
    ("solo_description/robots/solo12.urdf", RobotType::Quadruped),
    ("talos_data/robots/talos_full_v2.urdf", RobotType::Humanoid),
    (
        "talos_data/robots/talos_full_v2_box.urdf",
        RobotType::Humanoid,
    ),
    ("talos_data/robots/talos_left_arm.urdf", RobotType::ArmOnly),
    ("talos_data/robots/talos_reduced.urdf", RobotType::Humanoid),
    (
        "talos_data/robots/talos_reduced_box.urdf",
        RobotType::Humanoid,
    ),
    (
        "talos_data/robots/talos_reduced_corrected.urdf",
        RobotType::Humanoid,
    ),
    ("tiago_description/robots/tiago.urdf", RobotType::Wheeled),
    (
        "tiago_description/robots/tiago_dual.urdf",
        RobotType::Wheeled,
    ),
    (
        "tiago_description/robots/tiago_no_hand.urdf",
        RobotType::Wheeled,
    ),
    (
        "tiago_pro_description/robots/tiago_pro.urdf",
        RobotType::Wheeled,
    ),
    (
        "ur_description/urdf/ur10_joint_limited_robot.urdf",
        RobotType::ArmOnly,
    ),
    ("ur_description/urdf/ur10_robot.urdf", RobotType::ArmOnly),
    ("ur_description/urdf/ur3.urdf", RobotType::Unknown),
    ("ur_description/urdf/ur3_gripper.urdf", RobotType::ArmOnly),
    (
        "ur_description/urdf/ur3_joint_limited_robot.urdf",
        RobotType::ArmOnly,
    ),
    ("ur_description/urdf/ur3_robot.urdf", RobotType::ArmOnly),
    ("ur_description/urdf/ur5_gripper.urdf", RobotType::ArmOnly),
    (
        "ur_description/urdf/ur5_joint_limited_robot.urdf",
        RobotType::ArmOnly,
    ),
    ("ur_description/urdf/ur5_robot.urdf", RobotType::ArmOnly),
    ("xarm_description/urdf/xarm7.urdf", RobotType::ArmOnly),
    ("z1_description/urdf/z1.urdf", RobotType::ArmOnly),
];

fn report(path: &std::path::Path, options: &Options) -> Report {
    validate(path, options)
        .unwrap_or_else(|e| panic!("{e}"))
        .report
}

#[test]
fn every_corpus_robot_gets_its_type() {
    let Some(corpus) = common::corpus() else {
        return;
    };
    let files = common::urdfs_below(&corpus);
    assert_eq!(
        files.len(),
        EXPECTED.len(),
        "the table covers the whole corpus"
    );
    let options = Options::default();
    let wrong: Vec<String> = EXPECTED
        .iter()
        .filter_map(|(relative, expected)| {
            let got = report(&corpus.join(relative), &options);
            (got.robot_type != Some(*expected)).then(|| {
                format!(
                    "{relative}: expected {}, got {:?} ({:?})",
                    expected.as_str(),
                    got.robot_type,
                    got.robot_type_evidence
                )
            })
        })
        .collect();
    assert!(wrong.is_empty(), "{wrong:#?}");
}

#[test]
fn walking_robots_get_a_stability_result_at_their_standing_pose() {
    let Some(corpus) = common::corpus() else {
        return;
    };
    // Quadrupeds and humanoids with an SRDF standing state; each must end with a support polygon and a
    // margin (PASS or FAIL), not UNKNOWN.
    let standing = [
        (
            "solo_description/robots/solo12.urdf",
            "solo_description/srdf/solo.srdf",
            "standing",
        ),
        (
            "talos_data/robots/talos_reduced.urdf",
            "talos_data/srdf/talos.srdf",
            "half_sitting",
        ),
        (
            "romeo_description/urdf/romeo_laas_small.urdf",
            "romeo_description/srdf/romeo_small.srdf",
            "half_sitting",
        ),
        (
            "anymal_b_simple_description/robots/anymal.urdf",
            "anymal_b_simple_description/srdf/anymal.srdf",
            "standing",
        ),
    ];
    for (urdf, srdf, state) in standing {
        let options = Options {
            statics: StaticsOptions {
                pose: PoseOptions {
                    kind: PoseKind::Home,
                    srdf: Some(corpus.join(srdf)),
                    state: state.to_string(),
                    ..PoseOptions::default()
                },
                ..StaticsOptions::default()
            },
            ..Options::default()
        };
        let report = report(&corpus.join(urdf), &options);
        let statics = report.statics.as_ref().unwrap();
        assert!(
            statics.notes.iter().all(|n| !n.contains("no group_state")),
            "{urdf}: {:?}",
            statics.notes
        );
        let s = report.stability.unwrap();
        assert!(
            matches!(s.status, Status::Pass | Status::Fail),
            "{urdf}: {:?} {:?}",
            s.status,
            s.reason
        );
        assert!(
            s.support_polygon.len() >= 3 && s.margin_mm.is_some(),
            "{urdf}"
        );
        assert_eq!(s.contact_source.as_deref(), Some("feet"), "{urdf}");
    }
}

#[test]
fn reference_robots_stand_as_the_spec_says() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let options = Options::default();
    let load = |relative: &str| report(&robots.join(relative), &options);

    let turtlebot = load("turtlebot3/turtlebot3_description/urdf/turtlebot3_burger.urdf");
    assert_eq!(turtlebot.robot_type, Some(RobotType::Wheeled));
    let s = turtlebot.stability.unwrap();
    assert_eq!(s.status, Status::Pass);
    let margin = s.margin_mm.unwrap();
    assert!(
        margin > 0.0 && margin < 10.0,
        "the COM sits a few mm behind the wheel axle: {margin}"
    );
    assert!(s.contact_links.contains(&"caster_back_link".to_string()));

    for (relative, kind) in [
        (
            "fetch/fetch_description/robots/fetch.urdf",
            RobotType::Wheeled,
        ),
        ("pr2/pr2_description/robots/pr2.urdf", RobotType::Wheeled),
    ] {
        let report = load(relative);
        assert_eq!(report.robot_type, Some(kind), "{relative}");
        assert_eq!(report.stability.unwrap().status, Status::Pass, "{relative}");
    }
    let pr2 = load("pr2/pr2_description/robots/pr2.urdf")
        .stability
        .unwrap();
    assert!(
        (pr2.margin_mm.unwrap() - 208.5).abs() < 0.1,
        "the spec's 208.5 mm: {:?}",
        pr2.margin_mm
    );
    assert!(
        pr2.raised_contacts.is_empty(),
        "caster housings above their wheels are not raised contacts"
    );

    for relative in [
        "anymal/anymal_b_simple_description/urdf/anymal.urdf",
        "spot/spot_description/model.urdf",
    ] {
        let report = load(relative);
        assert_eq!(report.robot_type, Some(RobotType::Quadruped), "{relative}");
        let s = report.stability.unwrap();
        assert_eq!(s.contact_source.as_deref(), Some("feet"), "{relative}");
        assert!(s.support_polygon.len() >= 3, "{relative}: a foot polygon");
    }
    let franka = load("franka_panda/franka_description/robots/frankie_arm_hand.urdf");
    assert_eq!(franka.robot_type, Some(RobotType::ArmOnly));
    assert_eq!(franka.stability.unwrap().status, Status::NotApplicable);

    let declared = |kind: RobotType| Options {
        overrides: Overrides {
            robot_type: Some(kind),
            ..Overrides::default()
        },
        ..Options::default()
    };
    let vehicle = report(
        &robots.join("samples/ground_vehicle.urdf"),
        &declared(RobotType::GroundVehicle),
    );
    assert_eq!(vehicle.overall_status, Status::Pass);
    assert_eq!(vehicle.stability.unwrap().status, Status::Pass);
    assert_eq!(
        vehicle.findings.iter().filter(|f| f.rule == "U730").count(),
        1,
        "declared ground_vehicle, structure says wheeled"
    );
    let drone = report(
        &robots.join("samples/aerial_drone.urdf"),
        &declared(RobotType::Aerial),
    );
    assert_eq!(drone.overall_status, Status::Pass);
    assert_eq!(drone.stability.unwrap().status, Status::NotApplicable);
    assert!(
        drone.findings.iter().all(|f| f.rule != "U730"),
        "the structure agrees: rotors, nothing on the ground"
    );
}

/// Real robots from public description repositories, outside the example-robot-data corpus
/// (`tests/data/robots40`, sources and licenses in its `SOURCES.md`), with the type each one is.
/// Meshes are left out: classification works from the URDF text alone. Less obvious ones: the
/// Minitaur and the Vision 60 stand upside down at the zero pose and write each leg as two chains
/// from two motors to one foot (a five-bar loop); the Spirit 40 lies flat on its stretched legs;
/// the Mini Cheetah's joints are all continuous; the Go2-W has wheels for feet; Cassie walks on two
/// legs without arms, Kraby on six; the G1 dual-arm model is an upper body on a fixed pelvis and
/// the Dex3 a hand (fixed-base mechanisms, as in the corpus table); the Crazyflie models (`gpd_*`)
/// and the PyBullet quadrotor have no movable joint but rotors; the racecar steers its front
/// wheels.
const ROBOTS40: &[(&str, RobotType)] = &[
    ("drake_cassie_v2", RobotType::Legged),
    ("drake_folding_table", RobotType::Object),
    ("drake_open_top_box", RobotType::Object),
    ("gpd_cf2x", RobotType::Aerial),
    ("gpd_racer", RobotType::Aerial),
    ("kinova_j2n6s300", RobotType::ArmOnly),
    ("kraby_hexapod", RobotType::Legged),
    ("kinova_m1n4s200", RobotType::ArmOnly),
    ("omx_f", RobotType::ArmOnly),
    ("omy_f3m", RobotType::ArmOnly),
    ("open_manipulator_x", RobotType::ArmOnly),
    ("pb_duck", RobotType::Object),
    ("pb_husky", RobotType::Wheeled),
    ("pb_jenga", RobotType::Object),
    ("pb_kuka_iiwa", RobotType::ArmOnly),
    ("pb_kuka_lwr", RobotType::ArmOnly),
    ("pb_mini_cheetah", RobotType::Quadruped),
    ("pb_minitaur", RobotType::Quadruped),
    ("pb_mug", RobotType::Object),
    ("pb_nao", RobotType::Humanoid),
    ("pb_plate", RobotType::Object),
    ("pb_quadrotor", RobotType::Aerial),
    ("pb_r2d2", RobotType::Wheeled),
    ("pb_racecar", RobotType::GroundVehicle),
    ("pb_spirit40", RobotType::Quadruped),
    ("pb_table", RobotType::Object),
    ("pb_table_square", RobotType::Object),
    ("pb_traybox", RobotType::Object),
    ("pb_vision60", RobotType::Quadruped),
    ("pb_widowx", RobotType::ArmOnly),
    ("pb_xarm6_gripper", RobotType::ArmOnly),
    ("rotors_firefly", RobotType::Aerial),
    ("rotors_hummingbird", RobotType::Aerial),
    ("rotors_pelican", RobotType::Aerial),
    ("turtlebot3_waffle_pi", RobotType::Wheeled),
    ("unitree_a2", RobotType::Quadruped),
    ("unitree_aliengo", RobotType::Quadruped),
    ("unitree_b2", RobotType::Quadruped),
    ("unitree_dex3_1_r", RobotType::ArmOnly),
    ("unitree_g1_dual_arm", RobotType::ArmOnly),
    ("unitree_go2w", RobotType::Quadruped),
    ("unitree_h1", RobotType::Humanoid),
    ("unitree_h1_2_handless", RobotType::Humanoid),
    ("unitree_h2", RobotType::Humanoid),
    ("unitree_r1", RobotType::Humanoid),
    ("ur20", RobotType::ArmOnly),
    ("ur5e", RobotType::ArmOnly),
];

fn robots40() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/robots40")
}

/// Few workspace samples: these tests are about the type, not the reach.
fn quick() -> Options {
    Options {
        workspace: WorkspaceOptions {
            samples: 16,
            ..WorkspaceOptions::default()
        },
        ..Options::default()
    }
}

#[test]
fn robots40_get_their_types() {
    let dir = robots40();
    let files = common::urdfs_below(&dir);
    let mut listed: Vec<String> = ROBOTS40.iter().map(|(n, _)| format!("{n}.urdf")).collect();
    listed.sort();
    let found: Vec<String> = files
        .iter()
        .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(found, listed, "the table covers every file of robots40");
    let kinds: std::collections::BTreeSet<&str> =
        ROBOTS40.iter().map(|(_, kind)| kind.as_str()).collect();
    assert_eq!(kinds.len(), 8, "every category but unknown: {kinds:?}");

    let options = quick();
    let mut table = vec![format!(
        "{:24} {:15} {:15} evidence",
        "robot", "expected", "detected"
    )];
    let mut wrong = 0;
    for (name, expected) in ROBOTS40 {
        let got = report(&dir.join(format!("{name}.urdf")), &options);
        let detected = got.robot_type.map_or("none", |t| t.as_str());
        let mark = if got.robot_type == Some(*expected) {
            " "
        } else {
            wrong += 1;
            "✗"
        };
        table.push(format!(
            "{mark}{name:23} {:15} {detected:15} {}",
            expected.as_str(),
            got.robot_type_evidence.unwrap_or_default()
        ));
    }
    assert!(wrong == 0, "{wrong} wrong:\n{}", table.join("\n"));
}

#[test]
fn an_object_is_checked_as_an_object() {
    let options = quick();
    for name in ["pb_table", "pb_traybox", "pb_mug", "drake_folding_table"] {
        let report = report(&robots40().join(format!("{name}.urdf")), &options);
        assert_eq!(report.robot_type, Some(RobotType::Object), "{name}");
        let stability = report.stability.unwrap();
        assert_eq!(stability.status, Status::NotApplicable, "{name}");
        assert!(
            stability
                .reason
                .as_deref()
                .is_some_and(|r| r.contains("no movable joint")),
            "{name}: {:?}",
            stability.reason
        );
        let statics = report.statics.unwrap();
        assert!(statics.joints.is_empty(), "{name}");
        let workspace = report.workspace.unwrap();
        assert_eq!(workspace.status, Status::NotApplicable, "{name}");
        assert!(workspace.arms.is_empty(), "{name}");
        assert!(
            workspace
                .reason
                .as_deref()
                .is_some_and(|r| r.contains("'object' has no movable joint")),
            "{name}: {:?}",
            workspace.reason
        );
        assert!(
            report.warnings.is_empty() && report.critical_issues.is_empty(),
            "{name}: a sound object ends without WARN or FAIL: {:?}",
            report.warnings
        );
        assert_eq!(report.overall_status, Status::Pass, "{name}");
    }
    // Declared, it is exact and agrees with the structure.
    let declared = Options {
        overrides: Overrides {
            robot_type: Some(RobotType::Object),
            ..Overrides::default()
        },
        ..quick()
    };
    let table = report(&robots40().join("pb_table.urdf"), &declared);
    assert!(table.warnings.is_empty(), "{:?}", table.warnings);
    assert_eq!(RobotType::parse("object"), Some(RobotType::Object));
}

fn detected(urdf: &str) -> (Option<RobotType>, Option<String>) {
    let report =
        urdf_validator::validate_text(urdf.to_string(), std::path::Path::new("t.urdf"), &quick())
            .unwrap()
            .report;
    (report.robot_type, report.robot_type_evidence)
}

const INERTIAL: &str = r#"<inertial><mass value="0.2"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>"#;

/// A small desk arm on a base plate: three revolute joints, a two-finger gripper, and each motor's rotor
/// drawn as a link of its own (named `*_rotor`) inside the arm.
fn small_arm_with_rotor_named_motors() -> String {
    let link = |name: &str, geometry: &str| {
        format!(
            r#"<link name="{name}">{INERTIAL}<collision><geometry>{geometry}</geometry></collision></link>"#
        )
    };
    let joint = |name: &str, kind: &str, parent: &str, child: &str, xyz: &str, axis: &str| {
        format!(
            r#"<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/><origin xyz="{xyz}"/><axis xyz="{axis}"/><limit lower="-1" upper="1" effort="5" velocity="1"/></joint>"#
        )
    };
    let mut urdf = String::from(r#"<robot name="desk_arm">"#);
    urdf += &link("base", r#"<box size="0.1 0.1 0.02"/>"#);
    let mut parent = "base".to_string();
    for i in 1..=3 {
        let child = format!("link{i}");
        urdf += &link(&child, r#"<box size="0.03 0.03 0.1"/>"#);
        let axis = if i == 1 { "0 0 1" } else { "0 1 0" };
        urdf += &joint(
            &format!("joint{i}"),
            "revolute",
            &parent,
            &child,
            "0 0 0.06",
            axis,
        );
        let rotor = format!("link{i}_rotor");
        urdf += &link(&rotor, r#"<cylinder radius="0.01" length="0.01"/>"#);
        urdf += &joint(
            &format!("{rotor}_joint"),
            "fixed",
            &child,
            &rotor,
            "0 0 0",
            "0 0 1",
        );
        parent = child;
    }
    urdf += &link("hand", r#"<box size="0.04 0.06 0.02"/>"#);
    urdf += &joint("hand_joint", "fixed", &parent, "hand", "0 0 0.06", "0 0 1");
    for (side, y) in [("left", "0.02"), ("right", "-0.02")] {
        let finger = format!("{side}_finger");
        urdf += &link(&finger, r#"<box size="0.01 0.01 0.03"/>"#);
        urdf += &joint(
            &format!("{finger}_joint"),
            "prismatic",
            "hand",
            &finger,
            &format!("0 {y} 0.02"),
            "0 1 0",
        );
    }
    urdf + "</robot>"
}

#[test]
fn motors_named_rotor_inside_an_arm_do_not_make_a_drone() {
    // Before: any rotor name with no legs or wheels made the robot aerial.
    let (kind, evidence) = detected(&small_arm_with_rotor_named_motors());
    assert_eq!(kind, Some(RobotType::ArmOnly), "{evidence:?}");
}

/// Four unnamed propeller discs (cylinders 20 times wider than thick, vertical axes) on continuous joints
/// above a body standing on fixed skids.
fn drone_with_unnamed_discs() -> String {
    let mut urdf = format!(
        r#"<robot name="x4"><link name="body">{INERTIAL}<collision><geometry><box size="0.2 0.2 0.05"/></geometry></collision></link><link name="skids">{INERTIAL}<collision><geometry><box size="0.3 0.2 0.01"/></geometry></collision></link><joint name="skids_joint" type="fixed"><parent link="body"/><child link="skids"/><origin xyz="0 0 -0.1"/></joint>"#
    );
    for (i, (x, y)) in [(0.2, 0.2), (0.2, -0.2), (-0.2, 0.2), (-0.2, -0.2)]
        .iter()
        .enumerate()
    {
        urdf += &format!(
            r#"<link name="m{i}">{INERTIAL}<collision><geometry><cylinder radius="0.1" length="0.01"/></geometry></collision></link><joint name="j{i}" type="continuous"><parent link="body"/><child link="m{i}"/><origin xyz="{x} {y} 0.05"/><axis xyz="0 0 1"/></joint>"#
        );
    }
    urdf + "</robot>"
}

#[test]
fn rotors_are_found_by_their_shape() {
    // Before: no rotor name, so four spinning discs on a body resting on the ground were "a fixed-base
    // mechanism".
    let (kind, evidence) = detected(&drone_with_unnamed_discs());
    assert_eq!(kind, Some(RobotType::Aerial), "{evidence:?}");
    assert!(evidence.unwrap().contains("4 rotor disc"));
    // The same discs standing on edge (the cylinders' axes horizontal) are not rotors.
    let tilted = drone_with_unnamed_discs().replace(
        r#"<collision><geometry><cylinder"#,
        r#"<collision><origin rpy="1.5708 0 0"/><geometry><cylinder"#,
    );
    let (kind, evidence) = detected(&tilted);
    assert_ne!(kind, Some(RobotType::Aerial), "{evidence:?}");
}

/// A y-up quadruped modelled like PyBullet's `laikago.urdf` (pybullet_data/laikago): the body lies in the
/// x–z plane, each leg leaves it at a hip motor turning about z, and its upper and lower leg (turning about
/// x) hang along −y, the knee bent back by `knee_z` so the leg leans as laikago's do.
fn y_up_quadruped(knee_z: f64) -> String {
    let inertia = r#"<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>"#;
    let mut urdf = format!(
        r#"<robot name="y_up_quadruped">
  <link name="chassis">
    <inertial><origin xyz="0 0.03 0.02"/><mass value="13.7"/>{inertia}</inertial>
    <collision><geometry><box size="0.2 0.12 0.5"/></geometry></collision>
  </link>
"#
    );
    for (leg, x, z) in [
        ("FR", -0.08, 0.24),
        ("FL", 0.08, 0.24),
        ("RR", -0.08, -0.19),
        ("RL", 0.08, -0.19),
    ] {
        urdf.push_str(&format!(
            r#"  <link name="{leg}_hip_motor">
    <inertial><mass value="1.1"/>{inertia}</inertial>
    <collision><geometry><cylinder radius="0.04" length="0.06"/></geometry></collision>
  </link>
  <joint name="{leg}_hip_motor_2_chassis_joint" type="continuous">
    <parent link="chassis"/><child link="{leg}_hip_motor"/><axis xyz="0 0 1"/>
    <origin xyz="{x} 0 {z}"/><limit effort="100" velocity="100"/>
  </joint>
  <link name="{leg}_upper_leg">
    <inertial><origin xyz="0 -0.1 0"/><mass value="1.5"/>{inertia}</inertial>
    <collision><origin xyz="0 -0.1 {half}" rpy="1.5708 0 0"/><geometry><cylinder radius="0.025" length="0.2"/></geometry></collision>
  </link>
  <joint name="{leg}_upper_leg_2_hip_motor_joint" type="continuous">
    <parent link="{leg}_hip_motor"/><child link="{leg}_upper_leg"/><axis xyz="1 0 0"/>
    <limit effort="100" velocity="100"/>
  </joint>
  <link name="{leg}_lower_leg">
    <inertial><origin xyz="0 -0.1 0"/><mass value="0.24"/>{inertia}</inertial>
    <collision><origin xyz="0 -0.1 0" rpy="1.5708 0 0"/><geometry><cylinder radius="0.015" length="0.2"/></geometry></collision>
    <collision><origin xyz="0 -0.21 0"/><geometry><sphere radius="0.02"/></geometry></collision>
  </link>
  <joint name="{leg}_lower_leg_2_upper_leg_joint" type="continuous">
    <parent link="{leg}_upper_leg"/><child link="{leg}_lower_leg"/><axis xyz="1 0 0"/>
    <origin xyz="0 -0.2 {knee_z}"/><limit effort="100" velocity="100"/>
  </joint>
"#,
            half = knee_z / 2.0,
        ));
    }
    urdf.push_str("</robot>\n");
    urdf
}

fn y_up_report(options: &Options) -> Report {
    urdf_validator::validate_text(
        y_up_quadruped(-0.14),
        std::path::Path::new("y_up_quadruped.urdf"),
        options,
    )
    .unwrap()
    .report
}

#[test]
fn a_y_up_quadruped_is_a_quadruped_with_a_warning_and_up_axis_y_stands_it_up() {
    let options = || {
        let mut options = Options::default();
        options.workspace.samples = 200;
        options.deep.automatic = false;
        options
    };
    // As written (z up, as a simulator loads it): a quadruped by the structure in the y-up frame, U731 says
    // so, and the physics judges the robot lying on its side.
    let report = y_up_report(&options());
    assert_eq!(report.robot_type, Some(RobotType::Quadruped));
    let warned: Vec<_> = report
        .findings
        .iter()
        .filter(|f| f.rule == "U731")
        .collect();
    assert_eq!(warned.len(), 1, "{:?}", report.findings);
    assert!(
        warned[0].message.contains("+y up") && warned[0].message.contains("quadruped"),
        "{}",
        warned[0].message
    );
    assert_eq!(warned[0].line, Some(2), "at the root link");
    assert!(warned[0].help.as_deref().unwrap().contains("--up-axis y"));
    // Declared y up: gravity along −y for every analysis; it stands on its four feet.
    let mut declared = options();
    declared.overrides.up_axis = urdf_validator::model::UpAxis::parse("y");
    let standing = y_up_report(&declared);
    assert!(standing.findings.iter().all(|f| f.rule != "U731"));
    assert_eq!(standing.robot_type, Some(RobotType::Quadruped));
    let stability = standing.stability.unwrap();
    assert_eq!(stability.status, Status::Pass, "{:?}", stability.reason);
    assert!(stability.margin_mm.unwrap() > 50.0, "{stability:?}");
    assert_eq!(stability.support_polygon.len(), 4, "one point per foot");
    let statics = standing.statics.unwrap();
    let height = statics.com_height_above_ground.unwrap();
    assert!(
        (0.4..0.5).contains(&height),
        "COM {height} m above the feet"
    );
    // The same robot turned z-up in the file (a root link holding the body a quarter turn about x) shows no
    // other up axis and stands as the declared one does.
    let turned = y_up_quadruped(-0.14).replace(
        "  <link name=\"chassis\">",
        "  <link name=\"base\"/>\n  <joint name=\"base_to_chassis\" type=\"fixed\"><parent link=\"base\"/><child link=\"chassis\"/><origin rpy=\"1.5708 0 0\"/></joint>\n  <link name=\"chassis\">",
    );
    let z_up = urdf_validator::validate_text(
        turned,
        std::path::Path::new("z_up_quadruped.urdf"),
        &options(),
    )
    .unwrap()
    .report;
    assert!(z_up.findings.iter().all(|f| f.rule != "U731"));
    assert_eq!(z_up.robot_type, Some(RobotType::Quadruped));
    assert_eq!(z_up.stability.unwrap().status, Status::Pass);
    // MuJoCo loads the file z-up: --deep with a declared up axis is refused, not run on the lying robot.
    declared.deep.requested = true;
    let refused = urdf_validator::validate_text(
        y_up_quadruped(-0.14),
        std::path::Path::new("y_up_quadruped.urdf"),
        &declared,
    );
    assert!(
        matches!(&refused, Err(urdf_validator::Error::Unusable { message, .. }) if message.contains("--deep with --up-axis +y")),
        "{refused:?}"
    );
}

/// PyBullet's laikago files (pybullet 3.2.7, `pybullet_data/laikago`): the y-up ones are quadrupeds with a
/// U731 naming +y, and stand with `--up-axis y`; the z-up export is a quadruped without U731.
#[test]
fn pybullet_laikago_is_a_y_up_quadruped() {
    let Some(data) = common::pybullet_data() else {
        return;
    };
    let laikago = data.join("laikago");
    let options = |up: Option<&str>| {
        let mut options = Options::default();
        options.workspace.samples = 200;
        options.deep.automatic = false;
        options.overrides.up_axis = up.and_then(urdf_validator::model::UpAxis::parse);
        options
    };
    let run = report;
    for (file, y_up) in [
        ("laikago.urdf", true),
        ("laikago_toes.urdf", true),
        ("laikago_toes_limits.urdf", true),
        ("laikago_toes_zup.urdf", false),
    ] {
        let found = run(&laikago.join(file), &options(None));
        assert_eq!(found.robot_type, Some(RobotType::Quadruped), "{file}");
        let warned: Vec<_> = found.findings.iter().filter(|f| f.rule == "U731").collect();
        assert_eq!(warned.len(), usize::from(y_up), "{file}: {warned:?}");
        if y_up {
            assert!(warned[0].message.contains("+y up"), "{}", warned[0].message);
            let standing = run(&laikago.join(file), &options(Some("y")));
            assert!(standing.findings.iter().all(|f| f.rule != "U731"));
            assert_eq!(standing.robot_type, Some(RobotType::Quadruped), "{file}");
            let stability = standing.stability.unwrap();
            assert_eq!(
                stability.status,
                Status::Pass,
                "{file}: {:?}",
                stability.reason
            );
        }
    }
}
