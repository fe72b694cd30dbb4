//! Statics: total mass and centre of mass, and the gravity torque each actuated joint must hold, compared
//! with its declared effort; payloads and the payload capacity.
//!
//! Gravity torque of joint j (axis `a` through `o`, subtree mass `M` with centre `C`):
//! revolute/continuous `τ = −a · ((C − o) × M g)`, prismatic `f = −a · (M g)` — the effort the motor must
//! supply to hold the pose, Pinocchio's `computeGeneralizedGravity` for a fixed base. A mimic follower's
//! torque is folded into its leader (`τ_leader += multiplier · τ_follower`, by virtual work).

use nalgebra::Vector3;

use crate::model::kinematics::{forward_kinematics, Configuration, Data, LinkMass};
use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::{JointKind, STANDARD_GRAVITY};

/// The standard gravity in the root frame, m/s² ([`STANDARD_GRAVITY`]); a model may declare its own
/// ([`Model::gravity`]).
pub const GRAVITY: Vector3<f64> = Vector3::new(
    STANDARD_GRAVITY[0],
    STANDARD_GRAVITY[1],
    STANDARD_GRAVITY[2],
);

/// Torques below this (N·m or N) are negligible: no margin is computed.
pub const NEGLIGIBLE_TORQUE: f64 = 1e-3;

/// Margin at or above which a joint passes.
pub const PASS_MARGIN: f64 = 1.5;

/// The smallest effort limit that holds `torque` with the PASS margin.
pub fn effort_needed(torque: f64) -> f64 {
    PASS_MARGIN * torque.abs()
}

/// `value` rounded up to the hundredth: how an effort to declare is written (rounded to the nearest, it
/// could fall just short of the margin it is meant to give).
pub fn round_up_to_hundredth(value: f64) -> f64 {
    (value * 100.0).ceil() / 100.0
}

/// Mass carried by each link's subtree, at one configuration.
#[derive(Clone, Debug)]
pub struct SubtreeSums {
    /// Declared mass of the subtree, kg.
    pub mass: Vec<f64>,
    /// Σ m·c over the subtree (world), kg·m.
    pub moment: Vec<Vector3<f64>>,
    /// Links in the subtree with geometry but no usable mass.
    pub unknown: Vec<usize>,
    /// The mass of the subtree whose weight the motors hold (what `gravcomp` leaves), and its Σ m·c;
    /// empty when the model compensates no body (then it is `mass` and `moment`).
    pub held: Vec<(f64, Vector3<f64>)>,
}

/// Scratch for one statics evaluation: kinematics plus subtree sums.
#[derive(Clone, Debug)]
pub struct StaticsData {
    /// Forward kinematics.
    pub kinematics: Data,
    /// Subtree sums.
    pub sums: SubtreeSums,
    /// Raw gravity torque per joint (0 for joints that are not actuated), before mimic folding.
    pub raw_torque: Vec<f64>,
    /// Gravity torque per joint with followers folded into their independent leader.
    pub torque: Vec<f64>,
}

impl StaticsData {
    /// Scratch sized for `model`.
    pub fn new(model: &Model) -> Self {
        let links = model.parent_joint.len();
        let joints = model.joint_data.len();
        StaticsData {
            kinematics: Data::new(model),
            sums: SubtreeSums {
                mass: vec![0.0; links],
                moment: vec![Vector3::zeros(); links],
                unknown: vec![0; links],
                held: if model.weight_carried.is_empty() {
                    Vec::new()
                } else {
                    vec![(0.0, Vector3::zeros()); links]
                },
            },
            raw_torque: vec![0.0; joints],
            torque: vec![0.0; joints],
        }
    }
}

/// Forward kinematics, subtree sums and gravity torques at `q` (mimic relations already applied).
pub fn evaluate(model: &Model, q: &[f64], out: &mut StaticsData) {
    forward_kinematics(model, q, &mut out.kinematics);
    subtree_sums(model, &out.kinematics, &mut out.sums);
    for (j, torque) in out.raw_torque.iter_mut().enumerate() {
        *torque = joint_torque(model, &out.kinematics, &out.sums, JointId(j));
    }
    fold_mimic(model, &out.raw_torque, &mut out.torque);
}

