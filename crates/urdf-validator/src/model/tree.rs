//! The kinematic tree, built once from a [`Robot`] and then shared, immutable, by every analysis.
//!
//! Building it finds the structural problems (duplicate names, undefined links, loops, several roots,
//! broken mimic references); the tree keeps the first definition of a duplicated name and drops the joints
//! that would break it, so later analyses always see a forest of trees.

use std::collections::HashMap;

pub use crate::model::kinematics::{JointData, LinkMass};

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::diagnostics::suggest::did_you_mean;
use crate::urdf::robot::{JointKind, Robot, STANDARD_GRAVITY};

/// Index of a link in [`Robot::links`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct LinkId(pub usize);

/// Index of a joint in [`Robot::joints`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct JointId(pub usize);

/// A mimic relation: `q_follower = multiplier · q_leader + offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MimicLink {
    /// The joint being followed.
    pub leader: JointId,
    /// Scale.
    pub multiplier: f64,
    /// Offset.
    pub offset: f64,
}

/// What varying some joints moves ([`Model::motion_of`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Motion {
    /// Per joint: whether it varies (one of the joints, or a mimic follower of one).
    pub joints: Vec<bool>,
    /// Per link: whether its placement changes (a varying joint lies between it and its tree's root).
    pub links: Vec<bool>,
}

/// The kinematic tree of a robot.
#[derive(Clone, Debug, Default)]
pub struct Model {
    /// The root link (the root of the largest tree when there are several).
    pub root: Option<LinkId>,
    /// Every link without a parent joint, `root` first.
    pub roots: Vec<LinkId>,
    /// For each link, the joint that attaches it to its parent.
    pub parent_joint: Vec<Option<JointId>>,
    /// For each link, the joints to its children, in document order.
    pub child_joints: Vec<Vec<JointId>>,
    /// For each joint in the tree, (parent link, child link); `None` for joints left out of the tree.
    pub joint_links: Vec<Option<(LinkId, LinkId)>>,
    /// Links reachable from `root`, parents before children.
    pub topological_order: Vec<LinkId>,
    /// For each joint, its mimic leader when the reference is valid and acyclic.
    pub mimic: Vec<Option<MimicLink>>,
    /// The mimic followers, every leader before its followers (the order `apply_mimic` resolves them in).
    pub mimic_order: Vec<JointId>,
    /// For each joint, the independent joint its motion comes from and d q_joint / d q_leader (itself
    /// and 1 for a joint that mimics nothing).
    pub independent_leader: Vec<(JointId, f64)>,
    /// For each joint, its numbers ready for kinematics.
    pub joint_data: Vec<JointData>,
    /// For each link, its mass properties.
    pub link_mass: Vec<LinkMass>,
    /// The root frame's axis that points up in the world (`--up-axis`; +z, REP 103, unless declared): the
    /// root link is placed turned so it does.
    pub up: super::UpAxis,
    link_index: HashMap<String, LinkId>,
    joint_index: HashMap<String, JointId>,
    /// Gravity in the root frame, m/s² (the file's, else the standard (0, 0, −9.81)), as Pinocchio's
    /// `model.gravity`.
    pub gravity: nalgebra::Vector3<f64>,
    /// Per link, the share of its weight the simulator carries (MJCF `gravcomp`); empty when no link has
    /// one.
    pub weight_carried: Vec<f64>,
}

impl Model {
    /// Build the tree and report structural findings.
    pub fn build(robot: &Robot) -> (Model, Vec<Finding>) {
        let mut findings = Vec::new();
        let mut model = Model {
            parent_joint: vec![None; robot.links.len()],
            child_joints: vec![Vec::new(); robot.links.len()],
            joint_links: vec![None; robot.joints.len()],
            mimic: vec![None; robot.joints.len()],
            ..Model::default()
        };
        index_names(robot, &mut model, &mut findings);
        attach_joints(robot, &mut model, &mut findings);
        find_roots(robot, &mut model, &mut findings);
        resolve_mimics(robot, &mut model, &mut findings);
        model.joint_data = robot.joints.iter().map(JointData::from_joint).collect();
        model.link_mass = robot.links.iter().map(LinkMass::from_link).collect();
        model.gravity = robot
            .gravity
            .as_ref()
            .map_or(STANDARD_GRAVITY, |g| g.value)
            .into();
        if !robot.gravity_compensation.is_empty() {
            let mut carried = vec![0.0; robot.links.len()];
            for (name, share) in &robot.gravity_compensation {
                if let Some(link) = model.link_index.get(name) {
                    carried[link.0] = share.value;
                }
            }
            model.weight_carried = carried;
        }
        (model, findings)
    }

