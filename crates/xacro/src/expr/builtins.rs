//! The names xacro exposes to expressions (xacro 2.1.1 `create_global_symbols`): a few Python builtins
//! bare, all of them under `python.`, every public `math` name bare and under `math.`, and the `xacro.`
//! functions, plus indexing, slicing, attributes and methods of the built-in types.

use std::cmp::Ordering;
use std::rc::Rc;

use super::classes;
use super::eval::{add, Args, Ctx};
use super::format;
use super::math;
use super::ops::{check_items, check_str_len, int_divmod, int_overflow, too_large, MAX_STR_BYTES};
use super::sets;
use super::value::{as_num, py_cmp, py_eq, Num, TWO_POW_63};
use super::{EvalError, Value};

/// Builtins that xacro exposes without a namespace.
const BARE: &[&str] = &[
    "list", "dict", "map", "len", "str", "float", "int", "bool", "min", "max", "round", "sorted",
    "range",
];

/// Builtins exposed under `python.` (plus `True` and `False`, which are values).
const PYTHON: &[&str] = &[
    "list",
    "dict",
    "map",
    "len",
    "str",
    "float",
    "int",
    "bool",
    "min",
    "max",
    "round",
    "abs",
    "all",
    "any",
    "complex",
    "divmod",
    "enumerate",
    "filter",
    "frozenset",
    "hash",
    "isinstance",
    "issubclass",
    "ord",
    "repr",
    "reversed",
    "slice",
    "set",
    "sum",
    "tuple",
    "type",
    "vars",
    "zip",
    "sorted",
    "range",
];

/// Python builtins that exist in xacro but that this evaluator does not implement (they need object
/// types it does not model).
const PYTHON_UNSUPPORTED: &[&str] = &["complex", "hash", "issubclass", "slice", "type", "vars"];

/// Functions under `xacro.`.
const XACRO: &[&str] = &[
    "load_yaml",
    "abs_filename",
    "dotify",
    "arg",
    "message",
    "warning",
    "error",
    "print_location",
    "fatal",
    "tokenize",
];

/// `xacro.` functions that are also exposed bare (with a deprecation warning in Python xacro).
const XACRO_BARE: &[&str] = &["load_yaml", "abs_filename", "dotify"];

fn err(kind: &'static str, message: impl Into<String>) -> EvalError {
    EvalError::new(kind, message)
}

/// `repr(v)` for an error message, bounded (a tuple repeating a long string can have a huge repr).
fn shown(v: &Value) -> String {
    v.repr_within(MAX_STR_BYTES)
        .unwrap_or_else(|_| format!("<{} too large to show>", v.type_name()))
}

fn type_err(message: impl Into<String>) -> EvalError {
    err("TypeError", message)
}

fn fun(prefix: &str, name: &str) -> Value {
    Value::Function(Rc::from(format!("{prefix}.{name}")))
}

/// A built-in global name (after properties were tried).
pub(crate) fn global(name: &str) -> Option<Value> {
    match name {
        "python" | "math" | "xacro" => Some(Value::Namespace(Rc::from(name))),
        _ if BARE.contains(&name) => Some(fun("python", name)),
        _ if XACRO_BARE.contains(&name) => Some(fun("xacro", name)),
        _ => math::lookup(name),
    }
}

fn namespace_attr(ns: &str, name: &str) -> Option<Value> {
    match ns {
        "python" => match name {
            "True" => Some(Value::Bool(true)),
            "False" => Some(Value::Bool(false)),
            _ if PYTHON.contains(&name) => Some(fun("python", name)),
            _ => None,
        },
        "math" => math::lookup(name),
        "xacro" if XACRO.contains(&name) => Some(fun("xacro", name)),
        _ => None,
    }
}

/// `obj.name` (not followed by a call).
pub(crate) fn get_attr(obj: &Value, name: &str) -> Result<Value, EvalError> {
    if name.starts_with('_') {
        return Err(no_attr(obj, name));
    }
    match obj {
        Value::Namespace(ns) => namespace_attr(ns, name)
            .ok_or_else(|| err("NameError", format!("name '{name}' is not defined"))),
        Value::Dict(items) => items
            .iter()
            .find(|(k, _)| matches!(k, Value::Str(s) if &**s == name))
            .map(|(_, v)| v.clone())
            .ok_or_else(|| {
                err(
                    "AttributeError",
                    format!("The yaml dictionary has no key '{name}'"),
                )
            }),
        Value::Int(_) | Value::Bool(_) | Value::Float(_) if name == "real" => match as_num(obj) {
            Some(Num::Int(i)) => Ok(Value::Int(i)),
            _ => Ok(obj.clone()),
        },
        Value::Int(_) | Value::Bool(_) if name == "imag" => Ok(Value::Int(0)),
        Value::Float(_) if name == "imag" => Ok(Value::Float(0.0)),
        _ if is_method(obj, name) => Err(type_err(format!(
            "method '{name}' of '{}' objects must be called",
            obj.type_name()
        ))),
        _ => Err(no_attr(obj, name)),
    }
}

fn no_attr(obj: &Value, name: &str) -> EvalError {
    err(
        "AttributeError",
        format!("'{}' object has no attribute '{name}'", obj.type_name()),
    )
}

const STR_METHODS: &[&str] = &[
    "upper",
    "lower",
    "capitalize",
    "title",
    "swapcase",
    "casefold",
    "strip",
    "lstrip",
    "rstrip",
    "split",
    "rsplit",
    "splitlines",
    "replace",
    "format",
    "startswith",
    "endswith",
    "join",
    "find",
    "rfind",
    "index",
    "rindex",
    "count",
    "isdigit",
    "isalpha",
    "isalnum",
    "isspace",
    "isupper",
    "islower",
    "isnumeric",
    "isdecimal",
    "isidentifier",
    "zfill",
    "center",
    "ljust",
    "rjust",
    "partition",
    "rpartition",
    "removeprefix",
    "removesuffix",
];
const LIST_METHODS: &[&str] = &["index", "count", "copy"];
const TUPLE_METHODS: &[&str] = &["index", "count"];
const DICT_METHODS: &[&str] = &["keys", "values", "items", "get", "copy"];
const FLOAT_METHODS: &[&str] = &["is_integer"];
const INT_METHODS: &[&str] = &["bit_length"];

/// Whether `obj.name(...)` is a method call of a built-in type.
pub(crate) fn is_method(obj: &Value, name: &str) -> bool {
    let table: &[&str] = match obj {
        Value::Str(_) => STR_METHODS,
        Value::List(_) => LIST_METHODS,
        Value::Tuple(_) => TUPLE_METHODS,
        Value::Dict(_) => DICT_METHODS,
        Value::Float(_) => FLOAT_METHODS,
        Value::Int(_) | Value::Bool(_) => INT_METHODS,
        Value::Set(_) => return sets::METHODS.contains(&name) || sets::MUTATORS.contains(&name),
        Value::FrozenSet(_) => sets::METHODS,
        _ => &[],
    };
    table.contains(&name)
}

