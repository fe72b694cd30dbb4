//! Self-collision with real geometry: every link's collision shapes (primitives exactly, meshes as their
//! convex hulls), an allowed-collision matrix built as MoveIt's setup assistant builds it, and a per-pose
//! check with a bounding-sphere broad phase and a GJK narrow phase.
//!
//! Use from a sampling loop:
//!
//! ```no_run
//! # use urdf_validator::{analysis::collision::*, model::*, urdf::Robot};
//! # fn run(robot: &Robot, model: &Model, arm_joints: &[JointId], samples: &[Vec<f64>],
//! #        supports: &[urdf_validator::assets::LinkSupports]) {
//! let mut collision = CollisionModel::build(robot, model, supports);
//! // Reference pose: pairs already in contact are reported, then no longer checked.
//! let mut data = Data::new(model);
//! forward_kinematics(model, &model.zero_configuration(), &mut data);
//! let touching = collision.touching_pairs(&data.link_placement);
//! collision.allow(&touching, Allowed::Touching);
//! let pairs = collision.pairs_moved_by(&model.motion_of(arm_joints));
//! let mut scratch = CheckScratch::new(&collision);
//! let (mut free, mut clearance) = (0, f64::INFINITY);
//! for q in samples {
//!     forward_kinematics(model, q, &mut data);
//!     let check = collision.check(&pairs, &data.link_placement, clearance, &mut scratch);
//!     if check.is_free() {
//!         free += 1;
//!     }
//!     if let Some((distance, _pair)) = check.min_clearance {
//!         clearance = distance;
//!     }
//! }
//! # }
//! ```
//!
//! [`CollisionModel`] is immutable during checks and `Sync`; each thread keeps its own [`CheckScratch`]
//! (with rayon: `map_init`).

mod enclose;
mod held;
mod inside;
mod shape;

use std::collections::HashSet;
use std::ops::Range;

use nalgebra::{Isometry3, Matrix3, Point3, Vector3};
use parry3d_f64::math::Pose;
use parry3d_f64::query::gjk::VoronoiSimplex;
use rayon::prelude::*;

use crate::assets::LinkSupports;
use crate::input::srdf::{SrdfCollisions, SrdfPair};
use crate::model::{JointId, LinkId, Model, Motion};
use crate::urdf::robot::Robot;

pub use shape::{CONTACT_DISTANCE, MAX_EXTENT};

/// Where every link is in the world for a check, by link: a slice of placements indexed by link (as
/// [`crate::model::kinematics::Data::link_placement`]) is one. A check reads the placements of the links
/// its tests reach, each at most a few times, so a sampler can hand a view that assembles them on demand.
pub trait LinkPlacements {
    /// The placement of `link`; `None` when there is none.
    fn placement(&self, link: LinkId) -> Option<Isometry3<f64>>;
}

impl LinkPlacements for [Isometry3<f64>] {
    #[inline]
    fn placement(&self, link: LinkId) -> Option<Isometry3<f64>> {
        self.get(link.0).copied()
    }
}

impl LinkPlacements for Vec<Isometry3<f64>> {
    #[inline]
    fn placement(&self, link: LinkId) -> Option<Isometry3<f64>> {
        self.as_slice().placement(link)
    }
}

/// The most links a self-collision model is built for: the allowed-collision matrix and the pair lists
/// grow with the square of it (real robots have at most a few hundred links; a generated 6,000-link
/// chain took minutes and gigabytes).
pub const MAX_COLLISION_LINKS: usize = 1024;

use held::{set_bits, HeldBroad, HeldSpheres};
use shape::{
    boxes_apart, enclosing_sphere, proximity, to_pose, ConvexShape, PairMemory, Proximity,
};

/// Why a pair of links is never checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Allowed {
    /// Joined by a joint (possibly through links without collision geometry).
    Adjacent,
    /// No actuated joint between them: their relative placement never changes.
    Rigid,
    /// Allowed by an SRDF: a `<disable_collisions>` pair, or a `<disable_default_collisions>` link's pair
    /// that no `<enable_collisions>` names.
    Disabled,
    /// In contact at the reference pose (see [`CollisionModel::touching_pairs`]).
    Touching,
}

/// The collision geometry of a robot and its allowed-collision matrix.
#[derive(Clone, Debug)]
pub struct CollisionModel {
    shapes: Vec<ConvexShape>,
    /// Per shape: the index of its link's collision it was built from.
    sources: Vec<usize>,
    /// Per link: its shapes in `shapes` and a sphere around them (centre in the link frame, radius).
    bodies: Vec<Body>,
    /// Links with at least one shape, in index order.
    geometric: Vec<LinkId>,
    /// Row-major `links × links`, symmetric.
    allowed: Vec<Option<Allowed>>,
    /// Per link: the joint to its parent and the parent.
    parent: Vec<Option<(JointId, LinkId)>>,
    /// Per link: joints between it and its root.
    depth: Vec<usize>,
}

#[derive(Clone, Debug)]
struct Body {
    shapes: Range<usize>,
    centre: Vector3<f64>,
    radius: f64,
}

/// Link pairs to check in every pose (none of them allowed to collide).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PairSet {
    pairs: Vec<(LinkId, LinkId)>,
    /// Every link of `pairs`, once, sorted: the link of each slot.
    links: Vec<LinkId>,
    /// The slots whose links the set's joints move (every slot when the set has no joints).
    moving: Vec<u32>,
    /// Per slot: whether its link moves (is in `moving`).
    slot_moves: Vec<bool>,
    /// Per pair: the slots of its links and the sum of their bounding radii (the broad phase reads only
    /// this, from memory laid out in pair order).
    broad: Vec<(u32, u32, f64)>,
    /// For sets with many pairs per link (long chains): a sweep-and-prune index, so a pose costs about
    /// the number of nearby pairs instead of every pair.
    sweep: Option<SweepIndex>,
    /// For checks that hold the links the set's joints do not move ([`CheckScratch::holding_fixed`]):
    /// the moving links' rigid groups, whose spheres stand for their pairs.
    held: Option<HeldBroad>,
}

/// Pair sets with more pairs than this per link use the sweep-and-prune broad phase (below it, scanning
/// every pair is as fast).
const SWEEP_FROM_PAIRS_PER_LINK: usize = 64;

/// With the sweep, the first `SWEEP_AFTER_LINKS × links` pairs are still scanned one by one first.
const SWEEP_AFTER_LINKS: usize = 4;

/// Slack added to every sweep interval, metres: the sweep only preselects pairs (each is tested exactly
/// afterwards), so a margin that is too large changes nothing but a little time.
const SWEEP_SLACK: f64 = 1e-6;

/// What sweep-and-prune needs of a [`PairSet`]: each slot's bounding radius and, for each pair of slots,
/// its index in the set.
#[derive(Clone, Debug, PartialEq)]
struct SweepIndex {
    radius: Vec<f64>,
    /// `pair_of[a * slots + b]` (a < b): the pair's index, `u32::MAX` when the set does not hold it.
    pair_of: Vec<u32>,
}

