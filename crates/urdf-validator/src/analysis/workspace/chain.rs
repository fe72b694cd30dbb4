//! Fast forward kinematics of one arm: the tip position (and an approach direction) for vectors of the
//! arm's sampled joint values, with everything else at the reference pose.
//!
//! The chain is evaluated from the tip back to the base on vectors only (a plane rotation or Rodrigues'
//! rotation of a point, then the joint's fixed placement), which is what makes millions of samples per
//! second possible: no rotation matrices are composed. Fixed joints are folded into the next moving
//! joint's placement. [`BATCH`] samples are evaluated together, one joint at a time for all of them
//! (structure of arrays): the chain is read once per batch instead of once per sample, and the compiler
//! evaluates the samples' sines, cosines and rotations in vector registers. Every result is the same bits
//! as evaluating one sample at a time with `libm::sincos` and nalgebra's products.

use nalgebra::{Isometry3, Matrix3, Point3, Vector3};

use super::sincos::sincos;
use crate::analysis::arms::Arm;
use crate::model::kinematics::Data;
use crate::model::{JointId, Model};
use crate::rng::SplitMix64;
use crate::urdf::robot::JointKind;

/// Samples [`ArmChain::tips`] evaluates together.
pub const BATCH: usize = 64;

/// The sampled values of a batch of [`BATCH`] samples.
#[derive(Clone, Copy)]
pub enum Samples<'a> {
    /// `q[k]` holds sample `k`'s values, one per [`ArmChain::sampled`] joint.
    Rows(&'a [&'a [f64]; BATCH]),
    /// Drawn from the generator, sample by sample and joint by joint, each uniform within its joint's
    /// interval: what filling the rows in turn would give, computed where needed (the generator is left
    /// as it is).
    Drawn(&'a SplitMix64),
}

/// One value per sample of a batch.
type Lanes = [f64; BATCH];

/// One vector per sample of a batch, by component.
#[derive(Clone, Copy)]
struct Vectors {
    x: Lanes,
    y: Lanes,
    z: Lanes,
}

impl Vectors {
    /// `v` in every lane.
    fn splat(v: &Vector3<f64>) -> Self {
        Vectors {
            x: [v.x; BATCH],
            y: [v.y; BATCH],
            z: [v.z; BATCH],
        }
    }

    fn lane(&self, k: usize) -> Vector3<f64> {
        Vector3::new(self.x[k], self.y[k], self.z[k])
    }

    /// `v · by` added in every lane (`v · 1` is `v`, to the bit).
    #[inline(always)]
    fn add_scaled(&mut self, v: &Vector3<f64>, by: &Lanes) {
        for (k, by) in by.iter().enumerate() {
            self.x[k] += v.x * by;
            self.y[k] += v.y * by;
            self.z[k] += v.z * by;
        }
    }

    /// `m · v` in every lane, summed in nalgebra's order (column by column).
    #[inline(always)]
    fn rotate_by(&mut self, m: &Matrix3<f64>) {
        for k in 0..BATCH {
            let (x, y, z) = (self.x[k], self.y[k], self.z[k]);
            self.x[k] = m[(0, 0)] * x + m[(0, 1)] * y + m[(0, 2)] * z;
            self.y[k] = m[(1, 0)] * x + m[(1, 1)] * y + m[(1, 2)] * z;
            self.z[k] = m[(2, 0)] * x + m[(2, 1)] * y + m[(2, 2)] * z;
        }
    }
}

/// `(a, b)` turned by the angle with sines `s` and cosines `c`, lane by lane.
#[inline(always)]
fn plane_rotate(s: &Lanes, c: &Lanes, sign: f64, a: &mut Lanes, b: &mut Lanes) {
    for k in 0..BATCH {
        let s = s[k] * sign;
        let (x, y) = (a[k], b[k]);
        a[k] = c[k] * x - s * y;
        b[k] = s * x + c[k] * y;
    }
}

