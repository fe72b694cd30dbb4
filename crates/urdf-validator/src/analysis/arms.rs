//! Arm chains: where each arm leaves the body, the joints it moves, and its end effector.
//!
//! Detection works on the tree alone (no pose):
//! 1. **Fingers** are set apart first: the branches at a link where two or more actuated branches split and
//!    each has at most two independent joints (a gripper), branches that start at a mimic joint, and
//!    branches whose joint or link names say finger, thumb, gripper, jaw, claw or knuckle.
//! 2. **Limb joints** are independent, position-limited revolute and prismatic joints outside fingers,
//!    legs and wheels; continuous joints (wheels, casters, screws) do not make a limb but an arm still
//!    moves through them.
//! 3. From the body (the root), every branch holding at least three limb joints is followed down. Where
//!    the chain splits again and a branch holds three or more limb joints, what was followed so far is a
//!    torso (part of the body), and each such branch is followed in turn (PR2, TIAGo, Talos: a lift or a
//!    waist carrying two arms and a head). Where it splits into small branches only, or no actuated branch
//!    is left, the chain ends: that link is the wrist.
//! 4. The **tip** is the tool frame when the wrist carries one through fixed joints (a link named tcp,
//!    tool, grasp, end_effector or ee), else the hand (where the fingers attach), else the wrist.
//!
//! Branches named like a head, neck or eyes are sensors, not arms.

use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::{JointKind, Robot};

/// One arm.
#[derive(Clone, Debug, PartialEq)]
pub struct Arm {
    /// The body link the arm hangs from.
    pub base: LinkId,
    /// The end-effector frame whose reach is measured.
    pub tip: LinkId,
    /// Joints from `base` to `tip`, in order (fixed ones included).
    pub path: Vec<JointId>,
    /// Where the fingers attach, when the arm has a gripper.
    pub hand: Option<LinkId>,
    /// The finger links below the hand.
    pub fingers: Vec<LinkId>,
    /// True when declared with `--arm-root`/`--arm-tip`.
    pub declared: bool,
}

impl Arm {
    /// The first actuated joint of the arm (its shoulder), if any.
    pub fn first_joint(&self, model: &Model) -> Option<JointId> {
        self.path
            .iter()
            .copied()
            .find(|j| model.joint_data[j.0].is_actuated())
    }

    /// Independent actuated joints on the path (what sampling moves).
    pub fn sampled_joints(&self, model: &Model) -> Vec<JointId> {
        self.path
            .iter()
            .copied()
            .filter(|j| model.joint_data[j.0].is_actuated() && model.mimic[j.0].is_none())
            .collect()
    }
}

/// Parts of names that mark a finger wherever they appear (`LFinger`, `leftfinger_joint`).
const FINGER_PARTS: [&str; 6] = ["finger", "fngr", "thumb", "knuckle", "claw", "pinky"];
/// Whole words (between `_`, `.`, `-` or digits) that mark a finger: `hand_index_flex_1`, `ring_joint`.
const FINGER_WORDS: [&str; 5] = ["index", "middle", "ring", "little", "jaw"];
const SENSOR_PARTS: [&str; 5] = ["head", "neck", "eye", "camera", "pan_tilt"];
/// Parts of names of tool frames.
const TOOL_WORDS: [&str; 6] = ["tcp", "tool", "grasp", "end_effector", "ee_", "_ee"];
/// Whole words of virtual base joints (a planar base modelled with joints) that belong to the body.
const BASE_WORDS: [&str; 4] = ["base", "world", "odom", "virtual"];

fn has_part(name: &str, parts: &[&str]) -> bool {
    let name = name.to_ascii_lowercase();
    parts.iter().any(|w| name.contains(w))
}

fn has_word(name: &str, words: &[&str]) -> bool {
    name.to_ascii_lowercase()
        .split(|c: char| !c.is_ascii_alphabetic())
        .any(|token| words.contains(&token))
}

/// Parts of names of wrist rotations (`LeftGripperYaw` turns the whole hand: it is not a finger). Parts,
/// not words, for camel case; `roll` but not `roller` / `controller`.
const WRIST_PARTS: [&str; 4] = ["yaw", "pitch", "roll", "wrist"];

