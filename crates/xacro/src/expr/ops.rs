//! Python arithmetic, bitwise, unary and membership operators on [`Value`]s.

use std::rc::Rc;

use super::parser::{BinOp, UnOp};
use super::value::{as_num, py_eq, Num};
use super::{classes, format, sets, EvalError, Value};

/// Longest string result in bytes.
pub(crate) const MAX_STR_BYTES: usize = 16 * 1024 * 1024;
/// Most items in a list, tuple or dict result.
pub(crate) const MAX_ITEMS: usize = 1_000_000;

pub(crate) fn too_large() -> EvalError {
    EvalError::new("MemoryError", "result too large")
}

pub(crate) fn check_str_len(n: usize) -> Result<(), EvalError> {
    if n > MAX_STR_BYTES {
        Err(too_large())
    } else {
        Ok(())
    }
}

pub(crate) fn check_items(n: usize) -> Result<(), EvalError> {
    if n > MAX_ITEMS {
        Err(too_large())
    } else {
        Ok(())
    }
}

pub(crate) fn int_overflow() -> EvalError {
    EvalError::new("OverflowError", "integer result does not fit in 64 bits")
}

fn unsupported(op: BinOp, a: &Value, b: &Value) -> EvalError {
    EvalError::new(
        "TypeError",
        format!(
            "unsupported operand type(s) for {}: '{}' and '{}'",
            op.symbol(),
            a.type_name(),
            b.type_name()
        ),
    )
}

fn repeat_count(v: &Value) -> Option<i64> {
    match v {
        Value::Int(i) => Some(*i),
        Value::Bool(b) => Some(i64::from(*b)),
        _ => None,
    }
}

/// Python's float `//` and `%` (divmod with the sign of the divisor).
pub(crate) fn float_divmod(a: f64, b: f64) -> (f64, f64) {
    let mut m = a % b;
    let mut div = (a - m) / b;
    if m != 0.0 {
        if (b < 0.0) != (m < 0.0) {
            m += b;
            div -= 1.0;
        }
    } else {
        m = 0.0f64.copysign(b);
    }
    let floordiv = if div != 0.0 {
        let mut f = div.floor();
        if div - f > 0.5 {
            f += 1.0;
        }
        f
    } else {
        0.0f64.copysign(a / b)
    };
    (floordiv, m)
}

/// Python's int `//` and `%`.
pub(crate) fn int_divmod(a: i64, b: i64) -> Result<(i64, i64), EvalError> {
    if b == 0 {
        return Err(EvalError::new(
            "ZeroDivisionError",
            "integer division or modulo by zero",
        ));
    }
    let q = a.checked_div_euclid(b).ok_or_else(int_overflow)?;
    let r = a.rem_euclid(b);
    // Euclidean remainder is non-negative; Python's takes the sign of the divisor.
    if r != 0 && b < 0 {
        Ok((q - 1, r + b))
    } else {
        Ok((q, r))
    }
}

/// `a ** b` for numbers.
pub(crate) fn pow(a: Num, b: Num) -> Result<Value, EvalError> {
    match (a, b) {
        (Num::Int(x), Num::Int(y)) if y >= 0 => {
            match x {
                0 => return Ok(Value::Int(i64::from(y == 0))),
                1 => return Ok(Value::Int(1)),
                -1 => return Ok(Value::Int(if y % 2 == 0 { 1 } else { -1 })),
                _ => {}
            }
            let y = u32::try_from(y).map_err(|_| int_overflow())?;
            x.checked_pow(y).map(Value::Int).ok_or_else(int_overflow)
        }
        _ => {
            let x = num_f64(a);
            let y = num_f64(b);
            float_pow(x, y).map(Value::Float)
        }
    }
}

pub(crate) fn num_f64(n: Num) -> f64 {
    match n {
        Num::Int(i) => i as f64,
        Num::Float(f) => f,
    }
}

