//! `<default>` classes: for each class, the attributes it gives each element kind, its parents' merged
//! in (a nested class inherits every attribute it does not set). The top-level `<default>` is class
//! `main`. An element takes its `class`, else the `childclass` of the nearest enclosing body or frame that
//! has one, else `main`; an attribute written on the element wins over its class.

use std::collections::HashMap;

use super::xml::{El, Reader};
use crate::diagnostics::rules;
use crate::diagnostics::span::Span;

/// The top-level class.
pub const MAIN: &str = "main";

/// An attribute value as written, where it was written.
#[derive(Clone, Copy, Debug)]
pub struct Value<'a> {
    /// The text.
    pub text: &'a str,
    /// Its span (the attribute value, on the element or in the `<default>`).
    pub span: Span,
}

/// Attributes by element tag, then by attribute name.
type Class<'a> = HashMap<&'a str, HashMap<&'a str, Value<'a>>>;

/// Every default class of a model.
#[derive(Debug, Default)]
pub struct Defaults<'a> {
    classes: HashMap<String, Class<'a>>,
}

impl<'a> Defaults<'a> {
    /// The classes of the `<default>` elements among `sections` (the root's children, includes expanded).
    pub fn read(reader: &mut Reader<'a>, sections: &[El<'a>]) -> Self {
        let mut defaults = Defaults::default();
        defaults.classes.insert(MAIN.to_string(), Class::default());
        for el in sections.iter().filter(|el| el.tag() == "default") {
            let name = el.attr("class").unwrap_or(MAIN);
            defaults.class(reader, *el, name, &Class::default());
        }
        defaults
    }

    fn class(&mut self, reader: &mut Reader<'a>, el: El<'a>, name: &str, inherited: &Class<'a>) {
        let mut class = self.classes.get(name).cloned().unwrap_or_default();
        for (tag, attrs) in inherited {
            let own = class.entry(tag).or_default();
            for (attr, value) in attrs {
                own.entry(attr).or_insert(*value);
            }
        }
        let mut nested = Vec::new();
        for child in reader.children(el) {
            if child.tag() == "default" {
                nested.push(child);
                continue;
            }
            let attrs = class.entry(child.tag()).or_default();
            for attribute in child.node.attributes() {
                let span = reader.files().span(child.file, attribute.range_value());
                attrs.insert(
                    attribute.name(),
                    Value {
                        text: attribute.value(),
                        span,
                    },
                );
            }
        }
        self.classes.insert(name.to_string(), class.clone());
        for child in nested {
            match child.attr("class") {
                Some(sub) => self.class(reader, child, sub, &class),
                None => {
                    let span = reader.span(child);
                    reader.report(
                        &rules::MJCF_STRUCTURE,
                        span,
                        "a nested <default> has no class attribute (MuJoCo refuses it)".to_string(),
                    );
                }
            }
        }
    }

    /// Whether class `name` is defined.
    pub fn has(&self, name: &str) -> bool {
        self.classes.contains_key(name)
    }

    /// The value class `class` gives attribute `attr` of `tag` elements.
    pub fn get(&self, class: &str, tag: &str, attr: &str) -> Option<Value<'a>> {
        self.classes.get(class)?.get(tag)?.get(attr).copied()
    }
}
