//! A [`Scene`] as a URDF [`Robot`]: every link placed in its parent joint's frame (URDF's convention),
//! joints with their origin in the parent link's URDF frame and their axis in the joint frame, and a
//! `world` link when the model is fixed to the world, static, or its root link is not at the world origin.

use std::collections::HashMap;

use nalgebra::Vector3;

use super::frames::FrameGraph;
use super::link::{self, Placement};
use super::pose::{self, to_pose, Transform};
use super::scene::{El, JointDef, Scene, Sink, FRAME_SEMANTICS};
use crate::diagnostics::rules;
use crate::diagnostics::span::{Span, Spanned};
use crate::urdf::robot::{Dynamics, Joint, JointKind, Limit, Link, Mimic, Robot};

/// Joint limits at or beyond this magnitude mean "none" (SDFormat's default is ±1e16).
const NO_LIMIT: f64 = 1e15;

/// SDFormat's default for an unwritten `<lower>`/`<upper>`.
const DEFAULT_LIMIT: f64 = 1e16;

/// A joint between two resolved links.
struct Resolved<'d, 'a> {
    def: &'d JointDef<'a>,
    parent: String,
    child: String,
    frame: Transform,
}

/// Build the robot of `scene`.
pub fn robot(scene: &Scene, sink: &mut Sink) -> Robot {
    let mut graph = FrameGraph::new(scene);
    // Every frame is resolved once, so a cycle or a missing name is found even where nothing uses it.
    let mut names: Vec<&String> = scene.frames.keys().collect();
    names.sort();
    for name in names {
        graph.pose(name);
        graph.link_of(name);
    }
    graph.link_of("");
    let resolved: Vec<Resolved> = scene
        .joints
        .iter()
        .filter_map(|def| resolve(def, &mut graph, sink))
        .collect();
    // A link's URDF frame is the frame of the first joint that has it as child.
    let mut urdf_frame: HashMap<&str, Transform> = HashMap::new();
    for joint in &resolved {
        urdf_frame
            .entry(joint.child.as_str())
            .or_insert(joint.frame);
    }
    let mut link_frame: HashMap<&str, Transform> = HashMap::new();
    let mut links: Vec<Link> = Vec::new();
    for def in &scene.links {
        let at = graph.pose(&def.name).unwrap_or_else(Transform::identity);
        let placement = Placement {
            link: at,
            urdf: urdf_frame.get(def.name.as_str()).copied().unwrap_or(at),
        };
        links.push(link::link(sink, &mut graph, def, &placement));
        link_frame.insert(def.name.as_str(), placement.urdf);
    }
    let world = scene.model_pose;
    let frame_of = |name: &str| {
        link_frame
            .get(name)
            .copied()
            .unwrap_or_else(Transform::identity)
    };
    let mut joints: Vec<Joint> = resolved
        .iter()
        .map(|joint| {
            let parent_frame = if joint.parent == "world" {
                world.inverse()
            } else {
                frame_of(&joint.parent)
            };
            urdf_joint(
                joint,
                &(parent_frame.inverse() * joint.frame),
                &mut graph,
                sink,
            )
        })
        .collect();
    let roots: Vec<&Link> = links
        .iter()
        .filter(|l| !urdf_frame.contains_key(l.name.value.as_str()))
        .collect();
    let off_origin = roots.iter().any(|l| {
        let at = world * frame_of(&l.name.value);
        at.translation.vector.norm() > 1e-12 || at.rotation.angle() > 1e-12
    });
    let to_world = resolved.iter().any(|j| j.parent == "world");
    let mut robot_links = Vec::new();
    if to_world || scene.is_static || off_origin || roots.len() > 1 {
        robot_links.push(Link::world(scene.span));
        for (i, root) in roots.iter().enumerate() {
            if !scene.is_static && (to_world || i > 0) {
                sink.report(
                    &rules::SDF_JOINT_NOT_REPRESENTED,
                    root.name.span,
                    format!("link '{}' is joined to no other link (a free body in SDFormat): analysed fixed to the world", root.name.value),
                );
            }
            let at = world * frame_of(&root.name.value);
            joints.push(fixed_to_world(root, &at));
        }
    }
    if scene.is_static {
        let span = scene.static_span.unwrap_or(scene.span);
        sink.report(
            &rules::SDF_STATIC_MODEL,
            span,
            "the model is static: analysed fixed to the world with every joint held (no joint torques, no stability)".to_string(),
        );
        for joint in &mut joints {
            if let Some(kind) = &mut joint.kind {
                kind.value = JointKind::Fixed;
            }
        }
    }
    robot_links.extend(links);
    sink.findings.append(&mut graph.findings);
    Robot {
        name: scene.name.clone(),
        span: scene.span,
        links: robot_links,
        joints,
        format: crate::input::Format::Sdf,
        ..Robot::default()
    }
}

