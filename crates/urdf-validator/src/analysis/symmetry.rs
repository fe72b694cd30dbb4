//! Left/right symmetry: mirrored pairs of chains found by structure, compared link by link and joint by
//! joint.
//!
//! A pair starts at two sibling joints (same parent link, same type) whose origins mirror each other across
//! the parent frame's x–z plane (REP 103: y points left): equal x and z, opposite y. Below them the two
//! subtrees are walked together, child joints matched by type and distance from their parent (frames of
//! mirrored parts are often flipped, so components are not compared), names with left/right swapped
//! breaking ties. Names are only a hint: they never make a pair on their own.
//!
//! Each matched link pair compares mass and principal moments of inertia, each matched joint pair its
//! position limits (equal, or mirrored: `[l, u]` against `[−u, −l]`), effort and velocity (a pair coupled to
//! one drive, by mimic or an MJCF joint equality, may declare them on one side only). A difference
//! above the tolerances below is a U770 finding naming the pair and the difference; a true twin gives none.

use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::Serialize;

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::diagnostics::Status;
use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::{JointKind, Link, Robot};

/// Masses, principal moments of inertia, efforts and velocities of a mirrored pair may differ by this
/// fraction of the larger value.
pub const RELATIVE_TOLERANCE: f64 = 0.10;
/// Position limits of a mirrored pair may differ by this much (rad or m), plus 1 % of the range.
pub const LIMIT_TOLERANCE: f64 = 0.01;
/// Origins mirror each other to within this distance (m), plus 1 % of their distance from the parent.
const POSITION_TOLERANCE: f64 = 0.001;
/// Origins closer than this to the mirror plane are on it, not beside it (m).
const OFF_PLANE: f64 = 0.005;

/// The `symmetry` section: the mirrored pairs found and how they compare.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct SymmetrySection {
    /// WARN when a pair differs beyond the tolerances, PASS when every pair agrees, N/A when no mirrored
    /// pair was found.
    pub status: Status,
    /// The tolerances applied.
    pub tolerances: String,
    /// One entry per mirrored pair of chains.
    pub pairs: Vec<MirroredPair>,
}

/// Two mirrored chains.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct MirroredPair {
    /// The link both chains hang from.
    pub parent: String,
    /// The two sibling joints that start the chains (in document order).
    pub joints: [String; 2],
    /// Link pairs compared (the chains' links, matched).
    pub links_compared: usize,
    /// Joint pairs compared.
    pub joints_compared: usize,
    /// PASS, or WARN when something differs.
    pub status: Status,
    /// What differs, one entry per element pair: "links 'a' / 'b': mass 1.00 kg vs 2.00 kg (50 % apart)".
    pub differences: Vec<String>,
}

/// Find the mirrored pairs of `robot` and compare them.
pub fn analyse(robot: &Robot, model: &Model) -> (SymmetrySection, Vec<Finding>) {
    let mut pairs = Vec::new();
    let mut findings = Vec::new();
    for (parent, joints) in model.child_joints.iter().enumerate() {
        for (first, second) in sibling_pairs(robot, model, joints) {
            let mut pair = MirroredPair {
                parent: robot.links[parent].name.value.clone(),
                joints: [first, second].map(|j| robot.joints[j.0].name.value.clone()),
                links_compared: 0,
                joints_compared: 0,
                status: Status::Pass,
                differences: Vec::new(),
            };
            compare_chains(robot, model, (first, second), &mut pair, &mut findings);
            if pair.links_compared + pair.joints_compared > 0 {
                if !pair.differences.is_empty() {
                    pair.status = Status::Warn;
                }
                pairs.push(pair);
            }
        }
    }
    let status = pairs
        .iter()
        .map(|p| p.status)
        .max()
        .unwrap_or(Status::NotApplicable);
    let section = SymmetrySection {
        status,
        tolerances: format!(
            "mass, principal inertia, effort, velocity within {:.0} %; limits within {LIMIT_TOLERANCE} + 1 % of the range",
            RELATIVE_TOLERANCE * 100.0
        ),
        pairs,
    };
    (section, findings)
}

