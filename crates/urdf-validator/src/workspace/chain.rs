//! Fast forward kinematics of one arm: the tip position (and an approach direction) for a vector of the
//! arm's sampled joint values, with everything else at the reference pose.
//!
//! The chain is evaluated from the tip back to the base on vectors only (Rodrigues' rotation of a point,
//! then the joint's fixed placement), which is what makes millions of samples per second possible: no
//! rotation matrices are composed. Fixed joints are folded into the next moving joint's placement.

use nalgebra::{Isometry3, Matrix3, Point3, Vector3};

use crate::arms::Arm;
use crate::kinematics::Data;
use crate::model::{JointId, Model};
use crate::robot::JointKind;

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
    /// Unit axis in the joint frame.
    axis: Vector3<f64>,
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

/// A tip pose from [`ArmChain::tip`]: position and, when asked for, the approach direction, both world.
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
    pub fn new(
        model: &Model,
        arm: &Arm,
        reference: &Data,
        q_reference: &[f64],
    ) -> Option<ArmChain> {
        let sampled_ids = arm.sampled_joints(model);
        let sampled: Vec<(JointId, f64, f64)> = sampled_ids
            .iter()
            .map(|&j| {
                let data = &model.joint_data[j.0];
                let (lo, hi) = data
                    .range()
                    .unwrap_or((-std::f64::consts::PI, std::f64::consts::PI));
                (j, lo, hi)
            })
            .collect();
        let index_of = |j: JointId| sampled_ids.iter().position(|&s| s == j);
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
            let source = match (index_of(j), model.mimic[j.0]) {
                (Some(i), _) => Source::Sampled(i),
                (None, Some(mimic)) => match index_of(mimic.leader) {
                    Some(index) => Source::Mimic {
                        index,
                        multiplier: mimic.multiplier,
                        offset: mimic.offset,
                    },
                    None => Source::Constant(q_reference.get(j.0).copied().unwrap_or(0.0)),
                },
                (None, None) => Source::Constant(q_reference.get(j.0).copied().unwrap_or(0.0)),
            };
            let axis = data.axis.try_normalize(1e-12)?;
            joints.push(ChainJoint {
                rotation: *placement.rotation.to_rotation_matrix().matrix(),
                translation: placement.translation.vector,
                axis,
                prismatic: data.kind == JointKind::Prismatic,
                source,
            });
            pending = Isometry3::identity();
        }
        Some(ArmChain {
            base,
            joints,
            tip: pending,
            sampled,
            shoulder: shoulder.unwrap_or(base.translation.vector),
        })
    }

    /// Number of sampled joints.
    pub fn dof(&self) -> usize {
        self.sampled.len()
    }

    /// The tip pose for sampled values `q` (one per [`ArmChain::sampled`] joint). `approach` is the
    /// tool's approach axis in the tip frame (zero when not needed).
    pub fn tip(&self, q: &[f64], approach: &Vector3<f64>) -> TipPose {
        let mut point = self.tip.translation.vector;
        let mut direction = self.tip.rotation * approach;
        for joint in self.joints.iter().rev() {
            let value = match joint.source {
                Source::Sampled(i) => q[i],
                Source::Mimic {
                    index,
                    multiplier,
                    offset,
                } => multiplier * q[index] + offset,
                Source::Constant(v) => v,
            };
            if joint.prismatic {
                point += joint.axis * value;
            } else {
                let (s, c) = value.sin_cos();
                point = rotate(&joint.axis, s, c, &point);
                direction = rotate(&joint.axis, s, c, &direction);
            }
            point = joint.rotation * point + joint.translation;
            direction = joint.rotation * direction;
        }
        TipPose {
            position: self.base.transform_point(&Point3::from(point)).coords,
            approach: self.base.rotation * direction,
        }
    }
}

/// Rodrigues: `v` rotated by the angle with sine `s` and cosine `c` about the unit `axis`.
#[inline]
fn rotate(axis: &Vector3<f64>, s: f64, c: f64, v: &Vector3<f64>) -> Vector3<f64> {
    v * c + axis.cross(v) * s + axis * (axis.dot(v) * (1.0 - c))
}
