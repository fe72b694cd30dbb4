//! Python's `math` module (3.11) and `round()`.

use std::rc::Rc;

use super::builtins::{float_to_int, int_arg, iterate};
use super::eval::Args;
use super::ops::int_overflow;
use super::value::{as_num, Num};
use super::{EvalError, Value};

/// Every public name of Python 3.11's `math` module that is a function.
const FUNCTIONS: &[&str] = &[
    "acos",
    "acosh",
    "asin",
    "asinh",
    "atan",
    "atan2",
    "atanh",
    "cbrt",
    "ceil",
    "copysign",
    "cos",
    "cosh",
    "degrees",
    "dist",
    "erf",
    "erfc",
    "exp",
    "exp2",
    "expm1",
    "fabs",
    "factorial",
    "floor",
    "fmod",
    "frexp",
    "fsum",
    "gamma",
    "gcd",
    "hypot",
    "isclose",
    "isfinite",
    "isinf",
    "isnan",
    "isqrt",
    "lcm",
    "ldexp",
    "lgamma",
    "log",
    "log1p",
    "log10",
    "log2",
    "modf",
    "pow",
    "radians",
    "remainder",
    "sin",
    "sinh",
    "sqrt",
    "tan",
    "tanh",
    "trunc",
    "prod",
    "perm",
    "comb",
    "nextafter",
    "ulp",
];

/// `math` constants.
fn constant(name: &str) -> Option<f64> {
    Some(match name {
        "pi" => std::f64::consts::PI,
        "e" => std::f64::consts::E,
        "tau" => std::f64::consts::TAU,
        "inf" => f64::INFINITY,
        "nan" => f64::NAN,
        _ => return None,
    })
}

/// A `math` name: a constant or a function.
pub(crate) fn lookup(name: &str) -> Option<Value> {
    if let Some(c) = constant(name) {
        return Some(Value::Float(c));
    }
    FUNCTIONS
        .contains(&name)
        .then(|| Value::Function(Rc::from(format!("math.{name}"))))
}

fn err(kind: &'static str, message: impl Into<String>) -> EvalError {
    EvalError::new(kind, message)
}

fn domain() -> EvalError {
    err("ValueError", "math domain error")
}

fn range() -> EvalError {
    err("OverflowError", "math range error")
}

/// A real-number argument.
fn real(v: &Value) -> Result<f64, EvalError> {
    v.as_f64().ok_or_else(|| {
        err(
            "TypeError",
            format!("must be real number, not {}", v.type_name()),
        )
    })
}

fn nargs<'a>(args: &'a Args, name: &str, n: usize) -> Result<&'a [Value], EvalError> {
    if !args.kw.is_empty() {
        return Err(err(
            "TypeError",
            format!("math.{name}() takes no keyword arguments"),
        ));
    }
    if args.pos.len() != n {
        return Err(err(
            "TypeError",
            format!(
                "math.{name}() takes exactly {n} argument{} ({} given)",
                if n == 1 { "" } else { "s" },
                args.pos.len()
            ),
        ));
    }
    Ok(&args.pos)
}

/// Apply a libm-style function with CPython's error rules: NaN from a non-NaN input is a domain error,
/// an infinity from a finite input a range error (`can_overflow`) or a domain error (poles such as
/// `log(0)`).
fn checked1(x: f64, r: f64, can_overflow: bool) -> Result<Value, EvalError> {
    if r.is_nan() && !x.is_nan() {
        return Err(domain());
    }
    if r.is_infinite() && x.is_finite() {
        return Err(if can_overflow { range() } else { domain() });
    }
    Ok(Value::Float(r))
}

fn float_int(f: f64) -> Result<Value, EvalError> {
    float_to_int(f).map(Value::Int)
}

/// An integer argument; floats are refused as Python 3.10+ does.
fn exact_int(v: &Value) -> Result<i64, EvalError> {
    match v {
        Value::Float(_) => Err(err(
            "TypeError",
            "'float' object cannot be interpreted as an integer",
        )),
        other => int_arg(other),
    }
}

fn gcd(a: i64, b: i64) -> Result<i64, EvalError> {
    let (mut x, mut y) = (a.unsigned_abs(), b.unsigned_abs());
    while y != 0 {
        let t = x % y;
        x = y;
        y = t;
    }
    i64::try_from(x).map_err(|_| int_overflow())
}

