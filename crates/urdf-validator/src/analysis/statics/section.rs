//! The `statics` section of the report.

use schemars::JsonSchema;
use serde::Serialize;

use crate::diagnostics::{Confidence, Status};

/// The `statics` section: mass, centre of mass and gravity torque against declared effort.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct StaticsSection {
    /// Worst joint status (N/A when the robot has no actuated joint).
    pub status: Status,
    /// The pose evaluated: zero, limits, custom, home, worst or key:NAME (a keyframe of an MJCF model).
    pub pose: String,
    /// Value of every independent actuated joint at the evaluated pose (rad or m). For `worst`, the reference
    /// (zero) pose; each joint's own worst configuration is in `joints[].worst_configuration`.
    pub configuration: std::collections::BTreeMap<String, f64>,
    /// How the pose was made: clamping, fallbacks, values outside limits.
    pub notes: Vec<String>,
    /// The gravity the torques hold against, m/s² in the root frame: the model's own (MJCF `<option
    /// gravity>`, zero under `<flag gravity="disable">`), else (0, 0, −9.81), turned with `--up-axis`.
    pub gravity: [f64; 3],
    /// Centre of mass of all declared masses, root frame, metres.
    pub full_body_com: Option<[f64; 3]>,
    /// `estimated` when derived from declared masses, `missing` when none is declared.
    pub com_confidence: Confidence,
    /// Sum of declared masses in the tree, kg.
    pub total_mass: Option<f64>,
    /// `estimated` when at least one mass is declared, else `missing`.
    pub mass_confidence: Confidence,
    /// Height of the centre of mass above the ground (the lowest contact found by the stability
    /// analysis); above the root frame origin when no ground was found. Metres.
    pub com_height_above_ground: Option<f64>,
    /// Link with the largest declared mass.
    pub heaviest_link_name: Option<String>,
    /// Its share of the total mass, percent.
    pub heaviest_link_pct: Option<f64>,
    /// Joint with the lowest margin.
    pub weakest_joint_name: Option<String>,
    /// Largest payload at `payload_link` keeping every joint on its path at margin ≥ 1.5, kg.
    pub payload_capacity_kg: Option<f64>,
    /// `--payload-mass`, kg.
    pub payload_mass: Option<f64>,
    /// Where the payload (and the capacity) is evaluated.
    pub payload_link: Option<String>,
    /// Why the status is UNKNOWN or N/A, or why the capacity is 0 or absent.
    pub reason: Option<String>,
    /// Samples drawn for the worst pose.
    pub samples: Option<usize>,
    /// Seed of the worst-pose sampling.
    pub seed: Option<u64>,
    /// One entry per actuated joint, in document order.
    pub joints: Vec<JointStatics>,
}

/// One actuated joint in `statics.joints`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct JointStatics {
    /// Joint name.
    pub name: String,
    /// Signed torque (N·m; N for prismatic) the motor must supply to hold the pose, mimic followers folded in
    /// (Pinocchio's sign convention). For `worst`, the largest-magnitude value sampled.
    pub required_torque_gravity: Option<f64>,
    /// `estimated` when computed from declared masses, `missing` when nothing below declares a mass.
    pub torque_confidence: Confidence,
    /// `<limit effort>`.
    pub declared_effort: Option<f64>,
    /// The smallest effort limit that would PASS: 1.5 × |`required_torque_gravity`| (the worst over the analysed
    /// poses, payload included). Null when the torque is unknown and for mimic followers (their torque is their
    /// leader's to hold).
    pub effort_needed: Option<f64>,
    /// effort / |torque|; null when the torque is negligible or a value is missing.
    pub margin: Option<f64>,
    /// PASS ≥ 1.5, WARN 1.0–1.5, FAIL < 1.0, UNKNOWN when data is missing, N/A for mimic followers.
    pub status: Status,
    /// Declared mass carried by the joint (its child's subtree), kg.
    pub subtree_mass: Option<f64>,
    /// One-line verdict.
    pub summary: String,
    /// The joint this one mimics (its torque is folded into that joint).
    pub mimics: Option<String>,
    /// For `--pose worst`: the configuration that produced `required_torque_gravity`.
    pub worst_configuration: Option<std::collections::BTreeMap<String, f64>>,
}
