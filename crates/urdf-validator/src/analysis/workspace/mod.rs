//! The workspace section: every arm's reach envelope by Monte Carlo sampling within the joint limits,
//! task-height reachability with the whole-body COM checked at the reaching pose, orientation
//! reachability, and self-collision over the same samples.
//!
//! Each arm is sampled on its own (its joints uniform within their limits, continuous joints over a full
//! turn, everything else at the reference pose). Sample `i` of arm `a` is drawn from a generator seeded
//! by (seed, a, i / CHUNK), so results do not depend on the number of threads.

mod section;

pub use section::{body_joints_held, ArmWorkspace, WorkspaceSection};

pub mod chain;
mod placements;
mod sincos;
pub mod target;
mod verdict;

pub use verdict::findings;

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use nalgebra::Vector3;
use rayon::prelude::*;

use crate::analysis::arms::Arm;
use crate::analysis::classify::RobotType;
use crate::analysis::collision::{Allowed, CheckScratch, CollisionModel, PairSet};
use crate::analysis::memo::{Fingerprint, Memo};
use crate::analysis::stability::support_polygon::{margin, Point2};
use crate::analysis::statics::gravity::{evaluate, mass_and_com, StaticsData};
use crate::assets::LinkSupports;
use crate::diagnostics::{Confidence, Status};
use crate::input::srdf::SrdfCollisions;
use crate::model::kinematics::{Configuration, Data};
use crate::model::{JointId, LinkId, Model, Motion};
use crate::rng::SplitMix64;
use crate::timings::Progress;
use crate::urdf::robot::Robot;

use chain::{ArmChain, Samples, BATCH};
use placements::{BatchPlacements, LANES};
use target::{Orientation, OrientationMatcher, Task};

/// Samples per parallel work unit (and per generator seed).
const CHUNK: usize = 1024;
/// Half-width of the height band around a task height, metres.
pub const TASK_BAND: f64 = 0.05;
/// A task height this close to the sampled tip envelope (as a fraction of the arm's reach) may be reachable
/// by a pose no sample drew: the FAIL reason says so.
const NEAR_ENVELOPE: f64 = 0.02;
/// The most poses within the task band, per arm, whose centre of mass is checked (the first feasible ones
/// sampled).
const MAX_BAND_POSES: usize = 4096;
/// Fraction of samples that must meet an orientation.
pub const ORIENTATION_PASS_FRACTION: f64 = 0.05;
/// Fraction of samples that must be free of self-collision.
pub const COLLISION_FREE_PASS_FRACTION: f64 = 0.95;
/// The most tip positions per arm kept in the report ([`ArmWorkspace::tip_samples`]) for plots.
pub const MAX_TIP_SAMPLES: usize = 400;

/// Every how many samples a tip position is kept so that at most [`MAX_TIP_SAMPLES`] are.
fn tip_stride(samples: usize) -> usize {
    samples.div_ceil(MAX_TIP_SAMPLES).max(1)
}

/// A clearance of `metres`, in mm rounded to the micrometre: GJK stops within 10⁻¹¹ m or so of the
/// distance, and where it stops depends on the direction it started from (the pair's last direction,
/// so on the order the samples met the pair in), which the report should not show.
fn clearance_mm(metres: f64) -> f64 {
    (metres * 1e6).round() / 1000.0
}

/// A position rounded to the millimetre (the report's plots need no more, and the JSON stays small).
fn round_mm(p: &Vector3<f64>) -> [f64; 3] {
    let mm = |v: f64| (v * 1000.0).round() / 1000.0;
    [mm(p.x), mm(p.y), mm(p.z)]
}

/// What the workspace analysis is asked.
#[derive(Clone, Debug)]
pub struct WorkspaceOptions {
    /// Samples per arm (`--samples`).
    pub samples: usize,
    /// Seed (`--seed`).
    pub seed: u64,
    /// `--task` / `--height`.
    pub task: Option<Task>,
    /// `--orientation`.
    pub orientation: Option<Orientation>,
    /// `--orientation-tolerance`, degrees.
    pub orientation_tolerance_deg: f64,
    /// `--approach-axis` (tip frame); default: towards the fingers, else +z.
    pub approach_axis: Option<Vector3<f64>>,
    /// When cancelled, sampling stops at the next batch of samples (the section is then partial).
    pub progress: Option<Progress>,
    /// Sampled arms kept from earlier runs on the same document (the language server's): an arm whose
    /// sampling inputs did not change is not sampled again.
    pub memo: Option<Memo>,
    /// Arms the memo does not hold are sampled from this instant on, not before: the language server's
    /// typing pause (a newer edit cancels the run first, and the sampling never starts), while a run
    /// whose arms are all kept finishes at once.
    pub sample_from: Option<Instant>,
}

impl Default for WorkspaceOptions {
    fn default() -> Self {
        WorkspaceOptions {
            samples: crate::analysis::DEFAULT_SAMPLES,
            seed: crate::analysis::DEFAULT_SEED,
            task: None,
            orientation: None,
            orientation_tolerance_deg: 30.0,
            approach_axis: None,
            progress: None,
            memo: None,
            sample_from: None,
        }
    }
}

/// The robot at its reference pose, and what the other sections found about it.
pub struct Scene<'a> {
    /// The robot.
    pub robot: &'a Robot,
    /// Its tree.
    pub model: &'a Model,
    /// The reference configuration (the statics pose).
    pub q: &'a [f64],
    /// Placements at `q`.
    pub data: &'a Data,
    /// Height of the ground in the root frame.
    pub ground: f64,
    /// The support polygon at `q` (counter-clockwise), empty when the robot cannot tip.
    pub support_polygon: &'a [Point2],
    /// The robot category (for the N/A reason).
    pub robot_type: RobotType,
    /// `--payload-mass` in kg and `--payload-link`: the load the reaching arm carries, at that link, or at
    /// the arm's tip when no link is given.
    pub payload: Option<(f64, Option<LinkId>)>,
}

/// Self-collision set-up: the model with its allowed pairs, and what was excluded.
pub struct CollisionSetup {
    /// Shapes and allowed-collision matrix (touching-at-reference pairs already allowed).
    pub model: CollisionModel,
    /// Pairs in contact at the reference pose.
    pub touching: Vec<(LinkId, LinkId)>,
    /// Pairs an SRDF allows (not otherwise excluded).
    pub srdf_disabled: usize,
    /// SRDF entries naming links the robot does not have (`line:col: ...`).
    pub unknown_srdf_links: Vec<String>,
}