/// Where a chain joint's value comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Source {
    /// Sample `index` of the arm's sampled joints.
    Sampled(usize),
    /// `multiplier · sample[index] + offset` (a mimic follower of a sampled joint).
    Mimic {
        index: usize,
        multiplier: f64,
        offset: f64,
    },
    /// A constant (a mimic follower of a joint outside the arm, at the reference pose).
    Constant(f64),
}

/// One moving joint of the chain.
#[derive(Clone, Debug)]
struct ChainJoint {
    /// Placement of the joint frame in the previous moving joint's frame (fixed joints folded in).
    rotation: Matrix3<f64>,
    translation: Vector3<f64>,
    /// The placement's rotation is the identity and no translation component is −0, so points skip the
    /// product: `1·x + 0·y + 0·z + t` is `x + t` to the bit (a zero's sign included).
    translation_only: bool,
    /// Unit axis in the joint frame.
    axis: Vector3<f64>,
    /// When the axis is ±x, ±y or ±z: its index and sign (a plane rotation is cheaper than Rodrigues).
    principal: Option<(usize, f64)>,
    prismatic: bool,
    source: Source,
}

/// One arm ready for sampling.
#[derive(Clone, Debug)]
pub struct ArmChain {
    /// World placement of the arm's base link at the reference pose.
    base: Isometry3<f64>,
    joints: Vec<ChainJoint>,
    /// Tip frame in the last moving joint's frame.
    tip: Isometry3<f64>,
    /// The sampled joints, with the interval each is drawn from (continuous joints: a full turn).
    pub sampled: Vec<(JointId, f64, f64)>,
    /// World position of the first actuated joint's origin (what reach is measured from).
    pub shoulder: Vector3<f64>,
}

/// A tip pose from [`ArmChain::tips`]: position and, when asked for, the approach direction, both world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TipPose {
    /// Tip position.
    pub position: Vector3<f64>,
    /// The tool's approach axis in the world (unit), when an axis was given.
    pub approach: Vector3<f64>,
}

impl ArmChain {
    /// Build the chain of `arm` with the rest of the robot at the placement in `reference` (computed for
    /// configuration `q_reference`).
    pub fn new(model: &Model, arm: &Arm, reference: &Data, q_reference: &[f64]) -> ArmChain {
        // Joints without a usable interval stay at the reference pose, as in every other sampler.
        let sampled: Vec<(JointId, f64, f64)> = arm
            .sampled_joints(model)
            .into_iter()
            .filter_map(|j| {
                let (lo, hi) = model.joint_data[j.0].sampling_interval()?;
                Some((j, lo, hi))
            })
            .collect();
        let mut sampled_index = vec![None; model.joint_data.len()];
        for (i, &(j, _, _)) in sampled.iter().enumerate() {
            sampled_index[j.0] = Some(i);
        }
        let index_of = |j: JointId| sampled_index[j.0];
        let reference_value = |j: JointId| q_reference.get(j.0).copied().unwrap_or(0.0);
        let base = reference.link_placement[arm.base.0];
        let mut joints = Vec::new();
        let mut pending = Isometry3::identity();
        let mut shoulder = None;
        for &j in &arm.path {
            let data = &model.joint_data[j.0];
            let placement = pending * data.placement;
            let moving = matches!(
                data.kind,
                JointKind::Revolute | JointKind::Continuous | JointKind::Prismatic
            );
            if !moving {
                pending = placement;
                continue;
            }
            if shoulder.is_none() {
                // The first moving joint: nothing moves before it, so its origin is fixed.
                shoulder = Some((base * placement).translation.vector);
            }
            // A zero axis moves nothing (as in the full forward kinematics): fold it like a fixed joint.
            let Some(axis) = data.axis.try_normalize(1e-12) else {
                pending = placement;
                continue;
            };
            let source = match (index_of(j), model.mimic[j.0]) {
                (Some(i), _) => Source::Sampled(i),
                (None, Some(_)) => {
                    let (leader, multiplier, offset) = mimic_root(model, j);
                    match index_of(leader) {
                        Some(index) => Source::Mimic {
                            index,
                            multiplier,
                            offset,
                        },
                        None => Source::Constant(reference_value(j)),
                    }
                }
                (None, None) => Source::Constant(reference_value(j)),
            };
            let principal = (0..3)
                .find(|&k| axis[k].abs() == 1.0)
                .map(|k| (k, axis[k].signum()));
            let rotation = *placement.rotation.to_rotation_matrix().matrix();
            let translation = placement.translation.vector;
            let negative_zero = |v: f64| v.to_bits() == (-0.0f64).to_bits();
            let identity =
                (0..3).all(|r| (0..3).all(|c| rotation[(r, c)] == if r == c { 1.0 } else { 0.0 }));
            joints.push(ChainJoint {
                principal,
                rotation,
                translation,
                translation_only: identity && !translation.iter().any(|&v| negative_zero(v)),
                axis,
                prismatic: data.kind == JointKind::Prismatic,
                source,
            });
            pending = Isometry3::identity();
        }
        ArmChain {
            base,
            joints,
            tip: pending,
            sampled,
            shoulder: shoulder.unwrap_or(base.translation.vector),
        }
    }

