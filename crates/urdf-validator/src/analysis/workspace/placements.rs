//! World placements of the links self-collision reads, for a batch of samples at once.
//!
//! [`forward_kinematics_links`](crate::model::kinematics::forward_kinematics_links) places one sample's
//! links one after the other: two isometry products per moving joint, in scalar registers. Here the
//! [`LANES`] samples of a batch are placed together, link by link, each product lane by lane (structure
//! of arrays), so the compiler evaluates several samples per vector register. Every product is written
//! in nalgebra's order of operations, and each joint's rotation is the scalar code's
//! [`axis_rotation`](crate::model::kinematics::axis_rotation), its sines and cosines from [`sincos`]
//! lane by lane: every placement is the same bits as the scalar code gives.

use nalgebra::{Isometry3, Quaternion, Translation3, Unit, UnitQuaternion, Vector3};

use super::sincos::sincos;
use crate::analysis::collision::{usable_parts, LinkPlacements};
use crate::model::kinematics::{joint_motion, Data};
use crate::model::{JointId, LinkId, Model, Motion};
use crate::urdf::robot::JointKind;

/// Samples placed together: one AVX-512 register of doubles. A batch's placements stay in the first-level
/// cache (7 × 8 doubles per link) for the checks that read them sample by sample.
pub(super) const LANES: usize = 8;

/// One value per sample of a batch.
type Lanes = [f64; LANES];

/// One isometry per sample of a batch: rotation quaternion (`i`, `j`, `k`, `w`) and translation.
#[derive(Clone, Debug)]
struct Poses {
    i: Lanes,
    j: Lanes,
    k: Lanes,
    w: Lanes,
    x: Lanes,
    y: Lanes,
    z: Lanes,
}

impl Poses {
    /// `pose` in every lane.
    fn splat(pose: &Isometry3<f64>) -> Poses {
        let Constant([i, j, k, w, x, y, z]) = Constant::new(pose);
        Poses {
            i: [i; LANES],
            j: [j; LANES],
            k: [k; LANES],
            w: [w; LANES],
            x: [x; LANES],
            y: [y; LANES],
            z: [z; LANES],
        }
    }

    /// Lane `k`'s isometry.
    fn lane(&self, k: usize) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::new(self.x[k], self.y[k], self.z[k]),
            UnitQuaternion::new_unchecked(Quaternion::new(
                self.w[k], self.i[k], self.j[k], self.k[k],
            )),
        )
    }
}

/// The right operand of [`compose`]: one isometry per lane, or the same one in every lane.
trait Operand {
    /// Lane `n`'s rotation (`i`, `j`, `k`, `w`) and translation.
    fn at(&self, n: usize) -> [f64; 7];
}

impl Operand for Poses {
    #[inline(always)]
    fn at(&self, n: usize) -> [f64; 7] {
        [
            self.i[n], self.j[n], self.k[n], self.w[n], self.x[n], self.y[n], self.z[n],
        ]
    }
}

/// The same isometry in every lane: rotation (`i`, `j`, `k`, `w`) and translation.
#[derive(Clone, Copy, Debug)]
struct Constant([f64; 7]);

impl Constant {
    fn new(pose: &Isometry3<f64>) -> Constant {
        let q = pose.rotation.quaternion();
        let t = &pose.translation.vector;
        Constant([q.i, q.j, q.k, q.w, t.x, t.y, t.z])
    }
}

impl Operand for Constant {
    #[inline(always)]
    fn at(&self, _: usize) -> [f64; 7] {
        self.0
    }
}

/// `a · b` lane by lane, as nalgebra computes `Isometry3 * Isometry3`: the translation is `a` applied to
/// `b`'s translation ([`place_point`]) and the rotation the quaternion product `a.r ⊗ b.r`.
#[inline(always)]
fn compose(a: &Poses, b: &impl Operand, out: &mut Poses) {
    for n in 0..LANES {
        let (ai, aj, ak, aw) = (a.i[n], a.j[n], a.k[n], a.w[n]);
        let [bi, bj, bk, bw, vx, vy, vz] = b.at(n);
        [out.x[n], out.y[n], out.z[n]] = place_point(a, n, [vx, vy, vz]);
        out.w[n] = aw * bw - ai * bi - aj * bj - ak * bk;
        out.i[n] = aw * bi + ai * bw + aj * bk - ak * bj;
        out.j[n] = aw * bj - ai * bk + aj * bw + ak * bi;
        out.k[n] = aw * bk + ai * bj - aj * bi + ak * bw;
    }
}

