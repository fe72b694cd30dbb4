//! One `<model>` — its links, joints, frames, nested models and includes — read into a flat scene of
//! named frames, every name scoped from the analysed model (`arm::link` for link `link` of nested model
//! `arm`). Poses stay as written (relative to a named frame); [`super::frames`] resolves them.

use std::collections::HashMap;

use roxmltree::{Document, Node};

use super::pose::{self, Transform};
use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::diagnostics::span::{Span, Spanned};
use crate::input::xml_files::{FindingSink, IncludeTarget, XmlFiles};

/// An SDFormat version, `(major, minor)`.
pub type Version = (u32, u32);

/// First version with `relative_to`, `attached_to`, `<frame>` semantics and joint axes in the joint frame.
pub const FRAME_SEMANTICS: Version = (1, 7);

/// Deepest nesting of `<model>`s followed (includes count too).
const MAX_NESTING: usize = 32;

/// Most `<model>`s read in one file, includes expanded: a file included a thousand times by a file included
/// a thousand times would otherwise be read a million times (untrusted input: bounded work).
pub const MAX_MODELS: usize = 10_000;

pub use crate::input::xml_files::El;

/// A reference to a frame by name, resolved to its scoped name.
#[derive(Clone, Debug)]
pub struct Ref {
    /// The scoped name (`""` for the analysed model's frame, `world` for the world).
    pub name: String,
    /// As written, for messages.
    pub written: String,
    /// The attribute or element that names it (the element owning it for defaults).
    pub span: Span,
    /// Frame used when the name does not exist (the enclosing model's frame).
    pub fallback: String,
}

/// What a frame is.
#[derive(Clone, Debug)]
pub enum Kind {
    /// A `<link>`.
    Link,
    /// A `<joint>`: attached to its child.
    Joint {
        /// `<child>`.
        child: Ref,
    },
    /// A `<frame>`.
    Frame {
        /// `attached_to` (default: the enclosing model frame).
        attached_to: Ref,
    },
    /// A nested `<model>`: attached to its canonical link.
    Model {
        /// `canonical_link`, or its first link.
        canonical: Option<Ref>,
    },
}

/// One named frame of the scene.
#[derive(Clone, Debug)]
pub struct FrameDef {
    /// What it is.
    pub kind: Kind,
    /// Its `<pose>` relative to `relative_to`.
    pub pose: Transform,
    /// The frame its pose is relative to.
    pub relative_to: Ref,
    /// The element defining it.
    pub span: Span,
}

/// A `<link>` to turn into a URDF link.
#[derive(Clone, Debug)]
pub struct LinkDef<'a> {
    /// Scoped name.
    pub name: String,
    /// The `name` attribute.
    pub name_span: Span,
    /// The element.
    pub el: El<'a>,
    /// Its model's scope.
    pub scope: Scope,
    /// Version of its file.
    pub version: Version,
}

/// A `<joint>` to turn into a URDF joint.
#[derive(Clone, Debug)]
pub struct JointDef<'a> {
    /// Scoped name.
    pub name: String,
    /// The `name` attribute.
    pub name_span: Span,
    /// The element.
    pub el: El<'a>,
    /// Its model's scope.
    pub scope: Scope,
    /// Version of its file.
    pub version: Version,
    /// `<parent>`.
    pub parent: Option<Ref>,
    /// `<child>`.
    pub child: Option<Ref>,
}

/// The analysed model, flattened.
#[derive(Debug, Default)]
pub struct Scene<'a> {
    /// Scoped name → frame (links, joints, frames, nested models). The model frame is `""`.
    pub frames: HashMap<String, FrameDef>,
    /// Links in document order.
    pub links: Vec<LinkDef<'a>>,
    /// Joints in document order.
    pub joints: Vec<JointDef<'a>>,
    /// The model's canonical link.
    pub canonical: Option<Ref>,
    /// The model's name.
    pub name: Option<Spanned<String>>,
    /// Where a finding about the whole model points: its `name` (else the `<model>` element).
    pub span: Span,
    /// The model's pose in the world.
    pub model_pose: Transform,
    /// `<static>true</static>` (or the including `<include>` says so).
    pub is_static: bool,
    /// The `<static>` element, when written.
    pub static_span: Option<Span>,
}

