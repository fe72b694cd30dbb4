//! Macro definitions and their tables (Python xacro's `Macro`, `parse_macro_arg`, the `macros` table with
//! its namespaces).

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;
use std::sync::OnceLock;

use regex::Regex;

use crate::document::NodeRef;

/// A parameter's default: the forwarded property name (`:=^`) and the default text.
pub(crate) type DefaultSpec = (Option<String>, Option<String>);

/// A macro: its parameters in order (`*block` / `**block` included), their defaults, and its body (the
/// `xacro:macro` element, evaluated afresh at each call).
#[derive(Debug)]
pub(crate) struct Macro {
    pub params: Vec<String>,
    /// param -> (forwarded name for `:=^`, default text).
    pub defaults: HashMap<String, DefaultSpec>,
    pub body: NodeRef,
}

/// A shared macro table.
pub(crate) type MacroTableRef = Rc<MacroTable>;

/// What a macro table holds under a name.
#[derive(Clone, Debug)]
pub(crate) enum MacroEntry {
    Macro(Rc<Macro>),
    Namespace(MacroTableRef),
}

/// One scope of macros (a macro call opens one for macros defined in its body).
#[derive(Debug, Default)]
pub(crate) struct MacroTable {
    pub entries: RefCell<HashMap<String, MacroEntry>>,
    pub parent: Option<MacroTableRef>,
}

impl MacroTable {
    /// A new scope below `parent`.
    pub fn child(parent: &MacroTableRef) -> MacroTableRef {
        Rc::new(MacroTable {
            parent: Some(parent.clone()),
            ..Default::default()
        })
    }

    /// `macros[name]`: innermost first.
    pub fn get(self: &Rc<Self>, name: &str) -> Option<MacroEntry> {
        let mut t = Some(self.clone());
        while let Some(table) = t {
            if let Some(e) = table.entries.borrow().get(name) {
                return Some(e.clone());
            }
            t = table.parent.clone();
        }
        None
    }

    /// Every macro name visible from here (for suggestions).
    pub fn visible_names(self: &Rc<Self>) -> Vec<String> {
        let mut names = Vec::new();
        let mut t = Some(self.clone());
        while let Some(table) = t {
            names.extend(table.entries.borrow().keys().cloned());
            t = table.parent.clone();
        }
        names
    }
}

/// The macro-parameter pattern (a constant: `None` never happens, but is no reason to panic).
fn macro_arg_re() -> Option<&'static Regex> {
    static RE: OnceLock<Option<Regex>> = OnceLock::new();
    RE.get_or_init(|| {
        let default_value = r#"\$\{.*?\}|\$\(.*?\)|(?:'.*?'|".*?"|[^\s'"]+)+|"#;
        let pattern =
            format!(r"^\s*([^\s:=]+?)\s*:?=\s*(\^\|?)?({default_value})(?:\s+|$)((?s).*)");
        Regex::new(&pattern).ok()
    })
    .as_ref()
}

/// Python xacro's `parse_macro_arg`: the first parameter of `s`, its (forward, default) spec when it has
/// `:=` / `=`, and the rest of the string.
pub(crate) fn parse_macro_arg(s: &str) -> (String, Option<DefaultSpec>, String) {
    if let Some(c) = macro_arg_re().and_then(|re| re.captures(s)) {
        let param = c.get(1).map_or("", |m| m.as_str()).to_string();
        let forward = c.get(2).map(|_| param.clone());
        let default = c
            .get(3)
            .map(|m| m.as_str())
            .filter(|d| !d.is_empty())
            .map(str::to_string);
        let rest = c.get(4).map_or("", |m| m.as_str()).to_string();
        return (param, Some((forward, default)), rest);
    }
    let trimmed = s.trim_start();
    match trimmed.find(char::is_whitespace) {
        Some(i) => (
            trimmed[..i].to_string(),
            None,
            trimmed[i..].trim_start().to_string(),
        ),
        None => (trimmed.to_string(), None, String::new()),
    }
}

/// All parameters of a `params` attribute.
pub(crate) fn parse_params(params: &str) -> Vec<(String, Option<DefaultSpec>)> {
    let mut out = Vec::new();
    let mut rest = params.to_string();
    while !rest.is_empty() {
        let (name, spec, tail) = parse_macro_arg(&rest);
        if name.is_empty() {
            break;
        }
        out.push((name, spec));
        rest = tail;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn params_parse_like_python_xacro() {
        let p = parse_params("a b:=1 c:=^ d:=^|${x*2} *blk **more e:='a b' f=$(arg y)");
        let names: Vec<&str> = p.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["a", "b", "c", "d", "*blk", "**more", "e", "f"]);
        assert_eq!(p[1].1, Some((None, Some("1".into()))));
        assert_eq!(p[2].1, Some((Some("c".into()), None)));
        assert_eq!(p[3].1, Some((Some("d".into()), Some("${x*2}".into()))));
        assert_eq!(p[6].1, Some((None, Some("'a b'".into()))));
        assert_eq!(p[7].1, Some((None, Some("$(arg y)".into()))));
    }
}
