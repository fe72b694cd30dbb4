//! Workspace: reach, task heights, orientation and self-collision on robots whose answers are known on
//! paper; arm detection and maximum reach on real robots against an optimiser (scripts/oracle/max_reach.py).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::path::Path;

use urdf_validator::analysis::classify::RobotType;
use urdf_validator::analysis::pose::{PoseKind, PoseOptions};
use urdf_validator::analysis::statics::StaticsOptions;
use urdf_validator::analysis::workspace::target::{Orientation, Task};
use urdf_validator::analysis::workspace::WorkspaceOptions;
use urdf_validator::analysis::Overrides;
use urdf_validator::diagnostics::Section;
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::report::{Confidence, Report, Status, WorkspaceSection};
use urdf_validator::{validate, validate_text, Options};

fn inertial(mass: f64, xyz: [f64; 3]) -> String {
    format!(
        r#"<inertial><origin xyz="{} {} {}"/><mass value="{mass}"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>"#,
        xyz[0], xyz[1], xyz[2]
    )
}

/// A planar two-link arm (links `l1`, `l2`, both joints continuous about y) on a 0.2 m box base standing on
/// the ground, shoulder at height `h`; the tip frame `tip` is at the end of link 2. The base weighs
/// `base_mass`, the tip carries `tip_mass`.
fn planar_arm(l1: f64, l2: f64, h: f64, base_mass: f64, tip_mass: f64) -> String {
    format!(
        r#"<robot name="planar">
  <link name="base">{base}<collision><origin xyz="0 0 0.1"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="upper"/><origin xyz="0 0 {h}"/><axis xyz="0 1 0"/><limit effort="1000" velocity="1"/></joint>
  <link name="upper">{upper}</link>
  <joint name="elbow" type="continuous"><parent link="upper"/><child link="lower"/><origin xyz="0 0 {l1}"/><axis xyz="0 1 0"/><limit effort="1000" velocity="1"/></joint>
  <link name="lower">{lower}</link>
  <joint name="tip_joint" type="fixed"><parent link="lower"/><child link="tip"/><origin xyz="0 0 {l2}"/></joint>
  <link name="tip">{tip}</link>
</robot>"#,
        base = inertial(base_mass, [0.0, 0.0, 0.1]),
        upper = inertial(0.001, [0.0, 0.0, l1 / 2.0]),
        lower = inertial(0.001, [0.0, 0.0, l2 / 2.0]),
        tip = inertial(tip_mass, [0.0; 3]),
    )
}

fn declared_arm(root: &str, tip: &str) -> Overrides {
    Overrides {
        arms: vec![(root.to_string(), tip.to_string())],
        ..Overrides::default()
    }
}

/// The arm declared, standing on its base box (a mobile base that can tip, not a bolted-down arm).
fn standing_arm(root: &str, tip: &str) -> Overrides {
    Overrides {
        robot_type: Some(RobotType::Unknown),
        contact_links: Some(vec![root.to_string()]),
        ..declared_arm(root, tip)
    }
}

fn report_of(urdf: &str, overrides: Overrides, workspace: WorkspaceOptions) -> Report {
    let options = Options {
        overrides,
        workspace,
        ..Options::default()
    };
    validate_text(urdf.to_string(), Path::new("t.urdf"), &options)
        .expect("loads")
        .report
}

fn workspace_of(urdf: &str, overrides: Overrides, workspace: WorkspaceOptions) -> WorkspaceSection {
    report_of(urdf, overrides, workspace)
        .workspace
        .expect("a robot has a workspace section")
}

/// The (code, line) of every task and self-collision finding (the workspace section's but the contacts at
/// the reference pose and a declared arm that differs).
fn verdicts(report: &Report) -> Vec<(String, Option<u32>)> {
    report
        .findings
        .iter()
        .filter(|f| f.section == Section::Workspace && !["U601", "U730"].contains(&f.rule.as_str()))
        .map(|f| (f.rule.clone(), f.line))
        .collect()
}

#[test]
fn planar_arm_reach_is_the_sum_of_its_links() {
    let (l1, l2, h) = (0.5, 0.3, 1.0);
    let ws = workspace_of(
        &planar_arm(l1, l2, h, 10.0, 0.1),
        declared_arm("base", "tip"),
        WorkspaceOptions::default(),
    );
    assert_eq!(ws.arms.len(), 1);
    let arm = &ws.arms[0];
    assert_eq!(arm.confidence, Confidence::Exact);
    assert_eq!(arm.joints, ["shoulder", "elbow"]);
    // Reach from the shoulder is √(l1² + l2² + 2·l1·l2·cos q2): its maximum l1 + l2 is approached from
    // below. With 30,000 uniform samples of q2 over a full turn, P(min |q2| > 0.002) = (1 − 0.002/π)^30000
    // < 1e-8, and |q2| ≤ 0.002 costs at most l1·l2·q2²/(2(l1 + l2)) < 4e-7 m.
    let reach = l1 + l2;
    let max_reach = ws.max_reach.unwrap();
    assert!(
        max_reach <= reach + 1e-12 && max_reach >= reach - 4e-7,
        "{max_reach}"
    );
    // Horizontal, vertical and from-base maxima also need the arm's direction φ right: the deficit is
    // about 0.094·q2² + 0.4·δφ², below ε with probability ε/(4π·√(0.094·0.4)) ≈ 0.41·ε per sample, so
    // P(deficit > 2e-3) = (1 − 8.2e-4)^30000 < 1e-10.
    for (what, value, exact) in [
        ("horizontal", ws.horizontal_reach.unwrap(), reach),
        // The ground is the bottom of the base box (z = 0), the shoulder at h.
        ("vertical", ws.vertical_reach.unwrap(), h + reach),
        ("from base", ws.reach_from_base.unwrap(), h + reach),
    ] {
        assert!(
            value <= exact + 1e-12 && value >= exact - 2e-3,
            "{what}: {value} vs {exact}"
        );
    }
    // Lowest tip: h − (l1 + l2) = 0.2 m above the ground.
    assert!((arm.lowest_tip_height - (h - reach)).abs() < 1e-3);
    assert_eq!(ws.reach_confidence, Confidence::Estimated);
    assert_eq!(ws.status, Status::Pass);
}

