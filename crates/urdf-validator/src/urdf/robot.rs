//! The typed robot as written in the file: every value keeps the span it was read from.
//!
//! Values that the file omits stay `None` here; defaults are applied by the analyses that need them, so the
//! checks can tell "absent" from "zero".

use nalgebra::{Isometry3, Translation3, UnitQuaternion};

use crate::diagnostics::span::{Span, Spanned};

/// The standard gravity, m/s² in the root frame (Pinocchio's and MuJoCo's default): what a robot that
/// declares none ([`Robot::gravity`] `None`) is under.
pub const STANDARD_GRAVITY: [f64; 3] = [0.0, 0.0, -9.81];

/// A parsed `<robot>`.
#[derive(Clone, Debug, Default)]
pub struct Robot {
    /// `name` of `<robot>`.
    pub name: Option<Spanned<String>>,
    /// Where a finding about the whole robot points: the `name` of `<robot>` (of the analysed SDFormat
    /// `<model>`, of MJCF's `<mujoco model>`), else the tag; never the whole element.
    pub span: Span,
    /// `<link>` elements in document order.
    pub links: Vec<Link>,
    /// `<joint>` elements in document order.
    pub joints: Vec<Joint>,
    /// Robot-level `<material>` definitions.
    pub materials: Vec<Material>,
    /// `<transmission>` elements (old and ROS-control formats).
    pub transmissions: Vec<Transmission>,
    /// `<gazebo>` extension blocks.
    pub gazebo: Vec<GazeboBlock>,
    /// `<ros2_control>` blocks.
    pub ros2_control: Vec<Ros2Control>,
    /// The format it was read from: SDFormat leaves effort and velocity limits optional, URDF does not.
    pub format: crate::input::Format,
    /// Link pairs the file itself never lets collide (MJCF: `<contact><exclude>`, pairs no two of whose
    /// geoms pass `contype`/`conaffinity`, MuJoCo's parent filter), by link name: the self-collision
    /// check allows them as it allows an SRDF's `disable_collisions`.
    pub collision_filtered: Vec<(String, String)>,
    /// Named poses the file itself defines (MJCF: `<keyframe><key>`), for `--pose key:NAME`.
    pub keyframes: Vec<Keyframe>,
    /// The gravity the file declares, m/s² in the root frame (MJCF: `<option gravity>`, zero under
    /// `<flag gravity="disable">`); `None` for the standard (0, 0, −9.81).
    pub gravity: Option<Spanned<[f64; 3]>>,
    /// Bodies whose weight the simulator carries (MJCF `gravcomp`: 1 carries all of it), by link name.
    pub gravity_compensation: Vec<(String, Spanned<f64>)>,
    /// Per link (by name) whose collisions the file filters: each collision's `(contype, conaffinity)`
    /// bit masks, in the order of the link's `collisions` (MJCF). A link without an entry collides with
    /// everything.
    pub contact_bits: std::collections::HashMap<String, Vec<(u32, u32)>>,
    /// The ground planes of the world the robot starts on (MJCF world `<geom type="plane">`).
    pub world_planes: Vec<WorldPlane>,
    /// The simulator computes no contacts at all (MJCF `<option><flag contact="disable">` or
    /// `constraint="disable"`).
    pub contacts_disabled: bool,
    /// Where a fix adds the pairs the file excludes from contact (MJCF: the first `<contact>` section,
    /// else the `<mujoco>` element, which then gets one).
    pub contact_section: Option<ContactSection>,
}

/// Whether two geoms with these `(contype, conaffinity)` bit masks may collide (MuJoCo's rule:
/// `contype1 & conaffinity2` or `contype2 & conaffinity1` is not 0).
pub fn contact_bits_meet(a: (u32, u32), b: (u32, u32)) -> bool {
    a.0 & b.1 != 0 || b.0 & a.1 != 0
}

/// A plane of the world (MuJoCo: infinite, solid below its surface).
#[derive(Clone, Debug)]
pub struct WorldPlane {
    /// Its name, when it has one.
    pub name: Option<String>,
    /// The element.
    pub span: Span,
    /// A point of its surface, in the root frame.
    pub point: [f64; 3],
    /// Its unit normal (pointing out of the solid), in the root frame.
    pub normal: [f64; 3],
    /// Its `(contype, conaffinity)` bit masks.
    pub bits: (u32, u32),
}

/// Where the file's contact exclusions go.
#[derive(Clone, Copy, Debug)]
pub enum ContactSection {
    /// An existing `<contact>` element: excludes are added as its first children.
    Existing(Span),
    /// No `<contact>` yet: one is added as the first child of this (the root) element.
    Missing(Span),
}