impl CollisionSetup {
    /// Build the collision model, allow the pairs the robot file itself filters out
    /// ([`Robot::collision_filtered`]) and what the SRDF allows, and exclude what is in contact at the
    /// reference placements.
    pub fn new(
        robot: &Robot,
        model: &Model,
        reference: &Data,
        supports: &[LinkSupports],
        srdf: &SrdfCollisions,
    ) -> CollisionSetup {
        let mut collision = CollisionModel::build(robot, model, supports);
        let filtered: Vec<(LinkId, LinkId)> = robot
            .collision_filtered
            .iter()
            .filter_map(|(a, b)| Some((model.link(a)?, model.link(b)?)))
            .collect();
        collision.allow(&filtered, Allowed::Disabled);
        let before = collision.checked_pair_count();
        let unknown_srdf_links = collision.allow_srdf(model, srdf);
        let srdf_disabled = before - collision.checked_pair_count();
        let touching = collision.touching_pairs(&reference.link_placement);
        collision.allow(&touching, Allowed::Touching);
        CollisionSetup {
            model: collision,
            touching,
            srdf_disabled,
            unknown_srdf_links,
        }
    }
}

/// One arm prepared for sampling.
struct ArmJob<'a> {
    arm: &'a Arm,
    chain: ArmChain,
    approach: Vector3<f64>,
    approach_source: &'static str,
    /// Links whose placement changes with the arm's joints (parents first).
    moving_links: Vec<LinkId>,
    /// Of those, the ones self-collision reads, placed a batch of samples at a time: the links of `pairs`
    /// and the moving links above them (parents first). A moved link that no pair reaches (a tool frame,
    /// a finger without geometry) is never placed.
    placements: Option<BatchPlacements>,
    pairs: Option<PairSet>,
}

/// What the samples of one arm (or one chunk of them) showed.
#[derive(Clone, Debug)]
struct ArmStats {
    samples: usize,
    max_reach: f64,
    max_height: f64,
    min_height: f64,
    /// Tip height range over the feasible samples (free of self-collision, tip above the ground): what
    /// task heights are judged on.
    feasible_heights: Option<(f64, f64)>,
    max_horizontal: f64,
    max_from_base: f64,
    band_samples: usize,
    /// Furthest horizontal reach within the task band: (distance, sample index, arm values).
    band_best: Option<(f64, usize, Vec<f64>)>,
    /// The first [`MAX_BAND_POSES`] samples within the task band (by sample index): (index, arm values).
    band_poses: Vec<(usize, Vec<f64>)>,
    orientation_ok: usize,
    orientation_considered: usize,
    collision_free: usize,
    min_clearance: Option<(f64, (LinkId, LinkId))>,
    /// Per pair, the colliding samples where it was the first contact found.
    colliding: HashMap<(LinkId, LinkId), usize>,
    /// Every [`tip_stride`]-th sample's tip position: (sample index, position rounded to the mm).
    tips: Vec<(usize, [f64; 3])>,
}

impl ArmStats {
    fn new() -> Self {
        ArmStats {
            samples: 0,
            max_reach: f64::NEG_INFINITY,
            max_height: f64::NEG_INFINITY,
            min_height: f64::INFINITY,
            feasible_heights: None,
            max_horizontal: f64::NEG_INFINITY,
            max_from_base: f64::NEG_INFINITY,
            band_samples: 0,
            band_best: None,
            band_poses: Vec::new(),
            orientation_ok: 0,
            orientation_considered: 0,
            collision_free: 0,
            min_clearance: None,
            colliding: HashMap::new(),
            tips: Vec::new(),
        }
    }

    fn merge(mut self, other: ArmStats) -> ArmStats {
        self.samples += other.samples;
        self.max_reach = self.max_reach.max(other.max_reach);
        self.max_height = self.max_height.max(other.max_height);
        self.min_height = self.min_height.min(other.min_height);
        self.feasible_heights = match (self.feasible_heights, other.feasible_heights) {
            (Some(a), Some(b)) => Some((a.0.min(b.0), a.1.max(b.1))),
            (a, b) => a.or(b),
        };
        self.max_horizontal = self.max_horizontal.max(other.max_horizontal);
        self.max_from_base = self.max_from_base.max(other.max_from_base);
        self.band_samples += other.band_samples;
        self.band_best = match (self.band_best.take(), other.band_best) {
            (Some(a), Some(b)) => Some(
                if (b.0, std::cmp::Reverse(b.1)) > (a.0, std::cmp::Reverse(a.1)) {
                    b
                } else {
                    a
                },
            ),
            (a, b) => a.or(b),
        };
        self.band_poses.extend(other.band_poses);
        self.band_poses.sort_unstable_by_key(|(index, _)| *index);
        self.band_poses.truncate(MAX_BAND_POSES);
        self.orientation_ok += other.orientation_ok;
        self.orientation_considered += other.orientation_considered;
        self.collision_free += other.collision_free;
        self.min_clearance = match (self.min_clearance, other.min_clearance) {
            (Some(a), Some(b)) => Some(if b.0 < a.0 || (b.0 == a.0 && b.1 < a.1) {
                b
            } else {
                a
            }),
            (a, b) => a.or(b),
        };
        for (pair, count) in other.colliding {
            *self.colliding.entry(pair).or_default() += count;
        }
        self.tips.extend(other.tips);
        self.tips.sort_unstable_by_key(|(index, _)| *index);
        self
    }
}

/// What one sample needs besides the arm.
struct SampleContext<'a> {
    scene: &'a Scene<'a>,
    options: &'a WorkspaceOptions,
    matcher: Option<OrientationMatcher>,
    collision: Option<&'a CollisionModel>,
    /// The smallest self-collision clearance any chunk of the arm has found so far: a chunk needs no
    /// distance at or above it.
    nearest: SharedMinimum,
}

impl SampleContext<'_> {
    /// The clearance below which a pose's distances are worth computing: the smaller of the chunk's
    /// own smallest (`own`) and the arm's ([`SampleContext::nearest`]). Poses at or above it cannot
    /// change the arm's smallest clearance, whichever chunk finds which first, so the result does not
    /// depend on the order in which threads run chunks.
    fn clearance_cutoff(&self, own: Option<f64>) -> f64 {
        let shared = self.nearest.get();
        own.map_or(shared, |own| own.min(shared))
    }
}

/// The smallest non-negative number offered so far, from any thread (+∞ before any): kept as the bits of
/// an `f64`, which order as the values do for non-negative numbers.
struct SharedMinimum(AtomicU64);

impl SharedMinimum {
    fn new() -> Self {
        SharedMinimum(AtomicU64::new(f64::INFINITY.to_bits()))
    }

    fn get(&self) -> f64 {
        f64::from_bits(self.0.load(Ordering::Relaxed))
    }