#[test]
fn task_heights_are_reachable_between_the_lowest_and_highest_tip() {
    let urdf = planar_arm(0.5, 0.3, 1.0, 10.0, 0.1);
    let run = |task: Task| {
        workspace_of(
            &urdf,
            declared_arm("base", "tip"),
            WorkspaceOptions {
                task: Some(task),
                ..WorkspaceOptions::default()
            },
        )
    };
    // Tip heights span [0.2, 1.8] m above the ground.
    let table = run(Task::PickFromTable);
    assert_eq!(table.task_height_reachable, Some(true));
    let report = |task: Task| {
        report_of(
            &urdf,
            declared_arm("base", "tip"),
            WorkspaceOptions {
                task: Some(task),
                ..WorkspaceOptions::default()
            },
        )
    };
    assert_eq!(verdicts(&report(Task::PickFromTable)), []);
    // U720 at the arm's first joint (line 3 of planar_arm).
    assert_eq!(
        verdicts(&report(Task::PickFromGround)),
        [("U720".to_string(), Some(3))]
    );
    assert_eq!(table.task_target_height_m, Some(0.75));
    // A bolted-down arm cannot tip: the COM check says why it did not run.
    assert_eq!(table.task_com_stable_during_reach, None);
    assert!(table
        .task_com_not_assessed
        .as_deref()
        .is_some_and(|why| why.contains("no support polygon")));
    let floor = run(Task::PickFromGround);
    assert_eq!(floor.task_height_reachable, Some(false));
    assert_eq!(floor.status, Status::Fail);
    assert!(floor.reason.unwrap().contains("pick_from_ground"));
    let high = run(Task::Custom(1.9));
    assert_eq!(high.task_height_reachable, Some(false));
    assert!(!high.reason.as_deref().unwrap().contains("sampling error"));
    // 1.81 m is 10 mm above the true envelope: the reason says how close the samples came.
    let barely = run(Task::Custom(1.81));
    assert_eq!(barely.task_height_reachable, Some(false));
    assert!(
        barely
            .reason
            .as_deref()
            .unwrap()
            .contains("within sampling error"),
        "{:?}",
        barely.reason
    );
    // No sample at that height: the orientation is not assessed (not "met by 0%").
    let high_side = workspace_of(
        &urdf,
        declared_arm("base", "tip"),
        WorkspaceOptions {
            task: Some(Task::Custom(1.9)),
            orientation: Some(Orientation::Side),
            ..WorkspaceOptions::default()
        },
    );
    assert_eq!(high_side.orientation_fraction, None);
    assert_eq!(high_side.orientation_reachable, None);
    assert!(!high_side.reason.unwrap().contains("orientation"));
    let just = run(Task::Custom(1.79));
    assert_eq!(just.task_height_reachable, Some(true));
}

/// A torso lift is body, not arm: it stays at the `--pose` value, and an unreachable task says so.
#[test]
fn body_joints_under_the_arm_are_held_and_named() {
    let lifted = planar_arm(0.5, 0.3, 1.0, 10.0, 0.1)
        .replace(
            r#"<joint name="shoulder" type="continuous"><parent link="base"/>"#,
            r#"<joint name="lift" type="prismatic"><parent link="base"/><child link="torso"/><axis xyz="0 0 1"/><limit lower="0" upper="0.5" effort="1000" velocity="1"/></joint>
  <link name="torso">{TORSO}</link>
  <joint name="shoulder" type="continuous"><parent link="torso"/>"#,
        )
        .replace("{TORSO}", &inertial(1.0, [0.0; 3]));
    let run = |pose: PoseOptions| {
        let options = Options {
            overrides: declared_arm("torso", "tip"),
            workspace: WorkspaceOptions {
                task: Some(Task::Custom(2.0)),
                ..WorkspaceOptions::default()
            },
            statics: StaticsOptions {
                pose,
                ..StaticsOptions::default()
            },
            ..Options::default()
        };
        validate_text(lifted.clone(), Path::new("t.urdf"), &options)
            .unwrap()
            .report
            .workspace
            .unwrap()
    };
    // Tip heights reach 1.8 m with the lift down: 2.0 m is out of reach, and the reason names the lift.
    let down = run(PoseOptions::default());
    assert_eq!(down.arms[0].body_joints_held, ["lift=0.000"]);
    assert_eq!(down.task_height_reachable, Some(false));
    assert!(down
        .reason
        .unwrap()
        .contains("with the body held at lift=0.000"));
    let up = run(PoseOptions {
        kind: PoseKind::Custom,
        joint_angles: Some("lift=0.5".to_string()),
        ..PoseOptions::default()
    });
    assert_eq!(up.arms[0].body_joints_held, ["lift=0.500"]);
    assert_eq!(up.task_height_reachable, Some(true));
}

