//! Statics on robots whose answers are known on paper: pendulums, a mimic pair, a lift, a payload; and the
//! pose options on real SRDFs.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::path::Path;

use urdf_validator::analysis::pose::{PoseKind, PoseOptions};
use urdf_validator::analysis::statics::StaticsOptions;
use urdf_validator::report::{JointStatics, StaticsSection, Status};
use urdf_validator::{validate_text, Options};

const G: f64 = 9.81;

fn inertial(mass: f64, x: f64) -> String {
    format!(
        r#"<inertial><origin xyz="{x} 0 0"/><mass value="{mass}"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>"#
    )
}

/// A base with one revolute joint about +y carrying `mass` at `x`, then a `tool0` frame at `tool_x`.
fn pendulum(mass: f64, x: f64, tool_x: f64, effort: f64) -> String {
    format!(
        r#"<robot name="pendulum">
  <link name="base"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-1.5707963267948966" upper="1.5707963267948966" effort="{effort}" velocity="1"/>
  </joint>
  <link name="arm">{}</link>
  <joint name="tool_joint" type="fixed"><parent link="arm"/><child link="tool0"/><origin xyz="{tool_x} 0 0"/></joint>
  <link name="tool0"/>
</robot>"#,
        inertial(mass, x)
    )
}

fn statics_with(urdf: &str, statics: StaticsOptions) -> StaticsSection {
    let options = Options {
        statics,
        ..Options::default()
    };
    validate_text(urdf.to_string(), Path::new("t.urdf"), &options)
        .expect("loads")
        .report
        .statics
        .expect("statics")
}

fn statics(urdf: &str) -> StaticsSection {
    statics_with(urdf, StaticsOptions::default())
}

fn pose(kind: PoseKind) -> StaticsOptions {
    StaticsOptions {
        pose: PoseOptions {
            kind,
            ..PoseOptions::default()
        },
        ..StaticsOptions::default()
    }
}

fn joint<'a>(section: &'a StaticsSection, name: &str) -> &'a JointStatics {
    section
        .joints
        .iter()
        .find(|j| j.name == name)
        .unwrap_or_else(|| panic!("no joint {name}"))
}

fn torque(section: &StaticsSection, name: &str) -> f64 {
    joint(section, name)
        .required_torque_gravity
        .expect("torque")
}

#[test]
fn horizontal_pendulum_needs_m_g_x() {
    let section = statics(&pendulum(2.0, 0.5, 1.0, 30.0));
    // Gravity pulls the arm down (+y rotation lowers +x); holding it takes −m·g·x about +y.
    assert!((torque(&section, "shoulder") + 2.0 * G * 0.5).abs() < 1e-12);
    let shoulder = joint(&section, "shoulder");
    assert_eq!(shoulder.status, Status::Pass);
    assert!((shoulder.margin.unwrap() - 30.0 / (2.0 * G * 0.5)).abs() < 1e-12);
    assert_eq!(section.total_mass, Some(2.0));
    assert_eq!(section.full_body_com, Some([0.5, 0.0, 0.0]));
}

#[test]
fn verdicts_follow_the_margin_thresholds() {
    let torque = 2.0 * G * 0.5;
    for (effort, expected) in [
        (1.6 * torque, Status::Pass),
        (1.2 * torque, Status::Warn),
        (0.9 * torque, Status::Fail),
    ] {
        let section = statics(&pendulum(2.0, 0.5, 1.0, effort));
        assert_eq!(
            joint(&section, "shoulder").status,
            expected,
            "effort {effort}"
        );
        assert_eq!(section.status, expected);
    }
}

#[test]
fn limits_pose_hangs_the_pendulum_straight_down() {
    let section = statics_with(&pendulum(2.0, 0.5, 1.0, 30.0), pose(PoseKind::Limits));
    assert_eq!(
        section.configuration["shoulder"],
        std::f64::consts::FRAC_PI_2
    );
    assert!(torque(&section, "shoulder").abs() < 1e-12);
    assert_eq!(
        joint(&section, "shoulder").summary,
        "OK — torque negligible"
    );
    let com = section.full_body_com.unwrap();
    assert!((com[2] + 0.5).abs() < 1e-12, "COM below the joint: {com:?}");
}

