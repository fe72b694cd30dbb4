//! Native xacro expander: xacro 2.x (in-order processing) without Python, without code execution, with the
//! source location of every output element and attribute.
//!
//! ```no_run
//! let opts = xacro::Options { args: vec![("laser_enabled".into(), "true".into())], ..Default::default() };
//! match xacro::expand_file(std::path::Path::new("robot.urdf.xacro"), &opts) {
//!     Ok(expansion) => {
//!         // A byte offset in `expansion.xml` (e.g. of an attribute a validator complains about) maps back
//!         // to the xacro source that wrote it, and to the macro calls / includes that produced it.
//!         if let Some(origin) = expansion.map.origin(120) {
//!             let file = &expansion.sources[origin.file];
//!             let (line, col) = file.line_col(origin.span.start);
//!             println!("{}:{line}:{col}", file.path.display());
//!         }
//!     }
//!     Err(e) => eprintln!("{e}"), // file:line:col: message, then the macro / include stack
//! }
//! ```
//!
//! The language is Python xacro 2.1.1's (`xacro` on PyPI), followed closely: properties (scoped, lazy,
//! `remove`, `scope`, blocks), macros (defaults `:=`, `:=^`, `:=^|`, `*block`, `**block`,
//! `xacro:insert_block`, namespaces, `xacro:call`), `xacro:if` / `xacro:unless`, `xacro:include` (relative,
//! `$(find)`, `ns`, globs, `optional`), `xacro:arg` and `$(arg)`, `$(env)`, `$(optenv)`, `$(find)`,
//! `$(dirname)`, `$(eval)`, `$(cwd)`, `xacro:element`, `xacro:attribute`, `load_yaml`, `$$` escapes, comments
//! (with `xacro:eval-comments`) and the output layout of `xacro` (minidom's pretty printer).
//!
//! Safety: `${...}` and `$(eval ...)` go only through [`expr::eval`], which implements a subset of Python
//! and cannot run code; include cycles, runaway macro recursion, output size, node count and nesting depth
//! stop with an error ([`Limits`]); DTDs are refused.

pub mod expr;

mod document;
mod error;
mod expand;
mod include;
mod macros;
mod output;
mod properties;
pub mod source_map;
mod substitution;
mod yaml;

use std::path::{Path, PathBuf};
use std::sync::Arc;

pub use error::{ErrorKind, Location, StackEntry, XacroError};
pub use source_map::{Entry, Frame, FrameKind, Origin, Piece, SourceFile, SourceMap};

/// Finds the directory of a ROS package by name (for `$(find pkg)`): the directory, or, when it is not
/// found, the places searched (folder paths or short descriptions, listed in the error message in order).
pub type PackageFinder = Arc<dyn Fn(&str) -> Result<PathBuf, Vec<String>> + Send + Sync>;

/// Looks up an environment variable (for `$(env)`, `$(optenv)`, `AMENT_PREFIX_PATH`, `ROS_PACKAGE_PATH`).
pub type EnvLookup = Arc<dyn Fn(&str) -> Option<String> + Send + Sync>;

/// Decides which files and environment variables an expansion may read, for untrusted input (the
/// validator's sandbox). Every file the expander opens (the entry file aside: the caller chose it) and every
/// variable it reads go through it; a refused `$(env X)` expands to empty and a refused `$(optenv X d)` to
/// `d`, a refused include or `load_yaml` file is not read; each refusal is a [`Warning`] with
/// [`Warning::refused`] set, naming what was asked as written.
pub trait Gate: Send + Sync {
    /// `Ok` when the file at `path` may be read; otherwise why not (never the file's content).
    fn file(&self, path: &Path) -> Result<(), String>;
    /// `Ok` when the folder at `path` may be listed (include globs); otherwise why not.
    fn dir(&self, path: &Path) -> Result<(), String>;
    /// The value of variable `name` (`Ok(None)`: unset), or why it may not be read.
    fn env(&self, name: &str) -> Result<Option<String>, String>;
}

/// Safety limits. The defaults are far above what real robot descriptions need (PR2: ~2,000 output
/// nodes, 250 kB, macro depth 4).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Maximum size of the expanded XML, and of any single string built on the way (default 64 MiB).
    pub max_output_bytes: usize,
    /// Maximum number of nodes (elements, texts, comments) created (default 2,000,000).
    pub max_nodes: usize,
    /// Maximum depth of nested macro calls (default 200).
    pub max_macro_depth: usize,
    /// Maximum depth of nested includes (default 64).
    pub max_include_depth: usize,
    /// Maximum nesting of elements in a source file, and of evaluation overall (default 2,000).
    pub max_nesting: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_output_bytes: 64 << 20,
            max_nodes: 2_000_000,
            max_macro_depth: 200,
            max_include_depth: 64,
            max_nesting: 2_000,
        }
    }
}

/// How to expand.
#[derive(Clone, Default)]
pub struct Options {
    /// Arguments as given to `xacro name:=value` (they override `xacro:arg` defaults).
    pub args: Vec<(String, String)>,
    /// Folders holding ROS packages for `$(find pkg)`: `DIR/pkg`, or `DIR` itself when its `package.xml`
    /// names `pkg`. Searched after [`Options::find_package`], before `AMENT_PREFIX_PATH`,
    /// `ROS_PACKAGE_PATH` and the walk up from the current file to a `package.xml` naming the package.
    pub package_paths: Vec<PathBuf>,
    /// A package finder tried first (e.g. the validator's `package://` resolver). The places it reports
    /// having searched are listed in the "package not found" error.
    pub find_package: Option<PackageFinder>,
    /// A hint appended to "package not found" errors (e.g. which command-line option adds a folder).
    pub package_hint: Option<String>,
    /// Environment lookup; `None` reads the process environment.
    pub env: Option<EnvLookup>,
    /// The sandbox every file access and variable lookup asks first (`None`: everything is allowed).
    pub gate: Option<Arc<dyn Gate>>,
    /// Safety limits.
    pub limits: Limits,
    /// Write Python xacro's "autogenerated" banner comment at the top of the output (default off).
    pub banner: bool,
}

