//! Forward kinematics in f64 with Pinocchio's Model/Data split: the [`Model`] holds each joint's placement
//! and axis and each link's mass; a [`Data`] is the scratch of one evaluation, so evaluations can run in
//! parallel over one shared model.

use nalgebra::{Isometry3, Quaternion, Translation3, Unit, UnitQuaternion, Vector3};

use crate::model::{JointId, LinkId, Model};
pub use crate::urdf::robot::{pose_isometry, quaternion_xyzw};
use crate::urdf::robot::{Joint, JointKind, Link};

/// Widest prismatic range sampled, in metres: wider is a placeholder for "unlimited" (SDFormat's
/// default limits are ±1e16), not a travel.
pub const MAX_PRISMATIC_TRAVEL: f64 = 1e3;

/// A joint's numbers: what kinematics needs, with non-finite input replaced by zero (the parser already
/// reported it).
#[derive(Clone, Debug)]
pub struct JointData {
    /// The joint type; `Fixed` when the file's type is unknown.
    pub kind: JointKind,
    /// Joint frame in the parent link frame.
    pub placement: Isometry3<f64>,
    /// Unit axis in the joint frame; zero when the file's axis is degenerate.
    pub axis: Vector3<f64>,
    /// Lower position limit, when declared and finite.
    pub lower: Option<f64>,
    /// Upper position limit, when declared and finite.
    pub upper: Option<f64>,
    /// Declared effort, when finite.
    pub effort: Option<f64>,
}

fn finite(value: f64) -> f64 {
    if value.is_finite() {
        value
    } else {
        0.0
    }
}

impl JointData {
    /// Numbers of one parsed joint.
    pub fn from_joint(joint: &Joint) -> Self {
        let axis = Vector3::from(joint.axis_or_default().map(finite));
        let axis = Unit::try_new(axis, 1e-9).map_or(Vector3::zeros(), |u| u.into_inner());
        let limit_value = |v: &Option<crate::diagnostics::span::Spanned<f64>>| {
            v.as_ref().map(|s| s.value).filter(|v| v.is_finite())
        };
        let limit = joint.limit.as_ref();
        JointData {
            kind: joint.kind.as_ref().map_or(JointKind::Fixed, |k| k.value),
            placement: pose_isometry(&joint.origin),
            axis,
            // urdfdom reads an absent lower/upper as 0 when <limit> exists.
            lower: limit.and_then(|l| {
                if l.lower.is_some() {
                    limit_value(&l.lower)
                } else {
                    Some(0.0)
                }
            }),
            upper: limit.and_then(|l| {
                if l.upper.is_some() {
                    limit_value(&l.upper)
                } else {
                    Some(0.0)
                }
            }),
            effort: limit.and_then(|l| limit_value(&l.effort)),
        }
    }

    /// True for revolute, continuous and prismatic joints (one scalar each).
    pub fn is_actuated(&self) -> bool {
        self.kind.is_actuated()
    }

    /// The position range when the joint has a usable one (revolute and prismatic with lower < upper).
    pub fn range(&self) -> Option<(f64, f64)> {
        match (self.kind, self.lower, self.upper) {
            (JointKind::Revolute | JointKind::Prismatic, Some(lo), Some(hi)) if lo < hi => {
                Some((lo, hi))
            }
            _ => None,
        }
    }

    /// The interval positions are sampled from: a full turn for continuous joints and for revolute
    /// ranges of a full turn or more, the limits otherwise; `None` when the joint cannot be sampled (not
    /// actuated, no usable range, or a prismatic range too wide to be a number of metres).
    pub fn sampling_interval(&self) -> Option<(f64, f64)> {
        use std::f64::consts::{PI, TAU};
        match (self.kind, self.range()) {
            (JointKind::Continuous, _) => Some((-PI, PI)),
            (JointKind::Revolute, Some((lo, hi))) if hi - lo >= TAU => Some((-PI, PI)),
            (JointKind::Revolute, Some((lo, hi))) if (hi - lo).is_finite() => Some((lo, hi)),
            (JointKind::Prismatic, Some((lo, hi))) if hi - lo <= MAX_PRISMATIC_TRAVEL => {
                Some((lo, hi))
            }
            _ => None,
        }
    }

    /// The motion of the joint at position `q`, in the joint frame.
    fn motion(&self, q: f64) -> Isometry3<f64> {
        joint_motion(self.kind, self.axis, q)
    }
}

/// The motion of a joint of `kind` along or about `axis` at position `q`, in the joint frame (the
/// identity for joints without a scalar position, and about a zero axis).
#[inline]
pub fn joint_motion(kind: JointKind, axis: Vector3<f64>, q: f64) -> Isometry3<f64> {
    match kind {
        JointKind::Revolute | JointKind::Continuous => match Unit::try_new(axis, 1e-9) {
            Some(axis) => Isometry3::from_parts(Translation3::identity(), axis_rotation(&axis, q)),
            None => Isometry3::identity(),
        },
        JointKind::Prismatic => {
            Isometry3::from_parts(Translation3::from(axis * q), UnitQuaternion::identity())
        }
        JointKind::Fixed | JointKind::Floating | JointKind::Planar => Isometry3::identity(),
    }
}