/// `point` placed by `pose` lane by lane (see [`place_point`]).
#[inline(always)]
fn transform_point(pose: &Poses, point: &[f64; 3]) -> [Lanes; 3] {
    let mut out = [[0.0; LANES]; 3];
    let [xs, ys, zs] = &mut out;
    for (n, ((x, y), z)) in xs.iter_mut().zip(ys).zip(zs).enumerate() {
        [*x, *y, *z] = place_point(pose, n, *point);
    }
    out
}

/// Lane `n` of `pose` applied to `[vx, vy, vz]`, as nalgebra computes `Isometry3 * Point3`: the
/// translation plus the point turned by the quaternion as `t = (r × v) · 2`, then `t · w + r × t + v`.
#[inline(always)]
fn place_point(pose: &Poses, n: usize, [vx, vy, vz]: [f64; 3]) -> [f64; 3] {
    let (ai, aj, ak, aw) = (pose.i[n], pose.j[n], pose.k[n], pose.w[n]);
    let tx = (aj * vz - ak * vy) * 2.0;
    let ty = (ak * vx - ai * vz) * 2.0;
    let tz = (ai * vy - aj * vx) * 2.0;
    let cx = aj * tz - ak * ty;
    let cy = ak * tx - ai * tz;
    let cz = ai * ty - aj * tx;
    [
        pose.x[n] + (tx * aw + cx + vx),
        pose.y[n] + (ty * aw + cy + vy),
        pose.z[n] + (tz * aw + cz + vz),
    ]
}

/// `placed` in the lanes whose joint value is zero (the scalar code composes nothing there), `moved`
/// in the others.
#[inline(always)]
fn select_moved(values: &Lanes, placed: &Poses, moved: &mut Poses) {
    for (n, value) in values.iter().enumerate() {
        if *value == 0.0 {
            moved.i[n] = placed.i[n];
            moved.j[n] = placed.j[n];
            moved.k[n] = placed.k[n];
            moved.w[n] = placed.w[n];
            moved.x[n] = placed.x[n];
            moved.y[n] = placed.y[n];
            moved.z[n] = placed.z[n];
        }
    }
}

/// Where a link's parent is.
#[derive(Clone, Debug)]
enum Parent {
    /// A link of the batch (its index), placed before this one.
    Placed(usize),
    /// A link no sampled joint moves: the parent's placement times the joint frame, the same in every
    /// sample (in every lane).
    Held(Box<Poses>),
}

/// What a link's joint adds after its frame.
#[derive(Clone, Debug)]
enum JointMotion {
    /// Nothing (a fixed joint, or one held at zero).
    None,
    /// The same motion in every sample (a joint the arm does not sample, held away from zero).
    Constant(Constant),
    /// A revolute joint's rotation about its unit axis; `None`: a degenerate axis (the identity).
    Revolute(Option<Unit<Vector3<f64>>>),
    /// A prismatic joint's translation along its axis.
    Prismatic(Vector3<f64>),
}

#[derive(Clone, Debug)]
struct Step {
    joint: JointId,
    parent: Parent,
    /// The joint frame in the parent link's frame.
    frame: Constant,
    motion: JointMotion,
}

/// The links to place for one arm and their placements in the current batch.
#[derive(Clone)]
pub(super) struct BatchPlacements {
    steps: Vec<Step>,
    /// Per link: its step, `usize::MAX` when it is not placed here.
    step_of: Vec<usize>,
    /// Per step: its joint's value in each sample (loaded only where the joint varies).
    values: Vec<Lanes>,
    /// The steps whose joint varies (a revolute or prismatic motion).
    varying: Vec<usize>,
    /// Per step: its placement in each sample.
    poses: Vec<Poses>,
    /// Working lanes: a link's frame before its joint's motion; a revolute joint's rotations (no
    /// translation); a prismatic joint's translations (no rotation).
    framed: Poses,
    turn: Poses,
    slide: Poses,
    /// Per lane: whether every link carrying a point is usable for self-collision ([`usable_parts`]).
    usable: [bool; LANES],
    /// Points carried by placed links (a step and a point in its link's frame: the centres of the
    /// links' bounding spheres; `None` when a point's link is not placed here, then no lane is usable),
    /// and where they are in each sample.
    points: Option<Vec<(usize, [f64; 3])>>,
    placed_points: Vec<[Lanes; 3]>,
}