    /// The joints from `link` up to the root, the link's own parent joint first.
    pub fn joints_to_root(&self, link: LinkId) -> Vec<JointId> {
        let mut joints = Vec::new();
        let mut at = link;
        while let Some(joint) = self.parent_joint[at.0] {
            joints.push(joint);
            match self.joint_links[joint.0] {
                // At most one step per joint: the tree has no cycles, but never loop on a broken one.
                Some((parent, _)) if joints.len() <= self.joint_data.len() => at = parent,
                _ => break,
            }
        }
        joints
    }

    /// What varying `joints` moves (see [`Motion`]).
    pub fn motion_of(&self, joints: &[JointId]) -> Motion {
        let mut varies = vec![false; self.joint_data.len()];
        for joint in joints {
            if let Some(v) = varies.get_mut(joint.0) {
                *v = true;
            }
        }
        // Followers of varying joints vary too (leaders come first in `mimic_order`).
        for follower in &self.mimic_order {
            if self.mimic[follower.0].is_some_and(|m| varies[m.leader.0]) {
                varies[follower.0] = true;
            }
        }
        // A link moves when a varying joint lies between it and its root: each walk up stops at the first
        // link already known, so every link is visited once.
        let mut moves: Vec<Option<bool>> = vec![None; self.parent_joint.len()];
        let mut path = Vec::new();
        for start in 0..moves.len() {
            let mut link = start;
            let value = loop {
                if let Some(known) = moves[link] {
                    break known;
                }
                path.push(link);
                let Some((joint, parent)) = self.parent_joint[link]
                    .and_then(|j| self.joint_links[j.0].map(|(parent, _)| (j, parent)))
                else {
                    break false;
                };
                // Never loop on a broken tree (Model::build prevents one).
                if varies[joint.0] || path.len() > moves.len() {
                    break varies[joint.0];
                }
                link = parent.0;
            };
            for l in path.drain(..) {
                moves[l] = Some(value);
            }
        }
        Motion {
            joints: varies,
            links: moves.into_iter().map(|m| m.unwrap_or(false)).collect(),
        }
    }

    /// The link named `name` (first definition).
    pub fn link(&self, name: &str) -> Option<LinkId> {
        self.link_index.get(name).copied()
    }

    /// The joint named `name` (first definition).
    pub fn joint(&self, name: &str) -> Option<JointId> {
        self.joint_index.get(name).copied()
    }

    /// All link names, for suggestions.
    pub fn link_names(&self) -> impl Iterator<Item = &str> {
        self.link_index.keys().map(String::as_str)
    }

    /// All joint names, for suggestions.
    pub fn joint_names(&self) -> impl Iterator<Item = &str> {
        self.joint_index.keys().map(String::as_str)
    }

    /// True when the link hangs from its parent by a non-fixed joint.
    pub fn is_moving(&self, robot: &Robot, link: LinkId) -> bool {
        self.parent_joint[link.0]
            .and_then(|j| robot.joints[j.0].kind.as_ref())
            .is_some_and(|k| k.value != JointKind::Fixed)
    }
}