#[test]
fn reaching_with_a_heavy_tool_tips_a_light_base_over() {
    let task = WorkspaceOptions {
        task: Some(Task::Custom(1.0)),
        ..WorkspaceOptions::default()
    };
    // At 1.0 m (the shoulder's height) the furthest horizontal reach is the arm stretched out, 0.8 m from
    // a 0.2 m base: a 10 kg tool on a 1 kg base takes the COM ~0.7 m out, far beyond the base's 0.1 m edge.
    let light = workspace_of(
        &planar_arm(0.5, 0.3, 1.0, 1.0, 10.0),
        standing_arm("base", "tip"),
        task.clone(),
    );
    assert_eq!(light.task_height_reachable, Some(true));
    assert_eq!(light.task_com_stable_during_reach, Some(false));
    let margin = light.task_com_margin_mm.unwrap();
    // COM x = (10·0.8 + small) / 11.002 ≈ 0.727 m; margin = 0.1 − 0.727 → about −627 mm.
    assert!((-640.0..-600.0).contains(&margin), "margin {margin}");
    assert_eq!(light.status, Status::Fail);
    let light_report = report_of(
        &planar_arm(0.5, 0.3, 1.0, 1.0, 10.0),
        standing_arm("base", "tip"),
        task.clone(),
    );
    assert_eq!(verdicts(&light_report), [("U721".to_string(), Some(3))]);
    // A 1000 kg base keeps it: COM x ≈ 10·0.8/1010 ≈ 7.9 mm, margin ≈ 92 mm.
    let heavy = workspace_of(
        &planar_arm(0.5, 0.3, 1.0, 1000.0, 10.0),
        standing_arm("base", "tip"),
        task.clone(),
    );
    assert_eq!(heavy.task_com_stable_during_reach, Some(true));
    let margin = heavy.task_com_margin_mm.unwrap();
    assert!((88.0..96.0).contains(&margin), "margin {margin}");
    let heavy_report = report_of(
        &planar_arm(0.5, 0.3, 1.0, 1000.0, 10.0),
        standing_arm("base", "tip"),
        task,
    );
    assert_eq!(verdicts(&heavy_report), []);
    let shift = heavy.task_com_shift_estimate_m.unwrap();
    assert!((0.0075..0.0085).contains(&shift), "shift {shift}");
    // Every pose at that height is checked too: the worst is the arm stretched either way, as far out.
    let worst = heavy.task_com_worst_margin_mm.unwrap();
    assert!(
        worst <= margin && (88.0..96.0).contains(&worst),
        "worst {worst}"
    );
}

/// The margin at the single furthest pose depends on which heading the seed happened to sample; the worst
/// over every pose at the task height does not.
#[test]
fn the_worst_com_margin_at_the_task_height_is_stable_across_seeds() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/robots/mobile_manipulator.urdf");
    let run = |seed: u64| {
        let options = Options {
            workspace: WorkspaceOptions {
                task: Some(Task::PickFromTable),
                seed,
                ..WorkspaceOptions::default()
            },
            ..Options::default()
        };
        validate(&path, &options).unwrap().report.workspace.unwrap()
    };
    let runs: Vec<WorkspaceSection> = (1..=3).map(run).collect();
    let worst: Vec<f64> = runs
        .iter()
        .map(|w| w.task_com_worst_margin_mm.unwrap())
        .collect();
    let at_furthest: Vec<f64> = runs.iter().map(|w| w.task_com_margin_mm.unwrap()).collect();
    for (w, f) in worst.iter().zip(&at_furthest) {
        assert!(w <= f, "worst {w} above the furthest pose's {f}");
    }
    let spread = |v: &[f64]| {
        v.iter().copied().fold(f64::MIN, f64::max) - v.iter().copied().fold(f64::MAX, f64::min)
    };
    assert!(spread(&worst) < 1.0, "worst margins {worst:?}");
    assert!(runs.iter().all(|w| w.status == Status::Pass));
}

/// `--payload-mass` hangs at the reaching arm's tip: a 10 kg payload tips the light base as a 10 kg tool does.
#[test]
fn a_payload_at_the_tip_counts_in_the_com_during_reach() {
    let urdf = planar_arm(0.5, 0.3, 1.0, 1.0, 0.001);
    let with_payload = |payload_mass: Option<f64>| {
        let options = Options {
            overrides: standing_arm("base", "tip"),
            workspace: WorkspaceOptions {
                task: Some(Task::Custom(1.0)),
                ..WorkspaceOptions::default()
            },
            statics: StaticsOptions {
                payload_mass,
                ..StaticsOptions::default()
            },
            ..Options::default()
        };
        validate_text(urdf.clone(), Path::new("t.urdf"), &options)
            .expect("loads")
            .report
            .workspace
            .expect("a workspace section")
    };
    let empty = with_payload(None);
    assert_eq!(empty.task_com_stable_during_reach, Some(true));
    let loaded = with_payload(Some(10.0));
    assert_eq!(loaded.task_com_stable_during_reach, Some(false));
    let margin = loaded.task_com_margin_mm.unwrap();
    // COM x ≈ 10·0.8 / 11.003 ≈ 0.727 m; margin = 0.1 − 0.727 → about −627 mm.
    assert!((-640.0..-600.0).contains(&margin), "margin {margin}");
    assert_eq!(loaded.status, Status::Fail);
}

