//! Builds the report's `statics` section: resolves the pose, evaluates torques (or samples the worst
//! pose), adds the payload, and grades each joint against its declared effort.

pub mod gravity;
mod section;

pub use section::{JointStatics, StaticsSection};

use std::collections::BTreeMap;

use crate::analysis::pose::{self, PoseKind, PoseOptions};
use crate::diagnostics::fix::{self, Edit, Fix};
use crate::diagnostics::span::Span;
use crate::diagnostics::suggest::did_you_mean;
use crate::diagnostics::{rules, Confidence, Finding, Section, Status};
use crate::input::srdf::Srdf;
use crate::model::kinematics::{Configuration, LinkMass};
use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::{Limit, Robot};
use gravity::{StaticsData, NEGLIGIBLE_TORQUE, PASS_MARGIN};

/// What statics needs beyond the robot.
#[derive(Clone, Debug, Default)]
pub struct StaticsOptions {
    /// The pose to evaluate.
    pub pose: PoseOptions,
    /// `--payload-mass`, kg.
    pub payload_mass: Option<f64>,
    /// `--payload-link`; default: the end of the longest actuated chain.
    pub payload_link: Option<String>,
}

/// What statics produced: the section, its findings, and the configuration it was evaluated at.
pub struct StaticsOutcome {
    /// The report section.
    pub section: StaticsSection,
    /// One finding per joint that fails, is marginal or cannot be judged, and for a requested pose or
    /// payload that could not be used.
    pub findings: Vec<Finding>,
    /// The evaluated configuration (the reference pose for `worst`).
    pub q: Configuration,
}