impl SweepIndex {
    fn new(broad: &[(u32, u32, f64)], radius: Vec<f64>) -> SweepIndex {
        let slots = radius.len();
        let mut pair_of = vec![u32::MAX; slots * slots];
        for (index, &(a, b, _)) in broad.iter().enumerate() {
            let (a, b) = (a.min(b) as usize, a.max(b) as usize);
            pair_of[a * slots + b] = index as u32;
        }
        SweepIndex { radius, pair_of }
    }

    /// Into `scratch.candidates`, in increasing order: the index of every pair whose bounding spheres,
    /// grown by `margin`, may overlap (a superset of those that do), with every slot's centre at `centre`.
    fn candidates(&self, centre: &[Vector3<f64>], margin: f64, scratch: &mut SweepScratch) {
        let slots = self.radius.len();
        let (mut low, mut high) = (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        );
        for c in centre {
            low = low.inf(c);
            high = high.sup(c);
        }
        // Sweep along the axis the links spread most along.
        let axis = (high - low).imax();
        scratch.intervals.clear();
        scratch
            .intervals
            .extend(centre.iter().enumerate().map(|(slot, c)| {
                let grown = self.radius[slot] + margin / 2.0 + SWEEP_SLACK;
                (c[axis] - grown, c[axis] + grown, slot as u32)
            }));
        scratch
            .intervals
            .sort_unstable_by(|p, q| p.0.total_cmp(&q.0));
        scratch.candidates.clear();
        scratch.active.clear();
        for &(start, end, slot) in &scratch.intervals {
            scratch.active.retain(|&(other_end, _)| other_end > start);
            for &(_, other) in &scratch.active {
                let (a, b) = (slot.min(other) as usize, slot.max(other) as usize);
                let index = self.pair_of[a * slots + b];
                if index != u32::MAX {
                    scratch.candidates.push(index);
                }
            }
            scratch.active.push((end, slot));
        }
        scratch.candidates.sort_unstable();
    }
}

/// Where a pose's scan over its pairs stands.
struct Scan {
    /// Pairs further apart than this are not looked at (the nearest clearance so far).
    margin: f64,
    /// The nearest pair so far and its distance.
    nearest: Option<(f64, (LinkId, LinkId))>,
    /// Some pair is in contact.
    in_contact: bool,
}

/// Per-thread buffers of the sweep.
#[derive(Clone, Debug, Default)]
struct SweepScratch {
    intervals: Vec<(f64, f64, u32)>,
    active: Vec<(f64, u32)>,
    candidates: Vec<u32>,
}

impl PairSet {
    /// Every link of the set's pairs, once, sorted.
    pub fn links(&self) -> &[LinkId] {
        &self.links
    }

    /// The pairs, each with the lower link index first.
    pub fn pairs(&self) -> &[(LinkId, LinkId)] {
        &self.pairs
    }

    /// The links of the set the set's joints move, in slot order (the order in which a caller that
    /// places them hands their bounding-sphere centres to the check).
    pub fn moving_links(&self) -> impl Iterator<Item = LinkId> + '_ {
        self.moving.iter().map(|&slot| self.links[slot as usize])
    }

    /// Number of pairs.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// True when there is nothing to check.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }
}

/// The outcome of checking one pose.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PoseCheck {
    /// The first pair (in [`PairSet`] order) in contact: overlapping or closer than
    /// [`CONTACT_DISTANCE`].
    pub contact: Option<(LinkId, LinkId)>,
    /// When no pair is in contact: the smallest distance (metres) between the links of a pair and that
    /// pair, if it is below the `clearance_cutoff` given to [`CollisionModel::check`].
    pub min_clearance: Option<(f64, (LinkId, LinkId))>,
    /// Pairs not checked because a link's placement is not finite (or absurdly far away).
    pub skipped: usize,
}

impl PoseCheck {
    /// True when no pair is in contact.
    pub fn is_free(&self) -> bool {
        self.contact.is_none()
    }
}

/// Per-thread working memory of [`CollisionModel::check`].
#[derive(Clone, Debug)]
pub struct CheckScratch {
    /// Per slot of the pair set: the world centre of its link's bounding sphere; NaN when the link's
    /// placement is not usable.
    centre: Vec<Vector3<f64>>,
    /// Per slot: the pose its `centre` was computed in ([`HELD`]: a held slot's, kept). With the
    /// rigid-group broad phase a moving slot's centre is computed only when one of its pairs is looked at
    /// (unless the caller vouched for the centres, see [`CheckScratch::vouch_moving`]).
    centre_stamp: Vec<u32>,
    /// Per shape: where it is in the current pose, placed in stages as the tests reach them (most shapes
    /// go no further than the sphere test, most of the rest no further than the box test).
    placed: Vec<Placed>,
    /// Per link: its placement, read once per pose (once for all, for a link held in place) when a pair
    /// of it reaches the narrow phase, and the pose's stamp (see [`restamp`]).
    link_placed: Vec<(u32, Isometry3<f64>)>,
    stamp: u32,
    /// Per pair of the last pair set: what the narrow phase keeps of it (see [`shape::proximity`]).
    memory: Vec<PairMemory>,
    simplex: VoronoiSimplex,
    sweep: SweepScratch,
    /// With `hold_fixed`: the spheres of the pair set's [`HeldBroad`], and the pairs it keeps in the
    /// current pose.
    held_spheres: HeldSpheres,
    held_candidates: Vec<u64>,
    /// The links a pair set's joints do not move keep their placements between checks
    /// ([`CheckScratch::holding_fixed`]).
    hold_fixed: bool,
    /// With `hold_fixed`: `centre` holds every slot's centre from an earlier check, and whether every
    /// fixed slot's placement was usable.
    fixed_usable: Option<bool>,
    /// For the next check only: the caller checked that every moving link's placement is usable and put
    /// their bounding-sphere centres in `centre` (see [`CheckScratch::vouch_moving`]).
    moving_vouched: bool,
}

impl CheckScratch {
    /// Scratch sized for `model`.
    pub fn new(model: &CollisionModel) -> Self {
        CheckScratch {
            centre: Vec::new(),
            centre_stamp: Vec::new(),
            placed: vec![Placed::default(); model.shapes.len()],
            link_placed: vec![(0, Isometry3::identity()); model.bodies.len()],
            stamp: 0,
            memory: Vec::new(),
            simplex: VoronoiSimplex::new(),
            sweep: SweepScratch::default(),
            held_spheres: HeldSpheres::default(),
            held_candidates: Vec::new(),
            hold_fixed: false,
            fixed_usable: None,
            moving_vouched: false,
        }
    }

    /// Scratch for a sequence of checks of one pair set in which only the links its joints move change
    /// placement (a sampler varying those joints, every other link held): the bounding spheres and shape
    /// placements of the other links are computed at the first check and kept.
    pub fn holding_fixed(model: &CollisionModel) -> Self {
        CheckScratch {
            hold_fixed: true,
            ..CheckScratch::new(model)
        }
    }