/// Check positional/keyword argument counts; returns the positional arguments.
pub(crate) fn arity<'v>(
    args: &'v Args,
    name: &str,
    min: usize,
    max: usize,
) -> Result<&'v [Value], EvalError> {
    if !args.kw.is_empty() {
        return Err(type_err(format!("{name}() takes no keyword arguments")));
    }
    positional(args, name, min, max)
}

fn positional<'v>(
    args: &'v Args,
    name: &str,
    min: usize,
    max: usize,
) -> Result<&'v [Value], EvalError> {
    let n = args.pos.len();
    if n < min || n > max {
        let expected = if min == max {
            format!("exactly {min} argument{}", if min == 1 { "" } else { "s" })
        } else if n < min {
            format!("at least {min} argument{}", if min == 1 { "" } else { "s" })
        } else {
            format!("at most {max} argument{}", if max == 1 { "" } else { "s" })
        };
        return Err(type_err(format!("{name}() takes {expected} ({n} given)")));
    }
    Ok(&args.pos)
}

/// Keyword arguments limited to `allowed`; returns a lookup.
fn kwargs<'v>(
    args: &'v Args,
    name: &str,
    allowed: &[&str],
) -> Result<Vec<(&'v str, &'v Value)>, EvalError> {
    let mut out = Vec::new();
    for (k, v) in &args.kw {
        if !allowed.contains(&k.as_str()) {
            return Err(type_err(format!(
                "{name}() got an unexpected keyword argument '{k}'"
            )));
        }
        out.push((k.as_str(), v));
    }
    Ok(out)
}

fn kw_get<'v>(kw: &[(&str, &'v Value)], name: &str) -> Option<&'v Value> {
    kw.iter().find(|(k, _)| *k == name).map(|(_, v)| *v)
}

/// An `int` argument (`bool` accepted, as in Python).
pub(crate) fn int_arg(v: &Value) -> Result<i64, EvalError> {
    match v {
        Value::Int(i) => Ok(*i),
        Value::Bool(b) => Ok(i64::from(*b)),
        other => Err(type_err(format!(
            "'{}' object cannot be interpreted as an integer",
            other.type_name()
        ))),
    }
}

/// The items of an iterable (list, tuple, set, str characters, dict keys).
pub(crate) fn iterate(v: &Value) -> Result<Vec<Value>, EvalError> {
    match v {
        Value::List(items) | Value::Tuple(items) | Value::Set(items) | Value::FrozenSet(items) => {
            Ok(items.to_vec())
        }
        Value::Str(s) => {
            // One item per character: a long string is a long list (and one allocation per item).
            check_items(s.chars().count())?;
            Ok(s.chars().map(|c| Value::from(c.to_string())).collect())
        }
        Value::Dict(items) => Ok(items.iter().map(|(k, _)| k.clone()).collect()),
        other => Err(type_err(format!(
            "'{}' object is not iterable",
            other.type_name()
        ))),
    }
}

/// Dict keys and set items must be hashable (no lists, dicts or sets, also inside tuples; a frozenset's
/// items are hashable).
pub(crate) fn check_hashable(k: &Value) -> Result<(), EvalError> {
    match k {
        Value::List(_) | Value::Dict(_) | Value::Set(_) => {
            Err(type_err(format!("unhashable type: '{}'", k.type_name())))
        }
        Value::Tuple(items) => items.iter().try_for_each(check_hashable),
        _ => Ok(()),
    }
}

fn seq_index(len: usize, idx: &Value, what: &str) -> Result<usize, EvalError> {
    let i = match idx {
        Value::Int(i) => *i,
        Value::Bool(b) => i64::from(*b),
        other => {
            return Err(type_err(format!(
                "{what} indices must be integers or slices, not {}",
                other.type_name()
            )))
        }
    };
    let len_i = len as i64;
    let j = if i < 0 { i + len_i } else { i };
    if j < 0 || j >= len_i {
        return Err(err("IndexError", format!("{what} index out of range")));
    }
    Ok(j as usize)
}

/// `obj[idx]`.
pub(crate) fn index(obj: &Value, idx: &Value) -> Result<Value, EvalError> {
    match obj {
        Value::List(items) => Ok(items[seq_index(items.len(), idx, "list")?].clone()),
        Value::Tuple(items) => Ok(items[seq_index(items.len(), idx, "tuple")?].clone()),
        Value::Str(s) => {
            let n = s.chars().count();
            let i = seq_index(n, idx, "string")?;
            Ok(Value::from(
                s.chars().nth(i).map(String::from).unwrap_or_default(),
            ))
        }
        Value::Dict(items) => {
            check_hashable(idx)?;
            items
                .iter()
                .find(|(k, _)| py_eq(k, idx))
                .map(|(_, v)| v.clone())
                .ok_or_else(|| err("KeyError", shown(idx)))
        }
        Value::Namespace(ns) => match idx {
            Value::Str(name) => namespace_attr(ns, name).ok_or_else(|| err("KeyError", shown(idx))),
            _ => Err(err("KeyError", shown(idx))),
        },
        other => Err(type_err(format!(
            "'{}' object is not subscriptable",
            other.type_name()
        ))),
    }
}

fn slice_bound(v: &Value) -> Result<Option<i64>, EvalError> {
    match v {
        Value::None => Ok(None),
        Value::Int(i) => Ok(Some(*i)),
        Value::Bool(b) => Ok(Some(i64::from(*b))),
        _ => Err(type_err(
            "slice indices must be integers or None or have an __index__ method",
        )),
    }
}

/// The positions `seq[lo:hi:step]` selects in a sequence of `len` items (Python's slice rules).
fn slice_positions(
    len: usize,
    lo: &Value,
    hi: &Value,
    step: &Value,
) -> Result<Vec<usize>, EvalError> {
    let step = slice_bound(step)?.unwrap_or(1);
    if step == 0 {
        return Err(err("ValueError", "slice step cannot be zero"));
    }
    let len = len as i64;
    let (lower, upper) = if step > 0 { (0, len) } else { (-1, len - 1) };
    let adjust = |b: Option<i64>, default: i64| -> i64 {
        match b {
            None => default,
            Some(mut i) => {
                if i < 0 {
                    i = i.saturating_add(len);
                    if i < lower {
                        i = lower;
                    }
                } else if i > upper {
                    i = upper;
                }
                i
            }
        }
    };
    let start = adjust(slice_bound(lo)?, if step > 0 { lower } else { upper });
    let stop = adjust(slice_bound(hi)?, if step > 0 { upper } else { lower });
    let mut out = Vec::new();
    let mut i = start;
    while (step > 0 && i < stop) || (step < 0 && i > stop) {
        out.push(i as usize);
        i = match i.checked_add(step) {
            Some(n) => n,
            None => break,
        };
    }
    Ok(out)
}