    /// Offer `value`; negative numbers and NaN are ignored (and -0 is 0).
    fn offer(&self, value: f64) {
        if value >= 0.0 {
            self.0.fetch_min((value + 0.0).to_bits(), Ordering::Relaxed);
        }
    }
}

/// The generator seed of one chunk: the seed, the arm and the chunk hashed in turn, so nearby seeds
/// (7 and 6) share no chunk stream.
fn chunk_seed(seed: u64, arm: usize, chunk: usize) -> u64 {
    let mix = |value: u64| SplitMix64::new(value).next_u64();
    mix(mix(mix(seed) ^ arm as u64) ^ chunk as u64)
}

/// A chunk's self-collision state: a full configuration and placements, updated on the arm's moving
/// links only.
struct SampleCollision<'a> {
    model: &'a CollisionModel,
    pairs: &'a PairSet,
    q: Configuration,
    scratch: CheckScratch,
    placements: BatchPlacements,
}

impl SampleCollision<'_> {
    /// Place the moving links of up to [`LANES`] samples, a row of the arm's `sampled` joint values each.
    fn place(&mut self, model: &Model, rows: &[Vec<f64>], sampled: &[(JointId, f64, f64)]) {
        for (lane, row) in rows.iter().enumerate() {
            for (value, (joint, _, _)) in row.iter().zip(sampled) {
                self.q[joint.0] = *value;
            }
            model.apply_mimic(&mut self.q);
            self.placements.load(lane, &self.q);
        }
        self.placements.place();
    }
}

fn sample_chunk(ctx: &SampleContext, job: &ArmJob, arm_index: usize, chunk: usize) -> ArmStats {
    let scene = ctx.scene;
    let start = chunk * CHUNK;
    let cancelled = ctx
        .options
        .progress
        .as_ref()
        .is_some_and(Progress::is_cancelled);
    let count = if cancelled {
        0
    } else {
        CHUNK.min(ctx.options.samples.saturating_sub(start))
    };
    let mut stats = ArmStats::new();
    let mut rng = SplitMix64::new(chunk_seed(ctx.options.seed, arm_index, chunk));
    // One batch of samples' values, a row per sample.
    let mut rows = vec![vec![0.0; job.chain.dof()]; BATCH];
    let mut collision_state = match (ctx.collision, &job.pairs, &job.placements) {
        (Some(model), Some(pairs), Some(placements)) if !pairs.is_empty() => {
            Some(SampleCollision {
                model,
                pairs,
                q: scene.q.to_vec(),
                // Only the arm's links move in this chunk: every other link's placement is kept.
                scratch: CheckScratch::holding_fixed(model),
                placements: placements.clone(),
            })
        }
        _ => None,
    };
    let target_height = ctx
        .options
        .task
        .map(|t| scene.ground + t.height(scene.ground));
    let shoulder = job.chain.shoulder;
    let stride = tip_stride(ctx.options.samples);
    // The samples' values are needed one by one only for self-collision and the task band; otherwise the
    // tips are computed from values drawn where the chain needs them, never stored.
    let keep_rows = collision_state.is_some() || target_height.is_some();
    let approach = ctx.matcher.map(|_| &job.approach);
    for first in (0..count).step_by(BATCH) {
        if is_cancelled(ctx.options) {
            break;
        }
        let batch = BATCH.min(count - first);
        let poses = if keep_rows {
            for row in &mut rows[..batch] {
                for (value, (_, lo, hi)) in row.iter_mut().zip(&job.chain.sampled) {
                    *value = rng.uniform(*lo, *hi);
                }
            }
            // Rows past the batch's end hold earlier (or zero) values: evaluated, then ignored.
            let lanes: [&[f64]; BATCH] = std::array::from_fn(|k| rows[k].as_slice());
            job.chain.tips(&Samples::Rows(&lanes), approach)
        } else {
            let poses = job.chain.tips(&Samples::Drawn(&rng), approach);
            rng.skip((batch * job.chain.dof()) as u64);
            poses
        };
        // `q` is the sample's values when `keep_rows` (and only read then).
        for (k, (q, pose)) in rows.iter().zip(&poses).take(batch).enumerate() {
            let i = first + k;
            let p = pose.position;
            let offset = p - shoulder;
            stats.samples += 1;
            if (start + i) % stride == 0 {
                stats.tips.push((start + i, round_mm(&p)));
            }
            stats.max_reach = stats.max_reach.max(offset.norm());
            stats.max_height = stats.max_height.max(p.z - scene.ground);
            stats.min_height = stats.min_height.min(p.z - scene.ground);
            stats.max_horizontal = raise_horizontal(stats.max_horizontal, &offset);
            stats.max_from_base = stats.max_from_base.max(p.norm());
            // Self-collision first: task heights, the band and orientations count feasible poses only.
            let mut free = true;
            if let Some(state) = collision_state.as_mut() {
                if k % LANES == 0 {
                    let lanes = &rows[k..(k + LANES).min(batch)];
                    state.place(scene.model, lanes, &job.chain.sampled);
                }
                if state.placements.usable(k % LANES) {
                    let centres = state.placements.points(k % LANES);
                    state.scratch.vouch_moving(state.pairs, centres);
                }
                let cutoff = ctx.clearance_cutoff(stats.min_clearance.map(|c| c.0));
                let check = state.model.check(
                    state.pairs,
                    &state.placements.lane(k % LANES, &scene.data.link_placement),
                    cutoff,
                    &mut state.scratch,
                );
                free = check.is_free();
                if free {
                    stats.collision_free += 1;
                    if let Some(clearance) = check.min_clearance {
                        ctx.nearest.offer(clearance.0);
                        stats.min_clearance = Some(clearance);
                    }
                }
                if let Some(pair) = check.contact {
                    *stats.colliding.entry(pair).or_default() += 1;
                }
            }
            let height = p.z - scene.ground;
            if !free || height < 0.0 {
                continue;
            }
            stats.feasible_heights = Some(match stats.feasible_heights {
                Some((lo, hi)) => (lo.min(height), hi.max(height)),
                None => (height, height),
            });
            let in_band = target_height.map(|h| (p.z - h).abs() <= TASK_BAND);
            if in_band == Some(true) {
                stats.band_samples += 1;
                let horizontal = offset.x.hypot(offset.y);
                if stats.band_best.as_ref().is_none_or(|b| horizontal > b.0) {
                    stats.band_best = Some((horizontal, start + i, q.clone()));
                }
                if stats.band_poses.len() < MAX_BAND_POSES {
                    stats.band_poses.push((start + i, q.clone()));
                }
            }
            if let Some(matcher) = &ctx.matcher {
                if in_band != Some(false) {
                    stats.orientation_considered += 1;
                    stats.orientation_ok += usize::from(matcher.accepts(&pose.approach));
                }
            }
        }
    }
    stats
}