/// The sibling joints among `joints` whose origins mirror each other across the parent's x–z plane, each
/// joint in one pair at most, closest mirror first.
fn sibling_pairs(robot: &Robot, model: &Model, joints: &[JointId]) -> Vec<(JointId, JointId)> {
    let mut candidates = Vec::new();
    for (i, &a) in joints.iter().enumerate() {
        for &b in &joints[i + 1..] {
            let (pa, pb) = (origin(model, a), origin(model, b));
            let tolerance = POSITION_TOLERANCE + 0.01 * pa.norm().max(pb.norm());
            let mirrored = Vector3::new(pb.x, -pb.y, pb.z);
            let error = (pa - mirrored).norm();
            if pa.y.abs() > OFF_PLANE
                && error <= tolerance
                && model.joint_data[a.0].kind == model.joint_data[b.0].kind
                && !names_deny(robot, a, b)
            {
                candidates.push((error, !names_mirror(robot, a, b), a, b));
            }
        }
    }
    candidates.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    let mut used = Vec::new();
    let mut pairs = Vec::new();
    for (_, _, a, b) in candidates {
        if !used.contains(&a) && !used.contains(&b) {
            used.extend([a, b]);
            pairs.push((a, b));
        }
    }
    pairs
}

/// Walk two mirrored chains together from their first joints, comparing every matched joint and link.
fn compare_chains(
    robot: &Robot,
    model: &Model,
    start: (JointId, JointId),
    pair: &mut MirroredPair,
    findings: &mut Vec<Finding>,
) {
    let mut stack = vec![start];
    while let Some((a, b)) = stack.pop() {
        let (Some((_, link_a)), Some((_, link_b))) =
            (model.joint_links[a.0], model.joint_links[b.0])
        else {
            continue;
        };
        if model.joint_data[a.0].kind != JointKind::Fixed {
            pair.joints_compared += 1;
            report(
                robot,
                pair,
                findings,
                Element::Joints(a, b),
                joint_differences(robot, model, a, b),
            );
        }
        if has_mass_data(&robot.links[link_a.0]) || has_mass_data(&robot.links[link_b.0]) {
            pair.links_compared += 1;
            let differences = link_differences(&robot.links[link_a.0], &robot.links[link_b.0]);
            report(
                robot,
                pair,
                findings,
                Element::Links(link_a, link_b),
                differences,
            );
        }
        stack.extend(matched_children(robot, model, link_a, link_b));
    }
}

/// Which pair of elements a difference is about.
enum Element {
    Links(LinkId, LinkId),
    Joints(JointId, JointId),
}

/// Record the differences of one element pair: in the pair, and as one finding at the second element.
fn report(
    robot: &Robot,
    pair: &mut MirroredPair,
    findings: &mut Vec<Finding>,
    element: Element,
    differences: Vec<String>,
) {
    if differences.is_empty() {
        return;
    }
    let (kind, names, span) = match element {
        Element::Links(a, b) => {
            let link = &robot.links[b.0];
            let span = link
                .inertial
                .as_ref()
                .map_or(link.span, |inertial| inertial.span);
            (
                "links",
                [a.0, b.0].map(|l| &robot.links[l].name.value),
                span,
            )
        }
        Element::Joints(a, b) => {
            let joint = &robot.joints[b.0];
            let span = joint.limit.as_ref().map_or(joint.span, |limit| limit.span);
            (
                "joints",
                [a.0, b.0].map(|j| &robot.joints[j].name.value),
                span,
            )
        }
    };
    let text = format!(
        "{kind} '{}' / '{}': {}",
        names[0],
        names[1],
        differences.join("; ")
    );
    findings.push(Finding::new(
        &rules::MIRRORED_PAIR_DIFFERS,
        span,
        format!("Mirrored {text}"),
    ));
    pair.differences.push(text);
}