fn wrist_name(name: &str) -> bool {
    has_part(
        &name.to_ascii_lowercase().replace("roller", ""),
        &WRIST_PARTS,
    )
}

/// A joint whose own name says it moves a finger or a gripper's jaws.
fn finger_joint_name(name: &str) -> bool {
    has_part(name, &FINGER_PARTS)
        || has_word(name, &FINGER_WORDS)
        || (has_part(name, &["gripper"]) && !wrist_name(name))
}

/// A link whose name says it is a finger (a link named `gripper` is the hand itself).
fn finger_link_name(name: &str) -> bool {
    has_part(name, &FINGER_PARTS) || has_word(name, &FINGER_WORDS)
}

fn child(model: &Model, joint: JointId) -> Option<LinkId> {
    model.joint_links[joint.0].map(|(_, c)| c)
}

/// Every joint in the subtree hanging from `joint` (itself included).
fn subtree_joints(model: &Model, joint: JointId) -> Vec<JointId> {
    let mut out = vec![joint];
    let mut i = 0;
    while i < out.len() {
        if let Some(link) = child(model, out[i]) {
            out.extend(model.child_joints[link.0].iter().copied());
        }
        i += 1;
        if out.len() > model.joint_data.len() {
            break; // defensive: the tree has no cycles, but never loop on a broken one
        }
    }
    out
}

/// `seeds`, then every link welded below them through fixed joints (breadth first), each once, with the
/// fixed joint into it and the index of its parent in the list (`None` for the seeds).
fn welded_below(model: &Model, seeds: &[LinkId]) -> Vec<(LinkId, Option<(JointId, usize)>)> {
    let mut welded: Vec<(LinkId, Option<(JointId, usize)>)> =
        seeds.iter().map(|&link| (link, None)).collect();
    let mut seen = vec![false; model.parent_joint.len()];
    for &link in seeds {
        seen[link.0] = true;
    }
    let mut i = 0;
    while i < welded.len() {
        for &j in &model.child_joints[welded[i].0 .0] {
            if let (JointKind::Fixed, Some(c)) = (model.joint_data[j.0].kind, child(model, j)) {
                if !seen[c.0] {
                    seen[c.0] = true;
                    welded.push((c, Some((j, i))));
                }
            }
        }
        i += 1;
    }
    welded
}

/// Every link in the subtree below `link` (itself included).
pub fn subtree_links(model: &Model, link: LinkId) -> Vec<LinkId> {
    let mut out = vec![link];
    let mut i = 0;
    while i < out.len() && out.len() <= model.parent_joint.len() {
        out.extend(
            model.child_joints[out[i].0]
                .iter()
                .filter_map(|&j| child(model, j)),
        );
        i += 1;
    }
    out
}

fn independent(model: &Model, joint: JointId) -> bool {
    model.joint_data[joint.0].is_actuated() && model.mimic[joint.0].is_none()
}

/// Per joint, for the subtree hanging from it (itself included): whether it holds an actuated joint, and
/// how many independent joints it holds. One pass from the leaves up.
fn subtree_counts(model: &Model) -> (Vec<bool>, Vec<usize>) {
    let n = model.joint_data.len();
    let (mut actuated, mut independents) = (vec![false; n], vec![0; n]);
    for &link in model.topological_order.iter().rev() {
        for &j in &model.child_joints[link.0] {
            let below = child(model, j).map_or(&[][..], |c| &model.child_joints[c.0][..]);
            actuated[j.0] =
                model.joint_data[j.0].is_actuated() || below.iter().any(|b| actuated[b.0]);
            independents[j.0] = usize::from(independent(model, j))
                + below.iter().map(|b| independents[b.0]).sum::<usize>();
        }
    }
    (actuated, independents)
}