#[test]
fn orientation_fraction_matches_the_swept_angle() {
    // Both joints turn about y, so the tool's z axis points at angle q1 + q2 in the x-z plane, uniform
    // over the circle: top-down within 30° holds for 60/360 of samples; a sideways approach (horizontal
    // within 30°) for 2·60/360.
    let urdf = planar_arm(0.5, 0.3, 1.0, 10.0, 0.1);
    let run = |orientation: &str| {
        workspace_of(
            &urdf,
            declared_arm("base", "tip"),
            WorkspaceOptions {
                orientation: Some(Orientation::parse(orientation).unwrap()),
                ..WorkspaceOptions::default()
            },
        )
    };
    // Binomial standard deviation with 30,000 samples: √(p(1−p)/n) < 0.003; allow 4σ.
    let down = run("top_down");
    assert!((down.orientation_fraction.unwrap() - 1.0 / 6.0).abs() < 0.012);
    assert_eq!(down.orientation_reachable, Some(true));
    assert_eq!(down.orientation_tolerance_deg, 30.0);
    let side = run("side");
    assert!((side.orientation_fraction.unwrap() - 1.0 / 3.0).abs() < 0.012);
    // A quaternion target equal to identity: z up.
    let up = run("1,0,0,0");
    assert!((up.orientation_fraction.unwrap() - 1.0 / 6.0).abs() < 0.012);
    // Within 1°: 2/360 of samples, below 5% → WARN.
    let tight = workspace_of(
        &urdf,
        declared_arm("base", "tip"),
        WorkspaceOptions {
            orientation: Some(Orientation::TopDown),
            orientation_tolerance_deg: 1.0,
            ..WorkspaceOptions::default()
        },
    );
    assert_eq!(tight.orientation_reachable, Some(false));
    assert_eq!(tight.status, Status::Warn);
    let orientation_report = |tolerance: f64| {
        report_of(
            &urdf,
            declared_arm("base", "tip"),
            WorkspaceOptions {
                orientation: Some(Orientation::TopDown),
                orientation_tolerance_deg: tolerance,
                ..WorkspaceOptions::default()
            },
        )
    };
    assert_eq!(
        verdicts(&orientation_report(1.0)),
        [("U723".to_string(), Some(3))]
    );
    assert_eq!(verdicts(&orientation_report(30.0)), []);
}

/// A ball on a rod turning about y over a box base; the ball hits the base when the rod points down far
/// enough. The mount (a small sphere at the pivot) keeps the base and the ball from being adjacent.
fn swinging_ball(height: f64, length: f64, radius: f64) -> String {
    format!(
        r#"<robot name="swing">
  <link name="base">{m}<collision><origin xyz="0 0 -0.05"/><geometry><box size="2 2 0.1"/></geometry></collision></link>
  <joint name="mount_joint" type="fixed"><parent link="base"/><child link="mount"/><origin xyz="0 0 {height}"/></joint>
  <link name="mount">{m}<collision><geometry><sphere radius="0.02"/></geometry></collision></link>
  <joint name="swing" type="continuous"><parent link="mount"/><child link="rod"/><axis xyz="0 1 0"/><limit effort="100" velocity="1"/></joint>
  <link name="rod">{m}<collision><origin xyz="0 0 {length}"/><geometry><sphere radius="{radius}"/></geometry></collision></link>
</robot>"#,
        m = inertial(1.0, [0.0; 3])
    )
}

/// [`swinging_ball`] with a second ball, 0.5 m to the side on its own mount, that follows the swing joint
/// `offset` radians ahead (a mimic joint outside the arm).
fn swinging_twins(height: f64, length: f64, radius: f64, offset: f64) -> String {
    swinging_ball(height, length, radius).replace(
        "</robot>",
        &format!(
            r#"<joint name="twin_mount_joint" type="fixed"><parent link="base"/><child link="twin_mount"/><origin xyz="0 0.5 {height}"/></joint>
  <link name="twin_mount">{m}<collision><geometry><sphere radius="0.02"/></geometry></collision></link>
  <joint name="twin_swing" type="continuous"><parent link="twin_mount"/><child link="twin"/><axis xyz="0 1 0"/><limit effort="100" velocity="1"/><mimic joint="swing" multiplier="1" offset="{offset}"/></joint>
  <link name="twin">{m}<collision><origin xyz="0 0 {length}"/><geometry><sphere radius="{radius}"/></geometry></collision></link>
</robot>"#,
            m = inertial(1.0, [0.0; 3])
        ),
    )
}

#[test]
fn self_collision_fraction_matches_the_colliding_arc() {
    // Ball centre height h + L·cos q hits the base top (z = 0) when h + L·cos q < r, i.e. cos q < (r − h)/L:
    // an arc of 2·acos((h − r)/L) out of 2π.
    let (h, l, r): (f64, f64, f64) = (0.5, 0.6, 0.05);
    let colliding = 2.0 * ((h - r) / l).acos() / std::f64::consts::TAU;
    let ws = workspace_of(
        &swinging_ball(h, l, r),
        declared_arm("mount", "rod"),
        WorkspaceOptions::default(),
    );
    let free = ws.self_collision_free_fraction.unwrap();
    // σ = √(p(1−p)/30000) ≈ 0.0024; allow 4σ.
    assert!(
        (free - (1.0 - colliding)).abs() < 0.01,
        "free {free} vs {}",
        1.0 - colliding
    );
    assert_eq!(
        ws.self_collision_worst_pair.as_ref().unwrap(),
        &["base", "rod"]
    );
    assert_eq!(ws.status, Status::Warn, "{:?}", ws.reason);
    // U724 at the rod's collision (line 6 of swinging_ball).
    let report = report_of(
        &swinging_ball(h, l, r),
        declared_arm("mount", "rod"),
        WorkspaceOptions::default(),
    );
    assert_eq!(verdicts(&report), [("U724".to_string(), Some(6))]);
    assert!(report
        .findings
        .iter()
        .any(|f| f.rule == "U724" && f.message.contains("'base' × 'rod'")));
    assert_eq!(report.overall_status, Status::Warn);
    assert!(ws.self_collision_touching_at_reference.is_empty());
    // Clearance over free poses approaches 0 (the ball grazes the base).
    assert!(ws.self_collision_min_clearance_mm.unwrap() < 5.0);
}

