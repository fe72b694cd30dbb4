//! The end of the drop test read by what touches the ground: which links the robot may rest on (its support
//! contacts), which other links rest on the ground at the end (the robot has fallen onto them), and whether
//! that agrees with the stability section's verdict.

use serde_json::Value;

use crate::analysis::stability::{is_named_caster_or_wheel, StabilitySection, SUPPORT_TOLERANCE};
use crate::diagnostics::Status;
use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::Robot;

/// What the robot may rest on and what it rests on at the end of the drop test.
pub(super) struct Ground {
    /// The support contacts, in the tree's order.
    pub supports: Vec<String>,
    /// Links touching the ground at the end, in the tree's order.
    pub at_end: Vec<String>,
    /// Those of `at_end` that are not supports.
    pub fallen_onto: Vec<LinkId>,
}

/// What tells a support contact, and a link brought down by a weak joint, apart from a fall.
pub(super) struct Supports<'a> {
    /// The stability section (its contact links and raised contacts).
    pub stability: &'a StabilitySection,
    /// `--contact-links`.
    pub declared: Option<&'a [String]>,
    /// The joints that sag in the drop test.
    pub sagging: &'a [JointId],
}

/// The support contacts of `robot` and the links the drop test (`drop`, the bridge's reply) ends on.
///
/// A support is what a robot is meant to stand on: the stability section's contact links and raised
/// contacts (wheels, casters, feet, or `--contact-links`, as found or declared there), any link declared
/// with `--contact-links`, any link named as a wheel or caster, and whatever touches the ground when the
/// robot is released (its lowest geometry within the support tolerance): an aerial robot's skids, a base
/// that sits on the floor. A link below a sagging joint that ends on the ground (an arm whose shoulder
/// gives way) is not a fall but that joint's sag (U746): it is in `at_end`, not in `fallen_onto`.
pub(super) fn ground(robot: &Robot, model: &Model, supports: &Supports, drop: &Value) -> Ground {
    let Supports {
        stability,
        declared,
        sagging,
    } = *supports;
    let named = |names: &mut dyn Iterator<Item = &str>| -> Vec<LinkId> {
        names.filter_map(|n| model.link(n)).collect()
    };
    let mut support = vec![false; robot.links.len()];
    let from_stability = named(
        &mut stability
            .contact_links
            .iter()
            .map(String::as_str)
            .chain(stability.raised_contacts.iter().map(|r| r.link.as_str()))
            .chain(declared.into_iter().flatten().map(String::as_str)),
    );
    let at_release = named(
        &mut drop["start_clearance_m"]
            .as_object()
            .into_iter()
            .flatten()
            .filter(|(_, z)| z.as_f64().is_some_and(|z| z <= SUPPORT_TOLERANCE))
            .map(|(link, _)| link.as_str()),
    );
    for link in from_stability.into_iter().chain(at_release) {
        support[link.0] = true;
    }
    for (index, slot) in support.iter_mut().enumerate() {
        *slot = *slot || is_named_caster_or_wheel(robot, LinkId(index));
    }
    let mut below_sag = vec![false; robot.links.len()];
    for &link in &model.topological_order {
        if let Some(joint) = model.parent_joint[link.0] {
            let parent = model.joint_links[joint.0].map(|(parent, _)| parent);
            below_sag[link.0] = sagging.contains(&joint) || parent.is_some_and(|p| below_sag[p.0]);
        }
    }
    let mut on_ground = vec![false; robot.links.len()];
    let end = named(
        &mut drop["ground_links_end"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(Value::as_str),
    );
    for link in end {
        on_ground[link.0] = true;
    }
    let name = |l: &LinkId| robot.links[l.0].name.value.clone();
    let in_order = |set: &[bool]| -> Vec<LinkId> {
        model
            .topological_order
            .iter()
            .copied()
            .filter(|l| set[l.0])
            .collect()
    };
    let fallen_onto = in_order(&on_ground)
        .into_iter()
        .filter(|l| !support[l.0] && !below_sag[l.0])
        .collect();
    Ground {
        supports: in_order(&support).iter().map(name).collect(),
        at_end: in_order(&on_ground).iter().map(name).collect(),
        fallen_onto,
    }
}

/// The stability section's verdict against the drop test's: `Some(true)` when both say the robot stands
/// or both say it falls, `Some(false)` with a sentence when they contradict each other, `None` when either
/// has no verdict (stability not applicable or not computed, a fixed base, an unstable simulation).
pub(super) fn against_stability(
    stability: &StabilitySection,
    fell: Option<&str>,
    stood: &str,
) -> Option<(bool, Option<String>)> {
    let tips = match stability.status {
        Status::Fail => true,
        Status::Pass => false,
        _ => return None,
    };
    let margin = stability.margin_mm?;
    let statics = if tips {
        format!(
            "statics finds the centre of mass {:.1} mm outside the support polygon (the robot tips over{})",
            -margin,
            stability
                .tip_direction
                .as_deref()
                .map_or(String::new(), |d| format!(" to the {d}"))
        )
    } else {
        format!("statics finds the centre of mass {margin:.1} mm inside the support polygon (the robot stands)")
    };
    match (tips, fell) {
        (true, Some(_)) | (false, None) => Some((true, None)),
        (true, None) => Some((
            false,
            Some(format!(
                "Statics and the drop test disagree: {statics}, but in MuJoCo the robot {stood}"
            )),
        )),
        (false, Some(how)) => Some((
            false,
            Some(format!(
                "Statics and the drop test disagree: {statics}, but in MuJoCo it falls: {how}"
            )),
        )),
    }
}
