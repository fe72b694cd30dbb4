//! Python semantics of [`Value`]: `str()`, `repr()`, truthiness, equality and ordering.

use std::cmp::Ordering;
use std::collections::hash_map::{Entry, HashMap};
use std::rc::Rc;

use super::{EvalError, Value};

impl Value {
    /// Python's `str(value)`: floats as `repr` (`1.0`, `0.1`, `1e-05`, `inf`), `True`/`False`, lists as
    /// `[1, 'a']`, dicts as `{'a': 1}`, sets as `{1, 'a'}` / `set()` / `frozenset({1})` (in insertion
    /// order, where Python's is hash-based).
    ///
    /// Unbounded: containers share their items, so a value built by a short expression can have an
    /// exponentially long `str`. For values from untrusted input use [`Value::to_xacro_string_within`].
    pub fn to_xacro_string(&self) -> String {
        match self {
            Value::Str(s) => s.to_string(),
            other => other.repr(),
        }
    }

    /// Python's `repr(value)` (strings quoted as Python quotes them). Unbounded, as
    /// [`Value::to_xacro_string`].
    pub fn repr(&self) -> String {
        let mut out = String::new();
        let _ = self.write_repr(&mut out, usize::MAX);
        out
    }

    /// [`Value::to_xacro_string`], or a `MemoryError` as soon as the text grows beyond `limit` bytes (so in
    /// time and memory proportional to `limit`).
    pub fn to_xacro_string_within(&self, limit: usize) -> Result<String, EvalError> {
        match self {
            Value::Str(s) if s.len() > limit => Err(too_long()),
            Value::Str(s) => Ok(s.to_string()),
            other => other.repr_within(limit),
        }
    }

    /// [`Value::repr`], or a `MemoryError` as soon as the text grows beyond `limit` bytes.
    pub fn repr_within(&self, limit: usize) -> Result<String, EvalError> {
        let mut out = String::new();
        self.write_repr(&mut out, limit)?;
        Ok(out)
    }

    /// Append the repr to `out`, failing once `out` is longer than `limit`. Each value visited costs a step
    /// of the running evaluation's budget.
    fn write_repr(&self, out: &mut String, limit: usize) -> Result<(), EvalError> {
        if out.len() > limit {
            return Err(too_long());
        }
        if !super::eval::charge(1) {
            return Err(super::eval::budget_error());
        }
        match self {
            Value::None => out.push_str("None"),
            Value::Bool(true) => out.push_str("True"),
            Value::Bool(false) => out.push_str("False"),
            Value::Int(i) => out.push_str(&i.to_string()),
            Value::Float(f) => out.push_str(&float_repr(*f)),
            Value::Str(s) if s.len() > limit => return Err(too_long()),
            Value::Str(s) => out.push_str(&str_repr(s)),
            Value::List(items) => {
                out.push('[');
                write_items(items, out, limit)?;
                out.push(']');
            }
            Value::Tuple(items) => {
                out.push('(');
                write_items(items, out, limit)?;
                if items.len() == 1 {
                    out.push(',');
                }
                out.push(')');
            }
            Value::Dict(items) => {
                out.push('{');
                for (i, (k, v)) in items.iter().enumerate() {
                    if i > 0 {
                        out.push_str(", ");
                    }
                    k.write_repr(out, limit)?;
                    out.push_str(": ");
                    v.write_repr(out, limit)?;
                }
                out.push('}');
            }
            Value::Set(items) if items.is_empty() => out.push_str("set()"),
            Value::FrozenSet(items) if items.is_empty() => out.push_str("frozenset()"),
            Value::Set(items) => {
                out.push('{');
                write_items(items, out, limit)?;
                out.push('}');
            }
            Value::FrozenSet(items) => {
                out.push_str("frozenset({");
                write_items(items, out, limit)?;
                out.push_str("})");
            }
            Value::Function(name) => match super::classes::class_name(name) {
                Some(class) => {
                    out.push_str("<class '");
                    out.push_str(class);
                    out.push_str("'>");
                }
                None => {
                    let short = name.rsplit('.').next().unwrap_or(name);
                    out.push_str("<built-in function ");
                    out.push_str(short);
                    out.push('>');
                }
            },
            Value::Namespace(name) => {
                out.push_str("<namespace ");
                out.push_str(name);
                out.push('>');
            }
        }
        if out.len() > limit {
            return Err(too_long());
        }
        Ok(())
    }