#[test]
fn a_mimic_follower_outside_the_arm_moves_with_it() {
    // A second ball, 0.5 m to the side on its own mount, follows the swing joint a quarter turn ahead
    // (horizontal, so free, at the reference pose). It hits the base on its own arc, as wide as the first
    // (±0.72 rad) and centred π/2 from it, so the arcs do not overlap: twice the colliding fraction.
    let (h, l, r): (f64, f64, f64) = (0.5, 0.6, 0.05);
    let urdf = swinging_twins(h, l, r, std::f64::consts::FRAC_PI_2);
    let colliding = 2.0 * 2.0 * ((h - r) / l).acos() / std::f64::consts::TAU;
    let ws = workspace_of(
        &urdf,
        declared_arm("mount", "rod"),
        WorkspaceOptions::default(),
    );
    let free = ws.self_collision_free_fraction.unwrap();
    assert!(
        (free - (1.0 - colliding)).abs() < 0.012,
        "free {free} vs {}",
        1.0 - colliding
    );
}

#[test]
fn a_pair_touching_at_the_reference_pose_is_reported_and_not_sampled() {
    // The ball rests on the base at the zero pose (rod pointing down).
    let urdf = swinging_ball(0.5, -0.5, 0.05);
    let options = Options {
        overrides: declared_arm("mount", "rod"),
        ..Options::default()
    };
    let report = validate_text(urdf, Path::new("t.urdf"), &options)
        .unwrap()
        .report;
    let ws = report.workspace.unwrap();
    assert_eq!(ws.self_collision_touching_at_reference, [["base", "rod"]]);
    // Nothing else can collide: no pair is sampled, and the report says why.
    assert_eq!(ws.self_collision_free_fraction, None);
    assert!(
        ws.self_collision_not_assessed
            .as_deref()
            .is_some_and(|why| why.starts_with("no pair the arms move can collide")),
        "{:?}",
        ws.self_collision_not_assessed
    );
    assert!(report
        .findings
        .iter()
        .any(|f| f.rule == "U601" && f.message.contains("'base' and 'rod'")));
}

/// Task heights count feasible poses only: a height the tip reaches only by passing through the base
/// plate is out of reach.
#[test]
fn task_heights_count_only_poses_free_of_self_collision() {
    let (h, l, r): (f64, f64, f64) = (0.5, 0.6, 0.05);
    // A tip frame at the ball's centre.
    let urdf = swinging_ball(h, l, r).replace(
        "</robot>",
        &format!(
            r#"<joint name="ball_joint" type="fixed"><parent link="rod"/><child link="ball"/><origin xyz="0 0 {l}"/></joint>
  <link name="ball"/>
</robot>"#
        ),
    );
    let at = |height: f64| {
        workspace_of(
            &urdf,
            declared_arm("mount", "ball"),
            WorkspaceOptions {
                task: Some(Task::Custom(height)),
                ..WorkspaceOptions::default()
            },
        )
    };
    // The ground is the plate's underside (z = −0.1); the ball's centre sweeps z ∈ [−0.1, 1.1], but it
    // hits the plate (top z = 0) below z = r: feasible heights above the ground start at 0.1 + r.
    let through_the_plate = at(0.1);
    assert!(through_the_plate.arms[0].lowest_tip_height < 0.01);
    assert_eq!(through_the_plate.task_height_reachable, Some(false));
    assert_eq!(at(0.2).task_height_reachable, Some(true));
}

/// Self-collision that cannot run says so (it is not silently dropped from a PASS).
#[test]
fn missing_collision_meshes_are_named_when_self_collision_cannot_run() {
    let urdf = swinging_ball(0.5, 0.6, 0.05).replace(
        r#"<sphere radius="0.05"/>"#,
        r#"<mesh filename="package://nowhere/meshes/ball.stl"/>"#,
    );
    let ws = workspace_of(
        &urdf,
        declared_arm("mount", "rod"),
        WorkspaceOptions::default(),
    );
    assert_eq!(ws.self_collision_free_fraction, None);
    assert_eq!(
        ws.self_collision_not_assessed.as_deref(),
        Some("1 of the 1 links the arms move have <collision> geometry that could not be used (meshes not found or unreadable, or shapes of a millimetre or less): rod")
    );
    assert!(ws.self_collision_touching_at_reference.is_empty());
    let fine = workspace_of(
        &swinging_ball(0.5, 0.6, 0.05),
        declared_arm("mount", "rod"),
        WorkspaceOptions::default(),
    );
    assert_eq!(fine.self_collision_not_assessed, None);
}

/// Contacts are excluded at the zero pose only: at the `--pose` configuration a contact is a collision.
#[test]
fn contacts_at_the_statics_pose_are_sampled_not_excluded() {
    let (h, l, r): (f64, f64, f64) = (0.5, 0.6, 0.05);
    let options = Options {
        overrides: declared_arm("mount", "rod"),
        statics: StaticsOptions {
            pose: PoseOptions {
                kind: PoseKind::Custom,
                // The ball through the base plate.
                joint_angles: Some("swing=3.14159".to_string()),
                ..PoseOptions::default()
            },
            ..StaticsOptions::default()
        },
        ..Options::default()
    };
    let report = validate_text(swinging_ball(h, l, r), Path::new("t.urdf"), &options)
        .unwrap()
        .report;
    assert!(report.findings.iter().all(|f| f.rule != "U601"));
    let ws = report.workspace.unwrap();
    assert!(ws.self_collision_touching_at_reference.is_empty());
    let colliding = 2.0 * ((h - r) / l).acos() / std::f64::consts::TAU;
    let free = ws
        .self_collision_free_fraction
        .expect("the pair is sampled");
    assert!((free - (1.0 - colliding)).abs() < 0.01, "free {free}");
}