/// The links `motion` moves, parents first (those of the root's tree).
fn moved_links(model: &Model, motion: &Motion) -> Vec<LinkId> {
    model
        .topological_order
        .iter()
        .copied()
        .filter(|l| motion.links[l.0])
        .collect()
}

/// Of the `moving` links (parents first), those `pairs` reads: its links and the moving links above them.
fn links_to_place(model: &Model, moving: &[LinkId], pairs: &PairSet) -> Vec<LinkId> {
    let mut needed = vec![false; model.parent_joint.len()];
    for &link in pairs.links() {
        let mut at = Some(link);
        while let Some(link) = at.filter(|l| needed.get(l.0) == Some(&false)) {
            needed[link.0] = true;
            at = model.parent_joint[link.0]
                .and_then(|joint| model.joint_links[joint.0])
                .map(|(parent, _)| parent);
        }
    }
    moving
        .iter()
        .copied()
        .filter(|l| needed.get(l.0) == Some(&true))
        .collect()
}

/// The tool's approach axis in the tip frame: declared, else from the hand towards its fingers, else +z.
fn approach_axis(
    arm: &Arm,
    data: &Data,
    declared: Option<Vector3<f64>>,
) -> (Vector3<f64>, &'static str) {
    if let Some(axis) = declared {
        return (axis, "declared");
    }
    if let (Some(hand), false) = (arm.hand, arm.fingers.is_empty()) {
        let centroid = arm
            .fingers
            .iter()
            .map(|f| data.link_placement[f.0].translation.vector)
            .sum::<Vector3<f64>>()
            / arm.fingers.len() as f64;
        let from_hand = centroid - data.link_placement[hand.0].translation.vector;
        let tip = data.link_placement[arm.tip.0];
        if let Some(direction) = (tip.rotation.inverse() * from_hand).try_normalize(1e-4) {
            return (direction, "fingers");
        }
    }
    (Vector3::z(), "z")
}

fn names(robot: &Robot, pair: (LinkId, LinkId)) -> [String; 2] {
    [
        robot.links[pair.0 .0].name.value.clone(),
        robot.links[pair.1 .0].name.value.clone(),
    ]
}

fn not_applicable(scene: &Scene, options: &WorkspaceOptions, reason: String) -> WorkspaceSection {
    WorkspaceSection {
        status: Status::NotApplicable,
        max_reach: None,
        vertical_reach: None,
        horizontal_reach: None,
        reach_from_base: None,
        reach_confidence: Confidence::Missing,
        samples: options.samples,
        seed: options.seed,
        arms: Vec::new(),
        task: options.task.map(|t| t.name().to_string()),
        task_target_height_m: options.task.map(|task| task.height(scene.ground)),
        task_height_reachable: None,
        task_com_stable_during_reach: None,
        task_com_shift_estimate_m: None,
        task_com_margin_mm: None,
        task_com_worst_margin_mm: None,
        task_com_not_assessed: None,
        orientation: options.orientation.map(|o| o.label()),
        orientation_reachable: None,
        orientation_fraction: None,
        orientation_tolerance_deg: options.orientation_tolerance_deg,
        self_collision_free_fraction: None,
        self_collision_min_clearance_mm: None,
        self_collision_worst_pair: None,
        self_collision_touching_at_reference: Vec::new(),
        self_collision_srdf_disabled: 0,
        self_collision_not_assessed: None,
        reason: Some(reason),
    }
}

/// The workspace section for `arms` (detected or declared). `collision` is `None` when self-collision is
/// not assessed (more than [`crate::analysis::collision::MAX_COLLISION_LINKS`] links).
pub fn analyse(
    scene: &Scene,
    arms: &[Arm],
    collision: Option<&CollisionSetup>,
    options: &WorkspaceOptions,
) -> WorkspaceSection {
    let model = scene.model;
    if arms.is_empty() {
        let reason = if scene.robot_type == RobotType::Object {
            "not applicable — robot type 'object' has no movable joint, so no arm chain".to_string()
        } else {
            format!(
                "not applicable — no arm chain detected (robot type '{}'); declare one with --arm-root/--arm-tip",
                scene.robot_type.as_str()
            )
        };
        return not_applicable(scene, options, reason);
    }
    if options.samples == 0 {
        return not_applicable(
            scene,
            options,
            "no configuration sampled (--samples 0)".to_string(),
        );
    }
    let tolerance = options.orientation_tolerance_deg.to_radians();
    let jobs: Vec<ArmJob> = arms
        .iter()
        .filter_map(|arm| {
            let chain = ArmChain::new(model, arm, scene.data, scene.q);
            let (approach, approach_source) = approach_axis(arm, scene.data, options.approach_axis);
            arm.first_joint(model)?;
            let sampled: Vec<JointId> = chain.sampled.iter().map(|(j, _, _)| *j).collect();
            if sampled.is_empty() {
                return None;
            }
            let motion = model.motion_of(&sampled);
            let moving_links = moved_links(model, &motion);
            let pairs = collision.map(|c| (c, c.model.pairs_moved_by(&motion)));
            let placements = pairs.as_ref().map(|(collision, pairs)| {
                let links = links_to_place(model, &moving_links, pairs);
                // The moving links' bounding-sphere centres, placed with the links for the checks.
                let centres: Vec<(LinkId, Vector3<f64>)> = pairs
                    .moving_links()
                    .map(|link| (link, collision.model.sphere_centre(link)))
                    .collect();
                BatchPlacements::new(model, &links, &motion, scene.q, scene.data, &centres)
            });
            let pairs = pairs.map(|(_, pairs)| pairs);
            Some(ArmJob {
                arm,
                chain,
                approach,
                approach_source,
                moving_links,
                placements,
                pairs,
            })
        })
        .collect();
    if jobs.is_empty() {
        return not_applicable(scene, options, "no arm has a joint that moves".to_string());
    }
    let chunks = options.samples.div_ceil(CHUNK);
    let contexts: Vec<SampleContext> = jobs
        .iter()
        .map(|job| SampleContext {
            scene,
            options,
            matcher: options
                .orientation
                .map(|o| o.matcher(&job.approach, tolerance)),
            collision: collision.map(|c| &c.model),
            nearest: SharedMinimum::new(),
        })
        .collect();
    // Arms whose sampling inputs match a run kept in the memo take its statistics.
    let keys: Vec<Option<u64>> = match &options.memo {
        Some(_) => {
            let collision_print = collision.map(|c| {
                let mut print = Fingerprint::new("collision model");
                c.model.fingerprint(&mut print);
                print.finish()
            });
            jobs.iter()
                .map(|job| Some(sampling_fingerprint(scene, job, collision_print, options)))
                .collect()
        }
        None => vec![None; jobs.len()],
    };
    let mut per_arm: Vec<Option<ArmStats>> = keys
        .iter()
        .map(|key| Option::zip(options.memo.as_ref(), *key).and_then(|(m, k)| m.take(k)))
        .collect();
    let to_sample: Vec<usize> = (0..jobs.len()).filter(|&a| per_arm[a].is_none()).collect();
    if !to_sample.is_empty() {
        wait_for_sampling(options);
    }
    // Every arm's chunks in one parallel loop (no thread waits for the last chunk of one arm before the
    // next arm starts), merged as they finish into one statistics value per arm.
    let sampled = (0..to_sample.len() * chunks)
        .into_par_iter()
        .map(|k| {
            let arm = to_sample[k / chunks];
            vec![(
                arm,
                sample_chunk(&contexts[arm], &jobs[arm], arm, k % chunks),
            )]
        })
        .reduce(Vec::new, merge_runs);
    let whole = !is_cancelled(options);
    for (arm, stats) in sampled {
        if let (Some(memo), Some(key), true) = (&options.memo, keys[arm], whole) {
            memo.keep(key, stats.clone());
        }
        per_arm[arm] = Some(stats);
    }
    let per_arm: Vec<ArmStats> = per_arm
        .into_iter()
        .map(|stats| stats.unwrap_or_else(ArmStats::new))
        .collect();
    summarize(scene, &jobs, &per_arm, collision, options)
}