/// Shewchuk's exact summation (CPython's `math.fsum`).
fn fsum(items: &[f64]) -> Result<f64, EvalError> {
    let mut partials: Vec<f64> = Vec::new();
    let mut special = 0.0f64;
    let mut inf_sum = 0.0f64;
    for &x0 in items {
        let mut x = x0;
        if !x.is_finite() {
            if x.is_infinite() {
                inf_sum += x;
            }
            special += x;
            continue;
        }
        let mut i = 0;
        for j in 0..partials.len() {
            let mut y = partials[j];
            if x.abs() < y.abs() {
                std::mem::swap(&mut x, &mut y);
            }
            let hi = x + y;
            let lo = y - (hi - x);
            if lo != 0.0 {
                partials[i] = lo;
                i += 1;
            }
            x = hi;
        }
        partials.truncate(i);
        if x.is_infinite() {
            return Err(err("OverflowError", "intermediate overflow in fsum"));
        }
        partials.push(x);
    }
    if special != 0.0 {
        if inf_sum.is_nan() {
            return Err(err("ValueError", "-inf + inf in fsum"));
        }
        return Ok(special);
    }
    let mut hi = 0.0;
    if let Some(mut n) = partials.len().checked_sub(1) {
        hi = partials[n];
        let mut lo = 0.0;
        while n > 0 {
            let x = hi;
            n -= 1;
            let y = partials[n];
            hi = x + y;
            let yr = hi - x;
            lo = y - yr;
            if lo != 0.0 {
                break;
            }
        }
        if n > 0 && ((lo < 0.0 && partials[n - 1] < 0.0) || (lo > 0.0 && partials[n - 1] > 0.0)) {
            let y = lo * 2.0;
            let x = hi + y;
            let yr = x - hi;
            if y == yr {
                hi = x;
            }
        }
    }
    Ok(hi)
}

/// Next float after `x` towards `y`.
fn nextafter(x: f64, y: f64) -> f64 {
    if x.is_nan() || y.is_nan() {
        return f64::NAN;
    }
    if x == y {
        return y;
    }
    if x == 0.0 {
        return f64::from_bits(1).copysign(y);
    }
    let bits = x.to_bits();
    let up = (y > x) == (x > 0.0);
    f64::from_bits(if up { bits + 1 } else { bits - 1 })
}

fn ulp(x: f64) -> f64 {
    if x.is_nan() {
        return x;
    }
    let x = x.abs();
    if x.is_infinite() {
        return x;
    }
    let next = nextafter(x, f64::INFINITY);
    if next.is_infinite() {
        let prev = nextafter(x, -f64::INFINITY);
        return x - prev;
    }
    next - x
}

