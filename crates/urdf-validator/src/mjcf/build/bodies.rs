//! Bodies as links: a body's contents (frames flattened), its joints chained, its geoms and children.

use nalgebra::{Isometry3, Translation3};

use super::geoms::GeomParts;
use super::inertials::inertial_of;
use super::joints::blank_joint;
use super::{contacts, keyframes, pose, Builder, Parent};
use crate::diagnostics::rules;
use crate::diagnostics::span::Spanned;
use crate::mjcf::compiler::InertiaFromGeom;
use crate::mjcf::mass::MassProps;
use crate::mjcf::xml::El;
use crate::urdf::robot::{Joint, JointKind, Link};

/// Elements a body may hold that are not turned into the robot (and say nothing about mass).
const IGNORED_IN_BODY: [&str; 3] = ["site", "camera", "light"];

/// Elements that make bodies this reader does not build.
const NOT_BUILT_IN_BODY: [&str; 5] = ["composite", "flexcomp", "replicate", "attach", "plugin"];

/// A body's contents, `<frame>`s flattened.
#[derive(Default)]
pub(super) struct Contents<'a> {
    joints: Vec<(El<'a>, String)>,
    pub(super) geoms: Vec<(El<'a>, String, Isometry3<f64>)>,
    inertial: Option<El<'a>>,
    pub(super) bodies: Vec<(El<'a>, String, Isometry3<f64>)>,
}

impl<'a> Builder<'a, '_> {
    /// The contents of a body (or the world body, or a `<frame>`), frames flattened: `frame` places the
    /// element's frame in the body's, `class` is the childclass in force.
    pub(super) fn contents(
        &mut self,
        el: El<'a>,
        class: &str,
        frame: Isometry3<f64>,
        world: bool,
    ) -> Contents<'a> {
        let mut out = Contents::default();
        self.collect(el, class, frame, world, &mut out);
        out
    }

    fn collect(
        &mut self,
        el: El<'a>,
        class: &str,
        frame: Isometry3<f64>,
        world: bool,
        out: &mut Contents<'a>,
    ) {
        for child in self.reader.children(el) {
            let tag = child.tag();
            match tag {
                "body" => {
                    let inherited = self.child_class(child, class);
                    out.bodies.push((child, inherited, frame));
                }
                "frame" => {
                    let own = self.class_of(child, class);
                    let at = frame * self.placement(child, &own);
                    let inherited = self.child_class(child, class);
                    self.collect(child, &inherited, at, world, out);
                }
                "geom" => {
                    let own = self.class_of(child, class);
                    out.geoms.push((child, own, frame));
                }
                "joint" | "freejoint" if !world => {
                    let own = self.class_of(child, class);
                    out.joints.push((child, own));
                }
                "inertial" if !world => match out.inertial {
                    None => out.inertial = Some(child),
                    Some(_) => self.problem(
                        &rules::MJCF_STRUCTURE,
                        child,
                        "a second <inertial> in one body (MuJoCo refuses it)".to_string(),
                    ),
                },
                _ if IGNORED_IN_BODY.contains(&tag) => {}
                _ if NOT_BUILT_IN_BODY.contains(&tag) => self.note(
                    child,
                    format!("<{tag}> is not read: the bodies it makes are left out"),
                ),
                _ => self.problem(
                    &rules::MJCF_STRUCTURE,
                    child,
                    format!(
                        "<{tag}> cannot be in {} (MuJoCo refuses the model)",
                        if world { "<worldbody>" } else { "a <body>" }
                    ),
                ),
            }
        }
    }

    /// Build body `el` and, recursively, its children.
    pub(super) fn body(
        &mut self,
        el: El<'a>,
        class: &str,
        parent: &Parent,
        frame: Isometry3<f64>,
        top_level: bool,
        floating_root: bool,
    ) {
        self.bodies += 1;
        let name = el
            .attr("name")
            .map_or_else(|| format!("body#{}", self.bodies), str::to_string);
        let name_span = self.reader.attr_span(el, "name");
        let own = self.class_of(el, class);
        let placement = frame * self.placement(el, &own);
        let contents = self.contents(el, class, Isometry3::identity(), false);
        // The body's frame at q = 0 seen from the link being chained to.
        let mut at = parent.body_in_link * placement;
        let mut parent_link = parent.link.clone();
        let mut body_in_link = Isometry3::identity();
        let count = contents.joints.len();
        if let Some(text) = el.attr("gravcomp") {
            let span = self.reader.attr_span(el, "gravcomp");
            match text.trim().parse::<f64>() {
                Ok(share) if share.is_finite() => {
                    if share != 0.0 {
                        self.gravity_compensation
                            .push((name.clone(), Spanned { value: share, span }));
                    }
                }
                _ => self.reader.report(
                    &rules::MJCF_INVALID_VALUE,
                    span,
                    format!("<body gravcomp=\"{text}\">: a finite number expected"),
                ),
            }
        }
        if count == 0 {
            self.joints.push(Joint {
                name: Spanned {
                    value: format!("{}_to_{name}", parent.link),
                    span: name_span,
                },
                span: self.reader.span(el),
                kind: Some(Spanned {
                    value: JointKind::Fixed,
                    span: self.reader.span(el),
                }),
                origin: pose(&at),
                parent: Some(Spanned {
                    value: parent_link.clone(),
                    span: name_span,
                }),
                child: Some(Spanned {
                    value: name.clone(),
                    span: name_span,
                }),
                ..blank_joint()
            });
        }
        for (i, (joint_el, joint_class)) in contents.joints.iter().enumerate() {
            let last = i + 1 == count;
            let kind = self.joint_type(*joint_el, joint_class);
            if kind == "free" && floating_root {
                // The root of a floating-base robot: its link frame is the world frame at qpos0.
                body_in_link = at;
                let name = self.joint_name(*joint_el);
                self.qpos.push(keyframes::QposJoint::free(name, &at, None));
                self.joint_ids += 1;
                continue;
            }
            let joint = self.joint(*joint_el, joint_class, &name, kind, top_level);
            self.qpos.push(match joint.kind {
                JointKind::Floating => {
                    keyframes::QposJoint::free(joint.names[0].clone(), &at, Some(name.clone()))
                }
                _ if joint.axes.len() == 3 => keyframes::QposJoint::Ball {
                    hinges: joint.names.clone(),
                },
                _ => keyframes::QposJoint::Scalar {
                    joint: joint.names[0].clone(),
                    reference: joint.reference,
                },
            });
            for (k, axis) in joint.axes.iter().enumerate() {
                let final_link = last && k + 1 == joint.axes.len();
                let child = if final_link {
                    name.clone()
                } else {
                    format!("{name}:{}", joint.names[k])
                };
                let (origin, after) = match joint.kind {
                    JointKind::Prismatic | JointKind::Floating => (at, Isometry3::identity()),
                    _ if k == 0 => (
                        at * Translation3::from(joint.anchor),
                        Isometry3::from(Translation3::from(-joint.anchor)),
                    ),
                    _ => (
                        Isometry3::identity(),
                        Isometry3::from(Translation3::from(-joint.anchor)),
                    ),
                };
                self.joints.push(Joint {
                    name: Spanned {
                        value: joint.names[k].clone(),
                        span: joint.name_span,
                    },
                    span: joint.span,
                    kind: Some(Spanned {
                        value: joint.kind,
                        span: joint.type_span,
                    }),
                    origin: pose(&origin),
                    parent: Some(Spanned {
                        value: parent_link.clone(),
                        span: joint.span,
                    }),
                    child: Some(Spanned {
                        value: child.clone(),
                        span: joint.span,
                    }),
                    axis: Some(Spanned {
                        value: [axis.x, axis.y, axis.z],
                        span: joint.axis_span,
                    }),
                    limit: joint.limit.clone(),
                    dynamics: joint.dynamics,
                    ..blank_joint()
                });
                if !final_link {
                    self.links.push(Link {
                        name: Spanned {
                            value: child.clone(),
                            span: joint.name_span,
                        },
                        span: joint.span,
                        inertial: None,
                        visuals: Vec::new(),
                        collisions: Vec::new(),
                    });
                }
                parent_link = child;
                at = after;
                body_in_link = after;
            }
        }
        let link_index = self.links.len();
        let mut link = Link {
            name: Spanned {
                value: name.clone(),
                span: name_span,
            },
            span: self.reader.span(el),
            inertial: None,
            visuals: Vec::new(),
            collisions: Vec::new(),
        };
        let mut from_geoms = None;
        let mut filters = Vec::new();
        let mut all_read = true;
        for (geom_el, geom_class, geom_frame) in &contents.geoms {
            let GeomParts {
                shape,
                collides,
                mass,
                read,
            } = self.geom(*geom_el, geom_class, &(body_in_link * geom_frame));
            all_read &= read;
            if let Some(shape) = shape {
                match collides {
                    Some(filter) => {
                        link.collisions.push(shape);
                        filters.push(filter);
                    }
                    None => link.visuals.push(shape),
                }
            }
            if let Some(mass) = mass {
                from_geoms = Some(from_geoms.unwrap_or_else(MassProps::zero).plus(&mass));
            }
        }
        let declared = match (contents.inertial, self.compiler.inertia_from_geom) {
            (Some(inertial), InertiaFromGeom::False | InertiaFromGeom::Auto) => Some((
                self.inertial(inertial).placed(&body_in_link),
                self.reader.span(inertial),
            )),
            _ => None,
        };
        let mass = match declared {
            Some(props) => Some(props),
            None if self.compiler.inertia_from_geom != InertiaFromGeom::False => {
                if !all_read {
                    self.unread_geoms.insert(name.clone());
                }
                from_geoms.map(|props| (props, self.reader.span(el)))
            }
            None => None,
        };
        if let Some((props, span)) = mass {
            link.inertial = Some(inertial_of(&props, span));
            self.masses.push((link_index, props));
        } else if self.compiler.bound_mass > 0.0 {
            // MuJoCo gives a body without mass the inertial frame (pos, quat) of the body in its parent,
            // read in the body's own frame: that is where boundmass puts its mass.
            let frame = body_in_link * placement;
            self.masses.push((
                link_index,
                MassProps {
                    com: frame.translation.vector,
                    ..MassProps::zero()
                },
            ));
        } else if !(link.visuals.is_empty() && link.collisions.is_empty()) {
            // Geoms that count for no mass: MuJoCo's body is massless, not of unknown mass.
            link.inertial = Some(inertial_of(&MassProps::zero(), self.reader.span(el)));
        }
        self.body_contacts.push(contacts::BodyContacts {
            link: name.clone(),
            parent: parent.link.clone(),
            moving: count > 0,
            geoms: filters,
        });
        self.links.push(link);
        let here = Parent {
            link: name,
            body_in_link,
        };
        for (child, child_class, child_frame) in contents.bodies {
            self.body(child, &child_class, &here, child_frame, false, false);
        }
    }
}