    /// Python truthiness.
    pub fn is_truthy(&self) -> bool {
        match self {
            Value::None => false,
            Value::Bool(b) => *b,
            Value::Int(i) => *i != 0,
            Value::Float(f) => *f != 0.0,
            Value::Str(s) => !s.is_empty(),
            Value::List(v) | Value::Tuple(v) | Value::Set(v) | Value::FrozenSet(v) => !v.is_empty(),
            Value::Dict(v) => !v.is_empty(),
            Value::Function(_) | Value::Namespace(_) => true,
        }
    }

    /// Python's type name (`type(value).__name__`), as used in error messages.
    pub fn type_name(&self) -> &'static str {
        match self {
            Value::None => "NoneType",
            Value::Bool(_) => "bool",
            Value::Int(_) => "int",
            Value::Float(_) => "float",
            Value::Str(_) => "str",
            Value::List(_) => "list",
            Value::Tuple(_) => "tuple",
            Value::Dict(_) => "dict",
            Value::Set(_) => "set",
            Value::FrozenSet(_) => "frozenset",
            Value::Function(name) if super::classes::class_name(name).is_some() => "type",
            Value::Function(_) => "builtin_function_or_method",
            Value::Namespace(_) => "NameSpace",
        }
    }

    /// A `str` value.
    pub fn str(s: &str) -> Value {
        Value::Str(Rc::from(s))
    }

    /// A `list` value.
    pub fn list(items: Vec<Value>) -> Value {
        Value::List(Rc::new(items))
    }

    /// A `tuple` value.
    pub fn tuple(items: Vec<Value>) -> Value {
        Value::Tuple(Rc::new(items))
    }

    /// A `dict` value from key/value pairs in insertion order (later duplicates replace earlier values, as in
    /// Python).
    pub fn dict(pairs: Vec<(Value, Value)>) -> Value {
        let mut out: Vec<(Value, Value)> = Vec::with_capacity(pairs.len());
        let mut index = KeyIndex::default();
        for (k, v) in pairs {
            match index.insert(&k, out.len()) {
                Some(i) => out[i].1 = v,
                None => out.push((k, v)),
            }
        }
        Value::Dict(Rc::new(out))
    }

    /// A `set` value of the distinct `items` in insertion order (of equal items the first is kept, as in
    /// Python). The items must be hashable (the caller checks).
    pub fn set(items: Vec<Value>) -> Value {
        Value::Set(Rc::new(distinct(items)))
    }

    /// A `frozenset` value, as [`Value::set`].
    pub fn frozenset(items: Vec<Value>) -> Value {
        Value::FrozenSet(Rc::new(distinct(items)))
    }

    /// Python `==` (numbers compare across `bool`/`int`/`float`, containers element-wise).
    pub fn py_eq(&self, other: &Value) -> bool {
        py_eq(self, other)
    }

    /// The value as a float when it is a number (`bool`, `int`, `float`).
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Bool(b) => Some(f64::from(u8::from(*b))),
            Value::Int(i) => Some(*i as f64),
            Value::Float(f) => Some(*f),
            _ => None,
        }
    }
}

impl From<bool> for Value {
    fn from(b: bool) -> Value {
        Value::Bool(b)
    }
}

impl From<i64> for Value {
    fn from(i: i64) -> Value {
        Value::Int(i)
    }
}

impl From<f64> for Value {
    fn from(f: f64) -> Value {
        Value::Float(f)
    }
}