/// The statics section, its findings and the configuration it was evaluated at, or a usage error (unknown
/// joint or link name, unreadable SRDF).
pub fn analyse(
    robot: &Robot,
    model: &Model,
    srdf: Option<&Srdf>,
    options: &StaticsOptions,
) -> Result<StaticsOutcome, super::RequestError> {
    let resolved =
        pose::resolve(robot, model, srdf, &options.pose).map_err(super::RequestError::Pose)?;
    let payload_link = match &options.payload_link {
        Some(name) => Some(
            model
                .link(name)
                .ok_or_else(|| super::RequestError::UnknownLink {
                    flag: "--payload-link",
                    name: name.clone(),
                    suggestion: did_you_mean(name, model.link_names()),
                })?,
        ),
        None => gravity::default_payload_link(model),
    };
    if let Some(mass) = options.payload_mass {
        if !(mass.is_finite() && mass >= 0.0) {
            return Err(super::RequestError::PayloadMass(mass));
        }
    }
    let payload = options
        .payload_mass
        .zip(payload_link)
        .map(|(mass, link)| (link, mass));

    let mut data = StaticsData::new(model);
    gravity::evaluate(model, &resolved.q, &mut data);
    let per_kg =
        payload_link.map(|link| gravity::payload_torque_per_kg(model, &data.kinematics, link));
    let (total_mass, com) = gravity::mass_and_com(model, &data);
    let com = com.filter(|c| c.iter().all(|v| v.is_finite()));
    let any_mass = model
        .link_mass
        .iter()
        .any(|m| matches!(m, LinkMass::Declared { .. }));

    let worst = (options.pose.kind == PoseKind::Worst).then(|| {
        gravity::worst_configurations(
            model,
            &resolved.q,
            options.pose.samples,
            options.pose.seed,
            payload,
        )
    });

    let mut joints = Vec::new();
    let mut findings = Vec::new();
    let mut constraints = Vec::new();
    for (j, joint) in robot.joints.iter().enumerate() {
        let info = &model.joint_data[j];
        let Some((_, child)) = model.joint_links[j] else {
            continue;
        };
        if !info.is_actuated() {
            continue;
        }
        if let Some(mimic) = model.mimic[j] {
            let leader = &robot.joints[mimic.leader.0].name.value;
            joints.push(JointStatics {
                name: joint.name.value.clone(),
                required_torque_gravity: Some(data.raw_torque[j]),
                torque_confidence: if any_mass {
                    Confidence::Estimated
                } else {
                    Confidence::Missing
                },
                declared_effort: info.effort,
                effort_needed: None,
                margin: None,
                status: Status::NotApplicable,
                subtree_mass: Some(data.sums.mass[child.0]),
                summary: format!(
                    "follows '{leader}' (×{}): its torque is folded into that joint",
                    mimic.multiplier
                ),
                mimics: Some(leader.clone()),
                worst_configuration: None,
            });
            continue;
        }
        let payload_part = |per_kg: &[f64]| payload.map_or(0.0, |(_, mass)| per_kg[j] * mass);
        let (torque, unit, configuration) = match worst.as_ref().and_then(|w| w[j].as_ref()) {
            Some((torque, q)) => {
                let mut at_worst = StaticsData::new(model);
                gravity::evaluate(model, q, &mut at_worst);
                let unit = payload_link.map_or(0.0, |link| {
                    gravity::payload_torque_per_kg(model, &at_worst.kinematics, link)[j]
                });
                (*torque, unit, Some(named_configuration(robot, model, q)))
            }
            None => {
                let unit = per_kg.as_ref().map_or(0.0, |t| t[j]);
                (
                    data.torque[j] + per_kg.as_ref().map_or(0.0, |t| payload_part(t)),
                    unit,
                    None,
                )
            }
        };
        let mass_below = data.sums.mass[child.0];
        let unknown_below = data.sums.unknown[child.0];
        let mut graded = grade(torque, info.effort, mass_below, unknown_below);
        if let Some(&(held, _)) = data.sums.held.get(child.0) {
            let carried = mass_below - held;
            if carried > 0.0 {
                graded.summary.push_str(&format!(
                    " (MuJoCo's gravcomp carries {carried:.3} of the {mass_below:.3} kg below)"
                ));
            }
        }
        let at = VerdictContext {
            joint,
            prismatic: info.kind == crate::urdf::robot::JointKind::Prismatic,
            pose: if worst.is_some() {
                "its worst sampled configuration".to_string()
            } else {
                format!("the {} pose", options.pose.kind.label())
            },
            payload: payload.map(|(link, mass)| (robot.links[link.0].name.value.as_str(), mass)),
        };
        findings.extend(joint_finding(&at, &graded, any_mass));
        if let (Some(effort), Status::Pass | Status::Warn | Status::Fail) =
            (info.effort, graded.status)
        {
            let unloaded = torque - payload.map_or(0.0, |(_, m)| unit * m);
            constraints.push((unloaded, unit, effort, JointId(j)));
        }
        joints.push(JointStatics {
            name: joint.name.value.clone(),
            required_torque_gravity: graded.torque,
            torque_confidence: graded.confidence,
            declared_effort: info.effort,
            effort_needed: graded.torque.map(gravity::effort_needed),
            margin: graded.margin,
            status: graded.status,
            subtree_mass: Some(mass_below),
            summary: graded.summary,
            mimics: None,
            worst_configuration: configuration,
        });
    }

    let status = joints
        .iter()
        .map(|j| j.status)
        .filter(|s| *s != Status::NotApplicable)
        .max()
        .unwrap_or(Status::NotApplicable);
    let weakest_joint_name = joints
        .iter()
        .filter_map(|j| j.margin.map(|m| (m, &j.name)))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, name)| name.clone());
    let (payload_capacity_kg, capacity_reason) = capacity(model, payload_link, &constraints);
    let reason = if joints.is_empty() {
        Some("no actuated joint: gravity torques do not apply".to_string())
    } else if !any_mass {
        Some("no link declares a mass: torques cannot be computed".to_string())
    } else {
        capacity_reason
    };
    if !any_mass && status == Status::Unknown {
        let assessable = joints.iter().filter(|j| j.mimics.is_none()).count();
        findings.push(Finding::new(
            &rules::JOINT_NOT_ASSESSED,
            robot.span,
            format!(
                "No link declares a mass: the gravity torques of {assessable} actuated joint{} cannot be computed (statics UNKNOWN)",
                if assessable == 1 { "" } else { "s" }
            ),
        ));
    }
    if let Some(why) = &resolved.unavailable {
        findings.push(
            Finding::new(&rules::REQUESTED_CHECK_NOT_RUN, robot.span, why.clone())
                .in_section(Section::Statics),
        );
    }
    if let (Some(mass), None) = (options.payload_mass, payload) {
        findings.push(
            Finding::new(
                &rules::REQUESTED_CHECK_NOT_RUN,
                robot.span,
                format!("--payload-mass {mass}: no link to carry it (no actuated chain; name one with --payload-link)"),
            )
            .in_section(Section::Statics),
        );
    }
    let heaviest = model
        .topological_order
        .iter()
        .map(|&l| (l, model.link_mass[l.0].mass()))
        .filter(|(_, m)| *m > 0.0)
        .max_by(|a, b| a.1.total_cmp(&b.1));
    let confidence = if any_mass {
        Confidence::Estimated
    } else {
        Confidence::Missing
    };
    let mut notes = resolved.notes;
    if !robot.gravity_compensation.is_empty() {
        let bodies: Vec<String> = robot
            .gravity_compensation
            .iter()
            .map(|(name, share)| format!("{name} ({:.0} %)", 100.0 * share.value))
            .collect();
        notes.push(format!(
            "MuJoCo's gravcomp carries the weight of {}: the torques count only what the motors hold",
            bodies.join(", ")
        ));
    }
    let section = StaticsSection {
        status,
        pose: options.pose.kind.label(),
        configuration: named_configuration(robot, model, &resolved.q),
        notes,
        gravity: model.gravity.into(),
        full_body_com: com.map(|c| [c.x, c.y, c.z]),
        com_height_above_ground: com.map(|c| c.z),
        com_confidence: if com.is_some() {
            confidence
        } else {
            Confidence::Missing
        },
        total_mass: any_mass.then_some(total_mass),
        mass_confidence: confidence,
        heaviest_link_name: heaviest.map(|(l, _)| robot.links[l.0].name.value.clone()),
        heaviest_link_pct: heaviest
            .filter(|_| total_mass > 0.0)
            .map(|(_, m)| 100.0 * m / total_mass),
        weakest_joint_name,
        payload_capacity_kg,
        payload_mass: options.payload_mass,
        payload_link: payload_link
            .filter(|_| options.payload_mass.is_some() || payload_capacity_kg.is_some())
            .map(|l| robot.links[l.0].name.value.clone()),
        reason,
        samples: worst.as_ref().map(|_| options.pose.samples),
        seed: worst.as_ref().map(|_| options.pose.seed),
        joints,
    };
    Ok(StaticsOutcome {
        section,
        findings,
        q: resolved.q,
    })
}

