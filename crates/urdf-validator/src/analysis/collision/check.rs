//! The per-pose check: sphere, box and GJK stages over a pair set, with per-thread scratch memory.

use nalgebra::{Isometry3, Matrix3, Point3, Vector3};
use parry3d_f64::math::Pose;
use parry3d_f64::query::gjk::VoronoiSimplex;

use super::broad::SweepScratch;
use super::held::{set_bits, HeldSpheres};
use super::shape::{boxes_apart, proximity, to_pose, PairMemory, Proximity};
use super::{CollisionModel, LinkPlacements, PairSet, CONTACT_DISTANCE, MAX_EXTENT};
use crate::model::LinkId;

/// With the sweep, the first `SWEEP_AFTER_LINKS × links` pairs are still scanned one by one first.
const SWEEP_AFTER_LINKS: usize = 4;

/// Where a pose's scan over its pairs stands.
struct Scan {
    /// Pairs further apart than this are not looked at (the nearest clearance so far).
    margin: f64,
    /// The nearest pair so far and its distance.
    nearest: Option<(f64, (LinkId, LinkId))>,
    /// Some pair is in contact.
    in_contact: bool,
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
    /// Per pair of the last pair set: what the narrow phase keeps of it (see
    /// [`shape::proximity`](super::shape::proximity)).
    memory: Vec<PairMemory>,
    simplex: VoronoiSimplex,
    sweep: SweepScratch,
    /// With `hold_fixed`: the spheres of the pair set's [`HeldBroad`](super::held::HeldBroad), and the
    /// pairs it keeps in the current pose.
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
    /// Pairs (not yet allowed) in contact with every link at `placements` (world placements indexed by
    /// link, as [`crate::model::kinematics::Data::link_placement`]). At the reference pose these usually mean
    /// broken collision geometry: report them, then [`allow`](Self::allow) them as
    /// [`Allowed::Touching`](super::Allowed::Touching).
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
}