/// What an `<include>` overrides in the model it pulls in.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    /// `<name>`.
    pub name: Option<Spanned<String>>,
    /// `<pose>`, with its `relative_to`.
    pub pose: Option<(Transform, Option<Ref>, Span)>,
    /// `<static>`.
    pub is_static: Option<(bool, Span)>,
}

/// Where the names written inside one `<model>` live: the prefix of the names it defines and its model
/// frame. A nested model `arm` defines `arm::link` and has frame `arm`; a merge-included model
/// (`<include merge="true">`, SDFormat 1.9) defines its names in the including model's scope, and its
/// model frame is the proxy frame `_merged__NAME__model__` there, as libsdformat names it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Scope {
    /// Prefix of the names it defines: `""` or `arm::`.
    pub prefix: String,
    /// Scoped name of its model frame: `""` for the analysed model.
    pub frame: String,
}

impl Scope {
    /// The scope of nested model `name`.
    fn nested(&self, name: &str) -> Scope {
        Scope {
            prefix: format!("{}{name}::", self.prefix),
            frame: format!("{}{name}", self.prefix),
        }
    }

    /// The scope of model `name` merge-included into this one.
    fn merged(&self, name: &str) -> Scope {
        Scope {
            prefix: self.prefix.clone(),
            frame: format!("{}_merged__{name}__model__", self.prefix),
        }
    }

    /// The scoped name of `written` referred to from this scope: `__model__` is its model frame, `world`
    /// the world.
    pub fn resolve(&self, written: &str) -> String {
        if written == "world" {
            "world".to_string()
        } else if written == "__model__" {
            self.frame.clone()
        } else if let Some(model) = written.strip_suffix("::__model__") {
            format!("{}{model}", self.prefix)
        } else {
            format!("{}{written}", self.prefix)
        }
    }

    /// Whether this is the analysed model's scope.
    fn is_root(&self) -> bool {
        self.frame.is_empty() && self.prefix.is_empty()
    }
}

/// Where findings go, with the files their spans point into, and the SDFormat values read on the way.
pub struct Sink<'a> {
    base: FindingSink<'a>,
}

/// A sink is a finding sink (spans, `report`, `files`, `findings`) that also reads SDFormat values.
impl<'a> std::ops::Deref for Sink<'a> {
    type Target = FindingSink<'a>;
    fn deref(&self) -> &FindingSink<'a> {
        &self.base
    }
}

impl std::ops::DerefMut for Sink<'_> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.base
    }
}

impl<'a> Sink<'a> {
    /// A sink for findings in `files`.
    pub fn new(files: &'a XmlFiles) -> Self {
        Sink {
            base: FindingSink::new(files),
        }
    }

    /// The findings so far.
    pub fn into_findings(self) -> Vec<Finding> {
        self.base.findings
    }

    /// `value`, or a U029 finding at `el` and `None`.
    pub fn value<T>(&mut self, el: El<'_>, value: Result<T, String>) -> Option<T> {
        match value {
            Ok(v) => Some(v),
            Err(why) => {
                let span = self.span(el);
                self.report(&rules::SDF_INVALID_VALUE, span, why);
                None
            }
        }
    }