#[test]
fn worst_pose_finds_the_horizontal_arm_within_sampling_error() {
    let section = statics_with(&pendulum(2.0, 0.5, 1.0, 30.0), pose(PoseKind::Worst));
    let worst = torque(&section, "shoulder").abs();
    let exact = 2.0 * G * 0.5;
    // |τ| = m g x cos q with q uniform in ±π/2: 30,000 samples land within 0.01 rad of 0 with overwhelming
    // probability, so the maximum is within 1 − cos(0.01) ≈ 5e-5 of the exact value, and never above it.
    assert!(
        worst <= exact + 1e-12 && worst > exact * (1.0 - 1e-4),
        "{worst} vs {exact}"
    );
    let at = &joint(&section, "shoulder")
        .worst_configuration
        .as_ref()
        .unwrap()["shoulder"];
    assert!(at.abs() < 0.02, "worst near the horizontal, got {at}");
    assert_eq!(
        (section.samples, section.seed),
        (
            Some(urdf_validator::DEFAULT_SAMPLES),
            Some(urdf_validator::DEFAULT_SEED)
        )
    );
}

#[test]
fn prismatic_lift_holds_its_weight() {
    let urdf = format!(
        r#"<robot name="lift"><link name="base"/>
  <joint name="lift" type="prismatic"><parent link="base"/><child link="carriage"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="1" effort="100" velocity="0.1"/></joint>
  <link name="carriage">{}</link></robot>"#,
        inertial(3.0, 0.2)
    );
    let section = statics(&urdf);
    assert!((torque(&section, "lift") - 3.0 * G).abs() < 1e-12);
}

#[test]
fn mimic_follower_torque_folds_into_its_leader() {
    // Leader `drive` moves nothing itself; follower `finger` (×2) carries m at x. τ_finger = −m g x cos(2θ),
    // and by virtual work the leader must supply 2·τ_finger.
    let urdf = format!(
        r#"<robot name="mimic"><link name="base"/>
  <joint name="drive" type="revolute"><parent link="base"/><child link="crank"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="100" velocity="1"/></joint>
  <link name="crank"/>
  <joint name="finger" type="revolute"><parent link="base"/><child link="finger_link"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="100" velocity="1"/><mimic joint="drive" multiplier="2" offset="0"/></joint>
  <link name="finger_link">{}</link></robot>"#,
        inertial(1.5, 0.4)
    );
    let theta: f64 = 0.3;
    let options = StaticsOptions {
        pose: PoseOptions {
            kind: PoseKind::Custom,
            joint_angles: Some(format!("drive={theta}")),
            ..PoseOptions::default()
        },
        ..StaticsOptions::default()
    };
    let section = statics_with(&urdf, options);
    let follower = -1.5 * G * 0.4 * (2.0 * theta).cos();
    assert!((torque(&section, "finger") - follower).abs() < 1e-12);
    assert!((torque(&section, "drive") - 2.0 * follower).abs() < 1e-12);
    assert_eq!(joint(&section, "finger").status, Status::NotApplicable);
    assert_eq!(joint(&section, "finger").mimics.as_deref(), Some("drive"));
    assert!(
        !section.configuration.contains_key("finger"),
        "followers are not independent coordinates"
    );
}

/// Two links about +y, horizontal at the zero pose: `upper` (m1 at l1/2, elbow at l1) then `fore` (m2 at l2/2),
/// the payload at `tool0` (at l2 past the elbow).
fn two_link_arm(shoulder_effort: f64, elbow_effort: f64) -> String {
    let limit = |effort: f64| {
        format!(
            r#"<limit lower="-1.5707963267948966" upper="1.5707963267948966" effort="{effort}" velocity="1"/>"#
        )
    };
    format!(
        r#"<robot name="two_link">
  <link name="base"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 1 0"/>{}</joint>
  <link name="upper">{}</link>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0.4 0 0"/><axis xyz="0 1 0"/>{}</joint>
  <link name="fore">{}</link>
  <joint name="tool_joint" type="fixed"><parent link="fore"/><child link="tool0"/><origin xyz="0.3 0 0"/></joint>
  <link name="tool0"/>
</robot>"#,
        limit(shoulder_effort),
        inertial(3.0, 0.2),
        limit(elbow_effort),
        inertial(1.5, 0.15),
    )
}