    /// Number of sampled joints.
    pub fn dof(&self) -> usize {
        self.sampled.len()
    }

    /// The tip poses of a batch of samples: `q[k]` holds sample `k`'s values (one per
    /// [`ArmChain::sampled`] joint). `approach` is the tool's approach axis in the tip frame: with it, each
    /// pose carries its approach direction; without it, the tip position alone (what reach needs) and a
    /// zero approach.
    pub fn tips(&self, samples: &Samples, approach: Option<&Vector3<f64>>) -> [TipPose; BATCH] {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            if has!("avx512f") && has!("avx512dq") && has!("avx512vl") {
                // SAFETY: `tips_avx512` needs these three, and this CPU has them (checked just above).
                return unsafe { self.tips_avx512(samples, approach) };
            }
            if has!("avx2") {
                // SAFETY: `tips_avx2` needs AVX2, and this CPU has it (checked just above).
                return unsafe { self.tips_avx2(samples, approach) };
            }
        }
        self.tips_with::<false>(samples, approach)
    }

    /// [`ArmChain::tips`] compiled for AVX2: four samples per vector register, sines and cosines included.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn tips_avx2(&self, samples: &Samples, approach: Option<&Vector3<f64>>) -> [TipPose; BATCH] {
        self.tips_with::<true>(samples, approach)
    }

    /// [`ArmChain::tips`] compiled for AVX-512 (which also multiplies 64-bit integers and converts them to
    /// floats in vector registers: the drawn values too are computed several at once).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx512dq,avx512vl")]
    fn tips_avx512(&self, samples: &Samples, approach: Option<&Vector3<f64>>) -> [TipPose; BATCH] {
        self.tips_with::<true>(samples, approach)
    }

    /// [`ArmChain::tips`], with the lanes' sines and cosines from [`sincos`] when `VECTOR` (for a caller
    /// compiled for wide vectors), else from `libm::sincos` one by one: the same bits either way.
    #[inline(always)]
    fn tips_with<const VECTOR: bool>(
        &self,
        samples: &Samples,
        approach: Option<&Vector3<f64>>,
    ) -> [TipPose; BATCH] {
        match approach {
            Some(approach) => self.evaluate::<true, VECTOR>(samples, approach),
            None => self.evaluate::<false, VECTOR>(samples, &Vector3::zeros()),
        }
    }

    /// Walk from the tip back to the base; the approach direction is carried only when `APPROACH`.
    #[inline(always)]
    fn evaluate<const APPROACH: bool, const VECTOR: bool>(
        &self,
        samples: &Samples,
        approach: &Vector3<f64>,
    ) -> [TipPose; BATCH] {
        let mut point = Vectors::splat(&self.tip.translation.vector);
        let mut direction = Vectors::splat(&if APPROACH {
            self.tip.rotation * approach
        } else {
            Vector3::zeros()
        });
        // Per joint: its values, their sines and cosines (filled in place: 64 lanes returned by value
        // would be copied at every joint).
        let (mut value, mut s, mut c) = ([0.0; BATCH], [0.0; BATCH], [0.0; BATCH]);
        for joint in self.joints.iter().rev() {
            joint.values(samples, &self.sampled, &mut value);
            if joint.prismatic {
                point.add_scaled(&joint.axis, &value);
            } else {
                if VECTOR {
                    sincos(&value, &mut s, &mut c);
                } else {
                    for ((s, c), v) in s.iter_mut().zip(&mut c).zip(&value) {
                        (*s, *c) = libm::sincos(*v);
                    }
                }
                joint.rotate(&s, &c, &mut point);
                if APPROACH {
                    joint.rotate(&s, &c, &mut direction);
                }
            }
            if !joint.translation_only {
                point.rotate_by(&joint.rotation);
            }
            point.add_scaled(&joint.translation, &[1.0; BATCH]);
            if APPROACH {
                direction.rotate_by(&joint.rotation);
            }
        }
        std::array::from_fn(|k| TipPose {
            position: self
                .base
                .transform_point(&Point3::from(point.lane(k)))
                .coords,
            approach: if APPROACH {
                self.base.rotation * direction.lane(k)
            } else {
                Vector3::zeros()
            },
        })
    }
}

