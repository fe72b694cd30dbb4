//! The broad phase of a pair set checked over many poses in which only the links its joints move change
//! place (a sampler varying an arm's joints, the rest of the robot held).
//!
//! The moving links fall into rigid groups: the links below one varying joint, down to the next ones (a
//! hand with its fingers held is one group). A group keeps its shape from pose to pose, so one sphere
//! around its links' bounding spheres, carried by the group's root link, stands for all of them. A pose
//! tests each group's sphere against the held links' spheres and the other groups' spheres; only the
//! pairs behind a test that passes are then tested one by one, exactly and in pair order. This stage
//! changes which pairs are looked at, never a result.

use nalgebra::{Point3, Vector3};

use super::LinkPlacements;
use crate::model::LinkId;

/// Held spheres per block: a group's sphere is tested against a block at once, in straight-line code (no
/// branch per sphere).
const LANES: usize = 8;

/// Blocks per chunk of [`HeldSpheres::block`]: their spheres are tested against a group's at once.
const BLOCK_LANES: usize = 4;

/// The most rigid groups grouped this way: the group-against-group tests grow with the square of their
/// number (a long chain, every joint varying, is left to the other broad phases).
const MAX_GROUPS: usize = 64;

/// Added to every group radius, metres, on top of a relative 1e-9: a group sphere is computed once and
/// then carried by its root link, while the exact test places each link anew; the difference is
/// rounding, far below this.
const SLACK: f64 = 1e-6;

/// The rigid groups of a pair set's moving links, and its pairs sorted by which spheres stand for them.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct HeldBroad {
    /// Per group: the link whose placement carries it (the child link of its varying joint).
    group_root: Vec<LinkId>,
    /// Per group: its slots.
    members: Vec<Vec<u32>>,
    /// The held slots.
    held: Vec<u32>,
    /// The pairs of group `g` and held slot `held[h]` are the bits of `group_held_pairs[o[i]..o[i + 1]]`
    /// (see [`PairWords`]) with `i = g * held.len() + h` and `o` = `group_held_offsets`.
    group_held_offsets: Vec<u32>,
    group_held_pairs: Vec<PairWords>,
    /// Per two groups `g < k` with pairs between them: `g`, `k`, and where their pairs are in
    /// `group_pairs`.
    group_links: Vec<(u32, u32, u32, u32)>,
    group_pairs: Vec<PairWords>,
    /// One bit per pair of the set: the pairs no sphere stands for (always tested one by one).
    always: Vec<u64>,
}

/// Per-thread state of a [`HeldBroad`]: what the first check of the set measured.
#[derive(Clone, Debug, Default)]
pub(super) struct HeldSpheres {
    /// Per group: its sphere's centre in its root link's frame, and its radius (slack included; infinite
    /// when a link of the group had no usable placement then, so that every pair of it is kept).
    group: Vec<(Point3<f64>, f64)>,
    /// Per group: its sphere in the current pose (centre, and radius as in `group`).
    group_placed: Vec<(Vector3<f64>, f64)>,
    /// The held slots' spheres (they stay where they are), [`LANES`] per block: x, y, z and radius of each
    /// (the padding of the last block is infinitely far). Blocks gather nearby spheres (see
    /// [`spatial_order`]), so most blocks are far from a group as a whole.
    held: Vec<[[f64; LANES]; 4]>,
    /// Per lane of `held` (block by block): the index of its held slot in [`HeldBroad`]'s `held`.
    held_index: Vec<u32>,
    /// Per block of `held`: a sphere around its spheres (centre, radius; infinite when a lane is not
    /// finite), tested before its lanes; [`BLOCK_LANES`] blocks' spheres to a chunk, as x, y, z and
    /// radius of each (the padding of the last chunk is infinitely far), so that a group is tested
    /// against several blocks at once.
    block: Vec<[[f64; BLOCK_LANES]; 4]>,
    /// The held slots near one group (indices into [`HeldBroad`]'s `held`), refilled per group.
    near: Vec<u32>,
}