/// `obj[lo:hi:step]`.
pub(crate) fn slice(obj: &Value, lo: &Value, hi: &Value, step: &Value) -> Result<Value, EvalError> {
    match obj {
        Value::List(items) | Value::Tuple(items) => {
            let picked: Vec<Value> = slice_positions(items.len(), lo, hi, step)?
                .into_iter()
                .map(|i| items[i].clone())
                .collect();
            Ok(if matches!(obj, Value::List(_)) {
                Value::list(picked)
            } else {
                Value::tuple(picked)
            })
        }
        Value::Str(s) => {
            let chars: Vec<char> = s.chars().collect();
            let picked: String = slice_positions(chars.len(), lo, hi, step)?
                .into_iter()
                .map(|i| chars[i])
                .collect();
            Ok(Value::from(picked))
        }
        other => Err(type_err(format!(
            "'{}' object is not subscriptable",
            other.type_name()
        ))),
    }
}

/// Call a built-in function by qualified name.
pub(crate) fn call(ctx: &mut Ctx, name: &str, args: Args) -> Result<Value, EvalError> {
    let (ns, short) = name.split_once('.').unwrap_or(("python", name));
    match ns {
        "math" => math::call(short, &args),
        "xacro" => call_xacro(ctx, short, args),
        _ => call_python(ctx, short, args),
    }
}

fn call_xacro(ctx: &mut Ctx, short: &str, args: Args) -> Result<Value, EvalError> {
    let qualified = format!("xacro.{short}");
    if let Some(r) = ctx.scope.call_host(&qualified, &args.pos, &args.kw) {
        return r;
    }
    match short {
        "dotify" => {
            let pos = arity(&args, "dotify", 0, 1)?;
            match pos.first() {
                None => Ok(Value::dict(Vec::new())),
                Some(d @ Value::Dict(_)) => Ok(d.clone()),
                Some(other) => dict_from(other),
            }
        }
        "tokenize" => {
            let kw = kwargs(&args, "tokenize", &["s", "sep", "skip_empty"])?;
            let pos = positional(&args, "tokenize", 0, 3)?;
            let s = pos.first().or(kw_get(&kw, "s")).ok_or_else(|| {
                type_err("tokenize() missing 1 required positional argument: 's'")
            })?;
            let sep = pos
                .get(1)
                .or(kw_get(&kw, "sep"))
                .cloned()
                .unwrap_or(Value::str(",; "));
            let skip = pos
                .get(2)
                .or(kw_get(&kw, "skip_empty"))
                .is_none_or(Value::is_truthy);
            let (Value::Str(s), Value::Str(sep)) = (s, &sep) else {
                return Err(type_err("tokenize() expects strings"));
            };
            let parts: Vec<Value> = s
                .split(|c: char| sep.contains(c))
                .filter(|p| !skip || !p.is_empty())
                .map(Value::str)
                .collect();
            Ok(Value::list(parts))
        }
        "fatal" => {
            let words = args
                .pos
                .iter()
                .map(|v| v.to_xacro_string_within(MAX_STR_BYTES))
                .collect::<Result<Vec<_>, _>>()?;
            Err(err("XacroException", words.join(" ")))
        }
        _ => Err(err(
            "XacroException",
            format!("xacro.{short}() is not available in this context"),
        )),
    }
}

fn dict_from(v: &Value) -> Result<Value, EvalError> {
    if let Value::Dict(_) = v {
        return Ok(v.clone());
    }
    let mut pairs = Vec::new();
    for (i, item) in iterate(v)?.into_iter().enumerate() {
        let kv = iterate(&item).map_err(|_| {
            type_err(format!(
                "cannot convert dictionary update sequence element #{i} to a sequence"
            ))
        })?;
        if kv.len() != 2 {
            return Err(err(
                "ValueError",
                format!(
                    "dictionary update sequence element #{i} has length {}; 2 is required",
                    kv.len()
                ),
            ));
        }
        let mut it = kv.into_iter();
        let (Some(k), Some(val)) = (it.next(), it.next()) else {
            return Err(err(
                "ValueError",
                "dictionary update sequence element has the wrong length",
            ));
        };
        check_hashable(&k)?;
        pairs.push((k, val));
    }
    Ok(Value::dict(pairs))
}

/// Python's `float(str)`.
pub(crate) fn parse_float(s: &str) -> Result<f64, EvalError> {
    let fail = || {
        err(
            "ValueError",
            format!(
                "could not convert string to float: {}",
                Value::str(s).repr()
            ),
        )
    };
    let t = s.trim();
    let (sign, body) = match t.strip_prefix('-') {
        Some(rest) => (-1.0, rest),
        None => (1.0, t.strip_prefix('+').unwrap_or(t)),
    };
    let lower = body.to_ascii_lowercase();
    match lower.as_str() {
        "inf" | "infinity" => return Ok(sign * f64::INFINITY),
        "nan" => return Ok(f64::NAN),
        _ => {}
    }
    // Underscores only between digits.
    let b = body.as_bytes();
    for (i, c) in b.iter().enumerate() {
        if *c == b'_'
            && !(i > 0
                && b[i - 1].is_ascii_digit()
                && b.get(i + 1).is_some_and(|d| d.is_ascii_digit()))
        {
            return Err(fail());
        }
    }
    let cleaned: String = body.chars().filter(|c| *c != '_').collect();
    if cleaned.is_empty()
        || !cleaned
            .bytes()
            .all(|c| c.is_ascii_digit() || matches!(c, b'.' | b'e' | b'E' | b'+' | b'-'))
        || !cleaned.bytes().any(|c| c.is_ascii_digit())
    {
        return Err(fail());
    }
    cleaned.parse::<f64>().map(|f| sign * f).map_err(|_| fail())
}

/// Python's `int(str, base)`.
fn parse_int(s: &str, base: i64) -> Result<i64, EvalError> {
    let fail = || {
        err(
            "ValueError",
            format!(
                "invalid literal for int() with base {base}: {}",
                Value::str(s).repr()
            ),
        )
    };
    let t = s.trim();
    let (neg, mut body) = match t.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, t.strip_prefix('+').unwrap_or(t)),
    };
    let mut radix = base;
    let lower = body.to_ascii_lowercase();
    for (prefix, r) in [("0x", 16), ("0o", 8), ("0b", 2)] {
        if lower.starts_with(prefix) && (base == 0 || base == r) {
            radix = r;
            body = &body[2..];
            body = body.strip_prefix('_').unwrap_or(body);
            break;
        }
    }
    if radix == 0 {
        radix = 10;
        if body.len() > 1 && body.starts_with('0') && body.bytes().any(|c| c != b'0' && c != b'_') {
            return Err(fail());
        }
    }
    if !(2..=36).contains(&radix) {
        return Err(err("ValueError", "int() base must be >= 2 and <= 36, or 0"));
    }
    let b = body.as_bytes();
    if b.is_empty() || b[0] == b'_' || b[b.len() - 1] == b'_' || body.contains("__") {
        return Err(fail());
    }
    let digits: String = body.chars().filter(|c| *c != '_').collect();
    let magnitude = u64::from_str_radix(&digits, radix as u32).map_err(|e| {
        if matches!(e.kind(), std::num::IntErrorKind::PosOverflow) {
            int_overflow()
        } else {
            fail()
        }
    })?;
    if neg {
        if magnitude == 1u64 << 63 {
            Ok(i64::MIN)
        } else {
            i64::try_from(magnitude)
                .map(|m| -m)
                .map_err(|_| int_overflow())
        }
    } else {
        i64::try_from(magnitude).map_err(|_| int_overflow())
    }
}