impl ChainJoint {
    /// `v` rotated about the joint axis by the angles with sines `s` and cosines `c`, lane by lane.
    #[inline(always)]
    fn rotate(&self, s: &Lanes, c: &Lanes, v: &mut Vectors) {
        match self.principal {
            Some((0, sign)) => plane_rotate(s, c, sign, &mut v.y, &mut v.z),
            Some((1, sign)) => plane_rotate(s, c, sign, &mut v.z, &mut v.x),
            Some((_, sign)) => plane_rotate(s, c, sign, &mut v.x, &mut v.y),
            None => {
                for k in 0..BATCH {
                    let turned = rotate(&self.axis, s[k], c[k], &v.lane(k));
                    (v.x[k], v.y[k], v.z[k]) = (turned.x, turned.y, turned.z);
                }
            }
        }
    }

    /// This joint's value in each sample of a batch, into `values`.
    #[inline(always)]
    fn values(&self, samples: &Samples, sampled: &[(JointId, f64, f64)], values: &mut Lanes) {
        let (index, multiplier, offset) = match self.source {
            Source::Sampled(i) => (i, 1.0, 0.0),
            Source::Mimic {
                index,
                multiplier,
                offset,
            } => (index, multiplier, offset),
            Source::Constant(v) => {
                *values = [v; BATCH];
                return;
            }
        };
        match samples {
            Samples::Rows(q) => {
                for (value, q) in values.iter_mut().zip(q.iter()) {
                    *value = q[index];
                }
            }
            Samples::Drawn(rng) => {
                let (_, lo, hi) = sampled[index];
                let (index, dof) = (index as u64, sampled.len() as u64);
                for (k, value) in (0u64..).zip(values.iter_mut()) {
                    *value = rng.uniform_ahead(k * dof + index, lo, hi);
                }
            }
        }
        if let Source::Mimic { .. } = self.source {
            for value in values.iter_mut() {
                *value = multiplier * *value + offset;
            }
        }
    }
}

/// The independent joint a mimic follower ultimately follows, with the composed relation:
/// `q[joint] = multiplier · q[leader] + offset` along the whole chain.
fn mimic_root(model: &Model, joint: JointId) -> (JointId, f64, f64) {
    let (mut current, mut multiplier, mut offset) = (joint, 1.0, 0.0);
    for _ in 0..model.joint_data.len() {
        let Some(link) = model.mimic[current.0] else {
            break;
        };
        offset += multiplier * link.offset;
        multiplier *= link.multiplier;
        current = link.leader;
    }
    (current, multiplier, offset)
}