/// A pose the robot file defines (an MJCF `<key>`), already in this robot's joint values.
#[derive(Clone, Debug, Default)]
pub struct Keyframe {
    /// Its name (an unnamed MJCF key is named by its index, `0`, `1`, ...).
    pub name: String,
    /// The element.
    pub span: Span,
    /// The value of each joint it sets (radians or metres, as the robot's joints take them).
    pub joints: Vec<(String, f64)>,
    /// What of the key the robot cannot take, for the report's notes.
    pub notes: Vec<String>,
    /// Where the key puts a floating root's link frame in the frame it has at `qpos0` (`None`: where it
    /// is); the analyses keep the root there (see `notes`), the start-contact check moves it.
    pub base: Option<Pose>,
    /// The other bodies with a free joint the key moves, by link name, and where it puts each in the
    /// world; as `base`, only the start-contact check moves them.
    pub free_bodies: Vec<(String, Pose)>,
}

/// A rigid-body transform as `xyz` + fixed-axis `rpy` (radians), or `xyz` + `quat_xyzw` (URDF 1.1).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pose {
    /// Translation in metres.
    pub xyz: [f64; 3],
    /// Roll, pitch, yaw about fixed x, y, z.
    pub rpy: [f64; 3],
    /// `quat_xyzw` as written (x, y, z, w; not normalised), when the file's URDF version lets urdfdom read
    /// it (1.1 and later). When present it is the rotation and `rpy` is not used.
    pub quat_xyzw: Option<[f64; 4]>,
    /// The `<origin>` element, when written.
    pub span: Option<Span>,
    /// Where its attributes' values are, when written (for fixes that rewrite them).
    pub values: PoseValues,
}

/// The spans of an `<origin>`'s attribute values (without quotes), each when written.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PoseValues {
    /// `xyz`.
    pub xyz: Option<Span>,
    /// `rpy`.
    pub rpy: Option<Span>,
    /// `quat_xyzw`.
    pub quat_xyzw: Option<Span>,
}

/// A `<link>`.
#[derive(Clone, Debug)]
pub struct Link {
    /// `name` attribute.
    pub name: Spanned<String>,
    /// The `<link>` element.
    pub span: Span,
    /// `<inertial>`, if any.
    pub inertial: Option<Inertial>,
    /// `<visual>` elements.
    pub visuals: Vec<Shape>,
    /// `<collision>` elements.
    pub collisions: Vec<Shape>,
}

impl Link {
    /// The `world` link SDFormat and MJCF models hang from (no mass, no geometry), spanning `span`.
    pub fn world(span: Span) -> Link {
        Link {
            name: Spanned {
                value: "world".to_string(),
                span,
            },
            span,
            inertial: None,
            visuals: Vec::new(),
            collisions: Vec::new(),
        }
    }

    /// True when the link carries neither mass nor geometry: a coordinate frame.
    pub fn is_bare(&self) -> bool {
        self.inertial.is_none() && self.visuals.is_empty() && self.collisions.is_empty()
    }
}

/// An `<inertial>`.
#[derive(Clone, Debug)]
pub struct Inertial {
    /// The `<inertial>` element.
    pub span: Span,
    /// Centre-of-mass frame.
    pub origin: Pose,
    /// `<mass value>`.
    pub mass: Option<Spanned<f64>>,
    /// `<inertia>`, present only when all six components parsed.
    pub inertia: Option<Inertia>,
}

/// The six independent components of a symmetric inertia tensor, about the inertial frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertia {
    /// The `<inertia>` element.
    pub span: Span,
    /// ixx
    pub ixx: f64,
    /// ixy
    pub ixy: f64,
    /// ixz
    pub ixz: f64,
    /// iyy
    pub iyy: f64,
    /// iyz
    pub iyz: f64,
    /// izz
    pub izz: f64,
    /// The spans of the six attribute values (without quotes), in the order ixx, ixy, ixz, iyy, iyz, izz
    /// (SDFormat: the `<inertia>` element for each).
    pub values: [Span; 6],
}

impl Inertia {
    /// The full 3×3 tensor, row-major.
    pub fn matrix(&self) -> [[f64; 3]; 3] {
        [
            [self.ixx, self.ixy, self.ixz],
            [self.ixy, self.iyy, self.iyz],
            [self.ixz, self.iyz, self.izz],
        ]
    }

    /// The principal moments (the tensor's eigenvalues), ascending; `None` when a component is not finite.
    pub fn principal_moments(&self) -> Option<[f64; 3]> {
        principal_moments(&self.matrix())
    }
}

/// The principal moments of a symmetric 3×3 tensor (its eigenvalues), ascending; `None` when a component is
/// not finite.
pub fn principal_moments(tensor: &[[f64; 3]; 3]) -> Option<[f64; 3]> {
    if tensor.iter().flatten().any(|v| !v.is_finite()) {
        return None;
    }
    let m = nalgebra::Matrix3::from_fn(|r, c| tensor[r][c]);
    let mut values: [f64; 3] = nalgebra::SymmetricEigen::new(m).eigenvalues.into();
    values.sort_by(f64::total_cmp);
    Some(values)
}

