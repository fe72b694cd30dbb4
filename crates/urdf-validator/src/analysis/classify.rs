//! Robot classification from structure: legs, wheels, arms, rotors, fixed base — with names only as a
//! cross-check or a tie-break.
//!
//! - **Object**: no revolute, continuous or prismatic joint (a table, a tray, a mug), unless it shows
//!   rotors (a drone modelled with fixed propellers).
//! - **Legs**: chains of ≥ 2 limb joints from the body to a link on the ground that lift the body off it;
//!   else four or more jointed chains from the main body all on the ground (a quadruped lying on its
//!   legs); else four or more similar chains at the four corners of the body, whatever the pose (legs
//!   stretched out flat or pointing up); else leg names (a model lying on its side). Two chains to one
//!   foot are one (five-bar) leg.
//! - **Wheels**: round links (cylinder, sphere, capsule, a mesh round about its axle, or a wheel name) on
//!   the ground, turned by a continuous joint, carrying nothing that moves. Steered by a limited
//!   vertical joint and no arm: a `ground_vehicle` (a car).
//! - **Rotors**: three or more thin discs of one size spinning about vertical axes off the ground, or
//!   rotor names. Names decide over an arm only on the body or when the body hangs in the air.
//! - **Arms**: see [`crate::analysis::arms`].

use std::collections::BTreeSet;

use nalgebra::Vector3;

use crate::analysis::arms::{detect as detect_arms, subtree_links, Arm, BodyParts};
use crate::assets::supports::{lowest_points, LinkSupports, Support};
use crate::model::kinematics::Data;
use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::{Geometry, JointKind, Robot};

/// The spec's robot categories.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum RobotType {
    /// Drives on wheels (may carry arms).
    Wheeled,
    /// Drives on wheels, no manipulator. Detected for a car: wheels turned by steering joints and no arm
    /// (a differential-drive base without an arm stays `wheeled`, as the spec's TurtleBot does).
    GroundVehicle,
    /// Walks on legs (not two legs with arms, not four legs).
    Legged,
    /// Four legs.
    Quadruped,
    /// Two legs and an upper body with arms.
    Humanoid,
    /// A fixed-base manipulator (or any fixed-base mechanism).
    ArmOnly,
    /// Flies on rotors.
    Aerial,
    /// Nothing moves: no revolute, continuous or prismatic joint (a table, a tray, a mug, a scene asset).
    Object,
    /// None of the above could be established.
    Unknown,
}

impl RobotType {
    /// Every category, in the order `--robot-type` lists them.
    pub const ALL: [RobotType; 9] = [
        RobotType::Wheeled,
        RobotType::GroundVehicle,
        RobotType::Legged,
        RobotType::Quadruped,
        RobotType::Humanoid,
        RobotType::ArmOnly,
        RobotType::Aerial,
        RobotType::Object,
        RobotType::Unknown,
    ];

    /// The flag / JSON value.
    pub fn as_str(self) -> &'static str {
        match self {
            RobotType::Wheeled => "wheeled",
            RobotType::GroundVehicle => "ground_vehicle",
            RobotType::Legged => "legged",
            RobotType::Quadruped => "quadruped",
            RobotType::Humanoid => "humanoid",
            RobotType::ArmOnly => "arm_only",
            RobotType::Aerial => "aerial",
            RobotType::Object => "object",
            RobotType::Unknown => "unknown",
        }
    }

    /// Parse a flag value.
    pub fn parse(text: &str) -> Option<Self> {
        Some(match text {
            "wheeled" => RobotType::Wheeled,
            "ground_vehicle" => RobotType::GroundVehicle,
            "legged" => RobotType::Legged,
            "quadruped" => RobotType::Quadruped,
            "humanoid" => RobotType::Humanoid,
            "arm_only" => RobotType::ArmOnly,
            "aerial" => RobotType::Aerial,
            "object" => RobotType::Object,
            "unknown" => RobotType::Unknown,
            _ => return None,
        })
    }

    /// Walks on legs (legged, quadruped, humanoid).
    pub fn is_legged(self) -> bool {
        matches!(
            self,
            RobotType::Legged | RobotType::Quadruped | RobotType::Humanoid
        )
    }
}

/// One leg: the chain from the body to a foot.
#[derive(Clone, Debug, PartialEq)]
pub struct Leg {
    /// The joint where the leg leaves the body.
    pub top_joint: JointId,
    /// The lowest link of the leg.
    pub foot: LinkId,
}

/// What the structure shows.
#[derive(Clone, Debug)]
pub struct Classification {
    /// The category.
    pub robot_type: RobotType,
    /// Legs found.
    pub legs: Vec<Leg>,
    /// Wheel links touching the ground.
    pub wheels: Vec<LinkId>,
    /// Arms (see [`crate::analysis::arms`]).
    pub arms: Vec<Arm>,
    /// Rotor-named links or joints.
    pub rotors: usize,
    /// Height of the lowest geometry at the reference pose.
    pub ground_z: Option<f64>,
    /// One sentence saying why.
    pub evidence: String,
    /// The legs were found by their names only: none stands on the ground with z up.
    pub legs_by_name: bool,
}

/// How close to the lowest geometry a link must come to count as touching the ground: 5% of the robot's
/// height, between 1 and 5 cm.
fn ground_tolerance(height: f64) -> f64 {
    (0.05 * height).clamp(0.01, 0.05)
}