/// `int(float)`: truncation, errors for inf/nan/out of range.
pub(crate) fn float_to_int(f: f64) -> Result<i64, EvalError> {
    if f.is_nan() {
        return Err(err("ValueError", "cannot convert float NaN to integer"));
    }
    if f.is_infinite() {
        return Err(err(
            "OverflowError",
            "cannot convert float infinity to integer",
        ));
    }
    let t = f.trunc();
    if !(-TWO_POW_63..TWO_POW_63).contains(&t) {
        return Err(int_overflow());
    }
    Ok(t as i64)
}

fn to_float(v: &Value) -> Result<f64, EvalError> {
    match v {
        Value::Str(s) => parse_float(s),
        other => other.as_f64().ok_or_else(|| {
            type_err(format!(
                "float() argument must be a string or a real number, not '{}'",
                other.type_name()
            ))
        }),
    }
}

fn sort_values(
    ctx: &mut Ctx,
    items: Vec<Value>,
    key: Option<&Value>,
    reverse: bool,
) -> Result<Vec<Value>, EvalError> {
    let keys: Vec<Value> = match key {
        Some(f) if !matches!(f, Value::None) => {
            let mut ks = Vec::with_capacity(items.len());
            for it in &items {
                ks.push(ctx.call_value(
                    f,
                    Args {
                        pos: vec![it.clone()],
                        kw: Vec::new(),
                    },
                )?);
            }
            ks
        }
        _ => items.clone(),
    };
    let mut failure: Option<EvalError> = None;
    let order = merge_sort(items.len(), &mut |a, b| {
        let (x, y) = if reverse {
            (&keys[b], &keys[a])
        } else {
            (&keys[a], &keys[b])
        };
        match py_cmp(x, y, "<") {
            Ok(o) => o == Some(Ordering::Less),
            Err(e) => {
                failure.get_or_insert(e);
                false
            }
        }
    });
    if let Some(e) = failure {
        return Err(e);
    }
    Ok(order.into_iter().map(|i| items[i].clone()).collect())
}

/// The positions `0..n` in stable sorted order by `less` alone, as Python sorts with `<`. Unlike
/// `slice::sort_by` (which may panic), an inconsistent order (NaN, sets ordered by inclusion) only gives
/// some order.
fn merge_sort(n: usize, less: &mut dyn FnMut(usize, usize) -> bool) -> Vec<usize> {
    let mut src: Vec<usize> = (0..n).collect();
    let mut dst = Vec::with_capacity(n);
    let mut width = 1;
    while width < n {
        dst.clear();
        for start in (0..n).step_by(2 * width) {
            let mid = (start + width).min(n);
            let end = (start + 2 * width).min(n);
            let (mut i, mut j) = (start, mid);
            while i < mid && j < end {
                // The right item goes first only when strictly less: equal items keep their order.
                if less(src[j], src[i]) {
                    dst.push(src[j]);
                    j += 1;
                } else {
                    dst.push(src[i]);
                    i += 1;
                }
            }
            dst.extend_from_slice(&src[i..mid]);
            dst.extend_from_slice(&src[j..end]);
        }
        std::mem::swap(&mut src, &mut dst);
        width = width.saturating_mul(2);
    }
    src
}

fn min_max(ctx: &mut Ctx, name: &str, args: &Args, want: Ordering) -> Result<Value, EvalError> {
    let kw = kwargs(args, name, &["key", "default"])?;
    let key = kw_get(&kw, "key")
        .filter(|k| !matches!(k, Value::None))
        .cloned();
    let items = match args.pos.len() {
        0 => {
            return Err(type_err(format!(
                "{name} expected at least 1 argument, got 0"
            )))
        }
        1 => iterate(&args.pos[0])?,
        _ => {
            if kw_get(&kw, "default").is_some() {
                return Err(type_err(format!(
                    "Cannot specify a default for {name}() with multiple positional arguments"
                )));
            }
            args.pos.clone()
        }
    };
    let mut best: Option<(Value, Value)> = None;
    for item in items {
        let k = match &key {
            Some(f) => ctx.call_value(
                f,
                Args {
                    pos: vec![item.clone()],
                    kw: Vec::new(),
                },
            )?,
            None => item.clone(),
        };
        let replace = match &best {
            None => true,
            Some((bk, _)) => {
                py_cmp(&k, bk, if want == Ordering::Less { "<" } else { ">" })? == Some(want)
            }
        };
        if replace {
            best = Some((k, item));
        }
    }
    match best {
        Some((_, v)) => Ok(v),
        None => kw_get(&kw, "default")
            .cloned()
            .ok_or_else(|| err("ValueError", format!("{name}() arg is an empty sequence"))),
    }
}