    /// For the next check of `pairs` (checks holding the fixed links, after the first): every link the
    /// set's joints move has a usable placement ([`usable_parts`]), and `centres` are their bounding-sphere
    /// centres in the world, in [`PairSet::moving_links`] order, computed as the check computes them
    /// (the placement times [`CollisionModel::sphere_centre`], in nalgebra's order of operations: the
    /// same bits). The caller placed the links and checked; the check takes its word.
    pub(crate) fn vouch_moving(
        &mut self,
        pairs: &PairSet,
        centres: impl ExactSizeIterator<Item = Vector3<f64>>,
    ) {
        if !self.hold_fixed
            || self.centre.len() != pairs.links.len()
            || centres.len() != pairs.moving.len()
        {
            return;
        }
        for (&slot, centre) in pairs.moving.iter().zip(centres) {
            self.centre[slot as usize] = centre;
        }
        self.moving_vouched = true;
    }

    /// Read `link`'s placement for the current pose into [`CheckScratch::link_placed`] unless it is
    /// there (`held`: it stays in place between checks); false when `placements` has none.
    #[inline(always)]
    fn fetch_link<P: LinkPlacements + ?Sized>(
        &mut self,
        link: LinkId,
        held: bool,
        placements: &P,
    ) -> bool {
        let Some((stamp, placement)) = self.link_placed.get_mut(link.0) else {
            return false;
        };
        if restamp(stamp, self.stamp, held) {
            match placements.placement(link) {
                Some(found) => *placement = found,
                None => {
                    *stamp = 0;
                    return false;
                }
            }
        }
        true
    }

    /// Start a new pose: every cached shape placement becomes stale.
    fn next_pose(&mut self) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 || self.stamp == HELD {
            self.placed.iter_mut().for_each(Placed::forget);
            self.link_placed
                .iter_mut()
                .for_each(|(stamp, _)| *stamp = 0);
            self.centre_stamp
                .iter_mut()
                .filter(|s| **s != HELD)
                .for_each(|s| *s = 0);
            self.stamp = 1;
        }
    }
}

/// The stamp of a shape placement kept across poses (a link held in place, see
/// [`CheckScratch::holding_fixed`]).
const HELD: u32 = u32::MAX;

/// True when a placement stamped `stamp` is stale in the pose stamped `current` (one kept across poses
/// never is); it is then stamped as placed in that pose, or for every pose when its link is `held`.
fn restamp(stamp: &mut u32, current: u32, held: bool) -> bool {
    let stale = *stamp != current && *stamp != HELD;
    if stale {
        *stamp = if held { HELD } else { current };
    }
    stale
}

/// A shape in the world. Each part has the stamp of the pose it was placed in (see [`restamp`]).
#[derive(Clone, Copy, Debug)]
struct Placed {
    /// The bounding-sphere centre.
    centre: Vector3<f64>,
    centre_stamp: u32,
    /// The bounding box: centre and axes.
    obb: (Vector3<f64>, Matrix3<f64>),
    obb_stamp: u32,
    /// The shape frame, for the narrow phase.
    pose: Pose,
    pose_stamp: u32,
}

impl Placed {
    /// Every part stale.
    fn forget(&mut self) {
        (self.centre_stamp, self.obb_stamp, self.pose_stamp) = (0, 0, 0);
    }
}

impl Default for Placed {
    fn default() -> Self {
        Placed {
            centre: Vector3::zeros(),
            centre_stamp: 0,
            obb: (Vector3::zeros(), Matrix3::identity()),
            obb_stamp: 0,
            pose: Pose::IDENTITY,
            pose_stamp: 0,
        }
    }
}

/// True when a placement can be used: finite and within [`MAX_EXTENT`].
fn usable(placement: &Isometry3<f64>) -> bool {
    let (t, q) = (&placement.translation.vector, &placement.rotation.coords);
    usable_parts([t.x, t.y, t.z], [q.x, q.y, q.z, q.w])
}

/// [`usable`] on a placement's translation and rotation quaternion.
#[inline(always)]
pub(crate) fn usable_parts([x, y, z]: [f64; 3], [i, j, k, w]: [f64; 4]) -> bool {
    // Without short-circuits (the check runs for every moving link of every sampled pose): a NaN fails
    // each comparison, and a product by zero is zero exactly when the factor is finite.
    (x.abs() <= MAX_EXTENT)
        & (y.abs() <= MAX_EXTENT)
        & (z.abs() <= MAX_EXTENT)
        & (i * 0.0 + j * 0.0 + k * 0.0 + w * 0.0 == 0.0)
}

impl CollisionModel {
    /// The collision shapes of every link (`<collision>` elements only: primitives, and meshes as their
    /// convex hull), from the links' supports the assets stage built (`supports[link]`). Markers (≤ 1 mm)
    /// and unusable shapes are left out there. The allowed-collision matrix starts with the adjacent and
    /// rigidly attached pairs.
    pub fn build(robot: &Robot, model: &Model, supports: &[LinkSupports]) -> CollisionModel {
        let links = robot.links.len();
        // Each link's shapes (a mesh hull's edges and support map are built here), links in parallel.
        let per_link: Vec<Vec<(ConvexShape, usize)>> = robot
            .links
            .par_iter()
            .zip(supports)
            .map(|(link, link_supports)| {
                // Supports are the collisions, or the visuals when a link has none: only collisions
                // collide.
                if link.collisions.is_empty() {
                    return Vec::new();
                }
                link_supports
                    .shapes
                    .iter()
                    .zip(&link_supports.sources)
                    .filter_map(|(support, &source)| {
                        Some((ConvexShape::from_support(support)?, source))
                    })
                    .collect()
            })
            .collect();
        let mut shapes = Vec::new();
        let mut sources = Vec::new();
        let mut bodies = Vec::with_capacity(links);
        for link_shapes in per_link {
            let start = shapes.len();
            for (shape, source) in link_shapes {
                shapes.push(shape);
                sources.push(source);
            }
            let spheres: Vec<(Vector3<f64>, f64)> = shapes[start..]
                .iter()
                .map(|s| (s.centre, s.bound))
                .collect();
            let (centre, radius) = enclosing_sphere(&spheres).unwrap_or((Vector3::zeros(), 0.0));
            bodies.push(Body {
                shapes: start..shapes.len(),
                centre,
                radius,
            });
        }
        let parent: Vec<Option<(JointId, LinkId)>> = (0..links)
            .map(|l| {
                let joint = model.parent_joint.get(l).copied().flatten()?;
                let (p, _) = model.joint_links.get(joint.0).copied().flatten()?;
                Some((joint, p))
            })
            .collect();
        let depth = (0..links)
            .map(|l| {
                let mut link = l;
                let mut depth = 0;
                while let Some((_, p)) = parent[link] {
                    link = p.0;
                    depth += 1;
                    if depth > links {
                        break; // not a tree; Model::build prevents this
                    }
                }
                depth
            })
            .collect();
        let mut collision = CollisionModel {
            geometric: (0..links)
                .filter(|&l| !bodies[l].shapes.is_empty())
                .map(LinkId)
                .collect(),
            shapes,
            sources,
            bodies,
            allowed: vec![None; links * links],
            parent,
            depth,
        };
        collision.allow_structural(model);
        collision
    }