impl From<&str> for Value {
    fn from(s: &str) -> Value {
        Value::str(s)
    }
}

impl From<String> for Value {
    fn from(s: String) -> Value {
        Value::Str(Rc::from(s))
    }
}

fn write_items(items: &[Value], out: &mut String, limit: usize) -> Result<(), EvalError> {
    for (i, v) in items.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        v.write_repr(out, limit)?;
    }
    Ok(())
}

/// The distinct values of `items` under Python `==`, first occurrences in order.
pub(crate) fn distinct(items: Vec<Value>) -> Vec<Value> {
    let mut index = KeyIndex::default();
    let mut out = Vec::with_capacity(items.len());
    for v in items {
        if index.insert(&v, out.len()).is_none() {
            out.push(v);
        }
    }
    out
}

/// Positions of distinct dict keys or set items, found by Python `==`: numbers and strings through a hash
/// map (a linear search made building a large dict quadratic), other values (tuples, NaN, frozensets) by
/// comparing with each earlier such value.
#[derive(Default)]
pub(crate) struct KeyIndex {
    hashed: HashMap<KeyHash, usize>,
    others: Vec<(Value, usize)>,
}

impl KeyIndex {
    /// An index of `items` (distinct values) at their positions.
    pub(crate) fn of(items: &[Value]) -> KeyIndex {
        let mut index = KeyIndex::default();
        for (i, v) in items.iter().enumerate() {
            index.insert(v, i);
        }
        index
    }

    /// The position of the value equal to `k`.
    pub(crate) fn find(&self, k: &Value) -> Option<usize> {
        match KeyHash::of(k) {
            Some(h) => self.hashed.get(&h).copied(),
            None => self
                .others
                .iter()
                .find(|(v, _)| py_eq(v, k))
                .map(|(_, i)| *i),
        }
    }

    /// The position of the value equal to `k`, or `None` after recording `k` at position `at`.
    pub(crate) fn insert(&mut self, k: &Value, at: usize) -> Option<usize> {
        match KeyHash::of(k) {
            Some(h) => match self.hashed.entry(h) {
                Entry::Occupied(e) => Some(*e.get()),
                Entry::Vacant(e) => {
                    e.insert(at);
                    None
                }
            },
            None => {
                let found = self.find(k);
                if found.is_none() {
                    self.others.push((k.clone(), at));
                }
                found
            }
        }
    }
}

/// A dict key's identity under Python `==`, for the keys that have a simple one: `True == 1 == 1.0`.
#[derive(PartialEq, Eq, Hash)]
enum KeyHash {
    None,
    Int(i64),
    Float(u64),
    Str(Rc<str>),
}

impl KeyHash {
    fn of(v: &Value) -> Option<KeyHash> {
        Some(match v {
            Value::None => KeyHash::None,
            Value::Bool(b) => KeyHash::Int(i64::from(*b)),
            Value::Int(i) => KeyHash::Int(*i),
            Value::Float(f) if f.is_nan() => return None,
            // Integral floats in the i64 range equal that int (-0.0 included); the cast is then exact.
            Value::Float(f) if f.fract() == 0.0 && *f >= -TWO_POW_63 && *f < TWO_POW_63 => {
                KeyHash::Int(*f as i64)
            }
            Value::Float(f) => KeyHash::Float(f.to_bits()),
            Value::Str(s) => KeyHash::Str(s.clone()),
            _ => return None,
        })
    }
}

fn too_long() -> EvalError {
    EvalError::new("MemoryError", "string result too large")
}

