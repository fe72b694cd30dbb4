//! Robot classification from structure: legs, wheels, arms, rotors, fixed base — with names only as a
//! cross-check (aerial robots have nothing structural to show but their rotors).

use std::collections::BTreeSet;

use crate::analysis::arms::{detect as detect_arms, subtree_links, Arm, BodyParts};
use crate::assets::supports::{lowest_points, LinkSupports};
use crate::model::kinematics::Data;
use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::{Geometry, JointKind, Robot};

/// The spec's robot categories.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum RobotType {
    /// Drives on wheels (may carry arms).
    Wheeled,
    /// Drives on wheels, no manipulator.
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
    /// None of the above could be established.
    Unknown,
}

impl RobotType {
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
}

/// How close to the lowest geometry a link must come to count as touching the ground: 5% of the robot's
/// height, between 1 and 5 cm.
fn ground_tolerance(height: f64) -> f64 {
    (0.05 * height).clamp(0.01, 0.05)
}

/// A joint that moves a limb: revolute (limited or not) or prismatic, and not a mimic follower.
fn is_limb_joint(model: &Model, joint: JointId) -> bool {
    matches!(
        model.joint_data[joint.0].kind,
        JointKind::Revolute | JointKind::Prismatic
    ) && model.mimic[joint.0].is_none()
}

/// An actuated joint that is not a mimic follower (followers do not make a separate limb).
fn independent_actuated(model: &Model, joint: JointId) -> bool {
    model.joint_data[joint.0].is_actuated() && model.mimic[joint.0].is_none()
}