    /// Mark adjacent and rigidly attached pairs.
    fn allow_structural(&mut self, model: &Model) {
        let adjacent: Vec<(LinkId, LinkId)> = self
            .geometric
            .iter()
            .flat_map(|&link| {
                self.geometric_neighbours(model, link)
                    .into_iter()
                    .map(move |other| (link, other))
            })
            .collect();
        self.allow(&adjacent, Allowed::Adjacent);
        let actuated: Vec<bool> = model.joint_data.iter().map(|j| j.is_actuated()).collect();
        let rigid: Vec<(LinkId, LinkId)> = self
            .geometric_pairs()
            .filter(|&(a, b)| !self.path_has(a, b, |j| actuated.get(j.0).copied().unwrap_or(false)))
            .collect();
        self.allow(&rigid, Allowed::Rigid);
    }

    /// Links with geometry reached from `link` through tree edges, walking through links without geometry
    /// (MoveIt's setup assistant merges such links into their neighbours).
    fn geometric_neighbours(&self, model: &Model, link: LinkId) -> Vec<LinkId> {
        let tree_neighbours = |l: LinkId| {
            let parent = self.parent[l.0].map(|(_, p)| p);
            let children = model.child_joints[l.0]
                .iter()
                .filter_map(|j| model.joint_links[j.0].map(|(_, c)| c));
            parent.into_iter().chain(children)
        };
        let mut seen = vec![link];
        let mut stack: Vec<LinkId> = tree_neighbours(link).collect();
        let mut found = Vec::new();
        while let Some(next) = stack.pop() {
            if seen.contains(&next) {
                continue;
            }
            seen.push(next);
            if self.bodies[next.0].shapes.is_empty() {
                stack.extend(tree_neighbours(next));
            } else {
                found.push(next);
            }
        }
        found
    }

