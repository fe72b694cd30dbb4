//! Joint checks: limits, effort and velocity, axes, joint types that statics cannot move.

use crate::diagnostics::finding::Finding;
use crate::diagnostics::fix::{self, Edit, Fix};
use crate::diagnostics::rules;
use crate::input::Format;
use crate::model::{JointId, Model};
use crate::urdf::robot::{Joint, JointKind, Robot};

/// How far an axis length may stray from 1 before it counts as non-unit.
const AXIS_UNIT_TOLERANCE: f64 = 1e-3;

pub(super) fn check(robot: &Robot, model: &Model) -> Vec<Finding> {
    let mut findings = Vec::new();
    for (i, joint) in robot.joints.iter().enumerate() {
        let Some(kind) = &joint.kind else { continue };
        let owner = format!("Joint '{}'", joint.name.value);
        match kind.value {
            JointKind::Fixed => continue,
            JointKind::Floating | JointKind::Planar => {
                findings.push(Finding::new(
                    &rules::FLOATING_JOINT,
                    kind.span,
                    format!(
                        "{owner} is {}: statics holds it at identity",
                        kind.value.as_str()
                    ),
                ));
                if kind.value == JointKind::Floating {
                    continue;
                }
            }
            _ => {}
        }
        check_axis(joint, &owner, &mut findings);
        if kind.value.is_actuated() {
            let follower = model.mimic[JointId(i).0].is_some() || joint.mimic.is_some();
            check_limit(
                joint,
                kind.value,
                &owner,
                follower,
                robot.format,
                &mut findings,
            );
        }
    }
    findings
}

fn check_axis(joint: &Joint, owner: &str, findings: &mut Vec<Finding>) {
    let Some(axis) = &joint.axis else { return };
    let norm = axis.value.iter().map(|v| v * v).sum::<f64>().sqrt();
    if !norm.is_finite() {
        return; // Reported by the parser as non-finite.
    }
    if norm < 1e-9 {
        findings.push(Finding::new(
            &rules::ZERO_AXIS,
            axis.span,
            format!("{owner} has a zero axis"),
        ));
    } else if (norm - 1.0).abs() > AXIS_UNIT_TOLERANCE {
        let unit = axis.value.map(|v| fix::number(v / norm)).join(" ");
        findings.push(
            Finding::new(
                &rules::NON_UNIT_AXIS,
                axis.span,
                format!("{owner} axis has length {norm:.4}, not 1"),
            )
            .with_help(format!(
                "use xyz=\"{:.6} {:.6} {:.6}\"",
                axis.value[0] / norm,
                axis.value[1] / norm,
                axis.value[2] / norm
            ))
            // Parsers normalise the axis themselves (urdfdom, MuJoCo, Drake): the robot is the same.
            .with_fix(Fix::safe(
                format!("normalise the axis to xyz=\"{unit}\""),
                vec![Edit::ReplaceValue {
                    value: axis.span,
                    with: unit,
                }],
            )),
        );
    }
}

fn check_limit(
    joint: &Joint,
    kind: JointKind,
    owner: &str,
    follower: bool,
    format: Format,
    findings: &mut Vec<Finding>,
) {
    let kind_name = kind.as_str();
    let Some(limit) = &joint.limit else {
        if kind == JointKind::Continuous {
            findings.push(Finding::new(
                &rules::MISSING_EFFORT_VELOCITY,
                joint.span,
                format!("{owner} ({kind_name}) has no effort or velocity limit declared"),
            ));
        } else {
            findings.push(Finding::new(
                &rules::MISSING_LIMIT,
                joint.span,
                format!("{owner} ({kind_name}) has no <limit>: urdfdom refuses to load it"),
            ));
        }
        return;
    };
    for (value, attr) in [(&limit.effort, "effort"), (&limit.velocity, "velocity")] {
        if value.is_none() && format != Format::Urdf {
            // Optional in SDFormat (unlimited when absent); MJCF puts them on actuators.
            findings.push(Finding::new(
                &rules::MISSING_EFFORT_VELOCITY,
                limit.span,
                format!("{owner} ({kind_name}) declares no {attr} limit"),
            ));
        } else if value.is_none() {
            findings.push(Finding::new(
                &rules::INCOMPLETE_LIMIT,
                limit.span,
                format!("{owner} <limit> has no '{attr}' attribute: urdfdom refuses to load it"),
            ));
        }
    }
    if !follower {
        // Non-finite values are reported once, by the parser.
        if let Some(effort) = limit
            .effort
            .as_ref()
            .filter(|e| e.value <= 0.0 && e.value.is_finite())
        {
            findings.push(Finding::new(
                &rules::NON_POSITIVE_EFFORT,
                effort.span,
                format!(
                    "{owner} ({kind_name}) declares effort {}: the motor cannot hold any load",
                    effort.value
                ),
            ));
        }
        if let Some(velocity) = limit
            .velocity
            .as_ref()
            .filter(|v| v.value <= 0.0 && v.value.is_finite())
        {
            findings.push(Finding::new(
                &rules::NON_POSITIVE_VELOCITY,
                velocity.span,
                format!(
                    "{owner} ({kind_name}) declares velocity {}: the joint cannot move",
                    velocity.value
                ),
            ));
        }
    }
    if kind == JointKind::Continuous {
        if let Some(bound) = limit.lower.as_ref().or(limit.upper.as_ref()) {
            let removed = [&limit.lower, &limit.upper]
                .into_iter()
                .flatten()
                .map(|b| Edit::RemoveAttribute { value: b.span })
                .collect();
            findings.push(
                Finding::new(
                    &rules::CONTINUOUS_WITH_LIMITS,
                    bound.span,
                    format!("{owner} is continuous but declares lower/upper limits, which simulators ignore"),
                )
                // urdfdom and the simulators ignore them: removing them changes nothing they compute.
                .with_fix(Fix::safe("remove lower/upper from the continuous joint's <limit>", removed)),
            );
        }
        return;
    }
    // urdfdom defaults absent lower/upper to 0.
    let lower = limit.lower.as_ref().map_or(0.0, |l| l.value);
    let upper = limit.upper.as_ref().map_or(0.0, |u| u.value);
    let at = limit
        .lower
        .as_ref()
        .or(limit.upper.as_ref())
        .map_or(limit.span, |s| s.span);
    if !(lower.is_finite() && upper.is_finite()) {
        return; // Reported once, by the parser.
    }
    if lower > upper {
        let mut finding = Finding::new(
            &rules::INVERTED_LIMITS,
            at,
            format!("{owner} has inverted limits: lower {lower} > upper {upper}"),
        );
        if let (Some(l), Some(u)) = (&limit.lower, &limit.upper) {
            finding = finding.with_fix(Fix::unsafe_(
                format!("swap the limits: lower {upper}, upper {lower}"),
                vec![
                    Edit::ReplaceValue {
                        value: l.span,
                        with: fix::number(upper),
                    },
                    Edit::ReplaceValue {
                        value: u.span,
                        with: fix::number(lower),
                    },
                ],
            ));
        }
        findings.push(finding);
    } else if lower == upper {
        let note = if limit.lower.is_none() && limit.upper.is_none() {
            " (both default to 0)"
        } else {
            ""
        };
        findings.push(Finding::new(
            &rules::EMPTY_JOINT_RANGE,
            at,
            format!("{owner} ({kind_name}) has lower == upper == {lower}{note}: it cannot move"),
        ));
    }
}