/// A joint that moves a limb: revolute (limited or not) or prismatic, and not a mimic follower — or a
/// continuous joint that carries more moving joints or turns something not round (a hip or knee
/// modelled without limits, as the MIT Mini Cheetah, the Minitaur and the Vision 60 do; a continuous
/// joint turning a round leaf is a wheel or a rotor). `moves_below[link]`: the subtree below `link`
/// holds an actuated joint.
fn is_limb_joint(robot: &Robot, model: &Model, joint: JointId, moves_below: &[bool]) -> bool {
    let limb_like = || {
        model.joint_links[joint.0].is_some_and(|(_, child)| {
            moves_below[child.0] || (has_shapes(robot, child) && !is_wheel_shape(robot, child))
        })
    };
    model.mimic[joint.0].is_none()
        && match model.joint_data[joint.0].kind {
            JointKind::Revolute | JointKind::Prismatic => true,
            JointKind::Continuous => limb_like(),
            _ => false,
        }
}

fn has_shapes(robot: &Robot, link: LinkId) -> bool {
    let link = &robot.links[link.0];
    link.collisions
        .iter()
        .chain(&link.visuals)
        .any(|s| s.geometry.is_some())
}

/// Per link: whether some joint below it (in its subtree) is actuated and not a mimic follower.
fn moves_below(model: &Model) -> Vec<bool> {
    let mut below = vec![false; model.parent_joint.len()];
    for &link in model.topological_order.iter().rev() {
        for &joint in &model.child_joints[link.0] {
            if let Some((_, child)) = model.joint_links[joint.0] {
                below[link.0] |= below[child.0] || independent_actuated(model, joint);
            }
        }
    }
    below
}

/// An actuated joint that is not a mimic follower (followers do not make a separate limb).
fn independent_actuated(model: &Model, joint: JointId) -> bool {
    model.joint_data[joint.0].is_actuated() && model.mimic[joint.0].is_none()
}

/// Links where the tree branches into two or more subtrees that each hold an actuated joint.
fn branch_points(model: &Model, has_actuated: &[bool]) -> Vec<bool> {
    (0..model.parent_joint.len())
        .map(|l| {
            model.child_joints[l]
                .iter()
                .filter_map(|j| model.joint_links[j.0].map(|(_, c)| (j, c)))
                .filter(|(j, c)| has_actuated[c.0] || independent_actuated(model, **j))
                .count()
                >= 2
        })
        .collect()
}

/// A chain from a link up to the body.
#[derive(Clone, Copy)]
struct Chain {
    /// Limb joints passed.
    limb_joints: usize,
    /// The topmost joint (where the chain leaves the body).
    top: Option<JointId>,
    /// The body: the nearest branch point above, or the root.
    body: LinkId,
}

/// For every link, the walk up from it to the nearest branch point (or the root), found parents first in
/// one pass (walking up from every link of a long chain would be quadratic).
fn chains_to_body(
    robot: &Robot,
    model: &Model,
    branch: &[bool],
    moves_below: &[bool],
) -> Vec<Chain> {
    let mut chains: Vec<Chain> = (0..model.parent_joint.len())
        .map(|l| Chain {
            limb_joints: 0,
            top: None,
            body: LinkId(l),
        })
        .collect();
    for &link in &model.topological_order {
        let Some(joint) = model.parent_joint[link.0] else {
            continue;
        };
        let Some((parent, _)) = model.joint_links[joint.0] else {
            continue;
        };
        let limb = usize::from(is_limb_joint(robot, model, joint, moves_below));
        chains[link.0] = if branch[parent.0] {
            Chain {
                limb_joints: limb,
                top: Some(joint),
                body: parent,
            }
        } else {
            let above = chains[parent.0];
            Chain {
                limb_joints: above.limb_joints + limb,
                top: above.top.or(Some(joint)),
                body: above.body,
            }
        };
    }
    chains
}

fn name_has_rotor(name: &str) -> bool {
    let name = name.to_ascii_lowercase();
    ["rotor", "propel", "copter", "drone", "flying", "uav"]
        .iter()
        .any(|t| name.contains(t))
        // `prop0_link`, `prop_front`; not `proper` or `props_holder`.
        || name
            .split(|c: char| !c.is_ascii_alphabetic())
            .any(|word| word == "prop")
}

/// Parts named like rotors (or a robot named like a drone).
struct RotorNames {
    /// Anywhere in the file.
    anywhere: usize,
    /// On the body (the robot's name, links welded to the root, the joints into and out of them, and
    /// their meshes): a motor's `rotor` inside an arm or a leg does not make a drone.
    on_body: usize,
}

fn rotor_names(robot: &Robot, model: &Model, welded: &[bool]) -> RotorNames {
    let mut names = RotorNames {
        anywhere: 0,
        on_body: 0,
    };
    if robot
        .name
        .as_ref()
        .is_some_and(|n| name_has_rotor(&n.value))
    {
        names.anywhere += 1;
        names.on_body += 1;
    }
    for (index, link) in robot.links.iter().enumerate() {
        let meshes = link.visuals.iter().chain(&link.collisions).filter_map(|s| {
            match &s.geometry.as_ref()?.value {
                Geometry::Mesh { filename, .. } => Some(&filename.value),
                _ => None,
            }
        });
        let count = std::iter::once(&link.name.value)
            .chain(meshes)
            .filter(|n| name_has_rotor(n))
            .count();
        names.anywhere += count;
        if welded.get(index).copied().unwrap_or(false) {
            names.on_body += count;
        }
    }
    for (index, joint) in robot.joints.iter().enumerate() {
        if !name_has_rotor(&joint.name.value) {
            continue;
        }
        names.anywhere += 1;
        let on_body = model
            .joint_links
            .get(index)
            .copied()
            .flatten()
            .is_some_and(|(parent, child)| welded[parent.0] || welded[child.0]);
        names.on_body += usize::from(on_body);
    }
    names
}