fn index_names(robot: &Robot, model: &mut Model, findings: &mut Vec<Finding>) {
    for (i, link) in robot.links.iter().enumerate() {
        if model.link_index.contains_key(&link.name.value) {
            findings.push(Finding::new(
                &rules::DUPLICATE_NAME,
                link.name.span,
                format!("Link '{}' is defined more than once", link.name.value),
            ));
        } else {
            model.link_index.insert(link.name.value.clone(), LinkId(i));
        }
    }
    for (i, joint) in robot.joints.iter().enumerate() {
        if model.joint_index.contains_key(&joint.name.value) {
            findings.push(Finding::new(
                &rules::DUPLICATE_NAME,
                joint.name.span,
                format!("Joint '{}' is defined more than once", joint.name.value),
            ));
        } else {
            model
                .joint_index
                .insert(joint.name.value.clone(), JointId(i));
        }
    }
    let mut materials = HashMap::new();
    for material in &robot.materials {
        if materials.insert(material.name.value.as_str(), ()).is_some() {
            findings.push(Finding::new(
                &rules::DUPLICATE_NAME,
                material.name.span,
                format!(
                    "Material '{}' is defined more than once",
                    material.name.value
                ),
            ));
        }
    }
}

fn attach_joints(robot: &Robot, model: &mut Model, findings: &mut Vec<Finding>) {
    for (i, joint) in robot.joints.iter().enumerate() {
        let id = JointId(i);
        if model.joint(&joint.name.value) != Some(id) {
            continue; // A duplicate: only the first definition joins the tree.
        }
        let mut resolve = |role: &str, name: &Option<crate::diagnostics::span::Spanned<String>>| {
            let name = name.as_ref()?;
            let found = model.link(&name.value);
            if found.is_none() {
                findings.push(
                    Finding::new(
                        &rules::UNDEFINED_LINK,
                        name.span,
                        format!(
                            "Joint '{}' references {role} link '{}', which does not exist",
                            joint.name.value, name.value
                        ),
                    )
                    .with_help(did_you_mean(
                        &name.value,
                        model.link_index.keys().map(String::as_str),
                    )),
                );
            }
            found
        };
        let parent = resolve("parent", &joint.parent);
        let child = resolve("child", &joint.child);
        let (Some(parent), Some(child)) = (parent, child) else {
            continue;
        };
        if parent == child {
            findings.push(Finding::new(
                &rules::KINEMATIC_LOOP,
                joint.span,
                format!(
                    "Joint '{}' connects link '{}' to itself",
                    joint.name.value, robot.links[parent.0].name.value
                ),
            ));
            continue;
        }
        if let Some(existing) = model.parent_joint[child.0] {
            findings.push(Finding::new(
                &rules::KINEMATIC_LOOP,
                joint.span,
                format!(
                    "Link '{}' has two parent joints, '{}' and '{}': a kinematic loop",
                    robot.links[child.0].name.value,
                    robot.joints[existing.0].name.value,
                    joint.name.value
                ),
            ));
            continue;
        }
        model.parent_joint[child.0] = Some(id);
        model.child_joints[parent.0].push(id);
        model.joint_links[i] = Some((parent, child));
    }
}

/// Subtree of `start` in parent-before-child order; guards against cycles with `seen`.
fn descendants(model: &Model, start: LinkId, seen: &mut [bool]) -> Vec<LinkId> {
    let mut order = Vec::new();
    let mut stack = vec![start];
    while let Some(link) = stack.pop() {
        if std::mem::replace(&mut seen[link.0], true) {
            continue;
        }
        order.push(link);
        for joint in model.child_joints[link.0].iter().rev() {
            if let Some((_, child)) = model.joint_links[joint.0] {
                stack.push(child);
            }
        }
    }
    order
}