#[test]
fn effort_needed_is_one_and_a_half_times_the_worst_torque_payload_included() {
    let payload = 0.5;
    let options = StaticsOptions {
        payload_mass: Some(payload),
        ..StaticsOptions::default()
    };
    // τ_shoulder = g·(m1·l1/2 + m2·(l1 + l2/2) + p·(l1 + l2)); τ_elbow = g·(m2·l2/2 + p·l2).
    let shoulder_torque = G * (3.0 * 0.2 + 1.5 * (0.4 + 0.15) + payload * 0.7);
    let elbow_torque = G * (1.5 * 0.15 + payload * 0.3);
    let section = statics_with(&two_link_arm(10.0, 100.0), options);
    let shoulder = joint(&section, "shoulder");
    assert_eq!(shoulder.status, Status::Fail);
    assert!((shoulder.effort_needed.unwrap() - 1.5 * shoulder_torque).abs() < 1e-9);
    let elbow = joint(&section, "elbow");
    assert_eq!(elbow.status, Status::Pass);
    assert!((elbow.effort_needed.unwrap() - 1.5 * elbow_torque).abs() < 1e-9);

    // Declaring exactly the effort needed passes; a hair less does not.
    let needed = shoulder.effort_needed.unwrap();
    for (effort, expected) in [(needed, Status::Pass), (needed * 0.999, Status::Warn)] {
        let options = StaticsOptions {
            payload_mass: Some(payload),
            ..StaticsOptions::default()
        };
        let section = statics_with(&two_link_arm(effort, 100.0), options);
        assert_eq!(
            joint(&section, "shoulder").status,
            expected,
            "effort {effort}"
        );
    }
}

#[test]
fn the_undersized_finding_and_the_text_row_say_the_effort_needed() {
    let validation = validate_text(
        two_link_arm(10.0, 100.0),
        Path::new("t.urdf"),
        &Options::default(),
    )
    .expect("loads");
    let needed = 1.5 * G * (3.0 * 0.2 + 1.5 * (0.4 + 0.15));
    let finding = validation
        .report
        .findings
        .iter()
        .find(|f| f.rule == "U701")
        .expect("U701 on the shoulder");
    let help = finding.help.as_deref().unwrap_or_default();
    assert!(
        help.contains(&format!("declare effort ≥ {needed:.2} N·m")),
        "{help}"
    );
    let text = urdf_validator::render::text::render_text(
        &validation,
        &urdf_validator::render::text::TextOptions::default(),
    );
    let row = text
        .lines()
        .find(|l| l.trim_start().starts_with("shoulder"))
        .expect("a row for the failing shoulder");
    assert!(
        row.contains(&format!("→ declare effort ≥ {needed:.2}")),
        "{row}"
    );
}

#[test]
fn payload_capacity_has_the_closed_form() {
    // τ(m) = −g(M·x + m·L); capacity: g(M·x + m·L) = effort / 1.5.
    let (mass, x, length, effort) = (2.0, 0.5, 1.0, 30.0);
    let expected = (effort / 1.5 - G * mass * x) / (G * length);
    let loaded = |payload: f64| StaticsOptions {
        payload_mass: Some(payload),
        ..StaticsOptions::default()
    };
    let section = statics_with(&pendulum(mass, x, length, effort), loaded(1.0));
    assert_eq!(
        section.payload_link.as_deref(),
        Some("tool0"),
        "end of the longest actuated chain"
    );
    assert!((section.payload_capacity_kg.unwrap() - expected).abs() < 1e-12);
    assert!((torque(&section, "shoulder") + G * (mass * x + 1.0 * length)).abs() < 1e-12);
    assert_eq!(section.status, Status::Pass);
    let over = statics_with(&pendulum(mass, x, length, effort), loaded(expected + 0.01));
    assert_eq!(
        over.status,
        Status::Warn,
        "just past the capacity the margin drops below 1.5"
    );
}

#[test]
fn zero_outside_the_limits_is_clamped_with_a_note() {
    let urdf =
        pendulum(2.0, 0.5, 1.0, 30.0).replace(r#"lower="-1.5707963267948966""#, r#"lower="0.5""#);
    let section = statics(&urdf);
    assert_eq!(section.configuration["shoulder"], 0.5);
    assert!(
        section.notes[0].contains("0 is outside its limits"),
        "{:?}",
        section.notes
    );
}

#[test]
fn custom_pose_errors_and_notes() {
    let urdf = pendulum(2.0, 0.5, 1.0, 30.0);
    let custom = |angles: &str| StaticsOptions {
        pose: PoseOptions {
            kind: PoseKind::Custom,
            joint_angles: Some(angles.to_string()),
            ..PoseOptions::default()
        },
        ..StaticsOptions::default()
    };
    let options = Options {
        statics: custom("shouldr=0.1"),
        ..Options::default()
    };
    let error = validate_text(urdf.clone(), Path::new("t.urdf"), &options)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("unknown joint 'shouldr'") && error.contains("did you mean 'shoulder'"),
        "{error}"
    );
    let section = statics_with(&urdf, custom("shoulder=120deg"));
    assert!((section.configuration["shoulder"] - 120f64.to_radians()).abs() < 1e-12);
    assert!(section.notes[0].contains("outside its limits"));
}