impl HeldSpheres {
    /// Lay out the held spheres (centre, radius, per held slot) in blocks of nearby ones, each with its
    /// enclosing sphere.
    fn set_held(&mut self, held: &[(Vector3<f64>, f64)]) {
        self.held_index.clear();
        self.held_index
            .extend(spatial_order(held).into_iter().map(|h| h as u32));
        self.held.clear();
        self.block.clear();
        for indices in self.held_index.chunks(LANES) {
            let mut lanes = [[f64::INFINITY; LANES]; 4];
            lanes[3] = [0.0; LANES];
            for (lane, &h) in indices.iter().enumerate() {
                let (c, r) = held[h as usize];
                (lanes[0][lane], lanes[1][lane], lanes[2][lane]) = (c.x, c.y, c.z);
                lanes[3][lane] = r;
            }
            self.held.push(lanes);
            let (centre, radius) = enclosing(indices.iter().map(|&h| held[h as usize]));
            let block = self.held.len() - 1;
            if block % BLOCK_LANES == 0 {
                let mut chunk = [[f64::INFINITY; BLOCK_LANES]; 4];
                chunk[3] = [0.0; BLOCK_LANES];
                self.block.push(chunk);
            }
            if let Some(chunk) = self.block.last_mut() {
                let lane = block % BLOCK_LANES;
                (chunk[0][lane], chunk[1][lane], chunk[2][lane]) = (centre.x, centre.y, centre.z);
                chunk[3][lane] = radius;
            }
        }
    }
}

impl HeldBroad {
    /// The grouping of a pair set: `broad` holds each pair's two slots, `links` each slot's link;
    /// `group_root` gives, per link, the root of its rigid group when it moves (`None`: held). `None`
    /// when no link moves.
    pub(super) fn new(
        broad: &[(u32, u32, f64)],
        links: &[LinkId],
        group_root: &[Option<LinkId>],
    ) -> Option<HeldBroad> {
        let mut roots: Vec<LinkId> = links
            .iter()
            .filter_map(|l| group_root.get(l.0).copied().flatten())
            .collect();
        roots.sort_unstable();
        roots.dedup();
        if roots.is_empty() || roots.len() > MAX_GROUPS {
            return None;
        }
        let mut members = vec![Vec::new(); roots.len()];
        let mut held = Vec::new();
        // Per slot: its group, or its index among the held slots.
        let place: Vec<Result<usize, usize>> = links
            .iter()
            .enumerate()
            .map(
                |(slot, link)| match group_root.get(link.0).copied().flatten() {
                    Some(root) => {
                        let group = roots.binary_search(&root).unwrap_or_default();
                        members[group].push(slot as u32);
                        Ok(group)
                    }
                    None => {
                        held.push(slot as u32);
                        Err(held.len() - 1)
                    }
                },
            )
            .collect();
        let (groups, held_count) = (roots.len(), held.len());
        let mut always = vec![0u64; broad.len().div_ceil(64)];
        let mut by_group_held = vec![Vec::new(); groups * held_count];
        let mut by_groups = vec![Vec::new(); groups * groups];
        for (index, &(a, b, _)) in broad.iter().enumerate() {
            let at = |slot: u32| place.get(slot as usize).copied();
            match (at(a), at(b)) {
                (Some(Ok(g)), Some(Err(h))) | (Some(Err(h)), Some(Ok(g))) => {
                    by_group_held[g * held_count + h].push(index as u32);
                }
                (Some(Ok(g)), Some(Ok(k))) if g != k => {
                    by_groups[g.min(k) * groups + g.max(k)].push(index as u32);
                }
                _ => always[index / 64] |= 1 << (index % 64),
            }
        }
        let (group_held_offsets, group_held_pairs) = compressed(by_group_held);
        let (group_offsets, group_pairs) = compressed(by_groups);
        let group_links = (0..groups)
            .flat_map(|g| (g + 1..groups).map(move |k| (g, k)))
            .filter_map(|(g, k)| {
                let (start, end) = (
                    group_offsets[g * groups + k],
                    group_offsets[g * groups + k + 1],
                );
                (start < end).then_some((g as u32, k as u32, start, end))
            })
            .collect();
        Some(HeldBroad {
            group_root: roots,
            members,
            held,
            group_held_offsets,
            group_held_pairs,
            group_links,
            group_pairs,
            always,
        })
    }