/// Call `math.<name>`.
pub(crate) fn call(name: &str, args: &Args) -> Result<Value, EvalError> {
    let one = |f: fn(f64) -> f64, can_overflow: bool| -> Result<Value, EvalError> {
        let x = real(&nargs(args, name, 1)?[0])?;
        checked1(x, f(x), can_overflow)
    };
    match name {
        "acos" => one(f64::acos, false),
        "acosh" => one(f64::acosh, false),
        "asin" => one(f64::asin, false),
        "asinh" => one(f64::asinh, false),
        "atan" => one(f64::atan, false),
        "atanh" => one(f64::atanh, false),
        "cbrt" => one(f64::cbrt, true),
        "cos" => one(f64::cos, false),
        "cosh" => one(f64::cosh, true),
        "degrees" => one(f64::to_degrees, true),
        "radians" => one(f64::to_radians, true),
        "exp" => one(f64::exp, true),
        "exp2" => one(f64::exp2, true),
        "expm1" => one(f64::exp_m1, true),
        "fabs" => one(f64::abs, false),
        "log1p" => one(f64::ln_1p, false),
        "log10" => log_of(args, name, f64::log10),
        "log2" => log_of(args, name, f64::log2),
        "sin" => one(f64::sin, false),
        "sinh" => one(f64::sinh, true),
        "sqrt" => one(f64::sqrt, false),
        "tan" => one(f64::tan, false),
        "tanh" => one(f64::tanh, false),
        "erf" | "erfc" | "gamma" | "lgamma" => Err(err(
            "XacroException",
            format!("math.{name}() is not supported by the native xacro expander"),
        )),
        "ceil" | "floor" | "trunc" => {
            let v = &nargs(args, name, 1)?[0];
            match as_num(v) {
                Some(Num::Int(i)) => Ok(Value::Int(i)),
                Some(Num::Float(f)) => float_int(match name {
                    "ceil" => f.ceil(),
                    "floor" => f.floor(),
                    _ => f.trunc(),
                }),
                None => Err(err(
                    "TypeError",
                    format!("must be real number, not {}", v.type_name()),
                )),
            }
        }
        "isfinite" | "isinf" | "isnan" => {
            let x = real(&nargs(args, name, 1)?[0])?;
            Ok(Value::Bool(match name {
                "isfinite" => x.is_finite(),
                "isinf" => x.is_infinite(),
                _ => x.is_nan(),
            }))
        }
        "ulp" => Ok(Value::Float(ulp(real(&nargs(args, name, 1)?[0])?))),
        "frexp" => {
            let x = real(&nargs(args, name, 1)?[0])?;
            let (m, e) = frexp(x);
            Ok(Value::tuple(vec![Value::Float(m), Value::Int(e)]))
        }
        "modf" => {
            let x = real(&nargs(args, name, 1)?[0])?;
            if x.is_infinite() {
                return Ok(Value::tuple(vec![
                    Value::Float(0.0f64.copysign(x)),
                    Value::Float(x),
                ]));
            }
            let t = x.trunc();
            Ok(Value::tuple(vec![
                Value::Float((x - t).copysign(x)),
                Value::Float(t),
            ]))
        }
        "atan2" | "copysign" | "fmod" | "remainder" | "nextafter" => {
            let p = nargs(args, name, 2)?;
            let (x, y) = (real(&p[0])?, real(&p[1])?);
            let r = match name {
                "atan2" => x.atan2(y),
                "copysign" => x.copysign(y),
                "fmod" => {
                    if y == 0.0 && !x.is_nan() || x.is_infinite() && !y.is_nan() {
                        return Err(domain());
                    }
                    if y.is_infinite() && x.is_finite() {
                        x
                    } else {
                        x % y
                    }
                }
                "remainder" => {
                    if (y == 0.0 || x.is_infinite()) && !x.is_nan() && !y.is_nan() {
                        return Err(domain());
                    }
                    remainder(x, y)
                }
                _ => nextafter(x, y),
            };
            Ok(Value::Float(r))
        }
        "pow" => {
            let p = nargs(args, name, 2)?;
            let (x, y) = (real(&p[0])?, real(&p[1])?);
            if x == 0.0 && y < 0.0 && y.is_finite() {
                return Err(domain());
            }
            if x < 0.0 && x.is_finite() && y.is_finite() && y.fract() != 0.0 {
                return Err(domain());
            }
            let r = x.powf(y);
            if r.is_infinite() && x.is_finite() && y.is_finite() {
                return Err(range());
            }
            Ok(Value::Float(r))
        }
        "ldexp" => {
            let p = nargs(args, name, 2)?;
            let x = real(&p[0])?;
            let e = exact_int(&p[1])?;
            let mut e = e.clamp(-2200, 2200);
            let mut r = x;
            while e > 1000 {
                r *= 2f64.powi(1000);
                e -= 1000;
            }
            while e < -1000 {
                r *= 2f64.powi(-1000);
                e += 1000;
            }
            r *= 2f64.powi(e as i32);
            if r.is_infinite() && x.is_finite() {
                return Err(range());
            }
            Ok(Value::Float(r))
        }
        "log" => {
            if !args.kw.is_empty() || args.pos.is_empty() || args.pos.len() > 2 {
                return Err(err(
                    "TypeError",
                    format!("log expected 1 or 2 arguments, got {}", args.pos.len()),
                ));
            }
            let ln = |v: &Value| -> Result<f64, EvalError> {
                let x = real(v)?;
                if x <= 0.0 {
                    return Err(domain());
                }
                Ok(x.ln())
            };
            let num = ln(&args.pos[0])?;
            match args.pos.get(1) {
                None => Ok(Value::Float(num)),
                Some(b) => {
                    let den = ln(b)?;
                    if den == 0.0 {
                        return Err(err("ZeroDivisionError", "float division by zero"));
                    }
                    Ok(Value::Float(num / den))
                }
            }
        }
        "hypot" => {
            if !args.kw.is_empty() {
                return Err(err("TypeError", "hypot() takes no keyword arguments"));
            }
            let xs: Vec<f64> = args.pos.iter().map(real).collect::<Result<_, _>>()?;
            Ok(Value::Float(hypot(&xs)))
        }
        "dist" => {
            let p = nargs(args, name, 2)?;
            let (a, b) = (iterate(&p[0])?, iterate(&p[1])?);
            if a.len() != b.len() {
                return Err(err(
                    "ValueError",
                    "both points must have the same number of dimensions",
                ));
            }
            let d: Vec<f64> = a
                .iter()
                .zip(b.iter())
                .map(|(x, y)| Ok(real(x)? - real(y)?))
                .collect::<Result<_, EvalError>>()?;
            Ok(Value::Float(hypot(&d)))
        }
        "isclose" => {
            if args.pos.len() != 2 {
                return Err(err(
                    "TypeError",
                    "isclose() takes exactly 2 positional arguments",
                ));
            }
            let (a, b) = (real(&args.pos[0])?, real(&args.pos[1])?);
            let mut rel = 1e-9;
            let mut abs_tol = 0.0;
            for (k, v) in &args.kw {
                match k.as_str() {
                    "rel_tol" => rel = real(v)?,
                    "abs_tol" => abs_tol = real(v)?,
                    _ => {
                        return Err(err(
                            "TypeError",
                            format!("isclose() got an unexpected keyword argument '{k}'"),
                        ))
                    }
                }
            }
            if rel < 0.0 || abs_tol < 0.0 {
                return Err(err("ValueError", "tolerances must be non-negative"));
            }
            if a == b {
                return Ok(Value::Bool(true));
            }
            if a.is_infinite() || b.is_infinite() {
                return Ok(Value::Bool(false));
            }
            let diff = (b - a).abs();
            Ok(Value::Bool(
                diff <= (rel * b).abs() || diff <= (rel * a).abs() || diff <= abs_tol,
            ))
        }
        "fsum" => {
            let items = iterate(&nargs(args, name, 1)?[0])?;
            let xs: Vec<f64> = items.iter().map(real).collect::<Result<_, _>>()?;
            fsum(&xs).map(Value::Float)
        }
        "prod" => {
            let mut acc = Value::Int(1);
            for (k, v) in &args.kw {
                if k != "start" {
                    return Err(err(
                        "TypeError",
                        format!("prod() got an unexpected keyword argument '{k}'"),
                    ));
                }
                acc = v.clone();
            }
            if args.pos.len() != 1 {
                return Err(err(
                    "TypeError",
                    "prod() takes exactly 1 positional argument",
                ));
            }
            for item in iterate(&args.pos[0])? {
                acc = super::ops::binary(super::parser::BinOp::Mul, &acc, &item)?;
            }
            Ok(acc)
        }
        "gcd" | "lcm" => {
            if !args.kw.is_empty() {
                return Err(err(
                    "TypeError",
                    format!("{name}() takes no keyword arguments"),
                ));
            }
            let mut acc: i64 = if name == "gcd" { 0 } else { 1 };
            for v in &args.pos {
                let x = exact_int(v)?;
                acc = if name == "gcd" {
                    gcd(acc, x)?
                } else if acc == 0 || x == 0 {
                    0
                } else {
                    let g = gcd(acc, x)?;
                    (acc / g)
                        .checked_mul(x)
                        .ok_or_else(int_overflow)?
                        .checked_abs()
                        .ok_or_else(int_overflow)?
                };
            }
            Ok(Value::Int(acc))
        }
        "factorial" => {
            let n = exact_int(&nargs(args, name, 1)?[0])?;
            if n < 0 {
                return Err(err(
                    "ValueError",
                    "factorial() not defined for negative values",
                ));
            }
            (1..=n)
                .try_fold(1i64, |acc, k| acc.checked_mul(k))
                .map(Value::Int)
                .ok_or_else(int_overflow)
        }
        "isqrt" => {
            let n = exact_int(&nargs(args, name, 1)?[0])?;
            if n < 0 {
                return Err(err("ValueError", "isqrt() argument must be nonnegative"));
            }
            let mut r = (n as f64).sqrt() as i64;
            while r.checked_mul(r).is_none_or(|sq| sq > n) {
                r -= 1;
            }
            while (r + 1).checked_mul(r + 1).is_some_and(|sq| sq <= n) {
                r += 1;
            }
            Ok(Value::Int(r))
        }
        "comb" | "perm" => {
            if !args.kw.is_empty()
                || args.pos.is_empty()
                || args.pos.len() > 2
                || (name == "comb" && args.pos.len() != 2)
            {
                return Err(err(
                    "TypeError",
                    format!("{name}() takes the wrong number of arguments"),
                ));
            }
            let n = exact_int(&args.pos[0])?;
            let k = match args.pos.get(1) {
                Some(Value::None) | None => n,
                Some(v) => exact_int(v)?,
            };
            if n < 0 || k < 0 {
                return Err(err(
                    "ValueError",
                    format!(
                        "{} must be a non-negative integer",
                        if n < 0 { "n" } else { "k" }
                    ),
                ));
            }
            if k > n {
                return Ok(Value::Int(0));
            }
            let k = if name == "comb" { k.min(n - k) } else { k };
            let mut acc: i128 = 1;
            for i in 0..k {
                acc *= i128::from(n - i);
                if name == "comb" {
                    acc /= i128::from(i + 1);
                }
                if acc > i128::from(i64::MAX) {
                    return Err(int_overflow());
                }
            }
            Ok(Value::Int(acc as i64))
        }
        _ => Err(err("NameError", format!("name '{name}' is not defined"))),
    }
}

