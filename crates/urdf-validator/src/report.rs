//! The report: one serde type tree, the single source of truth for the JSON file and every renderer.
//!
//! Field names follow the Python tool's JSON so existing CI scripts keep working. Sections that are not
//! implemented yet (statics, stability, workspace) are absent, never filled with placeholders.

use schemars::JsonSchema;
use serde::Serialize;

use crate::finding::Severity;

/// A check's verdict. Overall = worst of the applicable ones (N/A is excluded).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, JsonSchema)]
pub enum Status {
    /// The check does not apply to this robot category.
    #[serde(rename = "N/A")]
    NotApplicable,
    /// Everything checked is fine.
    #[serde(rename = "PASS")]
    Pass,
    /// Usable, but something deserves attention.
    #[serde(rename = "WARN")]
    Warn,
    /// The check applies but could not run.
    #[serde(rename = "UNKNOWN")]
    Unknown,
    /// Something is wrong.
    #[serde(rename = "FAIL")]
    Fail,
}

impl Status {
    /// The label used in text output.
    pub fn label(self) -> &'static str {
        match self {
            Status::NotApplicable => "N/A",
            Status::Pass => "PASS",
            Status::Warn => "WARN",
            Status::Unknown => "UNKNOWN",
            Status::Fail => "FAIL",
        }
    }

    /// The process exit code for this overall status: 0 PASS (and N/A), 1 WARN, 2 FAIL or UNKNOWN.
    pub fn exit_code(self) -> i32 {
        match self {
            Status::NotApplicable | Status::Pass => 0,
            Status::Warn => 1,
            Status::Unknown | Status::Fail => 2,
        }
    }

    /// The worse of two statuses for the overall verdict (UNKNOWN ranks with FAIL for exit codes, below it here).
    pub fn worst(self, other: Status) -> Status {
        self.max(other)
    }
}

/// How far a number can be trusted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Confidence {
    /// Read from the file or declared by the user.
    Exact,
    /// Derived analytically from declared data, or a heuristic without a declaration to check it.
    Estimated,
    /// From geometry when data is missing.
    Guessed,
    /// No data.
    Missing,
    /// Cross-checked in a simulator.
    Simulated,
}

/// Overall quality of the physics data.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, JsonSchema)]
pub enum ConfidenceLevel {
    /// Every link that should have mass declares mass and inertia.
    #[serde(rename = "HIGH")]
    High,
    /// At least half of those links declare a mass.
    #[serde(rename = "MEDIUM")]
    Medium,
    /// Sparse physics data.
    #[serde(rename = "LOW")]
    Low,
}

impl ConfidenceLevel {
    /// The label used in text output.
    pub fn label(self) -> &'static str {
        match self {
            ConfidenceLevel::High => "HIGH",
            ConfidenceLevel::Medium => "MEDIUM",
            ConfidenceLevel::Low => "LOW",
        }
    }
}

/// The validation report of one robot: `<stem>_validation.json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct Report {
    /// The validated file, as given on the command line.
    pub urdf_path: String,
    /// `name` of `<robot>` (empty when absent).
    pub robot_name: String,
    /// When validation ran, ISO 8601 UTC.
    pub timestamp: String,
    /// Version of urdf_validate that wrote this report.
    pub validator_version: String,
    /// Worst applicable section status.
    pub overall_status: Status,
    /// The robot category used for the capability profile (declared with `--robot-type`, else detected).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robot_type: Option<crate::classify::RobotType>,
    /// `exact` when declared, `estimated` when detected.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robot_type_confidence: Option<Confidence>,
    /// What the structure shows (also when a type was declared, as a cross-check), and why.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robot_type_detected: Option<crate::classify::RobotType>,
    /// The evidence behind `robot_type_detected`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robot_type_evidence: Option<String>,
    /// Quality of the physics data.
    pub confidence_level: ConfidenceLevel,
    /// Messages of CRITICAL findings.
    pub critical_issues: Vec<String>,
    /// Messages of WARN findings.
    pub warnings: Vec<String>,
    /// What could not be assessed.
    pub unknowns: Vec<String>,
    /// Structural checks.
    pub schema: SchemaSection,
    /// Counts behind the `[PHYSICS]` line.
    pub physics: PhysicsSummary,
    /// Per-link mass data, in document order.
    pub links: Vec<LinkReport>,
    /// Mass, centre of mass and gravity torques (absent when the file is not a robot).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub statics: Option<StaticsSection>,
    /// Support polygon and tipping (absent when the file is not a robot).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stability: Option<StabilitySection>,
    /// Reach, task, orientation and self-collision of every arm (absent when the file is not a robot).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub workspace: Option<WorkspaceSection>,
    /// Every finding with its rule and source position.
    pub findings: Vec<FindingReport>,
}

/// The `schema` section.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct SchemaSection {
    /// FAIL with any CRITICAL finding, WARN with any WARN finding, else PASS.
    pub status: Status,
    /// Messages of CRITICAL findings.
    pub critical_issues: Vec<String>,
    /// Messages of WARN findings.
    pub warnings: Vec<String>,
    /// Messages of INFO findings.
    pub infos: Vec<String>,
}

