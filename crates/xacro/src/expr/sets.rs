//! Python `set` and `frozenset`: construction, membership, the operators `| & - ^` and the methods that do
//! not change the set (values are immutable, so `add`, `update`, ... are refused).
//!
//! Items keep insertion order (the first of equal items wins); where CPython's hash order decides which of
//! two equal items an intersection keeps (`{1, 2} & {1.0}` is `{1.0}`), the same side is kept.

use std::rc::Rc;

use super::builtins::{arity, check_hashable, iterate};
use super::eval::{budget_error, charge, Args};
use super::ops::check_items;
use super::parser::BinOp;
use super::value::{distinct, is_subset, py_eq, KeyIndex};
use super::{EvalError, Value};

/// Methods of both `set` and `frozenset`.
pub(crate) const METHODS: &[&str] = &[
    "union",
    "intersection",
    "difference",
    "symmetric_difference",
    "issubset",
    "issuperset",
    "isdisjoint",
    "copy",
];

/// Methods that change a `set` in place (not supported: values are immutable).
pub(crate) const MUTATORS: &[&str] = &[
    "add",
    "update",
    "remove",
    "discard",
    "pop",
    "clear",
    "intersection_update",
    "difference_update",
    "symmetric_difference_update",
];

/// The items of a `set` or `frozenset`.
pub(crate) fn set_items(v: &Value) -> Option<&Rc<Vec<Value>>> {
    match v {
        Value::Set(items) | Value::FrozenSet(items) => Some(items),
        _ => None,
    }
}

/// A set of the kind of `like` (`set` or `frozenset`) holding `items`, which are distinct.
fn same_kind(like: &Value, items: Vec<Value>) -> Value {
    match like {
        Value::FrozenSet(_) => Value::FrozenSet(Rc::new(items)),
        _ => Value::Set(Rc::new(items)),
    }
}

/// Spend a step per item visited by a set operation.
fn spend(n: usize) -> Result<(), EvalError> {
    if charge(n) {
        Ok(())
    } else {
        Err(budget_error())
    }
}

/// The distinct items of an iterable (a `TypeError` for an unhashable one), as `set(v)` builds them.
fn distinct_items(v: &Value) -> Result<Rc<Vec<Value>>, EvalError> {
    if let Some(items) = set_items(v) {
        return Ok(items.clone());
    }
    let items = iterate(v)?;
    spend(items.len())?;
    items.iter().try_for_each(check_hashable)?;
    Ok(Rc::new(distinct(items)))
}

/// `python.set(iterable)` (`frozen`: `python.frozenset(iterable)`); no argument is the empty set.
pub(crate) fn construct(frozen: bool, arg: Option<&Value>) -> Result<Value, EvalError> {
    let items = match arg {
        Some(v) => distinct_items(v)?,
        None => Rc::default(),
    };
    Ok(if frozen {
        Value::FrozenSet(items)
    } else {
        Value::Set(items)
    })
}

/// `needle in set`: the needle must be hashable (a `set` needle is looked up as a `frozenset`, as in
/// Python).
pub(crate) fn contains(items: &[Value], needle: &Value) -> Result<bool, EvalError> {
    if !matches!(needle, Value::Set(_)) {
        check_hashable(needle)?;
    }
    Ok(items.iter().any(|x| py_eq(x, needle)))
}

/// Items of `a`, then those of `b` not in `a`.
fn union(a: &[Value], b: &[Value]) -> Result<Vec<Value>, EvalError> {
    spend(a.len() + b.len())?;
    let mut index = KeyIndex::of(a);
    let mut out = a.to_vec();
    for v in b {
        if index.insert(v, out.len()).is_none() {
            out.push(v.clone());
        }
    }
    check_items(out.len())?;
    Ok(out)
}

/// Items of `a` that `keep` says are (or are not) in `b`.
fn filter(a: &[Value], b: &[Value], keep: bool) -> Result<Vec<Value>, EvalError> {
    spend(a.len() + b.len())?;
    let index = KeyIndex::of(b);
    Ok(a.iter()
        .filter(|v| index.find(v).is_some() == keep)
        .cloned()
        .collect())
}