    /// Every pair of links with geometry, lower index first.
    fn geometric_pairs(&self) -> impl Iterator<Item = (LinkId, LinkId)> + '_ {
        self.geometric
            .iter()
            .enumerate()
            .flat_map(move |(i, &a)| self.geometric[i + 1..].iter().map(move |&b| (a, b)))
    }

    /// True when a joint on the tree path between `a` and `b` passes `test`.
    fn path_has(&self, a: LinkId, b: LinkId, test: impl Fn(JointId) -> bool) -> bool {
        let (mut a, mut b) = (a.0, b.0);
        while a != b {
            let link = if self.depth[a] >= self.depth[b] {
                &mut a
            } else {
                &mut b
            };
            // Two roots: every joint of both paths has been seen.
            let Some((joint, parent)) = self.parent[*link] else {
                return false;
            };
            if test(joint) {
                return true;
            }
            *link = parent.0;
        }
        false
    }

    /// A pair set, largest links first: big links (a base, a torso) are the likeliest to be hit, and
    /// [`check`](Self::check) stops at the first contact.
    /// `motion`: which links the set's joints move (`None`: every link may move).
    fn pair_set(&self, mut pairs: Vec<(LinkId, LinkId)>, motion: Option<&Motion>) -> PairSet {
        let moves = motion.map(|m| m.links.as_slice());
        let size = |(a, b): (LinkId, LinkId)| self.bodies[a.0].radius + self.bodies[b.0].radius;
        // Largest first, equal sizes in their given order (a stable sort on sizes computed once).
        let mut sized: Vec<(f64, (LinkId, LinkId))> = pairs.iter().map(|&p| (size(p), p)).collect();
        sized.sort_by(|p, q| q.0.total_cmp(&p.0));
        pairs.clear();
        pairs.extend(sized.into_iter().map(|(_, pair)| pair));
        let mut links: Vec<LinkId> = pairs.iter().flat_map(|&(a, b)| [a, b]).collect();
        links.sort_unstable();
        links.dedup();
        let slot = |link: LinkId| links.binary_search(&link).unwrap_or_default() as u32;
        let broad: Vec<(u32, u32, f64)> = pairs
            .iter()
            .map(|&pair| (slot(pair.0), slot(pair.1), size(pair)))
            .collect();
        let slot_moves: Vec<bool> = links
            .iter()
            .map(|l| moves.is_none_or(|m| m.get(l.0).copied().unwrap_or(true)))
            .collect();
        let moving = (0..links.len() as u32)
            .filter(|&slot| slot_moves[slot as usize])
            .collect();
        let sweep = (pairs.len() > SWEEP_FROM_PAIRS_PER_LINK * links.len()).then(|| {
            let radius = links.iter().map(|l| self.bodies[l.0].radius).collect();
            SweepIndex::new(&broad, radius)
        });
        let held = motion.and_then(|motion| {
            let group_root: Vec<Option<LinkId>> = (0..self.parent.len())
                .map(|link| self.group_root(LinkId(link), motion))
                .collect();
            HeldBroad::new(&broad, &links, &group_root)
        });
        PairSet {
            pairs,
            links,
            moving,
            slot_moves,
            broad,
            sweep,
            held,
        }
    }

    /// Why `a` and `b` are never checked, if they are not.
    pub fn allowed(&self, a: LinkId, b: LinkId) -> Option<Allowed> {
        let n = self.bodies.len();
        self.allowed.get(a.0 * n + b.0).copied().flatten()
    }

    /// Never check `pairs` again, for `reason` (a pair keeps the first reason it was given). Links out of
    /// range are ignored.
    pub fn allow(&mut self, pairs: &[(LinkId, LinkId)], reason: Allowed) {
        let n = self.bodies.len();
        for &(a, b) in pairs {
            if a.0 < n && b.0 < n {
                for index in [a.0 * n + b.0, b.0 * n + a.0] {
                    self.allowed[index].get_or_insert(reason);
                }
            }
        }
    }

    /// Allow what the SRDF allows (see [`SrdfCollisions`]: `disable_collisions` pairs, and every pair of a
    /// `disable_default_collisions` link but those an `enable_collisions` names); returns one message
    /// per link name the robot does not have (`line:col: ...`), whose entry is otherwise ignored.
    pub fn allow_srdf(&mut self, model: &Model, srdf: &SrdfCollisions) -> Vec<String> {
        let problems = srdf
            .named_links()
            .into_iter()
            .filter(|(_, link, ..)| model.link(link).is_none())
            .map(|(tag, link, line, column)| {
                format!("{line}:{column}: <{tag}> names unknown link '{link}'")
            })
            .collect();
        let known = |pairs: &[SrdfPair]| -> Vec<(LinkId, LinkId)> {
            pairs
                .iter()
                .filter_map(|pair| Some((model.link(&pair.link1)?, model.link(&pair.link2)?)))
                .collect()
        };
        self.allow(&known(&srdf.disabled), Allowed::Disabled);
        // Sets, each entry once: an SRDF is untrusted input and may repeat entries by the thousand.
        let enabled: HashSet<(LinkId, LinkId)> = known(&srdf.enabled)
            .into_iter()
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect();
        let mut by_default_links: Vec<LinkId> = srdf
            .disabled_by_default
            .iter()
            .filter_map(|entry| model.link(&entry.link))
            .collect();
        by_default_links.sort_unstable();
        by_default_links.dedup();
        let by_default: Vec<(LinkId, LinkId)> = by_default_links
            .into_iter()
            .flat_map(|link| self.geometric.iter().map(move |&other| (link, other)))
            .filter(|&(link, other)| {
                link != other && !enabled.contains(&(link.min(other), link.max(other)))
            })
            .collect();
        self.allow(&by_default, Allowed::Disabled);
        problems
    }

    /// True when `link` has at least one usable collision shape.
    pub fn has_geometry(&self, link: LinkId) -> bool {
        self.bodies
            .get(link.0)
            .is_some_and(|b| !b.shapes.is_empty())
    }

    /// Every pair of links with geometry that is not allowed to collide.
    pub fn all_pairs(&self) -> PairSet {
        self.pair_set(self.checked_pairs().collect(), None)
    }

    /// How many pairs [`all_pairs`](Self::all_pairs) holds, without building the set.
    pub fn checked_pair_count(&self) -> usize {
        self.checked_pairs().count()
    }

    /// The pairs of links with geometry that are not allowed to collide, in index order.
    fn checked_pairs(&self) -> impl Iterator<Item = (LinkId, LinkId)> + '_ {
        self.geometric_pairs()
            .filter(|&(a, b)| self.allowed(a, b).is_none())
    }

    /// The pairs whose distance changes with `motion` (some joints varying, and the mimic joints that
    /// follow them): a varying joint lies on the tree path between the two links. Allowed pairs are left
    /// out. Pairs of links that both move rigidly together are left out, as their distance does not change.
    pub fn pairs_moved_by(&self, motion: &Motion) -> PairSet {
        let varies = |j: JointId| motion.joints.get(j.0).copied().unwrap_or(false);
        self.pair_set(
            self.geometric_pairs()
                .filter(|&(a, b)| self.allowed(a, b).is_none() && self.path_has(a, b, varies))
                .collect(),
            Some(motion),
        )
    }

    /// The root of `link`'s rigid group under `motion`: the nearest link at or above it whose parent joint
    /// varies (`None` when no joint above it varies: the link is held).
    fn group_root(&self, mut link: LinkId, motion: &Motion) -> Option<LinkId> {
        while let Some((joint, parent)) = self.parent.get(link.0).copied().flatten() {
            if motion.joints.get(joint.0).copied().unwrap_or(false) {
                return Some(link);
            }
            link = parent;
        }
        None
    }

    /// Pairs (not yet allowed) in contact with every link at `placements` (world placements indexed by
    /// link, as [`crate::model::kinematics::Data::link_placement`]). At the reference pose these usually mean
    /// broken collision geometry: report them, then [`allow`](Self::allow) them as
    /// [`Allowed::Touching`].
    pub fn touching_pairs(&self, placements: &[Isometry3<f64>]) -> Vec<(LinkId, LinkId)> {
        let mut touching = Vec::new();
        self.check_pairs(
            &self.all_pairs(),
            placements,
            0.0,
            &mut CheckScratch::new(self),
            &mut |pair| {
                touching.push(pair);
                true
            },
        );
        touching
    }

    /// The deepest overlap between a shape of `a` placed at `pose_a` and one of `b` at `pose_b` that
    /// `may_touch` lets collide (given the indices of the links' collisions they are): its depth
    /// (metres, > 0) and those two indices; `None` when no such pair overlaps.
    pub fn overlap_depth(
        &self,
        (a, pose_a): (LinkId, &Isometry3<f64>),
        (b, pose_b): (LinkId, &Isometry3<f64>),
        may_touch: &dyn Fn(usize, usize) -> bool,
    ) -> Option<(f64, usize, usize)> {
        let (body_a, body_b) = (self.bodies.get(a.0)?, self.bodies.get(b.0)?);
        let (centre_a, centre_b) = (
            pose_a.transform_point(&body_a.centre.into()),
            pose_b.transform_point(&body_b.centre.into()),
        );
        if (centre_a - centre_b).norm() >= body_a.radius + body_b.radius {
            return None;
        }
        let mut deepest: Option<(f64, usize, usize)> = None;
        for i in body_a.shapes.clone() {
            let at_a = to_pose(&(pose_a * self.shapes[i].frame));
            for j in body_b.shapes.clone() {
                let sources = (self.sources[i], self.sources[j]);
                if !may_touch(sources.0, sources.1) {
                    continue;
                }
                let at_b = to_pose(&(pose_b * self.shapes[j].frame));
                let depth = shape::overlap_depth(&self.shapes[i], &at_a, &self.shapes[j], &at_b);
                if depth > 0.0 && deepest.is_none_or(|d| depth > d.0) {
                    deepest = Some((depth, sources.0, sources.1));
                }
            }
        }
        deepest
    }

    /// The shape of `link` placed at `placement` that `may_touch` lets touch the plane through `point`
    /// with unit `normal` (solid on the side away from the normal) and reaches deepest below it: how far
    /// (metres, > 0) and the index of the link's collision it is; `None` when none reaches below.
    pub fn depth_below_plane(
        &self,
        link: LinkId,
        placement: &Isometry3<f64>,
        (point, normal): (&Vector3<f64>, &Vector3<f64>),
        may_touch: &dyn Fn(usize) -> bool,
    ) -> Option<(f64, usize)> {
        self.bodies
            .get(link.0)?
            .shapes
            .clone()
            .filter(|&i| may_touch(self.sources[i]))
            .map(|i| {
                let shape = &self.shapes[i];
                let depth =
                    shape::depth_below_plane(shape, &(placement * shape.frame), point, normal);
                (depth, self.sources[i])
            })
            .filter(|&(depth, _)| depth > 0.0)
            .max_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// The links with collision shapes, in index order.
    pub fn geometric_links(&self) -> &[LinkId] {
        &self.geometric
    }

    /// Check the pairs of `pairs` with the links at `placements` (world placements by link, such as
    /// [`crate::model::kinematics::Data::link_placement`]; see [`LinkPlacements`]), stopping at the first
    /// pair in contact.
    ///
    /// Bounding spheres first, then bounding boxes, then GJK on the shapes, each stage only for pairs
    /// that may be closer than the current margin: the smallest distance found so far in this pose,
    /// starting at `clearance_cutoff`. Pass the smallest clearance seen over earlier poses as
    /// `clearance_cutoff` (`f64::INFINITY` at first; 0 when clearance does not matter): distances are then
    /// only computed for pairs that can beat it, and [`PoseCheck::min_clearance`] is `Some` only when one
    /// does. Pairs with a link whose placement is not usable are skipped and counted.
    pub fn check<P: LinkPlacements + ?Sized>(
        &self,
        pairs: &PairSet,
        placements: &P,
        clearance_cutoff: f64,
        scratch: &mut CheckScratch,
    ) -> PoseCheck {
        let mut contact = None;
        let mut result =
            self.check_pairs(pairs, placements, clearance_cutoff, scratch, &mut |pair| {
                contact = Some(pair);
                false
            });
        result.contact = contact;
        result
    }

    /// [`check`](Self::check), calling `on_contact` for each pair in contact and going on while it
    /// returns true (`contact` of the result is left empty).
    fn check_pairs<P: LinkPlacements + ?Sized>(
        &self,
        pairs: &PairSet,
        placements: &P,
        clearance_cutoff: f64,
        scratch: &mut CheckScratch,
        on_contact: &mut dyn FnMut((LinkId, LinkId)) -> bool,
    ) -> PoseCheck {
        scratch.next_pose();
        let vouched = std::mem::take(&mut scratch.moving_vouched);
        let mut result = PoseCheck::default();
        let centre_of = |link: LinkId| {
            placements
                .placement(link)
                .filter(usable)
                .map(|p| self.world_centre(link, &p))
        };
        let held = match scratch.fixed_usable {
            Some(usable) if scratch.hold_fixed && scratch.centre.len() == pairs.links.len() => {
                Some(usable)
            }
            _ => None,
        };
        // With the rigid-group broad phase (held links measured, every link usable), the moving slots'
        // centres are the caller's (vouched for) or computed as their pairs are looked at.
        let grouped = pairs.held.as_ref().filter(|_| {
            held == Some(true)
                && pairs.sweep.is_none()
                && (vouched
                    || pairs.moving.iter().all(|&slot| {
                        placements
                            .placement(pairs.links[slot as usize])
                            .is_some_and(|p| usable(&p))
                    }))
        });
        let mut all_usable = true;
        if grouped.is_some() {
            // Vouched for by the caller, or computed in the scan as pairs need them.
        } else if let Some(fixed_usable) = held {
            // Only the moving slots' centres change.
            all_usable = fixed_usable;
            for &slot in &pairs.moving {
                let centre = centre_of(pairs.links[slot as usize]);
                all_usable &= centre.is_some();
                scratch.centre[slot as usize] = centre.unwrap_or(Vector3::repeat(f64::NAN));
                scratch.centre_stamp[slot as usize] = scratch.stamp;
            }
        } else {
            let mut fixed_usable = true;
            scratch.centre.clear();
            scratch.centre_stamp.clear();
            for (slot, &link) in pairs.links.iter().enumerate() {
                let centre = centre_of(link);
                all_usable &= centre.is_some();
                fixed_usable &= pairs.slot_moves[slot] || centre.is_some();
                scratch
                    .centre
                    .push(centre.unwrap_or(Vector3::repeat(f64::NAN)));
                scratch.centre_stamp.push(if pairs.slot_moves[slot] {
                    scratch.stamp
                } else {
                    HELD
                });
            }
            scratch.fixed_usable = scratch.hold_fixed.then_some(fixed_usable);
            if let (true, Some(held)) = (scratch.hold_fixed, &pairs.held) {
                let radius: Vec<f64> = pairs
                    .links
                    .iter()
                    .map(|l| self.bodies[l.0].radius)
                    .collect();
                held.load(
                    &scratch.centre,
                    &radius,
                    placements,
                    &mut scratch.held_spheres,
                );
            }
        }
        let centre = &scratch.centre;
        if !all_usable {
            result.skipped = pairs
                .broad
                .iter()
                .filter(|(a, b, _)| {
                    centre[*a as usize].x.is_nan() || centre[*b as usize].x.is_nan()
                })
                .count();
        }
        if scratch.memory.len() < pairs.len() {
            scratch.memory.resize(pairs.len(), PairMemory::default());
        }
        let margin = clearance_cutoff.max(CONTACT_DISTANCE);
        // Pairs are visited in set order either way, so the sweep changes no result, only the time. The
        // first pairs of the set (the largest links) are scanned before the sweep is built: a pose in
        // contact usually stops there.
        let mut state = Scan {
            margin,
            nearest: None,
            in_contact: false,
        };
        if let Some(held_broad) = grouped {
            // The held links are where the first check left them, and each moving group keeps its
            // shape: only the pairs behind spheres that meet can be within the margin (scanning the
            // largest links' pairs first, as the other broad phases do, only costs time here: a moving
            // link's centre is computed only for the pairs kept).
            let mut kept = std::mem::take(&mut scratch.held_candidates);
            held_broad.candidates(
                placements,
                &mut scratch.held_spheres,
                state.margin,
                &mut kept,
            );
            let kept_pairs = set_bits(&kept);
            if vouched {
                self.scan::<false, P>(
                    pairs, kept_pairs, placements, scratch, &mut state, on_contact,
                );
            } else {
                self.scan::<true, P>(
                    pairs, kept_pairs, placements, scratch, &mut state, on_contact,
                );
            }
            scratch.held_candidates = kept;
            if !state.in_contact {
                result.min_clearance = state.nearest;
            }
            return result;
        }
        let mut candidates = std::mem::take(&mut scratch.sweep.candidates);
        let sweep = pairs
            .sweep
            .as_ref()
            .filter(|_| all_usable && margin.is_finite());
        let scanned = match sweep {
            Some(_) => (SWEEP_AFTER_LINKS * pairs.links.len()).min(pairs.broad.len()),
            None => pairs.broad.len(),
        };
        let going = self.scan::<false, P>(
            pairs,
            0..scanned,
            placements,
            scratch,
            &mut state,
            on_contact,
        );
        if let (true, Some(sweep)) = (going, sweep) {
            scratch.sweep.candidates = candidates;
            sweep.candidates(&scratch.centre, state.margin, &mut scratch.sweep);
            candidates = std::mem::take(&mut scratch.sweep.candidates);
            let rest = candidates
                .iter()
                .map(|&i| i as usize)
                .filter(|&i| i >= scanned);
            self.scan::<false, P>(pairs, rest, placements, scratch, &mut state, on_contact);
        }
        scratch.sweep.candidates = candidates;
        if !state.in_contact {
            result.min_clearance = state.nearest;
        }
        result
    }

    /// Check the pairs at `indices` (increasing) in order, updating `state`; false when `on_contact` stopped
    /// the scan. `LAZY`: a moving slot's centre is computed here when it is not yet for this pose.
    fn scan<const LAZY: bool, P: LinkPlacements + ?Sized>(
        &self,
        pairs: &PairSet,
        indices: impl Iterator<Item = usize>,
        placements: &P,
        scratch: &mut CheckScratch,
        state: &mut Scan,
        on_contact: &mut dyn FnMut((LinkId, LinkId)) -> bool,
    ) -> bool {
        let mut margin = state.margin;
        let mut going = true;
        for index in indices {
            let (slot_a, slot_b, radii) = pairs.broad[index];
            if LAZY {
                for slot in [slot_a, slot_b] {
                    let stamp = scratch.centre_stamp[slot as usize];
                    if stamp != scratch.stamp && stamp != HELD {
                        scratch.centre[slot as usize] =
                            self.lazy_centre(pairs.links[slot as usize], placements);
                        scratch.centre_stamp[slot as usize] = scratch.stamp;
                    }
                }
            }
            // Squared, so no root; NaN centres are unusable placements.
            let reach = radii + margin;
            let squared =
                (scratch.centre[slot_a as usize] - scratch.centre[slot_b as usize]).norm_squared();
            if squared >= reach * reach || squared.is_nan() {
                continue;
            }
            let (a, b) = pairs.pairs[index];
            let held =
                [slot_a, slot_b].map(|slot| scratch.hold_fixed && !pairs.slot_moves[slot as usize]);
            match self.link_proximity((a, b), held, index, placements, margin, scratch) {
                Proximity::Contact => {
                    state.in_contact = true;
                    margin = CONTACT_DISTANCE;
                    if !on_contact((a, b)) {
                        going = false;
                        break;
                    }
                }
                Proximity::Apart(d) => {
                    state.nearest = Some((d, (a, b)));
                    margin = d;
                }
                Proximity::Beyond => {}
            }
        }
        state.margin = margin;
        going
    }

    /// The proximity of two links (both placements usable): the closest of their shape pairs. `held`: per
    /// link, whether it stays in place between checks (its shape placements are then kept).
    fn link_proximity<P: LinkPlacements + ?Sized>(
        &self,
        (a, b): (LinkId, LinkId),
        held: [bool; 2],
        pair_index: usize,
        placements: &P,
        mut margin: f64,
        scratch: &mut CheckScratch,
    ) -> Proximity {
        if !(scratch.fetch_link(a, held[0], placements)
            && scratch.fetch_link(b, held[1], placements))
        {
            return Proximity::Beyond;
        }
        let CheckScratch {
            link_placed,
            placed,
            stamp,
            memory,
            simplex,
            ..
        } = scratch;
        let (link_a, link_b) = (&link_placed[a.0].1, &link_placed[b.0].1);
        let mut best = Proximity::Beyond;
        for i in self.bodies[a.0].shapes.clone() {
            let centre_a = self.place_centre(i, link_a, held[0], placed, *stamp);
            for j in self.bodies[b.0].shapes.clone() {
                let centre_b = self.place_centre(j, link_b, held[1], placed, *stamp);
                let (sa, sb) = (&self.shapes[i], &self.shapes[j]);
                let reach = sa.bound + sb.bound + margin;
                if (centre_a - centre_b).norm_squared() >= reach * reach {
                    continue;
                }
                self.place_box(i, link_a, held[0], placed, *stamp);
                self.place_box(j, link_b, held[1], placed, *stamp);
                let (pa, pb) = (&placed[i], &placed[j]);
                if boxes_apart(&pa.obb, &sa.obb.half, &pb.obb, &sb.obb.half, margin) {
                    continue;
                }
                self.place_pose(i, link_a, held[0], placed, *stamp);
                self.place_pose(j, link_b, held[1], placed, *stamp);
                let (pa, pb) = (&placed[i], &placed[j]);
                // A shape held in place goes first, so that its support point along the pair's axis
                // is kept between poses (see `PairMemory`).
                let (first, second, first_held) = if held[1] && !held[0] {
                    ((sb, &pb.pose), (sa, &pa.pose), Some(j))
                } else {
                    ((sa, &pa.pose), (sb, &pb.pose), held[0].then_some(i))
                };
                let found = proximity(
                    first.0,
                    first.1,
                    second.0,
                    second.1,
                    margin,
                    &mut memory[pair_index],
                    first_held,
                    simplex,
                );
                match found {
                    Proximity::Contact => {
                        return Proximity::Contact;
                    }
                    Proximity::Apart(d) => {
                        best = Proximity::Apart(d);
                        margin = d;
                    }
                    Proximity::Beyond => {}
                }
            }
        }
        best
    }

    /// The centre of `link`'s bounding sphere, in the link's frame.
    pub fn sphere_centre(&self, link: LinkId) -> Vector3<f64> {
        self.bodies[link.0].centre
    }

    /// The world centre of `link`'s bounding sphere, the link at `placement`.
    fn world_centre(&self, link: LinkId, placement: &Isometry3<f64>) -> Vector3<f64> {
        placement
            .transform_point(&Point3::from(self.bodies[link.0].centre))
            .coords
    }

    /// For the lazy scan: the world centre of a link whose placement was found usable (NaN if it is not
    /// there).
    fn lazy_centre<P: LinkPlacements + ?Sized>(
        &self,
        link: LinkId,
        placements: &P,
    ) -> Vector3<f64> {
        placements
            .placement(link)
            .map_or(Vector3::repeat(f64::NAN), |p| self.world_centre(link, &p))
    }

    /// The bounding-sphere centre of shape `index` of a link placed at `link`, placed in `placed`
    /// (the scratch's shapes) unless it is there for the pose stamped `stamp` (or for every pose, when
    /// the link is `held` in place).
    #[inline(always)]
    fn place_centre(
        &self,
        index: usize,
        link: &Isometry3<f64>,
        held: bool,
        placed: &mut [Placed],
        stamp: u32,
    ) -> Vector3<f64> {
        let placed = &mut placed[index];
        if restamp(&mut placed.centre_stamp, stamp, held) {
            placed.centre = link
                .transform_point(&Point3::from(self.shapes[index].centre))
                .coords;
        }
        placed.centre
    }

    /// Place the box of shape `index` (as [`place_centre`](Self::place_centre) its centre).
    #[inline(always)]
    fn place_box(
        &self,
        index: usize,
        link: &Isometry3<f64>,
        held: bool,
        placed: &mut [Placed],
        stamp: u32,
    ) {
        let placed = &mut placed[index];
        if restamp(&mut placed.obb_stamp, stamp, held) {
            placed.obb = self.shapes[index].obb.placed(link);
        }
    }

    /// Place the frame of shape `index`, for the narrow phase (as [`place_centre`](Self::place_centre)
    /// its centre).
    #[inline(always)]
    fn place_pose(
        &self,
        index: usize,
        link: &Isometry3<f64>,
        held: bool,
        placed: &mut [Placed],
        stamp: u32,
    ) {
        let placed = &mut placed[index];
        if restamp(&mut placed.pose_stamp, stamp, held) {
            placed.pose = to_pose(&(link * self.shapes[index].frame));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::pose::ConfigurationSampler;
    use crate::assets::link_supports;
    use crate::model::{forward_kinematics, Data};

    /// A placement is usable when every number is finite and the origin within reach: a NaN or an
    /// infinity anywhere, or a coordinate beyond [`MAX_EXTENT`], makes it unusable.
    #[test]
    fn usable_placements_are_finite_and_within_reach() {
        let at = |x: f64| Isometry3::translation(x, 0.5, -0.5);
        assert!(usable(&at(MAX_EXTENT)));
        assert!(!usable(&at(MAX_EXTENT * 1.000001)));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(!usable(&at(bad)));
            for k in 0..4 {
                let mut placement = at(0.0);
                placement.rotation.as_mut_unchecked().coords[k] = bad;
                assert!(!usable(&placement), "rotation coordinate {k} = {bad}");
            }
        }
    }

    /// A chain of `n` box links 2 cm apart, each joint bending by up to `range` radians.
    fn chain(n: usize, range: f64) -> String {
        let body = "<collision><geometry><box size=\"0.01 0.01 0.01\"/></geometry></collision>";
        let links: String = (0..=n)
            .map(|i| format!("<link name=\"l{i}\">{body}</link>"))
            .collect();
        let joints: String = (0..n)
            .map(|i| {
                format!(
                    "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{i}\"/><child link=\"l{}\"/>\
                     <origin xyz=\"0 0 0.02\"/><axis xyz=\"{} 1 0\"/>\
                     <limit lower=\"-{range}\" upper=\"{range}\" effort=\"1\" velocity=\"1\"/></joint>",
                    i + 1,
                    i % 2
                )
            })
            .collect();
        format!("<robot name=\"chain\">{links}{joints}</robot>")
    }

    /// The tree and collision model of [`chain`]`(n, range)`.
    fn chain_collision(n: usize, range: f64) -> (Model, CollisionModel) {
        let text = chain(n, range);
        let (robot, _) = crate::urdf::parse_urdf(&text, std::path::Path::new("c.urdf")).unwrap();
        let (model, _) = Model::build(&robot);
        let supports: Vec<_> = robot
            .links
            .iter()
            .map(|l| link_supports(l, &|_| None))
            .collect();
        let collision = CollisionModel::build(&robot, &model, &supports);
        (model, collision)
    }

    /// A scratch holding the links the pair set's joints do not move gives every pose the same result as
    /// one recomputing every link, when only those joints vary (the other links stay where they are):
    /// with one link per moving group (the last six joints vary, the first six hold their reference
    /// bends), and with groups of three links (every third joint varies).
    #[test]
    fn holding_the_fixed_links_changes_no_result() {
        let six: Vec<JointId> = (6..12).map(JointId).collect();
        let every_third: Vec<JointId> = [2, 5, 8, 11].map(JointId).to_vec();
        holding_changes_no_result(&six);
        holding_changes_no_result(&every_third);
    }

    fn holding_changes_no_result(varied: &[JointId]) {
        let (model, collision) = chain_collision(12, 3.0);
        let pairs = collision.pairs_moved_by(&model.motion_of(varied));
        assert!(pairs.held.is_some(), "the rigid-group broad phase is used");
        assert!(
            pairs.moving.len() < pairs.links.len(),
            "some links are held"
        );
        let mut sampler = ConfigurationSampler::new(&model, 3);
        let mut reference = model.zero_configuration();
        sampler.sample_into(&mut reference);
        let mut q = reference.clone();
        let mut data = Data::new(&model);
        // Both scratches keep their GJK warm starts from pose to pose, as the sampler's do.
        let mut plain = CheckScratch::new(&collision);
        let mut held = CheckScratch::holding_fixed(&collision);
        // And one told the moving links' sphere centres (as the workspace sampler's batches tell it).
        let mut vouched = CheckScratch::holding_fixed(&collision);
        let (mut cutoff, mut contacts) = (f64::INFINITY, 0);
        for _ in 0..400 {
            let mut sample = model.zero_configuration();
            sampler.sample_into(&mut sample);
            for joint in varied {
                q[joint.0] = sample[joint.0];
            }
            forward_kinematics(&model, &q, &mut data);
            let reused = collision.check(&pairs, &data.link_placement, cutoff, &mut plain);
            let kept = collision.check(&pairs, &data.link_placement, cutoff, &mut held);
            assert_eq!(reused, kept);
            let centres: Vec<Vector3<f64>> = pairs
                .moving_links()
                .map(|link| {
                    (data.link_placement[link.0] * Point3::from(collision.sphere_centre(link)))
                        .coords
                })
                .collect();
            vouched.vouch_moving(&pairs, centres.into_iter());
            let told = collision.check(&pairs, &data.link_placement, cutoff, &mut vouched);
            assert_eq!(told, kept);
            // And as a scratch that knows nothing of earlier poses finds (up to GJK's warm start).
            let fresh = collision.check(
                &pairs,
                &data.link_placement,
                cutoff,
                &mut CheckScratch::new(&collision),
            );
            assert_eq!((fresh.contact, fresh.skipped), (kept.contact, kept.skipped));
            match (fresh.min_clearance, kept.min_clearance) {
                (Some((a, pa)), Some((b, pb))) => assert!(pa == pb && (a - b).abs() < 1e-12),
                (a, b) => assert_eq!(a, b),
            }
            contacts += usize::from(!fresh.is_free());
            if let Some((distance, _)) = kept.min_clearance {
                cutoff = distance;
            }
        }
        assert!(
            contacts > 0 && contacts < 400,
            "{contacts} poses in contact"
        );
    }

    /// The sweep-and-prune broad phase only skips pairs the full scan would reject: on long chains,
    /// folded (contacts) and nearly straight (clearances), every pose gives the same result both ways.
    #[test]
    fn the_sweep_gives_the_same_result_as_scanning_every_pair() {
        for range in [1.5, 0.2, 0.01] {
            let (model, collision) = chain_collision(300, range);
            let swept = collision.all_pairs();
            assert!(swept.sweep.is_some(), "a 300-link chain uses the sweep");
            let scanned = PairSet {
                sweep: None,
                ..swept.clone()
            };
            let mut sampler = ConfigurationSampler::new(&model, 11);
            let mut q = model.zero_configuration();
            let mut data = Data::new(&model);
            let (mut one, mut other) =
                (CheckScratch::new(&collision), CheckScratch::new(&collision));
            let mut cutoff = f64::INFINITY;
            let mut free = 0;
            for _ in 0..300 {
                sampler.sample_into(&mut q);
                forward_kinematics(&model, &q, &mut data);
                let a = collision.check(&swept, &data.link_placement, cutoff, &mut one);
                let b = collision.check(&scanned, &data.link_placement, cutoff, &mut other);
                assert_eq!(a, b, "range {range}");
                if let Some((distance, _)) = a.min_clearance {
                    cutoff = distance;
                }
                free += usize::from(a.is_free());
            }
            if range < 0.05 {
                assert_eq!(free, 300, "a nearly straight chain is free");
            }
        }
    }
}