/// The child joints of two mirrored links matched pairwise: same type, same distance from the parent
/// (within tolerance), left/right names preferred, then the closest distance.
fn matched_children(
    robot: &Robot,
    model: &Model,
    link_a: LinkId,
    link_b: LinkId,
) -> Vec<(JointId, JointId)> {
    let mut taken = vec![false; model.child_joints[link_b.0].len()];
    let mut matched = Vec::new();
    for &a in &model.child_joints[link_a.0] {
        let distance_a = origin(model, a).norm();
        let best = model.child_joints[link_b.0]
            .iter()
            .enumerate()
            .filter(|(k, &b)| {
                let gap = (origin(model, b).norm() - distance_a).abs();
                !taken[*k]
                    && model.joint_data[a.0].kind == model.joint_data[b.0].kind
                    && gap <= POSITION_TOLERANCE + 0.01 * distance_a
            })
            .min_by(|(_, &x), (_, &y)| {
                let gap = |j: JointId| (origin(model, j).norm() - distance_a).abs();
                (!names_mirror(robot, a, x))
                    .cmp(&!names_mirror(robot, a, y))
                    .then(gap(x).total_cmp(&gap(y)))
            });
        if let Some((k, &b)) = best {
            taken[k] = true;
            matched.push((a, b));
        }
    }
    matched
}

fn origin(model: &Model, joint: JointId) -> Vector3<f64> {
    model.joint_data[joint.0].placement.translation.vector
}

/// Whether the two joints' names are the same with one left/right marker swapped (`left`/`right`, `l_`/`r_`,
/// `_l`/`_r`, …).
fn names_mirror(robot: &Robot, a: JointId, b: JointId) -> bool {
    let (a, b) = (&robot.joints[a.0].name.value, &robot.joints[b.0].name.value);
    side_swaps(a).any(|swapped| swapped == *b)
}

/// Whether the names say the two joints are not a left/right pair: both carry side markers, yet no one swap
/// turns one name into the other (`gripper_left_joint` and `gripper_left_motor_joint`).
fn names_deny(robot: &Robot, a: JointId, b: JointId) -> bool {
    let marked = |j: JointId| side_swaps(&robot.joints[j.0].name.value).next().is_some();
    marked(a) && marked(b) && !names_mirror(robot, a, b)
}

/// `name` with one left/right marker swapped, for each marker it has: words anywhere (`FrontLeftHip`), the
/// one-letter markers only as whole words (`l_arm`, `leg_l_knee`).
fn side_swaps(name: &str) -> impl Iterator<Item = String> + '_ {
    const PAIRS: [(&str, &str); 10] = [
        ("left", "right"),
        ("right", "left"),
        ("Left", "Right"),
        ("Right", "Left"),
        ("LEFT", "RIGHT"),
        ("RIGHT", "LEFT"),
        ("l", "r"),
        ("r", "l"),
        ("L", "R"),
        ("R", "L"),
    ];
    let whole_word = move |at: usize, len: usize| {
        let boundary = |c: Option<char>| c.is_none_or(|c| !c.is_ascii_alphanumeric());
        boundary(name[..at].chars().next_back()) && boundary(name[at + len..].chars().next())
    };
    PAIRS.into_iter().flat_map(move |(from, to)| {
        name.match_indices(from)
            .filter(move |(at, _)| from.len() > 1 || whole_word(*at, from.len()))
            .map(move |(at, _)| format!("{}{to}{}", &name[..at], &name[at + from.len()..]))
    })
}

fn has_mass_data(link: &Link) -> bool {
    link.inertial.as_ref().is_some_and(|i| i.mass.is_some())
}

/// Mass and principal moments of two mirrored links, beyond the tolerance.
fn link_differences(a: &Link, b: &Link) -> Vec<String> {
    let mass = |link: &Link| {
        link.inertial
            .as_ref()
            .and_then(|i| i.mass.as_ref())
            .map(|m| m.value)
    };
    let mut differences = Vec::new();
    match (mass(a), mass(b)) {
        (Some(ma), Some(mb)) => {
            if let Some(apart) = apart(ma, mb) {
                differences.push(format!("mass {ma} kg vs {mb} kg ({apart})"));
            }
        }
        (Some(_), None) | (None, Some(_)) => {
            differences.push("mass declared on one side only".to_string());
        }
        (None, None) => {}
    }
    if let (Some(ia), Some(ib)) = (principal_moments(a), principal_moments(b)) {
        let largest = ia[2].max(ib[2]);
        let worst = (0..3).map(|k| (ia[k] - ib[k]).abs()).fold(0.0, f64::max);
        if largest > 0.0 && worst > RELATIVE_TOLERANCE * largest {
            let show = |m: [f64; 3]| format!("{:.4} {:.4} {:.4}", m[0], m[1], m[2]);
            differences.push(format!(
                "principal inertias {} vs {} kg·m² ({:.0} % of the largest apart)",
                show(ia),
                show(ib),
                100.0 * worst / largest
            ));
        }
    }
    differences
}