#[test]
fn no_declared_mass_is_unknown_and_no_actuated_joint_is_not_applicable() {
    let massless = pendulum(2.0, 0.5, 1.0, 30.0).replace(
        &inertial(2.0, 0.5),
        r#"<visual><geometry><box size="1 0.1 0.1"/></geometry></visual>"#,
    );
    let section = statics(&massless);
    assert_eq!(section.status, Status::Unknown);
    assert_eq!(section.full_body_com, None);
    assert!(section
        .reason
        .as_deref()
        .unwrap()
        .contains("no link declares a mass"));
    let rigid = r#"<robot name="r"><link name="a">
      <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>"#;
    assert_eq!(statics(rigid).status, Status::NotApplicable);
}

#[test]
fn home_pose_reads_the_srdf_found_beside_the_urdf() {
    let Some(corpus) = common::corpus() else {
        return;
    };
    let urdf = corpus.join("z1_description/urdf/z1.urdf");
    let options = Options {
        statics: pose(PoseKind::Home),
        ..Options::default()
    };
    let report = urdf_validator::validate(&urdf, &options)
        .expect("loads")
        .report;
    let section = report.statics.expect("statics");
    assert!(section.notes.is_empty(), "{:?}", section.notes);
    let srdf = std::fs::read_to_string(corpus.join("z1_description/srdf/z1.srdf")).unwrap();
    let states = urdf_validator::input::srdf::group_states(&srdf).unwrap();
    let home = states.iter().find(|s| s.name == "home").unwrap();
    for (name, value) in &home.joints {
        assert_eq!(section.configuration[name], *value, "{name}");
    }
}

#[test]
fn home_pose_without_the_state_warns_and_uses_zero() {
    let Some(corpus) = common::corpus() else {
        return;
    };
    let urdf = corpus.join("panda_description/urdf/panda.urdf");
    let options = Options {
        statics: pose(PoseKind::Home),
        ..Options::default()
    };
    let section = urdf_validator::validate(&urdf, &options)
        .expect("loads")
        .report
        .statics
        .expect("statics");
    assert!(
        section
            .notes
            .iter()
            .any(|n| n.contains("no group_state 'home'") && n.contains("default")),
        "{:?}",
        section.notes
    );
    let with_state = Options {
        statics: StaticsOptions {
            pose: PoseOptions {
                kind: PoseKind::Home,
                state: "default".to_string(),
                ..PoseOptions::default()
            },
            ..StaticsOptions::default()
        },
        ..Options::default()
    };
    let section = urdf_validator::validate(&urdf, &with_state)
        .expect("loads")
        .report
        .statics
        .expect("statics");
    assert_eq!(section.configuration["panda_joint4"], -2.35619);
}

#[test]
fn reference_robots_match_the_spec_where_the_physics_agrees() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let load = |relative: &str| {
        urdf_validator::validate(&robots.join(relative), &Options::default())
            .expect("loads")
            .report
            .statics
            .expect("statics")
    };
    let pr2 = load("pr2/pr2_description/robots/pr2.urdf");
    assert_eq!(pr2.status, Status::Fail);
    for side in ["r", "l"] {
        let shoulder = joint(&pr2, &format!("{side}_shoulder_lift_joint"));
        let needed = shoulder.required_torque_gravity.unwrap().abs();
        assert!((needed - 49.5).abs() < 0.1, "{side}: {needed}");
        assert_eq!(
            (shoulder.declared_effort, shoulder.status),
            (Some(30.0), Status::Fail)
        );
    }
    assert!((pr2.total_mass.unwrap() - 265.732).abs() < 1e-3);
    let fetch = load("fetch/fetch_description/robots/fetch.urdf");
    assert_eq!(
        (fetch.status, fetch.weakest_joint_name.as_deref()),
        (Status::Pass, Some("torso_lift_joint"))
    );
    assert!((fetch.total_mass.unwrap() - 121.538).abs() < 1e-3);
    let com = fetch.full_body_com.unwrap();
    assert!(
        (com[0] - 0.045).abs() < 5e-4 && (com[2] - 0.260).abs() < 5e-4,
        "{com:?}"
    );
    let turtlebot = load("turtlebot3/turtlebot3_description/urdf/turtlebot3_burger.urdf");
    assert_eq!(turtlebot.status, Status::Pass);
    assert!((turtlebot.heaviest_link_pct.unwrap() - 82.4).abs() < 0.05);
    let anymal = load("anymal/anymal_b_simple_description/urdf/anymal.urdf");
    assert_eq!(
        (anymal.status, anymal.weakest_joint_name.as_deref()),
        (Status::Pass, Some("RF_HAA"))
    );
}

