//! Property tables (Python xacro's `Table` / `NameSpace`): scoped, lazily evaluated, with the literal rules
//! of `Table._eval_literal` and the boolean rules of `get_boolean_value`.

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::{Rc, Weak};

use crate::document::{Loc, NodeRef};
use crate::expr::Value;

/// A shared table.
pub(crate) type TableRef = Rc<Table>;

/// What a property holds.
#[derive(Clone, Debug)]
pub(crate) enum Entry {
    /// An evaluated value.
    Value(Value),
    /// Text not evaluated yet (lazy evaluation at first use), and where it was defined.
    Lazy(Rc<str>, Option<Loc>),
    /// A block (`*param` of a macro call, or a property defined by its content, stored as `**name`).
    Block(NodeRef),
    /// A namespace created by `<xacro:include ns="...">`.
    Namespace(TableRef),
}

/// One scope of properties.
#[derive(Debug, Default)]
pub(crate) struct Table {
    pub entries: RefCell<HashMap<String, Entry>>,
    /// Names being resolved right now (circular definitions).
    pub resolving: RefCell<Vec<String>>,
    /// The enclosing scope (`None` at the global table).
    parent: Option<ParentLink>,
    /// A `NameSpace` (from an include with `ns`), skipped by `scope="parent"` from a macro.
    pub is_namespace: bool,
}

/// How a table reaches its enclosing scope.
///
/// A namespace table is stored in its parent's entries, so it holds its parent weakly: a strong link both
/// ways would be a reference cycle that outlives the expansion (every namespaced include leaked its tables).
/// A namespace is reachable only through its parent, so the parent is alive whenever the namespace is used.
#[derive(Debug)]
enum ParentLink {
    Scope(TableRef),
    Owner(Weak<Table>),
}

impl Table {
    /// A new scope below `parent`; a namespace (`is_namespace`) is owned by `parent`'s entries.
    pub fn child(parent: &TableRef, is_namespace: bool) -> TableRef {
        let link = if is_namespace {
            ParentLink::Owner(Rc::downgrade(parent))
        } else {
            ParentLink::Scope(parent.clone())
        };
        Rc::new(Table {
            parent: Some(link),
            is_namespace,
            ..Default::default()
        })
    }

    /// The enclosing scope, if any.
    pub fn parent(&self) -> Option<TableRef> {
        match self.parent.as_ref()? {
            ParentLink::Scope(table) => Some(table.clone()),
            ParentLink::Owner(table) => table.upgrade(),
        }
    }

    /// The table holding `name`, innermost first.
    pub fn find(self: &Rc<Self>, name: &str) -> Option<TableRef> {
        let mut t = Some(self.clone());
        while let Some(table) = t {
            if table.entries.borrow().contains_key(name) {
                return Some(table);
            }
            t = table.parent();
        }
        None
    }

    /// The global table (the one below Python's root of built-ins).
    pub fn top(self: &Rc<Self>) -> TableRef {
        let mut t = self.clone();
        while let Some(p) = t.parent() {
            t = p;
        }
        t
    }

    /// Store `value` (after `_eval_literal` when it is text); lazy text stays unevaluated.
    pub fn set_text(&self, name: &str, text: &str, lazy: bool, loc: Option<Loc>) {
        let entry = match eval_literal(text) {
            Value::Str(s) if lazy => Entry::Lazy(s, loc),
            v => Entry::Value(v),
        };
        self.entries.borrow_mut().insert(name.to_string(), entry);
    }

    /// Store an evaluated value (`_setitem(..., unevaluated=False)`): strings still go through
    /// `_eval_literal`.
    pub fn set_value(&self, name: &str, value: Value) {
        let value = match value {
            Value::Str(s) => eval_literal(&s),
            v => v,
        };
        self.entries
            .borrow_mut()
            .insert(name.to_string(), Entry::Value(value));
    }

    /// Store a block or namespace.
    pub fn set_entry(&self, name: &str, entry: Entry) {
        self.entries.borrow_mut().insert(name.to_string(), entry);
    }

    /// `del table[name]`: remove from this table and every parent.
    pub fn remove(self: &Rc<Self>, name: &str) {
        let mut t = Some(self.clone());
        while let Some(table) = t {
            table.entries.borrow_mut().remove(name);
            t = table.parent();
        }
    }