    /// Measure the groups and the held slots at the first check: `centre` and `radius` per slot (a NaN
    /// centre: placement not usable), `placements` per link.
    pub(super) fn load<P: LinkPlacements + ?Sized>(
        &self,
        centre: &[Vector3<f64>],
        radius: &[f64],
        placements: &P,
        into: &mut HeldSpheres,
    ) {
        let sphere = |slot: u32| {
            let slot = slot as usize;
            (
                centre
                    .get(slot)
                    .copied()
                    .unwrap_or(Vector3::repeat(f64::NAN)),
                radius.get(slot).copied().unwrap_or(f64::NAN),
            )
        };
        let held: Vec<(Vector3<f64>, f64)> = self.held.iter().map(|&slot| sphere(slot)).collect();
        into.set_held(&held);
        into.group.clear();
        into.group.extend(
            self.group_root
                .iter()
                .zip(&self.members)
                .map(|(root, members)| {
                    let Some(root) = placements.placement(*root) else {
                        return (Point3::origin(), f64::INFINITY);
                    };
                    let (centre, radius) = enclosing(members.iter().map(|&slot| {
                        let (c, r) = sphere(slot);
                        (root.inverse_transform_point(&Point3::from(c)).coords, r)
                    }));
                    (Point3::from(centre), radius)
                }),
        );
    }

    /// Into `bits` (one per pair of the set), with the links at `placements` (every moving link's
    /// placement usable) and the spheres [`load`](Self::load) measured: every pair that may be within
    /// `margin` of contact (and the pairs no sphere stands for).
    pub(super) fn candidates<P: LinkPlacements + ?Sized>(
        &self,
        placements: &P,
        spheres: &mut HeldSpheres,
        margin: f64,
        bits: &mut Vec<u64>,
    ) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: `candidates_avx2` needs AVX2, and this CPU has it (checked just above).
            return unsafe { self.candidates_avx2(placements, spheres, margin, bits) };
        }
        self.candidates_lanes(placements, spheres, margin, bits);
    }

    /// [`HeldBroad::candidates`] compiled for AVX2 (four lanes per register; no fused multiply-add: the
    /// same bits).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn candidates_avx2<P: LinkPlacements + ?Sized>(
        &self,
        placements: &P,
        spheres: &mut HeldSpheres,
        margin: f64,
        bits: &mut Vec<u64>,
    ) {
        self.candidates_lanes(placements, spheres, margin, bits);
    }

    /// The work of [`HeldBroad::candidates`], inlined into each instruction set's copy.
    #[inline(always)]
    fn candidates_lanes<P: LinkPlacements + ?Sized>(
        &self,
        placements: &P,
        spheres: &mut HeldSpheres,
        margin: f64,
        bits: &mut Vec<u64>,
    ) {
        bits.clear();
        bits.extend_from_slice(&self.always);
        let mut keep = |pairs: &[PairWords]| {
            for &(word, mask) in pairs {
                if let Some(word) = bits.get_mut(word as usize) {
                    *word |= mask;
                }
            }
        };
        spheres.group_placed.clear();
        spheres
            .group_placed
            .extend(
                self.group_root
                    .iter()
                    .zip(&spheres.group)
                    .map(
                        |(root, (local, radius))| match placements.placement(*root) {
                            Some(placement) => (placement.transform_point(local).coords, *radius),
                            None => (Vector3::repeat(f64::NAN), *radius),
                        },
                    ),
            );
        let near = |a: &Vector3<f64>, b: &Vector3<f64>, reach: f64| {
            // Infinite reach (a group measured unusable) or a centre gone non-finite: keep the pairs.
            let squared = (a - b).norm_squared();
            squared < reach * reach || squared.is_nan() || reach.is_nan()
        };
        let held_count = self.held.len();
        let range = |offsets: &[u32], i: usize| {
            offsets.get(i).copied().unwrap_or_default() as usize
                ..offsets.get(i + 1).copied().unwrap_or_default() as usize
        };
        let mut near_held = std::mem::take(&mut spheres.near);
        for g in 0..spheres.group_placed.len() {
            let (centre, radius) = spheres.group_placed[g];
            held_near(&centre, radius + margin, spheres, &mut near_held);
            for &h in &near_held {
                let h = h as usize;
                if h < held_count {
                    keep(
                        &self.group_held_pairs[range(&self.group_held_offsets, g * held_count + h)],
                    );
                }
            }
        }
        spheres.near = near_held;
        for &(g, k, start, end) in &self.group_links {
            let (one, one_radius) = spheres.group_placed[g as usize];
            let (other, other_radius) = spheres.group_placed[k as usize];
            if near(&one, &other, one_radius + other_radius + margin) {
                keep(&self.group_pairs[start as usize..end as usize]);
            }
        }
    }
}

