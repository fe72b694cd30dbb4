//! Left/right symmetry: a lopsided cart is named, its true twin is not; mirrored limits are equal; names only
//! break ties; real robots with twin sides give no finding.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::path::Path;

use urdf_validator::analysis::symmetry::SymmetrySection;
use urdf_validator::report::{Report, Status};
use urdf_validator::{validate, validate_text, Options};

/// A box with two wheels on continuous joints at y = ±0.2; the left weighs 1 kg with effort 5, the right
/// `right_mass` with `right_effort`.
fn cart(right_mass: f64, right_effort: f64) -> String {
    let wheel = |side: &str, y: f64, mass: f64, effort: f64| {
        format!(
            r#"<joint name="{side}_wheel_joint" type="continuous"><parent link="base_link"/><child link="{side}_wheel"/>
    <origin xyz="0 {y} 0.1" rpy="-1.5707963267948966 0 0"/><axis xyz="0 0 1"/><limit effort="{effort}" velocity="10"/></joint>
  <link name="{side}_wheel">
    <inertial><mass value="{mass}"/><inertia ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.004"/></inertial>
    <collision><geometry><cylinder radius="0.1" length="0.04"/></geometry></collision>
  </link>"#
        )
    };
    format!(
        r#"<robot name="cart">
  <link name="base_link">
    <inertial><origin xyz="0 0 0.15"/><mass value="5"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision><origin xyz="0 0 0.15"/><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  {}
  {}
</robot>"#,
        wheel("left", 0.2, 1.0, 5.0),
        wheel("right", -0.2, right_mass, right_effort)
    )
}

fn report(urdf: String) -> Report {
    validate_text(urdf, Path::new("cart.urdf"), &Options::default())
        .expect("loads")
        .report
}

fn symmetry(report: &Report) -> &SymmetrySection {
    report.symmetry.as_ref().expect("a symmetry section")
}

fn mirrored_findings(report: &Report) -> Vec<&str> {
    report
        .findings
        .iter()
        .filter(|f| f.rule == "U770")
        .map(|f| f.message.as_str())
        .collect()
}

#[test]
fn a_true_twin_cart_gives_a_passing_pair_and_no_finding() {
    let report = report(cart(1.0, 5.0));
    let section = symmetry(&report);
    assert_eq!(section.status, Status::Pass);
    assert_eq!(section.pairs.len(), 1);
    assert_eq!(
        section.pairs[0].joints,
        ["left_wheel_joint", "right_wheel_joint"]
    );
    assert_eq!(section.pairs[0].links_compared, 1);
    assert_eq!(section.pairs[0].joints_compared, 1);
    assert!(mirrored_findings(&report).is_empty());
}

#[test]
fn a_lopsided_cart_is_named_with_the_difference() {
    let report = report(cart(1.5, 5.0));
    assert_eq!(symmetry(&report).status, Status::Warn);
    let findings = mirrored_findings(&report);
    assert_eq!(findings.len(), 1, "{findings:?}");
    assert_eq!(
        findings[0],
        "Mirrored links 'left_wheel' / 'right_wheel': mass 1 kg vs 1.5 kg (33 % apart)"
    );
    let finding = report.findings.iter().find(|f| f.rule == "U770").unwrap();
    assert_eq!(finding.line, Some(15), "at the right wheel's <inertial>");
    assert_eq!(report.overall_status, Status::Warn);
}

#[test]
fn within_the_tolerance_is_a_twin_and_an_effort_beyond_it_is_not() {
    assert!(mirrored_findings(&report(cart(1.09, 5.4))).is_empty());
    let strong_right = report(cart(1.0, 50.0));
    assert_eq!(
        mirrored_findings(&strong_right),
        ["Mirrored joints 'left_wheel_joint' / 'right_wheel_joint': effort 5 vs 50 (90 % apart)"]
    );
}

/// Two one-joint arms at y = ±0.3 with the given limits and names.
fn arms(names: [&str; 2], left: (f64, f64), right: (f64, f64)) -> String {
    let arm = |name: &str, y: f64, (lower, upper): (f64, f64)| {
        format!(
            r#"<joint name="{name}" type="revolute"><parent link="torso"/><child link="{name}_link"/><origin xyz="0.1 {y} 0.5"/>
    <axis xyz="0 1 0"/><limit lower="{lower}" upper="{upper}" effort="20" velocity="2"/></joint>
  <link name="{name}_link"><inertial><origin xyz="0.2 0 0"/><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial></link>"#
        )
    };
    format!(
        r#"<robot name="arms"><link name="torso"/>{}{}</robot>"#,
        arm(names[0], 0.3, left),
        arm(names[1], -0.3, right)
    )
}

#[test]
fn mirrored_limits_are_equal_and_other_limits_are_named() {
    let names = ["l_shoulder", "r_shoulder"];
    let mirrored = report(arms(names, (-0.5, 2.0), (-2.0, 0.5)));
    assert_eq!(symmetry(&mirrored).status, Status::Pass);
    let skewed = report(arms(names, (-0.5, 2.0), (-1.0, 0.5)));
    assert_eq!(
        mirrored_findings(&skewed),
        ["Mirrored joints 'l_shoulder' / 'r_shoulder': limits [-0.5, 2] vs [-1, 0.5]"]
    );
}

#[test]
fn names_break_ties_but_never_make_or_unmake_a_structural_pair_on_their_own() {
    // Unmarked names: structure alone pairs them.
    let unmarked = report(arms(["joint_a", "joint_b"], (-1.0, 1.0), (-1.0, 1.0)));
    assert_eq!(symmetry(&unmarked).pairs.len(), 1);
    // Both on the same side by name: two parts of one gripper placed mirror-wise are not a left/right pair.
    let same_side = report(arms(
        ["gripper_left_joint", "gripper_left_motor_joint"],
        (-1.0, 1.0),
        (-1.0, 1.0),
    ));
    assert_eq!(symmetry(&same_side).status, Status::NotApplicable);
    // Names that mirror, origins that do not: no pair.
    let apart = arms(["left_arm", "right_arm"], (-1.0, 1.0), (-1.0, 1.0))
        .replace(r#"xyz="0.1 -0.3 0.5""#, r#"xyz="0.3 -0.3 0.5""#);
    assert_eq!(symmetry(&report(apart)).status, Status::NotApplicable);
}

#[test]
fn reference_robots_with_twin_sides_have_no_mirrored_pair_finding() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    for (file, pairs) in [
        ("pr2/pr2_description/robots/pr2.urdf", 10),
        ("fetch/fetch_description/robots/fetch.urdf", 2),
        (
            "turtlebot3/turtlebot3_description/urdf/turtlebot3_burger.urdf",
            1,
        ),
        ("anymal/anymal_b_simple_description/urdf/anymal.urdf", 2),
    ] {
        let options = Options {
            workspace: urdf_validator::analysis::workspace::WorkspaceOptions {
                samples: 200,
                ..Default::default()
            },
            ..Options::default()
        };
        let report = validate(&robots.join(file), &options).expect(file).report;
        let section = symmetry(&report);
        assert_eq!(section.pairs.len(), pairs, "{file}: {:#?}", section.pairs);
        assert_eq!(section.status, Status::Pass, "{file}");
        assert!(mirrored_findings(&report).is_empty(), "{file}");
    }
}