#[test]
fn sampling_is_reproducible_and_independent_of_threads() {
    let urdf = planar_arm(0.5, 0.3, 1.0, 10.0, 0.1);
    let run = || {
        workspace_of(
            &urdf,
            declared_arm("base", "tip"),
            WorkspaceOptions {
                samples: 5000,
                task: Some(Task::PickFromTable),
                ..WorkspaceOptions::default()
            },
        )
    };
    let many = run();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(run);
    let again = run();
    let key = |w: &WorkspaceSection| {
        (
            w.max_reach,
            w.vertical_reach,
            w.horizontal_reach,
            w.task_com_margin_mm,
        )
    };
    assert_eq!(key(&many), key(&one));
    assert_eq!(key(&many), key(&again));
    // The plotted tip samples too: the same points, in the same order.
    assert_eq!(many.arms[0].tip_samples, one.arms[0].tip_samples);
    assert_eq!(many.arms[0].tip_samples, again.arms[0].tip_samples);
    let other_seed = workspace_of(
        &urdf,
        declared_arm("base", "tip"),
        WorkspaceOptions {
            samples: 5000,
            seed: 8,
            ..WorkspaceOptions::default()
        },
    );
    assert_ne!(other_seed.max_reach, many.max_reach);
}

/// Chunks share the smallest clearance found so far (a chunk computes no distance that cannot beat it),
/// whichever thread finds it first: the self-collision results (free fraction, smallest clearance, worst
/// pair, the whole section) are the same on one thread as on two or four.
#[test]
fn self_collision_results_do_not_depend_on_threads() {
    // Two balls on their own arcs, both grazing the base.
    let urdf = swinging_twins(0.5, 0.6, 0.05, 1.0);
    let run = || {
        let ws = workspace_of(
            &urdf,
            declared_arm("mount", "rod"),
            WorkspaceOptions::default(),
        );
        serde_json::to_string(&ws).unwrap()
    };
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(run)
    };
    let one = on(1);
    assert!(one.contains("self_collision_min_clearance_mm"), "{one}");
    for threads in [2, 4, 4] {
        assert_eq!(on(threads), one, "{threads} threads");
    }
}

#[test]
fn tip_samples_are_every_kth_sample_at_most_400_rounded_to_the_mm() {
    let (l1, l2, h) = (0.5, 0.3, 1.0);
    let urdf = planar_arm(l1, l2, h, 10.0, 0.1);
    for (samples, expected) in [(30_000, 400), (5000, 385), (100, 100), (1, 1)] {
        let ws = workspace_of(
            &urdf,
            declared_arm("base", "tip"),
            WorkspaceOptions {
                samples,
                ..WorkspaceOptions::default()
            },
        );
        let tips = &ws.arms[0].tip_samples;
        // k = ⌈samples / 400⌉: 75 → 400 points, 13 → ⌈5000 / 13⌉ = 385, 1 → every sample.
        assert_eq!(tips.len(), expected, "{samples} samples");
        for p in tips {
            for v in p {
                assert_eq!(
                    *v,
                    (v * 1000.0).round() / 1000.0,
                    "not rounded to the mm: {p:?}"
                );
            }
            // The tip lies within reach of the shoulder (at height h above the root).
            let reach = (p[0] * p[0] + p[1] * p[1] + (p[2] - h) * (p[2] - h)).sqrt();
            assert!(reach <= l1 + l2 + 1e-3, "{p:?} is beyond reach");
        }
    }
    // Every k-th of the full run: the first points of 5,000 samples (k = 13) are not those of 30,000
    // (k = 75), but the first point (sample 0) is.
    let first = |samples| {
        workspace_of(
            &urdf,
            declared_arm("base", "tip"),
            WorkspaceOptions {
                samples,
                ..WorkspaceOptions::default()
            },
        )
        .arms[0]
            .tip_samples[0]
    };
    assert_eq!(first(30_000), first(5000));
}

#[test]
fn joints_without_a_usable_range_are_held_and_huge_ranges_stay_finite() {
    // j1 turns ±1 rad; j2 is a prismatic joint locked (empty range), huge (±1e308 m) or a revolute
    // with ±1e308 rad: the locked and huge prismatic joints stay at the reference, the huge revolute
    // range is a full turn.
    let arm = |j2: &str| {
        format!(
            r#"<robot name="r">
  <link name="base">{m}<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 1"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <link name="l1">{m}</link>
  {j2}
  <link name="l2">{m}</link>
</robot>"#,
            m = inertial(1.0, [0.0; 3])
        )
    };
    let reach = |j2: &str| {
        workspace_of(
            &arm(j2),
            declared_arm("base", "l2"),
            WorkspaceOptions::default(),
        )
        .max_reach
        .unwrap()
    };
    for limits in [r#"lower="0" upper="0""#, r#"lower="-1e308" upper="1e308""#] {
        let j2 = format!(
            r#"<joint name="j2" type="prismatic"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.5"/><axis xyz="0 0 1"/><limit {limits} effort="10" velocity="1"/></joint>"#
        );
        assert!((reach(&j2) - 0.5).abs() < 1e-12, "{limits}: {}", reach(&j2));
    }
    let turn = r#"<joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.5"/><axis xyz="0 0 1"/><limit lower="-1e308" upper="1e308" effort="10" velocity="1"/></joint>"#;
    assert!((reach(turn) - 0.5).abs() < 1e-12);
}