impl BatchPlacements {
    /// For `links` (parents first: the moving links self-collision reads and their moving ancestors),
    /// with the joints `motion` varies sampled and every other joint at `q` (mimic relations applied
    /// here), every other link where `reference` has it; `points` (each a placed link and a point in its
    /// frame) are placed with them (see [`BatchPlacements::points`]).
    pub(super) fn new(
        model: &Model,
        links: &[LinkId],
        motion: &Motion,
        q: &[f64],
        reference: &Data,
        points: &[(LinkId, Vector3<f64>)],
    ) -> BatchPlacements {
        let mut q = q.to_vec();
        model.apply_mimic(&mut q);
        let mut index = vec![usize::MAX; model.parent_joint.len()];
        let mut steps = Vec::with_capacity(links.len());
        for &link in links {
            // A placed link moves, so it has a parent joint; a root is held where it is.
            let Some((joint, parent)) = model.parent_joint[link.0]
                .and_then(|j| model.joint_links[j.0].map(|(p, _)| (j, p)))
            else {
                continue;
            };
            let info = &model.joint_data[joint.0];
            let parent = match index[parent.0] {
                usize::MAX => Parent::Held(Box::new(Poses::splat(
                    &(reference.link_placement[parent.0] * info.placement),
                ))),
                placed => Parent::Placed(placed),
            };
            let moves = matches!(
                info.kind,
                JointKind::Revolute | JointKind::Continuous | JointKind::Prismatic
            );
            let value = q.get(joint.0).copied().unwrap_or(0.0);
            let motion = if !moves {
                JointMotion::None
            } else if motion.joints.get(joint.0) == Some(&true) {
                match info.kind {
                    JointKind::Prismatic => JointMotion::Prismatic(info.axis),
                    _ => JointMotion::Revolute(Unit::try_new(info.axis, 1e-9)),
                }
            } else if value == 0.0 {
                JointMotion::None
            } else {
                JointMotion::Constant(Constant::new(&joint_motion(info.kind, info.axis, value)))
            };
            index[link.0] = steps.len();
            steps.push(Step {
                joint,
                parent,
                frame: Constant::new(&info.placement),
                motion,
            });
        }
        let placed_points = vec![[[0.0; LANES]; 3]; points.len()];
        let points = points
            .iter()
            .map(|(link, p)| {
                let step = index.get(link.0).copied().filter(|&s| s < steps.len())?;
                Some((step, [p.x, p.y, p.z]))
            })
            .collect();
        let identity = Poses::splat(&Isometry3::identity());
        BatchPlacements {
            step_of: index,
            points,
            placed_points,
            values: vec![[0.0; LANES]; steps.len()],
            varying: (0..steps.len())
                .filter(|&s| {
                    matches!(
                        steps[s].motion,
                        JointMotion::Revolute(_) | JointMotion::Prismatic(_)
                    )
                })
                .collect(),
            poses: vec![identity.clone(); steps.len()],
            steps,
            framed: identity.clone(),
            turn: identity.clone(),
            slide: identity,
            usable: [false; LANES],
        }
    }

    /// Take sample `lane`'s joint values from `q` (a full configuration, mimic relations applied).
    pub(super) fn load(&mut self, lane: usize, q: &[f64]) {
        for &s in &self.varying {
            self.values[s][lane] = q.get(self.steps[s].joint.0).copied().unwrap_or(0.0);
        }
    }