/// Python's `repr(float)`: the shortest string that round-trips, in exponent form when the decimal
/// exponent is below -4 or at least 16.
pub(crate) fn float_repr(f: f64) -> String {
    if f.is_nan() {
        return "nan".into();
    }
    if f.is_infinite() {
        return if f > 0.0 { "inf".into() } else { "-inf".into() };
    }
    if f == 0.0 {
        return if f.is_sign_negative() {
            "-0.0".into()
        } else {
            "0.0".into()
        };
    }
    // Rust's `{:e}` gives the shortest round-trip digits: `d[.ddd]e<exp>`.
    let sci = format!("{:e}", f.abs());
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let digits: String = mantissa.chars().filter(|c| c.is_ascii_digit()).collect();
    let sign = if f < 0.0 { "-" } else { "" };
    if !(-4..16).contains(&exp) {
        let mut m = digits[..1].to_string();
        if digits.len() > 1 {
            m.push('.');
            m.push_str(&digits[1..]);
        }
        let esign = if exp < 0 { '-' } else { '+' };
        return format!("{sign}{m}e{esign}{:02}", exp.abs());
    }
    let point = exp + 1; // digits before the decimal point
    let body = if point <= 0 {
        format!("0.{}{}", "0".repeat((-point) as usize), digits)
    } else if (point as usize) >= digits.len() {
        format!("{}{}.0", digits, "0".repeat(point as usize - digits.len()))
    } else {
        format!(
            "{}.{}",
            &digits[..point as usize],
            &digits[point as usize..]
        )
    };
    format!("{sign}{body}")
}

/// Python's `repr(str)`: single quotes unless the text holds a single quote and no double quote.
pub(crate) fn str_repr(s: &str) -> String {
    let quote = if s.contains('\'') && !s.contains('"') {
        '"'
    } else {
        '\''
    };
    let mut out = String::with_capacity(s.len() + 2);
    out.push(quote);
    for ch in s.chars() {
        match ch {
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if c == quote => {
                out.push('\\');
                out.push(c);
            }
            c if (c as u32) < 0x20 || (0x7f..0xa0).contains(&(c as u32)) => {
                out.push_str(&format!("\\x{:02x}", c as u32));
            }
            c if !is_printable(c) => {
                let v = c as u32;
                if v <= 0xff {
                    out.push_str(&format!("\\x{v:02x}"));
                } else if v <= 0xffff {
                    out.push_str(&format!("\\u{v:04x}"));
                } else {
                    out.push_str(&format!("\\U{v:08x}"));
                }
            }
            c => out.push(c),
        }
    }
    out.push(quote);
    out
}

/// An approximation of Python's `str.isprintable` for non-ASCII characters.
fn is_printable(c: char) -> bool {
    let v = c as u32;
    !(c.is_control()
        || c == '\u{ad}'
        || (0x2028..=0x202e).contains(&v)
        || (0x2060..=0x206f).contains(&v)
        || (0xd800..=0xdfff).contains(&v)
        || c == '\u{feff}'
        || (0xfff9..=0xfffb).contains(&v)
        || (0xe000..=0xf8ff).contains(&v)
        || (c.is_whitespace() && c != ' '))
}

/// Number view used by arithmetic and comparisons (`bool` is an `int`).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Num {
    Int(i64),
    Float(f64),
}

pub(crate) fn as_num(v: &Value) -> Option<Num> {
    match v {
        Value::Bool(b) => Some(Num::Int(i64::from(*b))),
        Value::Int(i) => Some(Num::Int(*i)),
        Value::Float(f) => Some(Num::Float(*f)),
        _ => None,
    }
}

/// 2**63 as a float (the first float above `i64::MAX`).
pub(crate) const TWO_POW_63: f64 = (1u64 << 63) as f64;

/// Exact comparison of an int with a float (no precision loss for large ints).
pub(crate) fn cmp_int_float(i: i64, f: f64) -> Option<Ordering> {
    if f.is_nan() {
        return None;
    }
    if f >= TWO_POW_63 {
        return Some(Ordering::Less);
    }
    if f < -TWO_POW_63 {
        return Some(Ordering::Greater);
    }
    let t = f.trunc();
    let ti = t as i64;
    match i.cmp(&ti) {
        Ordering::Equal => 0.0f64.partial_cmp(&(f - t)),
        o => Some(o),
    }
}