fn log_of(args: &Args, name: &str, f: fn(f64) -> f64) -> Result<Value, EvalError> {
    let x = real(&nargs(args, name, 1)?[0])?;
    if x <= 0.0 {
        return Err(domain());
    }
    Ok(Value::Float(f(x)))
}

/// IEEE 754 remainder (round-half-even quotient).
fn remainder(x: f64, y: f64) -> f64 {
    if x.is_nan() || y.is_nan() {
        return f64::NAN;
    }
    if y.is_infinite() {
        return x;
    }
    let absx = x.abs();
    let absy = y.abs();
    let m = absx % absy;
    let c = absy - m;
    let r = if m < c {
        m
    } else if m > c {
        -c
    } else {
        m - 2.0 * ((0.5 * (absx - m)) % absy)
    };
    1.0f64.copysign(x) * r
}

/// `math.hypot` over any number of coordinates.
fn hypot(xs: &[f64]) -> f64 {
    if xs.iter().any(|x| x.is_infinite()) {
        return f64::INFINITY;
    }
    if xs.iter().any(|x| x.is_nan()) {
        return f64::NAN;
    }
    match xs {
        [] => 0.0,
        [x] => x.abs(),
        [x, y] => x.hypot(*y),
        _ => {
            let max = xs.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            if max == 0.0 {
                return 0.0;
            }
            let s: f64 = xs.iter().map(|x| (x / max) * (x / max)).sum();
            max * s.sqrt()
        }
    }
}