/// Rodrigues: `v` rotated by the angle with sine `s` and cosine `c` about the unit `axis`.
#[inline]
fn rotate(axis: &Vector3<f64>, s: f64, c: f64, v: &Vector3<f64>) -> Vector3<f64> {
    v * c + axis.cross(v) * s + axis * (axis.dot(v) * (1.0 - c))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::kinematics::forward_kinematics;
    use crate::rng::SplitMix64;

    /// Every kind of joint the chain folds: principal and general axes (both signs), a prismatic joint,
    /// a fixed joint inside the chain, a mimic follower and a follower of that follower, a joint with a
    /// zero axis and a locked (empty-range) prismatic joint.
    const ARM: &str = r#"<robot name="a">
      <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="l4"/>
      <link name="l5"/><link name="l6"/><link name="l7"/><link name="l8"/><link name="l9"/><link name="l10"/><link name="tip"/>
      <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.3" rpy="0.1 0 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
      <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0.1 0.2" rpy="0 0.3 0"/><axis xyz="0 -1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
      <joint name="j3" type="continuous"><parent link="l2"/><child link="l3"/><origin xyz="0.2 0 0" rpy="0 0 0.5"/><axis xyz="0.6 0.8 0"/></joint>
      <joint name="f" type="fixed"><parent link="l3"/><child link="l4"/><origin xyz="0 0 0.1" rpy="0.2 0.1 0"/></joint>
      <joint name="j4" type="prismatic"><parent link="l4"/><child link="l5"/><origin xyz="0 0 0.05"/><axis xyz="1 0 0"/><limit lower="0" upper="0.2" effort="1" velocity="1"/></joint>
      <joint name="j5" type="revolute"><parent link="l5"/><child link="l6"/><origin xyz="0 0 0.1"/><axis xyz="-1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="j6" type="revolute"><parent link="l6"/><child link="l7"/><origin xyz="0 0.05 0.1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="j5" multiplier="-0.5" offset="0.2"/></joint>
      <joint name="j7" type="revolute"><parent link="l7"/><child link="l8"/><origin xyz="0 0 0.1" rpy="0.3 0 0"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="j6" multiplier="2" offset="-0.1"/></joint>
      <joint name="j8" type="revolute"><parent link="l8"/><child link="l9"/><origin xyz="0 0.1 0"/><axis xyz="0 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="j9" type="prismatic"><parent link="l9"/><child link="l10"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="0.3" upper="0.3" effort="1" velocity="1"/></joint>
      <joint name="t" type="fixed"><parent link="l10"/><child link="tip"/><origin xyz="0.03 0 0.12" rpy="0 1 0"/></joint>
    </robot>"#;

    /// The chain's tip, one sample at a time with nalgebra's products and `libm::sincos`: what a batch
    /// must equal to the bit.
    fn one_at_a_time(chain: &ArmChain, q: &[f64], approach: &Vector3<f64>) -> TipPose {
        let mut point = chain.tip.translation.vector;
        let mut direction = chain.tip.rotation * approach;
        for joint in chain.joints.iter().rev() {
            let mut values = [0.0; BATCH];
            joint.values(&Samples::Rows(&[q; BATCH]), &chain.sampled, &mut values);
            let value = values[0];
            if joint.prismatic {
                point += joint.axis * value;
            } else {
                let (s, c) = libm::sincos(value);
                let turn = |v: &Vector3<f64>| match joint.principal {
                    Some((0, sign)) => {
                        Vector3::new(v.x, c * v.y - s * sign * v.z, s * sign * v.y + c * v.z)
                    }
                    Some((1, sign)) => {
                        Vector3::new(c * v.x + s * sign * v.z, v.y, c * v.z - s * sign * v.x)
                    }
                    Some((_, sign)) => {
                        Vector3::new(c * v.x - s * sign * v.y, s * sign * v.x + c * v.y, v.z)
                    }
                    None => rotate(&joint.axis, s, c, v),
                };
                point = turn(&point);
                direction = turn(&direction);
            }
            point = joint.rotation * point + joint.translation;
            direction = joint.rotation * direction;
        }
        TipPose {
            position: chain.base.transform_point(&Point3::from(point)).coords,
            approach: chain.base.rotation * direction,
        }
    }

    fn bits(v: &Vector3<f64>) -> [u64; 3] {
        [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]
    }

    #[test]
    fn tip_equals_full_forward_kinematics() {
        let (robot, _) =
            crate::urdf::parse::parse_urdf(ARM, std::path::Path::new("a.urdf")).unwrap();
        let (model, _) = Model::build(&robot);
        let (base, tip) = (model.link("base").unwrap(), model.link("tip").unwrap());
        let arm = crate::analysis::arms::declared(&robot, &model, base, tip).unwrap();
        let q0 = model.zero_configuration();
        let mut data = Data::new(&model);
        forward_kinematics(&model, &q0, &mut data);
        let chain = ArmChain::new(&model, &arm, &data, &q0);
        // j6 and j7 follow j5, j9 has no range; j8 (zero axis) is sampled but moves nothing.
        assert_eq!(chain.dof(), 6);
        // Joints with and without a rotation in their placement.
        assert!(chain.joints.iter().any(|j| j.translation_only));
        assert!(chain.joints.iter().any(|j| !j.translation_only));
        let approach = Vector3::new(0.0, 0.6, 0.8);
        let mut rng = SplitMix64::new(3);
        for _ in 0..25 {
            let before = rng.clone();
            let samples: Vec<Vec<f64>> = (0..BATCH)
                .map(|_| {
                    chain
                        .sampled
                        .iter()
                        .map(|(_, lo, hi)| rng.uniform(*lo, *hi))
                        .collect()
                })
                .collect();
            let rows: [&[f64]; BATCH] = std::array::from_fn(|k| samples[k].as_slice());
            let batch = Samples::Rows(&rows);
            let poses = chain.tips(&batch, Some(&approach));
            let positions = chain.tips(&batch, None);
            // Both ways of computing the sines and cosines, whichever this CPU runs, and the values
            // drawn where needed rather than read.
            let vector = chain.tips_with::<true>(&batch, Some(&approach));
            let scalar = chain.tips_with::<false>(&batch, Some(&approach));
            let drawn = chain.tips(&Samples::Drawn(&before), Some(&approach));
            for (k, sample) in samples.iter().enumerate() {
                let mut q = q0.clone();
                for (value, (joint, _, _)) in sample.iter().zip(&chain.sampled) {
                    q[joint.0] = *value;
                }
                model.apply_mimic(&mut q);
                forward_kinematics(&model, &q, &mut data);
                let expected = data.link_placement[tip.0];
                let pose = poses[k];
                assert!((pose.position - expected.translation.vector).norm() < 1e-12);
                assert!((pose.approach - expected.rotation * approach).norm() < 1e-12);
                // Bit for bit what one sample at a time gives, with and without the approach.
                let single = one_at_a_time(&chain, sample, &approach);
                assert_eq!(bits(&pose.position), bits(&single.position));
                assert_eq!(bits(&pose.approach), bits(&single.approach));
                assert_eq!(bits(&positions[k].position), bits(&single.position));
                for pose in [vector[k], scalar[k], drawn[k]] {
                    assert_eq!(bits(&pose.position), bits(&single.position));
                    assert_eq!(bits(&pose.approach), bits(&single.approach));
                }
            }
        }
        // The shoulder is j1's origin.
        assert!((chain.shoulder - Vector3::new(0.0, 0.0, 0.3)).norm() < 1e-15);
    }
}
