//! `load_yaml`: a YAML file as an expression value (maps become dicts with dotted access, sequences lists),
//! with PyYAML's `safe_load` rules (YAML 1.1 plain scalars: `yes`/`off` are booleans, `010` is octal, `1e3`
//! is a string, `1_000` an integer, duplicate keys keep the last value) and Python xacro's unit tags
//! (`!radians`, `!degrees`, `!meters`, `!millimeters`, `!foot`, `!inches`).

use std::rc::Rc;

use saphyr::{ScalarStyle, Tag, Yaml, YamlLoader};

use crate::expr::{EvalError, Value};

fn yaml_error(message: String) -> EvalError {
    EvalError {
        kind: "YAMLError",
        message,
        undefined_name: None,
        offset: None,
    }
}

/// Parse `text` (one YAML document; empty text is `None`). `eval` evaluates the scalar of a unit tag
/// (Python: `safe_eval(value, _global_symbols)`).
pub(crate) fn load(
    text: &str,
    eval: &dyn Fn(&str) -> Result<Value, EvalError>,
) -> Result<Value, EvalError> {
    let mut loader: YamlLoader<Yaml> = YamlLoader::default();
    loader.early_parse(false);
    loader.allow_duplicate_keys(true);
    let mut parser = saphyr_parser::Parser::new_from_str(text);
    parser
        .load(&mut loader, true)
        .map_err(|e| yaml_error(e.to_string()))?;
    if let Some(e) = loader.error() {
        return Err(yaml_error(e.to_string()));
    }
    let docs = loader.into_documents();
    match docs.as_slice() {
        [] => Ok(Value::None),
        [doc] => convert(doc, eval, 0),
        _ => Err(yaml_error(
            "expected a single document in the stream".into(),
        )),
    }
}

const MAX_DEPTH: usize = 1000;

fn unit_factor(suffix: &str) -> Option<f64> {
    Some(match suffix {
        "radians" | "meters" => 1.0,
        "degrees" => std::f64::consts::PI / 180.0,
        "millimeters" => 0.001,
        "foot" => 0.3048,
        "inches" => 0.0254,
        _ => return None,
    })
}

fn convert(
    node: &Yaml,
    eval: &dyn Fn(&str) -> Result<Value, EvalError>,
    depth: usize,
) -> Result<Value, EvalError> {
    if depth > MAX_DEPTH {
        return Err(yaml_error("YAML nested too deeply".into()));
    }
    Ok(match node {
        Yaml::Representation(text, style, tag) => scalar(text, *style, tag.as_deref(), eval)?,
        Yaml::Value(s) => match s {
            saphyr::Scalar::Null => Value::None,
            saphyr::Scalar::Boolean(b) => Value::Bool(*b),
            saphyr::Scalar::Integer(i) => Value::Int(*i),
            saphyr::Scalar::FloatingPoint(f) => Value::Float(f.into_inner()),
            saphyr::Scalar::String(s) => Value::Str(Rc::from(&**s)),
        },
        Yaml::Sequence(items) => Value::List(Rc::new(
            items
                .iter()
                .map(|i| convert(i, eval, depth + 1))
                .collect::<Result<_, _>>()?,
        )),
        Yaml::Mapping(map) => {
            let pairs = map
                .iter()
                .map(|(k, v)| Ok((convert(k, eval, depth + 1)?, convert(v, eval, depth + 1)?)))
                .collect::<Result<Vec<_>, EvalError>>()?;
            // Duplicate keys keep the last value (Python dict semantics, in linear time).
            Value::dict(pairs)
        }
        Yaml::Tagged(tag, inner) => match &**inner {
            Yaml::Representation(text, style, _) => scalar(text, *style, Some(tag), eval)?,
            _ => {
                return Err(yaml_error(format!(
                    "could not determine a constructor for the tag '{tag}'"
                )))
            }
        },
        Yaml::Alias(_) => return Err(yaml_error("unresolved YAML alias".into())),
        Yaml::BadValue => return Err(yaml_error("invalid YAML value".into())),
    })
}

