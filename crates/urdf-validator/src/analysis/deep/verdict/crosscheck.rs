//! The cross-check: MuJoCo's gravity forces and centre of mass against ours.

use std::collections::{HashMap, HashSet};

use serde_json::Value;

use super::{vec3, Context, COM_SCALE_M, RELATIVE_TOLERANCE, TORQUE_SCALE};
use crate::analysis::deep::section::{DeepJoint, DeepSection};
use crate::diagnostics::{rules, Finding};
use crate::model::kinematics::{forward_kinematics, Data};
use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::Robot;

fn agrees(a: f64, b: f64) -> bool {
    (a - b).abs() <= RELATIVE_TOLERANCE * a.abs().max(b.abs()).max(TORQUE_SCALE)
}

/// Whether `joint` carries a link whose mass or frame MuJoCo changed.
fn carries_changed(model: &Model, joint: JointId, changed: &HashSet<LinkId>) -> bool {
    changed
        .iter()
        .any(|&link| model.joints_to_root(link).contains(&joint))
}

/// MuJoCo's gravity forces and COM against ours.
pub(super) fn crosscheck(
    cx: &Context,
    changed: &HashSet<LinkId>,
    section: &mut DeepSection,
    findings: &mut Vec<Finding>,
) {
    let (robot, model, physics) = (cx.robot, cx.model, cx.physics);
    let Some(results) = cx.reply["crosscheck"].as_array() else {
        return;
    };
    let configurations: HashMap<&str, &Value> = results
        .iter()
        .filter_map(|r| Some((r["label"].as_str()?, r)))
        .collect();
    let analysed = physics.statics.pose.as_str();
    let mut all_agree = true;
    let mut cache: HashMap<String, (Vec<f64>, Vec<Option<f64>>)> = HashMap::new();
    for (j, joint) in robot.joints.iter().enumerate() {
        let info = &model.joint_data[j];
        if model.joint_links[j].is_none() || !info.is_actuated() || model.mimic[j].is_some() {
            continue;
        }
        let worst = format!("worst:{}", joint.name.value);
        let label = if configurations.contains_key(worst.as_str()) {
            worst
        } else {
            analysed.to_string()
        };
        let Some(result) = configurations.get(label.as_str()) else {
            continue;
        };
        let (ours, theirs) = cache.entry(label.clone()).or_insert_with(|| {
            let q = if label == analysed {
                physics.q.clone()
            } else {
                let named = physics
                    .statics
                    .joints
                    .iter()
                    .find(|s| format!("worst:{}", s.name) == label)
                    .and_then(|s| s.worst_configuration.clone())
                    .unwrap_or_default();
                crate::analysis::deep::configuration(model, &physics.q, &named)
            };
            (
                crate::analysis::deep::our_torques(model, &q, cx.payload),
                folded(model, robot, &result["qfrc_bias"]),
            )
        });
        let (ours, theirs) = (ours[j], theirs[j]);
        let ok = theirs.is_some_and(|t| agrees(t, ours));
        let explained = !ok && carries_changed(model, JointId(j), changed);
        if !ok {
            all_agree = false;
        }
        if !ok && !explained {
            let span = joint.span;
            findings.push(Finding::new(
                &rules::SIMULATOR_DISAGREES,
                span,
                match theirs {
                    Some(t) => format!(
                        "MuJoCo's gravity force at joint '{}' is {t:.9} where statics computes {ours:.9} (|Δ| = {:.3e}, beyond {RELATIVE_TOLERANCE:e} relative) at the {} pose",
                        joint.name.value,
                        (t - ours).abs(),
                        label
                    ),
                    None => format!(
                        "MuJoCo has no joint '{}' (it dropped or renamed it): its gravity force cannot be compared",
                        joint.name.value
                    ),
                },
            ));
        }
        section.joints.push(DeepJoint {
            name: joint.name.value.clone(),
            mujoco_torque: theirs,
            our_torque: ours,
            abs_diff: theirs.map(|t| (t - ours).abs()),
            agrees: ok,
            configuration: label,
        });
    }
    // Centre of mass at the analysed pose, with the payload when there is one.
    if let Some(result) = configurations.get(analysed) {
        let theirs = vec3(&result["com"]);
        let ours =
            physics
                .statics
                .full_body_com
                .map(|c| match (cx.payload, physics.statics.total_mass) {
                    (Some((link, mass)), Some(total)) if total + mass > 0.0 => {
                        let mut data = Data::new(model);
                        forward_kinematics(model, &physics.q, &mut data);
                        let p = data.link_placement[link.0].translation.vector;
                        [
                            (c[0] * total + p.x * mass) / (total + mass),
                            (c[1] * total + p.y * mass) / (total + mass),
                            (c[2] * total + p.z * mass) / (total + mass),
                        ]
                    }
                    _ => c,
                });
        section.mujoco_com = theirs;
        section.our_com = ours;
        if let (Some(t), Some(o)) = (theirs, ours) {
            let diff =
                ((t[0] - o[0]).powi(2) + (t[1] - o[1]).powi(2) + (t[2] - o[2]).powi(2)).sqrt();
            section.com_abs_diff = Some(diff);
            let norm = (o[0] * o[0] + o[1] * o[1] + o[2] * o[2]).sqrt();
            if diff > RELATIVE_TOLERANCE * norm.max(COM_SCALE_M) {
                all_agree = false;
                if changed.is_empty() {
                    findings.push(Finding::new(
                        &rules::SIMULATOR_DISAGREES,
                        model.root.map_or(robot.span, |r| robot.links[r.0].span),
                        format!(
                            "MuJoCo's whole-body centre of mass is [{:.6}, {:.6}, {:.6}] m where statics computes [{:.6}, {:.6}, {:.6}] m ({:.3e} m apart)",
                            t[0], t[1], t[2], o[0], o[1], o[2], diff
                        ),
                    ));
                }
            }
        }
    }
    section.agreement = Some(all_agree);
}

/// MuJoCo's raw forces per joint (indexed like ours), followers folded into their independent leader.
fn folded(model: &Model, robot: &Robot, raw: &Value) -> Vec<Option<f64>> {
    let raw: Vec<Option<f64>> = robot
        .joints
        .iter()
        .map(|j| raw.get(j.name.value.as_str()).and_then(Value::as_f64))
        .collect();
    let mut out = raw.clone();
    for (j, value) in raw.iter().enumerate() {
        // A fixed joint can carry <mimic>: it has no force to fold (statics' raw torque is 0 there too).
        if model.mimic[j].is_none() || !model.joint_data[j].is_actuated() {
            continue;
        }
        let (leader, factor) =
            crate::analysis::statics::gravity::independent_leader(model, JointId(j));
        if leader.0 != j {
            out[leader.0] = match (out[leader.0], value) {
                (Some(l), Some(v)) => Some(l + factor * v),
                _ => None,
            };
        }
    }
    out
}
