//! The `${...}` evaluator alone: arbitrary text parsed and evaluated as one expression, with a few
//! properties in scope, and the result converted to the text xacro would write.
#![no_main]

use std::rc::Rc;

use libfuzzer_sys::fuzz_target;
use xacro::expr::{self, EvalError, Scope, Value};

struct FuzzScope;

impl Scope for FuzzScope {
    fn lookup(&self, name: &str) -> Result<Option<Value>, EvalError> {
        let s = |t: &str| Value::Str(Rc::from(t));
        Ok(Some(match name {
            "i" => Value::Int(7),
            "neg" => Value::Int(-3),
            "big" => Value::Int(i64::MAX),
            "small" => Value::Int(i64::MIN),
            "f" => Value::Float(0.5),
            "inf" => Value::Float(f64::INFINITY),
            "nan" => Value::Float(f64::NAN),
            "s" => s("abc"),
            "b" => Value::Bool(true),
            "n" => Value::None,
            "l" => Value::List(Rc::new(vec![Value::Int(1), Value::Float(2.5), s("x")])),
            "t" => Value::Tuple(Rc::new(vec![Value::Int(1), Value::Int(2)])),
            "d" => Value::Dict(Rc::new(vec![
                (s("a"), Value::Int(1)),
                (s("b"), Value::List(Rc::new(vec![Value::Int(2)]))),
            ])),
            "err" => return Err(EvalError::new("NameError", "lookup failed")),
            _ => return Ok(None),
        }))
    }

    fn call_host(
        &self,
        name: &str,
        args: &[Value],
        _kwargs: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>> {
        match name {
            "xacro.arg" => Some(Ok(args.first().cloned().unwrap_or(Value::None))),
            "xacro.load_yaml" => Some(Err(EvalError::new("XacroException", "no files"))),
            _ => None,
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match expr::eval_str(text, &FuzzScope) {
        // `to_xacro_string` is unbounded by design (a short expression can build a list with an
        // exponentially long text); the expander converts through the bounded variant.
        Ok(value) => {
            let _ = value.to_xacro_string_within(16 << 20);
        }
        Err(e) => assert!(!e.message.is_empty() || !e.kind.is_empty()),
    }
});