/// How much wider than thick a cylinder must be to be a rotor disc.
const DISC_RATIO: f64 = 4.0;

/// Rotors seen in the structure: leaf links off the ground, each a thin disc spinning about a vertical
/// axis (a cylinder at least [`DISC_RATIO`] times wider than thick, its axis vertical at the reference
/// pose), on a continuous or fixed joint. Counted only when three or more discs of one size are found:
/// one disc is a turntable or a lidar, and multirotors have at least three.
fn disc_rotors(
    model: &Model,
    data: &Data,
    supports: &[LinkSupports],
    touches: &dyn Fn(usize) -> bool,
) -> usize {
    let radii: Vec<f64> = model
        .topological_order
        .iter()
        .filter(|l| !touches(l.0) && model.child_joints[l.0].is_empty())
        .filter(|l| {
            model.parent_joint[l.0].is_some_and(|j| {
                matches!(
                    model.joint_data[j.0].kind,
                    JointKind::Continuous | JointKind::Fixed
                )
            })
        })
        .filter_map(|l| {
            supports[l.0].shapes.iter().find_map(|shape| match shape {
                Support::Cylinder {
                    frame,
                    radius,
                    length,
                } => {
                    let axis = (data.link_placement[l.0] * frame).rotation * Vector3::z();
                    (*radius * 2.0 >= DISC_RATIO * *length && axis.z.abs() > 0.95)
                        .then_some(*radius)
                }
                _ => None,
            })
        })
        .collect();
    radii
        .iter()
        .map(|r| {
            radii
                .iter()
                .filter(|other| (*other - r).abs() <= 0.05 * r)
                .count()
        })
        .max()
        .filter(|&n| n >= 3)
        .unwrap_or(0)
}

/// A wheel turned by a steering joint: the wheel's parent link hangs from a limited revolute joint whose
/// axis is vertical at the reference pose (a car's steering knuckle; a caster swivels without limits).
fn is_steered(model: &Model, data: &Data, wheel: LinkId) -> bool {
    let Some((knuckle, _)) = model.parent_joint[wheel.0].and_then(|j| model.joint_links[j.0])
    else {
        return false;
    };
    let Some(steering) = model.parent_joint[knuckle.0] else {
        return false;
    };
    let joint = &model.joint_data[steering.0];
    let axis = data.link_placement[knuckle.0].rotation * joint.axis;
    joint.kind == JointKind::Revolute
        && joint.range().is_some()
        && axis.try_normalize(1e-9).is_some_and(|a| a.z.abs() > 0.9)
}

/// How many names on the path from the root down to each link (each link's own and its parent joint's)
/// say "arm" and how many say "leg", so that the names between a link and one of its ancestors are
/// counted by a subtraction: one walk over the tree, not one per ground-touching link (a long chain lying
/// on the ground was quadratic).
struct LimbNames {
    arm: Vec<u32>,
    leg: Vec<u32>,
}

impl LimbNames {
    fn new(robot: &Robot, model: &Model) -> LimbNames {
        const ARM: [&str; 7] = [
            "arm", "shoulder", "elbow", "wrist", "hand", "gripper", "finger",
        ];
        const LEG: [&str; 8] = [
            "leg", "hip", "knee", "ankle", "foot", "thigh", "shin", "calf",
        ];
        let count = |names: [Option<&str>; 2], tokens: &[&str]| {
            let says = |name: &str| {
                let name = name.to_ascii_lowercase();
                tokens.iter().any(|t| name.contains(t))
            };
            names.into_iter().flatten().filter(|n| says(n)).count() as u32
        };
        let links = model.parent_joint.len();
        let mut names = LimbNames {
            arm: vec![0; links],
            leg: vec![0; links],
        };
        for &link in &model.topological_order {
            let joint = model.parent_joint[link.0];
            let own = [
                Some(robot.links[link.0].name.value.as_str()),
                joint.map(|j| robot.joints[j.0].name.value.as_str()),
            ];
            let parent = joint.and_then(|j| model.joint_links[j.0]).map(|(p, _)| p.0);
            let (arm_above, leg_above) = parent.map_or((0, 0), |p| (names.arm[p], names.leg[p]));
            names.arm[link.0] = arm_above + count(own, &ARM);
            names.leg[link.0] = leg_above + count(own, &LEG);
        }
        names
    }

    /// Names along a chain that say "arm" and none that say "leg" (`foot` and its parent joint up to, not
    /// including, its ancestor `body`): arms hanging to the ground at the zero pose (an upper body on a
    /// pedestal) are not legs.
    fn arm_between(&self, foot: LinkId, body: LinkId) -> bool {
        let between = |counts: &[u32]| counts[foot.0].saturating_sub(counts[body.0]);
        between(&self.arm) > 0 && between(&self.leg) == 0
    }
}