pub(crate) fn cmp_num(a: Num, b: Num) -> Option<Ordering> {
    match (a, b) {
        (Num::Int(x), Num::Int(y)) => Some(x.cmp(&y)),
        (Num::Float(x), Num::Float(y)) => x.partial_cmp(&y),
        (Num::Int(x), Num::Float(y)) => cmp_int_float(x, y),
        (Num::Float(x), Num::Int(y)) => cmp_int_float(y, x).map(Ordering::reverse),
    }
}

/// Python `==`.
///
/// Each call costs a step of the running evaluation's budget (containers share items, so a comparison can
/// visit exponentially many); when it runs out the answer is `false` and the evaluation fails.
pub(crate) fn py_eq(a: &Value, b: &Value) -> bool {
    if !super::eval::charge(1) {
        return false;
    }
    if let (Some(x), Some(y)) = (as_num(a), as_num(b)) {
        return cmp_num(x, y) == Some(Ordering::Equal);
    }
    match (a, b) {
        (Value::None, Value::None) => true,
        (Value::Str(x), Value::Str(y)) => x == y,
        (Value::List(x), Value::List(y)) | (Value::Tuple(x), Value::Tuple(y)) => {
            x.len() == y.len() && x.iter().zip(y.iter()).all(|(p, q)| py_eq(p, q))
        }
        (Value::Dict(x), Value::Dict(y)) => {
            x.len() == y.len()
                && x.iter()
                    .all(|(k, v)| y.iter().any(|(k2, v2)| py_eq(k, k2) && py_eq(v, v2)))
        }
        (Value::Set(x) | Value::FrozenSet(x), Value::Set(y) | Value::FrozenSet(y)) => {
            x.len() == y.len() && is_subset(x, y)
        }
        (Value::Function(x), Value::Function(y)) | (Value::Namespace(x), Value::Namespace(y)) => {
            x == y
        }
        _ => false,
    }
}

/// Whether every item of set `x` is in set `y`.
///
/// Costs a step of the running evaluation's budget per item; when it runs out the answer is `false` and
/// the evaluation fails.
pub(crate) fn is_subset(x: &[Value], y: &[Value]) -> bool {
    if x.len() > y.len() || !super::eval::charge(x.len() + y.len()) {
        return false;
    }
    let index = KeyIndex::of(y);
    x.iter().all(|v| index.find(v).is_some())
}