fn find_roots(robot: &Robot, model: &mut Model, findings: &mut Vec<Finding>) {
    let n = robot.links.len();
    let is_first_definition = |i: usize| model.link(&robot.links[i].name.value) == Some(LinkId(i));
    let roots: Vec<LinkId> = (0..n)
        .filter(|&i| model.parent_joint[i].is_none() && is_first_definition(i))
        .map(LinkId)
        .collect();
    let mut seen = vec![false; n];
    let mut trees: Vec<(LinkId, Vec<LinkId>)> = roots
        .iter()
        .map(|&r| (r, descendants(model, r, &mut seen)))
        .collect();
    // Links never reached from a root sit on (or below) a cycle of parent joints.
    let in_a_tree = seen.clone();
    for i in 0..n {
        if seen[i] || !is_first_definition(i) {
            continue;
        }
        let mut cycle = Vec::new();
        let mut link = LinkId(i);
        while !seen[link.0] {
            seen[link.0] = true;
            cycle.push(link);
            match model.parent_joint[link.0].and_then(|j| model.joint_links[j.0]) {
                Some((parent, _)) => link = parent,
                None => break,
            }
        }
        if let Some(pos) = cycle.iter().position(|&l| l == link) {
            let names: Vec<&str> = cycle[pos..]
                .iter()
                .map(|l| robot.links[l.0].name.value.as_str())
                .collect();
            let span = model.parent_joint[link.0]
                .map_or(robot.links[link.0].span, |j| robot.joints[j.0].span);
            findings.push(Finding::new(
                &rules::KINEMATIC_LOOP,
                span,
                format!("Joints form a cycle through links {}", names.join(" → ")),
            ));
        }
    }
    detach_unrooted(model, &in_a_tree);
    trees.sort_by_key(|(root, members)| (std::cmp::Reverse(members.len()), root.0));
    if trees.len() > 1 {
        for (root, members) in &trees[1..] {
            let link = &robot.links[root.0];
            findings.push(
                Finding::new(
                    &rules::MULTIPLE_ROOTS,
                    link.name.span,
                    format!(
                        "Link '{}' is a second root: it and {} link(s) below it are not connected to '{}'",
                        link.name.value,
                        members.len() - 1,
                        robot.links[trees[0].0 .0].name.value
                    ),
                )
                .with_help("connect it with a joint (often a forgotten fixed joint), or delete it"),
            );
        }
    }
    model.roots = trees.iter().map(|(root, _)| *root).collect();
    model.root = model.roots.first().copied();
    model.topological_order = trees
        .into_iter()
        .next()
        .map(|(_, members)| members)
        .unwrap_or_default();
}

/// Cut the joints that hang links no root reaches (links on or below a cycle of parent joints) out of
/// the tree, so the Model is a forest by construction: every walk up parents or down children ends.
fn detach_unrooted(model: &mut Model, in_a_tree: &[bool]) {
    for (link, reached) in in_a_tree.iter().enumerate() {
        if *reached {
            continue;
        }
        if let Some(joint) = model.parent_joint[link].take() {
            if let Some((parent, _)) = model.joint_links[joint.0].take() {
                model.child_joints[parent.0].retain(|&j| j != joint);
            }
        }
    }
}

fn resolve_mimics(robot: &Robot, model: &mut Model, findings: &mut Vec<Finding>) {
    for (i, joint) in robot.joints.iter().enumerate() {
        let Some(mimic) = &joint.mimic else { continue };
        if !(mimic.multiplier.is_finite() && mimic.offset.is_finite()) {
            continue; // Reported by the parser; the joint stays independent.
        }
        match model.joint(&mimic.joint.value) {
            Some(leader) => {
                model.mimic[i] = Some(MimicLink {
                    leader,
                    multiplier: mimic.multiplier,
                    offset: mimic.offset,
                })
            }
            None => findings.push(
                Finding::new(
                    &rules::MIMIC_UNDEFINED_JOINT,
                    mimic.joint.span,
                    format!(
                        "Joint '{}' mimics joint '{}', which does not exist",
                        joint.name.value, mimic.joint.value
                    ),
                )
                .with_help(did_you_mean(
                    &mimic.joint.value,
                    model.joint_index.keys().map(String::as_str),
                )),
            ),
        }
    }
    // Each joint has at most one leader, so every walk along leaders either ends at an independent
    // joint or runs into a cycle. Walking from every joint not visited yet, and stopping at joints
    // already visited, touches each joint once: linear time even for a chain of thousands of mimics.
    let n = robot.joints.len();
    #[derive(Clone, Copy, PartialEq)]
    enum Visit {
        New,
        OnPath,
        Done,
    }
    let mut visit = vec![Visit::New; n];
    let mut in_cycle = vec![false; n];
    let mut path = Vec::new();
    for start in 0..n {
        path.clear();
        let mut current = start;
        while visit[current] == Visit::New {
            visit[current] = Visit::OnPath;
            path.push(current);
            match model.mimic[current] {
                Some(link) => current = link.leader.0,
                None => break,
            }
        }
        if visit[current] == Visit::OnPath && model.mimic[current].is_some() {
            // The walk came back to a joint of its own path: the path from there on is a cycle.
            // Reported from its first member in document order, following the leaders.
            let at = path.iter().position(|&j| j == current).unwrap_or(0);
            let cycle = &path[at..];
            let first = cycle
                .iter()
                .enumerate()
                .min_by_key(|(_, &j)| j)
                .map_or(0, |(i, _)| i);
            let names: Vec<&str> = cycle[first..]
                .iter()
                .chain(&cycle[..first])
                .map(|&j| robot.joints[j].name.value.as_str())
                .collect();
            let head = cycle[first];
            let span = robot.joints[head]
                .mimic
                .as_ref()
                .map_or(robot.joints[head].span, |m| m.span);
            findings.push(Finding::new(
                &rules::MIMIC_CYCLE,
                span,
                format!(
                    "Mimic joints follow each other in a cycle: {} → {}",
                    names.join(" → "),
                    names[0]
                ),
            ));
            cycle.iter().for_each(|&j| in_cycle[j] = true);
        }
        path.iter().for_each(|&j| visit[j] = Visit::Done);
    }
    for (i, cyclic) in in_cycle.into_iter().enumerate() {
        if cyclic {
            model.mimic[i] = None;
        }
    }
    resolve_mimic_order(model);
}

