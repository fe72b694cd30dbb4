//! `${...}` expressions: the subset of Python that xacro files use, evaluated without running any code.
//!
//! INTERFACE CONTRACT (shared by the expression evaluator and the expander; change only together):
//! - [`parse`] turns the text between `${` and `}` into an [`Expr`]; [`eval`] evaluates it against a [`Scope`].
//! - Names resolve first through [`Scope::lookup`] (xacro properties, innermost scope first, lazily evaluated
//!   by the host), then through the built-ins (Python builtins xacro exposes, `math` functions and constants
//!   both bare and as `math.x`, `python.x`, `xacro.x` namespaces).
//! - Functions that need the host (file access or xacro state) go through [`Scope::call_host`]:
//!   `load_yaml` / `xacro.load_yaml`, `xacro.abs_filename`, `xacro.arg`, `xacro.message`, `xacro.warning`,
//!   `xacro.error`, `xacro.fatal`, `xacro.print_location`, `xacro.dotify`.
//! - [`Value::to_xacro_string`] is Python's `str()` of the value, which is what xacro writes into attributes.

use std::fmt;
use std::rc::Rc;

/// A Python value.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// `None`.
    None,
    /// `True` / `False`.
    Bool(bool),
    /// A Python `int` (values beyond i64 are an error, not a silent wrap).
    Int(i64),
    /// A Python `float`.
    Float(f64),
    /// A Python `str`.
    Str(Rc<str>),
    /// A Python `list`.
    List(Rc<Vec<Value>>),
    /// A Python `tuple`.
    Tuple(Rc<Vec<Value>>),
    /// A Python `dict` in insertion order (YAML maps, `dict(...)` literals). Keys are values; lookups
    /// compare with Python equality. Attribute access `d.key` works on dicts (xacro's YAML wrapper).
    Dict(Rc<Vec<(Value, Value)>>),
    /// A callable built-in or host function, by its qualified name (e.g. `"math.sin"`, `"xacro.load_yaml"`).
    Function(Rc<str>),
    /// A namespace such as `math`, `python` or `xacro`, whose attributes are functions or constants.
    Namespace(Rc<str>),
}

/// A parsed expression (opaque to the host).
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    // Filled in by the evaluator's implementation.
}

/// Why an expression could not be parsed or evaluated.
#[derive(Clone, Debug, PartialEq)]
pub struct EvalError {
    /// Python's error class name as Python xacro would report it: `NameError`, `TypeError`, `SyntaxError`,
    /// `ZeroDivisionError`, `KeyError`, `IndexError`, `ValueError`, `AttributeError`, or `XacroException`
    /// for host failures.
    pub kind: &'static str,
    /// The message, e.g. `name 'wheel_radus' is not defined`.
    pub message: String,
    /// For `NameError`: the undefined name (so the host can suggest close property names).
    pub undefined_name: Option<String>,
    /// Byte offset within the expression text where the problem is, when known.
    pub offset: Option<usize>,
}

impl fmt::Display for EvalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.kind, self.message)
    }
}

impl std::error::Error for EvalError {}

/// What an expression can see beyond the built-ins.
pub trait Scope {
    /// The value of property `name`, `Ok(None)` when no property has that name (then built-ins are tried).
    fn lookup(&self, name: &str) -> Result<Option<Value>, EvalError>;
    /// Call host function `name` (qualified, e.g. `"xacro.load_yaml"`; bare `load_yaml` is passed as
    /// `"xacro.load_yaml"`). `None` when the host does not provide it.
    fn call_host(
        &self,
        name: &str,
        args: &[Value],
        kwargs: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>>;
}

/// Parse the text of one `${...}` expression (without the delimiters).
pub fn parse(text: &str) -> Result<Expr, EvalError> {
    let _ = text;
    Err(EvalError {
        kind: "SyntaxError",
        message: "expression evaluation is not implemented yet".into(),
        undefined_name: None,
        offset: None,
    })
}

/// Evaluate a parsed expression.
pub fn eval(expr: &Expr, scope: &dyn Scope) -> Result<Value, EvalError> {
    let _ = (expr, scope);
    Err(EvalError {
        kind: "SyntaxError",
        message: "expression evaluation is not implemented yet".into(),
        undefined_name: None,
        offset: None,
    })
}

impl Value {
    /// Python's `str(value)`: floats as `repr` (`1.0`, `0.1`, `1e-05`, `inf`), `True`/`False`, lists as
    /// `[1, 'a']`, dicts as `{'a': 1}`.
    pub fn to_xacro_string(&self) -> String {
        String::new()
    }

    /// Python truthiness.
    pub fn is_truthy(&self) -> bool {
        false
    }
}