/// A scalar: explicit tags first, then (plain scalars only) PyYAML's implicit YAML 1.1 resolvers.
fn scalar(
    text: &str,
    style: ScalarStyle,
    tag: Option<&Tag>,
    eval: &dyn Fn(&str) -> Result<Value, EvalError>,
) -> Result<Value, EvalError> {
    if let Some(tag) = tag {
        if tag.handle == "!" {
            if let Some(factor) = unit_factor(&tag.suffix) {
                let v = match eval(text.trim())? {
                    Value::Int(i) => i as f64,
                    Value::Float(f) => f,
                    Value::Bool(b) => f64::from(u8::from(b)),
                    other => {
                        return Err(EvalError {
                            kind: "TypeError",
                            message: format!(
                                "float() argument must be a string or a real number, not '{}'",
                                other.type_name()
                            ),
                            undefined_name: None,
                            offset: None,
                        })
                    }
                };
                return Ok(Value::Float(v * factor));
            }
        }
        if tag.is_yaml_core_schema() {
            let bad = || yaml_error(format!("invalid value for !!{}: {text:?}", tag.suffix));
            return match tag.suffix.as_str() {
                "str" => Ok(Value::Str(text.into())),
                "int" => resolve_int(text).ok_or_else(bad),
                "float" => resolve_float(text)
                    .or_else(|| resolve_int(text).map(to_float))
                    .ok_or_else(bad),
                "bool" => resolve_bool(text).ok_or_else(bad),
                "null" => Ok(Value::None),
                _ => Ok(implicit(text)),
            };
        }
        return Err(yaml_error(format!(
            "could not determine a constructor for the tag '{tag}'"
        )));
    }
    if style != ScalarStyle::Plain {
        return Ok(Value::Str(text.into()));
    }
    Ok(implicit(text))
}

fn to_float(v: Value) -> Value {
    match v {
        Value::Int(i) => Value::Float(i as f64),
        v => v,
    }
}

/// PyYAML's implicit resolution of a plain scalar.
fn implicit(text: &str) -> Value {
    if matches!(text, "" | "~" | "null" | "Null" | "NULL") {
        return Value::None;
    }
    resolve_bool(text)
        .or_else(|| resolve_int(text))
        .or_else(|| resolve_float(text))
        .unwrap_or_else(|| Value::Str(text.into()))
}

fn resolve_bool(text: &str) -> Option<Value> {
    match text {
        "yes" | "Yes" | "YES" | "true" | "True" | "TRUE" | "on" | "On" | "ON" => {
            Some(Value::Bool(true))
        }
        "no" | "No" | "NO" | "false" | "False" | "FALSE" | "off" | "Off" | "OFF" => {
            Some(Value::Bool(false))
        }
        _ => None,
    }
}

fn split_sign(text: &str) -> (i64, &str) {
    match text.as_bytes().first() {
        Some(b'-') => (-1, &text[1..]),
        Some(b'+') => (1, &text[1..]),
        _ => (1, text),
    }
}

/// `int`: `0b` binary, `0x` hex, leading-`0` octal, decimal, sexagesimal `1:30`; `_` ignored.
fn resolve_int(text: &str) -> Option<Value> {
    let (sign, body) = split_sign(text);
    let digits_ok =
        |s: &str, f: fn(u8) -> bool| !s.is_empty() && s.bytes().all(|b| b == b'_' || f(b));
    let clean = |s: &str| s.replace('_', "");
    let value = if let Some(b) = body.strip_prefix("0b") {
        digits_ok(b, |c| c == b'0' || c == b'1')
            .then(|| i64::from_str_radix(&clean(b), 2).ok())??
    } else if let Some(h) = body.strip_prefix("0x") {
        digits_ok(h, |c| c.is_ascii_hexdigit())
            .then(|| i64::from_str_radix(&clean(h), 16).ok())??
    } else if body.len() > 1 && body.starts_with('0') {
        digits_ok(&body[1..], |c| (b'0'..=b'7').contains(&c))
            .then(|| i64::from_str_radix(&clean(&body[1..]), 8).ok())??
    } else if body == "0" {
        0
    } else if body.starts_with(|c: char| ('1'..='9').contains(&c)) && body.contains(':') {
        let mut total: i64 = 0;
        for (i, part) in body.split(':').enumerate() {
            let ok = if i == 0 {
                digits_ok(part, |c| c.is_ascii_digit())
            } else {
                sexagesimal_part(part)
            };
            if !ok {
                return None;
            }
            total = total
                .checked_mul(60)?
                .checked_add(clean(part).parse::<i64>().ok()?)?;
        }
        total
    } else if body.starts_with(|c: char| ('1'..='9').contains(&c)) {
        digits_ok(body, |c| c.is_ascii_digit()).then(|| clean(body).parse::<i64>().ok())??
    } else {
        return None;
    };
    Some(Value::Int(sign * value))
}