    /// The `<pose>` child of `el` (identity when absent or unreadable) and its explicit `relative_to`
    /// (read from SDFormat 1.7 on), resolved in `scope`.
    pub fn pose_of(
        &mut self,
        el: El<'_>,
        scope: &Scope,
        version: Version,
    ) -> (Transform, Option<Ref>, Span) {
        let Some(pose_el) = el.child("pose") else {
            return (Transform::identity(), None, self.span(el));
        };
        let span = self.span(pose_el);
        let node = pose_el.node;
        let transform = pose::pose_text(
            pose_el.text(),
            node.attribute("rotation_format"),
            node.attribute("degrees"),
        );
        let transform = self
            .value(pose_el, transform)
            .unwrap_or_else(Transform::identity);
        let relative_to = node
            .attribute("relative_to")
            .filter(|r| !r.is_empty() && version >= FRAME_SEMANTICS)
            .map(|r| self.reference(pose_el, "relative_to", r, scope));
        (transform, relative_to, span)
    }

    /// A reference written in attribute `attr` of `el`.
    pub fn reference(&self, el: El<'_>, attr: &str, written: &str, scope: &Scope) -> Ref {
        Ref {
            name: scope.resolve(written),
            written: written.to_string(),
            span: self.attr_span(el, attr),
            fallback: scope.frame.clone(),
        }
    }
}

/// Reads models into a [`Scene`], collecting findings.
pub struct Collector<'a> {
    /// Findings and files.
    pub sink: Sink<'a>,
    /// Each file parsed (`None` for a file that does not parse; the load stage already said so).
    pub docs: &'a [Option<Document<'a>>],
    /// Each file's version.
    pub versions: &'a [Version],
    /// The scene being built.
    pub scene: Scene<'a>,
    /// `<model>`s read so far (nested and included ones too), against [`MAX_MODELS`].
    pub models_read: usize,
}

impl<'a> Collector<'a> {
    /// A reference written as the text of element `el`.
    fn text_reference(&self, el: El<'a>, scope: &Scope) -> Ref {
        Ref {
            name: scope.resolve(el.text()),
            written: el.text().to_string(),
            span: self.sink.span(el),
            fallback: scope.frame.clone(),
        }
    }

    /// A default reference to `name` (no attribute written).
    fn implicit(&self, name: String, span: Span, scope: &Scope) -> Ref {
        Ref {
            written: name.clone(),
            name,
            span,
            fallback: scope.frame.clone(),
        }
    }

    /// Register frame `name`; a name used twice in one scope is U020.
    fn define(&mut self, name: &str, def: FrameDef, legacy: bool) {
        if self.scene.frames.contains_key(name) {
            if !legacy {
                self.sink.report(
                    &rules::SDF_STRUCTURE,
                    def.span,
                    format!("the name '{name}' is used by two elements of one model (links, joints, frames and nested models share one name space)"),
                );
            }
            return;
        }
        self.scene.frames.insert(name.to_string(), def);
    }

    /// The `name` attribute of `el`, checked: present, not reserved.
    fn name(&mut self, el: El<'a>, what: &str) -> Option<(String, Span)> {
        let span = self.sink.attr_span(el, "name");
        let Some(name) = el.node.attribute("name").filter(|n| !n.is_empty()) else {
            let at = self.sink.span(el);
            self.sink.report(
                &rules::SDF_STRUCTURE,
                at,
                format!("<{what}> without a name attribute"),
            );
            return None;
        };
        if name == "world"
            || (name.starts_with("__") && name.ends_with("__"))
            || name.contains("::")
        {
            self.sink.report(
                &rules::SDF_STRUCTURE,
                span,
                format!("<{what} name=\"{name}\">: the name is reserved ('world', '__…__') or holds the scope separator '::'"),
            );
        }
        Some((name.to_string(), span))
    }