pub(crate) fn float_pow(x: f64, y: f64) -> Result<f64, EvalError> {
    if x == 0.0 && y < 0.0 {
        return Err(EvalError::new(
            "ZeroDivisionError",
            "0.0 cannot be raised to a negative power",
        ));
    }
    if x < 0.0 && x.is_finite() && y.is_finite() && y.fract() != 0.0 {
        return Err(EvalError::new(
            "ValueError",
            "negative number raised to a fractional power gives a complex number, which is not supported",
        ));
    }
    let r = x.powf(y);
    if r.is_infinite() && x.is_finite() && y.is_finite() {
        return Err(EvalError::new(
            "OverflowError",
            "(34, 'Numerical result out of range')",
        ));
    }
    Ok(r)
}

fn int_op(op: BinOp, x: i64, y: i64) -> Result<Value, EvalError> {
    let r = match op {
        BinOp::Add => x.checked_add(y),
        BinOp::Sub => x.checked_sub(y),
        BinOp::Mul => x.checked_mul(y),
        BinOp::Div => {
            if y == 0 {
                return Err(EvalError::new("ZeroDivisionError", "division by zero"));
            }
            return Ok(Value::Float(int_true_div(x, y)));
        }
        BinOp::FloorDiv => return int_divmod(x, y).map(|(q, _)| Value::Int(q)),
        BinOp::Mod => return int_divmod(x, y).map(|(_, r)| Value::Int(r)),
        BinOp::Pow => return pow(Num::Int(x), Num::Int(y)),
        BinOp::BitAnd => Some(x & y),
        BinOp::BitOr => Some(x | y),
        BinOp::BitXor => Some(x ^ y),
        BinOp::LShift => {
            if y < 0 {
                return Err(EvalError::new("ValueError", "negative shift count"));
            }
            if x == 0 {
                Some(0)
            } else if y >= 64 {
                None
            } else {
                let r = x << y;
                if r >> y == x {
                    Some(r)
                } else {
                    None
                }
            }
        }
        BinOp::RShift => {
            if y < 0 {
                return Err(EvalError::new("ValueError", "negative shift count"));
            }
            Some(x >> y.min(63))
        }
        BinOp::MatMul => None,
    };
    r.map(Value::Int).ok_or_else(int_overflow)
}

/// int / int. Exact for operands up to 2**53, which is all xacro files use (Python rounds larger ones
/// correctly; this may differ in the last bit there).
fn int_true_div(x: i64, y: i64) -> f64 {
    x as f64 / y as f64
}

fn float_op(op: BinOp, x: f64, y: f64) -> Result<Value, EvalError> {
    let r = match op {
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        BinOp::Div => {
            if y == 0.0 {
                return Err(EvalError::new(
                    "ZeroDivisionError",
                    "float division by zero",
                ));
            }
            x / y
        }
        BinOp::FloorDiv => {
            if y == 0.0 {
                return Err(EvalError::new(
                    "ZeroDivisionError",
                    "float floor division by zero",
                ));
            }
            float_divmod(x, y).0
        }
        BinOp::Mod => {
            if y == 0.0 {
                return Err(EvalError::new("ZeroDivisionError", "float modulo"));
            }
            float_divmod(x, y).1
        }
        BinOp::Pow => float_pow(x, y)?,
        _ => {
            return Err(unsupported(op, &Value::Float(x), &Value::Float(y)));
        }
    };
    Ok(Value::Float(r))
}