fn subtree_sums(model: &Model, data: &Data, sums: &mut SubtreeSums) {
    for &link in &model.topological_order {
        let (mass, moment, unknown) = match model.link_mass[link.0] {
            LinkMass::Declared { mass, com } => {
                let centre = data.link_placement[link.0]
                    .transform_point(&com.into())
                    .coords;
                (mass, centre * mass, 0)
            }
            LinkMass::Massless => (0.0, Vector3::zeros(), 0),
            LinkMass::Unknown => (0.0, Vector3::zeros(), 1),
        };
        sums.mass[link.0] = mass;
        sums.moment[link.0] = moment;
        sums.unknown[link.0] = unknown;
        if let Some(held) = sums.held.get_mut(link.0) {
            let share = 1.0 - model.weight_carried[link.0];
            *held = (share * mass, share * moment);
        }
    }
    for &link in model.topological_order.iter().rev() {
        let Some((parent, _)) = model.parent_joint[link.0].and_then(|j| model.joint_links[j.0])
        else {
            continue;
        };
        sums.mass[parent.0] += sums.mass[link.0];
        let moment = sums.moment[link.0];
        sums.moment[parent.0] += moment;
        sums.unknown[parent.0] += sums.unknown[link.0];
        if let Some(&(mass, moment)) = sums.held.get(link.0) {
            sums.held[parent.0].0 += mass;
            sums.held[parent.0].1 += moment;
        }
    }
}

/// World axis and origin of an actuated joint in the tree.
fn joint_axis(model: &Model, data: &Data, joint: JointId) -> Option<(Vector3<f64>, Vector3<f64>)> {
    let info = &model.joint_data[joint.0];
    if !info.is_actuated() {
        return None;
    }
    let frame = model.joint_frame(data, joint)?;
    Some((frame.rotation * info.axis, frame.translation.vector))
}

fn joint_torque(model: &Model, data: &Data, sums: &SubtreeSums, joint: JointId) -> f64 {
    let (Some((axis, origin)), Some((_, child))) =
        (joint_axis(model, data, joint), model.joint_links[joint.0])
    else {
        return 0.0;
    };
    let (mass, moment) = sums
        .held
        .get(child.0)
        .copied()
        .unwrap_or((sums.mass[child.0], sums.moment[child.0]));
    match model.joint_data[joint.0].kind {
        JointKind::Prismatic => -axis.dot(&(model.gravity * mass)),
        _ => -axis.dot(&(moment - origin * mass).cross(&model.gravity)),
    }
}

/// The independent joint a joint's motion comes from, and d q_joint / d q_leader (precomputed by
/// [`Model::build`]).
pub fn independent_leader(model: &Model, joint: JointId) -> (JointId, f64) {
    model
        .independent_leader
        .get(joint.0)
        .copied()
        .unwrap_or((joint, 1.0))
}

/// `folded[leader] = raw[leader] + Σ factor · raw[follower]`; followers keep their raw value.
fn fold_mimic(model: &Model, raw: &[f64], folded: &mut [f64]) {
    folded.copy_from_slice(raw);
    for (joint, torque) in raw.iter().enumerate() {
        if model.mimic[joint].is_some() {
            let (leader, factor) = independent_leader(model, JointId(joint));
            if leader.0 != joint {
                folded[leader.0] += factor * torque;
            }
        }
    }
}

/// Torque per kilogram of payload at `link`'s origin, per joint, folded like gravity torques.
pub fn payload_torque_per_kg(model: &Model, data: &Data, link: LinkId) -> Vec<f64> {
    let point = data.link_placement[link.0].translation.vector;
    let mut raw = vec![0.0; model.joint_data.len()];
    let mut current = link;
    for _ in 0..model.parent_joint.len() {
        let Some(joint) = model.parent_joint[current.0] else {
            break;
        };
        if let Some((axis, origin)) = joint_axis(model, data, joint) {
            raw[joint.0] = match model.joint_data[joint.0].kind {
                JointKind::Prismatic => -axis.dot(&model.gravity),
                _ => -axis.dot(&(point - origin).cross(&model.gravity)),
            };
        }
        match model.joint_links[joint.0] {
            Some((parent, _)) => current = parent,
            None => break,
        }
    }
    let mut folded = vec![0.0; raw.len()];
    fold_mimic(model, &raw, &mut folded);
    folded
}

