//! The `<worldbody>` tree as a URDF [`Robot`]: one link per body (named as the body), its joints chained
//! through massless links, geoms as collision (or, with `contype` and `conaffinity` 0, visual) shapes,
//! and the body's mass from `<inertial>` or its geoms as `inertiafromgeom` says.
//!
//! Frames: a URDF joint turns its child about the joint frame's origin, a MuJoCo hinge about its `pos` in
//! the body. So a link's frame is its body's frame moved to the last hinge's anchor (`body_in_link` is
//! the body frame seen from the link): the joint origin is the anchor, and the body's geoms, mass and
//! child bodies are placed in the link frame through it. At q = 0 every body is where MuJoCo puts it at
//! `qpos0` (a joint's q is MuJoCo's `qpos − ref`, its limits shifted by `ref` too).

mod actuators;
mod attributes;
mod bodies;
mod contacts;
mod equality;
mod geoms;
mod inertials;
mod joints;
mod keyframes;
mod meshes;
mod world;

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use nalgebra::Isometry3;

use super::compiler::Compiler;
use super::defaults::{Defaults, MAIN};
use super::mass::MassProps;
use super::xml::{El, Reader};
use crate::diagnostics::rules::{self, Rule};
use crate::diagnostics::span::{Span, Spanned};
use crate::input::mesh::MeshCache;
use crate::input::resolve::PackageResolver;
use crate::urdf::robot::{ContactSection, Joint, Link, Pose, Robot};

use meshes::MeshAsset;
use world::contacts_disabled;

/// Top-level sections that say nothing about the tree or its mass.
const QUIET_SECTIONS: [&str; 10] = [
    "option",
    "size",
    "visual",
    "statistic",
    "sensor",
    "custom",
    "extension",
    "contact",
    "deformable",
    "default",
];

/// Sections read by the MJCF reader of a later step: what they hold is left out, with a U033.
const SECTIONS_NOT_READ: [(&str, &str); 1] = [("tendon", "tendons are not read yet")];

/// Where a body hangs: the URDF link of its parent body, and the parent body's frame seen from it.
#[derive(Clone)]
struct Parent {
    link: String,
    body_in_link: Isometry3<f64>,
}

/// The builder's state while it walks the tree.
pub struct Builder<'a, 'r> {
    reader: &'r mut Reader<'a>,
    defaults: Defaults<'a>,
    compiler: Compiler,
    meshes: HashMap<String, MeshAsset>,
    mesh_cache: &'r MeshCache,
    resolver: &'r PackageResolver,
    dir: PathBuf,
    links: Vec<Link>,
    joints: Vec<Joint>,
    /// The mass of each body link built, by index in `links`.
    masses: Vec<(usize, MassProps)>,
    bodies: usize,
    joint_ids: usize,
    /// Each hinge and slide joint's `actuatorfrcrange` when it is limited, with its span.
    actuator_force: HashMap<String, ((f64, f64), Span)>,
    /// What the actuator rules need to know of each hinge and slide joint, by name.
    joint_facts: HashMap<String, actuators::JointFacts>,
    /// What the contact filter needs to know of each body, in document order.
    body_contacts: Vec<contacts::BodyContacts>,
    /// Bodies whose weight MuJoCo carries (`gravcomp`), by link name.
    gravity_compensation: Vec<(String, Spanned<f64>)>,
    /// Bodies with a geom whose mesh could not be read: their mass is partly unknown, so MuJoCo's
    /// verdict on it (mjMINVAL) is too; the missing file is what it refuses.
    unread_geoms: HashSet<String>,
    /// Every joint in MuJoCo's qpos order, for the keyframes.
    qpos: Vec<keyframes::QposJoint>,
    /// Every actuator in MuJoCo's order (its name, or `actuator#INDEX`) and its `ctrlrange` when limited
    /// and read, for the keyframes' `ctrl`.
    actuator_ctrl: Vec<(String, Option<(f64, f64)>)>,
}

