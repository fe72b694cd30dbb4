//! Python's built-in classes as xacro exposes them (`list` and `python.list`, ...): besides constructors
//! (see `builtins`), they are the classes of values for `python.isinstance`, print as `<class 'list'>` and
//! have type `type`.

use super::eval::{budget_error, charge, Args};
use super::parser::BinOp;
use super::{EvalError, Value};

/// The builtins under `python.` that are classes in Python (the others are functions).
const CLASSES: &[&str] = &[
    "bool",
    "complex",
    "dict",
    "enumerate",
    "filter",
    "float",
    "frozenset",
    "int",
    "list",
    "map",
    "range",
    "reversed",
    "set",
    "slice",
    "str",
    "tuple",
    "type",
    "zip",
];

/// The class name when the built-in function `name` (qualified, e.g. `python.list`) is a Python class.
pub(crate) fn class_name(name: &str) -> Option<&str> {
    name.strip_prefix("python.")
        .filter(|short| CLASSES.contains(short))
}

fn is_class(v: &Value) -> bool {
    matches!(v, Value::Function(name) if class_name(name).is_some())
}

fn not_a_class() -> EvalError {
    EvalError::new(
        "TypeError",
        "isinstance() arg 2 must be a type, a tuple of types, or a union",
    )
}

/// Classes whose instances this evaluator represents as lists or plain dicts (`python.range(3)` is a
/// list here, a `xacro.dotify(...)` result a dict), so it cannot tell them apart.
fn indistinct(class: &str) -> EvalError {
    EvalError::new(
        "XacroException",
        format!(
            "python.isinstance() with class {class} is not supported by the native xacro expander \
             (its instances are plain lists or dicts here)"
        ),
    )
}

/// `python.isinstance(value, classinfo)`: `classinfo` is a class or a tuple of them, nested at will;
/// the first match ends the search, as in Python.
pub(crate) fn isinstance(args: &Args) -> Result<Value, EvalError> {
    if !args.kw.is_empty() {
        return Err(EvalError::new(
            "TypeError",
            "isinstance() takes no keyword arguments",
        ));
    }
    let [value, classinfo] = args.pos.as_slice() else {
        return Err(EvalError::new(
            "TypeError",
            format!("isinstance expected 2 arguments, got {}", args.pos.len()),
        ));
    };
    // Walked with a stack in Python's order, without recursion: tuples can nest deeply.
    let mut pending = vec![classinfo];
    while let Some(class) = pending.pop() {
        if !charge(1) {
            return Err(budget_error());
        }
        match class {
            Value::Tuple(items) => pending.extend(items.iter().rev()),
            _ if instance_of(value, class)? => return Ok(Value::Bool(true)),
            _ => {}
        }
    }
    Ok(Value::Bool(false))
}

/// `isinstance(value, class)` for one class.
fn instance_of(value: &Value, class: &Value) -> Result<bool, EvalError> {
    let Value::Function(name) = class else {
        return Err(not_a_class());
    };
    // `xacro.dotify` is xacro's YAML dict class (bare `dotify` a function, but the same value here).
    if &**name == "xacro.dotify" {
        return Err(indistinct(name));
    }
    let Some(class) = class_name(name) else {
        return Err(not_a_class());
    };
    Ok(match class {
        "bool" => matches!(value, Value::Bool(_)),
        "int" => matches!(value, Value::Int(_) | Value::Bool(_)),
        "float" => matches!(value, Value::Float(_)),
        "str" => matches!(value, Value::Str(_)),
        "list" => matches!(value, Value::List(_)),
        "tuple" => matches!(value, Value::Tuple(_)),
        // xacro's namespaces (`python`, `math`, `xacro`) are dicts in Python.
        "dict" => matches!(value, Value::Dict(_) | Value::Namespace(_)),
        "set" => matches!(value, Value::Set(_)),
        "frozenset" => matches!(value, Value::FrozenSet(_)),
        "type" if matches!(value, Value::Function(f) if &**f == "xacro.dotify") => {
            return Err(indistinct("xacro.dotify"));
        }
        "type" => is_class(value),
        // No value here is a complex number or a slice: neither can be made.
        "complex" | "slice" => false,
        _ => return Err(indistinct(name)),
    })
}

/// `a | b` of classes (or a class and `None`) is a type union in Python: refused rather than reported
/// as a `TypeError` (`None` when the operation is not a union).
pub(crate) fn union(op: BinOp, a: &Value, b: &Value) -> Option<EvalError> {
    let operand = |v: &Value| is_class(v) || matches!(v, Value::None);
    (op == BinOp::BitOr && (is_class(a) || is_class(b)) && operand(a) && operand(b)).then(|| {
        EvalError::new(
            "XacroException",
            "type unions (`int | None`) are not supported by the native xacro expander",
        )
    })
}
