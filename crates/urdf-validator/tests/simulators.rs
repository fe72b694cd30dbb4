//! `--simulator` load profiles (U750–U761): for each rule, a small document that triggers it and one that
//! does not; without a profile none of them reports.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::Path;

use urdf_validator::analysis::profiles::Simulator;
use urdf_validator::report::FindingReport;
use urdf_validator::{validate_text, Options};

fn findings(urdf: &str, simulators: &[Simulator]) -> Vec<FindingReport> {
    let options = Options {
        simulators: simulators.to_vec(),
        ..Options::default()
    };
    validate_text(urdf.to_string(), Path::new("t.urdf"), &options)
        .expect("a parsed document")
        .report
        .findings
}

/// (line, message) of every finding of `code`.
fn of(urdf: &str, simulator: Simulator, code: &str) -> Vec<(u32, String)> {
    findings(urdf, &[simulator])
        .into_iter()
        .filter(|f| f.rule == code)
        .map(|f| (f.line.unwrap_or(0), f.message))
        .collect()
}

const INERTIAL: &str = r#"<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>"#;

/// A base with a revolute arm link and a fixed tool link; `tool` and `arm` are the two links' bodies.
fn robot(arm: &str, tool: &str, fixed_extra: &str) -> String {
    format!(
        r#"<robot name="r">
  <link name="base">{INERTIAL}</link>
  <link name="arm">{arm}</link>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <link name="tool">{tool}</link>
  <joint name="tool_joint" type="fixed">
    <parent link="arm"/><child link="tool"/>
  </joint>
{fixed_extra}</robot>
"#
    )
}

const BOX_COLLISION: &str =
    r#"<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>"#;

#[test]
fn no_profile_no_simulator_findings() {
    let urdf = robot("", "", "");
    let all = findings(&urdf, &[]);
    assert!(all.iter().all(|f| !f.rule.starts_with("U75")), "{all:?}");
}

#[test]
fn simulator_names_parse_and_unknown_ones_are_refused() {
    assert_eq!("Gazebo".parse::<Simulator>(), Ok(Simulator::Gazebo));
    assert_eq!("isaac".parse::<Simulator>(), Ok(Simulator::Isaac));
    let err = "webots".parse::<Simulator>().unwrap_err();
    assert!(
        err.contains("mujoco, gazebo, pybullet, drake, isaac"),
        "{err}"
    );
}

// ---------------------------------------------------------------------------------------------- Gazebo

#[test]
fn u750_gazebo_lumps_fixed_joint() {
    let urdf = robot(INERTIAL, INERTIAL, "");
    let found = of(&urdf, Simulator::Gazebo, "U750");
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, 9);
    assert!(
        found[0].1.contains("'tool' is merged into 'arm'"),
        "{found:?}"
    );
}

#[test]
fn u750_clean_when_preserve_fixed_joint() {
    let keep = r#"  <gazebo reference="tool_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>
"#;
    assert!(of(&robot(INERTIAL, INERTIAL, keep), Simulator::Gazebo, "U750").is_empty());
    let disable = r#"  <gazebo reference="tool_joint"><disableFixedJointLumping>1</disableFixedJointLumping></gazebo>
"#;
    assert!(of(
        &robot(INERTIAL, INERTIAL, disable),
        Simulator::Gazebo,
        "U750"
    )
    .is_empty());
}

#[test]
fn u751_gazebo_drops_massless_link_and_below() {
    // `arm` has no inertial and its lumped child is massless too: dropped with `tool`.
    let urdf = robot("", "", "");
    let found = of(&urdf, Simulator::Gazebo, "U751");
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, 3);
    assert!(found[0].1.contains("'arm'"), "{found:?}");
    assert!(found[0].1.contains("'j1'"), "{found:?}");
    assert!(found[0].1.contains("the 1 link(s) below"), "{found:?}");
}

#[test]
fn u751_clean_when_a_lumped_child_brings_mass() {
    // sdformat lumps `tool` (with mass) into `arm` before deciding: `arm` has mass then.
    let urdf = robot("", INERTIAL, "");
    assert!(of(&urdf, Simulator::Gazebo, "U751").is_empty());
}

#[test]
fn u751_zero_mass_counts_as_none() {
    let zero = r#"<inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>"#;
    let found = of(&robot(zero, "", ""), Simulator::Gazebo, "U751");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].1.contains("mass ≤ 0"), "{found:?}");
}

// ---------------------------------------------------------------------------------------------- MuJoCo

#[test]
fn u752_mujoco_inertia_triangle() {
    let bad = r#"<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.05"/></inertial>"#;
    let found = of(&robot(bad, INERTIAL, ""), Simulator::Mujoco, "U752");
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, 3);
    assert!(of(&robot(INERTIAL, INERTIAL, ""), Simulator::Mujoco, "U752").is_empty());
    // A link on a fixed joint is checked too (MuJoCo refuses PR2's fixed sensor_mount_link).
    let fixed = of(&robot(INERTIAL, bad, ""), Simulator::Mujoco, "U752");
    assert_eq!(fixed.len(), 1, "{fixed:?}");
    assert!(fixed[0].1.contains("'tool'"), "{fixed:?}");
}

