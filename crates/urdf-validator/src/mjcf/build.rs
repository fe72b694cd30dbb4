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
mod contacts;
mod equality;
mod keyframes;

use std::cell::OnceCell;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::rc::Rc;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::compiler::{boolean, keyword, Compiler, InertiaFromGeom};
use super::defaults::{Defaults, Value, MAIN};
use super::mass::{self, MassProps, MeshVolume, Solid};
use super::orientation::{self, FORMS};
use super::xml::{numbers, El, Reader};
use crate::diagnostics::rules::{self, Rule};
use crate::diagnostics::span::{Span, Spanned};
use crate::input::mesh::{load_surface, MeshCache};
use crate::input::resolve::PackageResolver;
use crate::urdf::robot::{
    ContactSection, Dynamics, Geometry, Inertia, Inertial, Joint, JointKind, Limit, Link, Pose,
    Robot, Shape, WorldPlane, STANDARD_GRAVITY,
};

/// The limits of a slide joint without a range: SDFormat's "unlimited" (the samplers and checks read a
/// range this wide as no limit, see `model::kinematics::MAX_PRISMATIC_TRAVEL`).
const UNLIMITED_SLIDE: f64 = 1e16;
/// The actuator elements, which share one default per class.
const ACTUATOR_KINDS: [&str; 10] = [
    "general",
    "motor",
    "position",
    "velocity",
    "intvelocity",
    "damper",
    "cylinder",
    "muscle",
    "adhesion",
    "plugin",
];

/// Elements a body may hold that are not turned into the robot (and say nothing about mass).
const IGNORED_IN_BODY: [&str; 3] = ["site", "camera", "light"];

/// Elements that make bodies this reader does not build.
const NOT_BUILT_IN_BODY: [&str; 5] = ["composite", "flexcomp", "replicate", "attach", "plugin"];

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

/// A `<mesh>` asset.
#[derive(Clone, Debug)]
struct MeshAsset {
    /// The file, relative to the model file's folder (through `meshdir`).
    file: String,
    /// The `file` attribute.
    span: Span,
    /// `scale`.
    scale: [f64; 3],
    /// `inertia`: how its volume (or, for `shell`, its area) is summed.
    volume: MeshVolume,
    /// `inertia="convex"`: over the convex hull's triangles.
    convex: bool,
    /// `refpos` and `refquat`: the frame the file's vertices are written in (MuJoCo moves them by its
    /// inverse).
    reference: Isometry3<f64>,
    /// Its solid once read (shared by the clones: the file is read once however many geoms use it).
    solid: Rc<OnceCell<Option<Solid>>>,
}

impl MeshAsset {
    /// The file's `triangles` as MuJoCo winds them: reversed when the scale mirrors the mesh (an odd
    /// number of negative factors), so that they still face outwards (an `exact` volume stays positive).
    fn triangles(&self, triangles: &[[u32; 3]]) -> Vec<[u32; 3]> {
        let mirrored = self.scale.iter().product::<f64>() < 0.0;
        triangles
            .iter()
            .map(|&[a, b, c]| if mirrored { [a, c, b] } else { [a, b, c] })
            .collect()
    }

    /// The file's `points` as MuJoCo holds them, in the frame of the geoms that use the mesh: single-
    /// precision floats (an OBJ's decimals are read into floats; STL is floats already), moved by the
    /// inverse of `refpos`/`refquat`, then scaled. The same rounding gives MuJoCo's mass to 1e-9.
    fn vertices(&self, points: &[[f64; 3]]) -> Vec<[f64; 3]> {
        points
            .iter()
            .map(|p| {
                let read = self
                    .reference
                    .inverse_transform_point(&[0, 1, 2].map(|k| f64::from(p[k] as f32)).into());
                [0, 1, 2].map(|k| read[k] * self.scale[k])
            })
            .collect()
    }
}

/// The shape of a primitive geom of MuJoCo type `kind` and `size` (`None` for types without one).
fn primitive_geometry(kind: &str, [a, b, c]: [f64; 3]) -> Option<Geometry> {
    match kind {
        "sphere" => Some(Geometry::Sphere { radius: a }),
        "capsule" => Some(Geometry::Capsule {
            radius: a,
            length: 2.0 * b,
        }),
        "cylinder" => Some(Geometry::Cylinder {
            radius: a,
            length: 2.0 * b,
        }),
        "box" => Some(Geometry::Box {
            size: [2.0 * a, 2.0 * b, 2.0 * c],
        }),
        _ => None,
    }
}