/// Round geometry (or a wheel-named mesh) on a link: what a wheel looks like.
fn is_wheel_shape(robot: &Robot, link: LinkId) -> bool {
    let link = &robot.links[link.0];
    let shapes = if link.collisions.is_empty() {
        &link.visuals
    } else {
        &link.collisions
    };
    shapes
        .iter()
        .filter_map(|s| s.geometry.as_ref())
        .any(|g| match &g.value {
            Geometry::Cylinder { .. } | Geometry::Sphere { .. } | Geometry::Capsule { .. } => true,
            Geometry::Mesh { filename, .. } => {
                let lower = filename.value.to_ascii_lowercase();
                ["wheel", "tire", "tyre", "caster", "castor"]
                    .iter()
                    .any(|t| lower.contains(t))
            }
            Geometry::Box { .. } => false,
        })
        || link.name.value.to_ascii_lowercase().contains("wheel")
}

/// A loaded mesh that is round about `axis` (the axis of the joint turning it, in the link frame): its
/// extents across the axis agree within 10%, it is no longer along the axis than across it, and no point
/// lies much beyond the circle they span (a square's corners would). What a wheel or a tyre mesh looks
/// like whatever its file is called.
fn round_about(shapes: &[Support], axis: &Vector3<f64>) -> bool {
    let Some(axis) = axis.try_normalize(1e-9) else {
        return false;
    };
    let helper = if axis.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let u = axis.cross(&helper).normalize();
    let v = axis.cross(&u);
    shapes.iter().any(|shape| {
        let (Support::Points(points) | Support::Hull { points, .. }) = shape else {
            return false;
        };
        if points.len() < 8 {
            return false;
        }
        let extent = |d: &Vector3<f64>| {
            let (lo, hi) = points
                .iter()
                .map(|p| p.dot(d))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                    (lo.min(x), hi.max(x))
                });
            (lo, hi - lo)
        };
        let ((u0, eu), (v0, ev), (_, ea)) = (extent(&u), extent(&v), extent(&axis));
        let across = eu.max(ev);
        if across <= 0.0 || (eu - ev).abs() > 0.1 * across || ea > 1.2 * across {
            return false;
        }
        let (cu, cv) = (u0 + 0.5 * eu, v0 + 0.5 * ev);
        points
            .iter()
            .all(|p| (p.dot(&u) - cu).hypot(p.dot(&v) - cv) <= 0.55 * across)
    })
}

fn add_leg(legs: &mut Vec<Leg>, lowest: &[Option<f64>], top_joint: JointId, foot: LinkId) {
    match legs.iter_mut().find(|leg| leg.top_joint == top_joint) {
        Some(leg) if lowest[foot.0] < lowest[leg.foot.0] => leg.foot = foot,
        Some(_) => {}
        None => legs.push(Leg { top_joint, foot }),
    }
}

/// Where a foot touches, horizontally: the middle of its lowest points (its frame origin without shapes).
fn foot_point(data: &Data, supports: &[LinkSupports], foot: LinkId) -> (f64, f64) {
    let placement = &data.link_placement[foot.0];
    match lowest_points(&supports[foot.0].shapes, placement, 0.0) {
        Some((_, points)) if !points.is_empty() => {
            let n = points.len() as f64;
            (
                points.iter().map(|p| p.x).sum::<f64>() / n,
                points.iter().map(|p| p.y).sum::<f64>() / n,
            )
        }
        _ => (
            placement.translation.vector.x,
            placement.translation.vector.y,
        ),
    }
}

/// Chains whose feet meet are one leg: a closed-loop (five-bar) leg is written in URDF as two open
/// chains from two motors to the same foot (the Minitaur's and the Vision 60's). Feet closer than a
/// quarter of the spread of all feet are merged, keeping the first chain.
fn merge_closed_loops(legs: Vec<Leg>, data: &Data, supports: &[LinkSupports]) -> Vec<Leg> {
    if legs.len() < 4 {
        return legs;
    }
    let points: Vec<(f64, f64)> = legs
        .iter()
        .map(|leg| foot_point(data, supports, leg.foot))
        .collect();
    let distance = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    let spread = points
        .iter()
        .flat_map(|&a| points.iter().map(move |&b| distance(a, b)))
        .fold(0.0, f64::max);
    let mut kept: Vec<(Leg, (f64, f64))> = Vec::new();
    for (leg, point) in legs.into_iter().zip(points) {
        if !kept
            .iter()
            .any(|(_, other)| distance(*other, point) < 0.25 * spread)
        {
            kept.push((leg, point));
        }
    }
    kept.into_iter().map(|(leg, _)| leg).collect()
}