/// Into `near`: the index (in [`HeldBroad`]'s `held`) of every held sphere of `spheres` within `reach` plus
/// its radius of `centre` (and every one when a value is not finite: NaN keeps).
#[inline(always)]
fn held_near(centre: &Vector3<f64>, reach: f64, spheres: &HeldSpheres, near: &mut Vec<u32>) {
    near.clear();
    let (cx, cy, cz) = (centre.x, centre.y, centre.z);
    for (chunk, [bx, by, bz, block_radius]) in spheres.block.iter().enumerate() {
        // A block whose enclosing sphere is beyond the reach holds no sphere within it (the enclosing
        // radius has slack for rounding); NaN and infinite radii fail this test, so their lanes decide.
        let mut open = 0u32;
        for block in 0..BLOCK_LANES {
            let (dx, dy, dz) = (bx[block] - cx, by[block] - cy, bz[block] - cz);
            let far = block_radius[block] + reach;
            let beyond = dx * dx + dy * dy + dz * dz >= far * far;
            open |= u32::from(!beyond) << block;
        }
        while open != 0 {
            let block = chunk * BLOCK_LANES + open.trailing_zeros() as usize;
            open &= open - 1;
            // Past the last block: the padding, open only when a value is NaN.
            let Some([x, y, z, radius]) = spheres.held.get(block) else {
                break;
            };
            // Squared distance less squared reach, lane by lane: negative exactly when the distance is
            // below the reach (a rounded difference keeps the sign of the exact one).
            let mut excess = [0.0; LANES];
            for lane in 0..LANES {
                let (dx, dy, dz) = (cx - x[lane], cy - y[lane], cz - z[lane]);
                let lane_reach = reach + radius[lane];
                excess[lane] = dx * dx + dy * dy + dz * dz - lane_reach * lane_reach;
            }
            let mut hits = 0u32;
            for (lane, excess) in excess.iter().enumerate() {
                hits |= u32::from(*excess < 0.0 || excess.is_nan()) << lane;
            }
            while hits != 0 {
                let lane = block * LANES + hits.trailing_zeros() as usize;
                near.extend(spheres.held_index.get(lane));
                hits &= hits - 1;
            }
        }
    }
}

/// A sphere around `spheres` (centre, radius), with [`SLACK`] and a relative 1e-9 added for rounding;
/// infinitely large when a centre or radius is not finite.
fn enclosing(spheres: impl Iterator<Item = (Vector3<f64>, f64)> + Clone) -> (Vector3<f64>, f64) {
    let count = spheres.clone().count().max(1) as f64;
    let mean = spheres.clone().map(|(c, _)| c).sum::<Vector3<f64>>() / count;
    let reach = spheres
        .map(|(c, r)| (c - mean).norm() + r)
        .fold(
            0.0,
            |a: f64, b| if b.is_nan() { f64::NAN } else { a.max(b) },
        );
    let radius = reach + SLACK + 1e-9 * (mean.norm() + reach);
    if radius.is_finite() && mean.iter().all(|v| v.is_finite()) {
        (mean, radius)
    } else {
        (Vector3::zeros(), f64::INFINITY)
    }
}