impl std::fmt::Debug for Options {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Options")
            .field("args", &self.args)
            .field("package_paths", &self.package_paths)
            .field("find_package", &self.find_package.as_ref().map(|_| "<fn>"))
            .field("package_hint", &self.package_hint)
            .field("env", &self.env.as_ref().map(|_| "<fn>"))
            .field("gate", &self.gate.as_ref().map(|_| "<gate>"))
            .field("limits", &self.limits)
            .field("banner", &self.banner)
            .finish()
    }
}

/// A non-fatal message (xacro's warnings: unknown attributes on xacro tags, includes matching no file,
/// `xacro.warning(...)`, arguments given but never declared, ...).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Warning {
    /// The message.
    pub message: String,
    /// Where, when known.
    pub location: Option<Location>,
    /// The macro calls and includes that led there, innermost first (empty at the top level of the entry
    /// file), as for [`XacroError::stack`].
    pub stack: Vec<StackEntry>,
    /// The input asked for a file or variable that [`Options::gate`] refused (the message says which).
    pub refused: bool,
}

/// The result of an expansion.
#[derive(Clone, Debug)]
pub struct Expansion {
    /// The expanded XML, laid out as Python xacro writes it (`<?xml version="1.0" ?>`, two-space indent,
    /// attributes sorted by name).
    pub xml: String,
    /// Every source file read, in the order first read; index 0 is the entry file. [`Origin::file`] and
    /// [`Frame::file`] index this.
    pub sources: Vec<SourceFile>,
    /// Output byte ranges → source locations.
    pub map: SourceMap,
    /// Warnings, in order.
    pub warnings: Vec<Warning>,
}

impl Expansion {
    /// `file:line:col` of an origin.
    pub fn location(&self, origin: &Origin) -> Option<Location> {
        self.file_location(origin.file, origin.span.start)
    }

    /// Where the output byte `output_byte` was written, and the macro calls / includes that produced it
    /// (innermost first), ready to print: `None` for bytes no source produced (indentation, end tags).
    pub fn trace(&self, output_byte: usize) -> Option<(Location, Vec<StackEntry>)> {
        let origin = self.map.origin(output_byte)?;
        let stack = self
            .map
            .stack(origin)
            .filter_map(|f| {
                let location = self.file_location(f.file, f.span.start)?;
                Some(StackEntry {
                    kind: f.kind,
                    name: f.name.clone(),
                    location,
                })
            })
            .collect();
        Some((self.location(origin)?, stack))
    }

    fn file_location(&self, file: usize, byte: usize) -> Option<Location> {
        let source = self.sources.get(file)?;
        let (line, col) = source.line_col(byte);
        Some(Location {
            path: source.path.clone(),
            line,
            col,
            byte,
        })
    }
}

/// Parse a command-line argument `name:=value` (as `xacro` does: surrounding spaces trimmed; `None` when it
/// is not of that form).
pub fn parse_arg(text: &str) -> Option<(String, String)> {
    let (name, value) = text.split_once(":=")?;
    let (name, value) = (name.trim(), value.trim());
    (!name.is_empty() && !value.is_empty()).then(|| (name.to_string(), value.to_string()))
}

/// Expand the xacro file at `path`.
pub fn expand_file(path: &Path, opts: &Options) -> Result<Expansion, XacroError> {
    let text = include::read_text(path, opts.limits.max_output_bytes).map_err(|e| {
        XacroError::new(
            ErrorKind::Io,
            format!("cannot read {}: {e}", path.display()),
        )
    })?;
    expand_str(&text, path, opts)
}

/// Expand xacro `text` as if it were the file at `path` (relative includes, `load_yaml` and `$(dirname)`
/// resolve against its directory).
///
/// Runs on the calling thread, using at most 256 KiB of its stack for nesting (plus what one expression
/// needs), so any thread with Rust's default 2 MiB stack will do; inputs nested deeper are expanded again on
/// a helper thread with a 512 MiB (reserved, not committed) stack.
pub fn expand_str(text: &str, path: &Path, opts: &Options) -> Result<Expansion, XacroError> {
    // Shallow documents (all real robots) expand on the caller's thread within a small stack budget;
    // deeper ones start again on a thread with a large stack (reserved, not committed).
    const INLINE_STACK_BUDGET: usize = 256 << 10;
    const STACK: usize = 512 << 20;
    let internal = || {
        XacroError::new(
            ErrorKind::Internal,
            "internal error: the xacro expander panicked",
        )
    };
    let inline = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        expand::run(text, path, opts, Some(INLINE_STACK_BUDGET))
    }));
    match inline {
        Ok((result, false)) => return result,
        Ok((_, true)) => {}
        Err(_) => return Err(internal()),
    }
    std::thread::scope(|scope| {
        let worker = std::thread::Builder::new()
            .name("xacro-expand".into())
            .stack_size(STACK)
            .spawn_scoped(scope, || expand::run(text, path, opts, None).0);
        match worker {
            Ok(handle) => handle.join().unwrap_or_else(|_| Err(internal())),
            Err(e) => Err(XacroError::new(
                ErrorKind::Limit,
                format!("the input nests too deeply for this thread's stack, and no thread with a larger stack could be started: {e}"),
            )),
        }
    })
}
