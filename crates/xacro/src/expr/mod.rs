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
//!
//! SEMANTICS (Python 3.11 as xacro 2.1.1 evaluates it; checked against Python by `golden_tests`):
//! - Grammar: literals (ints with `0x`/`0o`/`0b`/underscores, floats, strings with escapes, `r''`, implicit
//!   concatenation), lists, tuples, dicts, list/dict comprehensions and generator arguments, all operators
//!   with Python precedence (chained comparisons, `in`, `is`, short-circuit `and`/`or` returning operands,
//!   `x if c else y`), indexing, slicing, attributes, calls with `*args`/`**kwargs`.
//! - Bare names: `list dict map len str float int bool min max round sorted range`, every `math` name,
//!   `load_yaml abs_filename dotify`; everything else lives under `python.`, `math.` or `xacro.` exactly as
//!   in xacro (so bare `abs` is a `NameError`, as in Python xacro).
//! - Deliberate differences: integers are 64-bit (`OverflowError` beyond); `range`, `map`, `zip`,
//!   `enumerate`, `filter`, `reversed`, `dict.keys()/values()/items()` produce lists; every dict allows
//!   `d.key` (xacro's YAML wrapper) and a missing key is `KeyError` on `d[k]`, `AttributeError` on `d.k`;
//!   `lambda`, f-strings, bytes, complex numbers, set displays (`{1, 2}`, which cannot appear inside
//!   `${...}` anyway) and `math.erf/erfc/gamma/lgamma` are not supported.
//! - Sets: `python.set(...)` / `python.frozenset(...)` with `in`, `len`, iteration, `==`, subset
//!   comparisons, `| & - ^` and the non-mutating methods; mutating methods (`add`, `update`, ...) are
//!   refused (values are immutable). A set iterates and prints in insertion order (the first of equal
//!   items kept), where Python's order is hash-based and, for strings, differs from run to run: the text
//!   of a set with several items (and the order of `list(s)`, `', '.join(s)`) is the one place the result
//!   may differ from Python's.
//! - Classes: `list dict str float int bool` (bare and under `python.`) and `python.tuple/set/frozenset/
//!   type/...` are constructors and, for `python.isinstance(x, cls)` (`cls` a class or a tuple of them),
//!   classes; they print as `<class 'list'>`. As `range`, `zip`, `dict.keys()`, ... make lists,
//!   `python.isinstance(x, list)` is `True` for their results (`False` in Python); `isinstance` against
//!   `python.range/zip/map/filter/enumerate/reversed` or `xacro.dotify` (whose instances are lists and dicts
//!   here), type unions (`int | None`), `python.type(x)` and `python.issubclass` are refused.
//! - Safety: there is nothing that can run code, open files or reach object internals; names or
//!   attributes starting with `__` are refused at parse time (`XacroException`, as xacro's `safe_eval`),
//!   other `_x` attributes do not exist. Nesting is limited to 200 levels, results to 16 MiB / 1M items,
//!   evaluation to 10M loop steps; no input makes the evaluator panic.

use std::rc::Rc;

mod builtins;
mod classes;
mod eval;
mod format;
#[cfg(test)]
mod golden_tests;
mod lexer;
mod math;
mod ops;
mod parser;
mod sets;
#[cfg(test)]
mod tests;
mod value;

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
    /// A Python `set` (`python.set(...)`): distinct hashable items, in insertion order (see
    /// [`Value::set`]). Values are immutable, so sets have no mutating methods.
    Set(Rc<Vec<Value>>),
    /// A Python `frozenset` (`python.frozenset(...)`), as [`Value::Set`] but hashable.
    FrozenSet(Rc<Vec<Value>>),
    /// A callable built-in or host function, by its qualified name (e.g. `"math.sin"`, `"xacro.load_yaml"`);
    /// the built-in classes (`"python.list"`, ...) are also classes for `python.isinstance`.
    Function(Rc<str>),
    /// A namespace such as `math`, `python` or `xacro`, whose attributes are functions or constants.
    Namespace(Rc<str>),
}

/// A parsed expression (opaque to the host).
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    root: parser::Node,
}

/// Why an expression could not be parsed or evaluated.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{kind}: {message}")]
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

impl EvalError {
    /// An error of Python class `kind` (e.g. `"ValueError"`) with `message`, without name or offset.
    pub fn new(kind: &'static str, message: impl Into<String>) -> Self {
        EvalError {
            kind,
            message: message.into(),
            undefined_name: None,
            offset: None,
        }
    }
}

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
///
/// Errors are `SyntaxError` (with the byte offset), `XacroException` for names or attributes starting
/// with `__` (refused like xacro's `safe_eval`), or `OverflowError` for integer literals beyond 64 bits.
/// Nesting deeper than 200 levels is a `SyntaxError`, never a stack overflow.
pub fn parse(text: &str) -> Result<Expr, EvalError> {
    parser::parse_expression(text).map(|root| Expr { root })
}

/// Evaluate a parsed expression.
///
/// Resource use is bounded: strings above 16 MiB, containers above 1M items, integers beyond i64 and
/// evaluations above 10M loop steps are errors (`MemoryError` / `OverflowError`).
pub fn eval(expr: &Expr, scope: &dyn Scope) -> Result<Value, EvalError> {
    eval::Ctx::new(scope).eval(&expr.root)
}

/// Parse and evaluate `text` in one step.
pub fn eval_str(text: &str, scope: &dyn Scope) -> Result<Value, EvalError> {
    eval(&parse(text)?, scope)
}

/// A [`Scope`] without properties or host functions: only the built-ins are visible.
#[derive(Clone, Copy, Debug, Default)]
pub struct EmptyScope;

impl Scope for EmptyScope {
    fn lookup(&self, _name: &str) -> Result<Option<Value>, EvalError> {
        Ok(None)
    }

    fn call_host(
        &self,
        _name: &str,
        _args: &[Value],
        _kwargs: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>> {
        None
    }
}
