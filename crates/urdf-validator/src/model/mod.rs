//! The model stage: the kinematic tree built once from a [`crate::urdf::Robot`] (immutable, shared by every
//! analysis), forward kinematics and mass properties, with Pinocchio's Model/Data split.

pub mod kinematics;
pub mod overrides;
mod tree;
pub mod up_axis;

pub use kinematics::{forward_kinematics, Configuration, Data, JointData, LinkMass};
pub use tree::{JointId, LinkId, MimicLink, Model, Motion};
pub use up_axis::UpAxis;