/// An order of `spheres` (centre, radius) in which each run of [`LANES`] lies close together: split in
/// two at a multiple of [`LANES`] across the widest extent of the centres, recursively. Spheres with a
/// centre that is not finite come last.
fn spatial_order(spheres: &[(Vector3<f64>, f64)]) -> Vec<usize> {
    let (mut order, not_finite): (Vec<usize>, Vec<usize>) =
        (0..spheres.len()).partition(|&i| spheres[i].0.iter().all(|v| v.is_finite()));
    split_widest(&mut order, spheres);
    order.extend(not_finite);
    order
}

/// [`spatial_order`] of the finite spheres at `order`, in place.
fn split_widest(order: &mut [usize], spheres: &[(Vector3<f64>, f64)]) {
    if order.len() <= LANES {
        return;
    }
    let extent = |axis: usize| {
        let values = order.iter().map(|&i| spheres[i].0[axis]);
        let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        hi - lo
    };
    let axis = (1..3).fold(0, |best, axis| {
        if extent(axis) > extent(best) {
            axis
        } else {
            best
        }
    });
    order.sort_by(|&a, &b| {
        spheres[a].0[axis]
            .total_cmp(&spheres[b].0[axis])
            .then(a.cmp(&b))
    });
    let half = (order.len() / 2).div_ceil(LANES) * LANES;
    let (left, right) = order.split_at_mut(half.min(order.len()));
    split_widest(left, spheres);
    split_widest(right, spheres);
}

/// Lists of pairs (each increasing) as one array of [`PairWords`] and the offsets of each list's start
/// (and of the end).
fn compressed(lists: Vec<Vec<u32>>) -> (Vec<u32>, Vec<PairWords>) {
    let mut offsets = Vec::with_capacity(lists.len() + 1);
    let mut all: Vec<PairWords> = Vec::new();
    offsets.push(0);
    for list in lists {
        let start = all.len();
        for pair in list {
            let (word, bit) = (pair / 64, 1u64 << (pair % 64));
            let open = all.len() > start;
            match all.last_mut() {
                Some((last, mask)) if open && *last == word => *mask |= bit,
                _ => all.push((word, bit)),
            }
        }
        offsets.push(all.len() as u32);
    }
    (offsets, all)
}

/// Pairs of the set as bits of the candidate words: a word's index and the pairs' bits in it. A group's
/// pairs with one link are mostly neighbours in the set, so one word holds several.
type PairWords = (u32, u64);