fn call_python(ctx: &mut Ctx, name: &str, args: Args) -> Result<Value, EvalError> {
    if PYTHON_UNSUPPORTED.contains(&name) {
        return Err(err(
            "XacroException",
            format!("python.{name}() is not supported by the native xacro expander"),
        ));
    }
    match name {
        "list" | "tuple" => {
            let pos = arity(&args, name, 0, 1)?;
            let items = match pos.first() {
                Some(v) => iterate(v)?,
                None => Vec::new(),
            };
            Ok(if name == "list" {
                Value::list(items)
            } else {
                Value::tuple(items)
            })
        }
        "set" | "frozenset" => {
            let pos = arity(&args, name, 0, 1)?;
            sets::construct(name == "frozenset", pos.first())
        }
        "isinstance" => classes::isinstance(&args),
        "dict" => {
            let pos = positional(&args, name, 0, 1)?;
            let base = match pos.first() {
                Some(v) => dict_from(v)?,
                None => Value::dict(Vec::new()),
            };
            let Value::Dict(items) = base else {
                return Ok(base);
            };
            let mut pairs = items.to_vec();
            pairs.extend(args.kw.iter().map(|(k, v)| (Value::str(k), v.clone())));
            Ok(Value::dict(pairs))
        }
        "map" => {
            if args.pos.len() < 2 {
                return Err(type_err("map() must have at least two arguments."));
            }
            arity(&args, name, 2, usize::MAX)?;
            let f = args.pos[0].clone();
            let lists: Vec<Vec<Value>> = args.pos[1..]
                .iter()
                .map(iterate)
                .collect::<Result<_, _>>()?;
            let n = lists.iter().map(Vec::len).min().unwrap_or(0);
            let mut out = Vec::with_capacity(n);
            for i in 0..n {
                ctx.spend(1)?;
                let call_args = lists.iter().map(|l| l[i].clone()).collect();
                out.push(ctx.call_value(
                    &f,
                    Args {
                        pos: call_args,
                        kw: Vec::new(),
                    },
                )?);
            }
            Ok(Value::list(out))
        }
        "filter" => {
            let pos = arity(&args, name, 2, 2)?;
            let f = pos[0].clone();
            let mut out = Vec::new();
            for item in iterate(&pos[1])? {
                ctx.spend(1)?;
                let keep = match f {
                    Value::None => item.is_truthy(),
                    _ => ctx
                        .call_value(
                            &f,
                            Args {
                                pos: vec![item.clone()],
                                kw: Vec::new(),
                            },
                        )?
                        .is_truthy(),
                };
                if keep {
                    out.push(item);
                }
            }
            Ok(Value::list(out))
        }
        "len" => {
            let pos = arity(&args, name, 1, 1)?;
            let n = match &pos[0] {
                Value::Str(s) => s.chars().count(),
                Value::List(v) | Value::Tuple(v) | Value::Set(v) | Value::FrozenSet(v) => v.len(),
                Value::Dict(v) => v.len(),
                other => {
                    return Err(type_err(format!(
                        "object of type '{}' has no len()",
                        other.type_name()
                    )))
                }
            };
            Ok(Value::Int(n as i64))
        }
        "str" => {
            let pos = arity(&args, name, 0, 1)?;
            match pos.first() {
                Some(v) => Ok(Value::from(v.to_xacro_string_within(MAX_STR_BYTES)?)),
                None => Ok(Value::from("")),
            }
        }
        "repr" => Ok(Value::from(
            arity(&args, name, 1, 1)?[0].repr_within(MAX_STR_BYTES)?,
        )),
        "float" => {
            let pos = arity(&args, name, 0, 1)?;
            Ok(Value::Float(match pos.first() {
                Some(v) => to_float(v)?,
                None => 0.0,
            }))
        }
        "int" => {
            let kw = kwargs(&args, name, &["base"])?;
            let pos = positional(&args, name, 0, 2)?;
            let base = pos.get(1).or(kw_get(&kw, "base"));
            match (pos.first(), base) {
                (None, None) => Ok(Value::Int(0)),
                (None, Some(_)) => Err(type_err("int() missing string argument")),
                (Some(Value::Str(s)), base) => {
                    let b = base.map(int_arg).transpose()?.unwrap_or(10);
                    parse_int(s, b).map(Value::Int)
                }
                (Some(_), Some(_)) => Err(type_err("int() can't convert non-string with explicit base")),
                (Some(v), None) => match as_num(v) {
                    Some(Num::Int(i)) => Ok(Value::Int(i)),
                    Some(Num::Float(f)) => float_to_int(f).map(Value::Int),
                    None => Err(type_err(format!(
                        "int() argument must be a string, a bytes-like object or a real number, not '{}'",
                        v.type_name()
                    ))),
                },
            }
        }
        "bool" => {
            let pos = arity(&args, name, 0, 1)?;
            Ok(Value::Bool(pos.first().is_some_and(Value::is_truthy)))
        }
        "min" => min_max(ctx, name, &args, Ordering::Less),
        "max" => min_max(ctx, name, &args, Ordering::Greater),
        "round" => {
            let kw = kwargs(&args, name, &["number", "ndigits"])?;
            let pos = positional(&args, name, 0, 2)?;
            let x = pos
                .first()
                .or(kw_get(&kw, "number"))
                .ok_or_else(|| type_err("round() missing required argument 'number' (pos 1)"))?;
            let nd = pos
                .get(1)
                .or(kw_get(&kw, "ndigits"))
                .filter(|v| !matches!(v, Value::None));
            let nd = nd.map(int_arg).transpose()?;
            math::round(x, nd)
        }
        "sorted" => {
            let kw = kwargs(&args, name, &["key", "reverse"])?;
            let pos = positional(&args, name, 1, 1)?;
            let items = iterate(&pos[0])?;
            let reverse = kw_get(&kw, "reverse").is_some_and(Value::is_truthy);
            sort_values(ctx, items, kw_get(&kw, "key"), reverse).map(Value::list)
        }
        "reversed" => {
            let pos = arity(&args, name, 1, 1)?;
            let mut items = iterate(&pos[0])?;
            items.reverse();
            Ok(Value::list(items))
        }
        "range" => {
            let pos = arity(&args, name, 1, 3)?;
            let ints: Vec<i64> = pos.iter().map(int_arg).collect::<Result<_, _>>()?;
            let (start, stop, step) = match ints.as_slice() {
                [stop] => (0, *stop, 1),
                [start, stop] => (*start, *stop, 1),
                [start, stop, step] => (*start, *stop, *step),
                _ => (0, 0, 1),
            };
            if step == 0 {
                return Err(err("ValueError", "range() arg 3 must not be zero"));
            }
            let span = if step > 0 {
                (i128::from(stop) - i128::from(start) + i128::from(step) - 1) / i128::from(step)
            } else {
                (i128::from(start) - i128::from(stop) - i128::from(step) - 1) / i128::from(-step)
            };
            let n = usize::try_from(span.max(0)).map_err(|_| too_large())?;
            check_items(n)?;
            ctx.spend(n)?;
            Ok(Value::list(
                (0..n)
                    .map(|i| Value::Int(start + (i as i64) * step))
                    .collect(),
            ))
        }
        "abs" => {
            let pos = arity(&args, name, 1, 1)?;
            match as_num(&pos[0]) {
                Some(Num::Int(i)) => i.checked_abs().map(Value::Int).ok_or_else(int_overflow),
                Some(Num::Float(f)) => Ok(Value::Float(f.abs())),
                None => Err(type_err(format!(
                    "bad operand type for abs(): '{}'",
                    pos[0].type_name()
                ))),
            }
        }
        "all" => Ok(Value::Bool(
            iterate(&arity(&args, name, 1, 1)?[0])?
                .iter()
                .all(Value::is_truthy),
        )),
        "any" => Ok(Value::Bool(
            iterate(&arity(&args, name, 1, 1)?[0])?
                .iter()
                .any(Value::is_truthy),
        )),
        "divmod" => {
            let pos = arity(&args, name, 2, 2)?;
            match (as_num(&pos[0]), as_num(&pos[1])) {
                (Some(Num::Int(a)), Some(Num::Int(b))) => {
                    let (q, r) = int_divmod(a, b)?;
                    Ok(Value::tuple(vec![Value::Int(q), Value::Int(r)]))
                }
                (Some(a), Some(b)) => {
                    let (x, y) = (super::ops::num_f64(a), super::ops::num_f64(b));
                    if y == 0.0 {
                        return Err(err("ZeroDivisionError", "float divmod()"));
                    }
                    let (q, r) = super::ops::float_divmod(x, y);
                    Ok(Value::tuple(vec![Value::Float(q), Value::Float(r)]))
                }
                _ => Err(type_err(format!(
                    "unsupported operand type(s) for divmod(): '{}' and '{}'",
                    pos[0].type_name(),
                    pos[1].type_name()
                ))),
            }
        }
        "enumerate" => {
            let kw = kwargs(&args, name, &["iterable", "start"])?;
            let pos = positional(&args, name, 0, 2)?;
            let it = pos.first().or(kw_get(&kw, "iterable")).ok_or_else(|| {
                type_err("enumerate() missing required argument 'iterable' (pos 1)")
            })?;
            let start = pos
                .get(1)
                .or(kw_get(&kw, "start"))
                .map(int_arg)
                .transpose()?
                .unwrap_or(0);
            let mut out = Vec::new();
            for (i, v) in iterate(it)?.into_iter().enumerate() {
                let n = start.checked_add(i as i64).ok_or_else(int_overflow)?;
                out.push(Value::tuple(vec![Value::Int(n), v]));
            }
            Ok(Value::list(out))
        }
        "zip" => {
            let kw = kwargs(&args, name, &["strict"])?;
            let lists: Vec<Vec<Value>> = args.pos.iter().map(iterate).collect::<Result<_, _>>()?;
            let n = lists.iter().map(Vec::len).min().unwrap_or(0);
            if kw_get(&kw, "strict").is_some_and(Value::is_truthy)
                && lists.iter().any(|l| l.len() != n)
            {
                return Err(err("ValueError", "zip() arguments have different lengths"));
            }
            Ok(Value::list(
                (0..n)
                    .map(|i| Value::tuple(lists.iter().map(|l| l[i].clone()).collect()))
                    .collect(),
            ))
        }
        "ord" => {
            let pos = arity(&args, name, 1, 1)?;
            match &pos[0] {
                Value::Str(s) if s.chars().count() == 1 => {
                    Ok(Value::Int(s.chars().next().map_or(0, |c| c as i64)))
                }
                Value::Str(s) => Err(type_err(format!(
                    "ord() expected a character, but string of length {} found",
                    s.chars().count()
                ))),
                other => Err(type_err(format!(
                    "ord() expected string of length 1, but {} found",
                    other.type_name()
                ))),
            }
        }
        "sum" => {
            let kw = kwargs(&args, name, &["start"])?;
            let pos = positional(&args, name, 1, 2)?;
            let mut acc = pos
                .get(1)
                .or(kw_get(&kw, "start"))
                .cloned()
                .unwrap_or(Value::Int(0));
            if matches!(acc, Value::Str(_)) {
                return Err(type_err(
                    "sum() can't sum strings [use ''.join(seq) instead]",
                ));
            }
            for item in iterate(&pos[0])? {
                acc = add(&acc, &item)?;
            }
            Ok(acc)
        }
        _ => Err(err("NameError", format!("name '{name}' is not defined"))),
    }
}