#[test]
fn u753_mujoco_mass_below_minimum() {
    let found = of(&robot("", "", ""), Simulator::Mujoco, "U753");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].1.contains("'arm'"), "{found:?}");
}

#[test]
fn u753_clean_with_collision_mass_or_a_fused_child_with_mass() {
    assert!(of(&robot(BOX_COLLISION, "", ""), Simulator::Mujoco, "U753").is_empty());
    assert!(of(&robot("", INERTIAL, ""), Simulator::Mujoco, "U753").is_empty());
    assert!(of(&robot(INERTIAL, "", ""), Simulator::Mujoco, "U753").is_empty());
}

#[test]
fn u754_mujoco_fuses_static() {
    let found = of(&robot(INERTIAL, INERTIAL, ""), Simulator::Mujoco, "U754");
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, 9);
    assert!(found[0].1.contains("'tool' into 'arm'"), "{found:?}");
    let no_fixed = r#"<robot name="r"><link name="a"/></robot>"#;
    assert!(of(no_fixed, Simulator::Mujoco, "U754").is_empty());
}

#[test]
fn u755_mujoco_discards_visual() {
    let visual = r#"<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>"#;
    let found = of(&robot(INERTIAL, visual, ""), Simulator::Mujoco, "U755");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].1.contains("'tool'"), "{found:?}");
    let both = format!("{visual}{BOX_COLLISION}");
    assert!(of(&robot(INERTIAL, &both, ""), Simulator::Mujoco, "U755").is_empty());
}

// -------------------------------------------------------------------------------------------- PyBullet

#[test]
fn u756_pybullet_default_inertial() {
    let found = of(&robot(INERTIAL, "", ""), Simulator::Pybullet, "U756");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].1.contains("'tool'") && found[0].1.contains("1 kg"),
        "{found:?}"
    );
    assert!(of(&robot(INERTIAL, INERTIAL, ""), Simulator::Pybullet, "U756").is_empty());
    let world = r#"<robot name="r"><link name="world"/></robot>"#;
    assert!(of(world, Simulator::Pybullet, "U756").is_empty());
}

#[test]
fn u757_pybullet_inertia_from_collision() {
    let found = of(&robot(INERTIAL, INERTIAL, ""), Simulator::Pybullet, "U757");
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, 2);
    assert!(
        found[0].1.contains("3 declared inertia tensor(s)"),
        "{found:?}"
    );
    let frames = r#"<robot name="r"><link name="a"/></robot>"#;
    assert!(of(frames, Simulator::Pybullet, "U757").is_empty());
}

// ----------------------------------------------------------------------------------------------- Drake

fn joint_robot(extra: &str) -> String {
    format!(
        r#"<robot name="r">
  <link name="a">{INERTIAL}</link>
  <link name="b">{INERTIAL}</link>
  <joint name="j" type="revolute">
    <parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
    {extra}
  </joint>
</robot>
"#
    )
}

#[test]
fn u758_drake_ignores_joint_friction() {
    let found = of(
        &joint_robot(r#"<dynamics damping="0.1" friction="0.2"/>"#),
        Simulator::Drake,
        "U758",
    );
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, 4);
    let no_friction = joint_robot(r#"<dynamics damping="0.1" friction="0"/>"#);
    assert!(of(&no_friction, Simulator::Drake, "U758").is_empty());
}

#[test]
fn u759_drake_ignores_element() {
    let urdf = joint_robot(
        r#"<safety_controller k_velocity="1" soft_lower_limit="-0.9" soft_upper_limit="0.9"/><calibration rising="0"/>"#,
    );
    let found = of(&urdf, Simulator::Drake, "U759");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].1.contains("<calibration> and <safety_controller>"),
        "{found:?}"
    );
    assert!(of(&joint_robot(""), Simulator::Drake, "U759").is_empty());
}

// ----------------------------------------------------------------------------------------------- Isaac

#[test]
fn u760_isaac_no_mass() {
    // `arm` has collision but no inertial; `tool` has neither.
    let urdf = robot(BOX_COLLISION, "", "");
    let found = of(&urdf, Simulator::Isaac, "U760");
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(
        found[0].1.contains("link 'arm'") && found[0].1.contains("density"),
        "{found:?}"
    );
    assert!(
        found[1].1.contains("link 'tool'") && !found[1].1.contains("density"),
        "{found:?}"
    );
    // Every link with a mass: nothing.
    let urdf = robot(INERTIAL, INERTIAL, "");
    assert!(of(&urdf, Simulator::Isaac, "U760").is_empty());
}

#[test]
fn u761_isaac_default_inertia() {
    // `tool` has no collision and no inertial: the small isotropic inertia. `arm` has a collision.
    let urdf = robot(BOX_COLLISION, "", "");
    let found = of(&urdf, Simulator::Isaac, "U761");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].1.contains("link 'tool'") && found[0].1.contains("1e-4"),
        "{found:?}"
    );
    // A declared tensor is imported: nothing.
    let urdf = robot(INERTIAL, INERTIAL, "");
    assert!(of(&urdf, Simulator::Isaac, "U761").is_empty());
}