/// Where and how a joint's verdict is told.
struct VerdictContext<'a> {
    joint: &'a crate::urdf::robot::Joint,
    prismatic: bool,
    /// "the zero pose", "its worst sampled configuration".
    pose: String,
    /// Payload link and mass, when one is carried.
    payload: Option<(&'a str, f64)>,
}

/// Declare the effort that holds `torque` with the 1.5× margin (rounded up to 0.01), when an effort is
/// written: unsafe, as it changes what the robot claims its motors can do.
fn effort_fix(limit: Option<&Limit>, torque: f64, unit: &str) -> Option<Fix> {
    let effort = limit?.effort.as_ref()?;
    let needed = gravity::round_up_to_hundredth(gravity::effort_needed(torque));
    let value = fix::number(needed);
    Some(Fix::unsafe_(
        format!("set effort to {value} {unit} (1.5 × the gravity torque): this changes what the robot claims its motors can do"),
        vec![Edit::ReplaceValue {
            value: effort.span,
            with: value,
        }],
    ))
}

/// The finding for one graded joint: FAIL below margin 1, WARN below 1.5, WARN when it cannot be judged
/// (unless no link declares a mass at all: one finding says so for the whole robot).
fn joint_finding(at: &VerdictContext, graded: &Grade, any_mass: bool) -> Option<Finding> {
    let joint = at.joint;
    let name = &joint.name.value;
    let unit = if at.prismatic { "N" } else { "N·m" };
    let limit = joint.limit.as_ref();
    let effort_span: Span = limit
        .and_then(|l| l.effort.as_ref().map(|e| e.span))
        .or(limit.map(|l| l.span))
        .unwrap_or(joint.span);
    let payload = at.payload.map_or(String::new(), |(link, mass)| {
        format!(" with the {mass} kg payload at '{link}'")
    });
    let torque = graded.torque.map(f64::abs);
    match (graded.status, torque) {
        (Status::Fail, Some(torque)) => Some(
            Finding::new(
                &rules::JOINT_UNDERSIZED,
                effort_span,
                format!(
                    "Joint '{name}' needs {torque:.2} {unit} to hold {}{payload} against gravity but declares effort {} (margin {:.2}×)",
                    at.pose,
                    declared(limit),
                    graded.margin.unwrap_or(0.0)
                ),
            )
            .with_help(format!(
                "declare effort ≥ {:.2} {unit} (1.5 × the gravity torque), or lighten the links below '{name}'",
                gravity::round_up_to_hundredth(gravity::effort_needed(torque))
            ))
            .with_fix_option(effort_fix(limit, torque, unit)),
        ),
        (Status::Warn, Some(torque)) => Some(
            Finding::new(
                &rules::JOINT_MARGINAL,
                effort_span,
                format!(
                    "Joint '{name}' needs {torque:.2} {unit} to hold {}{payload}; its effort {} leaves a margin of {:.2}× (< {PASS_MARGIN}×)",
                    at.pose,
                    declared(limit),
                    graded.margin.unwrap_or(0.0)
                ),
            )
            .with_help(format!(
                "effort ≥ {:.2} {unit} gives the 1.5× margin",
                gravity::round_up_to_hundredth(gravity::effort_needed(torque))
            ))
            .with_fix_option(effort_fix(limit, torque, unit)),
        ),
        (Status::Unknown, _) if any_mass => {
            let span = if torque.is_some() {
                effort_span
            } else {
                joint.span
            };
            Some(Finding::new(
                &rules::JOINT_NOT_ASSESSED,
                span,
                format!("Joint '{name}': {}", graded.summary),
            ))
        }
        _ => None,
    }
}

