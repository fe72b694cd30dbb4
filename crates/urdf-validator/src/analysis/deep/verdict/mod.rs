//! The bridge's reply read against our model: what MuJoCo refused or changed (found by comparing the
//! compiled model with ours, not by guessing), the cross-check of gravity forces and centre of mass, and
//! the drop test's verdict, each as findings with the element's span.

mod changes;
mod crosscheck;
mod drop_test;

use std::collections::HashSet;

use serde_json::Value;

use super::job::Job;
use super::section::DeepSection;
use crate::analysis::Physics;
use crate::diagnostics::{rules, Finding, Status};
use crate::model::{LinkId, Model};
use crate::urdf::robot::Robot;

use changes::{compare_model, named_element, refusals, Changes};
use crosscheck::crosscheck;
use drop_test::drop_test;

/// Relative agreement of a gravity force or the centre of mass.
pub const RELATIVE_TOLERANCE: f64 = 1e-6;
/// Torques are compared relative to at least this (N·m): the negligible torque of statics.
pub const TORQUE_SCALE: f64 = 1e-3;
/// The centre of mass is compared relative to at least this distance from the root (m).
pub const COM_SCALE_M: f64 = 1e-3;
/// A joint sags when it ends further than this from its target (rad; revolute and continuous).
pub const SAG_TOLERANCE_RAD: f64 = 0.05;
/// A prismatic joint sags when it ends further than this from its target (m).
pub const SAG_TOLERANCE_M: f64 = 0.01;
/// The robot has tipped over when its root link ends tilted more than this, degrees.
pub const TIP_OVER_DEG: f64 = 15.0;
/// It rocks when its tilt varies by more than this over the last second, degrees.
pub const ROCKING_DEG: f64 = 2.0;
/// It drifts when its centre of mass moves further than this horizontally, metres.
pub const DRIFT_M: f64 = 0.05;

/// What the verdicts read.
pub struct Context<'a> {
    /// The robot.
    pub robot: &'a Robot,
    /// Its tree.
    pub model: &'a Model,
    /// The analyses.
    pub physics: &'a Physics,
    /// The job that was run.
    pub job: &'a Job,
    /// The bridge's reply.
    pub reply: &'a Value,
    /// The payload in the MuJoCo model.
    pub payload: Option<(LinkId, f64)>,
    /// `--contact-links`, when declared.
    pub contact_links: Option<&'a [String]>,
    /// Root held in place.
    pub fixed_base: bool,
    /// `requested` or `automatic`.
    pub trigger: &'a str,
}

/// The section and its findings.
pub fn judge(cx: &Context) -> (DeepSection, Vec<Finding>) {
    let reply = cx.reply;
    let mut changes = Changes {
        list: Vec::new(),
        findings: Vec::new(),
        physics_changed: HashSet::new(),
    };
    for prepared in &cx.job.prepared {
        changes.push(
            &rules::SIMULATOR_CHANGES_MODEL,
            prepared.kind,
            &prepared.element,
            prepared.span,
            prepared.message.clone(),
        );
    }
    refusals(cx, &mut changes);
    let mut section = DeepSection {
        status: Status::Pass,
        trigger: cx.trigger.to_string(),
        simulator: "mujoco".to_string(),
        simulator_version: reply["mujoco_version"].as_str().map(str::to_string),
        python: reply["python"].as_str().map(str::to_string),
        reason: None,
        simulator_changes: Vec::new(),
        joints: Vec::new(),
        mujoco_com: None,
        our_com: None,
        com_abs_diff: None,
        agreement: None,
        tolerance: RELATIVE_TOLERANCE,
        drop_test: None,
    };
    if reply["ok"].as_bool() != Some(true) {
        let message = reply["message"].as_str().unwrap_or("no message");
        let span = named_element(cx, message).unwrap_or(cx.robot.span);
        changes.findings.push(
            Finding::new(
                &rules::SIMULATOR_CANNOT_LOAD,
                span,
                format!("MuJoCo cannot load this robot: {}", one_line(message)),
            )
            .with_help("the static report is complete; fix what MuJoCo names and run --deep again"),
        );
        section.status = Status::Fail;
        section.reason = Some(format!(
            "MuJoCo cannot load the file: {}",
            one_line(message)
        ));
        section.simulator_changes = changes.list;
        return (section, changes.findings);
    }
    compare_model(cx, &mut changes);
    let mut findings = Vec::new();
    crosscheck(cx, &changes.physics_changed, &mut section, &mut findings);
    section.drop_test = Some(drop_test(cx, &mut findings));
    section.simulator_changes = changes.list;
    findings.splice(0..0, changes.findings);
    section.status = findings
        .iter()
        .map(|f| match f.severity() {
            crate::diagnostics::Severity::Info => Status::Pass,
            crate::diagnostics::Severity::Warn => Status::Warn,
            _ => Status::Fail,
        })
        .max()
        .unwrap_or(Status::Pass)
        .max(
            section
                .drop_test
                .as_ref()
                .map_or(Status::Pass, |d| match d.status {
                    Status::Unknown => Status::Warn,
                    s => s,
                }),
        );
    (section, findings)
}

fn one_line(message: &str) -> String {
    message
        .trim_start_matches("Error: ")
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" — ")
}

fn vec3(value: &Value) -> Option<[f64; 3]> {
    let a = value.as_array()?;
    Some([
        a.first()?.as_f64()?,
        a.get(1)?.as_f64()?,
        a.get(2)?.as_f64()?,
    ])
}