/// The rotation by `angle` about the unit `axis`: nalgebra's `UnitQuaternion::from_axis_angle`, with the
/// half angle's sine and cosine from `libm::sincos` (FreeBSD's msun in Rust: the same bits on every
/// platform, and what the workspace sampler computes for many samples at once).
pub fn axis_rotation(axis: &Unit<Vector3<f64>>, angle: f64) -> UnitQuaternion<f64> {
    let (sine, cosine) = libm::sincos(angle / 2.0);
    UnitQuaternion::new_unchecked(Quaternion::from_parts(cosine, axis.as_ref() * sine))
}

/// What a link contributes to the robot's mass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LinkMass {
    /// A declared, finite, non-negative mass with its centre in the link frame.
    Declared {
        /// Mass in kg.
        mass: f64,
        /// Centre of mass in the link frame.
        com: Vector3<f64>,
    },
    /// No inertial and no geometry: a frame, massless by construction.
    Massless,
    /// Geometry without a usable mass: its weight is unknown.
    Unknown,
}

impl LinkMass {
    /// Mass properties of one parsed link.
    pub fn from_link(link: &Link) -> Self {
        let declared = link.inertial.as_ref().and_then(|inertial| {
            let mass = inertial.mass.as_ref()?.value;
            (mass.is_finite() && mass >= 0.0).then(|| LinkMass::Declared {
                mass,
                com: Vector3::from(inertial.origin.xyz.map(finite)),
            })
        });
        match declared {
            Some(mass) => mass,
            None if link.is_bare() => LinkMass::Massless,
            None => LinkMass::Unknown,
        }
    }

    /// The mass in kg (0 unless declared).
    pub fn mass(&self) -> f64 {
        match self {
            LinkMass::Declared { mass, .. } => *mass,
            _ => 0.0,
        }
    }
}

/// One position per joint, indexed by [`JointId`]; values of non-actuated joints are ignored.
pub type Configuration = Vec<f64>;

/// Scratch of one forward-kinematics evaluation.
#[derive(Clone, Debug)]
pub struct Data {
    /// World (root frame) placement of each link frame; identity for links outside the main tree.
    pub link_placement: Vec<Isometry3<f64>>,
}

impl Data {
    /// Scratch sized for `model`.
    pub fn new(model: &Model) -> Self {
        Data {
            link_placement: vec![Isometry3::identity(); model.parent_joint.len()],
        }
    }
}

impl Model {
    /// The all-zero configuration.
    pub fn zero_configuration(&self) -> Configuration {
        vec![0.0; self.joint_data.len()]
    }

    /// Overwrite every mimic follower with `multiplier · q_leader + offset` (chains resolved leader first,
    /// in the order [`Model::mimic_order`] prepared once: linear in the number of joints).
    pub fn apply_mimic(&self, q: &mut Configuration) {
        for &JointId(joint) in &self.mimic_order {
            if let Some(link) = self.mimic[joint] {
                q[joint] = link.multiplier * q[link.leader.0] + link.offset;
            }
        }
    }

    /// World placement of the frame of joint `joint` (before its motion), given its parent's placement.
    pub fn joint_frame(&self, data: &Data, joint: JointId) -> Option<Isometry3<f64>> {
        let (parent, _) = self.joint_links[joint.0]?;
        Some(data.link_placement[parent.0] * self.joint_data[joint.0].placement)
    }
}

/// Fill `data.link_placement` for configuration `q` (mimic relations must already be applied).
pub fn forward_kinematics(model: &Model, q: &[f64], data: &mut Data) {
    forward_kinematics_links(model, q, &model.topological_order, data);
}

/// Update the placements of `links` only (parents before children, e.g. a subtree in topological order),
/// keeping every other link where `data` has it.
pub fn forward_kinematics_links(model: &Model, q: &[f64], links: &[LinkId], data: &mut Data) {
    for &link in links {
        data.link_placement[link.0] = match model.parent_joint[link.0]
            .and_then(|j| model.joint_links[j.0].map(|(p, _)| (j, p)))
        {
            Some((joint, parent)) => {
                let info = &model.joint_data[joint.0];
                let value = q.get(joint.0).copied().unwrap_or(0.0);
                let placed = data.link_placement[parent.0] * info.placement;
                // A joint at zero (and a fixed one) moves nothing: its motion is the identity, and
                // composing with it would change no bit of the placement, only cost a sine and cosine.
                if value == 0.0
                    || matches!(
                        info.kind,
                        JointKind::Fixed | JointKind::Floating | JointKind::Planar
                    )
                {
                    placed
                } else {
                    placed * info.motion(value)
                }
            }
            None => model.up.root_placement(),
        };
    }
}

/// World position of `link`'s frame origin.
pub fn link_origin(data: &Data, link: LinkId) -> Vector3<f64> {
    data.link_placement[link.0].translation.vector
}

#[cfg(test)]
mod tests {
    use super::*;

    fn prismatic(lower: f64, upper: f64) -> JointData {
        JointData {
            kind: JointKind::Prismatic,
            placement: Isometry3::identity(),
            axis: Vector3::z(),
            lower: Some(lower),
            upper: Some(upper),
            effort: None,
        }
    }

    #[test]
    fn a_placeholder_prismatic_range_is_not_sampled() {
        assert_eq!(prismatic(-0.1, 0.2).sampling_interval(), Some((-0.1, 0.2)));
        assert_eq!(prismatic(-1e16, 1e16).sampling_interval(), None);
    }
}