/// The parent and child links and the frame of a joint; `None` (with findings) when a link cannot be
/// found.
fn resolve<'d, 'a>(
    def: &'d JointDef<'a>,
    graph: &mut FrameGraph,
    sink: &mut Sink,
) -> Option<Resolved<'d, 'a>> {
    let span = sink.span(def.el);
    let mut end = |reference: &Option<super::scene::Ref>| -> Option<String> {
        let reference = reference.as_ref().filter(|r| !r.written.is_empty())?;
        if !graph.exists(&reference.name) {
            graph.target(reference);
            return None;
        }
        graph.link_of(&reference.name)
    };
    let parent = end(&def.parent)?;
    let child = end(&def.child)?;
    if child == "world" {
        sink.report(
            &rules::SDF_STRUCTURE,
            span,
            format!("joint '{}': the child is the world", def.name),
        );
        return None;
    }
    if parent == child {
        sink.report(
            &rules::SDF_STRUCTURE,
            span,
            format!(
                "joint '{}': parent and child are the same link '{child}'",
                def.name
            ),
        );
        return None;
    }
    let frame = graph.pose(&def.name)?;
    Some(Resolved {
        def,
        parent,
        child,
        frame,
    })
}

/// The fixed joint holding root link `root` at `at` in the world.
fn fixed_to_world(root: &Link, at: &Transform) -> Joint {
    let span = root.span;
    Joint {
        name: Spanned {
            value: format!("world_to_{}", root.name.value),
            span,
        },
        span,
        kind: Some(Spanned {
            value: JointKind::Fixed,
            span,
        }),
        origin: to_pose(at, None),
        parent: Some(Spanned {
            value: "world".to_string(),
            span,
        }),
        child: Some(root.name.clone()),
        axis: None,
        limit: None,
        dynamics: None,
        mimic: None,
        safety_controller: None,
        calibration: None,
    }
}

/// The URDF joint of `joint`, placed at `origin` in its parent's URDF frame.
fn urdf_joint(
    joint: &Resolved,
    origin: &Transform,
    graph: &mut FrameGraph,
    sink: &mut Sink,
) -> Joint {
    let def = joint.def;
    let el = def.el;
    let type_span = sink.attr_span(el, "type");
    let written = el.node.attribute("type").unwrap_or("");
    let kind = match written {
        "revolute" => JointKind::Revolute,
        "continuous" => JointKind::Continuous,
        "prismatic" => JointKind::Prismatic,
        "fixed" => JointKind::Fixed,
        "ball" | "universal" | "revolute2" | "screw" | "gearbox" => {
            sink.report(
                &rules::SDF_JOINT_NOT_REPRESENTED,
                type_span,
                format!(
                    "joint '{}' is a {written} joint: analysed as fixed",
                    def.name
                ),
            );
            JointKind::Fixed
        }
        _ => {
            if !written.is_empty() {
                sink.report(
                    &rules::SDF_STRUCTURE,
                    type_span,
                    format!("joint '{}': unknown type '{written}' (revolute, prismatic, continuous, fixed, ball, universal, revolute2, screw, gearbox)", def.name),
                );
            }
            JointKind::Fixed
        }
    };
    let axis_el = el.child("axis");
    let axis = axis_el.and_then(|a| axis(a, joint, graph, sink));
    let limit = axis_el
        .and_then(|a| a.child("limit"))
        .map(|l| limit(l, sink));
    let kind = match (kind, &limit) {
        (JointKind::Revolute, limit) if limit.as_ref().is_none_or(unlimited) => {
            JointKind::Continuous
        }
        (kind, _) => kind,
    };
    let limit = match kind {
        JointKind::Continuous => limit.map(|l| Limit {
            lower: None,
            upper: None,
            ..l
        }),
        JointKind::Revolute | JointKind::Prismatic => {
            Some(with_defaults(limit, sink.span(axis_el.unwrap_or(el))))
        }
        _ => limit,
    };
    let dynamics = axis_el.and_then(|a| a.child("dynamics")).map(|d| {
        let mut read = |tag: &str| {
            let c = d.child(tag)?;
            let value = pose::number(c.text(), &format!("<{tag}>"));
            sink.value(c, value)
        };
        Dynamics {
            damping: read("damping"),
            friction: read("friction"),
        }
    });
    let mimic = axis_el.and_then(|a| a.child("mimic")).and_then(|m| {
        let leader = m.node.attribute("joint")?;
        let mut read = |tag: &str, default: f64| match m.child(tag) {
            Some(c) => {
                let value = pose::number(c.text(), &format!("<{tag}>"));
                sink.value(c, value).unwrap_or(default)
            }
            None => default,
        };
        let (multiplier, offset) = (read("multiplier", 1.0), read("offset", 0.0));
        Some(Mimic {
            span: sink.span(m),
            joint: Spanned {
                value: def.scope.resolve(leader),
                span: sink.attr_span(m, "joint"),
            },
            multiplier,
            offset,
        })
    });
    Joint {
        name: Spanned {
            value: def.name.clone(),
            span: def.name_span,
        },
        span: sink.span(el),
        kind: Some(Spanned {
            value: kind,
            span: type_span,
        }),
        origin: to_pose(origin, el.child("pose").map(|p| sink.span(p))),
        parent: Some(Spanned {
            value: joint.parent.clone(),
            span: def.parent.as_ref().map_or(sink.span(el), |r| r.span),
        }),
        child: Some(Spanned {
            value: joint.child.clone(),
            span: def.child.as_ref().map_or(sink.span(el), |r| r.span),
        }),
        axis,
        limit,
        dynamics,
        mimic,
        safety_controller: None,
        calibration: None,
    }
}