/// Joints inside finger branches (`by_name`: also branches named like fingers).
fn finger_joints(robot: &Robot, model: &Model, by_name: bool) -> Vec<bool> {
    let mut finger = vec![false; model.joint_data.len()];
    // Parents come first, so a marked top has its whole subtree marked already.
    let mark = |finger: &mut Vec<bool>, top: JointId| {
        if !finger[top.0] {
            for j in subtree_joints(model, top) {
                finger[j.0] = true;
            }
        }
    };
    let (actuated, independents) = subtree_counts(model);
    let small = |j: JointId| independents[j.0] <= 2;
    for &link in &model.topological_order {
        let branches: Vec<JointId> = model.child_joints[link.0]
            .iter()
            .copied()
            .filter(|j| actuated[j.0])
            .collect();
        if branches.len() >= 2 && branches.iter().all(|&j| small(j)) {
            for &top in &branches {
                mark(&mut finger, top);
            }
        }
        let mut any_named = false;
        for &j in &model.child_joints[link.0] {
            let named = by_name
                && (finger_joint_name(&robot.joints[j.0].name.value)
                    || child(model, j)
                        .is_some_and(|c| finger_link_name(&robot.links[c.0].name.value)));
            // A name marks a branch only as small as a finger: a joint named `gripper_*` that carries a
            // whole hand is the wrist.
            let finger_sized = independents[j.0] <= FINGER_JOINTS;
            if model.mimic[j.0].is_some()
                || (named && model.joint_data[j.0].is_actuated() && finger_sized)
            {
                mark(&mut finger, j);
                any_named = true;
            }
        }
        // Beside a finger, every small actuated branch is a finger too (TIAGo's `hand_mrl_joint`).
        if any_named {
            for &top in &branches {
                if small(top) {
                    mark(&mut finger, top);
                }
            }
        }
    }
    finger
}

/// What arm detection needs from classification.
pub struct BodyParts<'a> {
    /// Top joints of the legs.
    pub leg_tops: &'a [JointId],
    /// Wheel links.
    pub wheels: &'a [LinkId],
}

struct Detector<'a> {
    robot: &'a Robot,
    model: &'a Model,
    finger: Vec<bool>,
    /// Independent actuated joints in the subtree of each joint (itself included), outside fingers, legs
    /// and wheels: the joints that make a limb.
    limbs: Vec<usize>,
    /// Joints whose subtree is a leg or a wheel: where they attach is the body.
    locomotion: Vec<bool>,
    arms: Vec<Arm>,
}

/// A split into this many limb branches, none longer than [`FINGER_JOINTS`], is a hand, not a torso.
const HAND_BRANCHES: usize = 4;
/// The most joints a finger has.
const FINGER_JOINTS: usize = 4;