/// The pendulum of [`pendulum`] with `origin` on its joint, in a file declaring `version`.
fn tilted_pendulum(version: &str, origin: &str) -> String {
    pendulum(2.0, 0.5, 1.0, 30.0)
        .replacen(
            "<robot name=\"pendulum\">",
            &format!("<robot name=\"pendulum\"{version}>"),
            1,
        )
        .replacen(
            "<axis xyz=\"0 1 0\"/>",
            &format!("<axis xyz=\"0 1 0\"/>{origin}"),
            1,
        )
}

#[test]
fn a_joint_quat_xyzw_turning_the_axis_vertical_leaves_no_gravity_torque() {
    // Rx(+90°) maps the joint's y axis to the world's z axis: the arm swings in a horizontal plane and
    // gravity no longer turns it. The mass stays at x = 0.5 (Rx keeps x).
    let v11 = r#" version="1.1""#;
    let half = std::f64::consts::FRAC_1_SQRT_2;
    let vertical = statics(&tilted_pendulum(
        v11,
        &format!(r#"<origin quat_xyzw="{half} 0 0 {half}"/>"#),
    ));
    assert!(
        torque(&vertical, "shoulder").abs() < 1e-12,
        "{}",
        torque(&vertical, "shoulder")
    );
    assert_eq!(
        vertical.full_body_com.map(|c| (c[0] * 1e12).round() / 1e12),
        Some(0.5)
    );
    // The same rotation as rpy agrees, and urdfdom normalises a quaternion that is not unit.
    let rpy = statics(&tilted_pendulum(
        v11,
        r#"<origin rpy="1.5707963267948966 0 0"/>"#,
    ));
    assert!(torque(&rpy, "shoulder").abs() < 1e-12);
    let unnormalised = statics(&tilted_pendulum(v11, r#"<origin quat_xyzw="3 0 0 3"/>"#));
    assert!(torque(&unnormalised, "shoulder").abs() < 1e-12);
    // A zero quaternion is the identity for urdfdom (Rotation::normalize): the horizontal axis again.
    let zero = statics(&tilted_pendulum(v11, r#"<origin quat_xyzw="0 0 0 0"/>"#));
    assert!((torque(&zero, "shoulder") + 2.0 * G * 0.5).abs() < 1e-12);
    // In a 1.0 file urdfdom ignores quat_xyzw: the axis stays horizontal and the torque is m·g·x.
    for version in ["", r#" version="1.0""#] {
        let ignored = statics(&tilted_pendulum(
            version,
            &format!(r#"<origin quat_xyzw="{half} 0 0 {half}"/>"#),
        ));
        assert!((torque(&ignored, "shoulder") + 2.0 * G * 0.5).abs() < 1e-12);
    }
}

/// The effort the help tells to declare is the one the fix writes, rounded up: the elbow needs
/// 1.5 × 2.20725 = 3.310875 N·m, so "≥ 3.32" (to the nearest hundredth, 3.31 would leave it short).
#[test]
fn the_help_the_text_row_and_the_fix_name_the_same_effort_rounded_up() {
    let validation = validate_text(
        two_link_arm(10.0, 2.0),
        Path::new("t.urdf"),
        &Options::default(),
    )
    .expect("loads");
    let needed = 1.5 * G * 1.5 * 0.15;
    assert!((needed - 3.310875).abs() < 1e-3, "{needed}");
    let finding = validation
        .report
        .findings
        .iter()
        .find(|f| f.rule == "U701" && f.message.contains("'elbow'"))
        .expect("U701 on the elbow");
    let help = finding.help.as_deref().unwrap_or_default();
    assert!(help.contains("declare effort ≥ 3.32 N·m"), "{help}");
    let fix = finding.fix.as_ref().expect("a fix");
    assert!(
        fix.description.contains("set effort to 3.32 N·m"),
        "{}",
        fix.description
    );
    let text = urdf_validator::render::text::render_text(
        &validation,
        &urdf_validator::render::text::TextOptions::default(),
    );
    let row = text
        .lines()
        .find(|l| l.trim_start().starts_with("elbow"))
        .expect("a row for the failing elbow");
    assert!(row.contains("→ declare effort ≥ 3.32"), "{row}");
}