/// Mass-data counts over the links (frames are counted apart, not as missing mass).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, JsonSchema)]
pub struct PhysicsSummary {
    /// All links.
    pub links: usize,
    /// Pure frames: no inertial, no geometry, fixed to their parent (or the root).
    pub frames: usize,
    /// Non-frame links declaring a finite mass.
    pub mass_exact: usize,
    /// Non-frame links without a usable mass.
    pub mass_missing: usize,
    /// Non-frame links declaring a finite inertia tensor.
    pub inertia_exact: usize,
    /// Non-frame links without a usable inertia tensor.
    pub inertia_missing: usize,
}

/// One entry of `links`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct LinkReport {
    /// Link name.
    pub name: String,
    /// True for a pure frame link.
    pub frame: bool,
    /// Declared mass in kg.
    pub mass: Option<f64>,
    /// `exact` when declared, else `missing`.
    pub mass_confidence: Confidence,
    /// Row-major 3×3 inertia tensor in kg·m², about the inertial frame.
    pub inertia_tensor: Option<[f64; 9]>,
    /// `exact` when declared, else `missing`.
    pub inertia_confidence: Confidence,
    /// Centre of mass in the link frame (the `<inertial><origin xyz>`, zero when omitted), metres.
    pub com_offset: Option<[f64; 3]>,
    /// `exact` when the link has an inertial, else `missing`.
    pub com_confidence: Confidence,
}

/// One finding, positioned.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct FindingReport {
    /// Rule code, e.g. `U205`.
    pub rule: String,
    /// Rule name, e.g. `inertia-not-positive-definite`.
    pub name: String,
    /// CRITICAL, WARN or INFO.
    pub severity: Severity,
    /// What is wrong, naming the element.
    pub message: String,
    /// File holding the problem (null when it has no place).
    pub file: Option<String>,
    /// 1-based line.
    pub line: Option<u32>,
    /// 1-based column.
    pub column: Option<u32>,
    /// 1-based line where the flagged text ends.
    pub end_line: Option<u32>,
    /// 1-based column just past the flagged text.
    pub end_column: Option<u32>,
    /// What to do about it.
    pub help: Option<String>,
    /// For xacro input: the macro calls and includes that produced the flagged text, innermost first
    /// (`in macro 'wheel' called at robot.urdf.xacro:40:3`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub expanded_from: Vec<String>,
}

/// The JSON Schema of [`Report`], pretty-printed.
pub fn json_schema() -> String {
    let schema = schemars::schema_for!(Report);
    serde_json::to_string_pretty(&schema).unwrap_or_default() + "\n"
}

/// The `statics` section: mass, centre of mass and gravity torque against declared effort.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct StaticsSection {
    /// Worst joint status (N/A when the robot has no actuated joint).
    pub status: Status,
    /// The pose evaluated: zero, limits, custom, home or worst.
    pub pose: String,
    /// Value of every independent actuated joint at the evaluated pose (rad or m). For `worst`, the reference
    /// (zero) pose; each joint's own worst configuration is in `joints[].worst_configuration`.
    pub configuration: std::collections::BTreeMap<String, f64>,
    /// How the pose was made: clamping, fallbacks, values outside limits.
    pub notes: Vec<String>,
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

/// The `stability` section: the support polygon and where the centre of mass sits over it.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct StabilitySection {
    /// PASS when the COM projects inside the support polygon, FAIL outside, UNKNOWN when there is no
    /// polygon or no COM, N/A for fixed-base and aerial robots.
    pub status: Status,
    /// True when the COM projects inside the polygon.
    pub stable: Option<bool>,
    /// Signed distance from the COM projection to the polygon boundary, mm (positive inside).
    pub margin_mm: Option<f64>,
    /// Where the robot would tip: front, front-left, left, back-left, back, back-right, right, front-right.
    pub tip_direction: Option<String>,
    /// COM height above the ground over the polygon's minimum width.
    pub com_height_ratio: Option<f64>,
    /// Confidence of the ratio.
    pub com_height_ratio_confidence: Confidence,
    /// very_stable < 0.5 ≤ stable < 1 ≤ manageable < 2 ≤ requires_active_balancing < 3 ≤ will_fall.
    pub com_height_ratio_class: Option<String>,
    /// Smallest tilt that brings the COM over an edge: min over edges of atan(d / h), degrees.
    pub tipping_angle_deg: Option<f64>,
    /// `exact` with `--contact-links`, else `estimated`.
    pub contact_confidence: Confidence,
    /// How contacts were found: declared, wheels, feet, lowest_geometry.
    pub contact_source: Option<String>,
    /// Links touching the ground (supporting).
    pub contact_links: Vec<String>,
    /// Counter-clockwise support polygon in the root frame's ground plane, metres.
    pub support_polygon: Vec<[f64; 2]>,
    /// Height of the ground (the lowest contact) in the root frame, metres.
    pub ground_height: Option<f64>,
    /// COM height above the ground, metres.
    pub com_height: Option<f64>,
    /// Contact candidates more than 5 mm above the ground: they do not support (the robot rocks).
    pub raised_contacts: Vec<RaisedContact>,
    /// Why the status is UNKNOWN or N/A.
    pub reason: Option<String>,
}

/// A contact candidate that does not reach the ground.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct RaisedContact {
    /// The link.
    pub link: String,
    /// Its lowest point above the ground, mm.
    pub height_mm: f64,
}

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
    /// Smallest distance between two links over the collision-free sampled poses, mm.
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
    /// Smallest clearance over this arm's collision-free samples, mm.
    pub self_collision_min_clearance_mm: Option<f64>,
}
