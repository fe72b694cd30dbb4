//! The `deep` section of the report: what MuJoCo did with the file, its gravity forces and centre of mass
//! against ours, and the 2-second drop test.

use schemars::JsonSchema;
use serde::Serialize;

use crate::diagnostics::Status;

/// The `deep` section (present only when the deep pass ran or was asked for).
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct DeepSection {
    /// FAIL when MuJoCo disagrees with the analysis, cannot load the file, or the robot fails the drop
    /// test; WARN when MuJoCo refuses the file as written (loaded after a stated adjustment) or the drop
    /// test rocks or drifts; UNKNOWN when MuJoCo was not found or could not run; else PASS.
    pub status: Status,
    /// Why it ran: `requested` (`--deep`) or `automatic` (the stability margin is negative).
    pub trigger: String,
    /// The simulator: `mujoco`.
    pub simulator: String,
    /// MuJoCo's version, as its Python package reports it.
    pub simulator_version: Option<String>,
    /// The Python interpreter that ran MuJoCo.
    pub python: Option<String>,
    /// Why the status is UNKNOWN (MuJoCo not found, the bridge timed out or crashed).
    pub reason: Option<String>,
    /// Everything MuJoCo refused or changed while loading the file, and what was done about it.
    pub simulator_changes: Vec<SimulatorChange>,
    /// Gravity generalized force of every independent actuated joint, MuJoCo's against ours (mimic
    /// followers folded into their leader as statics does), at the analysed pose — for `--pose worst`, at
    /// each joint's own worst configuration.
    pub joints: Vec<DeepJoint>,
    /// Whole-body centre of mass at the analysed pose, root frame, metres: MuJoCo's.
    pub mujoco_com: Option<[f64; 3]>,
    /// Ours (the statics section's).
    pub our_com: Option<[f64; 3]>,
    /// |MuJoCo's − ours|, metres.
    pub com_abs_diff: Option<f64>,
    /// True when every compared joint and the centre of mass agree within the tolerance (then statics'
    /// torques and centre of mass are labelled `simulated`).
    pub agreement: Option<bool>,
    /// The relative tolerance: |a − b| ≤ 1e-6 · max(|a|, |b|, 1e-3 N·m) for a torque (1e-3 m for the
    /// centre of mass).
    pub tolerance: f64,
    /// The 2-second drop test.
    pub drop_test: Option<DropTest>,
}

/// One thing MuJoCo refused or changed.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct SimulatorChange {
    /// `refused` (MuJoCo would not load the file as written; the stated adjustment was made), `fused`,
    /// `mimic`, `visual_dropped`, `limits`, `effort`, `mesh`, `mass`, `frame`, `inertia`.
    pub kind: String,
    /// The link or joint concerned.
    pub element: String,
    /// What MuJoCo did, and what this pass did about it.
    pub message: String,
}

/// One joint's gravity force, MuJoCo's against ours.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct DeepJoint {
    /// Joint name.
    pub name: String,
    /// MuJoCo's `qfrc_bias` at zero velocity (N·m or N), followers folded in.
    pub mujoco_torque: Option<f64>,
    /// Ours (the statics gravity torque, without payload unless `--payload-mass` is given, then with
    /// the payload in both), followers folded in.
    pub our_torque: f64,
    /// |MuJoCo's − ours|.
    pub abs_diff: Option<f64>,
    /// Within the tolerance.
    pub agrees: bool,
    /// The configuration compared: the analysed pose, or this joint's worst configuration.
    pub configuration: String,
}

/// The drop test: the robot on a ground plane, joints held by servos clamped to their declared effort,
/// dropped from 2 cm and simulated for 2.0 s.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct DropTest {
    /// FAIL when the robot falls (a link that is not a support contact rests on the ground at the end, or
    /// the root link ends more than 15° from upright) or a joint sags; WARN when it rocks or drifts;
    /// UNKNOWN when the simulation could not run or became unstable, or nothing of the robot touches the
    /// ground at the end (no collision geometry: it falls through the floor).
    pub status: Status,
    /// Simulated time, seconds (2.0).
    pub simulated_s: f64,
    /// Fixed time step, seconds.
    pub timestep_s: f64,
    /// `free` (dropped on the ground) or `fixed` (a fixed-base arm: the root is held, no ground).
    pub base: String,
    /// Largest tilt of the root link from upright during the test, degrees.
    pub max_tilt_deg: Option<f64>,
    /// Tilt at the end, degrees.
    pub final_tilt_deg: Option<f64>,
    /// Horizontal drift of the centre of mass from start to end, metres.
    pub com_drift_m: Option<f64>,
    /// Joints that end further from their pose than the tolerance (0.05 rad, 0.01 m).
    pub joints_sagging: Vec<SaggingJoint>,
    /// The links the robot may rest on: the stability section's contact links and raised contacts,
    /// `--contact-links`, links named as wheels or casters, and the links touching the ground (within
    /// 5 mm of the robot's lowest point) when it is released.
    pub support_links: Vec<String>,
    /// The links touching the ground at the end of the test (a MuJoCo contact with the floor at the last
    /// step). Links fused by MuJoCo are named as in the file.
    pub ground_links: Vec<String>,
    /// Those of `ground_links` that are not support links (nor below a sagging joint, which is that
    /// joint's sag, U746): the robot has fallen onto them (U745).
    pub fallen_onto: Vec<String>,
    /// Whether the drop test agrees with the stability section (both say the robot stands, or both that
    /// it falls); null when either has no verdict (stability not applicable or not computed, a fixed
    /// base, a simulation that could not run).
    pub agrees_with_stability: Option<bool>,
    /// When they disagree, how, in one sentence.
    pub stability_disagreement: Option<String>,
    /// The root link's tilt from upright over the test, `[time s, degrees]`, from the release to the end:
    /// at most 200 samples, evenly spaced (for plots).
    pub tilt_trace: Vec<[f64; 2]>,
    /// Why the verdict is not PASS, in one sentence.
    pub reason: Option<String>,
}

/// A joint that could not hold its pose.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct SaggingJoint {
    /// Joint name.
    pub name: String,
    /// Distance from its target at the end, rad (m for prismatic joints).
    pub deviation: f64,
    /// Its declared effort, when there is one.
    pub declared_effort: Option<f64>,
}