/// Char index → byte offset in `s` (clamped).
fn byte_at(s: &str, char_idx: usize) -> usize {
    s.char_indices().nth(char_idx).map_or(s.len(), |(b, _)| b)
}

fn char_count(s: &str, byte: usize) -> usize {
    s[..byte].chars().count()
}

fn str_arg<'v>(v: &'v Value, method: &str) -> Result<&'v str, EvalError> {
    match v {
        Value::Str(s) => Ok(s),
        other => Err(type_err(format!(
            "{method}() argument must be str, not {}",
            other.type_name()
        ))),
    }
}

/// Optional `chars` argument of `strip` and friends.
fn strip_chars(pos: &[Value]) -> Result<Option<Vec<char>>, EvalError> {
    match pos.first() {
        None | Some(Value::None) => Ok(None),
        Some(v) => Ok(Some(str_arg(v, "strip")?.chars().collect())),
    }
}

/// Python's whitespace `split()`.
fn split_whitespace(s: &str, maxsplit: i64, from_right: bool) -> Vec<Value> {
    if !from_right {
        let mut out = Vec::new();
        let mut rest = s.trim_start();
        while !rest.is_empty() {
            if maxsplit >= 0 && out.len() as i64 >= maxsplit {
                out.push(Value::str(rest));
                return out;
            }
            let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
            out.push(Value::str(&rest[..end]));
            rest = rest[end..].trim_start();
        }
        out
    } else {
        let mut out = Vec::new();
        let mut rest = s.trim_end();
        while !rest.is_empty() {
            if maxsplit >= 0 && out.len() as i64 >= maxsplit {
                out.push(Value::str(rest));
                break;
            }
            let start = rest.rfind(char::is_whitespace).map_or(0, |i| {
                i + rest[i..].chars().next().map_or(1, char::len_utf8)
            });
            out.push(Value::str(&rest[start..]));
            rest = rest[..start].trim_end();
        }
        out.reverse();
        out
    }
}

fn find_args(pos: &[Value], s: &str, method: &str) -> Result<(String, usize, usize), EvalError> {
    let sub = str_arg(
        pos.first()
            .ok_or_else(|| type_err(format!("{method}() takes at least 1 argument (0 given)")))?,
        method,
    )?
    .to_string();
    let n = s.chars().count();
    let bound = |v: Option<&Value>, default: usize| -> Result<usize, EvalError> {
        match v {
            None | Some(Value::None) => Ok(default),
            Some(v) => {
                let i = int_arg(v)?;
                let i = if i < 0 {
                    (i + n as i64).max(0)
                } else {
                    i.min(n as i64)
                };
                Ok(i as usize)
            }
        }
    };
    let start = bound(pos.get(1), 0)?;
    let end = bound(pos.get(2), n)?;
    Ok((sub, start, end))
}

/// Call `obj.name(args)` for a built-in type.
pub(crate) fn call_method(
    ctx: &mut Ctx,
    obj: &Value,
    name: &str,
    args: Args,
) -> Result<Value, EvalError> {
    match obj {
        Value::Str(s) => str_method(s, name, &args),
        Value::Set(items) | Value::FrozenSet(items) => sets::call_method(obj, items, name, &args),
        Value::List(items) | Value::Tuple(items) => {
            let what = obj.type_name();
            match name {
                "copy" => {
                    arity(&args, name, 0, 0)?;
                    Ok(obj.clone())
                }
                "count" => {
                    let pos = arity(&args, name, 1, 1)?;
                    Ok(Value::Int(
                        items.iter().filter(|x| py_eq(x, &pos[0])).count() as i64,
                    ))
                }
                _ => {
                    let pos = arity(&args, name, 1, 3)?;
                    let n = items.len() as i64;
                    let clamp = |v: Option<&Value>, d: i64| -> Result<i64, EvalError> {
                        Ok(match v {
                            None => d,
                            Some(v) => {
                                let i = int_arg(v)?;
                                if i < 0 {
                                    (i + n).max(0)
                                } else {
                                    i.min(n)
                                }
                            }
                        })
                    };
                    let (a, b) = (clamp(pos.get(1), 0)?, clamp(pos.get(2), n)?);
                    (a..b.max(a))
                        .find(|&i| py_eq(&items[i as usize], &pos[0]))
                        .map(Value::Int)
                        .ok_or_else(|| {
                            err(
                                "ValueError",
                                if what == "list" {
                                    format!("{} is not in list", shown(&pos[0]))
                                } else {
                                    "tuple.index(x): x not in tuple".to_string()
                                },
                            )
                        })
                }
            }
        }
        Value::Dict(items) => match name {
            "keys" => {
                arity(&args, name, 0, 0)?;
                Ok(Value::list(items.iter().map(|(k, _)| k.clone()).collect()))
            }
            "values" => {
                arity(&args, name, 0, 0)?;
                Ok(Value::list(items.iter().map(|(_, v)| v.clone()).collect()))
            }
            "items" => {
                arity(&args, name, 0, 0)?;
                Ok(Value::list(
                    items
                        .iter()
                        .map(|(k, v)| Value::tuple(vec![k.clone(), v.clone()]))
                        .collect(),
                ))
            }
            "copy" => {
                arity(&args, name, 0, 0)?;
                Ok(obj.clone())
            }
            _ => {
                let pos = arity(&args, name, 1, 2)?;
                check_hashable(&pos[0])?;
                Ok(items
                    .iter()
                    .find(|(k, _)| py_eq(k, &pos[0]))
                    .map(|(_, v)| v.clone())
                    .unwrap_or_else(|| pos.get(1).cloned().unwrap_or(Value::None)))
            }
        },
        Value::Float(f) => {
            arity(&args, name, 0, 0)?;
            Ok(Value::Bool(f.is_finite() && f.fract() == 0.0))
        }
        Value::Int(_) | Value::Bool(_) => {
            arity(&args, name, 0, 0)?;
            let i = int_arg(obj)?;
            Ok(Value::Int(i64::from(64 - i.unsigned_abs().leading_zeros())))
        }
        _ => {
            let _ = ctx;
            Err(no_attr(obj, name))
        }
    }
}