/// `a & b`: CPython walks the smaller set (`b` when the sizes are equal) and keeps its items.
fn intersection(a: &[Value], b: &[Value]) -> Result<Vec<Value>, EvalError> {
    if b.len() > a.len() {
        filter(a, b, true)
    } else {
        filter(b, a, true)
    }
}

/// `a ^ b`: items of `a` not in `b`, then items of `b` not in `a`.
fn symmetric_difference(a: &[Value], b: &[Value]) -> Result<Vec<Value>, EvalError> {
    let mut out = filter(a, b, false)?;
    out.extend(filter(b, a, false)?);
    check_items(out.len())?;
    Ok(out)
}

/// `a <op> b` when both are sets, of the kind of `a`; `None` when the operator does not apply to sets.
pub(crate) fn binary(op: BinOp, a: &Value, b: &Value) -> Option<Result<Value, EvalError>> {
    let (x, y) = (set_items(a)?, set_items(b)?);
    let result = match op {
        BinOp::BitOr => union(x, y),
        BinOp::BitAnd => intersection(x, y),
        BinOp::Sub => filter(x, y, false),
        BinOp::BitXor => symmetric_difference(x, y),
        _ => return None,
    };
    Some(result.map(|items| same_kind(a, items)))
}

/// Whether `set` holds every item of iterable `other`, or (`any`) at least one; stops at the first answer,
/// as CPython does, so an unhashable item after it is not an error.
fn holds(set: &[Value], other: &Value, any: bool) -> Result<bool, EvalError> {
    if let Some(o) = set_items(other) {
        return Ok(if any {
            !filter(o, set, true)?.is_empty()
        } else {
            is_subset(o, set)
        });
    }
    let index = KeyIndex::of(set);
    for v in iterate(other)? {
        spend(1)?;
        if !matches!(v, Value::Set(_)) {
            check_hashable(&v)?;
        }
        if index.find(&v).is_some() == any {
            return Ok(any);
        }
    }
    Ok(!any)
}

/// `obj.name(args)` for a `set` or `frozenset` `obj` with `items`.
pub(crate) fn call_method(
    obj: &Value,
    items: &[Value],
    name: &str,
    args: &Args,
) -> Result<Value, EvalError> {
    let what = obj.type_name();
    let qualified = format!("{what}.{name}");
    if MUTATORS.contains(&name) {
        return Err(EvalError::new(
            "XacroException",
            format!("{qualified}() is not supported by the native xacro expander (its values cannot change)"),
        ));
    }
    match name {
        "union" | "intersection" | "difference" => {
            let others = arity(args, &qualified, 0, usize::MAX)?;
            let mut acc = items.to_vec();
            for other in others {
                acc = match (name, set_items(other)) {
                    ("union", _) => union(&acc, &distinct_items(other)?)?,
                    ("intersection", Some(o)) => intersection(&acc, o)?,
                    // An iterable that is not a set: its items, in its order, that are in the result.
                    ("intersection", None) => {
                        let o = distinct_items(other)?;
                        filter(&o, &acc, true)?
                    }
                    _ => filter(&acc, &distinct_items(other)?, false)?,
                };
            }
            Ok(same_kind(obj, acc))
        }
        "symmetric_difference" => {
            let other = &arity(args, &qualified, 1, 1)?[0];
            Ok(same_kind(
                obj,
                symmetric_difference(items, &distinct_items(other)?)?,
            ))
        }
        "issubset" => {
            let other = &arity(args, &qualified, 1, 1)?[0];
            Ok(Value::Bool(is_subset(items, &distinct_items(other)?)))
        }
        "issuperset" => Ok(Value::Bool(holds(
            items,
            &arity(args, &qualified, 1, 1)?[0],
            false,
        )?)),
        "isdisjoint" => Ok(Value::Bool(!holds(
            items,
            &arity(args, &qualified, 1, 1)?[0],
            true,
        )?)),
        _ => {
            arity(args, &qualified, 0, 0)?;
            // `frozenset.copy()` is the same object, `set.copy()` a new one.
            Ok(match obj {
                Value::Set(_) => Value::Set(Rc::new(items.to_vec())),
                _ => obj.clone(),
            })
        }
    }
}