/// A body's contents, `<frame>`s flattened.
#[derive(Default)]
struct Contents<'a> {
    joints: Vec<(El<'a>, String)>,
    geoms: Vec<(El<'a>, String, Isometry3<f64>)>,
    inertial: Option<El<'a>>,
    bodies: Vec<(El<'a>, String, Isometry3<f64>)>,
}

/// A world plane tilted by more than this (degrees) is a slope the stability analysis does not model.
const PLANE_TILT_DEG: f64 = 0.01;

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

    /// The model's gravity: the last `<option gravity>`, zero when an `<option><flag gravity="disable">`
    /// says so (MuJoCo then applies none); `None` when the file declares nothing. A U040 when it is not
    /// the standard one.
    fn gravity(&mut self, sections: &[El<'a>]) -> Option<Spanned<[f64; 3]>> {
        let mut gravity = None;
        let mut disabled = None;
        for option in sections.iter().filter(|s| s.tag() == "option") {
            if let Some(text) = option.attr("gravity") {
                let span = self.reader.attr_span(*option, "gravity");
                match numbers(text).map(<[f64; 3]>::try_from) {
                    Ok(Ok(value)) if value.iter().all(|v| v.is_finite()) => {
                        gravity = Some(Spanned { value, span });
                    }
                    _ => self.reader.report(
                        &rules::MJCF_INVALID_VALUE,
                        span,
                        "<option gravity>: 3 finite numbers expected".to_string(),
                    ),
                }
            }
            for flag in option.node.children().filter(|n| n.has_tag_name("flag")) {
                let flag = El {
                    file: option.file,
                    node: flag,
                };
                if flag.attr("gravity").map(str::trim) == Some("disable") {
                    disabled = Some(Spanned {
                        value: [0.0; 3],
                        span: self.reader.attr_span(flag, "gravity"),
                    });
                }
            }
        }
        let off = disabled.is_some();
        let gravity = disabled.or(gravity)?;
        let standard = Vector3::from(STANDARD_GRAVITY);
        let [x, y, z] = gravity.value;
        if (Vector3::new(x, y, z) - standard).norm() > 1e-9 {
            let how = if off {
                "disabled (<flag gravity=\"disable\">)".to_string()
            } else {
                format!("({x}, {y}, {z}) m/s² (<option gravity>)")
            };
            self.reader.report(
                &rules::MODEL_GRAVITY,
                gravity.span,
                format!("the model's gravity is {how}, not the standard (0, 0, -9.81): gravity torques, payload and stability follow it, as MuJoCo simulates it"),
            );
        }
        Some(gravity)
    }

    /// A geom's `(contype, conaffinity)` bit masks (1 and 1 unless written), as the integers MuJoCo reads.
    fn contact_masks(&mut self, el: El<'a>, class: &str) -> (u32, u32) {
        let contype = self.scalar(el, class, "contype", 1.0).max(0.0) as u32;
        let conaffinity = self.scalar(el, class, "conaffinity", 1.0).max(0.0) as u32;
        (contype, conaffinity)
    }

    /// The planes of the world among its `geoms`, with a U033 for each that is not horizontal: the
    /// stability analysis stands a floating robot on horizontal ground under its lowest point, which a
    /// horizontal plane's height does not change (the robot settles onto it), but a slope would.
    fn world_planes(&mut self, geoms: &[(El<'a>, String, Isometry3<f64>)]) -> Vec<WorldPlane> {
        let mut planes = Vec::new();
        for (el, class, frame) in geoms {
            if self.value(*el, class, "type").map(|v| v.text.trim()) != Some("plane") {
                continue;
            }
            let at = frame * self.placement(*el, class);
            let normal = at * Vector3::z();
            let tilt = normal.z.clamp(-1.0, 1.0).acos().to_degrees();
            if tilt > PLANE_TILT_DEG {
                let name = el.attr("name").map_or(String::new(), |n| format!(" '{n}'"));
                self.note(
                    *el,
                    format!("world plane{name} is tilted by {tilt:.1}°: the stability analysis assumes horizontal ground and does not use the tilt (--deep's drop test does)"),
                );
            }
            let (contype, conaffinity) = self.contact_masks(*el, class);
            planes.push(WorldPlane {
                name: el.attr("name").map(str::to_string),
                span: self.reader.span(*el),
                point: at.translation.vector.into(),
                normal: normal.into(),
                bits: (contype, conaffinity),
            });
        }
        planes
    }

    fn problem(&mut self, rule: &'static Rule, el: El<'_>, message: String) {
        let span = self.reader.span(el);
        self.reader.report(rule, span, message);
    }

    fn note(&mut self, el: El<'_>, message: String) {
        self.problem(&rules::MJCF_NOT_READ, el, message);
    }

    /// Attribute `name` of `el`: written on it, else given by its class.
    fn value(&self, el: El<'a>, class: &str, name: &str) -> Option<Value<'a>> {
        match el.node.attribute_node(name) {
            Some(a) => Some(Value {
                text: a.value(),
                span: self.reader.files().span(el.file, a.range_value()),
            }),
            None => self.defaults.get(class, el.tag(), name).or_else(|| {
                // One default actuator per class, whichever element kind wrote it (MuJoCo).
                ACTUATOR_KINDS
                    .contains(&el.tag())
                    .then(|| {
                        ACTUATOR_KINDS
                            .iter()
                            .find_map(|kind| self.defaults.get(class, kind, name))
                    })
                    .flatten()
            }),
        }
    }

    /// `{prefix}range` when `{prefix}limited` says it applies (`auto`: when written and `autolimits`),
    /// with the range's span.
    fn range(&mut self, el: El<'a>, class: &str, prefix: &str) -> Option<((f64, f64), Span)> {
        let name = format!("{prefix}range");
        let written = self.value(el, class, &name);
        let on = match self.word(
            el,
            class,
            &format!("{prefix}limited"),
            &["auto", "true", "false"],
        ) {
            "true" => true,
            "false" => false,
            _ => written.is_some() && self.compiler.auto_limits,
        };
        let span = written.filter(|_| on)?.span;
        let [lo, hi] = self.vector(el, class, &name, [0.0, 0.0]);
        Some(((lo, hi), span))
    }

    /// The class of `el`: its `class`, else `inherited` (a U030 when the class does not exist).
    fn class_of(&mut self, el: El<'a>, inherited: &str) -> String {
        match el.attr("class") {
            Some(class) if self.defaults.has(class) => class.to_string(),
            Some(class) => {
                let span = self.reader.attr_span(el, "class");
                self.reader.report(
                    &rules::MJCF_STRUCTURE,
                    span,
                    format!("class '{class}' is not a <default> class of this model (MuJoCo refuses it)"),
                );
                inherited.to_string()
            }
            None => inherited.to_string(),
        }
    }

    /// The class the children of `el` (a body or frame) take: its `childclass`, else `inherited` (a U030
    /// when the class does not exist).
    fn child_class(&mut self, el: El<'a>, inherited: &str) -> String {
        match el.attr("childclass") {
            Some(class) if self.defaults.has(class) => class.to_string(),
            Some(class) => {
                let span = self.reader.attr_span(el, "childclass");
                self.reader.report(
                    &rules::MJCF_STRUCTURE,
                    span,
                    format!("childclass '{class}' is not a <default> class of this model (MuJoCo refuses it)"),
                );
                inherited.to_string()
            }
            None => inherited.to_string(),
        }
    }

    /// The numbers of attribute `name` (`count` of them), else `fallback`; a U032 when they do not parse.
    fn vector<const N: usize>(
        &mut self,
        el: El<'a>,
        class: &str,
        name: &str,
        fallback: [f64; N],
    ) -> [f64; N] {
        let Some(value) = self.value(el, class, name) else {
            return fallback;
        };
        match numbers(value.text).map(<[f64; N]>::try_from) {
            Ok(Ok(v)) => v,
            Ok(Err(v)) => {
                self.reader.report(
                    &rules::MJCF_INVALID_VALUE,
                    value.span,
                    format!(
                        "<{} {name}>: {N} numbers expected, {} written",
                        el.tag(),
                        v.len()
                    ),
                );
                fallback
            }
            Err(why) => {
                self.reader.report(
                    &rules::MJCF_INVALID_VALUE,
                    value.span,
                    format!("<{} {name}>: {why}", el.tag()),
                );
                fallback
            }
        }
    }

    /// The numbers of attribute `name`, however many; a U032 when they do not parse.
    fn list(&mut self, el: El<'a>, class: &str, name: &str) -> Option<Vec<f64>> {
        let value = self.value(el, class, name)?;
        match numbers(value.text) {
            Ok(v) => Some(v),
            Err(why) => {
                self.reader.report(
                    &rules::MJCF_INVALID_VALUE,
                    value.span,
                    format!("<{} {name}>: {why}", el.tag()),
                );
                None
            }
        }
    }

    fn scalar(&mut self, el: El<'a>, class: &str, name: &str, fallback: f64) -> f64 {
        self.vector(el, class, name, [fallback])[0]
    }

    /// A keyword attribute among `words` (the first when unwritten); a U032 names the words.
    fn word(
        &mut self,
        el: El<'a>,
        class: &str,
        name: &str,
        words: &[&'static str],
    ) -> &'static str {
        let Some(value) = self.value(el, class, name) else {
            return words[0];
        };
        match keyword(value.text.trim(), words) {
            Some(i) => words[i],
            None => {
                self.reader.report(
                    &rules::MJCF_INVALID_VALUE,
                    value.span,
                    format!(
                        "<{} {name}=\"{}\">: expected one of {}",
                        el.tag(),
                        value.text,
                        words.join(", ")
                    ),
                );
                words[0]
            }
        }
    }

    /// `pos` and the orientation of `el` (at most one of [`FORMS`]) as a transform.
    fn placement(&mut self, el: El<'a>, class: &str) -> Isometry3<f64> {
        let pos = self.vector(el, class, "pos", [0.0; 3]);
        let rotation = self.rotation(el, class);
        Isometry3::from_parts(Translation3::from(Vector3::from(pos)), rotation)
    }

    fn rotation(&mut self, el: El<'a>, class: &str) -> UnitQuaternion<f64> {
        let written: Vec<(&str, Value<'a>)> = FORMS
            .iter()
            .filter_map(|form| self.value(el, class, form).map(|v| (*form, v)))
            .collect();
        let Some((form, value)) = written.first().copied() else {
            return UnitQuaternion::identity();
        };
        if written.len() > 1 {
            let names: Vec<&str> = written.iter().map(|(f, _)| *f).collect();
            self.reader.report(
                &rules::MJCF_STRUCTURE,
                value.span,
                format!(
                    "<{}> has more than one orientation ({}): MuJoCo refuses it",
                    el.tag(),
                    names.join(", ")
                ),
            );
        }
        let rotation = numbers(value.text)
            .and_then(|values| orientation::rotation(form, &values, &self.compiler));
        match rotation {
            Ok(r) => r,
            Err(why) => {
                self.reader.report(
                    &rules::MJCF_INVALID_VALUE,
                    value.span,
                    format!("<{} {form}>: {why}", el.tag()),
                );
                UnitQuaternion::identity()
            }
        }
    }

    fn assets(&mut self, section: El<'a>) {
        for el in self.reader.children(section) {
            if el.tag() != "mesh" {
                continue;
            }
            let class = self.class_of(el, MAIN);
            let Some(file) = self.value(el, &class, "file") else {
                self.note(
                    el,
                    "a <mesh> without a file (inline vertices) is not read: geoms using it have no shape or mass".to_string(),
                );
                continue;
            };
            let name = el.attr("name").map(str::to_string).unwrap_or_else(|| {
                Path::new(file.text)
                    .file_stem()
                    .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
            });
            let scale = self.vector(el, &class, "scale", [1.0; 3]);
            let inertia = self.word(
                el,
                &class,
                "inertia",
                &["legacy", "exact", "convex", "shell"],
            );
            let relative = self.mesh_path(el, file.text);
            let refpos = self.vector(el, &class, "refpos", [0.0; 3]);
            let refquat = self.vector(el, &class, "refquat", [1.0, 0.0, 0.0, 0.0]);
            let rotation = match orientation::rotation("quat", &refquat, &self.compiler) {
                Ok(r) => r,
                Err(why) => {
                    let span = self.reader.attr_span(el, "refquat");
                    self.reader.report(
                        &rules::MJCF_INVALID_VALUE,
                        span,
                        format!("<mesh refquat>: {why}"),
                    );
                    UnitQuaternion::identity()
                }
            };
            self.meshes.insert(
                name,
                MeshAsset {
                    file: relative,
                    span: file.span,
                    scale,
                    volume: match inertia {
                        "legacy" => MeshVolume::Legacy,
                        "shell" => MeshVolume::Shell,
                        _ => MeshVolume::Exact,
                    },
                    convex: inertia == "convex",
                    reference: Isometry3::from_parts(
                        Translation3::from(Vector3::from(refpos)),
                        rotation,
                    ),
                    solid: Rc::default(),
                },
            );
        }
    }

    /// Where MuJoCo finds a mesh file (relative to the model's folder): under `meshdir`, else, for a
    /// mesh declared in an included file, in that file's folder (MuJoCo 4.0 looks there second).
    fn mesh_path(&self, el: El<'a>, file: &str) -> String {
        let under_meshdir = match &self.compiler.mesh_dir {
            Some(dir) if !Path::new(file).is_absolute() => Path::new(dir).join(file),
            _ => PathBuf::from(file),
        };
        let beside_include = self
            .reader
            .files()
            .path(el.file)
            .parent()
            .map(|folder| folder.join(file));
        match beside_include {
            // The included file's path is as it was opened; the asset checks join the result to `dir`.
            Some(path)
                if el.file != 0 && !self.dir.join(&under_meshdir).is_file() && path.is_file() =>
            {
                match path.strip_prefix(&self.dir) {
                    Ok(relative) => relative.to_path_buf(),
                    Err(_) => std::path::absolute(&path).unwrap_or(path),
                }
            }
            _ => under_meshdir,
        }
        .to_string_lossy()
        .into_owned()
    }

    /// The contents of a body (or the world body, or a `<frame>`), frames flattened: `frame` places the
    /// element's frame in the body's, `class` is the childclass in force.
    fn contents(
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

    fn joint_type(&self, el: El<'a>, class: &str) -> &'a str {
        if el.tag() == "freejoint" {
            return "free";
        }
        self.value(el, class, "type")
            .map_or("hinge", |v| v.text.trim())
    }

    /// Build body `el` and, recursively, its children.
    fn body(
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

    /// The name of joint `el`: its `name`, else `joint#N` (N its MuJoCo joint id).
    fn joint_name(&self, el: El<'a>) -> String {
        el.attr("name")
            .map_or_else(|| format!("joint#{}", self.joint_ids), str::to_string)
    }

    /// A joint's numbers (three hinges for a ball joint).
    fn joint(
        &mut self,
        el: El<'a>,
        class: &str,
        body: &str,
        kind: &str,
        top_level: bool,
    ) -> JointSpec {
        let name = self.joint_name(el);
        self.joint_ids += 1;
        let span = self.reader.span(el);
        let name_span = self.reader.attr_span(el, "name");
        let type_span = self.reader.attr_span(el, "type");
        let anchor = Vector3::from(self.vector(el, class, "pos", [0.0; 3]));
        let axis_span = self.value(el, class, "axis").map_or(span, |v| v.span);
        let written_axis = Vector3::from(self.vector(el, class, "axis", [0.0, 0.0, 1.0]));
        let axis = match written_axis.try_normalize(1e-14) {
            Some(a) => a,
            None => {
                self.reader.report(
                    &rules::MJCF_STRUCTURE,
                    axis_span,
                    format!("joint '{name}': the axis is zero (MuJoCo refuses it)"),
                );
                Vector3::z()
            }
        };
        let mut spec = JointSpec {
            names: vec![name.clone()],
            span,
            name_span,
            type_span,
            axis_span,
            anchor,
            axes: vec![axis],
            kind: JointKind::Revolute,
            reference: 0.0,
            limit: None,
            dynamics: None,
        };
        match kind {
            "free" => {
                if !top_level {
                    self.problem(
                        &rules::MJCF_STRUCTURE,
                        el,
                        format!("joint '{name}' in body '{body}' is free, but only a body of the <worldbody> may have a free joint (MuJoCo refuses it)"),
                    );
                }
                spec.kind = JointKind::Floating;
                return spec;
            }
            "ball" => {
                self.note(
                    el,
                    format!("ball joint '{name}' is analysed as three hinges '{name}_x', '{name}_y', '{name}_z' about the body's axes (MuJoCo's three ball dofs at the pose analysed)"),
                );
                spec.names = ["x", "y", "z"]
                    .iter()
                    .map(|a| format!("{name}_{a}"))
                    .collect();
                spec.axes = vec![Vector3::x(), Vector3::y(), Vector3::z()];
                spec.kind = JointKind::Continuous;
                return spec;
            }
            "hinge" | "slide" => {}
            other => {
                self.problem(
                    &rules::MJCF_INVALID_VALUE,
                    el,
                    format!("joint '{name}': type '{other}' is not free, ball, slide or hinge; read as a hinge"),
                );
            }
        }
        let hinge = kind != "slide";
        let degrees = hinge && self.compiler.degrees;
        let to_q = |v: f64| if degrees { v.to_radians() } else { v };
        let reference = to_q(self.scalar(el, class, "ref", 0.0));
        spec.reference = reference;
        let range = self.value(el, class, "range");
        let limited = match self.word(el, class, "limited", &["auto", "true", "false"]) {
            "true" => true,
            "false" => false,
            _ => {
                if range.is_some() && !self.compiler.auto_limits {
                    self.problem(
                        &rules::MJCF_STRUCTURE,
                        el,
                        format!("joint '{name}' has a range but neither limited=\"true\" nor <compiler autolimits=\"true\"> (MuJoCo refuses it)"),
                    );
                }
                range.is_some() && self.compiler.auto_limits
            }
        };
        let bounds = self.vector(el, class, "range", [0.0, 0.0]);
        spec.kind = match (hinge, limited) {
            (true, true) => JointKind::Revolute,
            (true, false) => JointKind::Continuous,
            (false, _) => JointKind::Prismatic,
        };
        let limit_span = range.map_or(span, |r| r.span);
        // An unlimited slide moves freely: as SDFormat writes it, ±1e16 (no travel, not "both limits 0").
        let (lower, upper) = if limited {
            (to_q(bounds[0]) - reference, to_q(bounds[1]) - reference)
        } else {
            (-UNLIMITED_SLIDE, UNLIMITED_SLIDE)
        };
        let bound = |value: f64| {
            (limited || !hinge).then_some(Spanned {
                value,
                span: limit_span,
            })
        };
        spec.limit = Some(Limit {
            span: limit_span,
            lower: bound(lower),
            upper: bound(upper),
            effort: None,
            velocity: None,
        });
        if let Some(range) = self.range(el, class, "actuatorfrc") {
            self.actuator_force.insert(name.clone(), range);
        }
        let damping = self.scalar(el, class, "damping", 0.0);
        let armature = self.scalar(el, class, "armature", 0.0);
        self.joint_facts.insert(
            name.clone(),
            actuators::JointFacts {
                range: limited.then(|| (to_q(bounds[0]), to_q(bounds[1]))),
                written_range: range.is_some().then(|| (to_q(bounds[0]), to_q(bounds[1]))),
                span,
                still: damping == 0.0 && armature == 0.0,
            },
        );
        let friction = self.scalar(el, class, "frictionloss", 0.0);
        spec.dynamics = Some(Dynamics {
            damping: Some(damping),
            friction: Some(friction),
        });
        spec
    }

    /// The mass properties of an `<inertial>`, in the body frame.
    fn inertial(&mut self, el: El<'a>) -> MassProps {
        let mass = self.scalar(el, MAIN, "mass", 0.0);
        let placement = self.placement(el, MAIN);
        let diagonal = self.list(el, MAIN, "diaginertia");
        let full = self.list(el, MAIN, "fullinertia");
        let inertia = match (diagonal.as_deref(), full.as_deref()) {
            (Some([a, b, c]), None) => nalgebra::Matrix3::from_diagonal(&Vector3::new(*a, *b, *c)),
            (None, Some([xx, yy, zz, xy, xz, yz])) => {
                nalgebra::Matrix3::new(*xx, *xy, *xz, *xy, *yy, *yz, *xz, *yz, *zz)
            }
            // Neither: MuJoCo 4.0 takes a zero tensor (a moving body is then refused for mjMINVAL, which
            // refuse_massless_moving_bodies says; a welded one is accepted).
            (None, None) => nalgebra::Matrix3::zeros(),
            _ => {
                self.problem(
                    &rules::MJCF_STRUCTURE,
                    el,
                    "<inertial> takes diaginertia (3 numbers) or fullinertia (6), not both and no other count (MuJoCo refuses it)".to_string(),
                );
                nalgebra::Matrix3::zeros()
            }
        };
        MassProps {
            mass,
            com: Vector3::zeros(),
            inertia,
        }
        .placed(&placement)
    }

    /// A geom's shape (in the link frame: `frame` places the geom's written frame there), collision
    /// filter, mass properties and whether its mesh was read.
    fn geom(&mut self, el: El<'a>, class: &str, frame: &Isometry3<f64>) -> GeomParts {
        let kind = self.word(
            el,
            class,
            "type",
            &[
                "sphere",
                "capsule",
                "ellipsoid",
                "cylinder",
                "box",
                "mesh",
                "plane",
                "hfield",
                "sdf",
            ],
        );
        let mut size = self.list(el, class, "size").unwrap_or_default();
        size.resize(3, 0.0);
        let mut size = [size[0], size[1], size[2]];
        let mut placement = self.placement(el, class);
        if let Some(fromto) = self.value(el, class, "fromto") {
            match numbers(fromto.text).map(<[f64; 6]>::try_from) {
                Ok(Ok([x0, y0, z0, x1, y1, z1])) => {
                    let (a, b) = (Vector3::new(x0, y0, z0), Vector3::new(x1, y1, z1));
                    let d = b - a;
                    let half = d.norm() / 2.0;
                    match kind {
                        "capsule" | "cylinder" => size[1] = half,
                        "box" | "ellipsoid" => size[2] = half,
                        _ => {}
                    }
                    let rotation = d
                        .try_normalize(1e-14)
                        .map_or_else(UnitQuaternion::identity, orientation::z_to);
                    placement = Isometry3::from_parts(Translation3::from((a + b) / 2.0), rotation);
                }
                _ => self.reader.report(
                    &rules::MJCF_INVALID_VALUE,
                    fromto.span,
                    "<geom fromto>: 6 finite numbers expected".to_string(),
                ),
            }
        }
        let mut at = frame * placement;
        let (contype, conaffinity) = self.contact_masks(el, class);
        let collides = (contype != 0 || conaffinity != 0).then_some((contype, conaffinity));
        let group = self.scalar(el, class, "group", 0.0);
        let (lo, hi) = self.compiler.inertia_groups;
        let counts = group >= lo as f64 && group <= hi as f64;
        let span = self.reader.span(el);
        let (geometry, solid) = match kind {
            "mesh" => self.mesh_geom(el, class),
            "plane" => (None, None),
            "hfield" | "sdf" => {
                self.note(el, format!("a {kind} geom is not read: no shape, no mass"));
                (None, None)
            }
            _ if self.value(el, class, "mesh").is_some() => {
                match self.fitted_geom(el, class, kind) {
                    Some((geometry, fitted, solid)) => {
                        at *= fitted;
                        (geometry, Some(solid))
                    }
                    None => (None, None),
                }
            }
            _ => (
                primitive_geometry(kind, size),
                mass::primitive(kind, size, self.shell_inertia(el, class)),
            ),
        };
        // A mesh that cannot be read (the asset checks say why) gives no solid: its explicit `mass` still
        // counts, as a point at the geom's frame (MuJoCo puts it at the mesh's centroid, unknown here).
        let explicit = self
            .value(el, class, "mass")
            .map(|_| self.scalar(el, class, "mass", 0.0));
        let unread = solid.is_none() && (kind == "mesh" || self.value(el, class, "mesh").is_some());
        let mass = match (solid, explicit) {
            (Some(solid), _) if counts => {
                let mass = explicit
                    .unwrap_or_else(|| self.scalar(el, class, "density", 1000.0) * solid.volume);
                Some(solid.with_mass(mass).placed(&at))
            }
            (None, Some(mass)) if counts && unread => Some(MassProps {
                mass,
                com: at.translation.vector,
                inertia: nalgebra::Matrix3::zeros(),
            }),
            _ => None,
        };
        let shape = geometry.map(|geometry| Shape {
            span,
            name: el.attr("name").map(str::to_string),
            origin: pose(&at),
            geometry: Some(Spanned {
                value: geometry,
                span,
            }),
            material: None,
        });
        GeomParts {
            shape,
            collides,
            mass,
            read: !unread,
        }
    }

    /// A mesh geom's shape and solid (the mesh file read through the sandbox and the mesh cache).
    fn mesh_geom(&mut self, el: El<'a>, class: &str) -> (Option<Geometry>, Option<Solid>) {
        let Some(asset) = self.mesh_asset(el, class) else {
            return (None, None);
        };
        if self.shell_inertia(el, class) {
            self.problem(
                &rules::MJCF_STRUCTURE,
                el,
                "shellinertia on a mesh geom (MuJoCo refuses it: \"for mesh geoms, inertia should be specified in the mesh asset\", <mesh inertia=\"shell\">)".to_string(),
            );
        }
        let geometry = Geometry::Mesh {
            filename: Spanned {
                value: asset.file.clone(),
                span: asset.span,
            },
            scale: asset.scale,
        };
        (Some(geometry), self.mesh_solid(&asset))
    }

    /// A primitive geom that names a mesh (`type="capsule" mesh=…`): the primitive MuJoCo fits to the
    /// mesh, its shape and its solid, both in the geom frame. `None` when the mesh cannot be read (the
    /// asset checks say why) or MuJoCo cannot fit it.
    fn fitted_geom(
        &mut self,
        el: El<'a>,
        class: &str,
        kind: &str,
    ) -> Option<(Option<Geometry>, Isometry3<f64>, Solid)> {
        let asset = self.mesh_asset(el, class)?;
        let solid = self.mesh_solid(&asset)?;
        let vertices = if self.compiler.fit_aabb {
            Some(asset.vertices(&load_surface(&self.readable(&asset)?).ok()?.vertices))
        } else {
            None
        };
        let fitscale = self.scalar(el, class, "fitscale", 1.0);
        let Some(fitted) = mass::fit_primitive(kind, &solid, vertices.as_deref(), fitscale) else {
            self.problem(
                &rules::MJCF_STRUCTURE,
                el,
                format!(
                    "a {kind} fitted to mesh '{}' has no positive size (MuJoCo refuses it)",
                    asset.file
                ),
            );
            return None;
        };
        let solid = mass::primitive(kind, fitted.size, self.shell_inertia(el, class))?;
        Some((primitive_geometry(kind, fitted.size), fitted.frame, solid))
    }

    /// Whether a geom's mass is spread over its surface (`shellinertia="true"`, written or from its class).
    fn shell_inertia(&self, el: El<'a>, class: &str) -> bool {
        self.value(el, class, "shellinertia")
            .is_some_and(|v| boolean(v.text) == Some(true))
    }

    /// The `<mesh>` asset a geom's `mesh` attribute names (a finding when it names none).
    fn mesh_asset(&mut self, el: El<'a>, class: &str) -> Option<MeshAsset> {
        let Some(name) = self.value(el, class, "mesh") else {
            self.problem(
                &rules::MJCF_STRUCTURE,
                el,
                "a mesh geom without a mesh attribute (MuJoCo refuses it)".to_string(),
            );
            return None;
        };
        let asset = self.meshes.get(name.text).cloned();
        if asset.is_none() {
            self.reader.report(
                &rules::MJCF_STRUCTURE,
                name.span,
                format!(
                    "mesh '{}' is not an <asset> mesh of this model (MuJoCo refuses it)",
                    name.text
                ),
            );
        }
        asset
    }

    /// The path of a mesh asset's file when the sandbox lets it be read and it is there (the asset
    /// checks report a missing or refused mesh file).
    fn readable(&self, asset: &MeshAsset) -> Option<PathBuf> {
        let path = self.dir.join(&asset.file);
        (self.resolver.sandbox().check_file(&path).is_ok() && path.is_file()).then_some(path)
    }

    /// The solid of a mesh asset, in the frame of the geoms that use it (`None` without a readable file, or
    /// when MuJoCo would refuse the mesh), read on its first use.
    fn mesh_solid(&self, asset: &MeshAsset) -> Option<Solid> {
        *asset.solid.get_or_init(|| self.read_mesh_solid(asset))
    }

    fn read_mesh_solid(&self, asset: &MeshAsset) -> Option<Solid> {
        let path = self.readable(asset)?;
        if asset.convex {
            let data = self.mesh_cache.get(&path);
            let data = data.as_ref().as_ref().ok()?;
            mass::mesh(
                &asset.vertices(&data.hull),
                &asset.triangles(&data.hull_triangles),
                asset.volume,
            )
        } else {
            let surface = load_surface(&path).ok()?;
            mass::mesh(
                &asset.vertices(&surface.vertices),
                &asset.triangles(&surface.triangles),
                asset.volume,
            )
        }
    }

    /// `boundmass`, `boundinertia`, `balanceinertia` and `settotalmass` applied to every body's mass.
    /// A body whose inertia only a compiler setting makes acceptable is a U037.
    fn finish_masses(&mut self) {
        let c = &self.compiler;
        let bounded: Vec<(usize, MassProps)> = self
            .masses
            .iter()
            .map(|(i, p)| {
                (
                    *i,
                    p.bounded(c.bound_mass, c.bound_inertia, c.balance_inertia),
                )
            })
            .collect();
        let rescued: Vec<(usize, &'static str)> = self
            .masses
            .iter()
            .filter_map(|(i, p)| Some((*i, p.rescued_by(c.bound_inertia, c.balance_inertia)?)))
            .collect();
        for (i, setting) in rescued {
            if let Some(link) = self.links.get(i) {
                let span = link.inertial.as_ref().map_or(link.span, |m| m.span);
                let message = format!(
                    "body '{}': MuJoCo accepts its inertia only thanks to <compiler {setting}>; the inertia simulated is the compiler's, not the one written",
                    link.name.value
                );
                self.reader
                    .report(&rules::MJCF_INERTIA_RESCUED, span, message);
            }
        }
        let total: f64 = bounded.iter().map(|(_, p)| p.mass).sum();
        let factor = match c.set_total_mass {
            Some(target) if total > 0.0 => target / total,
            _ => 1.0,
        };
        for (i, props) in bounded {
            let props = props.scaled(factor);
            if let Some(link) = self.links.get_mut(i) {
                let span = link.inertial.as_ref().map_or(link.span, |m| m.span);
                let mut inertial = inertial_of(&props, span);
                // A mesh not read leaves the tensor unknown (not zero): the mass and centre of mass stand.
                if self.unread_geoms.contains(&link.name.value) {
                    inertial.inertia = None;
                }
                link.inertial = Some(inertial);
            }
        }
    }
}

impl Builder<'_, '_> {
    /// U030 for each moving body MuJoCo refuses ("mass and inertia of moving bodies must be larger than
    /// mjMINVAL"): one none of whose weld group (itself and the bodies welded to it) has, on its own, a
    /// mass and all three principal moments of inertia of at least `mjMINVAL`. Not the group's combined
    /// mass or inertia: MuJoCo 4.0 refuses a body of 1 kg with moments (1, 10⁻²⁰, 1) welded to one with
    /// (1, 1, 10⁻²⁰), and three welded point masses (checked in tests/mjcf_mjminval.rs).
    fn refuse_massless_moving_bodies(&mut self) {
        let enough = |link: &str| {
            self.links
                .iter()
                .find(|l| l.name.value == link)
                .and_then(|l| l.inertial.as_ref())
                .is_some_and(|inertial| {
                    let mass = inertial.mass.as_ref().map_or(0.0, |m| m.value);
                    let least = inertial
                        .inertia
                        .as_ref()
                        .and_then(|i| i.principal_moments())
                        .map_or(0.0, |[a, _, _]| a);
                    mass >= mass::MIN_VALUE && least >= mass::MIN_VALUE
                })
        };
        let by_link = contacts::by_link(&self.body_contacts);
        let mut accepted: HashSet<String> = HashSet::new();
        for body in &self.body_contacts {
            if enough(&body.link) || self.unread_geoms.contains(&body.link) {
                accepted.insert(contacts::weld_root(&by_link, &body.link));
            }
        }
        let refused: Vec<(Span, String)> = self
            .body_contacts
            .iter()
            .filter(|b| b.moving && !accepted.contains(&b.link))
            .filter_map(|b| {
                let link = self.links.iter().find(|l| l.name.value == b.link)?;
                Some((
                    link.span,
                    format!(
                        "body '{}' moves (it has a joint) but neither it nor a body welded to it has a mass and three principal moments of inertia of at least 1e-15 (mjMINVAL): MuJoCo refuses the model (\"mass and inertia of moving bodies must be larger than mjMINVAL\")",
                        b.link
                    ),
                ))
            })
            .collect();
        for (span, message) in refused {
            self.reader.report(&rules::MJCF_STRUCTURE, span, message);
        }
    }
}

/// What a geom element turns into.
struct GeomParts {
    /// Its shape in the link frame.
    shape: Option<Shape>,
    /// Its `contype` and `conaffinity` when it collides (not both 0).
    collides: Option<(u32, u32)>,
    /// Its mass properties when it counts for the body's mass.
    mass: Option<MassProps>,
    /// Whether its mesh (if it names one) was read.
    read: bool,
}

/// What a joint element turns into: one URDF joint per axis (three for a ball).
struct JointSpec {
    names: Vec<String>,
    span: Span,
    name_span: Span,
    type_span: Span,
    axis_span: Span,
    anchor: Vector3<f64>,
    axes: Vec<Vector3<f64>>,
    kind: JointKind,
    /// `ref` (radians or metres): MuJoCo's `qpos0` of a hinge or slide joint, 0 for the others.
    reference: f64,
    limit: Option<Limit>,
    dynamics: Option<Dynamics>,
}

fn blank_joint() -> Joint {
    Joint {
        name: Spanned {
            value: String::new(),
            span: Span::default(),
        },
        span: Span::default(),
        kind: None,
        origin: Pose::default(),
        parent: None,
        child: None,
        axis: None,
        limit: None,
        dynamics: None,
        mimic: None,
        safety_controller: None,
        calibration: None,
    }
}

/// Whether an `<option><flag>` among `sections` turns MuJoCo's contacts off (`contact` or `constraint`
/// disabled).
fn contacts_disabled(sections: &[El<'_>]) -> bool {
    sections
        .iter()
        .filter(|s| s.tag() == "option")
        .flat_map(|option| option.node.children().filter(|n| n.has_tag_name("flag")))
        .any(|flag| {
            ["contact", "constraint"]
                .iter()
                .any(|name| flag.attribute(*name).map(str::trim) == Some("disable"))
        })
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

/// Mass properties (in the link frame) as a URDF inertial at their centre, axes of the link.
fn inertial_of(props: &MassProps, span: Span) -> Inertial {
    let m = props.inertia;
    Inertial {
        span,
        origin: Pose {
            xyz: props.com.into(),
            ..Pose::default()
        },
        mass: Some(Spanned {
            value: props.mass,
            span,
        }),
        inertia: Some(Inertia {
            span,
            ixx: m[(0, 0)],
            ixy: m[(0, 1)],
            ixz: m[(0, 2)],
            iyy: m[(1, 1)],
            iyz: m[(1, 2)],
            izz: m[(2, 2)],
            values: [span; 6],
        }),
    }
}