/// Four or more chains of the same number of limb joints (≥ 2) from the main body (`welded` to the root),
/// each to its own leaf, whose
/// top joints sit in one horizontal plane at the four corners of the body (front-left, front-right,
/// rear-left, rear-right): legs, whatever the pose. The fingers of a hand leave the palm in a row, not at
/// four corners of a plane.
fn limbs_at_corners(
    model: &Model,
    data: &Data,
    chains: &[Chain],
    in_tree: &BTreeSet<usize>,
    lowest: &[Option<f64>],
    welded: &[bool],
) -> Option<Vec<Leg>> {
    let mut groups: Vec<(usize, Vec<Leg>)> = Vec::new();
    for &l in in_tree {
        let chain = chains[l];
        let Some(top) = chain.top else { continue };
        if !model.child_joints[l].is_empty() || chain.limb_joints < 2 || !welded[chain.body.0] {
            continue;
        }
        // The main body may branch in several links (the Minitaur's two side rails): one group per
        // chain length.
        match groups.iter_mut().find(|(n, _)| *n == chain.limb_joints) {
            Some((_, group)) => add_leg(group, lowest, top, LinkId(l)),
            None => {
                let mut group = Vec::new();
                add_leg(&mut group, lowest, top, LinkId(l));
                groups.push((chain.limb_joints, group));
            }
        }
    }
    groups.into_iter().find_map(|(_, group)| {
        if group.len() < 4 {
            return None;
        }
        let tops: Vec<Vector3<f64>> = group
            .iter()
            .filter_map(|leg| model.joint_links[leg.top_joint.0])
            .map(|(_, child)| data.link_placement[child.0].translation.vector)
            .collect();
        let centre = tops.iter().sum::<Vector3<f64>>() / tops.len() as f64;
        let spread = |axis: usize| {
            tops.iter()
                .map(|p| (p[axis] - centre[axis]).abs())
                .fold(0.0, f64::max)
        };
        let (sx, sy, sz) = (spread(0), spread(1), spread(2));
        if sx <= 0.0 || sy <= 0.0 || sz > 0.25 * sx.max(sy) {
            return None;
        }
        let corner = |fx: f64, fy: f64| {
            tops.iter()
                .any(|p| (p.x - centre.x) * fx > 0.25 * sx && (p.y - centre.y) * fy > 0.25 * sy)
        };
        (corner(1.0, 1.0) && corner(1.0, -1.0) && corner(-1.0, 1.0) && corner(-1.0, -1.0))
            .then_some(group)
    })
}

/// Legs by name: leaves whose chain to the body has ≥ 2 limb joints and leg-like names (no arm-like ones).
fn leaves_named_like_legs(
    robot: &Robot,
    limb_names: &LimbNames,
    chains: &[Chain],
    in_tree: &BTreeSet<usize>,
    lowest: &[Option<f64>],
) -> Vec<Leg> {
    const LEG: [&str; 6] = ["leg", "knee", "ankle", "foot", "thigh", "shin"];
    let mut legs = Vec::new();
    for &l in in_tree {
        let chain = chains[l];
        let name = robot.links[l].name.value.to_ascii_lowercase();
        let Some(top) = chain.top else { continue };
        let top_name = robot.joints[top.0].name.value.to_ascii_lowercase();
        let leg_like = LEG.iter().any(|t| name.contains(t)) || top_name.contains("hip");
        if chain.limb_joints >= 2 && leg_like && !limb_names.arm_between(LinkId(l), chain.body) {
            add_leg(&mut legs, lowest, top, LinkId(l));
        }
    }
    legs
}

/// Longest finger, top joint to fingertip, m (a human hand's middle finger is ~0.1 m, Allegro's 0.16 m).
const MAX_FINGER_LENGTH: f64 = 0.25;

/// Names that say finger: a cross-check, never enough alone.
const FINGER_NAMES: [&str; 9] = [
    "finger", "thumb", "index", "pinky", "phalan", "knuckle", "palm", "hand", "digit",
];

/// Whether the chains leaving `palm` at `tops` are the fingers of a hand: at least two, none longer than
/// [`MAX_FINGER_LENGTH`] from its top joint to its farthest link or lowest point, none with a leg-like
/// name, and one more sign of a hand: a mimic (coupled) joint in a finger, finger-like names on the
/// fingers or the palm, or at least three fingers of four or more moving joints each (Allegro's and
/// LEAP's unnamed fingers; a walking robot's legs have three, a humanoid's are longer).
fn fingers_of_hand(
    robot: &Robot,
    model: &Model,
    data: &Data,
    palm: LinkId,
    tops: &[JointId],
    limb_names: &LimbNames,
    lowest: &[Option<f64>],
) -> bool {
    let fingers: Vec<(Vector3<f64>, Vec<LinkId>)> = tops
        .iter()
        .filter_map(|top| model.joint_links[top.0])
        .map(|(_, child)| {
            let origin = data.link_placement[child.0].translation.vector;
            (origin, subtree_links(model, child))
        })
        .collect();
    if fingers.len() < 2 || fingers.len() != tops.len() {
        return false;
    }
    let short = fingers.iter().all(|(origin, links)| {
        links.iter().all(|l| {
            let at = data.link_placement[l.0].translation.vector;
            let low = lowest[l.0].unwrap_or(at.z);
            (at - origin).norm() <= MAX_FINGER_LENGTH && origin.z - low <= MAX_FINGER_LENGTH
        })
    });
    let leg_named = fingers
        .iter()
        .flat_map(|(_, links)| links)
        .any(|l| limb_names.leg[l.0] > limb_names.leg[palm.0]);
    if !short || leg_named {
        return false;
    }
    let moving_joints = |links: &[LinkId]| -> Vec<JointId> {
        links
            .iter()
            .filter_map(|l| model.parent_joint[l.0])
            .filter(|j| model.joint_data[j.0].kind != JointKind::Fixed)
            .collect()
    };
    let coupled = fingers
        .iter()
        .flat_map(|(_, links)| moving_joints(links))
        .any(|j| model.mimic[j.0].is_some());
    let says = |name: &str| {
        let name = name.to_ascii_lowercase();
        FINGER_NAMES.iter().any(|t| name.contains(t))
    };
    let named = says(&robot.links[palm.0].name.value)
        || fingers.iter().flat_map(|(_, links)| links).any(|l| {
            says(&robot.links[l.0].name.value)
                || model.parent_joint[l.0].is_some_and(|j| says(&robot.joints[j.0].name.value))
        });
    let many_jointed = fingers.len() >= 3
        && fingers
            .iter()
            .all(|(_, links)| moving_joints(links).len() >= 4);
    coupled || named || many_jointed
}