fn frexp(x: f64) -> (f64, i64) {
    if x == 0.0 || !x.is_finite() {
        return (x, 0);
    }
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i64;
    if exp == 0 {
        // Subnormal: scale up first.
        let (m, e) = frexp(x * 2f64.powi(64));
        return (m, e - 64);
    }
    let e = exp - 1022;
    let m = f64::from_bits((bits & !(0x7ffu64 << 52)) | (1022u64 << 52));
    (m, e)
}

/// Python's `round(x[, ndigits])`.
pub(crate) fn round(x: &Value, ndigits: Option<i64>) -> Result<Value, EvalError> {
    match (as_num(x), ndigits) {
        (Some(Num::Int(i)), None) => Ok(Value::Int(i)),
        (Some(Num::Int(i)), Some(nd)) => {
            if nd >= 0 {
                return Ok(Value::Int(i));
            }
            if nd < -18 {
                return Ok(Value::Int(0));
            }
            let p = 10i64.pow((-nd) as u32);
            let (q, r) = (i.div_euclid(p), i.rem_euclid(p));
            let q = if 2 * (r as i128) > p as i128 || (2 * (r as i128) == p as i128 && q % 2 != 0) {
                q + 1
            } else {
                q
            };
            q.checked_mul(p).map(Value::Int).ok_or_else(int_overflow)
        }
        (Some(Num::Float(f)), None) => float_to_int(f.round_ties_even()).map(Value::Int),
        (Some(Num::Float(f)), Some(nd)) => Ok(Value::Float(round_float(f, nd))),
        (None, _) => Err(EvalError::new(
            "TypeError",
            format!("type {} doesn't define __round__ method", x.type_name()),
        )),
    }
}