/// Python ordering (`<` and friends); `None` for incomparable values (NaN), a `TypeError` for
/// unsupported type pairs.
pub(crate) fn py_cmp(a: &Value, b: &Value, op: &str) -> Result<Option<Ordering>, EvalError> {
    if !super::eval::charge(1) {
        return Err(super::eval::budget_error());
    }
    if let (Some(x), Some(y)) = (as_num(a), as_num(b)) {
        return Ok(cmp_num(x, y));
    }
    match (a, b) {
        (Value::Str(x), Value::Str(y)) => Ok(Some(x.cmp(y))),
        (Value::List(x), Value::List(y)) | (Value::Tuple(x), Value::Tuple(y)) => {
            for (p, q) in x.iter().zip(y.iter()) {
                if !py_eq(p, q) {
                    return py_cmp(p, q, op);
                }
            }
            Ok(Some(x.len().cmp(&y.len())))
        }
        // Sets are ordered by inclusion: `Less` is a proper subset, `None` neither subset nor superset.
        (Value::Set(x) | Value::FrozenSet(x), Value::Set(y) | Value::FrozenSet(y)) => {
            Ok(match (is_subset(x, y), is_subset(y, x)) {
                (true, true) => Some(Ordering::Equal),
                (true, false) => Some(Ordering::Less),
                (false, true) => Some(Ordering::Greater),
                (false, false) => None,
            })
        }
        _ => Err(EvalError::new(
            "TypeError",
            format!(
                "'{op}' not supported between instances of '{}' and '{}'",
                a.type_name(),
                b.type_name()
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_repr_matches_python() {
        let cases = [
            (1.0, "1.0"),
            (0.1, "0.1"),
            (1e-5, "1e-05"),
            (1e16, "1e+16"),
            (1e15, "1000000000000000.0"),
            (0.0001, "0.0001"),
            (-0.0, "-0.0"),
            (123.456, "123.456"),
            (1.5e300, "1.5e+300"),
            (5e-324, "5e-324"),
            (0.30000000000000004, "0.30000000000000004"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "-inf"),
            (f64::NAN, "nan"),
            (-2.5e-7, "-2.5e-07"),
            (1234567890123456.7, "1234567890123456.8"),
        ];
        for (f, s) in cases {
            assert_eq!(float_repr(f), s, "{f}");
        }
    }

    #[test]
    fn str_and_repr() {
        assert_eq!(Value::str("it's").repr(), "\"it's\"");
        assert_eq!(Value::str("a'b\"c").repr(), "'a\\'b\"c'");
        assert_eq!(Value::str("x\ny").repr(), "'x\\ny'");
        assert_eq!(Value::str("é").repr(), "'é'");
        let l = Value::list(vec![Value::Int(1), Value::Float(2.0), Value::str("a")]);
        assert_eq!(l.to_xacro_string(), "[1, 2.0, 'a']");
        assert_eq!(Value::tuple(vec![Value::Int(1)]).to_xacro_string(), "(1,)");
        assert_eq!(Value::tuple(vec![]).to_xacro_string(), "()");
        assert_eq!(
            Value::dict(vec![(Value::str("a"), Value::Int(1))]).to_xacro_string(),
            "{'a': 1}"
        );
        assert_eq!(Value::set(vec![]).to_xacro_string(), "set()");
        assert_eq!(
            Value::set(vec![Value::str("b"), Value::str("a"), Value::str("b")]).to_xacro_string(),
            "{'b', 'a'}"
        );
        assert_eq!(Value::frozenset(vec![]).to_xacro_string(), "frozenset()");
        assert_eq!(
            Value::frozenset(vec![Value::Int(1), Value::Float(1.0), Value::Bool(true)]).repr(),
            "frozenset({1})"
        );
        assert_eq!(Value::None.to_xacro_string(), "None");
        assert_eq!(Value::Bool(true).to_xacro_string(), "True");
    }

    #[test]
    fn equality_and_order() {
        assert!(py_eq(&Value::Int(1), &Value::Float(1.0)));
        assert!(py_eq(&Value::Bool(true), &Value::Int(1)));
        assert!(!py_eq(&Value::list(vec![]), &Value::tuple(vec![])));
        assert_eq!(cmp_int_float(i64::MAX, TWO_POW_63), Some(Ordering::Less));
        assert_eq!(cmp_int_float(3, 3.5), Some(Ordering::Less));
        assert_eq!(cmp_int_float(-3, -3.5), Some(Ordering::Greater));
        assert!(py_cmp(&Value::Int(1), &Value::str("a"), "<").is_err());
        let (a, ab) = (
            Value::set(vec![Value::str("a")]),
            Value::frozenset(vec![Value::str("b"), Value::str("a")]),
        );
        assert_eq!(py_cmp(&a, &ab, "<").ok(), Some(Some(Ordering::Less)));
        assert_eq!(py_cmp(&ab, &a, "<").ok(), Some(Some(Ordering::Greater)));
        assert_eq!(
            py_cmp(&a, &Value::set(vec![Value::str("b")]), "<").ok(),
            Some(None)
        );
        assert!(ab.py_eq(&Value::set(vec![Value::str("a"), Value::str("b")])));
        assert!(Value::dict(vec![
            (Value::Int(1), Value::Int(2)),
            (Value::Float(1.0), Value::Int(3))
        ])
        .py_eq(&Value::dict(vec![(Value::Int(1), Value::Int(3))])));
    }
}