/// Wait until [`WorkspaceOptions::sample_from`], or until the run is cancelled.
fn wait_for_sampling(options: &WorkspaceOptions) {
    const STEP: Duration = Duration::from_millis(2);
    let Some(from) = options.sample_from else {
        return;
    };
    while !is_cancelled(options) {
        let left = from.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return;
        }
        std::thread::sleep(left.min(STEP));
    }
}

/// Whether the run was cancelled (sampling then stops, and its statistics are partial).
fn is_cancelled(options: &WorkspaceOptions) -> bool {
    options
        .progress
        .as_ref()
        .is_some_and(Progress::is_cancelled)
}

/// A fingerprint of everything sampling `job`'s arm reads: the options, the ground, the pose, the
/// placements at the pose of the links it places (its path, the links of its self-collision pairs and the
/// moving links above them), the joints that move them, the collision model (`collision`, its
/// fingerprint) and the link names (the statistics name links by index). Masses,
/// efforts and everything else the sampling does not read are left out, so editing them keeps the arm.
fn sampling_fingerprint(
    scene: &Scene,
    job: &ArmJob,
    collision: Option<u64>,
    options: &WorkspaceOptions,
) -> u64 {
    let (robot, model, arm) = (scene.robot, scene.model, job.arm);
    let mut print = Fingerprint::new("workspace arm sampling");
    print
        .value(options.samples)
        .value(options.seed)
        .value(format!("{:?} {:?}", options.task, options.orientation))
        .float(options.orientation_tolerance_deg)
        .value(
            options
                .approach_axis
                .map(|a| [a.x, a.y, a.z].map(f64::to_bits)),
        )
        .float(scene.ground)
        .floats(scene.q)
        .value(model.up.as_str())
        .value(collision);
    print.value(robot.links.len());
    for link in &robot.links {
        print.value(&link.name.value);
    }
    print
        .value((
            arm.base,
            arm.tip,
            &arm.path,
            arm.hand,
            &arm.fingers,
            arm.declared,
        ))
        .vector(&job.approach);
    // The links sampling places: the arm's path, its self-collision pairs' links and the moving links
    // above them (a moved frame without geometry that no pair reaches is never read).
    let mut links: Vec<LinkId> = vec![arm.base];
    for joint in &arm.path {
        links.extend(
            model.joint_links[joint.0]
                .iter()
                .flat_map(|(p, c)| [*p, *c]),
        );
    }
    if let Some(pairs) = &job.pairs {
        links.extend(pairs.links());
        links.extend(links_to_place(model, &job.moving_links, pairs));
    }
    links.sort_unstable();
    links.dedup();
    for &link in &links {
        if let Some(placement) = scene.data.link_placement.get(link.0) {
            print.value(link).placement(placement);
        }
    }
    // The joints that move them, and the arm's own.
    let moving: std::collections::HashSet<LinkId> = job.moving_links.iter().copied().collect();
    let mut joints: Vec<JointId> = links
        .iter()
        .filter(|link| moving.contains(link))
        .filter_map(|link| model.parent_joint[link.0])
        .chain(arm.path.iter().copied())
        .collect();
    joints.sort_unstable();
    joints.dedup();
    for joint in joints {
        let index = joint.0;
        let data = &model.joint_data[index];
        print
            .value((joint, model.joint_links[index], data.kind.as_str()))
            .placement(&data.placement)
            .vector(&data.axis)
            .optional(data.lower)
            .optional(data.upper)
            .value(model.independent_leader[index].0)
            .float(model.independent_leader[index].1);
        match &model.mimic[index] {
            Some(mimic) => print
                .value(mimic.leader)
                .float(mimic.multiplier)
                .float(mimic.offset),
            None => print.value(0u8),
        };
    }
    print.finish()
}

/// `known` (the largest horizontal distance so far), raised to `offset`'s horizontal distance when that is
/// larger. `hypot` (exact to the last bit, and slow) runs only where the sum of the squares, within a few
/// rounding errors of the square of the distance, leaves it a chance (above 1e-100 m, where no square is
/// subnormal).
fn raise_horizontal(known: f64, offset: &Vector3<f64>) -> f64 {
    let squared = offset.x * offset.x + offset.y * offset.y;
    if known > 1e-100 && squared < known * known * (1.0 - 1e-9) {
        known
    } else {
        known.max(offset.x.hypot(offset.y))
    }
}

/// Two runs of consecutive chunks' statistics, each a list of (arm, statistics) in arm order, as one:
/// the arm where they meet is merged. Associative, so a parallel reduction gives one entry per arm.
fn merge_runs(
    mut left: Vec<(usize, ArmStats)>,
    right: Vec<(usize, ArmStats)>,
) -> Vec<(usize, ArmStats)> {
    let mut right = right.into_iter();
    match (left.last_mut(), right.next()) {
        (Some((last_arm, last)), Some((arm, stats))) if *last_arm == arm => {
            *last = std::mem::replace(last, ArmStats::new()).merge(stats);
        }
        (_, Some(first)) => left.push(first),
        (_, None) => {}
    }
    left.extend(right);
    left
}

