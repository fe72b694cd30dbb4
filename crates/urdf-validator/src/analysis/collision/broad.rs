//! The pair sets a pose is checked over, and their broad phase: bounding spheres and sweep-and-prune.

use nalgebra::Vector3;

use super::held::HeldBroad;
use super::CollisionModel;
use crate::model::{JointId, LinkId, Motion};

/// Link pairs to check in every pose (none of them allowed to collide).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PairSet {
    pub(super) pairs: Vec<(LinkId, LinkId)>,
    /// Every link of `pairs`, once, sorted: the link of each slot.
    pub(super) links: Vec<LinkId>,
    /// The slots whose links the set's joints move (every slot when the set has no joints).
    pub(super) moving: Vec<u32>,
    /// Per slot: whether its link moves (is in `moving`).
    pub(super) slot_moves: Vec<bool>,
    /// Per pair: the slots of its links and the sum of their bounding radii (the broad phase reads only
    /// this, from memory laid out in pair order).
    pub(super) broad: Vec<(u32, u32, f64)>,
    /// For sets with many pairs per link (long chains): a sweep-and-prune index, so a pose costs about
    /// the number of nearby pairs instead of every pair.
    pub(super) sweep: Option<SweepIndex>,
    /// For checks that hold the links the set's joints do not move
    /// ([`CheckScratch::holding_fixed`](super::CheckScratch::holding_fixed)): the moving links' rigid
    /// groups, whose spheres stand for their pairs.
    pub(super) held: Option<HeldBroad>,
}

/// Pair sets with more pairs than this per link use the sweep-and-prune broad phase (below it, scanning
/// every pair is as fast).
const SWEEP_FROM_PAIRS_PER_LINK: usize = 64;

/// Slack added to every sweep interval, metres: the sweep only preselects pairs (each is tested exactly
/// afterwards), so a margin that is too large changes nothing but a little time.
const SWEEP_SLACK: f64 = 1e-6;

/// What sweep-and-prune needs of a [`PairSet`]: each slot's bounding radius and, for each pair of slots,
/// its index in the set.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct SweepIndex {
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
    pub(super) fn candidates(
        &self,
        centre: &[Vector3<f64>],
        margin: f64,
        scratch: &mut SweepScratch,
    ) {
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

/// Per-thread buffers of the sweep.
#[derive(Clone, Debug, Default)]
pub(super) struct SweepScratch {
    intervals: Vec<(f64, f64, u32)>,
    active: Vec<(f64, u32)>,
    pub(super) candidates: Vec<u32>,
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

impl CollisionModel {
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
}