/// The palm and the finger count when `legs` are the fingers of a hand hanging from it (a stand-alone
/// hand with its fingers below the palm stands on its fingertips only on paper): every leg leaves the same
/// link and [`fingers_of_hand`] says they are fingers.
fn hand_of_legs(
    robot: &Robot,
    model: &Model,
    data: &Data,
    legs: &[Leg],
    chains: &[Chain],
    limb_names: &LimbNames,
    lowest: &[Option<f64>],
) -> Option<(LinkId, usize)> {
    let palm = chains[legs.first()?.foot.0].body;
    if legs.iter().any(|leg| chains[leg.foot.0].body != palm) {
        return None;
    }
    let tops: Vec<JointId> = legs.iter().map(|leg| leg.top_joint).collect();
    fingers_of_hand(robot, model, data, palm, &tops, limb_names, lowest)
        .then_some((palm, tops.len()))
}

/// The palm and the finger count of a hand found by its structure alone (no legs, wheels, arms or
/// rotors were found: fingers of one moving joint each and mimic followers, as the Fourier and Inspire
/// hands are built): the link with the most moving chains leaving it, when [`fingers_of_hand`] says they
/// are fingers.
fn hand_of_structure(
    robot: &Robot,
    model: &Model,
    data: &Data,
    moving: &[bool],
    limb_names: &LimbNames,
    lowest: &[Option<f64>],
) -> Option<(LinkId, usize)> {
    let chains_from = |link: usize| -> Vec<JointId> {
        model.child_joints[link]
            .iter()
            .copied()
            .filter(|j| {
                model.joint_links[j.0]
                    .is_some_and(|(_, child)| moving[child.0] || independent_actuated(model, *j))
            })
            .collect()
    };
    let (palm, tops) = model
        .topological_order
        .iter()
        .map(|l| (*l, chains_from(l.0)))
        .max_by_key(|(_, tops)| tops.len())?;
    (tops.len() >= 3 && fingers_of_hand(robot, model, data, palm, &tops, limb_names, lowest))
        .then_some((palm, tops.len()))
}