fn fraction(part: usize, whole: usize) -> Option<f64> {
    (whole > 0).then(|| part as f64 / whole as f64)
}

fn summarize(
    scene: &Scene,
    jobs: &[ArmJob],
    per_arm: &[ArmStats],
    collision: Option<&CollisionSetup>,
    options: &WorkspaceOptions,
) -> WorkspaceSection {
    let robot = scene.robot;
    let model = scene.model;
    let target = options.task.map(|task| task.height(scene.ground));
    let mut arms = Vec::new();
    for (job, stats) in jobs.iter().zip(per_arm) {
        let link_name = |l: LinkId| robot.links[l.0].name.value.clone();
        let checked = job.pairs.as_ref().is_some_and(|p| !p.is_empty());
        arms.push(ArmWorkspace {
            root_link: link_name(job.arm.base),
            tip_link: link_name(job.arm.tip),
            first_joint: job
                .arm
                .first_joint(model)
                .map(|j| robot.joints[j.0].name.value.clone()),
            joints: job
                .chain
                .sampled
                .iter()
                .map(|(j, _, _)| robot.joints[j.0].name.value.clone())
                .collect(),
            body_joints_held: body_joints(model, job.arm.base)
                .into_iter()
                .map(|j| format!("{}={:.3}", robot.joints[j.0].name.value, scene.q[j.0]))
                .collect(),
            confidence: if job.arm.declared {
                Confidence::Exact
            } else {
                Confidence::Estimated
            },
            hand_link: job.arm.hand.map(link_name),
            approach_axis: [job.approach.x, job.approach.y, job.approach.z],
            approach_axis_source: job.approach_source.to_string(),
            max_reach: stats.max_reach,
            vertical_reach: stats.max_height,
            lowest_tip_height: stats.min_height,
            horizontal_reach: stats.max_horizontal,
            reach_from_base: stats.max_from_base,
            task_height_reachable: target.map(|h| {
                stats
                    .feasible_heights
                    .is_some_and(|(lo, hi)| lo <= h && h <= hi)
            }),
            task_band_samples: target.map(|_| stats.band_samples),
            orientation_fraction: options
                .orientation
                .and_then(|_| fraction(stats.orientation_ok, stats.orientation_considered)),
            self_collision_free_fraction: checked
                .then(|| fraction(stats.collision_free, stats.samples))
                .flatten(),
            self_collision_min_clearance_mm: checked
                .then(|| stats.min_clearance.map(|c| clearance_mm(c.0)))
                .flatten(),
            tip_samples: stats.tips.iter().map(|(_, p)| *p).collect(),
        });
    }
    let max = |f: fn(&ArmWorkspace) -> f64| arms.iter().map(f).reduce(f64::max);
    let mut status = Status::Pass;
    let mut reasons = Vec::new();

    // Task: reachable by some arm; COM at the furthest horizontal reach at that height.
    let task_height_reachable =
        target.map(|_| arms.iter().any(|a| a.task_height_reachable == Some(true)));
    let (mut com_stable, mut com_shift, mut com_margin, mut com_note) = (None, None, None, None);
    let mut com_worst = None;
    if let (Some(task), Some(reachable)) = (options.task, task_height_reachable) {
        if !reachable {
            status = status.worst(Status::Fail);
            let held = body_joints_held(&arms);
            // Sampled extremes approach the true ones from inside: a target just beyond them may be
            // reachable by a pose no sample drew.
            let gap = per_arm
                .iter()
                .filter_map(|stats| stats.feasible_heights)
                .map(|(lo, hi)| {
                    let h = task.height(scene.ground);
                    if h > hi {
                        h - hi
                    } else {
                        lo - h
                    }
                })
                .reduce(f64::min);
            let reach = arms.iter().map(|a| a.max_reach).fold(0.0, f64::max);
            let near = gap.filter(|&gap| gap < NEAR_ENVELOPE * reach);
            reasons.push(format!(
                "no arm reaches the {} height ({:.2} m above the ground){}{}",
                task.name(),
                task.height(scene.ground),
                if held.is_empty() {
                    String::new()
                } else {
                    format!(" with the body held at {}", held.join(", "))
                },
                near.map_or(String::new(), |gap| format!(
                    " (the nearest sampled tip is {:.0} mm away, within sampling error: more --samples may reach it)",
                    gap * 1000.0
                ))
            ));
        }
        let best = jobs
            .iter()
            .zip(per_arm)
            .filter_map(|(job, stats)| stats.band_best.as_ref().map(|b| (job, b)))
            .max_by(|a, b| a.1 .0.total_cmp(&b.1 .0));
        com_note = match (&best, scene.support_polygon.is_empty()) {
            (_, true) => Some(
                "no support polygon (a fixed base, or stability could not be computed)".to_string(),
            ),
            (None, false) => Some(format!(
                "no sampled pose within {:.0} cm of the height",
                TASK_BAND * 100.0
            )),
            _ => None,
        };
        if let (Some((job, (_, _, q_arm))), false) = (best, scene.support_polygon.is_empty()) {
            let com = com_at(scene, job, q_arm);
            if com.is_none() {
                com_note = Some("no centre of mass (no declared mass)".to_string());
            }
            if let Some((stable, shift, margin_mm)) = com {
                com_stable = Some(stable);
                com_shift = Some(shift);
                com_margin = Some(margin_mm);
                if !stable {
                    status = status.worst(Status::Fail);
                    reasons.push(format!(
                        "the robot tips over while reaching for the {} height (COM {:.1} mm outside the support polygon)",
                        task.name(),
                        -margin_mm
                    ));
                }
            }
            // The furthest pose is one heading; the worst over every pose at that height is stable
            // from seed to seed and catches headings over a short edge of the polygon.
            let mut probe = ComProbe::new(scene);
            com_worst = jobs
                .iter()
                .zip(per_arm)
                .flat_map(|(job, stats)| stats.band_poses.iter().map(move |(_, q)| (job, q)))
                .filter_map(|(job, q_arm)| probe.margin(job, q_arm))
                .reduce(f64::min)
                .map(|worst| worst * 1000.0);
            if let (Some(worst), Some(true)) = (com_worst, com_stable) {
                if worst < 0.0 {
                    status = status.worst(Status::Warn);
                    reasons.push(format!(
                        "some sampled poses at the {} height tip the robot over (worst: COM {:.1} mm outside the support polygon)",
                        task.name(),
                        -worst
                    ));
                }
            }
        }
    }

    // Orientation: the best arm's fraction.
    let orientation_fraction = arms
        .iter()
        .filter_map(|a| a.orientation_fraction)
        .reduce(f64::max);
    // No fraction: no sampled pose at the task height, so the orientation was not assessed.
    let orientation_reachable = options
        .orientation
        .and(orientation_fraction)
        .map(|f| f >= ORIENTATION_PASS_FRACTION);
    if orientation_reachable == Some(false) {
        status = status.worst(Status::Warn);
        reasons.push(format!(
            "orientation {} is met by {:.1}% of samples (< {:.0}%)",
            options.orientation.map(|o| o.label()).unwrap_or_default(),
            orientation_fraction.unwrap_or_default() * 100.0,
            ORIENTATION_PASS_FRACTION * 100.0
        ));
    }

    // Self-collision over every arm's samples.
    let checked: Vec<&ArmStats> = jobs
        .iter()
        .zip(per_arm)
        .filter(|(job, _)| job.pairs.as_ref().is_some_and(|p| !p.is_empty()))
        .map(|(_, s)| s)
        .collect();
    let total: usize = checked.iter().map(|s| s.samples).sum();
    let free: usize = checked.iter().map(|s| s.collision_free).sum();
    let free_fraction = fraction(free, total);
    let mut colliding: HashMap<(LinkId, LinkId), usize> = HashMap::new();
    for stats in &checked {
        for (pair, count) in &stats.colliding {
            *colliding.entry(*pair).or_default() += count;
        }
    }
    let min_clearance = checked
        .iter()
        .filter_map(|s| s.min_clearance)
        .min_by(|a, b| a.0.total_cmp(&b.0));
    let worst_pair = colliding
        .iter()
        .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0)))
        .map(|(pair, _)| *pair)
        .or(min_clearance.map(|c| c.1));
    if let Some(f) = free_fraction.filter(|f| *f < COLLISION_FREE_PASS_FRACTION) {
        status = status.worst(Status::Warn);
        reasons.push(format!(
            "{:.1}% of sampled poses are free of self-collision (< {:.0}%){}",
            f * 100.0,
            COLLISION_FREE_PASS_FRACTION * 100.0,
            worst_pair.map_or(String::new(), |p| {
                let [a, b] = names(robot, p);
                format!("; most often {a} × {b}")
            })
        ));
    }
    WorkspaceSection {
        status,
        max_reach: max(|a| a.max_reach),
        vertical_reach: max(|a| a.vertical_reach),
        horizontal_reach: max(|a| a.horizontal_reach),
        reach_from_base: max(|a| a.reach_from_base),
        reach_confidence: Confidence::Estimated,
        samples: options.samples,
        seed: options.seed,
        arms,
        task: options.task.map(|t| t.name().to_string()),
        task_target_height_m: target,
        task_height_reachable,
        task_com_stable_during_reach: com_stable,
        task_com_shift_estimate_m: com_shift,
        task_com_margin_mm: com_margin,
        task_com_worst_margin_mm: com_worst,
        task_com_not_assessed: com_note,
        orientation: options.orientation.map(|o| o.label()),
        orientation_reachable,
        orientation_fraction,
        orientation_tolerance_deg: options.orientation_tolerance_deg,
        self_collision_free_fraction: free_fraction,
        self_collision_min_clearance_mm: min_clearance.map(|c| clearance_mm(c.0)),
        self_collision_worst_pair: worst_pair.map(|p| names(robot, p)),
        self_collision_touching_at_reference: collision
            .map(|c| c.touching.iter().map(|&p| names(robot, p)).collect())
            .unwrap_or_default(),
        self_collision_srdf_disabled: collision.map_or(0, |c| c.srdf_disabled),
        self_collision_not_assessed: checked
            .is_empty()
            .then(|| collision_not_assessed(robot, jobs, collision)),
        reason: (!reasons.is_empty()).then(|| reasons.join("; ")),
    }
}