impl Detector<'_> {
    /// Child joints of `link` that move a limb, with their limb-joint counts.
    fn limb_branches(&self, link: LinkId) -> Vec<(JointId, usize)> {
        self.model.child_joints[link.0]
            .iter()
            .filter(|j| self.model.joint_links[j.0].is_some() && self.limbs[j.0] > 0)
            .map(|&j| (j, self.limbs[j.0]))
            .collect()
    }

    fn is_sensor_branch(&self, joint: JointId) -> bool {
        has_part(&self.robot.joints[joint.0].name.value, &SENSOR_PARTS)
            || child(self.model, joint)
                .is_some_and(|c| has_part(&self.robot.links[c.0].name.value, &SENSOR_PARTS))
    }

    /// A virtual base joint (a planar base modelled with joints: joint and child both named base) belongs
    /// to the body.
    fn is_base_joint(&self, joint: JointId) -> bool {
        has_word(&self.robot.joints[joint.0].name.value, &BASE_WORDS)
            && child(self.model, joint)
                .is_some_and(|c| has_word(&self.robot.links[c.0].name.value, &BASE_WORDS))
    }

    fn carries_locomotion(&self, link: LinkId) -> bool {
        self.model.child_joints[link.0]
            .iter()
            .any(|j| self.locomotion[j.0])
    }

    fn visit_body(&mut self, link: LinkId, depth: usize) {
        if depth > self.model.parent_joint.len() {
            return;
        }
        for (joint, count) in self.limb_branches(link) {
            if count >= 3 && !self.is_sensor_branch(joint) {
                self.follow(link, joint, depth + 1);
            }
        }
    }

    fn follow(&mut self, base: LinkId, first: JointId, depth: usize) {
        let mut path = vec![first];
        let Some(mut link) = child(self.model, first) else {
            return;
        };
        let leading_base =
            self.is_base_joint(first) || !self.model.joint_data[first.0].is_actuated();
        loop {
            let branches = self.limb_branches(link);
            let hand = branches.len() >= HAND_BRANCHES
                && branches.iter().all(|(_, n)| *n <= FINGER_JOINTS);
            let torso = self.carries_locomotion(link)
                || (leading_base
                    && path.iter().all(|&j| {
                        self.is_base_joint(j) || !self.model.joint_data[j.0].is_actuated()
                    }))
                || (branches.len() >= 2 && !hand && branches.iter().any(|(_, n)| *n >= 3));
            if torso && !branches.is_empty() {
                // What was followed so far is body: the arms start here.
                self.visit_body(link, depth);
                return;
            }
            match branches.as_slice() {
                [(joint, _)] => {
                    path.push(*joint);
                    match child(self.model, *joint) {
                        Some(next) => link = next,
                        None => return,
                    }
                }
                // No limb left, or a split into small branches or many fingers: the wrist.
                _ => break,
            }
            if path.len() > self.model.joint_data.len() {
                return;
            }
        }
        let arm = self.finish(base, path, link, false);
        self.arms.push(arm);
    }

    /// Complete an arm ending at the wrist `wrist`: find the hand, the fingers and the tool frame.
    fn finish(&self, base: LinkId, mut path: Vec<JointId>, wrist: LinkId, declared: bool) -> Arm {
        let model = self.model;
        // Links welded to the wrist, each with the fixed joint into it and the index of its parent here
        // (paths are rebuilt on demand: copying them per link is quadratic on long welded chains).
        let welded = welded_below(model, &[wrist]);
        let depth: Vec<usize> = {
            let mut depth = vec![0; welded.len()];
            for (index, (_, from)) in welded.iter().enumerate() {
                if let Some((_, parent)) = from {
                    depth[index] = depth[*parent] + 1;
                }
            }
            depth
        };
        let via = |mut index: usize| -> Vec<JointId> {
            let mut joints = Vec::new();
            while let Some((joint, parent)) = welded[index].1 {
                joints.push(joint);
                index = parent;
            }
            joints.reverse();
            joints
        };
        let finger_tops = |link: LinkId| -> Vec<JointId> {
            model.child_joints[link.0]
                .iter()
                .copied()
                .filter(|j| self.finger[j.0])
                .collect()
        };
        let hand_index = welded.iter().position(|(l, _)| !finger_tops(*l).is_empty());
        let hand = hand_index.map(|index| welded[index].0);
        let fingers: Vec<LinkId> = hand
            .map(|h| {
                finger_tops(h)
                    .into_iter()
                    .filter_map(|j| child(model, j))
                    .flat_map(|c| subtree_links(model, c))
                    .collect()
            })
            .unwrap_or_default();
        // A tool frame (tcp, tool, grasp, end effector) beats a `tip` link, deeper beating shallower; then
        // the first link named `hand`, `palm` or `gripper` (not its welded jaws). Links named like fingers
        // are fingers when the arm has a hand, and a frame above the hand (a wrist force-torque sensor's
        // `ft_tool_link`) is not the tool.
        let mut above_hand = vec![false; welded.len()];
        if let Some(mut index) = hand_index {
            while let Some((_, parent)) = welded[index].1 {
                above_hand[parent] = true;
                index = parent;
            }
        }
        let tool_score = |link: LinkId| -> usize {
            let name = self.robot.links[link.0].name.value.to_ascii_lowercase();
            if hand.is_some() && finger_link_name(&name) {
                0
            } else if has_part(&name, &TOOL_WORDS)
                || has_word(&name, &["ee"])
                || name.ends_with("ee_link")
            {
                3
            } else if has_word(&name, &["tip"]) {
                2
            } else {
                usize::from(has_word(&name, &["hand", "palm", "gripper"]))
            }
        };
        let depth_preference = |score: usize, index: usize| {
            let depth = depth[index] as isize;
            if score == 1 {
                -depth
            } else {
                depth
            }
        };
        let tool = (0..welded.len())
            .filter(|&index| tool_score(welded[index].0) > 0 && !above_hand[index])
            .max_by_key(|&index| {
                let score = tool_score(welded[index].0);
                (score, depth_preference(score, index))
            });
        let tip_index = tool.or(hand_index).unwrap_or(0);
        let tip = welded[tip_index].0;
        path.extend(via(tip_index));
        Arm {
            base,
            tip,
            path,
            hand,
            fingers,
            declared,
        }
    }
}