impl<'a, 'r> Builder<'a, 'r> {
    /// A builder for the model whose top-level sections are `sections`; mesh files are found from
    /// `model_path`'s folder and loaded through `mesh_cache` when the resolver's sandbox allows.
    pub fn new(
        reader: &'r mut Reader<'a>,
        sections: &[El<'a>],
        model_path: &Path,
        mesh_cache: &'r MeshCache,
        resolver: &'r PackageResolver,
    ) -> Self {
        let compiler = Compiler::read(reader, sections);
        let defaults = Defaults::read(reader, sections);
        let dir = model_path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
            .to_path_buf();
        let mut builder = Builder {
            reader,
            defaults,
            compiler,
            meshes: HashMap::new(),
            mesh_cache,
            resolver,
            dir,
            links: Vec::new(),
            joints: Vec::new(),
            masses: Vec::new(),
            bodies: 0,
            joint_ids: 0,
            actuator_force: HashMap::new(),
            joint_facts: HashMap::new(),
            body_contacts: Vec::new(),
            unread_geoms: HashSet::new(),
            gravity_compensation: Vec::new(),
            qpos: Vec::new(),
            actuator_ctrl: Vec::new(),
        };
        for section in sections {
            match section.tag() {
                "asset" => builder.assets(*section),
                "worldbody" | "compiler" | "actuator" | "equality" | "keyframe" => {}
                tag if QUIET_SECTIONS.contains(&tag) => {}
                tag => match SECTIONS_NOT_READ.iter().find(|(t, _)| *t == tag) {
                    Some((_, why)) => builder.note(*section, why.to_string()),
                    None => builder.problem(
                        &rules::MJCF_STRUCTURE,
                        *section,
                        format!("<{tag}> is not an MJCF section (MuJoCo refuses the model)"),
                    ),
                },
            }
        }
        builder
    }

    /// The robot of the `<worldbody>` sections among `sections`.
    pub fn robot(mut self, root: El<'a>, sections: &[El<'a>]) -> Robot {
        let mut top: Vec<(El<'a>, String, Isometry3<f64>)> = Vec::new();
        let mut world_planes = Vec::new();
        for world in sections.iter().filter(|s| s.tag() == "worldbody") {
            let contents = self.contents(*world, MAIN, Isometry3::identity(), true);
            world_planes.extend(self.world_planes(&contents.geoms));
            top.extend(contents.bodies);
        }
        let floating_root = match top.as_slice() {
            [(el, class, _)] => {
                let joints: Vec<El<'a>> = el
                    .node
                    .children()
                    .filter(|n| n.has_tag_name("joint") || n.has_tag_name("freejoint"))
                    .map(|node| El {
                        file: el.file,
                        node,
                    })
                    .collect();
                matches!(joints.as_slice(), [j] if self.joint_type(*j, class) == "free")
            }
            _ => false,
        };
        if !floating_root {
            self.links.push(Link::world(self.reader.span(root)));
        }
        let world = Parent {
            link: "world".to_string(),
            body_in_link: Isometry3::identity(),
        };
        for (el, class, frame) in top {
            self.body(el, &class, &world, frame, true, floating_root);
        }
        self.finish_masses();
        self.refuse_massless_moving_bodies();
        self.set_efforts(sections);
        self.equalities(sections);
        let keyframes = self.keyframes(sections);
        let collision_filtered = self.filtered_pairs(sections);
        let contact_bits = self
            .body_contacts
            .iter()
            .map(|b| (b.link.clone(), b.geoms.clone()))
            .collect();
        let gravity = self.gravity(sections);
        let span = self.reader.span(root);
        let contact_section = Some(match sections.iter().find(|s| s.tag() == "contact") {
            Some(contact) => ContactSection::Existing(self.reader.span(*contact)),
            None => ContactSection::Missing(span),
        });
        Robot {
            name: root.attr("model").map(|m| Spanned {
                value: m.to_string(),
                span: self.reader.attr_span(root, "model"),
            }),
            span,
            links: self.links,
            joints: self.joints,
            format: crate::input::Format::Mjcf,
            collision_filtered,
            keyframes,
            gravity,
            gravity_compensation: self.gravity_compensation,
            contact_bits,
            contacts_disabled: contacts_disabled(sections),
            world_planes,
            contact_section,
            ..Robot::default()
        }
    }

    fn problem(&mut self, rule: &'static Rule, el: El<'_>, message: String) {
        let span = self.reader.span(el);
        self.reader.report(rule, span, message);
    }

    fn note(&mut self, el: El<'_>, message: String) {
        self.problem(&rules::MJCF_NOT_READ, el, message);
    }
}

/// A transform as a URDF pose (translation and quaternion).
fn pose(at: &Isometry3<f64>) -> Pose {
    let q = at.rotation.quaternion();
    Pose {
        xyz: at.translation.vector.into(),
        quat_xyzw: Some([q.i, q.j, q.k, q.w]),
        ..Pose::default()
    }
}