/// `mimic_order` and `independent_leader` from the (acyclic) `mimic` relation, in linear time.
fn resolve_mimic_order(model: &mut Model) {
    let n = model.mimic.len();
    let mut resolved = vec![false; n];
    model.independent_leader = (0..n).map(|j| (JointId(j), 1.0)).collect();
    model.mimic_order = Vec::new();
    let mut chain = Vec::new();
    for start in 0..n {
        // Climb to a joint already resolved (or an independent one), then resolve back down.
        chain.clear();
        let mut current = start;
        while !resolved[current] {
            chain.push(current);
            match model.mimic[current] {
                Some(link) => current = link.leader.0,
                None => break,
            }
        }
        for &joint in chain.iter().rev() {
            resolved[joint] = true;
            if let Some(link) = model.mimic[joint] {
                let (leader, factor) = model.independent_leader[link.leader.0];
                model.independent_leader[joint] = (leader, link.multiplier * factor);
                model.mimic_order.push(JointId(joint));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `base` carries `a` (j1, with `c` fixed below it), `b` (j2, mimicking j1) and `d` (j4); `e` carries
    /// `f` (j5) in a second tree.
    const ROBOT: &str = r#"<robot name="r">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <link name="e"/><link name="f"/>
  <joint name="j1" type="continuous"><parent link="base"/><child link="a"/></joint>
  <joint name="j2" type="continuous"><parent link="base"/><child link="b"/><mimic joint="j1"/></joint>
  <joint name="j3" type="fixed"><parent link="a"/><child link="c"/></joint>
  <joint name="j4" type="continuous"><parent link="base"/><child link="d"/></joint>
  <joint name="j5" type="continuous"><parent link="e"/><child link="f"/></joint>
</robot>"#;

    #[test]
    fn a_motion_moves_the_subtrees_of_its_joints_and_of_their_followers() {
        let (robot, _) = crate::urdf::parse_urdf(ROBOT, std::path::Path::new("r.urdf")).unwrap();
        let (model, _) = Model::build(&robot);
        let named = |names: &[&str], of: &dyn Fn(&str) -> Option<usize>, count: usize| {
            let mut flags = vec![false; count];
            for name in names {
                flags[of(name).unwrap()] = true;
            }
            flags
        };
        let links = |names: &[&str]| named(names, &|n| model.link(n).map(|l| l.0), 7);
        let joints = |names: &[&str]| named(names, &|n| model.joint(n).map(|j| j.0), 5);
        let j = |name: &str| model.joint(name).unwrap();
        assert_eq!(
            model.motion_of(&[j("j1")]),
            Motion {
                joints: joints(&["j1", "j2"]),
                links: links(&["a", "b", "c"]),
            }
        );
        assert_eq!(model.motion_of(&[j("j5")]).links, links(&["f"]));
        assert_eq!(model.motion_of(&[]).links, links(&[]));
    }
}