    /// Place every link in every lane from the values loaded.
    pub(super) fn place(&mut self) {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            if has!("avx512f") {
                // SAFETY: `place_avx512` needs AVX-512F, and this CPU has it (checked just above).
                return unsafe { self.place_avx512() };
            }
            if has!("avx2") {
                // SAFETY: `place_avx2` needs AVX2, and this CPU has it (checked just above).
                return unsafe { self.place_avx2() };
            }
        }
        self.place_lanes();
    }

    /// [`BatchPlacements::place`] compiled for AVX2: four samples per vector register.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn place_avx2(&mut self) {
        self.place_lanes();
    }

    /// [`BatchPlacements::place`] compiled for AVX-512: eight samples per vector register.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f")]
    fn place_avx512(&mut self) {
        self.place_lanes();
    }

    #[inline(always)]
    fn place_lanes(&mut self) {
        for s in 0..self.steps.len() {
            let (done, rest) = self.poses.split_at_mut(s);
            let out = &mut rest[0];
            let step = &self.steps[s];
            let values = &self.values[s];
            if let (Parent::Placed(parent), JointMotion::None) = (&step.parent, &step.motion) {
                // A rigidly attached link (a finger of a held hand): its frame is its placement.
                compose(&done[*parent], &step.frame, out);
                continue;
            }
            // The link's frame: its parent's placement times the joint frame.
            let framed = match &step.parent {
                Parent::Placed(parent) => {
                    compose(&done[*parent], &step.frame, &mut self.framed);
                    &self.framed
                }
                Parent::Held(framed) => framed,
            };
            match &step.motion {
                JointMotion::None => out.clone_from(framed),
                JointMotion::Constant(motion) => compose(framed, motion, out),
                JointMotion::Revolute(axis) => {
                    // `axis_rotation` lane by lane: the half angles' sines and cosines, the axis scaled
                    // by the sine (a degenerate axis turns nothing).
                    let (mut sines, mut cosines) = ([0.0; LANES], [0.0; LANES]);
                    sincos(&values.map(|value| value / 2.0), &mut sines, &mut cosines);
                    for n in 0..LANES {
                        let (v, w) = match axis {
                            Some(axis) => (axis.as_ref() * sines[n], cosines[n]),
                            None => (Vector3::zeros(), 1.0),
                        };
                        (self.turn.i[n], self.turn.j[n]) = (v.x, v.y);
                        (self.turn.k[n], self.turn.w[n]) = (v.z, w);
                    }
                    compose(framed, &self.turn, out);
                    select_moved(values, framed, out);
                }
                JointMotion::Prismatic(axis) => {
                    for (n, value) in values.iter().enumerate() {
                        let t = axis * *value;
                        (self.slide.x[n], self.slide.y[n], self.slide.z[n]) = (t.x, t.y, t.z);
                    }
                    compose(framed, &self.slide, out);
                    select_moved(values, framed, out);
                }
            }
        }
        // Every link carrying a point usable (`usable_parts`) in a lane: its largest translation
        // coordinate is within the extent, and no coordinate is infinite or NaN (a product by zero is
        // zero exactly when the factor is finite; NaN sums to NaN). As comparisons, so they vectorise
        // across lanes.
        let (mut widest, mut finite) = ([0.0f64; LANES], [0.0f64; LANES]);
        for ((step, point), placed) in self.points.iter().flatten().zip(&mut self.placed_points) {
            let poses = &self.poses[*step];
            // Coordinate by coordinate, each across the lanes (one vector operation per step).
            for coordinate in [&poses.x, &poses.y, &poses.z] {
                for (widest, value) in widest.iter_mut().zip(coordinate) {
                    let size = value.abs();
                    *widest = if size > *widest { size } else { *widest };
                }
            }
            for coordinate in [
                &poses.x, &poses.y, &poses.z, &poses.i, &poses.j, &poses.k, &poses.w,
            ] {
                for (finite, value) in finite.iter_mut().zip(coordinate) {
                    *finite += value * 0.0;
                }
            }
            *placed = transform_point(poses, point);
        }
        self.usable = std::array::from_fn(|n| {
            self.points.is_some() && usable_parts([widest[n], 0.0, 0.0], [finite[n], 0.0, 0.0, 0.0])
        });
    }

    /// The points given to [`BatchPlacements::new`] where sample `lane` puts them, in that order (only
    /// meaningful when the lane is [`usable`](Self::usable)).
    pub(super) fn points(&self, lane: usize) -> impl ExactSizeIterator<Item = Vector3<f64>> + '_ {
        self.placed_points
            .iter()
            .map(move |[x, y, z]| Vector3::new(x[lane], y[lane], z[lane]))
    }

    /// Whether every point given to [`BatchPlacements::new`] is on a placed link, and every such link
    /// has a usable placement for self-collision in `lane`.
    pub(super) fn usable(&self, lane: usize) -> bool {
        self.usable.get(lane).copied().unwrap_or(false)
    }

    /// Sample `lane`'s link placements: this batch's for the links it places, `others` (indexed by link)
    /// for every other link.
    pub(super) fn lane<'a>(
        &'a self,
        lane: usize,
        others: &'a [Isometry3<f64>],
    ) -> LanePlacements<'a> {
        LanePlacements {
            batch: self,
            lane,
            others,
        }
    }
}

