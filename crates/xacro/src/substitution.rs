//! `$(...)` substitution arguments, as Python xacro's `substitution_args.resolve_args` does them:
//! `$(arg)`, `$(env)`, `$(optenv)`, `$(find)`, `$(dirname)` (`$(eval)` and `$(cwd)` are handled by the
//! expander, which owns the expression evaluator).

use crate::error::{ErrorKind, XacroError};

/// A variable the gate refused (already reported): `$(env)` expands to empty, `$(optenv)` to its default.
pub(crate) struct Refused;

const VALID: [&str; 5] = ["find", "env", "optenv", "dirname", "arg"];

/// What substitutions need from the expander.
pub(crate) trait SubstitutionHost {
    /// The value of argument `name` (given by the caller or declared by `xacro:arg`).
    fn arg(&self, name: &str) -> Result<String, XacroError>;
    /// An environment variable (`Ok(None)`: unset), or `Err` when the gate refused it (the expander has
    /// reported the refusal).
    fn env(&self, name: &str) -> Result<Option<String>, Refused>;
    /// The directory of package `pkg`.
    fn find(&self, pkg: &str) -> Result<String, XacroError>;
    /// The absolute directory of the file being processed.
    fn dirname(&self) -> Result<String, XacroError>;
}

fn subst_error(message: String) -> XacroError {
    XacroError::new(ErrorKind::Substitution, message)
}

/// Resolve the substitution arguments in `text` (two passes, the second one for `$(find)` only, as
/// Python xacro does).
pub(crate) fn resolve_args(text: &str, host: &dyn SubstitutionHost) -> Result<String, XacroError> {
    if text.is_empty() {
        return Ok(String::new());
    }
    let resolved = resolve_pass(text, host, false)?;
    resolve_pass(&resolved, host, true)
}

fn resolve_pass(
    text: &str,
    host: &dyn SubstitutionHost,
    find_only: bool,
) -> Result<String, XacroError> {
    let mut resolved = text.to_string();
    for a in collect_args(text)? {
        let splits: Vec<&str> = a.split(' ').filter(|s| !s.is_empty()).collect();
        let Some((&command, args)) = splits.split_first() else {
            return Err(subst_error(format!("empty substitution command [{a}]")));
        };
        if !VALID.contains(&command) {
            return Err(subst_error(format!(
                "Unknown substitution command [{a}]. Valid commands are ['find', 'env', 'optenv', 'dirname', 'arg']"
            )));
        }
        if find_only && command != "find" {
            continue;
        }
        let value = match command {
            "env" => {
                if args.len() != 1 {
                    return Err(subst_error(format!(
                        "$(env var) command only accepts one argument [{a}]"
                    )));
                }
                match host.env(args[0]) {
                    Ok(Some(value)) => value,
                    Ok(None) => {
                        return Err(subst_error(format!(
                            "environment variable '{}' is not set",
                            args[0]
                        )))
                    }
                    Err(Refused) => String::new(),
                }
            }
            "optenv" => {
                let Some((name, default)) = args.split_first() else {
                    return Err(subst_error(format!(
                        "$(optenv var) must specify an environment variable [{a}]"
                    )));
                };
                host.env(name)
                    .ok()
                    .flatten()
                    .unwrap_or_else(|| default.join(" "))
            }
            "dirname" => host.dirname()?,
            "arg" => match args {
                [] => {
                    return Err(subst_error(format!(
                        "$(arg var) must specify a variable name [{a}]"
                    )))
                }
                [name] => host.arg(name)?,
                _ => {
                    return Err(subst_error(format!(
                        "$(arg var) may only specify one arg [{a}]"
                    )))
                }
            },
            _ => {
                if args.len() != 1 {
                    return Err(subst_error(format!(
                        "$(find pkg) accepts exactly one argument [{a}]"
                    )));
                }
                host.find(args[0])?
            }
        };
        resolved = resolved.replace(&format!("$({a})"), &value);
    }
    Ok(resolved)
}