    /// Every property name visible from here (for "did you mean" suggestions).
    pub fn visible_names(self: &Rc<Self>) -> Vec<String> {
        let mut names = Vec::new();
        let mut t = Some(self.clone());
        while let Some(table) = t {
            names.extend(
                table
                    .entries
                    .borrow()
                    .keys()
                    .filter(|k| !k.starts_with('*'))
                    .cloned(),
            );
            t = table.parent();
        }
        names
    }
}

/// Python xacro's `Table._eval_literal` on text: `'quoted'` strings lose their quotes, text with `_` stays
/// text, then `int`, `float` and the boolean words are tried in that order.
pub(crate) fn eval_literal(text: &str) -> Value {
    if text.len() >= 2 && text.starts_with('\'') && text.ends_with('\'') {
        return Value::Str(text[1..text.len() - 1].into());
    }
    if text.contains('_') {
        return Value::Str(text.into());
    }
    if let Some(i) = python_int(text) {
        return Value::Int(i);
    }
    if let Some(f) = python_float(text) {
        return Value::Float(f);
    }
    match text {
        "true" | "True" => Value::Bool(true),
        "false" | "False" => Value::Bool(false),
        _ => Value::Str(text.into()),
    }
}

/// Python's `int(text)` for base-10 text (surrounding whitespace, sign; no underscores).
pub(crate) fn python_int(text: &str) -> Option<i64> {
    let t = text.trim();
    let digits = t.strip_prefix(['+', '-']).unwrap_or(t);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    t.parse::<i64>().ok()
}

/// Python's `float(text)`: decimal or exponent notation, `inf`, `infinity`, `nan` (any case), with
/// surrounding whitespace.
pub(crate) fn python_float(text: &str) -> Option<f64> {
    let t = text.trim();
    let body = t.strip_prefix(['+', '-']).unwrap_or(t);
    let lower = body.to_ascii_lowercase();
    if matches!(lower.as_str(), "inf" | "infinity" | "nan") {
        return t.to_ascii_lowercase().parse::<f64>().ok();
    }
    // Rust accepts the same decimal forms ("1.", ".5", "1e5"); reject anything else it might take.
    if body.is_empty()
        || !body
            .bytes()
            .all(|b| b.is_ascii_digit() || matches!(b, b'.' | b'e' | b'E' | b'+' | b'-'))
    {
        return None;
    }
    t.parse::<f64>().ok()
}

/// Python xacro's `get_boolean_value`: `None` when the value is not a boolean expression.
pub(crate) fn boolean_value(value: &Value) -> Option<bool> {
    match value {
        Value::Str(s) => match &**s {
            "true" | "True" => Some(true),
            "false" | "False" => Some(false),
            other => python_int(other).map(|i| i != 0),
        },
        v => Some(v.is_truthy()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_namespace_table_is_freed_with_its_parent() {
        let global: TableRef = Rc::default();
        let namespace = Table::child(&global, true);
        global.set_entry("ns", Entry::Namespace(namespace.clone()));
        assert!(Rc::ptr_eq(&namespace.parent().expect("parent"), &global));
        let weak = Rc::downgrade(&namespace);
        drop(namespace);
        drop(global);
        assert!(
            weak.upgrade().is_none(),
            "the namespace outlived its parent: a cycle"
        );
    }

    #[test]
    fn literals_follow_python_xacro() {
        assert_eq!(eval_literal("'a b'"), Value::Str("a b".into()));
        assert_eq!(eval_literal("1_000"), Value::Str("1_000".into()));
        assert_eq!(eval_literal(" 12 "), Value::Int(12));
        assert_eq!(eval_literal("1.5"), Value::Float(1.5));
        assert_eq!(eval_literal("1e3"), Value::Float(1000.0));
        assert_eq!(eval_literal("True"), Value::Bool(true));
        assert_eq!(eval_literal("yes"), Value::Str("yes".into()));
        assert_eq!(eval_literal("0x10"), Value::Str("0x10".into()));
        assert_eq!(boolean_value(&Value::Str("1.0".into())), None);
        assert_eq!(boolean_value(&Value::Str(" 2".into())), Some(true));
    }
}