/// The independent actuated joints from the robot's root down to `link`, root first.
fn body_joints(model: &Model, link: LinkId) -> Vec<JointId> {
    let mut joints: Vec<JointId> = model
        .joints_to_root(link)
        .into_iter()
        .filter(|j| model.joint_data[j.0].is_actuated() && model.mimic[j.0].is_none())
        .collect();
    joints.reverse();
    joints
}

/// Why no pair was checked for self-collision.
fn collision_not_assessed(
    robot: &Robot,
    jobs: &[ArmJob],
    collision: Option<&CollisionSetup>,
) -> String {
    let Some(collision) = collision else {
        return format!(
            "the robot has more than {} links (a limit that bounds self-collision's time and memory)",
            crate::analysis::collision::MAX_COLLISION_LINKS
        );
    };
    let mut moved: Vec<LinkId> = jobs
        .iter()
        .flat_map(|j| j.moving_links.iter().copied())
        .collect();
    moved.sort_unstable();
    moved.dedup();
    let without: Vec<LinkId> = moved
        .iter()
        .copied()
        .filter(|&l| !collision.model.has_geometry(l))
        .collect();
    let unusable: Vec<&str> = without
        .iter()
        .map(|l| &robot.links[l.0])
        .filter(|link| !link.collisions.is_empty())
        .map(|link| link.name.value.as_str())
        .collect();
    if !unusable.is_empty() {
        let shown: Vec<&str> = unusable.iter().copied().take(4).collect();
        format!(
            "{} of the {} links the arms move have <collision> geometry that could not be used (meshes not found or unreadable, or shapes of a millimetre or less): {}{}",
            unusable.len(),
            moved.len(),
            shown.join(", "),
            if unusable.len() > shown.len() { ", …" } else { "" }
        )
    } else if without.len() == moved.len() {
        "the links the arms move have no <collision> geometry".to_string()
    } else {
        "no pair the arms move can collide (adjacent, rigidly attached, allowed by the SRDF or in contact at the zero pose)".to_string()
    }
}

/// Whole-body COM, with the payload, at the reference pose with an arm moved: one scratch reused over
/// many poses.
struct ComProbe<'a> {
    scene: &'a Scene<'a>,
    q: Configuration,
    statics: StaticsData,
}

impl<'a> ComProbe<'a> {
    fn new(scene: &'a Scene<'a>) -> Self {
        ComProbe {
            scene,
            q: scene.q.to_vec(),
            statics: StaticsData::new(scene.model),
        }
    }

