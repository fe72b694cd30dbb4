//! The bridge's reply read against our model: what MuJoCo refused or changed (found by comparing the
//! compiled model with ours, not by guessing), the cross-check of gravity forces and centre of mass, and
//! the drop test's verdict, each as findings with the element's span.

use std::collections::{HashMap, HashSet};

use serde_json::Value;

use super::ground;
use super::job::{Job, BOUND_MASS, DROP_DURATION_S, DROP_TIMESTEP_S};
use super::section::{DeepJoint, DeepSection, DropTest, SaggingJoint, SimulatorChange};
use crate::analysis::Physics;
use crate::diagnostics::span::Span;
use crate::diagnostics::{rules, Finding, Status};
use crate::model::kinematics::{forward_kinematics, Data, LinkMass};
use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::{Geometry, JointKind, Robot};

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
/// A compiled mass or body position differs from the file's beyond this (relative, with 1 kg / 1 m
/// floors).
const MODEL_TOLERANCE: f64 = 1e-9;

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

struct Changes {
    list: Vec<SimulatorChange>,
    findings: Vec<Finding>,
    /// Links whose mass or frame MuJoCo changed (their joints' forces are expected to differ).
    physics_changed: HashSet<LinkId>,
}

impl Changes {
    fn push(
        &mut self,
        rule: &'static rules::Rule,
        kind: &str,
        element: &str,
        span: Span,
        message: String,
    ) {
        self.list.push(SimulatorChange {
            kind: kind.to_string(),
            element: element.to_string(),
            message: message.clone(),
        });
        self.findings.push(Finding::new(rule, span, message));
    }
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

/// The element MuJoCo's message names (`Element name 'sensor_mount_link', id 21`): a link, a joint or a
/// mesh of ours.
fn named_element(cx: &Context, message: &str) -> Option<Span> {
    let name = message.split("Element name '").nth(1)?.split('\'').next()?;
    if let Some(link) = cx.model.link(name) {
        return Some(cx.robot.links[link.0].span);
    }
    if let Some(joint) = cx.model.joint(name) {
        return Some(cx.robot.joints[joint.0].span);
    }
    // Our mesh assets are `urdf_validate_mesh<N>_`, MuJoCo appends a number for each other scale.
    let stem = name.rsplit_once('_').map_or(name, |(stem, _)| stem);
    cx.job.mesh_spans.get(&format!("{stem}_")).copied()
}

/// What MuJoCo refused and the bridge adjusted (`attempts`).
fn refusals(cx: &Context, changes: &mut Changes) {
    let Some(attempts) = cx.reply["attempts"].as_array() else {
        return;
    };
    for attempt in attempts {
        let error = one_line(attempt["error"].as_str().unwrap_or(""));
        match attempt["applied"].as_str() {
            Some("inertia") => {
                let real: Vec<_> = cx
                    .job
                    .inertia_fixes
                    .iter()
                    .filter(|f| f.shortfall > 0.0)
                    .collect();
                let fixes = if real.is_empty() {
                    cx.job.inertia_fixes.iter().collect()
                } else {
                    real
                };
                for fix in fixes {
                    let link = &cx.robot.links[fix.link.0];
                    let span = link
                        .inertial
                        .as_ref()
                        .and_then(|i| i.inertia.map(|t| t.span))
                        .unwrap_or(link.span);
                    let [a, b, c] = fix.before;
                    let raise = fix.after[0] - a;
                    changes.push(
                        &rules::SIMULATOR_REFUSES,
                        "refused",
                        &link.name.value,
                        span,
                        format!(
                            "MuJoCo refuses link '{}': its principal moments {a:.6e}, {b:.6e}, {c:.6e} break A + B ≥ C by {:.3e} kg·m² (MuJoCo stops at the first such body: \"{error}\"); loaded with the two smaller moments each raised by {raise:.3e} kg·m², the smallest change that makes A + B = C (axes, mass and centre of mass unchanged)",
                            link.name.value, fix.shortfall
                        ),
                    );
                }
            }
            Some("bound") => {
                let span = named_element(cx, &error).unwrap_or(cx.robot.span);
                let element = error
                    .split("Element name '")
                    .nth(1)
                    .and_then(|s| s.split('\'').next())
                    .unwrap_or("")
                    .to_string();
                changes.push(
                    &rules::SIMULATOR_REFUSES,
                    "refused",
                    &element,
                    span,
                    format!(
                        "MuJoCo refuses a moving link without mass or inertia (\"{error}\"); loaded with MuJoCo's boundmass = {BOUND_MASS:e} kg and boundinertia = {:e} kg·m², the smallest it accepts in practice",
                        super::job::BOUND_INERTIA
                    ),
                );
            }
            _ => {}
        }
    }
}

/// The compiled model against ours: fused links, dropped visuals, mimic, limits, efforts, masses, frames,
/// convex hulls. What MuJoCo's URDF importer changes (fusing, visuals, mimic, efforts, hulls) is not said
/// of an MJCF model, which MuJoCo loads as the user does.
fn compare_model(cx: &Context, changes: &mut Changes) {
    let (robot, model) = (cx.robot, cx.model);
    let urdf = !cx.job.mjcf;
    let model_json = &cx.reply["model"];
    let empty = Vec::new();
    let bodies = model_json["bodies"].as_array().unwrap_or(&empty);
    let body_mass: HashMap<&str, f64> = bodies
        .iter()
        .filter_map(|b| Some((b["name"].as_str()?, b["mass"].as_f64()?)))
        .collect();
    // The body each link ends up in: itself, or the nearest ancestor MuJoCo kept.
    let mut body_of: Vec<Option<LinkId>> = vec![None; robot.links.len()];
    for &link in &model.topological_order {
        let name = robot.links[link.0].name.value.as_str();
        body_of[link.0] = if body_mass.contains_key(name) {
            Some(link)
        } else {
            model.parent_joint[link.0]
                .and_then(|j| model.joint_links[j.0])
                .and_then(|(parent, _)| body_of[parent.0])
        };
    }
    for &link in &model.topological_order {
        let l = &robot.links[link.0];
        let name = l.name.value.as_str();
        // (An MJCF body's joints after its first are massless links without shape: not bodies.)
        let chain_link =
            !urdf && l.inertial.is_none() && l.visuals.is_empty() && l.collisions.is_empty();
        if let Some(body) = body_of[link.0].filter(|b| *b != link && !chain_link) {
            changes.push(
                &rules::SIMULATOR_CHANGES_MODEL,
                "fused",
                name,
                l.span,
                format!(
                    "MuJoCo fuses link '{name}' into '{}' (fixed joint; `fusestatic`, on for URDF): it is no body of its own in the simulation, its mass and geometry move to '{}'",
                    robot.links[body.0].name.value, robot.links[body.0].name.value
                ),
            );
        }
        if urdf && !l.visuals.is_empty() && l.collisions.is_empty() {
            changes.push(
                &rules::SIMULATOR_CHANGES_MODEL,
                "visual_dropped",
                name,
                l.visuals[0].span,
                format!(
                    "MuJoCo drops the visual geometry of a URDF (`discardvisual`, on for URDF): link '{name}' has visuals only, so it has no shape in the simulation"
                ),
            );
        }
    }
    // Masses per body, the links fused into it summed.
    let mut expected: HashMap<LinkId, f64> = HashMap::new();
    let mut fused_in: HashMap<LinkId, Vec<LinkId>> = HashMap::new();
    for &link in &model.topological_order {
        if let Some(body) = body_of[link.0] {
            let mass = match model.link_mass[link.0] {
                LinkMass::Declared { mass, .. } => mass,
                _ => 0.0,
            };
            *expected.entry(body).or_default() += mass;
            fused_in.entry(body).or_default().push(link);
        }
    }
    if let Some((link, mass)) = cx.payload {
        if let Some(body) = body_of[link.0] {
            *expected.entry(body).or_default() += mass;
        }
    }
    let mut bodies_sorted: Vec<_> = expected.iter().collect();
    bodies_sorted.sort_by_key(|(body, _)| body.0);
    for (&body, &ours) in bodies_sorted {
        let name = robot.links[body.0].name.value.as_str();
        let Some(&theirs) = body_mass.get(name) else {
            continue;
        };
        if (theirs - ours).abs() <= MODEL_TOLERANCE * ours.abs().max(1.0) {
            continue;
        }
        let members = fused_in.get(&body).cloned().unwrap_or_default();
        let no_inertial: Vec<&str> = members
            .iter()
            .filter(|l| {
                robot.links[l.0].inertial.is_none() && !robot.links[l.0].collisions.is_empty()
            })
            .map(|l| robot.links[l.0].name.value.as_str())
            .collect();
        let why = if name == "world" {
            "a link named 'world' is MuJoCo's world body, and the mass of links fused into it is dropped (src/user/user_model.cc, FuseStatic): it does not move, so only the centre of mass shows it".to_string()
        } else if !no_inertial.is_empty() {
            format!(
                "{} no <inertial>: MuJoCo gives a link without one the mass of its collision geometry at 1000 kg/m³ (`inertiafromgeom=\"auto\"`)",
                quoted_list(&no_inertial, "has", "have")
            )
        } else if ours < BOUND_MASS * 10.0 {
            "a moving link without mass gets MuJoCo's lower bound".to_string()
        } else {
            "MuJoCo's compiled mass differs".to_string()
        };
        for member in &members {
            changes.physics_changed.insert(*member);
        }
        changes.push(
            &rules::SIMULATOR_CHANGES_PHYSICS,
            "mass",
            name,
            robot.links[body.0].span,
            format!("MuJoCo's body '{name}' weighs {theirs:.6} kg where the file declares {ours:.6} kg: {why}"),
        );
    }
    // Frames at the analysed pose.
    let mut data = Data::new(model);
    forward_kinematics(model, &cx.physics.q, &mut data);
    // (An MJCF body's link frame is at its joint's anchor, its floating root's at the world origin: the
    // forces and centre of mass compare its placement.)
    let positions = cx.reply["crosscheck"][0]["body_pos"]
        .as_object()
        .filter(|_| urdf);
    if let Some(positions) = positions {
        for &link in &model.topological_order {
            let name = robot.links[link.0].name.value.as_str();
            let Some(p) = positions.get(name).and_then(vec3) else {
                continue;
            };
            let ours = data.link_placement[link.0].translation.vector;
            let diff =
                ((p[0] - ours.x).powi(2) + (p[1] - ours.y).powi(2) + (p[2] - ours.z).powi(2))
                    .sqrt();
            if diff > MODEL_TOLERANCE * ours.norm().max(1.0) {
                changes.physics_changed.insert(link);
                let why = if urdf {
                    " (MuJoCo's URDF importer reads `rpy` only, not URDF 1.1's `quat_xyzw`)"
                } else {
                    ""
                };
                changes.push(
                    &rules::SIMULATOR_CHANGES_PHYSICS,
                    "frame",
                    name,
                    robot.links[link.0].span,
                    format!(
                        "MuJoCo places link '{name}' {:.3} mm from where the file puts it at the analysed pose{why}",
                        diff * 1000.0
                    ),
                );
            }
        }
    }
    // Joints: mimic, limits, efforts.
    let joints: HashMap<&str, &Value> = model_json["joints"]
        .as_array()
        .unwrap_or(&empty)
        .iter()
        .filter_map(|j| Some((j["name"].as_str()?, j)))
        .collect();
    for (j, joint) in cx.robot.joints.iter().enumerate() {
        let name = joint.name.value.as_str();
        let info = &model.joint_data[j];
        if model.joint_links[j].is_none() || !info.is_actuated() {
            continue;
        }
        if let (Some(mimic), Some(link), true) = (&joint.mimic, model.mimic[j], urdf) {
            changes.push(
                &rules::SIMULATOR_CHANGES_MODEL,
                "mimic",
                name,
                mimic.span,
                format!(
                    "MuJoCo's URDF importer ignores <mimic> (src/xml/xml_urdf.cc reads none): joint '{name}' would move freely; this pass adds it as a joint equality constraint ({name} = {} · {} + {}), as an MJCF model would",
                    link.multiplier, cx.robot.joints[link.leader.0].name.value, link.offset
                ),
            );
        }
        let Some(compiled) = joints.get(name) else {
            continue;
        };
        let limited = compiled["limited"].as_bool().unwrap_or(false);
        let limit_span = joint.limit.as_ref().map_or(joint.span, |l| l.span);
        match info.kind {
            JointKind::Continuous if limited => changes.push(
                &rules::SIMULATOR_CHANGES_PHYSICS,
                "limits",
                name,
                limit_span,
                format!(
                    "MuJoCo enforces lower/upper on continuous joint '{name}', which URDF (urdfdom) ignores: the joint stops at its limits in MuJoCo only"
                ),
            ),
            // (A URDF prismatic joint always has limits, an MJCF slide joint may have none.)
            JointKind::Revolute | JointKind::Prismatic
                if info.range().is_some()
                    && !limited
                    && (urdf || info.kind == JointKind::Revolute) =>
            {
                changes.push(
                &rules::SIMULATOR_CHANGES_PHYSICS,
                "limits",
                name,
                limit_span,
                format!("MuJoCo does not enforce the limits of joint '{name}'"),
            )
            }
            _ => {}
        }
        let force_limited = compiled["force_limited"].as_bool().unwrap_or(false);
        if urdf && !force_limited && model.mimic[j].is_none() {
            changes.push(
                &rules::SIMULATOR_CHANGES_MODEL,
                "effort",
                name,
                limit_span,
                format!(
                    "joint '{name}' declares no effort above 0: MuJoCo leaves its actuator force unlimited (it maps effort to `actuatorfrcrange`), and so does the drop test's servo"
                ),
            );
        }
    }
    let mesh_links: Vec<&str> = robot
        .links
        .iter()
        .filter(|l| {
            l.collisions.iter().any(|c| {
                matches!(
                    c.geometry.as_ref().map(|g| &g.value),
                    Some(Geometry::Mesh { .. })
                )
            })
        })
        .map(|l| l.name.value.as_str())
        .collect();
    if let Some(first) = robot.links.iter().filter(|_| urdf).find_map(|l| {
        l.collisions.iter().find_map(|c| match c.geometry.as_ref() {
            Some(g) if matches!(g.value, Geometry::Mesh { .. }) => Some(g.span),
            _ => None,
        })
    }) {
        changes.push(
            &rules::SIMULATOR_CHANGES_MODEL,
            "mesh",
            mesh_links.first().copied().unwrap_or(""),
            first,
            format!(
                "MuJoCo collides meshes by their convex hulls: the collision meshes of {} link{} ({}) are convex in the simulation, concave parts filled",
                mesh_links.len(),
                if mesh_links.len() == 1 { "" } else { "s" },
                abbreviated(&mesh_links)
            ),
        );
    }
}

fn quoted_list(names: &[&str], one: &str, many: &str) -> String {
    let verb = if names.len() == 1 { one } else { many };
    format!("'{}' {verb}", names.join("', '"))
}

fn abbreviated(names: &[&str]) -> String {
    let shown: Vec<&str> = names.iter().take(4).copied().collect();
    if names.len() > shown.len() {
        format!("{}, …", shown.join(", "))
    } else {
        shown.join(", ")
    }
}

fn vec3(value: &Value) -> Option<[f64; 3]> {
    let a = value.as_array()?;
    Some([
        a.first()?.as_f64()?,
        a.get(1)?.as_f64()?,
        a.get(2)?.as_f64()?,
    ])
}

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
fn crosscheck(
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
                super::configuration(model, &physics.q, &named)
            };
            (
                super::our_torques(model, &q, cx.payload),
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

/// The drop test's verdict.
fn drop_test(cx: &Context, findings: &mut Vec<Finding>) -> DropTest {
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
        super::job::DROP_HEIGHT_M * 100.0
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
        .take(super::job::TILT_TRACE_POINTS)
        .collect()
}