/// Evaluate `a <op> b`.
pub(crate) fn binary(op: BinOp, a: &Value, b: &Value) -> Result<Value, EvalError> {
    if let (Some(x), Some(y)) = (as_num(a), as_num(b)) {
        // `True & False` stays a bool.
        if let (Value::Bool(p), Value::Bool(q)) = (a, b) {
            match op {
                BinOp::BitAnd => return Ok(Value::Bool(*p & *q)),
                BinOp::BitOr => return Ok(Value::Bool(*p | *q)),
                BinOp::BitXor => return Ok(Value::Bool(*p ^ *q)),
                _ => {}
            }
        }
        return match (x, y) {
            (Num::Int(x), Num::Int(y)) => int_op(op, x, y),
            (x, y) => match op {
                BinOp::BitAnd
                | BinOp::BitOr
                | BinOp::BitXor
                | BinOp::LShift
                | BinOp::RShift
                | BinOp::MatMul => Err(unsupported(op, a, b)),
                _ => float_op(op, num_f64(x), num_f64(y)),
            },
        };
    }
    if let Some(r) = sets::binary(op, a, b) {
        return r;
    }
    if let Some(e) = classes::union(op, a, b) {
        return Err(e);
    }
    match (op, a, b) {
        (BinOp::Add, Value::Str(x), Value::Str(y)) => {
            check_str_len(x.len() + y.len())?;
            let mut s = String::with_capacity(x.len() + y.len());
            s.push_str(x);
            s.push_str(y);
            Ok(Value::from(s))
        }
        (BinOp::Add, Value::List(x), Value::List(y)) => Ok(Value::List(Rc::new(concat(x, y)?))),
        (BinOp::Add, Value::Tuple(x), Value::Tuple(y)) => Ok(Value::Tuple(Rc::new(concat(x, y)?))),
        (BinOp::Add, Value::Str(_), _) => Err(EvalError::new(
            "TypeError",
            format!(
                "can only concatenate str (not \"{}\") to str",
                b.type_name()
            ),
        )),
        (BinOp::Add, Value::List(_), _) => Err(EvalError::new(
            "TypeError",
            format!(
                "can only concatenate list (not \"{}\") to list",
                b.type_name()
            ),
        )),
        (BinOp::Add, Value::Tuple(_), _) => Err(EvalError::new(
            "TypeError",
            format!(
                "can only concatenate tuple (not \"{}\") to tuple",
                b.type_name()
            ),
        )),
        (BinOp::Mul, seq, n) | (BinOp::Mul, n, seq)
            if repeat_count(n).is_some()
                && matches!(seq, Value::Str(_) | Value::List(_) | Value::Tuple(_)) =>
        {
            repeat(seq, repeat_count(n).unwrap_or(0))
        }
        (BinOp::Mod, Value::Str(fmt), args) => format::percent_format(fmt, args).map(Value::from),
        _ => Err(unsupported(op, a, b)),
    }
}

fn concat(x: &[Value], y: &[Value]) -> Result<Vec<Value>, EvalError> {
    check_items(x.len() + y.len())?;
    let mut v = Vec::with_capacity(x.len() + y.len());
    v.extend_from_slice(x);
    v.extend_from_slice(y);
    Ok(v)
}

fn repeat(seq: &Value, n: i64) -> Result<Value, EvalError> {
    let n = usize::try_from(n.max(0)).map_err(|_| too_large())?;
    match seq {
        Value::Str(s) => {
            check_str_len(s.len().checked_mul(n).ok_or_else(too_large)?)?;
            Ok(Value::from(s.repeat(n)))
        }
        Value::List(v) | Value::Tuple(v) => {
            check_items(v.len().checked_mul(n).ok_or_else(too_large)?)?;
            let mut out = Vec::with_capacity(v.len() * n);
            // An empty sequence stays empty however large `n` is (`[] * 10**10` must not loop).
            if !v.is_empty() {
                for _ in 0..n {
                    out.extend_from_slice(v);
                }
            }
            Ok(if matches!(seq, Value::List(_)) {
                Value::list(out)
            } else {
                Value::tuple(out)
            })
        }
        _ => Err(EvalError::new("TypeError", "can't multiply sequence")),
    }
}

/// Evaluate a unary operator.
pub(crate) fn unary(op: UnOp, v: &Value) -> Result<Value, EvalError> {
    let bad = || {
        let sym = match op {
            UnOp::Neg => "-",
            UnOp::Pos => "+",
            UnOp::Invert => "~",
        };
        EvalError::new(
            "TypeError",
            format!("bad operand type for unary {sym}: '{}'", v.type_name()),
        )
    };
    match (op, as_num(v)) {
        (UnOp::Neg, Some(Num::Int(i))) => i.checked_neg().map(Value::Int).ok_or_else(int_overflow),
        (UnOp::Neg, Some(Num::Float(f))) => Ok(Value::Float(-f)),
        (UnOp::Pos, Some(Num::Int(i))) => Ok(Value::Int(i)),
        (UnOp::Pos, Some(Num::Float(f))) => Ok(Value::Float(f)),
        (UnOp::Invert, Some(Num::Int(i))) => Ok(Value::Int(!i)),
        _ => Err(bad()),
    }
}

