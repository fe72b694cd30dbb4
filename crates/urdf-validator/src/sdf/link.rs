//! A `<link>`'s contents — `<inertial>`, `<visual>`, `<collision>` — as URDF values placed in the link's
//! URDF frame (which is its parent joint's frame, where SDFormat lets the two differ).

use std::path::Path;

use super::frames::FrameGraph;
use super::pose::{self, to_pose, Transform};
use super::scene::{El, LinkDef, Sink, FRAME_SEMANTICS};
use crate::diagnostics::rules;
use crate::diagnostics::span::Spanned;
use crate::urdf::robot::{Geometry, Inertia, Inertial, Link, Shape};

/// Where a link is: its SDFormat frame and its URDF frame, both in the model frame.
pub struct Placement {
    /// The `<link>` frame.
    pub link: Transform,
    /// The frame the URDF link is expressed in (its parent joint's frame, or the link frame for a root).
    pub urdf: Transform,
}

/// The URDF link of `def`.
pub fn link(sink: &mut Sink, graph: &mut FrameGraph, def: &LinkDef, at: &Placement) -> Link {
    let to_urdf = at.urdf.inverse();
    // sdformat gives a link without <inertial> 1 kg and unit inertia at its origin, and Gazebo and Drake
    // simulate it so: the link is read the same way.
    let inertial_el = def.el.child("inertial").unwrap_or(def.el);
    let (local, _, pose_span) = match def.el.child("inertial") {
        Some(el) => sink.pose_of(el, &def.scope, def.version),
        None => (Transform::identity(), None, sink.span(def.el)),
    };
    let origin = to_pose(&(to_urdf * at.link * local), Some(pose_span));
    let inertial = Some(inertial(sink, inertial_el, origin));
    let mut shapes = |tag: &'static str| -> Vec<Shape> {
        def.el
            .children(tag)
            .filter_map(|el| {
                let (local, relative_to, pose_span) = sink.pose_of(el, &def.scope, def.version);
                let frame = match relative_to.filter(|_| def.version >= FRAME_SEMANTICS) {
                    Some(reference) => {
                        let target = graph.target(&reference);
                        graph.pose(&target)?
                    }
                    None => at.link,
                };
                let geometry = geometry(sink, el)?;
                Some(Shape {
                    span: sink.span(el),
                    name: el.node.attribute("name").map(str::to_string),
                    origin: to_pose(&(to_urdf * frame * local), Some(pose_span)),
                    geometry: Some(geometry),
                    material: None,
                })
            })
            .collect()
    };
    let visuals = shapes("visual");
    let collisions = shapes("collision");
    Link {
        name: Spanned {
            value: def.name.clone(),
            span: def.name_span,
        },
        span: sink.span(def.el),
        inertial,
        visuals,
        collisions,
    }
}

/// `<inertial>` with SDFormat's defaults: mass 1 kg, inertia diag(1, 1, 1) kg·m² for what is not written
/// (`el` is the `<link>` itself when it has no `<inertial>`: every value is then the default).
fn inertial(sink: &mut Sink, el: El, origin: crate::urdf::robot::Pose) -> Inertial {
    let span = sink.span(el);
    let mass = match el.child("mass") {
        Some(m) => {
            let value = pose::number(m.text(), "<mass>");
            sink.value(m, value).map(|value| Spanned {
                value,
                span: sink.span(m),
            })
        }
        None => Some(Spanned { value: 1.0, span }),
    };
    let tensor = el.child("inertia");
    let component = |sink: &mut Sink, name: &str, default: f64| -> Option<f64> {
        match tensor.and_then(|t| t.child(name)) {
            Some(c) => {
                let value = pose::number(c.text(), &format!("<{name}>"));
                sink.value(c, value)
            }
            None => Some(default),
        }
    };
    let values = [
        component(sink, "ixx", 1.0),
        component(sink, "ixy", 0.0),
        component(sink, "ixz", 0.0),
        component(sink, "iyy", 1.0),
        component(sink, "iyz", 0.0),
        component(sink, "izz", 1.0),
    ];
    let inertia = match values {
        [Some(ixx), Some(ixy), Some(ixz), Some(iyy), Some(iyz), Some(izz)] => Some(Inertia {
            span: tensor.map_or(span, |t| sink.span(t)),
            values: [tensor.map_or(span, |t| sink.span(t)); 6],
            ixx,
            ixy,
            ixz,
            iyy,
            iyz,
            izz,
        }),
        _ => None,
    };
    Inertial {
        span,
        origin,
        mass,
        inertia,
    }
}

/// The shape in the `<geometry>` of a visual or collision; `None` (with a finding) when there is none
/// this validator models.
fn geometry(sink: &mut Sink, el: El) -> Option<Spanned<Geometry>> {
    let owner = sink.span(el);
    let Some(shape) = el.child("geometry").and_then(|g| {
        g.node
            .children()
            .find(|n| n.is_element())
            .map(|node| El { file: g.file, node })
    }) else {
        sink.report(
            &rules::SDF_STRUCTURE,
            owner,
            format!("<{}> without a <geometry> shape", el.node.tag_name().name()),
        );
        return None;
    };
    let span = sink.span(shape);
    let required = |sink: &mut Sink, tag: &str| {
        let found = shape.child(tag);
        if found.is_none() {
            sink.report(
                &rules::SDF_STRUCTURE,
                span,
                format!("<{}> without <{tag}>", shape.node.tag_name().name()),
            );
        }
        found
    };
    let read = |sink: &mut Sink, tag: &str| -> Option<f64> {
        let c = required(sink, tag)?;
        let value = pose::number(c.text(), &format!("<{tag}>"));
        sink.value(c, value)
    };
    let value = match shape.node.tag_name().name() {
        "box" => {
            let size = required(sink, "size")?;
            let value = pose::vector3(size.text(), "<size>");
            Geometry::Box {
                size: sink.value(size, value)?,
            }
        }
        "cylinder" => Geometry::Cylinder {
            radius: read(sink, "radius")?,
            length: read(sink, "length")?,
        },
        "capsule" => Geometry::Capsule {
            radius: read(sink, "radius")?,
            length: read(sink, "length")?,
        },
        "sphere" => Geometry::Sphere {
            radius: read(sink, "radius")?,
        },
        "mesh" => {
            let uri = required(sink, "uri")?;
            let scale = match shape.child("scale") {
                Some(s) => {
                    let value = pose::vector3(s.text(), "<scale>");
                    sink.value(s, value)?
                }
                None => [1.0; 3],
            };
            Geometry::Mesh {
                filename: Spanned {
                    value: mesh_uri(uri.text(), sink.files.path(el.file), el.file),
                    span: sink.span(uri),
                },
                scale,
            }
        }
        other => {
            sink.report(
                &rules::SDF_NOT_READ,
                span,
                format!("<{other}> geometry is not modelled here: left out of the analyses"),
            );
            return None;
        }
    };
    Some(Spanned { value, span })
}

/// A mesh URI as the asset stage resolves it: a relative path in an included file made absolute from
/// that file's folder (the asset stage resolves relative paths from the entry file).
fn mesh_uri(uri: &str, file: &Path, index: usize) -> String {
    if index == 0 || uri.contains("://") || Path::new(uri).is_absolute() {
        return uri.to_string();
    }
    let dir = file.parent().unwrap_or(Path::new("."));
    std::path::absolute(dir.join(uri))
        .unwrap_or_else(|_| dir.join(uri))
        .display()
        .to_string()
}