#[test]
fn neighbouring_seeds_draw_different_samples() {
    let urdf = planar_arm(0.5, 0.3, 1.0, 10.0, 0.1);
    let reach = |seed: u64| {
        workspace_of(
            &urdf,
            declared_arm("base", "tip"),
            WorkspaceOptions {
                seed,
                ..WorkspaceOptions::default()
            },
        )
        .horizontal_reach
    };
    assert_ne!(reach(6), reach(7));
    assert_ne!(reach(4), reach(5));
}

/// A declared arm off every detected arm is checked against the structure, as a declared robot type is.
#[test]
fn a_declared_arm_unlike_the_detected_ones_is_warned_about() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/robots/mobile_manipulator.urdf");
    let warnings = |root: &str, tip: &str| {
        let options = Options {
            overrides: declared_arm(root, tip),
            workspace: WorkspaceOptions {
                samples: 100,
                ..WorkspaceOptions::default()
            },
            ..Options::default()
        };
        let report = validate(&path, &options).unwrap().report;
        report
            .findings
            .into_iter()
            .filter(|f| f.rule == "U730")
            .map(|f| f.message)
            .collect::<Vec<_>>()
    };
    let wheel = warnings("base_link", "left_wheel_link");
    assert!(
        wheel.iter().any(|w| w
            == "User declared the arm base_link → left_wheel_link, but the structure suggests arm_mount_link → tool0"),
        "{wheel:?}"
    );
    // Part of the detected arm (to the wrist), or all of it: nothing to say.
    for tip in ["wrist_2_link", "tool0"] {
        let fine = warnings("arm_mount_link", tip);
        assert!(
            fine.iter().all(|w| !w.contains("declared the arm")),
            "{fine:?}"
        );
    }
}

#[test]
fn a_declared_arm_must_move() {
    let urdf = planar_arm(0.5, 0.3, 1.0, 10.0, 0.1);
    let options = |root: &str, tip: &str| Options {
        overrides: declared_arm(root, tip),
        ..Options::default()
    };
    let error = |root: &str, tip: &str| {
        validate_text(urdf.clone(), Path::new("t.urdf"), &options(root, tip))
            .expect_err("refused")
            .to_string()
    };
    assert!(error("base", "base").contains("both name 'base'"));
    assert!(error("lower", "tip").contains("no actuated joint"));
}

#[test]
fn zero_samples_give_no_numbers() {
    let ws = workspace_of(
        &planar_arm(0.5, 0.3, 1.0, 10.0, 0.1),
        declared_arm("base", "tip"),
        WorkspaceOptions {
            samples: 0,
            ..WorkspaceOptions::default()
        },
    );
    assert_eq!(ws.status, Status::NotApplicable);
    assert_eq!(ws.max_reach, None);
    assert!(ws.arms.is_empty());
}

#[test]
fn a_robot_without_arms_has_no_workspace() {
    let urdf = format!(
        r#"<robot name="box"><link name="base">{}<collision><geometry><box size="1 1 1"/></geometry></collision></link></robot>"#,
        inertial(1.0, [0.0; 3])
    );
    let ws = workspace_of(&urdf, Overrides::default(), WorkspaceOptions::default());
    assert_eq!(ws.status, Status::NotApplicable);
    assert!(ws.reason.unwrap().contains("no arm chain"));
    assert_eq!(ws.max_reach, None);
    // No arm, so nothing reads an SRDF: a --srdf that does not exist is refused all the same.
    let options = Options {
        statics: StaticsOptions {
            pose: PoseOptions {
                srdf: Some("/nonexistent/box.srdf".into()),
                ..PoseOptions::default()
            },
            ..StaticsOptions::default()
        },
        ..Options::default()
    };
    let error = validate_text(urdf, Path::new("t.urdf"), &options).expect_err("usage error");
    assert!(error.to_string().contains("box.srdf"), "{error}");
}

fn real_report(path: &Path) -> Report {
    let options = Options {
        resolver: PackageResolver::default(),
        workspace: WorkspaceOptions {
            samples: 30_000,
            ..WorkspaceOptions::default()
        },
        ..Options::default()
    };
    validate(path, &options)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .report
}

/// The maximum reach found by the optimiser (tests/golden/reach), for the link our detection picks as tip.
#[test]
fn monte_carlo_reach_is_within_half_a_percent_of_the_optimum_and_never_above() {
    let Some(corpus) = common::corpus() else {
        return;
    };
    let golden_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/reach");
    for robot in ["ur5", "panda", "z1", "kinova"] {
        let text = std::fs::read_to_string(golden_dir.join(format!("{robot}.json"))).unwrap();
        let golden: serde_json::Value = serde_json::from_str(&text).unwrap();
        let urdf = corpus.join(golden["urdf"].as_str().unwrap());
        let report = real_report(&urdf);
        let ws = report.workspace.unwrap();
        assert_eq!(ws.arms.len(), 1, "{robot}: {:?}", ws.arms);
        let arm = &ws.arms[0];
        assert_eq!(
            arm.first_joint.as_deref(),
            golden["root_joint"].as_str(),
            "{robot}: reach is measured from a different joint"
        );
        let optimum = golden["links"][&arm.tip_link]["max_reach_m"]
            .as_f64()
            .unwrap_or_else(|| panic!("{robot}: no golden for tip {}", arm.tip_link));
        let ratio = arm.max_reach / optimum;
        eprintln!(
            "{robot}: tip {} Monte Carlo {:.6} m, optimum {optimum:.6} m ({:.3}%)",
            arm.tip_link,
            arm.max_reach,
            (1.0 - ratio) * 100.0
        );
        assert!(
            arm.max_reach <= optimum + 1e-9,
            "{robot}: above the optimum"
        );
        assert!(ratio >= 0.995, "{robot}: {ratio}");
    }
}