/// One sample's link placements ([`BatchPlacements::lane`]), each assembled from the batch's lanes when a
/// check reads it: a check reaches a few of the links a sample moves, so most are never read.
pub(super) struct LanePlacements<'a> {
    batch: &'a BatchPlacements,
    lane: usize,
    others: &'a [Isometry3<f64>],
}

impl LinkPlacements for LanePlacements<'_> {
    #[inline]
    fn placement(&self, link: LinkId) -> Option<Isometry3<f64>> {
        match self
            .batch
            .step_of
            .get(link.0)
            .and_then(|&s| self.batch.poses.get(s))
        {
            Some(poses) => Some(poses.lane(self.lane)),
            None => self.others.get(link.0).copied(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::kinematics::{forward_kinematics, forward_kinematics_links};
    use crate::rng::SplitMix64;
    use nalgebra::Point3;

    /// Every kind of step: a revolute joint about a skew axis under a held parent, a continuous one, a
    /// prismatic one, a mimic follower, a fixed link, a revolute joint with a degenerate axis, and one the
    /// arm does not sample, held at a non-zero angle.
    const ARM: &str = r#"<robot name="arm">
      <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
      <link name="e"/><link name="f"/><link name="g"/>
      <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
        <origin xyz="0.1 -0.2 0.3" rpy="0.3 -0.7 1.1"/><axis xyz="0.2 0.5 -0.8"/>
        <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
      <joint name="j2" type="continuous"><parent link="a"/><child link="b"/>
        <origin xyz="0 0 0.4" rpy="1.2 0 -0.4"/><axis xyz="0 1 0"/></joint>
      <joint name="j3" type="prismatic"><parent link="b"/><child link="c"/>
        <origin xyz="0.05 0.02 0.3"/><axis xyz="0.6 0 0.8"/>
        <limit lower="-0.2" upper="0.2" effort="1" velocity="1"/></joint>
      <joint name="j4" type="revolute"><parent link="c"/><child link="d"/>
        <origin xyz="0 0.1 0" rpy="0 0.4 0"/><axis xyz="1 0 0"/><mimic joint="j2" multiplier="-1.5" offset="0.2"/>
        <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
      <joint name="j5" type="fixed"><parent link="d"/><child link="e"/><origin xyz="0.01 0.02 0.03" rpy="0.1 0.2 0.3"/></joint>
      <joint name="j6" type="revolute"><parent link="e"/><child link="f"/><axis xyz="0 0 0"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="j7" type="revolute"><parent link="f"/><child link="g"/><origin xyz="0 0 0.2"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    </robot>"#;

    /// A point on a link the batch does not place (the held base) is placed nowhere: no lane is usable.
    #[test]
    fn a_point_off_the_placed_links_makes_no_lane_usable() {
        let (robot, _) = crate::urdf::parse_urdf(ARM, std::path::Path::new("arm.urdf")).unwrap();
        let (model, _) = Model::build(&robot);
        let sampled = [model.joint("j1").unwrap()];
        let motion = model.motion_of(&sampled);
        let links = [model.link("a").unwrap()];
        let q = model.zero_configuration();
        let mut reference = Data::new(&model);
        forward_kinematics(&model, &q, &mut reference);
        for (point_link, usable) in [("a", true), ("base", false)] {
            let point = [(model.link(point_link).unwrap(), Vector3::x())];
            let mut placements =
                BatchPlacements::new(&model, &links, &motion, &q, &reference, &point);
            (0..LANES).for_each(|lane| placements.load(lane, &q));
            placements.place();
            assert_eq!(placements.usable(0), usable, "{point_link}");
        }
    }

    /// The batch gives every link the same bits as placing each sample alone, in the vector code the
    /// CPU runs and in the portable code, with joint values that are random, exactly zero, NaN, tiny, a
    /// whole turn or several turns (the vector sine and cosine hand some of them to libm).
    #[test]
    fn a_batch_places_every_link_as_the_scalar_kinematics_does() {
        let (robot, _) = crate::urdf::parse_urdf(ARM, std::path::Path::new("arm.urdf")).unwrap();
        let (model, _) = Model::build(&robot);
        let joint = |name: &str| model.joint(name).unwrap();
        let sampled: Vec<JointId> = ["j1", "j2", "j3", "j6"].map(joint).to_vec();
        let motion = model.motion_of(&sampled);
        let links: Vec<LinkId> = model
            .topological_order
            .iter()
            .copied()
            .filter(|l| motion.links[l.0])
            .collect();
        assert_eq!(links.len(), 7, "every link but the base moves");
        let mut reference_q = model.zero_configuration();
        reference_q[joint("j7").0] = 0.7;
        let mut reference = Data::new(&model);
        forward_kinematics(&model, &reference_q, &mut reference);
        let mut rng = SplitMix64::new(5);
        // A point on every placed link, two on the last.
        let points: Vec<(LinkId, Vector3<f64>)> = links
            .iter()
            .chain(links.last())
            .map(|&link| (link, Vector3::from_fn(|_, _| rng.uniform(-0.5, 0.5))))
            .collect();
        let mut placements =
            BatchPlacements::new(&model, &links, &motion, &reference_q, &reference, &points);
        // Points on the first two links only (above the prismatic joint): only they decide a lane's use.
        let upper = &points[..2];
        let mut upper_placements =
            BatchPlacements::new(&model, &links, &motion, &reference_q, &reference, upper);
        for round in 0..200 {
            let mut rows = Vec::new();
            for lane in 0..LANES {
                let mut q = reference_q.clone();
                for &j in &sampled {
                    q[j.0] = match rng.next_u64() % 16 {
                        0 => 0.0,
                        1 if round % 7 == 0 => f64::NAN,
                        // Far out: a prismatic joint's link beyond the collision extent.
                        2 if round % 5 == 0 => 1e12,
                        // Half angles the vector sine and cosine leave to libm: next to zero, next to
                        // π, beyond 5π/4.
                        3 => rng.uniform(-1e-8, 1e-8),
                        4 => std::f64::consts::TAU * if round % 2 == 0 { 1.0 } else { -1.0 },
                        5 => rng.uniform(-12.0, 12.0),
                        _ => rng.uniform(-4.0, 4.0),
                    };
                }
                model.apply_mimic(&mut q);
                placements.load(lane, &q);
                upper_placements.load(lane, &q);
                rows.push(q);
            }
            for vector in [true, false] {
                if vector {
                    placements.place();
                    upper_placements.place();
                } else {
                    placements.place_lanes();
                    upper_placements.place_lanes();
                }
                for (lane, q) in rows.iter().enumerate() {
                    let mut alone = reference.clone();
                    forward_kinematics_links(&model, q, &links, &mut alone);
                    let mut batched = reference.clone();
                    let view = placements.lane(lane, &reference.link_placement);
                    for (link, placement) in batched.link_placement.iter_mut().enumerate() {
                        *placement = view.placement(LinkId(link)).unwrap_or(*placement);
                    }
                    let usable = |link: &LinkId| {
                        let p = &batched.link_placement[link.0];
                        let (r, t) = (p.rotation.coords, p.translation.vector);
                        usable_parts([t.x, t.y, t.z], [r.x, r.y, r.z, r.w])
                    };
                    assert_eq!(
                        placements.usable(lane),
                        links.iter().all(usable),
                        "lane {lane} round {round} vector {vector}"
                    );
                    assert_eq!(
                        upper_placements.usable(lane),
                        upper.iter().all(|(link, _)| usable(link)),
                        "upper links, lane {lane} round {round} vector {vector}"
                    );
                    // Each point where nalgebra's `Isometry3 * Point3` puts it, to the bit.
                    for (placed, (link, point)) in placements.points(lane).zip(&points) {
                        let expected = batched.link_placement[link.0] * Point3::from(*point);
                        assert_eq!(
                            placed.map(f64::to_bits),
                            expected.coords.map(f64::to_bits),
                            "point on {link:?} lane {lane} round {round} vector {vector}"
                        );
                    }
                    for link in &links {
                        let bits = |data: &Data| {
                            let p = &data.link_placement[link.0];
                            let (r, t) = (p.rotation.coords, p.translation.vector);
                            [r.x, r.y, r.z, r.w, t.x, t.y, t.z].map(f64::to_bits)
                        };
                        assert_eq!(
                            bits(&batched),
                            bits(&alone),
                            "link {link:?} lane {lane} round {round} vector {vector}"
                        );
                    }
                }
            }
        }
    }
}
