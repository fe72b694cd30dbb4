//! The model diff: what MuJoCo refused, and what its compiled model changed compared with ours.

use std::collections::{HashMap, HashSet};

use serde_json::Value;

use super::{one_line, vec3, Context};
use crate::analysis::deep::job::BOUND_MASS;
use crate::analysis::deep::section::SimulatorChange;
use crate::diagnostics::span::Span;
use crate::diagnostics::{rules, Finding};
use crate::model::kinematics::{forward_kinematics, Data, LinkMass};
use crate::model::LinkId;
use crate::urdf::robot::{Geometry, JointKind};

/// A compiled mass or body position differs from the file's beyond this (relative, with 1 kg / 1 m
/// floors).
const MODEL_TOLERANCE: f64 = 1e-9;

pub(super) struct Changes {
    pub(super) list: Vec<SimulatorChange>,
    pub(super) findings: Vec<Finding>,
    /// Links whose mass or frame MuJoCo changed (their joints' forces are expected to differ).
    pub(super) physics_changed: HashSet<LinkId>,
}

impl Changes {
    pub(super) fn push(
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

/// The element MuJoCo's message names (`Element name 'sensor_mount_link', id 21`): a link, a joint or a
/// mesh of ours.
pub(super) fn named_element(cx: &Context, message: &str) -> Option<Span> {
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
pub(super) fn refusals(cx: &Context, changes: &mut Changes) {
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
                        crate::analysis::deep::job::BOUND_INERTIA
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
pub(super) fn compare_model(cx: &Context, changes: &mut Changes) {
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