/// The principal moments of a link's inertia tensor (frame-independent, so flipped frames compare).
fn principal_moments(link: &Link) -> Option<[f64; 3]> {
    link.inertial
        .as_ref()?
        .inertia
        .as_ref()?
        .principal_moments()
}

/// Limits, effort and velocity of two mirrored joints, beyond the tolerances. Two joints coupled to one
/// drive (one mimics the other, or both the same leader: a gripper's fingers) may declare an effort or
/// velocity on the driven side only: the other moves through the coupling.
fn joint_differences(robot: &Robot, model: &Model, a: JointId, b: JointId) -> Vec<String> {
    let (da, db) = (&model.joint_data[a.0], &model.joint_data[b.0]);
    let coupled = model.independent_leader[a.0].0 == model.independent_leader[b.0].0;
    let mut differences = Vec::new();
    if let (Some(la), Some(ua), Some(lb), Some(ub)) = (da.lower, da.upper, db.lower, db.upper) {
        let tolerance = LIMIT_TOLERANCE + 0.01 * (ua - la).abs().max((ub - lb).abs());
        let close = |x: f64, y: f64| (x - y).abs() <= tolerance;
        let same = close(la, lb) && close(ua, ub);
        let mirrored = close(la, -ub) && close(ua, -lb);
        if !same && !mirrored {
            differences.push(format!("limits [{la}, {ua}] vs [{lb}, {ub}]"));
        }
    }
    let velocity = |j: JointId| {
        robot.joints[j.0]
            .limit
            .as_ref()
            .and_then(|l| l.velocity.as_ref())
            .map(|v| v.value)
            .filter(|v| v.is_finite())
    };
    for (what, x, y) in [
        ("effort", da.effort, db.effort),
        ("velocity", velocity(a), velocity(b)),
    ] {
        match (x, y) {
            (Some(x), Some(y)) => {
                if let Some(apart) = apart(x, y) {
                    differences.push(format!("{what} {x} vs {y} ({apart})"));
                }
            }
            (Some(_), None) | (None, Some(_)) if !coupled => {
                differences.push(format!("{what} declared on one side only"));
            }
            (Some(_), None) | (None, Some(_)) => {}
            (None, None) => {}
        }
    }
    differences
}

/// "50 % apart" when two magnitudes differ by more than the tolerance of the larger.
fn apart(x: f64, y: f64) -> Option<String> {
    let larger = x.abs().max(y.abs());
    let gap = (x - y).abs();
    (larger > 0.0 && gap > RELATIVE_TOLERANCE * larger)
        .then(|| format!("{:.0} % apart", 100.0 * gap / larger))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn side_markers_swap_as_words_or_letters() {
        let swaps = |name: &str| side_swaps(name).collect::<Vec<_>>();
        assert_eq!(swaps("left_wheel_joint"), ["right_wheel_joint"]);
        assert_eq!(swaps("r_shoulder_pan"), ["l_shoulder_pan"]);
        assert_eq!(swaps("leg_l_knee"), ["leg_r_knee"]);
        assert_eq!(swaps("FrontLeftHip"), ["FrontRightHip"]);
        assert_eq!(
            swaps("r_gripper_l_finger_joint"),
            ["r_gripper_r_finger_joint", "l_gripper_l_finger_joint"]
        );
        assert!(swaps("elbow").is_empty(), "no whole-word l or r");
    }

    #[test]
    fn magnitudes_are_apart_beyond_ten_percent_of_the_larger() {
        assert_eq!(apart(1.0, 1.1), None);
        assert_eq!(apart(1.0, 2.0).as_deref(), Some("50 % apart"));
        assert_eq!(apart(0.0, 0.0), None);
    }
}
