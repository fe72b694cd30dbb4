//! The drop test's verdict: whether the robot stands, sags, rocks, drifts or tips over on the ground.

use serde_json::Value;

use super::{Context, DRIFT_M, ROCKING_DEG, SAG_TOLERANCE_M, SAG_TOLERANCE_RAD, TIP_OVER_DEG};
use crate::analysis::deep::ground;
use crate::analysis::deep::job::{DROP_DURATION_S, DROP_TIMESTEP_S};
use crate::analysis::deep::section::{DropTest, SaggingJoint};
use crate::diagnostics::{rules, Finding, Status};
use crate::model::JointId;
use crate::urdf::robot::JointKind;

/// The drop test's verdict.
pub(super) fn drop_test(cx: &Context, findings: &mut Vec<Finding>) -> DropTest {
    let (robot, model) = (cx.robot, cx.model);
    let mut test = DropTest {
        status: Status::Pass,
        simulated_s: DROP_DURATION_S,
        timestep_s: DROP_TIMESTEP_S,
        base: if cx.fixed_base { "fixed" } else { "free" }.to_string(),
        max_tilt_deg: None,
        final_tilt_deg: None,
        com_drift_m: None,
        joints_sagging: Vec::new(),
        support_links: Vec::new(),
        ground_links: Vec::new(),
        fallen_onto: Vec::new(),
        agrees_with_stability: None,
        stability_disagreement: None,
        tilt_trace: Vec::new(),
        reason: None,
    };
    let root_span = model.root.map_or(robot.span, |r| robot.links[r.0].span);
    let drop = &cx.reply["drop"];
    if drop.is_null() {
        let why = cx.reply["drop_error"]
            .as_str()
            .unwrap_or("no result")
            .to_string();
        test.status = Status::Unknown;
        test.reason = Some(format!("the drop test could not run: {why}"));
        findings.push(Finding::new(
            &rules::DROP_TEST_UNSTEADY,
            root_span,
            format!("The MuJoCo drop test could not run: {why}"),
        ));
        return test;
    }
    test.simulated_s = drop["simulated_s"].as_f64().unwrap_or(DROP_DURATION_S);
    test.timestep_s = drop["timestep_s"].as_f64().unwrap_or(DROP_TIMESTEP_S);
    test.max_tilt_deg = drop["max_tilt_deg"].as_f64();
    test.final_tilt_deg = drop["final_tilt_deg"].as_f64();
    test.com_drift_m = drop["com_drift_m"].as_f64();
    let mut reasons = Vec::new();
    if let Some(unstable) = drop["unstable"].as_str() {
        test.status = Status::Unknown;
        reasons.push(unstable.to_string());
        findings.push(Finding::new(
            &rules::DROP_TEST_UNSTEADY,
            root_span,
            format!("The MuJoCo drop test became unstable: {unstable}; its numbers are not to be trusted"),
        ));
    }
    test.tilt_trace = tilt_trace(&drop["tilt_trace"]);
    for joint in drop["joints"].as_array().into_iter().flatten() {
        let Some(name) = joint["name"].as_str() else {
            continue;
        };
        let Some(id) = model.joint(name) else {
            continue;
        };
        let deviation = joint["final_deviation"].as_f64().unwrap_or(0.0);
        let info = &model.joint_data[id.0];
        let (tolerance, unit) = if info.kind == JointKind::Prismatic {
            (SAG_TOLERANCE_M, "m")
        } else {
            (SAG_TOLERANCE_RAD, "rad")
        };
        if deviation > tolerance {
            let effort = info.effort.filter(|e| *e > 0.0);
            test.joints_sagging.push(SaggingJoint {
                name: name.to_string(),
                deviation,
                declared_effort: effort,
            });
            let j = &robot.joints[id.0];
            let span = j
                .limit
                .as_ref()
                .and_then(|l| l.effort.as_ref().map(|e| e.span))
                .unwrap_or(j.span);
            findings.push(Finding::new(
                &rules::DROP_TEST_JOINT_SAGS,
                span,
                format!(
                    "Joint '{name}' cannot hold its pose in MuJoCo: after {:.1} s it is {deviation:.3} {unit} from its target (> {tolerance} {unit}) with its servo clamped to {}",
                    test.simulated_s,
                    effort.map_or("no limit".to_string(), |e| format!("its effort {e}")),
                ),
            ));
        }
    }
    // After the sagging joints: what rests on the ground below one of them is that joint's sag.
    let fell = (!cx.fixed_base)
        .then(|| fall(cx, drop, &mut test, findings))
        .flatten();
    if let Some(how) = &fell {
        test.status = Status::Fail;
        reasons.push(how.clone());
    }
    if !cx.fixed_base && test.ground_links.is_empty() && test.status != Status::Unknown {
        // Nothing landed: MuJoCo has no shape of the robot to collide (URDF visuals are dropped).
        let why = if cx.job.mjcf {
            "nothing of the robot touches the ground at the end: none of its geoms collides with the model's ground (contype/conaffinity), so it falls through"
        } else {
            "nothing of the robot touches the ground at the end: MuJoCo has no collision geometry of it to land on (it drops URDF visuals), so it falls through the floor"
        };
        test.status = Status::Unknown;
        reasons.push(why.to_string());
        findings.push(Finding::new(
            &rules::DROP_TEST_UNSTEADY,
            root_span,
            format!("The MuJoCo drop test cannot judge whether the robot stands: {why}"),
        ));
    }
    if !test.joints_sagging.is_empty() {
        test.status = Status::Fail;
        reasons.push(format!(
            "{} joint{} sag{}",
            test.joints_sagging.len(),
            if test.joints_sagging.len() == 1 {
                ""
            } else {
                "s"
            },
            if test.joints_sagging.len() == 1 {
                "s"
            } else {
                ""
            }
        ));
    }
    if test.status == Status::Pass {
        let rocking = drop["tilt_range_last_s_deg"].as_f64().unwrap_or(0.0);
        let drift = test.com_drift_m.unwrap_or(0.0);
        if rocking > ROCKING_DEG {
            test.status = Status::Warn;
            reasons.push(format!("rocks ({rocking:.1}° over the last second)"));
            findings.push(Finding::new(
                &rules::DROP_TEST_UNSTEADY,
                root_span,
                format!("In MuJoCo the robot rocks after the drop: its tilt still varies by {rocking:.1}° over the last second (> {ROCKING_DEG}°)"),
            ));
        }
        if drift > DRIFT_M {
            test.status = Status::Warn;
            reasons.push(format!("drifts {:.0} mm", drift * 1000.0));
            findings.push(Finding::new(
                &rules::DROP_TEST_UNSTEADY,
                root_span,
                format!(
                    "In MuJoCo the robot drifts after the drop: its centre of mass moves {:.0} mm horizontally in {:.1} s (> {:.0} mm)",
                    drift * 1000.0,
                    test.simulated_s,
                    DRIFT_M * 1000.0
                ),
            ));
        }
    }
    if !reasons.is_empty() {
        test.reason = Some(reasons.join("; "));
    }
    if !cx.fixed_base && test.status != Status::Unknown {
        let stood = format!(
            "stays on its support contacts, its root link {:.1}° from upright after {:.1} s",
            test.final_tilt_deg.unwrap_or(0.0),
            test.simulated_s
        );
        if let Some((agrees, sentence)) =
            ground::against_stability(&cx.physics.stability, fell.as_deref(), &stood)
        {
            test.agrees_with_stability = Some(agrees);
            test.stability_disagreement = sentence;
        }
    }
    test
}