/// No limit on either side: an SDFormat revolute joint without limits turns freely.
fn unlimited(limit: &Limit) -> bool {
    let free =
        |v: &Option<Spanned<f64>>, sign: f64| v.as_ref().is_none_or(|v| v.value * sign >= NO_LIMIT);
    free(&limit.lower, -1.0) && free(&limit.upper, 1.0)
}

/// A revolute or prismatic joint's limit with SDFormat's defaults (±1e16) for an unwritten side.
fn with_defaults(limit: Option<Limit>, span: Span) -> Limit {
    let limit = limit.unwrap_or(Limit {
        span,
        lower: None,
        upper: None,
        effort: None,
        velocity: None,
    });
    let default = |value: f64| {
        Some(Spanned {
            value,
            span: limit.span,
        })
    };
    Limit {
        lower: limit.lower.clone().or_else(|| default(-DEFAULT_LIMIT)),
        upper: limit.upper.clone().or_else(|| default(DEFAULT_LIMIT)),
        ..limit
    }
}

/// `<limit>`: each value spans its element; a negative effort or velocity (SDFormat's "unlimited", -1) is
/// read as not given.
fn limit(el: El, sink: &mut Sink) -> Limit {
    let mut read = |tag: &str| {
        let c = el.child(tag)?;
        let value = pose::number(c.text(), &format!("<{tag}>"));
        let value = sink.value(c, value)?;
        Some(Spanned {
            value,
            span: sink.span(c),
        })
    };
    let lower = read("lower");
    let upper = read("upper");
    let effort = read("effort").filter(|e| e.value >= 0.0);
    let velocity = read("velocity").filter(|v| v.value >= 0.0);
    Limit {
        span: sink.span(el),
        lower,
        upper,
        effort,
        velocity,
    }
}

/// The axis in the joint frame. `<xyz>` is expressed in `expressed_in` (SDFormat ≥ 1.7, default the
/// joint frame); in 1.5–1.6 in the joint frame unless `<use_parent_model_frame>` is true; in 1.4 always in
/// the model frame. Normalised, as sdformat does.
fn axis(
    el: El,
    joint: &Resolved,
    graph: &mut FrameGraph,
    sink: &mut Sink,
) -> Option<Spanned<[f64; 3]>> {
    let def = joint.def;
    let xyz_el = el.child("xyz");
    let xyz = match xyz_el {
        Some(x) => {
            let value = pose::vector3(x.text(), "<xyz>");
            sink.value(x, value)?
        }
        None => [0.0, 0.0, 1.0],
    };
    let model = def.scope.frame.clone();
    let expressed_in = if def.version >= FRAME_SEMANTICS {
        match xyz_el.and_then(|x| {
            x.node
                .attribute("expressed_in")
                .filter(|e| !e.is_empty())
                .map(|e| (x, e))
        }) {
            Some((x, written)) => {
                let reference = sink.reference(x, "expressed_in", written, &def.scope);
                Some(graph.target(&reference))
            }
            None => None,
        }
    } else if def.version < (1, 5) {
        Some(model)
    } else {
        let parent_frame = el.child("use_parent_model_frame").and_then(|u| {
            let value = pose::boolean(u.text(), "<use_parent_model_frame>");
            sink.value(u, value)
        });
        parent_frame.unwrap_or(false).then_some(model)
    };
    let rotation = match expressed_in {
        Some(frame) => joint.frame.rotation.inverse() * graph.pose(&frame)?.rotation,
        None => nalgebra::UnitQuaternion::identity(),
    };
    let v = rotation * Vector3::from(xyz);
    let v = if v.norm() > 0.0 { v / v.norm() } else { v };
    Some(Spanned {
        value: [v.x, v.y, v.z],
        span: sink.span(xyz_el.unwrap_or(el)),
    })
}
