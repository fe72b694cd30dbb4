//! Contacts the simulator applies the moment it starts: bodies MuJoCo collides that overlap at `qpos0`
//! or at a keyframe (U042, with the `<contact><exclude>` that stops it as the fix), and collision
//! geometry below the ground (U603): an MJCF model's world planes at `qpos0` and each keyframe, as MuJoCo
//! collides them, and for other formats the ground the stability section stands the robot on, at the
//! evaluated pose.
//!
//! MuJoCo's filters are the file's (`Robot::collision_filtered`: excludes, `contype`/`conaffinity` of
//! whole bodies, the parent filter, welded bodies) plus each geom pair's bit masks
//! (`Robot::contact_bits`); a body welded to the world never touches the world's planes.

use std::collections::{BTreeMap, HashSet};

use nalgebra::Vector3;

use crate::analysis::collision::CollisionModel;
use crate::diagnostics::finding::Finding;
use crate::diagnostics::fix::{Edit, Fix};
use crate::diagnostics::rules;
use crate::input::Format;
use crate::model::kinematics::{forward_kinematics, pose_isometry, Data};
use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::{contact_bits_meet, ContactSection, JointKind, Link, Robot};

/// Overlaps up to this deep (metres) are not findings: meshes that meet at a joint overlap by a fraction
/// of a millimetre, which a simulator resolves without anyone noticing.
pub const START_OVERLAP: f64 = 1e-3;

/// At most this many keyframes are checked (a `<size nkey>` can make a thousand, all at `qpos0`).
const MAX_KEYS: usize = 64;

/// What the start-contact check found.
#[derive(Debug, Default)]
pub struct StartContacts {
    /// Its findings (U042, U603).
    pub findings: Vec<Finding>,
    /// The link pairs a U042 reports (smaller index first): a U601 for them would say it again.
    pub reported_pairs: HashSet<(LinkId, LinkId)>,
}

/// One pose of the start: its name in messages, and the link placements there.
struct StartPose {
    name: String,
    data: Data,
}

/// The overlaps of one link pair (or one link and the ground) over the poses, and where the deepest is.
struct Deepest {
    depth: f64,
    /// The collision of the second link (or the link) it is at.
    collision: usize,
    /// Each pose it is found at, with its depth there (metres).
    poses: Vec<(String, f64)>,
}

impl Deepest {
    fn merge(slot: &mut Option<Deepest>, depth: f64, collision: usize, pose: &str) {
        let d = slot.get_or_insert(Deepest {
            depth,
            collision,
            poses: Vec::new(),
        });
        if depth > d.depth {
            d.depth = depth;
            d.collision = collision;
        }
        d.poses.push((pose.to_string(), depth));
    }

    fn at_qpos0(&self) -> bool {
        self.poses.iter().any(|(p, _)| p == QPOS0)
    }