/// A `<visual>` or `<collision>`.
#[derive(Clone, Debug)]
pub struct Shape {
    /// The element.
    pub span: Span,
    /// Optional `name`.
    pub name: Option<String>,
    /// Placement relative to the link frame.
    pub origin: Pose,
    /// The shape, when `<geometry>` holds a valid one.
    pub geometry: Option<Spanned<Geometry>>,
    /// `<material>` of a visual (name reference and/or inline colour).
    pub material: Option<MaterialRef>,
}

/// A geometric primitive or a mesh.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// `<box size>`: full side lengths.
    Box {
        /// x, y, z side lengths in metres.
        size: [f64; 3],
    },
    /// `<cylinder>` along the local z axis.
    Cylinder {
        /// Radius in metres.
        radius: f64,
        /// Length in metres.
        length: f64,
    },
    /// `<sphere>`.
    Sphere {
        /// Radius in metres.
        radius: f64,
    },
    /// `<capsule>` (URDF 1.x extension some tools accept), along z.
    Capsule {
        /// Radius in metres.
        radius: f64,
        /// Length of the cylindrical part in metres.
        length: f64,
    },
    /// `<mesh filename scale>`.
    Mesh {
        /// The URI as written.
        filename: Spanned<String>,
        /// Per-axis scale (default 1 1 1).
        scale: [f64; 3],
    },
}

/// The `<material>` of a visual.
#[derive(Clone, Debug)]
pub struct MaterialRef {
    /// The element.
    pub span: Span,
    /// `name`, possibly referring to a robot-level material.
    pub name: Option<String>,
    /// True when the element defines a colour or texture itself.
    pub defines_appearance: bool,
}

/// A robot-level `<material>` definition.
#[derive(Clone, Debug)]
pub struct Material {
    /// `name`.
    pub name: Spanned<String>,
    /// `<color rgba>`.
    pub rgba: Option<[f64; 4]>,
    /// `<texture filename>` (optional: real files carry `<texture/>` without it).
    pub texture: Option<String>,
}

/// The six URDF joint types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// Rotation about the axis within limits.
    Revolute,
    /// Unlimited rotation about the axis.
    Continuous,
    /// Translation along the axis within limits.
    Prismatic,
    /// No motion.
    Fixed,
    /// Six degrees of freedom.
    Floating,
    /// Motion in the plane normal to the axis.
    Planar,
}

impl JointKind {
    /// Parse a `type` attribute.
    pub fn parse(text: &str) -> Option<Self> {
        Some(match text {
            "revolute" => JointKind::Revolute,
            "continuous" => JointKind::Continuous,
            "prismatic" => JointKind::Prismatic,
            "fixed" => JointKind::Fixed,
            "floating" => JointKind::Floating,
            "planar" => JointKind::Planar,
            _ => return None,
        })
    }

    /// The keyword as written in URDF.
    pub fn as_str(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Continuous => "continuous",
            JointKind::Prismatic => "prismatic",
            JointKind::Fixed => "fixed",
            JointKind::Floating => "floating",
            JointKind::Planar => "planar",
        }
    }

    /// One scalar degree of freedom driven by a motor: revolute, continuous or prismatic.
    pub fn is_actuated(self) -> bool {
        matches!(
            self,
            JointKind::Revolute | JointKind::Continuous | JointKind::Prismatic
        )
    }
}

/// A `<joint>`.
#[derive(Clone, Debug)]
pub struct Joint {
    /// `name`.
    pub name: Spanned<String>,
    /// The `<joint>` element.
    pub span: Span,
    /// `type`; `None` when absent or not a URDF type (a finding says which).
    pub kind: Option<Spanned<JointKind>>,
    /// Placement of the joint frame in the parent link frame.
    pub origin: Pose,
    /// `<parent link>`.
    pub parent: Option<Spanned<String>>,
    /// `<child link>`.
    pub child: Option<Spanned<String>>,
    /// `<axis xyz>` when written (URDF's default is 1 0 0).
    pub axis: Option<Spanned<[f64; 3]>>,
    /// `<limit>`.
    pub limit: Option<Limit>,
    /// `<dynamics>`.
    pub dynamics: Option<Dynamics>,
    /// `<mimic>`.
    pub mimic: Option<Mimic>,
    /// `<safety_controller>`.
    pub safety_controller: Option<SafetyController>,
    /// `<calibration>`.
    pub calibration: Option<Calibration>,
}

impl Joint {
    /// The axis with URDF's default (1, 0, 0) applied.
    pub fn axis_or_default(&self) -> [f64; 3] {
        self.axis.as_ref().map_or([1.0, 0.0, 0.0], |a| a.value)
    }
}

