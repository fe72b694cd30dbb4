//! The `workspace` section of the report.

use schemars::JsonSchema;
use serde::Serialize;

use crate::diagnostics::{Confidence, Status};

/// The `workspace` section: what the arms reach, sampled uniformly within the joint limits.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct WorkspaceSection {
    /// PASS; WARN when fewer than 95% of sampled poses are free of self-collision or the orientation is
    /// met by fewer than 5% of samples; FAIL when the task height is out of reach or the robot tips over
    /// while reaching; N/A without arms.
    pub status: Status,
    /// Largest distance from an arm's first joint to its tip, metres (maximum over arms).
    pub max_reach: Option<f64>,
    /// Highest tip position above the ground, metres.
    pub vertical_reach: Option<f64>,
    /// Largest horizontal distance from an arm's first joint to its tip, metres.
    pub horizontal_reach: Option<f64>,
    /// Largest distance from the robot's root frame to a tip, metres.
    pub reach_from_base: Option<f64>,
    /// `estimated`: Monte Carlo maxima approach the true ones from below.
    pub reach_confidence: Confidence,
    /// Samples per arm.
    pub samples: usize,
    /// Seed of the sampling.
    pub seed: u64,
    /// Per arm.
    pub arms: Vec<ArmWorkspace>,
    /// `--task`.
    pub task: Option<String>,
    /// Height of the task above the ground, metres.
    pub task_target_height_m: Option<f64>,
    /// Whether some arm's tip can be at the task height (tip heights vary continuously over the joint
    /// space, so lying between the lowest and highest feasible sampled tip is enough). Feasible: free of
    /// self-collision (when assessed), tip above the ground; the band poses and orientations below count
    /// feasible samples only.
    pub task_height_reachable: Option<bool>,
    /// Whether the whole-body COM stays over the support polygon at the sampled pose that reaches
    /// furthest horizontally at the task height (null when the robot cannot tip: fixed base, no polygon).
    pub task_com_stable_during_reach: Option<bool>,
    /// Horizontal COM displacement from the reference pose to that pose, metres.
    pub task_com_shift_estimate_m: Option<f64>,
    /// Stability margin at that pose, mm (positive inside the polygon).
    pub task_com_margin_mm: Option<f64>,
    /// The smallest margin over the feasible sampled poses within 5 cm of the task height (per arm, the
    /// first 4,096 sampled), mm: negative when some heading tips the robot.
    pub task_com_worst_margin_mm: Option<f64>,
    /// Why the COM during the reach was not assessed, when it was not.
    pub task_com_not_assessed: Option<String>,
    /// `--orientation`.
    pub orientation: Option<String>,
    /// Whether at least 5% of feasible samples (within 5 cm of the task height when a task is given) meet
    /// the orientation; `null` when there was no such sample (not assessed).
    pub orientation_reachable: Option<bool>,
    /// Fraction of those samples meeting the orientation (best arm).
    pub orientation_fraction: Option<f64>,
    /// Tolerance on the approach direction, degrees.
    pub orientation_tolerance_deg: f64,
    /// Fraction of sampled poses (all arms) free of self-collision.
    pub self_collision_free_fraction: Option<f64>,
    /// Smallest distance between two links over the collision-free sampled poses, mm, rounded to the
    /// micrometre (GJK's last digits depend on where its search started).
    pub self_collision_min_clearance_mm: Option<f64>,
    /// The pair found in contact in the most colliding samples (each colliding sample counts its first
    /// contact in a fixed pair order), else the pair with the smallest clearance.
    pub self_collision_worst_pair: Option<[String; 2]>,
    /// Link pairs already in contact at the zero pose (joints clamped into their limits): excluded from
    /// sampling.
    pub self_collision_touching_at_reference: Vec<[String; 2]>,
    /// Link pairs excluded by the SRDF (`disable_collisions`, and `disable_default_collisions` links'
    /// pairs no `enable_collisions` names) and not by adjacency or rigid attachment.
    pub self_collision_srdf_disabled: usize,
    /// Why self-collision was not assessed (no pair the arms move can collide, or their links have no
    /// usable collision geometry), when it was not.
    pub self_collision_not_assessed: Option<String>,
    /// Why the status is N/A or UNKNOWN, or what lowered it.
    pub reason: Option<String>,
}

impl WorkspaceSection {
    /// Every arm's `body_joints_held`, sorted, each once.
    pub fn body_joints_held(&self) -> Vec<&str> {
        body_joints_held(&self.arms)
    }
}

/// The `body_joints_held` of `arms`, sorted, each once.
pub fn body_joints_held(arms: &[ArmWorkspace]) -> Vec<&str> {
    let mut held: Vec<&str> = arms
        .iter()
        .flat_map(|arm| arm.body_joints_held.iter().map(String::as_str))
        .collect();
    held.sort_unstable();
    held.dedup();
    held
}

/// The reach of one arm.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct ArmWorkspace {
    /// The link the arm hangs from.
    pub root_link: String,
    /// The end-effector frame whose reach is measured.
    pub tip_link: String,
    /// The first actuated joint (reach is measured from its origin).
    pub first_joint: Option<String>,
    /// The sampled joints, shoulder first.
    pub joints: Vec<String>,
    /// Actuated joints between the robot's root and the arm (a torso lift, a waist), held at the `--pose`
    /// values while the arm is sampled: `name=value`.
    pub body_joints_held: Vec<String>,
    /// `exact` when declared with `--arm-root`/`--arm-tip`, else `estimated` (detected).
    pub confidence: Confidence,
    /// Where the fingers attach, when the arm has a gripper.
    pub hand_link: Option<String>,
    /// The tool's approach axis in the tip frame, and how it was chosen (`declared`, `fingers`, `z`).
    pub approach_axis: [f64; 3],
    /// How the approach axis was chosen.
    pub approach_axis_source: String,
    /// Largest distance from the first joint to the tip, metres.
    pub max_reach: f64,
    /// Highest tip above the ground, metres.
    pub vertical_reach: f64,
    /// Lowest tip above the ground, metres.
    pub lowest_tip_height: f64,
    /// Largest horizontal distance from the first joint, metres.
    pub horizontal_reach: f64,
    /// Largest distance from the root frame, metres.
    pub reach_from_base: f64,
    /// Whether the tip can be at the task height (feasible samples).
    pub task_height_reachable: Option<bool>,
    /// Feasible samples within 5 cm of the task height.
    pub task_band_samples: Option<usize>,
    /// Fraction of feasible samples meeting `--orientation` (within the task band when a task is given).
    pub orientation_fraction: Option<f64>,
    /// Fraction of this arm's samples free of self-collision.
    pub self_collision_free_fraction: Option<f64>,
    /// Smallest clearance over this arm's collision-free samples, mm, rounded to the micrometre.
    pub self_collision_min_clearance_mm: Option<f64>,
    /// Tip positions of a deterministic subset of the samples, for plots of the reach envelope: every
    /// k-th sample (k = ⌈samples / 400⌉, sample indices 0, k, 2k, …), at most 400, in sample order,
    /// whether or not the pose is free of self-collision; root frame, metres, rounded to the millimetre.
    /// The same seed gives the same points on any number of threads.
    pub tip_samples: Vec<[f64; 3]>,
}