/// Classify at the placements in `data` (a reference pose).
pub fn classify(
    robot: &Robot,
    model: &Model,
    data: &Data,
    supports: &[LinkSupports],
) -> Classification {
    // A link without shapes counts by its frame origin: sparse files (a few meshes, the rest frames) still
    // show where their limbs end.
    let lowest: Vec<Option<f64>> = (0..model.parent_joint.len())
        .map(
            |l| match lowest_points(&supports[l].shapes, &data.link_placement[l], 0.0) {
                Some((z, _)) => Some(z),
                None => Some(data.link_placement[l].translation.vector.z),
            },
        )
        .collect();
    let in_tree: BTreeSet<usize> = model.topological_order.iter().map(|l| l.0).collect();
    let ground = in_tree
        .iter()
        .filter_map(|&l| lowest[l])
        .fold(f64::INFINITY, f64::min);
    let top = in_tree
        .iter()
        .flat_map(|&l| {
            supports[l]
                .shapes
                .iter()
                .flat_map(move |s| s.world_points(&data.link_placement[l]))
        })
        .map(|p| p.z)
        .chain(
            in_tree
                .iter()
                .map(|&l| data.link_placement[l].translation.vector.z),
        )
        .fold(f64::NEG_INFINITY, f64::max);
    // The body: the root and everything welded to it.
    let mut welded = vec![false; model.parent_joint.len()];
    for &link in &model.topological_order {
        welded[link.0] = match model.parent_joint[link.0] {
            None => true,
            Some(joint) => {
                model.joint_data[joint.0].kind == JointKind::Fixed
                    && model.joint_links[joint.0].is_some_and(|(parent, _)| welded[parent.0])
            }
        };
    }
    let named_rotors = rotor_names(robot, model, &welded);
    let rotors = named_rotors.anywhere;
    let movable = model.joint_data.iter().any(|j| j.is_actuated());
    let nothing_found = |robot_type, rotors, ground_z, evidence| Classification {
        robot_type,
        legs: Vec::new(),
        wheels: Vec::new(),
        arms: Vec::new(),
        rotors,
        ground_z,
        evidence,
        legs_by_name: false,
    };
    if !ground.is_finite() {
        let (robot_type, evidence) = if rotors > 0 {
            (RobotType::Aerial, format!("{rotors} rotor-named part(s)"))
        } else if !movable && !robot.links.is_empty() {
            (RobotType::Object, "no movable joint".to_string())
        } else {
            (
                RobotType::Unknown,
                "no geometry to find the ground with".to_string(),
            )
        };
        return nothing_found(robot_type, rotors, None, evidence);
    }
    let tolerance = ground_tolerance(top - ground);
    let touches = |l: usize| lowest[l].is_some_and(|z| z <= ground + tolerance);
    let discs = disc_rotors(model, data, supports, &touches);
    let rotor_evidence = if discs >= rotors {
        format!("{discs} rotor disc(s)")
    } else {
        format!("{rotors} rotor-named part(s)")
    };
    let rotors = rotors.max(discs);
    // Nothing moves: an object (a table, a tray, a mug), unless it shows rotors (a drone modelled with
    // fixed propellers).
    if !movable {
        let (robot_type, evidence) = if rotors > 0 {
            (
                RobotType::Aerial,
                format!("{rotor_evidence}, no movable joint"),
            )
        } else {
            (
                RobotType::Object,
                "no movable joint (only fixed joints or a single link)".to_string(),
            )
        };
        return nothing_found(robot_type, rotors, Some(ground), evidence);
    }
    let moving = moves_below(model);
    let branch = branch_points(model, &moving);
    let chains = chains_to_body(robot, model, &branch, &moving);
    let limb_names = LimbNames::new(robot, model);
    // The body rests on the ground when the root or anything welded to it touches it (a fixed base).
    let root_on_ground = in_tree.iter().any(|&l| welded[l] && touches(l));

    // Legs: from each ground-touching link, the chain up to the body holds ≥ 2 limb joints and lifts the
    // body well off the ground (a fifth of the robot's height: fingers hanging from a hand do not). One leg
    // per top joint (a foot with toes is one leg).
    let lift = tolerance.max(0.2 * (top - ground));
    let mut legs: Vec<Leg> = Vec::new();
    // Jointed chains on the ground that do not lift their body, by body.
    let mut resting: Vec<(LinkId, Vec<Leg>)> = Vec::new();
    for &l in &in_tree {
        if !touches(l) {
            continue;
        }
        let chain = chains[l];
        let jointed = chain.limb_joints >= 2 && !limb_names.arm_between(LinkId(l), chain.body);
        let Some(top_joint) = chain.top.filter(|_| jointed) else {
            continue;
        };
        if lowest[chain.body.0].is_none_or(|z| z > ground + lift) {
            add_leg(&mut legs, &lowest, top_joint, LinkId(l));
        } else if welded[chain.body.0] {
            match resting.iter_mut().find(|(body, _)| *body == chain.body) {
                Some((_, group)) => add_leg(group, &lowest, top_joint, LinkId(l)),
                None => {
                    let mut group = Vec::new();
                    add_leg(&mut group, &lowest, top_joint, LinkId(l));
                    resting.push((chain.body, group));
                }
            }
        }
    }
    // Folded flat at the zero pose (the Ghost Robotics Spirit 40 lies on its legs): four or more jointed
    // chains from the main body (the root or a link welded to it), all on the ground, walk even though they
    // do not lift it. (Two could be arms resting on a table; the fingers of a hand on the ground leave a
    // palm at the end of an arm.)
    if legs.len() < 2 {
        if let Some((_, group)) = resting
            .into_iter()
            .filter(|(_, group)| group.len() >= 4)
            .max_by_key(|(_, group)| group.len())
        {
            legs = group;
        }
    }
    // Legs stretched out flat or pointing up at the zero pose (the Spirit 40 lies on its legs, the
    // Minitaur stands on its head): four or more similar jointed chains leaving the body at its four
    // corners, in one horizontal plane.
    let mut folded = false;
    if legs.len() < 2 {
        if let Some(corners) = limbs_at_corners(model, data, &chains, &in_tree, &lowest, &welded) {
            legs = corners;
            folded = true;
        }
    }
    // A model that is not z-up (lying on its side) shows no legs by height: fall back to leg names.
    let mut by_name = false;
    if legs.len() < 2 {
        let named: Vec<Leg> =
            leaves_named_like_legs(robot, &limb_names, &chains, &in_tree, &lowest);
        if named.len() >= 2 {
            legs = named;
            by_name = true;
        }
    }
    let mut legs = merge_closed_loops(legs, data, supports);
    // Fingers hanging from a hand are no legs: a hand has nothing to stand on.
    let mut hand = if legs.len() >= 2 && !by_name && !folded {
        hand_of_legs(robot, model, data, &legs, &chains, &limb_names, &lowest)
    } else {
        None
    };
    if hand.is_some() {
        legs.clear();
    }
    // Wheels: round links touching the ground, turned by a continuous (or unlimited revolute) joint — or
    // named wheels welded by a fixed joint (files prepared for a fixed-base solver do that).
    let wheels: Vec<LinkId> = in_tree
        .iter()
        .copied()
        .filter(|&l| {
            touches(l)
                && !supports[l].shapes.is_empty()
                && (is_wheel_shape(robot, LinkId(l))
                    || model.parent_joint[l].is_some_and(|j| {
                        round_about(&supports[l].shapes, &model.joint_data[j.0].axis)
                    }))
        })
        .filter(|&l| {
            model.parent_joint[l].is_some_and(|j| match model.joint_data[j.0].kind {
                JointKind::Continuous => true,
                JointKind::Revolute => model.joint_data[j.0].range().is_none(),
                JointKind::Fixed => robot.links[l]
                    .name
                    .value
                    .to_ascii_lowercase()
                    .contains("wheel"),
                _ => false,
            })
        })
        // A wheel carries nothing that moves (a continuous base joint of an arm is not a wheel).
        .filter(|&l| {
            subtree_links(model, LinkId(l)).iter().all(|s| {
                model.child_joints[s.0]
                    .iter()
                    .all(|j| !model.joint_data[j.0].is_actuated())
            })
        })
        .map(LinkId)
        .collect();
    // One "leg" is an arm resting on the ground, not locomotion.
    let leg_tops: Vec<JointId> = if legs.len() >= 2 {
        legs.iter().map(|leg| leg.top_joint).collect()
    } else {
        Vec::new()
    };
    let arms = detect_arms(
        robot,
        model,
        &BodyParts {
            leg_tops: &leg_tops,
            wheels: &wheels,
        },
    );
    let arm_count = arms.len();
    if hand.is_none() && legs.len() < 2 && wheels.is_empty() && arm_count == 0 && rotors == 0 {
        hand = hand_of_structure(robot, model, data, &moving, &limb_names, &lowest);
    }
    let actuated = model.joint_data.iter().any(|j| j.is_actuated());
    let named = if by_name {
        " (found by name: the model does not stand on z)"
    } else if folded {
        " (at the corners of the body; the zero pose does not stand on them)"
    } else {
        ""
    };
    let (robot_type, evidence) = match (hand, legs.len()) {
        (Some((palm, fingers)), _) if wheels.is_empty() => (
            RobotType::ArmOnly,
            format!(
                "a hand: {fingers} fingers on '{}' (short jointed chains off one palm), nothing to stand on",
                robot.links[palm.0].name.value
            ),
        ),
        (_, legs) => match legs {
        2 if arm_count > 0 => (
            RobotType::Humanoid,
            format!("2 legs and {arm_count} arm chain(s){named}"),
        ),
        4 => (RobotType::Quadruped, format!("4 legs{named}")),
        n if n >= 2 => (RobotType::Legged, format!("{n} legs{named}")),
        _ if wheels.len() >= 2
            && arm_count == 0
            && wheels.iter().any(|&w| is_steered(model, data, w)) =>
        {
            (
                RobotType::GroundVehicle,
                format!(
                    "{} wheels on the ground, steered like a car, no arm",
                    wheels.len()
                ),
            )
        }
        _ if wheels.len() >= 2 => (
            RobotType::Wheeled,
            format!("{} wheels on the ground", wheels.len()),
        ),
        _ if discs > 0 => (
            RobotType::Aerial,
            format!("{rotor_evidence}, no legs or wheels"),
        ),
        // Rotor names decide over an arm only on the body, or when the body hangs in the air (a drone
        // carrying an arm below it); a fixed-base arm with `rotor`-named motors is an arm.
        _ if arm_count > 0 && (named_rotors.on_body > 0 || (rotors > 0 && !root_on_ground)) => (
            RobotType::Aerial,
            format!("{rotor_evidence} and {arm_count} arm chain(s)"),
        ),
        _ if arm_count == 0 && rotors > 0 => (
            RobotType::Aerial,
            format!("{rotor_evidence}, no legs or wheels"),
        ),
        _ if arm_count > 0 => (
            RobotType::ArmOnly,
            format!("{arm_count} arm chain(s), no legs, wheels or rotors"),
        ),
        _ if actuated && root_on_ground => {
            (RobotType::ArmOnly, "a fixed-base mechanism".to_string())
        }
        _ => (
            RobotType::Unknown,
            "no legs, wheels, rotors or arms found".to_string(),
        ),
        },
    };
    Classification {
        robot_type,
        legs,
        wheels,
        arms,
        rotors,
        ground_z: Some(ground),
        evidence,
        legs_by_name: by_name,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use nalgebra::Vector3;

    use super::{name_has_rotor, round_about};
    use crate::assets::supports::Support;

    fn ring(radius: f64, width: f64, n: usize) -> Vec<Vector3<f64>> {
        (0..n)
            .flat_map(|k| {
                let t = std::f64::consts::TAU * k as f64 / n as f64;
                [-0.5, 0.5].map(|s| Vector3::new(radius * t.cos(), s * width, radius * t.sin()))
            })
            .collect()
    }

    #[test]
    fn a_tyre_mesh_is_round_about_its_axle_and_a_cube_is_not() {
        let tyre = [Support::Points(ring(0.1, 0.05, 24))];
        assert!(round_about(&tyre, &Vector3::y()));
        assert!(!round_about(&tyre, &Vector3::z()), "not about a diameter");
        let cube: Vec<Vector3<f64>> = (0..8)
            .map(|i| {
                Vector3::new(
                    f64::from(i & 1) - 0.5,
                    f64::from((i >> 1) & 1) - 0.5,
                    f64::from((i >> 2) & 1) - 0.5,
                )
            })
            .collect();
        assert!(!round_about(&[Support::Points(cube)], &Vector3::y()));
        let long_roller = [Support::Points(ring(0.05, 0.5, 24))];
        assert!(
            !round_about(&long_roller, &Vector3::y()),
            "a roller, not a wheel"
        );
    }

    #[test]
    fn propeller_names_are_words() {
        assert!(name_has_rotor("prop0_link"));
        assert!(name_has_rotor("front_prop"));
        assert!(name_has_rotor("rotor_3"));
        assert!(!name_has_rotor("property_frame"));
        assert!(!name_has_rotor("proprioception_imu"));
    }
}
