//! Expansion errors: what went wrong, where (file:line:col), and through which includes and macro calls.

use std::fmt;
use std::path::PathBuf;

/// The class of an expansion error. Each kind corresponds to one failure of Python xacro 2.1.1 (its
/// `XacroException` message, or the Python exception it wraps), so callers and tests can match on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    /// A source file is not well-formed XML (or holds a DTD, which is refused). Python: `XML parsing error`.
    XmlParse,
    /// A file could not be read (the entry file, an include, a YAML file). Python: `No such file or directory`.
    Io,
    /// An included file does not exist. Python: `No such file or directory: <path>`.
    IncludeNotFound,
    /// `$(find pkg)` named a package that no search path holds. Python: `PackageNotFoundError`.
    PackageNotFound,
    /// An expression used a name that is neither a property nor a built-in. Python: `NameError`.
    UndefinedProperty,
    /// `$(arg name)` or `xacro.arg(name)` named an argument that was never declared nor given.
    /// Python: `Undefined substitution argument`.
    UndefinedArgument,
    /// A malformed or unknown `$(...)` substitution, or `$(env VAR)` of an unset variable.
    Substitution,
    /// A `${...}` expression could not be parsed or evaluated (Python `SyntaxError`, `TypeError`,
    /// `ZeroDivisionError`, ...; the Python class is in the message).
    Expression,
    /// An expression used a name starting with `__` (Python: `Use of invalid name(s)`), or a property name
    /// is not a valid identifier.
    InvalidName,
    /// A `<xacro:foo>` call of a macro that is not defined. Python: `unknown macro name`.
    UnknownMacro,
    /// A macro was called without a parameter that has no default. Python: `Undefined parameters`.
    MissingParameter,
    /// A macro was called with an attribute that is not one of its parameters. Python: `Invalid parameter`.
    UnknownParameter,
    /// Block parameters: not enough blocks, an unused block, or `xacro:insert_block` of an undefined block.
    Block,
    /// A xacro tag lacks a required attribute. Python: `missing attribute`.
    MissingAttribute,
    /// `xacro:if` / `xacro:unless` value is not a boolean. Python: `Xacro conditional ... is not a boolean
    /// expression`.
    BadCondition,
    /// A property refers to itself through lazy evaluation. Python: `circular variable definition`.
    CircularProperty,
    /// `load_yaml` could not parse its file.
    Yaml,
    /// `xacro.fatal(...)` was called.
    Fatal,
    /// Any other error Python xacro reports as a `XacroException` (bad macro name, empty element name,...).
    Other,
    /// Includes form a cycle (Python recurses until `RecursionError`).
    IncludeCycle,
    /// A safety limit was hit: macro call depth (runaway recursion; Python: `RecursionError`), include
    /// depth, nesting depth, number of output nodes or output size.
    Limit,
    /// A bug in the expander (it caught its own panic); please report it.
    Internal,
}

impl ErrorKind {
    /// A short stable name (`undefined-property`, `unknown-macro`, ...).
    pub fn name(self) -> &'static str {
        match self {
            ErrorKind::XmlParse => "xml-parse",
            ErrorKind::Io => "io",
            ErrorKind::IncludeNotFound => "include-not-found",
            ErrorKind::PackageNotFound => "package-not-found",
            ErrorKind::UndefinedProperty => "undefined-property",
            ErrorKind::UndefinedArgument => "undefined-argument",
            ErrorKind::Substitution => "substitution",
            ErrorKind::Expression => "expression",
            ErrorKind::InvalidName => "invalid-name",
            ErrorKind::UnknownMacro => "unknown-macro",
            ErrorKind::MissingParameter => "missing-parameter",
            ErrorKind::UnknownParameter => "unknown-parameter",
            ErrorKind::Block => "block",
            ErrorKind::MissingAttribute => "missing-attribute",
            ErrorKind::BadCondition => "bad-condition",
            ErrorKind::CircularProperty => "circular-property",
            ErrorKind::Yaml => "yaml",
            ErrorKind::Fatal => "fatal",
            ErrorKind::Other => "other",
            ErrorKind::IncludeCycle => "include-cycle",
            ErrorKind::Limit => "limit",
            ErrorKind::Internal => "internal",
        }
    }
}

/// A position in a source file, 1-based line and column (column counted in characters).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The file.
    pub path: PathBuf,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub col: usize,
    /// Byte offset in the file.
    pub byte: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.path.display(), self.line, self.col)
    }
}

/// One entry of the include / macro-call stack of an error, innermost first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StackEntry {
    /// Whether this is a macro call or an include.
    pub kind: crate::source_map::FrameKind,
    /// The macro name, or the included file's path.
    pub name: String,
    /// Where the call or the `xacro:include` tag is.
    pub location: Location,
}

/// Why an expansion failed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct XacroError {
    /// The class of the error.
    pub kind: ErrorKind,
    /// The message (without the location), e.g. `name 'wheel_radus' is not defined (did you mean
    /// 'wheel_radius'?)`.
    pub message: String,
    /// Where in the sources the problem is, when known.
    pub location: Option<Location>,
    /// The macro calls and includes that led there, innermost first.
    pub stack: Vec<StackEntry>,
}

impl XacroError {
    /// An error without a location yet.
    pub(crate) fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        XacroError {
            kind,
            message: message.into(),
            location: None,
            stack: Vec::new(),
        }
    }
}

impl fmt::Display for XacroError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.location {
            Some(loc) => write!(f, "{loc}: {}", self.message)?,
            None => write!(f, "{}", self.message)?,
        }
        for entry in &self.stack {
            match entry.kind {
                crate::source_map::FrameKind::Macro => write!(
                    f,
                    "\n  in macro '{}' called at {}",
                    entry.name, entry.location
                )?,
                crate::source_map::FrameKind::Include => write!(
                    f,
                    "\n  in file '{}' included at {}",
                    entry.name, entry.location
                )?,
            }
        }
        Ok(())
    }
}

impl std::error::Error for XacroError {}

/// The candidate closest to `name` by edit distance, when it is close enough to be a likely typo.
pub(crate) fn closest<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let limit = (name.chars().count() / 3).max(1) + 1;
    candidates
        .into_iter()
        .filter(|c| *c != name)
        .map(|c| (edit_distance(name, c), c))
        .filter(|(d, _)| *d <= limit)
        .min_by(|a, b| a.0.cmp(&b.0).then_with(|| a.1.cmp(b.1)))
        .map(|(_, c)| c)
}

/// " (did you mean 'x'?)" or "".
pub(crate) fn did_you_mean<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> String {
    closest(name, candidates)
        .map(|c| format!(" (did you mean '{c}'?)"))
        .unwrap_or_default()
}

/// Levenshtein distance by characters; `usize::MAX` for names too long or too different to be a typo
/// (keeps the quadratic cost bounded on untrusted input).
fn edit_distance(a: &str, b: &str) -> usize {
    let (len_a, len_b) = (a.chars().count(), b.chars().count());
    if len_a.abs_diff(len_b) > 8 || len_a > 128 || len_b > 128 {
        return usize::MAX;
    }
    strsim::levenshtein(a, b)
}