    /// "12.0 mm deep at qpos0 and key 'down'", "5.0 mm deep at qpos0, 155.0 mm at key 'home'": poses of
    /// one depth (to 0.1 mm) together.
    fn depths(&self) -> String {
        let mut groups: Vec<(String, Vec<String>)> = Vec::new();
        for (pose, depth) in &self.poses {
            let depth = format!("{:.1} mm", depth * 1e3);
            let pose = if pose == QPOS0 {
                QPOS0.to_string()
            } else {
                format!("key '{pose}'")
            };
            match groups.iter_mut().find(|(d, _)| *d == depth) {
                Some((_, poses)) => poses.push(pose),
                None => groups.push((depth, vec![pose])),
            }
        }
        groups
            .iter()
            .enumerate()
            .map(|(i, (depth, poses))| {
                format!(
                    "{depth}{} at {}",
                    if i == 0 { " deep" } else { "" },
                    poses.join(" and ")
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    }
}

const QPOS0: &str = "qpos0";

/// The start contacts of `robot`: an MJCF model's at `qpos0` and its keyframes; another format's below
/// `ground` (the stability section's ground height, `None` when it has none) at `evaluated`.
pub fn check(
    robot: &Robot,
    model: &Model,
    collision: &CollisionModel,
    evaluated: &Data,
    ground: Option<f64>,
) -> StartContacts {
    if robot.format != Format::Mjcf {
        let mut found = StartContacts::default();
        if let Some(height) = ground {
            let plane = Plane {
                name: "the ground the stability section stands the robot on".to_string(),
                point: Vector3::new(0.0, 0.0, height),
                normal: Vector3::z(),
                bits: None,
            };
            let poses = [StartPose {
                name: "the evaluated pose".to_string(),
                data: evaluated.clone(),
            }];
            found.findings = below_ground(robot, model, collision, &poses, &[plane], false);
        }
        return found;
    }
    if robot.contacts_disabled {
        return StartContacts::default();
    }
    let poses = mjcf_poses(robot, model);
    let planes: Vec<Plane> = robot
        .world_planes
        .iter()
        .map(|p| Plane {
            name: p.name.as_ref().map_or("a world plane".to_string(), |n| {
                format!("world plane '{n}'")
            }),
            point: Vector3::from(p.point),
            normal: Vector3::from(p.normal)
                .try_normalize(1e-12)
                .unwrap_or_else(Vector3::z),
            bits: Some(p.bits),
        })
        .collect();
    let (mut findings, reported_pairs) = self_overlaps(robot, model, collision, &poses);
    findings.extend(below_ground(robot, model, collision, &poses, &planes, true));
    StartContacts {
        findings,
        reported_pairs,
    }
}

/// `qpos0` (every joint at 0, unclamped: MuJoCo starts where the file puts the bodies) and each of the
/// first [`MAX_KEYS`] keyframes that differs from it, its floating root moved as the key moves it.
fn mjcf_poses(robot: &Robot, model: &Model) -> Vec<StartPose> {
    let zero = model.zero_configuration();
    let mut at_zero = Data::new(model);
    forward_kinematics(model, &zero, &mut at_zero);
    let mut poses = vec![StartPose {
        name: QPOS0.to_string(),
        data: at_zero,
    }];
    for key in robot.keyframes.iter().take(MAX_KEYS) {
        let mut q = zero.clone();
        for (name, value) in &key.joints {
            if let Some(JointId(j)) = model.joint(name) {
                if model.joint_data[j].is_actuated() {
                    q[j] = *value;
                }
            }
        }
        if q == zero && key.base.is_none() && key.free_bodies.is_empty() {
            continue;
        }
        let mut data = Data::new(model);
        forward_kinematics(model, &q, &mut data);
        for (body, placement) in &key.free_bodies {
            let Some(link) = model.link(body) else {
                continue;
            };
            let moved = pose_isometry(placement) * data.link_placement[link.0].inverse();
            for (other, at) in data.link_placement.iter_mut().enumerate() {
                if in_subtree(model, LinkId(other), link) {
                    *at = moved * *at;
                }
            }
        }
        if let Some(base) = &key.base {
            let base = pose_isometry(base);
            for placement in &mut data.link_placement {
                *placement = base * *placement;
            }
        }
        poses.push(StartPose {
            name: key.name.clone(),
            data,
        });
    }
    poses
}

/// Whether `link` is `top` or hangs below it.
fn in_subtree(model: &Model, link: LinkId, top: LinkId) -> bool {
    let mut at = link;
    for _ in 0..=model.parent_joint.len() {
        if at == top {
            return true;
        }
        let Some(joint) = model.parent_joint.get(at.0).copied().flatten() else {
            return false;
        };
        let Some((parent, _)) = model.joint_links.get(joint.0).copied().flatten() else {
            return false;
        };
        at = parent;
    }
    false
}

/// The masks of `link`'s `collision`-th collision (everything collides where the file says nothing).
fn bits(robot: &Robot, link: &Link, collision: usize) -> (u32, u32) {
    robot
        .contact_bits
        .get(&link.name.value)
        .and_then(|b| b.get(collision).copied())
        .unwrap_or((1, 1))
}

/// U042 for each pair of bodies MuJoCo collides that overlap by more than [`START_OVERLAP`] at one of
/// `poses`, and the pairs reported.
fn self_overlaps(
    robot: &Robot,
    model: &Model,
    collision: &CollisionModel,
    poses: &[StartPose],
) -> (Vec<Finding>, HashSet<(LinkId, LinkId)>) {
    let filtered: HashSet<(LinkId, LinkId)> = robot
        .collision_filtered
        .iter()
        .filter_map(|(a, b)| {
            let (a, b) = (model.link(a)?, model.link(b)?);
            Some((a.min(b), a.max(b)))
        })
        .collect();
    let links = collision.geometric_links();
    let mut deepest: BTreeMap<(LinkId, LinkId), Option<Deepest>> = BTreeMap::new();
    for pose in poses {
        let placements = &pose.data.link_placement;
        for (i, &a) in links.iter().enumerate() {
            for &b in &links[i + 1..] {
                if filtered.contains(&(a, b)) {
                    continue;
                }
                let (link_a, link_b) = (&robot.links[a.0], &robot.links[b.0]);
                let may_touch = |i: usize, j: usize| {
                    contact_bits_meet(bits(robot, link_a, i), bits(robot, link_b, j))
                };
                let found = collision.overlap_depth(
                    (a, &placements[a.0]),
                    (b, &placements[b.0]),
                    &may_touch,
                );
                if let Some((depth, _, at_b)) = found.filter(|f| f.0 > START_OVERLAP) {
                    Deepest::merge(deepest.entry((a, b)).or_default(), depth, at_b, &pose.name);
                }
            }
        }
    }
    let pairs: Vec<((LinkId, LinkId), Deepest)> = deepest
        .into_iter()
        .filter_map(|(pair, d)| Some((pair, d?)))
        .collect();
    // Excluded by the fix: a parent and child in contact at qpos0, the pair MuJoCo's parent filter leaves
    // out in every other model. Other pairs stay collidable: an exclude would let them pass through
    // each other in every pose (a hand's fingers through the arm); their geometry or pose is to change.
    let parents: Vec<Option<LinkId>> = pairs
        .iter()
        .map(|&((a, b), _)| parent_in_pair(robot, model, a, b))
        .collect();
    let fixable: Vec<bool> = pairs
        .iter()
        .zip(&parents)
        .map(|((_, d), parent)| d.at_qpos0() && parent.is_some())
        .collect();
    let fixed: Vec<(LinkId, LinkId)> = pairs
        .iter()
        .zip(&fixable)
        .filter(|(_, &f)| f)
        .map(|(&(pair, _), _)| pair)
        .collect();
    let fix = exclude_fix(robot, &fixed);
    let findings = pairs
        .iter()
        .zip(parents.iter().zip(&fixable))
        .map(|(&((a, b), ref d), (&parent, &fixable))| {
            let (link_a, link_b) = (&robot.links[a.0], &robot.links[b.0]);
            let why = match parent {
                Some(p) if welded_to_world(robot, model, p) => format!(
                    " (parent and child: MuJoCo's parent filter does not apply to '{}', which is welded to the world)",
                    robot.links[p.0].name.value
                ),
                Some(_) => " (parent and child: <flag filterparent=\"disable\"> turns MuJoCo's parent filter off)".to_string(),
                None => String::new(),
            };
            let span = link_b
                .collisions
                .get(d.collision)
                .map_or(link_b.span, |c| c.span);
            Finding::new(
                &rules::MJCF_CONTACT_AT_START,
                span,
                format!(
                    "bodies '{}' and '{}' overlap {}, and MuJoCo collides them{why}: contacts push them apart from the first step",
                    link_a.name.value,
                    link_b.name.value,
                    d.depths(),
                ),
            )
            .with_fix_option(fix.clone().filter(|_| fixable))
        })
        .collect();
    (findings, pairs.into_iter().map(|(pair, _)| pair).collect())
}

/// The body `link` hangs from, past the links without geometry of a multi-joint body.
fn parent_body(robot: &Robot, model: &Model, link: LinkId) -> Option<LinkId> {
    let chain_prefix = format!("{}:", robot.links[link.0].name.value);
    let mut at = link;
    for _ in 0..model.parent_joint.len() {
        let joint = model.parent_joint.get(at.0).copied().flatten()?;
        let (parent, _) = model.joint_links.get(joint.0).copied().flatten()?;
        // A multi-joint body's intermediate links are named `BODY:JOINT` after the body they lead to.
        if !robot.links[parent.0].name.value.starts_with(&chain_prefix) {
            return Some(parent);
        }
        at = parent;
    }
    None
}

/// The parent of the two when one hangs from the other.
fn parent_in_pair(robot: &Robot, model: &Model, a: LinkId, b: LinkId) -> Option<LinkId> {
    if parent_body(robot, model, b) == Some(a) {
        Some(a)
    } else if parent_body(robot, model, a) == Some(b) {
        Some(b)
    } else {
        None
    }
}

/// The fix of the parent-and-child U042s at `qpos0` (the model as designed; a pair that only a keyframe
/// puts in contact is the key's doing, which no exclude should hide): one `<exclude>` per pair, all in
/// one edit (fixes at the same place must be the same edit to be applied together); `None` when there
/// are none, or a body has no name to exclude it by.
fn exclude_fix(robot: &Robot, pairs: &[(LinkId, LinkId)]) -> Option<Fix> {
    let section = robot.contact_section?;
    let mut excludes = Vec::new();
    for &(a, b) in pairs {
        let (a, b) = (&robot.links[a.0].name.value, &robot.links[b.0].name.value);
        if a.starts_with("body#") || b.starts_with("body#") {
            return None;
        }
        excludes.push(format!(
            "<exclude body1=\"{}\" body2=\"{}\"/>",
            escape(a),
            escape(b)
        ));
    }
    let count = excludes.len();
    if count == 0 {
        return None;
    }
    let (element, lines) = match section {
        ContactSection::Existing(span) => (span, excludes),
        ContactSection::Missing(span) => (
            span,
            std::iter::once("<contact>".to_string())
                .chain(excludes.into_iter().map(|e| format!("  {e}")))
                .chain(std::iter::once("</contact>".to_string()))
                .collect(),
        ),
    };
    Some(
        Fix::unsafe_(
            format!(
                "exclude {} from contact (<contact><exclude>)",
                if count == 1 {
                    "the pair".to_string()
                } else {
                    format!("the {count} parent-and-child pairs that overlap at qpos0")
                }
            ),
            vec![Edit::InsertChild { element, lines }],
        )
        .in_mjcf(),
    )
}

/// `text` as an XML attribute value between double quotes.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
}

/// A ground the robot may start inside.
struct Plane {
    name: String,
    point: Vector3<f64>,
    normal: Vector3<f64>,
    /// Its `(contype, conaffinity)` (MJCF); `None`: everything collides with it.
    bits: Option<(u32, u32)>,
}

/// U603 for each link whose collision geometry reaches more than [`START_OVERLAP`] below one of `planes`
/// at one of `poses`; with `mujoco`, links welded to the world are left out (MuJoCo never collides them
/// with the world's geoms).
fn below_ground(
    robot: &Robot,
    model: &Model,
    collision: &CollisionModel,
    poses: &[StartPose],
    planes: &[Plane],
    mujoco: bool,
) -> Vec<Finding> {
    let mut findings = Vec::new();
    for &link in collision.geometric_links() {
        if mujoco && welded_to_world(robot, model, link) {
            continue;
        }
        let robot_link = &robot.links[link.0];
        for plane in planes {
            let may_touch = |i: usize| {
                plane
                    .bits
                    .is_none_or(|p| contact_bits_meet(p, bits(robot, robot_link, i)))
            };
            let mut deepest = None;
            for pose in poses {
                let found = collision.depth_below_plane(
                    link,
                    &pose.data.link_placement[link.0],
                    (&plane.point, &plane.normal),
                    &may_touch,
                );
                if let Some((depth, at)) = found.filter(|f| f.0 > START_OVERLAP) {
                    Deepest::merge(&mut deepest, depth, at, &pose.name);
                }
            }
            let Some(d) = deepest else { continue };
            let span = robot_link
                .collisions
                .get(d.collision)
                .map_or(robot_link.span, |c| c.span);
            let (what, when) = if mujoco {
                (format!("body '{}'", robot_link.name.value), d.depths())
            } else {
                (
                    format!("link '{}'", robot_link.name.value),
                    format!("{:.1} mm deep at {}", d.depth * 1e3, d.poses[0].0),
                )
            };
            findings.push(Finding::new(
                &rules::INSIDE_GROUND_AT_START,
                span,
                format!(
                    "{what} starts {when} inside {}: the contact pushes it out on the first step, with a force far above its weight",
                    plane.name,
                ),
            ));
        }
    }
    findings
}

/// Whether nothing but fixed joints lies between `link` and a fixed base's `world` root.
fn welded_to_world(robot: &Robot, model: &Model, link: LinkId) -> bool {
    let Some(root) = model.root else {
        return false;
    };
    if robot.links[root.0].name.value != "world" {
        return false; // a floating root: everything moves with its free joint
    }
    let mut at = link;
    for _ in 0..model.parent_joint.len() {
        if at == root {
            return true;
        }
        let Some(joint) = model.parent_joint.get(at.0).copied().flatten() else {
            return false;
        };
        if model.joint_data[joint.0].kind != JointKind::Fixed {
            return false;
        }
        let Some((parent, _)) = model.joint_links.get(joint.0).copied().flatten() else {
            return false;
        };
        at = parent;
    }
    false
}
