//! Robot types of every example-robot-data robot and of the reference robots, and stability on them.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use urdf_validator::analysis::classify::RobotType;
use urdf_validator::analysis::pose::{PoseKind, PoseOptions};
use urdf_validator::analysis::statics::StaticsOptions;
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