/// The link a payload goes to by default: the end of the longest chain of independent actuated joints
/// (ties: the deeper link, then document order).
pub fn default_payload_link(model: &Model) -> Option<LinkId> {
    let mut depth = vec![(0usize, 0usize); model.parent_joint.len()];
    for &link in &model.topological_order {
        if let Some(joint) = model.parent_joint[link.0] {
            if let Some((parent, _)) = model.joint_links[joint.0] {
                let actuated =
                    model.joint_data[joint.0].is_actuated() && model.mimic[joint.0].is_none();
                let (a, d) = depth[parent.0];
                depth[link.0] = (a + usize::from(actuated), d + 1);
            }
        }
    }
    model
        .topological_order
        .iter()
        .copied()
        .filter(|l| depth[l.0].0 > 0)
        .max_by(|a, b| depth[a.0].cmp(&depth[b.0]).then(b.0.cmp(&a.0)))
}

/// Total declared mass and its centre (world) over the main tree, at the configuration of `data`.
pub fn mass_and_com(model: &Model, data: &StaticsData) -> (f64, Option<Vector3<f64>>) {
    let Some(root) = model.root else {
        return (0.0, None);
    };
    let mass = data.sums.mass[root.0];
    (mass, (mass > 0.0).then(|| data.sums.moment[root.0] / mass))
}

/// The largest payload (kg, ≥ 0) keeping `|τ0 + m·t| ≤ effort / PASS_MARGIN` on every constrained joint.
/// `constraints` holds (τ0, t, effort). `None` when the unloaded robot already violates a constraint.
pub fn payload_capacity(constraints: &[(f64, f64, f64)]) -> Option<f64> {
    let mut capacity = f64::INFINITY;
    for &(torque, per_kg, effort) in constraints {
        let bound = effort / PASS_MARGIN;
        if torque.abs() > bound {
            return None;
        }
        if per_kg.abs() < 1e-12 {
            continue;
        }
        // τ0 + m·t stays in [−bound, bound]; the side it moves towards limits m.
        let limit = if per_kg > 0.0 {
            (bound - torque) / per_kg
        } else {
            (-bound - torque) / per_kg
        };
        capacity = capacity.min(limit.max(0.0));
    }
    Some(capacity)
}

/// Seeded sampling for the worst pose: per joint, the configuration with the largest |folded torque|
/// (payload included).
pub fn worst_configurations(
    model: &Model,
    reference: &Configuration,
    samples: usize,
    seed: u64,
    payload: Option<(LinkId, f64)>,
) -> Vec<Option<(f64, Configuration)>> {
    let mut best: Vec<Option<(f64, Configuration)>> = vec![None; model.joint_data.len()];
    let mut sampler = crate::analysis::pose::ConfigurationSampler::new(model, seed);
    let mut q = reference.clone();
    let mut data = StaticsData::new(model);
    for _ in 0..samples {
        sampler.sample_into(&mut q);
        evaluate(model, &q, &mut data);
        let per_kg = payload.map(|(link, _)| payload_torque_per_kg(model, &data.kinematics, link));
        for (j, slot) in best.iter_mut().enumerate() {
            if !model.joint_data[j].is_actuated() || model.mimic[j].is_some() {
                continue;
            }
            let torque = data.torque[j]
                + per_kg
                    .as_ref()
                    .zip(payload)
                    .map_or(0.0, |(t, (_, m))| t[j] * m);
            if slot
                .as_ref()
                .is_none_or(|(best, _)| torque.abs() > best.abs())
            {
                *slot = Some((torque, q.clone()));
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn capacity_is_the_tightest_joint() {
        // Joint A: 10 N·m now, +5 per kg, effort 30 → bound 20 → 2 kg. Joint B: −4, −1 per kg, effort 15 → 6 kg.
        let capacity = payload_capacity(&[(10.0, 5.0, 30.0), (-4.0, -1.0, 15.0)]).unwrap();
        assert!((capacity - 2.0).abs() < 1e-12);
        assert!(
            payload_capacity(&[(25.0, 1.0, 30.0)]).is_none(),
            "already over 30/1.5 unloaded"
        );
        assert_eq!(payload_capacity(&[(1.0, 0.0, 30.0)]), Some(f64::INFINITY));
    }
}