/// The declared effort as written, or "none".
fn declared(limit: Option<&crate::urdf::robot::Limit>) -> String {
    limit
        .and_then(|l| l.effort.as_ref())
        .map_or("none".to_string(), |e| e.value.to_string())
}

/// Independent actuated joints by name.
fn named_configuration(robot: &Robot, model: &Model, q: &Configuration) -> BTreeMap<String, f64> {
    model
        .joint_data
        .iter()
        .enumerate()
        .filter(|(j, info)| {
            info.is_actuated() && model.mimic[*j].is_none() && model.joint_links[*j].is_some()
        })
        .map(|(j, _)| (robot.joints[j].name.value.clone(), q[j]))
        .collect()
}

struct Grade {
    torque: Option<f64>,
    confidence: Confidence,
    margin: Option<f64>,
    status: Status,
    summary: String,
}

/// Grade one joint: torque against effort.
fn grade(torque: f64, effort: Option<f64>, mass_below: f64, unknown_below: usize) -> Grade {
    if mass_below == 0.0 && unknown_below > 0 {
        return Grade {
            torque: None,
            confidence: Confidence::Missing,
            margin: None,
            status: Status::Unknown,
            summary: "Cannot assess — no link below this joint declares a mass".to_string(),
        };
    }
    if !torque.is_finite() {
        return Grade {
            torque: None,
            confidence: Confidence::Missing,
            margin: None,
            status: Status::Unknown,
            summary: "Cannot assess — the torque overflows (check the masses and origins below)"
                .to_string(),
        };
    }
    let caveat = match unknown_below {
        0 => String::new(),
        1 => " (1 link below has geometry but no mass: torque may be underestimated)".to_string(),
        n => format!(" ({n} links below have geometry but no mass: torque may be underestimated)"),
    };
    let (margin, status, verdict) = if torque.abs() < NEGLIGIBLE_TORQUE {
        (None, Status::Pass, "OK — torque negligible".to_string())
    } else {
        match effort {
            None => (
                None,
                Status::Unknown,
                format!(
                    "Cannot assess — no effort limit declared (needs {:.2})",
                    torque.abs()
                ),
            ),
            // `effort="0"` is how many files say "not specified".
            Some(effort) if effort <= 0.0 => (
                None,
                Status::Unknown,
                format!(
                    "Cannot assess — effort not specified (effort=\"{effort}\"; needs {:.2})",
                    torque.abs()
                ),
            ),
            Some(effort) => {
                let margin = effort / torque.abs();
                let (status, verdict) = if margin >= PASS_MARGIN {
                    (Status::Pass, format!("OK — margin {margin:.2}×"))
                } else if margin >= 1.0 {
                    (
                        Status::Warn,
                        format!("marginal — margin {margin:.2}× (< {PASS_MARGIN}×)"),
                    )
                } else {
                    (
                        Status::Fail,
                        format!("undersized — needs {:.2}, declares {effort}", torque.abs()),
                    )
                };
                (Some(margin), status, verdict)
            }
        }
    };
    Grade {
        torque: Some(torque),
        confidence: Confidence::Estimated,
        margin,
        status,
        summary: verdict + &caveat,
    }
}

/// Payload capacity over the joints on the payload link's path, and why it is 0 or absent.
fn capacity(
    model: &Model,
    link: Option<LinkId>,
    constraints: &[(f64, f64, f64, JointId)],
) -> (Option<f64>, Option<String>) {
    let Some(link) = link else {
        return (None, None);
    };
    let mut on_path = vec![false; model.joint_data.len()];
    for joint in path_joints(model, link) {
        on_path[joint.0] = true;
    }
    let relevant: Vec<(f64, f64, f64)> = constraints
        .iter()
        .filter(|c| on_path[c.3 .0])
        .map(|&(t, u, e, _)| (t, u, e))
        .collect();
    if relevant.is_empty() {
        return (
            None,
            Some("no joint with a declared effort carries the payload link".to_string()),
        );
    }
    match gravity::payload_capacity(&relevant) {
        Some(kg) if kg.is_finite() => (Some(kg), None),
        Some(_) => (
            None,
            Some("no joint on the payload path is loaded by a payload".to_string()),
        ),
        None => (
            Some(0.0),
            Some("a joint on the payload path is below margin 1.5 without payload".to_string()),
        ),
    }
}

/// Independent actuated joints between the root and `link` (followers are represented by their leaders).
fn path_joints(model: &Model, link: LinkId) -> Vec<JointId> {
    model
        .joints_to_root(link)
        .into_iter()
        .map(|joint| gravity::independent_leader(model, joint).0)
        .collect()
}