/// A `<limit>`; absent attributes stay `None`.
#[derive(Clone, Debug)]
pub struct Limit {
    /// The element.
    pub span: Span,
    /// `lower` (urdfdom's default: 0).
    pub lower: Option<Spanned<f64>>,
    /// `upper` (urdfdom's default: 0).
    pub upper: Option<Spanned<f64>>,
    /// `effort` (required by urdfdom).
    pub effort: Option<Spanned<f64>>,
    /// `velocity` (required by urdfdom).
    pub velocity: Option<Spanned<f64>>,
}

/// A `<dynamics>`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Dynamics {
    /// Viscous damping.
    pub damping: Option<f64>,
    /// Coulomb friction.
    pub friction: Option<f64>,
}

/// A `<mimic>`: `q = multiplier · q_leader + offset`.
#[derive(Clone, Debug)]
pub struct Mimic {
    /// The element.
    pub span: Span,
    /// The leader joint's name.
    pub joint: Spanned<String>,
    /// Default 1.
    pub multiplier: f64,
    /// Default 0.
    pub offset: f64,
}

/// A `<safety_controller>`.
#[derive(Clone, Copy, Debug, Default)]
pub struct SafetyController {
    /// `soft_lower_limit`.
    pub soft_lower_limit: Option<f64>,
    /// `soft_upper_limit`.
    pub soft_upper_limit: Option<f64>,
    /// `k_position`.
    pub k_position: Option<f64>,
    /// `k_velocity` (required by urdfdom).
    pub k_velocity: Option<f64>,
}

/// A `<calibration>`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Calibration {
    /// `rising`.
    pub rising: Option<f64>,
    /// `falling`.
    pub falling: Option<f64>,
    /// `reference_position`.
    pub reference_position: Option<f64>,
}

/// A `<transmission>`, in the old (`type` attribute) or the ROS-control (`<type>` element) format.
#[derive(Clone, Debug)]
pub struct Transmission {
    /// `name`.
    pub name: Option<String>,
    /// The element.
    pub span: Span,
    /// The transmission type, from the attribute or the `<type>` element.
    pub kind: Option<String>,
    /// Every joint the transmission names (`<joint name>` and PR2-style `<flexJoint>`, `<rollJoint>`, ...).
    pub joints: Vec<Spanned<String>>,
}

/// A `<gazebo>` block, kept for its reference.
#[derive(Clone, Debug)]
pub struct GazeboBlock {
    /// The element.
    pub span: Span,
    /// `reference` (a link or joint name); robot-level blocks have none.
    pub reference: Option<Spanned<String>>,
    /// A `<preserveFixedJoint>` or `<disableFixedJointLumping>` child set to `true`, `yes` or `1`: Gazebo's
    /// URDF converter keeps the referenced fixed joint instead of lumping its child link into the parent.
    pub keeps_fixed_joint: bool,
}

/// A `<ros2_control>` block, kept for its joint names.
#[derive(Clone, Debug)]
pub struct Ros2Control {
    /// `name`.
    pub name: Option<String>,
    /// The element.
    pub span: Span,
    /// `<joint name>` entries.
    pub joints: Vec<Spanned<String>>,
}

/// The rigid transform of a URDF `<origin>`: rotation `Rz(yaw)·Ry(pitch)·Rx(roll)` (or the `quat_xyzw`
/// quaternion when given), then translation.
pub fn pose_isometry(pose: &Pose) -> Isometry3<f64> {
    let [x, y, z] = pose.xyz.map(zero_if_not_finite);
    let rotation = match pose.quat_xyzw {
        Some(q) => quaternion_xyzw(q),
        None => {
            let [roll, pitch, yaw] = pose.rpy.map(zero_if_not_finite);
            UnitQuaternion::from_euler_angles(roll, pitch, yaw)
        }
    };
    Isometry3::from_parts(Translation3::new(x, y, z), rotation)
}

/// A `quat_xyzw` as urdfdom_headers' `Rotation::initQuaternion` reads it: normalised, and the identity when
/// its norm is zero (`Rotation::normalize`); non-finite components (already reported) give the identity too.
pub fn quaternion_xyzw([x, y, z, w]: [f64; 4]) -> UnitQuaternion<f64> {
    let squared_norm = x * x + y * y + z * z + w * w;
    if !(squared_norm.is_finite() && squared_norm > 0.0) {
        return UnitQuaternion::identity();
    }
    UnitQuaternion::new_normalize(nalgebra::Quaternion::new(w, x, y, z))
}

/// `value`, or 0 when it is not finite (a NaN or infinite value, already reported, places nothing).
fn zero_if_not_finite(value: f64) -> f64 {
    if value.is_finite() {
        value
    } else {
        0.0
    }
}