/// Correctly rounded `round(f, nd)` (half-even on the exact binary value, as CPython does).
fn round_float(f: f64, nd: i64) -> f64 {
    if !f.is_finite() || f == 0.0 {
        return f;
    }
    if nd > 323 {
        return f;
    }
    if nd < -308 {
        return 0.0f64.copysign(f);
    }
    if nd >= 0 {
        // Rust's fixed-precision formatting is exact and rounds half to even.
        let s = format!("{:.*}", nd as usize, f);
        return s.parse::<f64>().unwrap_or(f);
    }
    // Negative digits: round the exact integer part at position -nd.
    let k = (-nd) as usize;
    let int_digits = format!("{:.0}", f.abs().trunc());
    let frac = f.abs() - f.abs().trunc();
    if int_digits.len() < k {
        // |f| < 10**(k-1): below half of 10**k.
        return 0.0f64.copysign(f);
    }
    let (head, tail) = int_digits.split_at(int_digits.len() - k);
    let half = format!("5{}", "0".repeat(k - 1));
    let cmp = tail.cmp(half.as_str());
    let last_odd = head.bytes().last().is_some_and(|d| (d - b'0') % 2 == 1);
    let up = match cmp {
        std::cmp::Ordering::Greater => true,
        std::cmp::Ordering::Less => false,
        std::cmp::Ordering::Equal => frac > 0.0 || last_odd,
    };
    let mut digits: Vec<u8> = head.bytes().collect();
    if up {
        let mut i = digits.len();
        loop {
            if i == 0 {
                digits.insert(0, b'1');
                break;
            }
            i -= 1;
            if digits[i] == b'9' {
                digits[i] = b'0';
            } else {
                digits[i] += 1;
                break;
            }
        }
    }
    let s = format!("{}{}", String::from_utf8_lossy(&digits), "0".repeat(k));
    s.parse::<f64>().unwrap_or(f).copysign(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding() {
        assert_eq!(round_float(0.125, 2), 0.12);
        assert_eq!(round_float(0.375, 2), 0.38);
        assert_eq!(round_float(2.675, 2), 2.67);
        assert_eq!(round_float(1234.5, -2), 1200.0);
        assert_eq!(round_float(1250.0, -2), 1200.0);
        assert_eq!(round_float(1350.0, -2), 1400.0);
        assert_eq!(round_float(-1251.0, -2), -1300.0);
        assert_eq!(round_float(49.0, -2), 0.0);
        assert_eq!(round_float(51.0, -2), 100.0);
        assert_eq!(round(&Value::Float(2.5), None).ok(), Some(Value::Int(2)));
        assert_eq!(round(&Value::Float(3.5), None).ok(), Some(Value::Int(4)));
        assert_eq!(
            round(&Value::Int(1250), Some(-2)).ok(),
            Some(Value::Int(1200))
        );
        assert_eq!(
            round(&Value::Int(-1350), Some(-2)).ok(),
            Some(Value::Int(-1400))
        );
    }

    #[test]
    fn fsum_is_exact() {
        assert_eq!(fsum(&[0.1; 10]).ok(), Some(1.0));
        assert_eq!(
            fsum(&[1e100, 1.0, -1e100, 1e-100, 1e50, -1.0, -1e50]).ok(),
            Some(1e-100)
        );
    }

    #[test]
    fn frexp_and_friends() {
        assert_eq!(frexp(8.0), (0.5, 4));
        assert_eq!(frexp(-0.1), (-0.8, -3));
        assert_eq!(nextafter(1.0, 2.0), 1.0000000000000002);
        assert_eq!(ulp(1.0), f64::EPSILON);
        assert_eq!(remainder(5.0, 2.0), 1.0);
        assert_eq!(remainder(7.0, 2.0), -1.0);
        assert_eq!(remainder(-7.0, 2.0), 1.0);
    }
}