/// Links where the tree branches into two or more subtrees that each hold an actuated joint.
fn branch_points(model: &Model) -> Vec<bool> {
    let mut has_actuated = vec![false; model.parent_joint.len()];
    for &link in model.topological_order.iter().rev() {
        for &joint in &model.child_joints[link.0] {
            if let Some((_, child)) = model.joint_links[joint.0] {
                has_actuated[link.0] |= has_actuated[child.0] || independent_actuated(model, joint);
            }
        }
    }
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
fn chains_to_body(model: &Model, branch: &[bool]) -> Vec<Chain> {
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
        let limb = usize::from(is_limb_joint(model, joint));
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
    [
        "rotor",
        "propeller",
        "prop_",
        "copter",
        "drone",
        "flying",
        "uav",
    ]
    .iter()
    .any(|t| name.contains(t))
}

/// Names along a chain that say "arm" and none that say "leg": arms hanging to the ground at the zero pose
/// (an upper body on a pedestal) are not legs.
fn named_like_an_arm(robot: &Robot, model: &Model, foot: LinkId, body: LinkId) -> bool {
    const ARM: [&str; 7] = [
        "arm", "shoulder", "elbow", "wrist", "hand", "gripper", "finger",
    ];
    const LEG: [&str; 8] = [
        "leg", "hip", "knee", "ankle", "foot", "thigh", "shin", "calf",
    ];
    let mut names = Vec::new();
    let mut current = foot;
    while current != body {
        names.push(robot.links[current.0].name.value.to_ascii_lowercase());
        let Some(joint) = model.parent_joint[current.0] else {
            break;
        };
        names.push(robot.joints[joint.0].name.value.to_ascii_lowercase());
        match model.joint_links[joint.0] {
            Some((parent, _)) if names.len() <= 2 * model.parent_joint.len() => current = parent,
            _ => break,
        }
    }
    let any = |tokens: &[&str]| names.iter().any(|n| tokens.iter().any(|t| n.contains(t)));
    any(&ARM) && !any(&LEG)
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

fn add_leg(legs: &mut Vec<Leg>, lowest: &[Option<f64>], top_joint: JointId, foot: LinkId) {
    match legs.iter_mut().find(|leg| leg.top_joint == top_joint) {
        Some(leg) if lowest[foot.0] < lowest[leg.foot.0] => leg.foot = foot,
        Some(_) => {}
        None => legs.push(Leg { top_joint, foot }),
    }
}

/// Legs by name: leaves whose chain to the body has ≥ 2 limb joints and leg-like names (no arm-like ones).
fn leaves_named_like_legs(
    robot: &Robot,
    model: &Model,
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
        if chain.limb_joints >= 2
            && leg_like
            && !named_like_an_arm(robot, model, LinkId(l), chain.body)
        {
            add_leg(&mut legs, lowest, top, LinkId(l));
        }
    }
    legs
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
    let meshes = robot
        .links
        .iter()
        .flat_map(|l| l.visuals.iter().chain(&l.collisions))
        .filter_map(|s| match &s.geometry {
            Some(g) => match &g.value {
                Geometry::Mesh { filename, .. } => Some(&filename.value),
                _ => None,
            },
            None => None,
        });
    let rotors = robot
        .links
        .iter()
        .map(|l| &l.name.value)
        .chain(robot.joints.iter().map(|j| &j.name.value))
        .chain(robot.name.as_ref().map(|n| &n.value))
        .chain(meshes)
        .filter(|n| name_has_rotor(n))
        .count();
    if !ground.is_finite() {
        let robot_type = if rotors > 0 {
            RobotType::Aerial
        } else {
            RobotType::Unknown
        };
        return Classification {
            robot_type,
            legs: Vec::new(),
            wheels: Vec::new(),
            arms: Vec::new(),
            rotors,
            ground_z: None,
            evidence: "no geometry to find the ground with".to_string(),
        };
    }
    let tolerance = ground_tolerance(top - ground);
    let touches = |l: usize| lowest[l].is_some_and(|z| z <= ground + tolerance);
    let branch = branch_points(model);
    let chains = chains_to_body(model, &branch);
    // The body rests on the ground when the root or anything welded to it touches it (a fixed base).
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
    let root_on_ground = in_tree.iter().any(|&l| welded[l] && touches(l));

    // Legs: from each ground-touching link, the chain up to the body holds ≥ 2 limb joints and lifts the
    // body well off the ground (a fifth of the robot's height: fingers hanging from a hand do not). One leg
    // per top joint (a foot with toes is one leg).
    let lift = tolerance.max(0.2 * (top - ground));
    let mut legs: Vec<Leg> = Vec::new();
    for &l in &in_tree {
        if !touches(l) {
            continue;
        }
        let chain = chains[l];
        let body_off_ground = lowest[chain.body.0].is_none_or(|z| z > ground + lift);
        let is_leg = chain.limb_joints >= 2
            && body_off_ground
            && !named_like_an_arm(robot, model, LinkId(l), chain.body);
        if let Some(top_joint) = chain.top.filter(|_| is_leg) {
            add_leg(&mut legs, &lowest, top_joint, LinkId(l));
        }
    }
    // A model that is not z-up (lying on its side) shows no legs by height: fall back to leg names.
    let mut by_name = false;
    if legs.len() < 2 {
        let named: Vec<Leg> = leaves_named_like_legs(robot, model, &chains, &in_tree, &lowest);
        if named.len() >= 2 {
            legs = named;
            by_name = true;
        }
    }
    // Wheels: round links touching the ground, turned by a continuous (or unlimited revolute) joint — or
    // named wheels welded by a fixed joint (files prepared for a fixed-base solver do that).
    let wheels: Vec<LinkId> = in_tree
        .iter()
        .copied()
        .filter(|&l| {
            touches(l) && !supports[l].shapes.is_empty() && is_wheel_shape(robot, LinkId(l))
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
    let actuated = model.joint_data.iter().any(|j| j.is_actuated());
    let named = if by_name {
        " (found by name: the model does not stand on z)"
    } else {
        ""
    };
    let (robot_type, evidence) = match legs.len() {
        2 if arm_count > 0 => (
            RobotType::Humanoid,
            format!("2 legs and {arm_count} arm chain(s){named}"),
        ),
        4 => (RobotType::Quadruped, format!("4 legs{named}")),
        n if n >= 2 => (RobotType::Legged, format!("{n} legs{named}")),
        _ if wheels.len() >= 2 => (
            RobotType::Wheeled,
            format!("{} wheels on the ground", wheels.len()),
        ),
        _ if rotors > 0 => (
            RobotType::Aerial,
            format!("{rotors} rotor-named part(s), no legs or wheels"),
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
    };
    Classification {
        robot_type,
        legs,
        wheels,
        arms,
        rotors,
        ground_z: Some(ground),
        evidence,
    }
}