/// The state machine of `_collect_args`: the contents of every `$(...)` in `text`.
fn collect_args(text: &str) -> Result<Vec<String>, XacroError> {
    #[derive(PartialEq)]
    enum State {
        Out,
        Dollar,
        Lp,
        In,
    }
    let mut state = State::Out;
    let mut buf = String::new();
    let mut args = Vec::new();
    for c in text.chars() {
        match c {
            '$' => match state {
                State::Out | State::Dollar => state = State::Dollar,
                _ => {
                    return Err(subst_error(format!(
                        "Dollar signs \"$\" cannot be inside of substitution args [{text}]"
                    )))
                }
            },
            '(' => match state {
                State::Dollar => state = State::Lp,
                State::Out => {}
                _ => {
                    return Err(subst_error(format!(
                        "Invalid left parenthesis \"(\" in substitution args [{text}]"
                    )))
                }
            },
            ')' => {
                if state == State::In {
                    args.push(std::mem::take(&mut buf));
                }
                state = State::Out;
            }
            _ => match state {
                State::Dollar => state = State::Out,
                State::Lp => state = State::In,
                _ => {}
            },
        }
        if state == State::In {
            buf.push(c);
        }
    }
    Ok(args)
}

/// `convert_value(value, 'auto')` of `$(eval)`: a float if it has a dot, else an int, else a boolean word,
/// else the text.
pub(crate) fn convert_auto(value: &str) -> crate::expr::Value {
    use crate::expr::Value;
    if value.contains('.') {
        if let Some(f) = crate::properties::python_float(value) {
            return Value::Float(f);
        }
    } else if let Some(i) = crate::properties::python_int(value) {
        return Value::Int(i);
    }
    match value.to_lowercase().as_str() {
        "true" => Value::Bool(true),
        "false" => Value::Bool(false),
        _ => Value::Str(value.into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Host;
    impl SubstitutionHost for Host {
        fn arg(&self, name: &str) -> Result<String, XacroError> {
            match name {
                "a" => Ok("1".into()),
                "p" => Ok("$(find pkg)/x".into()),
                _ => Err(XacroError::new(ErrorKind::UndefinedArgument, name)),
            }
        }
        fn env(&self, name: &str) -> Result<Option<String>, Refused> {
            match name {
                "SECRET" => Err(Refused),
                _ => Ok((name == "HOME").then(|| "/home/u".into())),
            }
        }
        fn find(&self, pkg: &str) -> Result<String, XacroError> {
            Ok(format!("/share/{pkg}"))
        }
        fn dirname(&self) -> Result<String, XacroError> {
            Ok("/d".into())
        }
    }

    #[test]
    fn substitutions() {
        assert_eq!(resolve_args("$(arg a)", &Host).unwrap(), "1");
        assert_eq!(resolve_args("$(arg p)", &Host).unwrap(), "/share/pkg/x");
        assert_eq!(resolve_args("$(optenv NOPE a b)", &Host).unwrap(), "a b");
        assert_eq!(resolve_args("$(env HOME)", &Host).unwrap(), "/home/u");
        assert_eq!(resolve_args("$()", &Host).unwrap(), "$()");
        assert_eq!(resolve_args("[$(env SECRET)]", &Host).unwrap(), "[]");
        assert_eq!(resolve_args("$(optenv SECRET d)", &Host).unwrap(), "d");
        assert_eq!(
            resolve_args("$(bogus x)", &Host).unwrap_err().kind,
            ErrorKind::Substitution
        );
        assert_eq!(
            resolve_args("$(env NOPE)", &Host).unwrap_err().kind,
            ErrorKind::Substitution
        );
        assert_eq!(
            resolve_args("$(arg zz)", &Host).unwrap_err().kind,
            ErrorKind::UndefinedArgument
        );
    }
}