    /// The COM with `job`'s arm at `q_arm` (`None`: the arm at the reference pose).
    fn com(&mut self, job: &ArmJob, q_arm: Option<&[f64]>) -> Option<Vector3<f64>> {
        let (scene, model) = (self.scene, self.scene.model);
        self.q.copy_from_slice(scene.q);
        if let Some(q_arm) = q_arm {
            for (value, (joint, _, _)) in q_arm.iter().zip(&job.chain.sampled) {
                self.q[joint.0] = *value;
            }
            model.apply_mimic(&mut self.q);
        }
        evaluate(model, &self.q, &mut self.statics);
        let (mass, com) = mass_and_com(model, &self.statics);
        let com = com?;
        let Some((load, link)) = scene.payload else {
            return Some(com);
        };
        let at = self.statics.kinematics.link_placement[link.unwrap_or(job.arm.tip).0].translation;
        Some((com * mass + at.vector * load) / (mass + load))
    }

    /// The support-polygon margin of the COM with `job`'s arm at `q_arm`, metres.
    fn margin(&mut self, job: &ArmJob, q_arm: &[f64]) -> Option<f64> {
        let com = self.com(job, Some(q_arm))?;
        Some(margin(self.scene.support_polygon, [com.x, com.y])?.distance)
    }
}

/// Whole-body COM, with the payload, at the reference pose with `job`'s arm at `q_arm`: (over the polygon,
/// horizontal shift from the reference COM in metres, margin in mm).
fn com_at(scene: &Scene, job: &ArmJob, q_arm: &[f64]) -> Option<(bool, f64, f64)> {
    let mut probe = ComProbe::new(scene);
    let reference_com = probe.com(job, None)?;
    let com = probe.com(job, Some(q_arm))?;
    let m = margin(scene.support_polygon, [com.x, com.y])?;
    let shift = (com.xy() - reference_com.xy()).norm();
    Some((m.distance >= 0.0, shift, m.distance * 1000.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Raising the largest horizontal distance skips `hypot` only where it could not raise it: the same
    /// bits as `known.max(hypot)` for distances a hair either side of the known one (the ulps where a
    /// skip on the sum of squares alone would go wrong), far below and above it, at every scale, and
    /// for infinite, NaN, subnormal and zero values.
    #[test]
    fn raising_the_horizontal_distance_skips_only_what_cannot_raise_it() {
        let mut rng = SplitMix64::new(7);
        let scales = [1e-300, 1e-160, 1e-100, 1e-3, 1.0, 1e3, 1e150, 1e300];
        let specials = [0.0, -0.0, f64::MIN_POSITIVE / 8.0, f64::INFINITY, f64::NAN];
        let mut skipped = 0;
        for round in 0..200_000 {
            let scale = scales[round % scales.len()];
            let angle = rng.uniform(0.0, std::f64::consts::TAU);
            let known = match round % 11 {
                0 => f64::NEG_INFINITY,
                1 => specials[(round / 11) % specials.len()],
                _ => scale * rng.uniform(0.1, 10.0),
            };
            let length = match round % 5 {
                // A few ulps either side of the known distance.
                0 | 1 => {
                    known * (1.0 + (rng.next_u64() % 9) as f64 * f64::EPSILON - 4.0 * f64::EPSILON)
                }
                2 => specials[(round / 5) % specials.len()],
                _ => scale * rng.uniform(0.0, 10.0),
            };
            let offset = Vector3::new(
                length * angle.cos(),
                length * angle.sin(),
                rng.uniform(-1.0, 1.0),
            );
            let expected = known.max(offset.x.hypot(offset.y));
            let raised = raise_horizontal(known, &offset);
            assert_eq!(
                raised.to_bits(),
                expected.to_bits(),
                "known {known:e}, offset {offset:?}"
            );
            skipped += usize::from(known > 1e-100 && raised.to_bits() == known.to_bits());
        }
        assert!(skipped > 10_000, "the shortcut was taken {skipped} times");
    }

    /// Offered from four threads at once, the shared minimum is the smallest non-negative value offered
    /// (zero, subnormal and infinite values included; negative ones and NaN ignored).
    #[test]
    fn the_shared_minimum_is_the_smallest_value_offered() {
        let shared = SharedMinimum::new();
        assert_eq!(shared.get(), f64::INFINITY);
        let values = |thread: u64| {
            let mut rng = SplitMix64::new(thread);
            (0..2000).map(move |k| match k % 7 {
                0 => -rng.uniform(0.0, 1.0),
                1 => f64::NAN,
                2 => f64::INFINITY,
                3 => f64::MIN_POSITIVE / 4.0 * (1.0 + thread as f64),
                _ => rng.uniform(1e-6, 1.0),
            })
        };
        std::thread::scope(|scope| {
            for thread in 0..4 {
                let shared = &shared;
                scope.spawn(move || values(thread).for_each(|v| shared.offer(v)));
            }
        });
        assert_eq!(shared.get(), f64::MIN_POSITIVE / 4.0);
        shared.offer(0.0);
        assert_eq!(shared.get(), 0.0);
        shared.offer(-0.0);
        assert_eq!(shared.get().to_bits(), 0.0f64.to_bits());
    }

    #[test]
    fn clearances_are_reported_to_the_micrometre() {
        assert_eq!(clearance_mm(3.313_386_979_314_514e-6), 0.003);
        assert_eq!(clearance_mm(0.012_345_6), 12.346);
        assert_eq!(clearance_mm(0.0), 0.0);
    }

    /// Statistics of one chunk of `samples` samples reaching `reach`.
    fn chunk(samples: usize, reach: f64) -> ArmStats {
        ArmStats {
            samples,
            max_reach: reach,
            ..ArmStats::new()
        }
    }

    #[test]
    fn runs_merge_into_one_entry_per_arm_whatever_the_grouping() {
        let chunks = || {
            vec![
                vec![(0, chunk(1, 0.1))],
                vec![(0, chunk(2, 0.3))],
                vec![(1, chunk(4, 0.2))],
                vec![(1, chunk(8, 0.5))],
                vec![(2, chunk(16, 0.4))],
            ]
        };
        let summary = |runs: Vec<(usize, ArmStats)>| -> Vec<(usize, usize, f64)> {
            runs.into_iter()
                .map(|(arm, s)| (arm, s.samples, s.max_reach))
                .collect()
        };
        let expected = vec![(0, 3, 0.3), (1, 12, 0.5), (2, 16, 0.4)];
        let left_to_right = chunks().into_iter().fold(Vec::new(), merge_runs);
        assert_eq!(summary(left_to_right), expected);
        // ((c0 c1) (c2 (c3 c4))), as a parallel reduction may group them.
        let mut c = chunks().into_iter();
        let mut next = || c.next().unwrap();
        let (c0, c1, c2, c3, c4) = (next(), next(), next(), next(), next());
        let grouped = merge_runs(merge_runs(c0, c1), merge_runs(c2, merge_runs(c3, c4)));
        assert_eq!(summary(grouped), expected);
        assert!(merge_runs(Vec::new(), Vec::new()).is_empty());
    }
}