fn sexagesimal_part(part: &str) -> bool {
    (1..=2).contains(&part.len())
        && part.bytes().all(|b| b.is_ascii_digit())
        && (part.len() == 1 || part.as_bytes()[0] <= b'5')
}

/// `float`: digits with a `.` (exponent only with a sign), `.5`, sexagesimal, `.inf`, `.nan`.
fn resolve_float(text: &str) -> Option<Value> {
    let (sign, body) = split_sign(text);
    match body {
        ".inf" | ".Inf" | ".INF" => return Some(Value::Float(sign as f64 * f64::INFINITY)),
        ".nan" | ".NaN" | ".NAN" if sign == 1 && !text.starts_with('+') => {
            return Some(Value::Float(f64::NAN))
        }
        _ => {}
    }
    if body.contains(':') {
        let (whole, frac) = body.split_once('.')?;
        let mut total = 0f64;
        for (i, part) in whole.split(':').enumerate() {
            let ok = if i == 0 {
                !part.is_empty() && part.bytes().all(|b| b.is_ascii_digit() || b == b'_')
            } else {
                sexagesimal_part(part)
            };
            if !ok {
                return None;
            }
            total = total * 60.0 + part.replace('_', "").parse::<f64>().ok()?;
        }
        if !frac.bytes().all(|b| b.is_ascii_digit() || b == b'_') {
            return None;
        }
        let frac: f64 = format!("0.{}", frac.replace('_', "")).parse().ok()?;
        return Some(Value::Float(sign as f64 * (total + frac)));
    }
    let (mantissa, exponent) = match body.find(['e', 'E']) {
        Some(i) => (&body[..i], Some(&body[i + 1..])),
        None => (body, None),
    };
    let (int_part, frac_part) = mantissa.split_once('.')?;
    let int_ok = if int_part.is_empty() {
        text.starts_with('.') && frac_part.starts_with(|c: char| c.is_ascii_digit())
    } else {
        int_part.starts_with(|c: char| c.is_ascii_digit())
            && int_part.bytes().all(|b| b.is_ascii_digit() || b == b'_')
    };
    let frac_ok = frac_part.bytes().all(|b| b.is_ascii_digit() || b == b'_');
    let exp_ok = exponent.is_none_or(|e| {
        e.len() > 1 && e.starts_with(['+', '-']) && e[1..].bytes().all(|b| b.is_ascii_digit())
    });
    if !(int_ok && frac_ok && exp_ok) {
        return None;
    }
    let clean = body.replace('_', "").to_ascii_lowercase();
    let clean = if clean.starts_with('.') {
        format!("0{clean}")
    } else {
        clean
    };
    let clean = clean.replace(".e", ".0e");
    let v: f64 = clean.trim_end_matches('.').parse().ok()?;
    Some(Value::Float(sign as f64 * v))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plain(text: &str) -> Value {
        implicit(text)
    }

    #[test]
    fn yaml_1_1_plain_scalars_like_pyyaml() {
        assert_eq!(plain("yes"), Value::Bool(true));
        assert_eq!(plain("Off"), Value::Bool(false));
        assert_eq!(plain("~"), Value::None);
        assert_eq!(plain("010"), Value::Int(8));
        assert_eq!(plain("08"), Value::Str("08".into()));
        assert_eq!(plain("0x1F"), Value::Int(31));
        assert_eq!(plain("0b101"), Value::Int(5));
        assert_eq!(plain("1_000"), Value::Int(1000));
        assert_eq!(plain("-12"), Value::Int(-12));
        assert_eq!(plain("1:30"), Value::Int(90));
        assert_eq!(plain("1e3"), Value::Str("1e3".into()));
        assert_eq!(plain("1.0e5"), Value::Str("1.0e5".into()));
        assert_eq!(plain("1.0e+5"), Value::Float(1.0e5));
        assert_eq!(plain("1."), Value::Float(1.0));
        assert_eq!(plain(".5"), Value::Float(0.5));
        assert_eq!(plain("-.inf"), Value::Float(f64::NEG_INFINITY));
        assert_eq!(plain("3.25"), Value::Float(3.25));
        assert_eq!(plain("abc"), Value::Str("abc".into()));
    }
}
