//! `load_yaml`: a YAML file as an expression value (maps become dicts with dotted access, sequences lists),
//! including Python xacro's unit tags (`!radians`, `!degrees`, `!meters`, `!millimeters`, `!foot`,
//! `!inches`).

use saphyr::{LoadableYamlNode, Scalar, Yaml};

use crate::expr::{EvalError, Value};
use std::rc::Rc;

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
    let docs = Yaml::load_from_str(text).map_err(|e| yaml_error(e.to_string()))?;
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

fn scalar_text(node: &Yaml) -> Option<String> {
    Some(match node {
        Yaml::Value(Scalar::String(s)) => s.to_string(),
        Yaml::Value(Scalar::Integer(i)) => i.to_string(),
        Yaml::Value(Scalar::FloatingPoint(f)) => format!("{:?}", f.into_inner()),
        Yaml::Value(Scalar::Boolean(b)) => if *b { "True" } else { "False" }.to_string(),
        Yaml::Representation(s, _, _) => s.to_string(),
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
        Yaml::Value(s) => match s {
            Scalar::Null => Value::None,
            Scalar::Boolean(b) => Value::Bool(*b),
            Scalar::Integer(i) => Value::Int(*i),
            Scalar::FloatingPoint(f) => Value::Float(f.into_inner()),
            Scalar::String(s) => Value::Str(Rc::from(&**s)),
        },
        Yaml::Representation(s, _, _) => Value::Str(Rc::from(&**s)),
        Yaml::Sequence(items) => Value::List(Rc::new(
            items
                .iter()
                .map(|i| convert(i, eval, depth + 1))
                .collect::<Result<_, _>>()?,
        )),
        Yaml::Mapping(map) => {
            let mut out = Vec::with_capacity(map.len());
            for (k, v) in map {
                out.push((convert(k, eval, depth + 1)?, convert(v, eval, depth + 1)?));
            }
            Value::Dict(Rc::new(out))
        }
        Yaml::Tagged(tag, inner) => {
            let factor = if tag.handle == "!" {
                unit_factor(&tag.suffix)
            } else {
                None
            };
            let Some(factor) = factor else {
                return Err(yaml_error(format!(
                    "could not determine a constructor for the tag '{}{}'",
                    tag.handle, tag.suffix
                )));
            };
            let text = scalar_text(inner).ok_or_else(|| {
                yaml_error(format!("expected a scalar node after !{}", tag.suffix))
            })?;
            let v =
                match eval(&text)? {
                    Value::Int(i) => i as f64,
                    Value::Float(f) => f,
                    Value::Bool(b) => f64::from(u8::from(b)),
                    other => return Err(EvalError {
                        kind: "TypeError",
                        message: format!(
                            "float() argument must be a string or a real number, not '{other:?}'"
                        ),
                        undefined_name: None,
                        offset: None,
                    }),
                };
            Value::Float(v * factor)
        }
        Yaml::Alias(_) => return Err(yaml_error("unresolved YAML alias".into())),
        Yaml::BadValue => return Err(yaml_error("invalid YAML value".into())),
    })
}