/// Every arm of the robot, found from its structure.
pub fn detect(robot: &Robot, model: &Model, parts: &BodyParts) -> Vec<Arm> {
    let arms = detect_with(robot, model, parts, true);
    if arms.is_empty() {
        // A robot that is one finger (a TriFinger module) is an arm.
        detect_with(robot, model, parts, false)
    } else {
        arms
    }
}

fn detect_with(robot: &Robot, model: &Model, parts: &BodyParts, fingers_by_name: bool) -> Vec<Arm> {
    let finger = finger_joints(robot, model, fingers_by_name);
    let mut locomotion = vec![false; model.joint_data.len()];
    for &top in parts.leg_tops {
        for j in subtree_joints(model, top) {
            locomotion[j.0] = true;
        }
    }
    for &wheel in parts.wheels {
        if let Some(j) = model.parent_joint[wheel.0] {
            locomotion[j.0] = true;
        }
    }
    let mut limbs = vec![0; model.joint_data.len()];
    for &link in model.topological_order.iter().rev() {
        if let Some(j) = model.parent_joint[link.0] {
            if locomotion[j.0] || finger[j.0] {
                continue;
            }
            let below: usize = model.child_joints[link.0].iter().map(|c| limbs[c.0]).sum();
            limbs[j.0] = below + usize::from(independent(model, j));
        }
    }
    let mut detector = Detector {
        robot,
        model,
        finger,
        limbs,
        locomotion,
        arms: Vec::new(),
    };
    if let Some(root) = model.root {
        detector.visit_body(root, 0);
    }
    detector.arms
}

/// The arm declared with `--arm-root`/`--arm-tip` (the tip must lie below the root).
pub fn declared(robot: &Robot, model: &Model, root: LinkId, tip: LinkId) -> Option<Arm> {
    let mut path = Vec::new();
    let mut current = tip;
    while current != root {
        let joint = model.parent_joint[current.0]?;
        let (parent, _) = model.joint_links[joint.0]?;
        path.push(joint);
        current = parent;
        if path.len() > model.joint_data.len() {
            return None;
        }
    }
    path.reverse();
    let finger = finger_joints(robot, model, true);
    let fingers_at = |link: LinkId| -> Vec<LinkId> {
        model.child_joints[link.0]
            .iter()
            .filter(|j| finger[j.0])
            .filter_map(|&j| child(model, j))
            .flat_map(|c| subtree_links(model, c))
            .collect()
    };
    // The hand: the tip, or the nearest link welded to it (a tool frame hangs from the palm) that fingers
    // attach to.
    let mut welded_above = vec![tip];
    let mut up = tip;
    while up != root && welded_above.len() <= model.parent_joint.len() {
        let Some(joint) = model.parent_joint[up.0] else {
            break;
        };
        match model.joint_links[joint.0] {
            Some((parent, _)) if model.joint_data[joint.0].kind == JointKind::Fixed => {
                welded_above.push(parent);
                up = parent;
            }
            _ => break,
        }
    }
    let hand = welded_below(model, &welded_above)
        .into_iter()
        .map(|(link, _)| link)
        .find(|&l| !fingers_at(l).is_empty());
    Some(Arm {
        base: root,
        tip,
        path,
        hand,
        fingers: hand.map(fingers_at).unwrap_or_default(),
        declared: true,
    })
}

#[cfg(test)]
mod tests {
    use super::finger_joint_name;

    #[test]
    fn gripper_joints_are_fingers_unless_they_turn_the_wrist() {
        assert!(finger_joint_name("jointGripper"));
        assert!(finger_joint_name("gripper_roller_joint"));
        assert!(finger_joint_name("gripper_controller_joint"));
        assert!(!finger_joint_name("LeftGripperYaw"));
        assert!(!finger_joint_name("gripper_roll_joint"));
        assert!(finger_joint_name("r_gripper_l_finger_joint"));
        assert!(finger_joint_name("hand_index_flex_1"));
    }
}