fn str_method(s: &str, name: &str, args: &Args) -> Result<Value, EvalError> {
    let simple = |f: fn(&str) -> String| -> Result<Value, EvalError> {
        arity(args, name, 0, 0)?;
        Ok(Value::from(f(s)))
    };
    let pred = |f: fn(char) -> bool| -> Result<Value, EvalError> {
        arity(args, name, 0, 0)?;
        Ok(Value::Bool(!s.is_empty() && s.chars().all(f)))
    };
    match name {
        "upper" => simple(str::to_uppercase),
        "lower" | "casefold" => simple(str::to_lowercase),
        "swapcase" => simple(|s| {
            s.chars()
                .flat_map(|c| {
                    if c.is_uppercase() {
                        c.to_lowercase().collect::<Vec<_>>()
                    } else {
                        c.to_uppercase().collect::<Vec<_>>()
                    }
                })
                .collect()
        }),
        "capitalize" => simple(|s| {
            let mut cs = s.chars();
            match cs.next() {
                Some(c) => c
                    .to_uppercase()
                    .chain(cs.flat_map(char::to_lowercase))
                    .collect(),
                None => String::new(),
            }
        }),
        "title" => simple(|s| {
            let mut out = String::with_capacity(s.len());
            let mut prev_cased = false;
            for c in s.chars() {
                if prev_cased {
                    out.extend(c.to_lowercase());
                } else {
                    out.extend(c.to_uppercase());
                }
                prev_cased = c.is_alphabetic();
            }
            out
        }),
        "strip" | "lstrip" | "rstrip" => {
            let pos = arity(args, name, 0, 1)?;
            let chars = strip_chars(pos)?;
            let is_strip = |c: char| match &chars {
                Some(set) => set.contains(&c),
                None => c.is_whitespace(),
            };
            let r = match name {
                "strip" => s.trim_matches(is_strip),
                "lstrip" => s.trim_start_matches(is_strip),
                _ => s.trim_end_matches(is_strip),
            };
            Ok(Value::str(r))
        }
        "split" | "rsplit" => {
            let kw = kwargs(args, name, &["sep", "maxsplit"])?;
            let pos = positional(args, name, 0, 2)?;
            let sep = pos
                .first()
                .or(kw_get(&kw, "sep"))
                .filter(|v| !matches!(v, Value::None));
            let maxsplit = pos
                .get(1)
                .or(kw_get(&kw, "maxsplit"))
                .map(int_arg)
                .transpose()?
                .unwrap_or(-1);
            let rsplit = name == "rsplit";
            let parts = match sep {
                None => split_whitespace(s, maxsplit, rsplit),
                Some(sep) => {
                    let sep = str_arg(sep, name)?;
                    if sep.is_empty() {
                        return Err(err("ValueError", "empty separator"));
                    }
                    let parts: Vec<&str> = match (maxsplit, rsplit) {
                        (m, false) if m >= 0 => s.splitn(m as usize + 1, sep).collect(),
                        (m, true) if m >= 0 => {
                            let mut v: Vec<&str> = s.rsplitn(m as usize + 1, sep).collect();
                            v.reverse();
                            v
                        }
                        _ => s.split(sep).collect(),
                    };
                    parts.into_iter().map(Value::str).collect()
                }
            };
            check_items(parts.len())?;
            Ok(Value::list(parts))
        }
        "splitlines" => {
            let kw = kwargs(args, name, &["keepends"])?;
            let pos = positional(args, name, 0, 1)?;
            let keep = pos
                .first()
                .or(kw_get(&kw, "keepends"))
                .is_some_and(Value::is_truthy);
            let mut out = Vec::new();
            let mut start = 0;
            let b: Vec<(usize, char)> = s.char_indices().collect();
            let mut i = 0;
            while i < b.len() {
                let (pos_b, c) = b[i];
                if matches!(
                    c,
                    '\n' | '\r'
                        | '\x0b'
                        | '\x0c'
                        | '\x1c'
                        | '\x1d'
                        | '\x1e'
                        | '\u{85}'
                        | '\u{2028}'
                        | '\u{2029}'
                ) {
                    let mut end = pos_b + c.len_utf8();
                    if c == '\r' && b.get(i + 1).is_some_and(|(_, n)| *n == '\n') {
                        end += 1;
                        i += 1;
                    }
                    out.push(Value::str(if keep {
                        &s[start..end]
                    } else {
                        &s[start..pos_b]
                    }));
                    start = end;
                }
                i += 1;
            }
            if start < s.len() {
                out.push(Value::str(&s[start..]));
            }
            Ok(Value::list(out))
        }
        "replace" => {
            let pos = arity(args, name, 2, 3)?;
            let (old, new) = (str_arg(&pos[0], name)?, str_arg(&pos[1], name)?);
            let count = pos.get(2).map(int_arg).transpose()?.unwrap_or(-1);
            let n_matches = if old.is_empty() {
                s.chars().count() + 1
            } else {
                s.matches(old).count()
            };
            let n = if count < 0 {
                n_matches
            } else {
                n_matches.min(count as usize)
            };
            check_str_len(s.len() + n.saturating_mul(new.len()))?;
            if old.is_empty() {
                let mut out = String::new();
                let mut done = 0;
                for c in s.chars() {
                    if done < n {
                        out.push_str(new);
                        done += 1;
                    }
                    out.push(c);
                }
                if done < n {
                    out.push_str(new);
                }
                return Ok(Value::from(out));
            }
            Ok(Value::from(if count < 0 {
                s.replace(old, new)
            } else {
                s.replacen(old, new, n)
            }))
        }
        "format" => format::str_format(s, &args.pos, &args.kw).map(Value::from),
        "startswith" | "endswith" => {
            let pos = arity(args, name, 1, 3)?;
            let n = s.chars().count();
            let bound = |v: Option<&Value>, d: usize| -> Result<usize, EvalError> {
                match v {
                    None | Some(Value::None) => Ok(d),
                    Some(v) => {
                        let i = int_arg(v)?;
                        Ok(if i < 0 {
                            (i + n as i64).max(0) as usize
                        } else {
                            (i as usize).min(n)
                        })
                    }
                }
            };
            let (a, b) = (bound(pos.get(1), 0)?, bound(pos.get(2), n)?);
            let window = if a <= b {
                &s[byte_at(s, a)..byte_at(s, b)]
            } else {
                ""
            };
            let candidates: Vec<Value> = match &pos[0] {
                Value::Tuple(items) => items.to_vec(),
                Value::Str(_) => vec![pos[0].clone()],
                other => {
                    return Err(type_err(format!(
                        "{name} first arg must be str or a tuple of str, not {}",
                        other.type_name()
                    )))
                }
            };
            if a > b {
                return Ok(Value::Bool(false));
            }
            for c in candidates {
                let c = str_arg(&c, name)?;
                let hit = if name == "startswith" {
                    window.starts_with(c)
                } else {
                    window.ends_with(c)
                };
                if hit {
                    return Ok(Value::Bool(true));
                }
            }
            Ok(Value::Bool(false))
        }
        "join" => {
            let pos = arity(args, name, 1, 1)?;
            let items = iterate(&pos[0])?;
            let mut out = String::new();
            for (i, item) in items.iter().enumerate() {
                let Value::Str(part) = item else {
                    return Err(type_err(format!(
                        "sequence item {i}: expected str instance, {} found",
                        item.type_name()
                    )));
                };
                if i > 0 {
                    out.push_str(s);
                }
                out.push_str(part);
                check_str_len(out.len())?;
            }
            Ok(Value::from(out))
        }
        "find" | "rfind" | "index" | "rindex" | "count" => {
            let pos = arity(args, name, 1, 3)?;
            let (sub, a, b) = find_args(pos, s, name)?;
            if a > b {
                return Ok(Value::Int(if name == "count" { 0 } else { -1 }));
            }
            let (ba, bb) = (byte_at(s, a), byte_at(s, b));
            let window = &s[ba..bb];
            if name == "count" {
                let n = if sub.is_empty() {
                    window.chars().count() + 1
                } else {
                    window.matches(sub.as_str()).count()
                };
                return Ok(Value::Int(n as i64));
            }
            let found = if name.starts_with('r') {
                window.rfind(sub.as_str())
            } else {
                window.find(sub.as_str())
            };
            match found {
                Some(off) => Ok(Value::Int(char_count(s, ba + off) as i64)),
                None if name.ends_with("index") => Err(err("ValueError", "substring not found")),
                None => Ok(Value::Int(-1)),
            }
        }
        "isdigit" | "isdecimal" | "isnumeric" => pred(|c| c.is_ascii_digit() || c.is_numeric()),
        "isalpha" => pred(char::is_alphabetic),
        "isalnum" => pred(char::is_alphanumeric),
        "isspace" => pred(char::is_whitespace),
        "isupper" | "islower" => {
            arity(args, name, 0, 0)?;
            let upper = name == "isupper";
            let cased: Vec<char> = s
                .chars()
                .filter(|c| c.is_uppercase() || c.is_lowercase())
                .collect();
            Ok(Value::Bool(
                !cased.is_empty()
                    && cased.iter().all(|c| {
                        if upper {
                            c.is_uppercase()
                        } else {
                            c.is_lowercase()
                        }
                    }),
            ))
        }
        "isidentifier" => {
            arity(args, name, 0, 0)?;
            let mut cs = s.chars();
            Ok(Value::Bool(
                cs.next().is_some_and(|c| c == '_' || c.is_alphabetic())
                    && cs.all(|c| c == '_' || c.is_alphanumeric()),
            ))
        }
        "zfill" => {
            let pos = arity(args, name, 1, 1)?;
            let width = int_arg(&pos[0])?;
            let n = s.chars().count() as i64;
            if width <= n {
                return Ok(Value::str(s));
            }
            check_str_len(width as usize)?;
            let pad = "0".repeat((width - n) as usize);
            let out = match s.chars().next() {
                Some(c @ ('+' | '-')) => format!("{c}{pad}{}", &s[1..]),
                _ => format!("{pad}{s}"),
            };
            Ok(Value::from(out))
        }
        "center" | "ljust" | "rjust" => {
            let pos = arity(args, name, 1, 2)?;
            let width = int_arg(&pos[0])?;
            let fill = match pos.get(1) {
                Some(v) => {
                    let f = str_arg(v, name)?;
                    let mut cs = f.chars();
                    match (cs.next(), cs.next()) {
                        (Some(c), None) => c,
                        _ => {
                            return Err(type_err(
                                "The fill character must be exactly one character long",
                            ))
                        }
                    }
                }
                None => ' ',
            };
            let n = s.chars().count() as i64;
            if width <= n {
                return Ok(Value::str(s));
            }
            check_str_len(width as usize * fill.len_utf8())?;
            let total = (width - n) as usize;
            let (left, right) = match name {
                "ljust" => (0, total),
                "rjust" => (total, 0),
                _ => {
                    // CPython: left = pad/2 + (pad & width & 1).
                    let left = total / 2 + (total & (width as usize) & 1);
                    (left, total - left)
                }
            };
            let fill_s = fill.to_string();
            Ok(Value::from(format!(
                "{}{s}{}",
                fill_s.repeat(left),
                fill_s.repeat(right)
            )))
        }
        "partition" | "rpartition" => {
            let pos = arity(args, name, 1, 1)?;
            let sep = str_arg(&pos[0], name)?;
            if sep.is_empty() {
                return Err(err("ValueError", "empty separator"));
            }
            let found = if name == "partition" {
                s.find(sep)
            } else {
                s.rfind(sep)
            };
            let parts = match found {
                Some(i) => [&s[..i], sep, &s[i + sep.len()..]],
                None if name == "partition" => [s, "", ""],
                None => ["", "", s],
            };
            Ok(Value::tuple(parts.iter().map(|p| Value::str(p)).collect()))
        }
        "removeprefix" => {
            let pos = arity(args, name, 1, 1)?;
            let p = str_arg(&pos[0], name)?;
            Ok(Value::str(s.strip_prefix(p).unwrap_or(s)))
        }
        "removesuffix" => {
            let pos = arity(args, name, 1, 1)?;
            let p = str_arg(&pos[0], name)?;
            Ok(Value::str(s.strip_suffix(p).unwrap_or(s)))
        }
        _ => Err(no_attr(&Value::str(s), name)),
    }
}
