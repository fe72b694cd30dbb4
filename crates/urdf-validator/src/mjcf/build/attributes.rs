//! Reading an element's attributes through its class's defaults: values, vectors, words, frames.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::Builder;
use crate::diagnostics::rules;
use crate::diagnostics::span::Span;
use crate::mjcf::compiler::keyword;
use crate::mjcf::defaults::Value;
use crate::mjcf::orientation::{self, FORMS};
use crate::mjcf::xml::{numbers, El};

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

impl<'a> Builder<'a, '_> {
    /// Attribute `name` of `el`: written on it, else given by its class.
    pub(super) fn value(&self, el: El<'a>, class: &str, name: &str) -> Option<Value<'a>> {
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
    pub(super) fn range(
        &mut self,
        el: El<'a>,
        class: &str,
        prefix: &str,
    ) -> Option<((f64, f64), Span)> {
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
    pub(super) fn class_of(&mut self, el: El<'a>, inherited: &str) -> String {
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
    pub(super) fn child_class(&mut self, el: El<'a>, inherited: &str) -> String {
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
    pub(super) fn vector<const N: usize>(
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
    pub(super) fn list(&mut self, el: El<'a>, class: &str, name: &str) -> Option<Vec<f64>> {
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

    pub(super) fn scalar(&mut self, el: El<'a>, class: &str, name: &str, fallback: f64) -> f64 {
        self.vector(el, class, name, [fallback])[0]
    }

    /// A keyword attribute among `words` (the first when unwritten); a U032 names the words.
    pub(super) fn word(
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
    pub(super) fn placement(&mut self, el: El<'a>, class: &str) -> Isometry3<f64> {
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
}