/// Python `needle in haystack`.
pub(crate) fn contains(haystack: &Value, needle: &Value) -> Result<bool, EvalError> {
    match haystack {
        Value::Str(h) => match needle {
            Value::Str(n) => Ok(h.contains(&**n)),
            _ => Err(EvalError::new(
                "TypeError",
                format!(
                    "'in <string>' requires string as left operand, not {}",
                    needle.type_name()
                ),
            )),
        },
        Value::List(items) | Value::Tuple(items) => Ok(items.iter().any(|x| py_eq(x, needle))),
        Value::Dict(items) => Ok(items.iter().any(|(k, _)| py_eq(k, needle))),
        Value::Set(items) | Value::FrozenSet(items) => sets::contains(items, needle),
        _ => Err(EvalError::new(
            "TypeError",
            format!(
                "argument of type '{}' is not iterable",
                haystack.type_name()
            ),
        )),
    }
}

/// Python `a is b` as far as it is observable on immutable values.
pub(crate) fn is_same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::None, Value::None) => true,
        (Value::Bool(x), Value::Bool(y)) => x == y,
        (Value::Int(x), Value::Int(y)) => x == y && (-5..=256).contains(x),
        (Value::Str(x), Value::Str(y)) => Rc::ptr_eq(x, y) || (x == y && x.len() <= 1),
        (Value::List(x), Value::List(y)) | (Value::Tuple(x), Value::Tuple(y)) => Rc::ptr_eq(x, y),
        (Value::Dict(x), Value::Dict(y)) => Rc::ptr_eq(x, y),
        (Value::Set(x), Value::Set(y)) | (Value::FrozenSet(x), Value::FrozenSet(y)) => {
            Rc::ptr_eq(x, y)
        }
        (Value::Function(x), Value::Function(y)) | (Value::Namespace(x), Value::Namespace(y)) => {
            x == y
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_semantics() {
        assert_eq!(int_divmod(-7, 2).ok(), Some((-4, 1)));
        assert_eq!(int_divmod(7, -2).ok(), Some((-4, -1)));
        assert_eq!(int_divmod(-7, -2).ok(), Some((3, -1)));
        assert!(int_divmod(i64::MIN, -1).is_err());
        assert_eq!(float_divmod(-7.0, 2.0), (-4.0, 1.0));
        assert_eq!(float_divmod(7.5, -2.0), (-4.0, -0.5));
    }

    #[test]
    fn power() {
        assert_eq!(pow(Num::Int(2), Num::Int(10)).ok(), Some(Value::Int(1024)));
        assert_eq!(pow(Num::Int(2), Num::Int(-1)).ok(), Some(Value::Float(0.5)));
        assert!(pow(Num::Int(2), Num::Int(64)).is_err());
        assert!(pow(Num::Int(10), Num::Int(i64::MAX)).is_err());
        assert_eq!(
            pow(Num::Int(1), Num::Int(i64::MAX)).ok(),
            Some(Value::Int(1))
        );
        assert!(pow(Num::Float(10.0), Num::Float(400.0)).is_err());
    }

    #[test]
    fn sizes_are_bounded() {
        assert!(binary(BinOp::Mul, &Value::str("ab"), &Value::Int(1 << 40)).is_err());
        assert!(binary(
            BinOp::Mul,
            &Value::list(vec![Value::None]),
            &Value::Int(2_000_000)
        )
        .is_err());
        assert_eq!(
            binary(BinOp::Mul, &Value::Int(3), &Value::str("ab")).ok(),
            Some(Value::str("ababab"))
        );
        assert_eq!(
            binary(BinOp::Mul, &Value::str("ab"), &Value::Int(-3)).ok(),
            Some(Value::str(""))
        );
    }
}