    /// Read model `el` whose contents live in `scope` ([`Scope::default`] for the analysed model), inside
    /// the model of scope `parent` (the analysed model's own for it).
    pub fn model(
        &mut self,
        el: El<'a>,
        scope: &Scope,
        parent: &Scope,
        overrides: Overrides,
        depth: usize,
    ) {
        self.models_read += 1;
        if self.models_read > MAX_MODELS {
            if self.models_read == MAX_MODELS + 1 {
                let span = self.sink.span(el);
                self.sink.report(
                    &rules::SDF_STRUCTURE,
                    span,
                    format!("more than {MAX_MODELS} models once includes are expanded: this one and the rest are not read"),
                );
            }
            return;
        }
        let version = self
            .versions
            .get(el.file)
            .copied()
            .unwrap_or(FRAME_SEMANTICS);
        let legacy = version < FRAME_SEMANTICS;
        let (own_pose, own_relative, pose_span) = self.sink.pose_of(el, parent, version);
        let (pose, relative_to, pose_span) =
            overrides
                .pose
                .clone()
                .unwrap_or((own_pose, own_relative, pose_span));
        let static_el = el.child("static");
        let own_static = static_el
            .and_then(|s| {
                let value = pose::boolean(s.text(), "<static>");
                self.sink.value(s, value)
            })
            .map(|v| (v, static_el.map(|s| self.sink.span(s)).unwrap_or_default()));
        let is_static = overrides.is_static.or(own_static);
        let span = self.sink.span(el);
        if scope.is_root() {
            // A finding about the whole robot points at the model's name, not at the whole model.
            self.scene.span = self.sink.attr_span(el, "name");
            self.scene.model_pose = pose;
            self.scene.name = overrides.name.clone().or_else(|| {
                el.node.attribute("name").map(|n| Spanned {
                    value: n.to_string(),
                    span: self.sink.attr_span(el, "name"),
                })
            });
            if let Some((value, at)) = is_static {
                self.scene.is_static = value;
                self.scene.static_span = Some(at);
            }
        } else if is_static.is_some_and(|(value, _)| value) {
            let at = is_static.map_or(span, |(_, at)| at);
            self.sink.report(
                &rules::SDF_NOT_READ,
                at,
                format!(
                    "nested model '{}' is static: analysed as part of the moving model",
                    scope.frame
                ),
            );
        }
        if depth > MAX_NESTING {
            self.sink.report(
                &rules::SDF_STRUCTURE,
                span,
                format!("models nested more than {MAX_NESTING} deep: the inner ones are not read"),
            );
            return;
        }
        let mut first_link: Option<Ref> = None;
        let mut first_nested: Option<String> = None;
        for child in el.node.children().filter(Node::is_element) {
            let child = El {
                file: el.file,
                node: child,
            };
            match child.node.tag_name().name() {
                "link" => {
                    if let Some(name) = self.link(child, scope, version) {
                        first_link.get_or_insert(name);
                    }
                }
                "joint" => self.joint(child, scope, version),
                "frame" => self.frame(child, scope, version),
                "model" => {
                    if let Some((name, _)) = self.name(child, "model") {
                        let inner = scope.nested(&name);
                        self.model(child, &inner, scope, Overrides::default(), depth + 1);
                        first_nested.get_or_insert(inner.frame);
                    }
                }
                "include" => {
                    if let Some(name) = self.include(child, scope, depth) {
                        first_nested.get_or_insert(name);
                    }
                }
                _ => {}
            }
        }
        let canonical = match el
            .node
            .attribute("canonical_link")
            // Unset or empty: the first link, as the spec says.
            .filter(|c| !legacy && !c.is_empty())
        {
            Some(written) => Some(self.sink.reference(el, "canonical_link", written, scope)),
            None => first_link.or_else(|| {
                let nested = first_nested?;
                match &self.scene.frames.get(&nested)?.kind {
                    Kind::Model { canonical } => canonical.clone(),
                    _ => None,
                }
            }),
        };
        if canonical.is_none() {
            self.sink.report(
                &rules::SDF_STRUCTURE,
                span,
                format!(
                    "model '{}' has no link (sdformat: a model must have at least one link)",
                    el.node.attribute("name").unwrap_or("")
                ),
            );
        }
        if scope.is_root() {
            self.scene.canonical = canonical;
        } else {
            let relative_to =
                relative_to.unwrap_or_else(|| self.implicit(parent.frame.clone(), span, parent));
            let def = FrameDef {
                kind: Kind::Model { canonical },
                pose,
                relative_to,
                span: pose_span,
            };
            self.define(&scope.frame, def, legacy);
        }
    }