/// Whether the robot fell, in a few words, with its U745 finding: a link that is not a support contact
/// (nor below a sagging joint) rests on the ground at the end (the finding points at the first such link),
/// or else the root link ends more than [`TIP_OVER_DEG`] from upright.
fn fall(
    cx: &Context,
    drop: &Value,
    test: &mut DropTest,
    findings: &mut Vec<Finding>,
) -> Option<String> {
    let (robot, model) = (cx.robot, cx.model);
    let sagging: Vec<JointId> = test
        .joints_sagging
        .iter()
        .filter_map(|j| model.joint(&j.name))
        .collect();
    let ground = ground::ground(
        robot,
        model,
        &ground::Supports {
            stability: &cx.physics.stability,
            declared: cx.contact_links,
            sagging: &sagging,
        },
        drop,
    );
    test.support_links = ground.supports;
    test.ground_links = ground.at_end;
    test.fallen_onto = ground
        .fallen_onto
        .iter()
        .map(|l| robot.links[l.0].name.value.clone())
        .collect();
    if test.ground_links.is_empty() {
        return None; // it never landed: no verdict (the caller says so)
    }
    let final_tilt = test.final_tilt_deg.unwrap_or(0.0);
    let dropped = format!(
        "dropped from {} cm onto flat ground with its joints held",
        crate::analysis::deep::job::DROP_HEIGHT_M * 100.0
    );
    if let Some(first) = ground.fallen_onto.first() {
        let names = test
            .fallen_onto
            .iter()
            .map(|n| format!("'{n}'"))
            .collect::<Vec<_>>()
            .join(", ");
        let which = if test.fallen_onto.len() == 1 {
            "which is not a support contact"
        } else {
            "which are not support contacts"
        };
        let supports = if test.support_links.is_empty() {
            "it has none".to_string()
        } else {
            test.support_links.join(", ")
        };
        findings.push(Finding::new(
            &rules::DROP_TEST_TIPS_OVER,
            robot.links[first.0].span,
            format!(
                "In MuJoCo the robot falls onto {names}: {dropped}, after {:.1} s it rests on {names}, {which} (support contacts: {supports}), its root link {final_tilt:.1}° from upright",
                test.simulated_s,
            ),
        ));
        return Some(format!(
            "falls onto {} ({final_tilt:.1}° from upright)",
            test.fallen_onto.join(", ")
        ));
    }
    if final_tilt > TIP_OVER_DEG {
        findings.push(Finding::new(
            &rules::DROP_TEST_TIPS_OVER,
            model.root.map_or(robot.span, |r| robot.links[r.0].span),
            format!(
                "In MuJoCo the robot tips over: {dropped}, its root link ends {final_tilt:.1}° from upright after {:.1} s (> {TIP_OVER_DEG}°)",
                test.simulated_s
            ),
        ));
        return Some(format!("tips over ({final_tilt:.1}° from upright)"));
    }
    None
}

/// The bridge's `[[t, degrees]]` samples, rounded to the microsecond and the millidegree.
fn tilt_trace(trace: &Value) -> Vec<[f64; 2]> {
    let round = |v: f64, per_unit: f64| (v * per_unit).round() / per_unit;
    trace
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|point| {
            let t = point.get(0)?.as_f64()?;
            let tilt = point.get(1)?.as_f64()?;
            Some([round(t, 1e6), round(tilt, 1e3)])
        })
        .take(crate::analysis::deep::job::TILT_TRACE_POINTS)
        .collect()
}