/// The indices of the set bits of `bits`, in increasing order.
pub(super) fn set_bits(bits: &[u64]) -> impl Iterator<Item = usize> + '_ {
    bits.iter().enumerate().flat_map(|(word_index, &word)| {
        let mut word = word;
        std::iter::from_fn(move || {
            (word != 0).then(|| {
                let bit = word.trailing_zeros() as usize;
                word &= word - 1;
                word_index * 64 + bit
            })
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Isometry3;

    #[test]
    fn set_bits_come_in_order() {
        let bits = [0b1010_0001, 0, 1 << 63];
        assert_eq!(set_bits(&bits).collect::<Vec<_>>(), vec![0, 5, 7, 191]);
    }

    /// Links 0 and 1 are held; links 2 and 3 form one group (root 2), link 4 another (root 4).
    #[test]
    fn keeps_the_pairs_of_the_spheres_that_meet() {
        let links: Vec<LinkId> = (0..5).map(LinkId).collect();
        let roots = [
            None,
            None,
            Some(LinkId(2)),
            Some(LinkId(2)),
            Some(LinkId(4)),
        ];
        // Pairs: 2–0, 3–1, 2–4, 0–1 (both held: always).
        let broad = [(2, 0, 0.0), (3, 1, 0.0), (2, 4, 0.0), (0, 1, 0.0)];
        let grouping = HeldBroad::new(&broad, &links, &roots).unwrap();
        let at = |x: f64| Vector3::new(x, 0.0, 0.0);
        // Slot centres: held 0 at x=0, held 1 at x=10; group (2, 3) at x=3 and x=5; link 4 at x=20.
        let centre = [at(0.0), at(10.0), at(3.0), at(5.0), at(20.0)];
        let radius = [0.5; 5];
        let placements: Vec<Isometry3<f64>> = centre
            .iter()
            .map(|c| Isometry3::translation(c.x, c.y, c.z))
            .collect();
        let mut spheres = HeldSpheres::default();
        grouping.load(&centre, &radius, &placements, &mut spheres);
        // The group's sphere: centre x=4, radius 1.5 (+ slack).
        let mut bits = Vec::new();
        grouping.candidates(&placements, &mut spheres, 0.0, &mut bits);
        assert_eq!(set_bits(&bits).collect::<Vec<_>>(), vec![3]);
        grouping.candidates(&placements, &mut spheres, 2.1, &mut bits);
        assert_eq!(set_bits(&bits).collect::<Vec<_>>(), vec![0, 3]);
        grouping.candidates(&placements, &mut spheres, 4.1, &mut bits);
        assert_eq!(set_bits(&bits).collect::<Vec<_>>(), vec![0, 1, 3]);
        // The group moves next to link 4: 2–4 is kept.
        let mut moved = placements.clone();
        for link in [2, 3] {
            moved[link] = Isometry3::translation(15.0, 0.0, 0.0) * moved[link];
        }
        grouping.candidates(&moved, &mut spheres, 0.0, &mut bits);
        assert_eq!(set_bits(&bits).collect::<Vec<_>>(), vec![2, 3]);
    }

    /// The block spheres only skip what the lanes would reject: over random held spheres (some not
    /// finite) and query spheres, the held spheres found are those a test of every sphere finds.
    #[test]
    fn blocks_skip_only_spheres_out_of_reach() {
        let mut rng = crate::rng::SplitMix64::new(7);
        for count in [1, 7, 8, 9, 30, 64, 100] {
            let mut held: Vec<(Vector3<f64>, f64)> = (0..count)
                .map(|_| {
                    let c = Vector3::from_fn(|_, _| rng.uniform(-1.0, 1.0));
                    (c, rng.uniform(0.0, 0.2))
                })
                .collect();
            if count > 8 {
                held[3].0.x = f64::NAN;
            }
            let mut sorted = spatial_order(&held);
            sorted.sort_unstable();
            assert_eq!(sorted, (0..count).collect::<Vec<_>>(), "a permutation");
            let mut spheres = HeldSpheres::default();
            spheres.set_held(&held);
            let mut near = Vec::new();
            for query in 0..500 {
                let mut centre = Vector3::from_fn(|_, _| rng.uniform(-1.5, 1.5));
                let mut reach = rng.uniform(0.0, 0.5);
                // Unusable values keep every sphere.
                if query % 50 == 0 {
                    reach = f64::INFINITY;
                } else if query % 70 == 1 {
                    centre.y = f64::NAN;
                }
                held_near(&centre, reach, &spheres, &mut near);
                near.sort_unstable();
                let every: Vec<u32> = (0..count as u32)
                    .filter(|&h| {
                        let (c, r) = held[h as usize];
                        let excess = (centre - c).norm_squared() - (reach + r) * (reach + r);
                        excess < 0.0 || excess.is_nan()
                    })
                    .collect();
                assert_eq!(near, every, "{count} held spheres, reach {reach}");
            }
        }
    }

    #[test]
    fn no_moving_link_no_grouping() {
        let links = [LinkId(0), LinkId(1)];
        assert_eq!(HeldBroad::new(&[(0, 1, 1.0)], &links, &[None, None]), None);
    }
}