#[test]
fn arms_are_found_on_multi_arm_and_legged_robots() {
    let Some(corpus) = common::corpus() else {
        return;
    };
    let cases: [(&str, &[&str]); 6] = [
        (
            "baxter_description/urdf/baxter.urdf",
            &["right_s0", "left_s0"],
        ),
        (
            "tiago_description/robots/tiago_dual.urdf",
            &["arm_left_1_joint", "arm_right_1_joint"],
        ),
        (
            "talos_data/robots/talos_full_v2.urdf",
            &["arm_left_1_joint", "arm_right_1_joint"],
        ),
        (
            "anymal_b_simple_description/robots/anymal-kinova.urdf",
            &["j2s6s200_joint_1"],
        ),
        ("b1_description/urdf/b1-z1.urdf", &["joint1"]),
        ("panda_description/urdf/panda.urdf", &["panda_joint1"]),
    ];
    for (file, first_joints) in cases {
        let ws = real_report(&corpus.join(file)).workspace.unwrap();
        let mut found: Vec<&str> = ws
            .arms
            .iter()
            .filter_map(|a| a.first_joint.as_deref())
            .collect();
        found.sort_unstable();
        let mut expected = first_joints.to_vec();
        expected.sort_unstable();
        assert_eq!(found, expected, "{file}");
        assert!(ws.arms.iter().all(|a| a.max_reach > 0.3), "{file}");
    }
}

/// Where arms end: a wrist joint named `*GripperYaw` that carries a whole hand is the arm's 7th joint, not
/// a finger; a force-torque sensor's `ft_tool_link` above the hand is not the tool; a welded `hand` link
/// beats the wrist; a one-jaw gripper (z1's `jointGripper`) stays out of the arm.
#[test]
fn arms_end_at_the_hand_not_above_it_nor_in_its_jaws() {
    let Some(corpus) = common::corpus() else {
        return;
    };
    let cases: [(&str, &str, usize); 5] = [
        (
            "alex_description/urdf/alex_psyonic_hands.urdf",
            "Left_thumb_base",
            7,
        ),
        (
            "alex_description/urdf/alex_sake_hands.urdf",
            "LeftSakePalmLink",
            7,
        ),
        (
            "talos_data/robots/talos_full_v2.urdf",
            "gripper_left_base_link",
            7,
        ),
        (
            "g1_description/urdf/g1_29dof_rev_1_0.urdf",
            "left_rubber_hand",
            7,
        ),
        ("z1_description/urdf/z1.urdf", "gripperStator", 6),
    ];
    for (file, tip, dof) in cases {
        let ws = real_report(&corpus.join(file)).workspace.unwrap();
        let arm = ws
            .arms
            .iter()
            .find(|a| a.tip_link == tip)
            .unwrap_or_else(|| {
                panic!(
                    "{file}: no arm ends at {tip}: {:?}",
                    ws.arms.iter().map(|a| &a.tip_link).collect::<Vec<_>>()
                )
            });
        assert_eq!(arm.joints.len(), dof, "{file}");
    }
}

#[test]
fn pr2_reports_both_arms_to_their_tool_frames() {
    let Some(shared) = common::shared_robots() else {
        return;
    };
    let report = real_report(&shared.join("pr2/pr2_description/robots/pr2.urdf"));
    let ws = report.workspace.unwrap();
    let tips: Vec<&str> = ws.arms.iter().map(|a| a.tip_link.as_str()).collect();
    assert_eq!(tips, ["r_gripper_tool_frame", "l_gripper_tool_frame"]);
    for arm in &ws.arms {
        assert_eq!(arm.joints.len(), 7);
        assert_eq!(arm.approach_axis_source, "fingers");
        // The PR2 gripper approaches along its tool frame's x axis.
        assert!(arm.approach_axis[0] > 0.99, "{:?}", arm.approach_axis);
        // Shoulder to tool frame: 0.1 + 0.4 + 0.321 + 0.18 = 1.001 m at full stretch.
        assert!(
            (0.99..=1.0012).contains(&arm.max_reach),
            "{}",
            arm.max_reach
        );
        assert!(arm.self_collision_free_fraction.is_some());
    }
    // The wheels sit inside the base's collision box: reported, not sampled.
    assert!(ws.self_collision_touching_at_reference.contains(&[
        "base_link".to_string(),
        "fl_caster_l_wheel_link".to_string()
    ]));
    // Declared to the tool frame, the arm still finds its hand (the palm the frame is welded to), so the
    // approach axis is the detected arm's.
    let options = Options {
        overrides: declared_arm("torso_lift_link", "r_gripper_tool_frame"),
        workspace: WorkspaceOptions {
            samples: 1000,
            ..WorkspaceOptions::default()
        },
        ..Options::default()
    };
    let declared = validate(
        &shared.join("pr2/pr2_description/robots/pr2.urdf"),
        &options,
    )
    .unwrap()
    .report
    .workspace
    .unwrap();
    let arm = &declared.arms[0];
    assert_eq!(arm.hand_link.as_deref(), Some("r_gripper_palm_link"));
    assert_eq!(arm.approach_axis_source, "fingers");
    assert_eq!(arm.approach_axis, ws.arms[0].approach_axis);
}