    /// A `<link>`: its frame and the link to build; returns a reference to it.
    fn link(&mut self, el: El<'a>, scope: &Scope, version: Version) -> Option<Ref> {
        let (name, name_span) = self.name(el, "link")?;
        let full = format!("{}{name}", scope.prefix);
        let (pose, relative_to, pose_span) = self.sink.pose_of(el, scope, version);
        let relative_to =
            relative_to.unwrap_or_else(|| self.implicit(scope.frame.clone(), pose_span, scope));
        self.define(
            &full,
            FrameDef {
                kind: Kind::Link,
                pose,
                relative_to,
                span: pose_span,
            },
            version < FRAME_SEMANTICS,
        );
        self.scene.links.push(LinkDef {
            name: full.clone(),
            name_span,
            el,
            scope: scope.clone(),
            version,
        });
        Some(self.implicit(full, name_span, scope))
    }

    /// A `<joint>`: its frame (attached to its child) and the joint to build.
    fn joint(&mut self, el: El<'a>, scope: &Scope, version: Version) {
        let Some((name, name_span)) = self.name(el, "joint") else {
            return;
        };
        let full = format!("{}{name}", scope.prefix);
        let parent = el.child("parent").map(|p| self.text_reference(p, scope));
        let child = el.child("child").map(|c| self.text_reference(c, scope));
        let span = self.sink.span(el);
        for (tag, found) in [("parent", &parent), ("child", &child)] {
            if found.as_ref().is_none_or(|r| r.written.is_empty()) {
                self.sink.report(
                    &rules::SDF_STRUCTURE,
                    span,
                    format!("joint '{full}' has no <{tag}>"),
                );
            }
        }
        if el.node.attribute("type").is_none() {
            self.sink.report(
                &rules::SDF_STRUCTURE,
                span,
                format!("joint '{full}' has no type attribute"),
            );
        }
        let (pose, relative_to, pose_span) = self.sink.pose_of(el, scope, version);
        if let Some(child) = child.clone().filter(|c| !c.written.is_empty()) {
            let relative_to = relative_to.unwrap_or_else(|| child.clone());
            self.define(
                &full,
                FrameDef {
                    kind: Kind::Joint { child },
                    pose,
                    relative_to,
                    span: pose_span,
                },
                version < FRAME_SEMANTICS,
            );
        }
        self.scene.joints.push(JointDef {
            name: full,
            name_span,
            el,
            scope: scope.clone(),
            version,
            parent,
            child,
        });
    }

    /// A `<frame>` (SDFormat 1.7 on).
    fn frame(&mut self, el: El<'a>, scope: &Scope, version: Version) {
        if version < FRAME_SEMANTICS {
            let span = self.sink.span(el);
            self.sink.report(
                &rules::SDF_NOT_READ,
                span,
                format!(
                    "<frame> in an SDFormat {}.{} file: frame semantics start with 1.7; not read",
                    version.0, version.1
                ),
            );
            return;
        }
        let Some((name, _)) = self.name(el, "frame") else {
            return;
        };
        let attached_to = match el.node.attribute("attached_to").filter(|a| !a.is_empty()) {
            Some(written) => self.sink.reference(el, "attached_to", written, scope),
            None => self.implicit(scope.frame.clone(), self.sink.span(el), scope),
        };
        let (pose, relative_to, pose_span) = self.sink.pose_of(el, scope, version);
        let relative_to = relative_to.unwrap_or_else(|| attached_to.clone());
        self.define(
            &format!("{}{name}", scope.prefix),
            FrameDef {
                kind: Kind::Frame { attached_to },
                pose,
                relative_to,
                span: pose_span,
            },
            false,
        );
    }

    /// An `<include>` inside a model: the included model nested under its (possibly overridden) name,
    /// or with `merge="true"` its contents in this scope, placed by its proxy model frame. Returns the
    /// scoped name of the included model's frame.
    fn include(&mut self, el: El<'a>, scope: &Scope, depth: usize) -> Option<String> {
        let (model, overrides) = self.included_model(el, scope)?;
        let name = overrides
            .name
            .as_ref()
            .map(|n| n.value.clone())
            .or_else(|| model.node.attribute("name").map(str::to_string))?;
        let inner = if el.node.attribute("merge") == Some("true") {
            scope.merged(&name)
        } else {
            scope.nested(&name)
        };
        self.model(model, &inner, scope, overrides, depth + 1);
        Some(inner.frame)
    }

    /// The `<model>` an `<include>` pulls in and what the include overrides; a finding when it cannot be
    /// read.
    pub fn included_model(&mut self, el: El<'a>, scope: &Scope) -> Option<(El<'a>, Overrides)> {
        let span = self.sink.span(el);
        let file = match self.sink.files.include(span) {
            Some(IncludeTarget::File(file)) => *file,
            Some(IncludeTarget::Refused(why)) => {
                let why = why.clone();
                self.sink.report(&rules::ACCESS_REFUSED, span, why);
                return None;
            }
            Some(IncludeTarget::Unresolved(why)) => {
                let why = why.clone();
                self.sink.report(
                    &rules::SDF_INCLUDE_UNRESOLVED,
                    span,
                    format!("<include> not read: {why}"),
                );
                return None;
            }
            None => {
                self.sink.report(
                    &rules::SDF_INCLUDE_UNRESOLVED,
                    span,
                    "<include> not read".to_string(),
                );
                return None;
            }
        };
        let root = self.docs.get(file)?.as_ref()?.root_element();
        let root = El { file, node: root };
        let model = if root.node.has_tag_name("model") {
            Some(root)
        } else {
            root.child("model")
        };
        let Some(model) = model else {
            let message = format!(
                "<include>: {} holds no <model>",
                self.sink.files.path(file).display()
            );
            self.sink
                .report(&rules::SDF_INCLUDE_UNRESOLVED, span, message);
            return None;
        };
        if el.child("placement_frame").is_some() {
            self.sink.report(
                &rules::SDF_NOT_READ,
                span,
                "<include> with <placement_frame>: the model is placed by its model frame"
                    .to_string(),
            );
        }
        let version = self
            .versions
            .get(el.file)
            .copied()
            .unwrap_or(FRAME_SEMANTICS);
        let name = el.child("name").map(|n| Spanned {
            value: n.text().to_string(),
            span: self.sink.span(n),
        });
        let pose = el
            .child("pose")
            .map(|_| self.sink.pose_of(el, scope, version));
        let is_static = el.child("static").and_then(|s| {
            let value = pose::boolean(s.text(), "<static>");
            let at = self.sink.span(s);
            self.sink.value(s, value).map(|v| (v, at))
        });
        Some((
            model,
            Overrides {
                name,
                pose,
                is_static,
            },
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_scoped_from_the_analysed_model() {
        let root = Scope::default();
        let arm = root.nested("arm");
        assert_eq!(root.resolve("__model__"), "");
        assert_eq!(arm.resolve("__model__"), "arm");
        assert_eq!(root.resolve("arm::__model__"), "arm");
        assert_eq!(arm.resolve("link"), "arm::link");
        assert_eq!(arm.resolve("world"), "world");
        assert_eq!(arm.nested("b").frame, "arm::b");
        // A merge-included model names in its includer's scope; its model frame is the proxy frame.
        let gripper = arm.merged("gripper");
        assert_eq!(gripper.resolve("link"), "arm::link");
        assert_eq!(
            gripper.resolve("__model__"),
            "arm::_merged__gripper__model__"
        );
        assert_eq!(gripper.resolve("inner::__model__"), "arm::inner");
    }
}
