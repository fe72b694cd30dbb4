//! The expansion itself: a port of Python xacro 2.1.1's `eval_all` and helpers (in-order processing) over
//! the immutable [`crate::document`] tree, building new output nodes.

use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use crate::document::{
    self, Attr, Element, FrameData, FrameRef, Kind, Loc, Node, NodeRef, ParsedDoc, Src,
};
use crate::error::{did_you_mean, ErrorKind, Location, StackEntry, XacroError};
use crate::expr::{self, EvalError, Scope, Value};
use crate::include;
use crate::macros::{parse_params, Macro, MacroEntry, MacroTable, MacroTableRef};
use crate::properties::{boolean_value, Entry, Table, TableRef};
use crate::source_map::{FrameKind, SourceFile};
use crate::substitution::{self, SubstitutionHost};
use crate::{Expansion, Options, Warning};

/// A `$(find)` result: the package directory, or the places searched.
type FoundPackage = Result<String, Vec<String>>;

/// Where the expansion is: the innermost macro call / include, and the depths.
#[derive(Clone, Default)]
struct Ctx {
    frame: Option<FrameRef>,
    macro_depth: usize,
    include_depth: usize,
}

/// An element after `eval_all`: evaluated attributes and processed children.
struct Built {
    name: Rc<str>,
    attrs: Vec<Attr>,
    children: Vec<NodeRef>,
    src: Src,
}

impl Built {
    fn into_node(self) -> NodeRef {
        Rc::new(Node {
            kind: Kind::Element(Element {
                name: self.name,
                attrs: self.attrs,
                children: self.children,
            }),
            src: self.src,
        })
    }
}

pub(crate) struct Expander<'o> {
    opts: &'o Options,
    sources: RefCell<Vec<SourceFile>>,
    docs: RefCell<HashMap<PathBuf, (u32, Rc<ParsedDoc>)>>,
    args: RefCell<HashMap<String, String>>,
    /// Python's `filestack`: the files being processed (includes), innermost last.
    file_stack: RefCell<Vec<PathBuf>>,
    /// The canonical paths of `file_stack` (include cycles).
    open_files: RefCell<Vec<Option<PathBuf>>>,
    /// The detailed error behind an `EvalError` returned to the evaluator through [`Scope`].
    pending: RefCell<Option<XacroError>>,
    warnings: RefCell<Vec<Warning>>,
    nodes: Cell<usize>,
    bytes: Cell<usize>,
    nesting: Cell<usize>,
    /// Generation of the live `_empty_text_node` separator.
    separator: Cell<u64>,
    exprs: RefCell<HashMap<String, Rc<expr::Expr>>>,
    /// YAML files loaded so far (each is read, and listed in the sources, once).
    yaml_files: RefCell<HashMap<PathBuf, Value>>,
    /// `$(find)` results by (package, folder of the current file).
    packages: RefCell<HashMap<(String, PathBuf), FoundPackage>>,
    /// Whether a name is a built-in of the evaluator (cache).
    builtins: RefCell<HashMap<String, bool>>,
    /// Address of a local of [`run`] and how much stack below it this run may use (`None`: unbounded, on
    /// the expander's own large-stack thread).
    stack_base: usize,
    stack_budget: Option<usize>,
    /// Set when the stack budget ran out: the caller retries on a thread with a large stack.
    stack_exhausted: &'o Cell<bool>,
}

/// Expand `text` (the file `path`), using at most `stack_budget` bytes of stack when given. The second value
/// is true when that budget ran out (the result is then an error, and the caller should retry without a
/// budget on a thread with a large stack).
pub(crate) fn run(
    text: &str,
    path: &Path,
    opts: &Options,
    stack_budget: Option<usize>,
) -> (Result<Expansion, XacroError>, bool) {
    let marker = 0u8;
    let exhausted = Cell::new(false);
    let x = Expander {
        opts,
        sources: RefCell::default(),
        docs: RefCell::default(),
        args: RefCell::new(opts.args.iter().cloned().collect()),
        file_stack: RefCell::new(vec![path.to_path_buf()]),
        open_files: RefCell::new(vec![Some(lexical_absolute(path))]),
        pending: RefCell::default(),
        warnings: RefCell::default(),
        nodes: Cell::new(0),
        bytes: Cell::new(0),
        nesting: Cell::new(0),
        separator: Cell::new(0),
        exprs: RefCell::default(),
        builtins: RefCell::default(),
        packages: RefCell::default(),
        yaml_files: RefCell::default(),
        stack_base: std::ptr::addr_of!(marker) as usize,
        stack_budget,
        stack_exhausted: &exhausted,
    };
    let result = x.expand(text, path);
    (result, exhausted.get())
}

impl Expander<'_> {
    /// The whole expansion.
    fn expand(self, text: &str, path: &Path) -> Result<Expansion, XacroError> {
        let x = self;
        let opts = x.opts;
        let (_, doc) = x.register(path, text.to_string())?;
        let root = doc
            .root()
            .cloned()
            .ok_or_else(|| XacroError::new(ErrorKind::XmlParse, "no root element"))?;
        let macros: MacroTableRef = Rc::default();
        let symbols: TableRef = Rc::default();
        let ctx = Ctx::default();
        // xacro:targetNamespace becomes the default namespace.
        let root = match &root.kind {
            Kind::Element(el) if el.attrs.iter().any(|a| &*a.name == "xacro:targetNamespace") => {
                let mut attrs = el.attrs.clone();
                for a in attrs
                    .iter_mut()
                    .filter(|a| &*a.name == "xacro:targetNamespace")
                {
                    a.name = "xmlns".into();
                }
                Rc::new(Node {
                    kind: Kind::Element(Element {
                        name: el.name.clone(),
                        attrs,
                        children: el.children.clone(),
                    }),
                    src: root.src.clone(),
                })
            }
            _ => root,
        };
        let built = x.eval_element(&root, &macros, &symbols, &ctx)?;
        let mut top: Vec<NodeRef> = doc.children.clone();
        if let Some(slot) = top.get_mut(doc.root) {
            *slot = built.into_node();
        }
        let sources = x.sources.into_inner();
        let banner = opts.banner.then(|| path.display().to_string());
        let (xml, map) = crate::output::write(
            &top,
            banner.as_deref(),
            x.separator.get(),
            opts.limits.max_output_bytes,
            // Text and attribute bytes created, plus markup and indentation per node.
            x.bytes.get() + 48 * x.nodes.get(),
        )?;
        Ok(Expansion {
            xml,
            sources,
            map,
            warnings: x.warnings.into_inner(),
        })
    }
}

const PY_KEYWORDS: [&str; 35] = [
    "False", "None", "True", "and", "as", "assert", "async", "await", "break", "class", "continue",
    "def", "del", "elif", "else", "except", "finally", "for", "from", "global", "if", "import",
    "in", "is", "lambda", "nonlocal", "not", "or", "pass", "raise", "return", "try", "while",
    "with", "yield",
];

/// `path` made absolute with `.` and `..` resolved lexically (no file system access; symlinked cycles are
/// caught by the include depth limit instead).
fn lexical_absolute(path: &Path) -> PathBuf {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut out = PathBuf::new();
    for c in abs.components() {
        match c {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

/// The text of an evaluated value (Python's `str()`), sharing the string when it is one.
fn into_text(v: Value) -> Rc<str> {
    match v {
        Value::Str(s) => s,
        v => v.to_xacro_string().into(),
    }
}

/// A Python identifier that is not a keyword (`is_valid_name`).
fn is_valid_name(name: &str) -> bool {
    let mut chars = name.chars();
    let Some(first) = chars.next() else {
        return false;
    };
    (first == '_' || first.is_alphabetic())
        && chars.all(|c| c == '_' || c.is_alphanumeric())
        && !PY_KEYWORDS.contains(&name)
}

/// Names in an expression that start with `__` (outside string literals): Python xacro refuses them.
fn dunder_names(code: &str) -> Vec<String> {
    let mut names = Vec::new();
    let mut chars = code.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        if c == '\'' || c == '"' {
            let mut escaped = false;
            for (_, d) in chars.by_ref() {
                if escaped {
                    escaped = false;
                } else if d == '\\' {
                    escaped = true;
                } else if d == c {
                    break;
                }
            }
        } else if c == '_' || c.is_alphabetic() {
            let mut end = i + c.len_utf8();
            while let Some(&(j, d)) = chars.peek() {
                if d == '_' || d.is_alphanumeric() {
                    end = j + d.len_utf8();
                    chars.next();
                } else {
                    break;
                }
            }
            let word = &code[i..end];
            if word.starts_with("__") {
                names.push(word.to_string());
            }
        } else if c.is_ascii_digit() {
            while chars
                .peek()
                .is_some_and(|&(_, d)| d.is_alphanumeric() || d == '_' || d == '.')
            {
                chars.next();
            }
        }
    }
    names
}

/// The scope `${...}` expressions see: properties, then host functions.
struct PropScope<'a, 'o> {
    x: &'a Expander<'o>,
    symbols: &'a TableRef,
    ctx: &'a Ctx,
}

impl Scope for PropScope<'_, '_> {
    fn lookup(&self, name: &str) -> Result<Option<Value>, EvalError> {
        self.x
            .lookup_property(self.symbols, name, self.ctx)
            .map_err(|e| self.x.stash(e))
    }

    fn call_host(
        &self,
        name: &str,
        args: &[Value],
        kwargs: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>> {
        self.x.call_host(name, args, kwargs, self.ctx)
    }
}

/// The scope of `$(eval ...)`: arguments (converted as roslaunch does), `true`/`false`, and the functions
/// `arg`, `dirname`, `env`, `optenv`, `find`.
struct ArgScope<'a, 'o> {
    x: &'a Expander<'o>,
    ctx: &'a Ctx,
}

impl Scope for ArgScope<'_, '_> {
    fn lookup(&self, name: &str) -> Result<Option<Value>, EvalError> {
        Ok(match name {
            "true" | "True" => Some(Value::Bool(true)),
            "false" | "False" => Some(Value::Bool(false)),
            "arg" | "dirname" | "env" | "optenv" | "find" => {
                Some(Value::Function(format!("xacro.eval_{name}").into()))
            }
            _ => self
                .x
                .args
                .borrow()
                .get(name)
                .map(|v| substitution::convert_auto(v)),
        })
    }

    fn call_host(
        &self,
        name: &str,
        args: &[Value],
        kwargs: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>> {
        self.x.call_host(name, args, kwargs, self.ctx)
    }
}

/// A scope with no properties (built-ins only).
struct NoScope;

impl Scope for NoScope {
    fn lookup(&self, _: &str) -> Result<Option<Value>, EvalError> {
        Ok(None)
    }

    fn call_host(
        &self,
        _: &str,
        _: &[Value],
        _: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>> {
        None
    }
}

fn host_error(kind: &'static str, message: String) -> EvalError {
    EvalError {
        kind,
        message,
        undefined_name: None,
        offset: None,
    }
}

fn str_arg(args: &[Value], i: usize) -> Option<String> {
    args.get(i).map(Value::to_xacro_string)
}

impl<'o> Expander<'o> {
    // ----------------------------------------------------------------------------------------------------
    // Files, locations, errors

    /// Add a source file and parse it.
    fn register(&self, path: &Path, text: String) -> Result<(u32, Rc<ParsedDoc>), XacroError> {
        let file = self.sources.borrow().len() as u32;
        let stack_ok = || self.check_stack().is_ok();
        let parsed = document::parse(&text, file, self.opts.limits.max_nesting, &stack_ok);
        self.sources
            .borrow_mut()
            .push(SourceFile::new(path.to_path_buf(), text));
        match parsed {
            Ok(doc) => {
                let doc = Rc::new(doc);
                self.docs
                    .borrow_mut()
                    .insert(path.to_path_buf(), (file, doc.clone()));
                Ok((file, doc))
            }
            Err((message, byte)) => {
                let mut e = document::parse_error(path, &message);
                e.location = self.location(Loc {
                    file,
                    start: byte as u32,
                    end: byte as u32,
                });
                Err(e)
            }
        }
    }

    /// Read and parse a file (cached).
    fn load(&self, path: &Path) -> Result<Rc<ParsedDoc>, XacroError> {
        if let Some((_, doc)) = self.docs.borrow().get(path) {
            return Ok(doc.clone());
        }
        let text = std::fs::read_to_string(path).map_err(|e| {
            let kind = if e.kind() == std::io::ErrorKind::NotFound {
                ErrorKind::IncludeNotFound
            } else {
                ErrorKind::Io
            };
            XacroError::new(
                kind,
                format!("No such file or directory: {} ({e})", path.display()),
            )
        })?;
        self.register(path, text).map(|(_, d)| d)
    }

    fn current_file(&self) -> PathBuf {
        self.file_stack.borrow().last().cloned().unwrap_or_default()
    }

    fn location(&self, loc: Loc) -> Option<Location> {
        let sources = self.sources.borrow();
        let file = sources.get(loc.file as usize)?;
        let (line, col) = file.line_col(loc.start as usize);
        Some(Location {
            path: file.path.clone(),
            line,
            col,
            byte: loc.start as usize,
        })
    }

    fn stack(&self, ctx: &Ctx) -> Vec<StackEntry> {
        let mut out = Vec::new();
        let mut f = ctx.frame.clone();
        while let Some(frame) = f {
            if let Some(location) = self.location(frame.loc) {
                out.push(StackEntry {
                    kind: frame.kind,
                    name: frame.name.clone(),
                    location,
                });
            }
            f = frame.parent.clone();
        }
        out
    }

    /// Give `e` a location and stack unless it has them.
    fn locate(&self, mut e: XacroError, loc: Loc, ctx: &Ctx) -> XacroError {
        if e.location.is_none() {
            e.location = self.location(loc);
            e.stack = self.stack(ctx);
        }
        e
    }

    fn warn(&self, message: String, loc: Option<Loc>) {
        let location = loc.and_then(|l| self.location(l));
        self.warnings
            .borrow_mut()
            .push(Warning { message, location });
    }

    /// Fail (and remember why) when this run has used its stack budget.
    fn check_stack(&self) -> Result<(), XacroError> {
        let Some(budget) = self.stack_budget else {
            return Ok(());
        };
        let marker = 0u8;
        let used = self
            .stack_base
            .saturating_sub(std::ptr::addr_of!(marker) as usize);
        if used > budget {
            self.stack_exhausted.set(true);
            return Err(XacroError::new(ErrorKind::Limit, "stack budget exhausted"));
        }
        Ok(())
    }

    /// Keep the detailed error for when the evaluator gives up, and tell the evaluator.
    fn stash(&self, e: XacroError) -> EvalError {
        let message = e.message.clone();
        let mut pending = self.pending.borrow_mut();
        if pending.is_none() {
            *pending = Some(e);
        }
        host_error("XacroException", message)
    }

    fn count_node(&self, bytes: usize) -> Result<(), XacroError> {
        let limits = &self.opts.limits;
        self.nodes.set(self.nodes.get() + 1);
        self.bytes.set(self.bytes.get().saturating_add(bytes));
        if self.nodes.get() > limits.max_nodes {
            return Err(XacroError::new(
                ErrorKind::Limit,
                format!("the expansion creates more than {} nodes", limits.max_nodes),
            ));
        }
        if self.bytes.get() > limits.max_output_bytes.saturating_mul(4) {
            return Err(XacroError::new(
                ErrorKind::Limit,
                format!(
                    "the expansion creates more than {} bytes of text",
                    limits.max_output_bytes.saturating_mul(4)
                ),
            ));
        }
        Ok(())
    }

    // ----------------------------------------------------------------------------------------------------
    // Text evaluation: eval_text, ${...}, $(...)

    /// Python xacro's `eval_text`: one token returns its typed value, several are joined as text.
    fn eval_text(&self, text: &str, symbols: &TableRef, ctx: &Ctx) -> Result<Value, XacroError> {
        if !text.contains('$') {
            return Ok(Value::Str(text.into()));
        }
        let mut results: Vec<Value> = Vec::new();
        let mut rest = text;
        while !rest.is_empty() {
            let dollars = rest.bytes().take_while(|&b| b == b'$').count();
            if dollars >= 2 && matches!(rest.as_bytes().get(dollars), Some(b'{' | b'(')) {
                results.push(Value::Str(rest[1..=dollars].into()));
                rest = &rest[dollars + 1..];
            } else if let Some(inner) = rest
                .strip_prefix("${")
                .and_then(|r| r.find('}').map(|i| &r[..i]))
            {
                results.push(self.handle_expr(inner, symbols, ctx)?);
                rest = &rest[inner.len() + 3..];
            } else if let Some(inner) = rest
                .strip_prefix("$(")
                .and_then(|r| r.find(')').map(|i| &r[..i]))
            {
                results.push(self.handle_extension(inner, symbols, ctx)?);
                rest = &rest[inner.len() + 3..];
            } else if dollars == 0 {
                let end = rest.find('$').unwrap_or(rest.len());
                results.push(Value::Str(rest[..end].into()));
                rest = &rest[end..];
            } else if dollars == 1 && rest.len() == 1 {
                results.push(Value::Str("$".into()));
                rest = "";
            } else if dollars == 1 && !matches!(rest.as_bytes().get(1), Some(b'{' | b'(')) {
                let end = rest[1..]
                    .find(['{', '(', '$'])
                    .map_or(rest.len(), |i| i + 1);
                results.push(Value::Str(rest[..end].into()));
                rest = &rest[end..];
            } else {
                return Err(XacroError::new(
                    ErrorKind::Expression,
                    format!("invalid expression: {rest}"),
                ));
            }
        }
        if results.len() == 1 {
            return Ok(results.pop().unwrap_or(Value::None));
        }
        let joined: String = results.iter().map(Value::to_xacro_string).collect();
        if joined.len() > self.opts.limits.max_output_bytes {
            return Err(XacroError::new(
                ErrorKind::Limit,
                "a string exceeds the output size limit",
            ));
        }
        Ok(Value::Str(joined.into()))
    }

    fn parse_expr(&self, code: &str) -> Result<Rc<expr::Expr>, EvalError> {
        if let Some(e) = self.exprs.borrow().get(code) {
            return Ok(e.clone());
        }
        let parsed = Rc::new(expr::parse(code)?);
        self.exprs
            .borrow_mut()
            .insert(code.to_string(), parsed.clone());
        Ok(parsed)
    }

    /// `${inner}`.
    fn handle_expr(&self, inner: &str, symbols: &TableRef, ctx: &Ctx) -> Result<Value, XacroError> {
        let code = self.eval_text(inner, symbols, ctx)?.to_xacro_string();
        let bad = dunder_names(&code);
        if !bad.is_empty() {
            return Err(XacroError::new(
                ErrorKind::InvalidName,
                format!(
                    "Use of invalid name(s): {} in expression '${{{inner}}}'",
                    bad.join(", ")
                ),
            ));
        }
        let scope = PropScope {
            x: self,
            symbols,
            ctx,
        };
        let result = self
            .parse_expr(code.trim())
            .and_then(|e| expr::eval(&e, &scope));
        let value = match result {
            Ok(v) => {
                self.pending.borrow_mut().take();
                v
            }
            Err(e) => {
                if let Some(detail) = self.pending.borrow_mut().take() {
                    return Err(detail);
                }
                return Err(self.expr_error(e, inner, Some(symbols)));
            }
        };
        if let Value::Str(s) = &value {
            if s.len() > self.opts.limits.max_output_bytes {
                return Err(XacroError::new(
                    ErrorKind::Limit,
                    "a string exceeds the output size limit",
                ));
            }
        }
        Ok(value)
    }

    fn expr_error(&self, e: EvalError, inner: &str, symbols: Option<&TableRef>) -> XacroError {
        if e.kind == "NameError" {
            let hint = match (&e.undefined_name, symbols) {
                (Some(name), Some(t)) => {
                    let names = t.visible_names();
                    did_you_mean(name, names.iter().map(String::as_str))
                }
                _ => String::new(),
            };
            return XacroError::new(
                ErrorKind::UndefinedProperty,
                format!("{}{hint}, when evaluating expression '{inner}'", e.message),
            );
        }
        XacroError::new(
            ErrorKind::Expression,
            format!(
                "{}: {}, when evaluating expression '{inner}'",
                e.kind, e.message
            ),
        )
    }

    /// `$(inner)`.
    fn handle_extension(
        &self,
        inner: &str,
        symbols: &TableRef,
        ctx: &Ctx,
    ) -> Result<Value, XacroError> {
        let inner = self.eval_text(inner, symbols, ctx)?.to_xacro_string();
        let s = format!("$({inner})");
        if s == "$(cwd)" {
            let cwd = std::env::current_dir().unwrap_or_default();
            return Ok(Value::Str(cwd.display().to_string().into()));
        }
        if let Some(code) = s.strip_prefix("$(eval ").and_then(|r| r.strip_suffix(')')) {
            if code.contains("__") {
                return Err(XacroError::new(
                    ErrorKind::InvalidName,
                    "$(eval ...) may not contain double underscore expressions",
                ));
            }
            let scope = ArgScope { x: self, ctx };
            let result = self
                .parse_expr(code.trim())
                .and_then(|e| expr::eval(&e, &scope));
            return match result {
                Ok(v) => {
                    self.pending.borrow_mut().take();
                    Ok(Value::Str(v.to_xacro_string().into()))
                }
                Err(e) => match self.pending.borrow_mut().take() {
                    Some(detail) => Err(detail),
                    None => Err(self.expr_error(e, &s, None)),
                },
            };
        }
        let host = SubstHost { x: self };
        substitution::resolve_args(&s, &host).map(|v| Value::Str(v.into()))
    }

    fn arg_value(&self, name: &str) -> Result<String, XacroError> {
        let args = self.args.borrow();
        args.get(name).cloned().ok_or_else(|| {
            let hint = did_you_mean(name, args.keys().map(String::as_str));
            XacroError::new(
                ErrorKind::UndefinedArgument,
                format!("Undefined substitution argument {name}{hint}"),
            )
        })
    }

    fn env_var(&self, name: &str) -> Option<String> {
        match &self.opts.env {
            Some(env) => env(name),
            None => std::env::var(name).ok(),
        }
    }

    fn find_package(&self, pkg: &str) -> Result<String, XacroError> {
        let current = self.current_file();
        // Every file of a package asks the same question: cache by (package, folder of the current file).
        let key = (
            pkg.to_string(),
            current.parent().map(Path::to_path_buf).unwrap_or_default(),
        );
        let cached = self.packages.borrow().get(&key).cloned();
        let found = match cached {
            Some(found) => found,
            None => {
                let env = |n: &str| self.env_var(n);
                let found = include::find_package(pkg, self.opts, &env, &current)
                    .map(|p| p.display().to_string());
                self.packages.borrow_mut().insert(key, found.clone());
                found
            }
        };
        found.map_err(|searched| {
            let where_ = if searched.is_empty() {
                String::new()
            } else {
                format!("; searched: {}", searched.join(", "))
            };
            XacroError::new(
                ErrorKind::PackageNotFound,
                format!("package '{pkg}' not found{where_}"),
            )
        })
    }

    fn dirname(&self) -> Result<String, XacroError> {
        let current = self.current_file();
        let abs = std::path::absolute(&current).unwrap_or(current);
        Ok(abs
            .parent()
            .map(|p| p.display().to_string())
            .unwrap_or_default())
    }

    // ----------------------------------------------------------------------------------------------------
    // Properties and host functions

    /// `symbols[name]` with lazy evaluation; `Ok(None)` when no property has that name.
    fn lookup_property(
        &self,
        symbols: &TableRef,
        name: &str,
        ctx: &Ctx,
    ) -> Result<Option<Value>, XacroError> {
        let Some(table) = symbols.find(name) else {
            return Ok(None);
        };
        let entry = table.entries.borrow().get(name).cloned();
        match entry {
            None | Some(Entry::Block(_)) => Ok(None),
            Some(Entry::Value(v)) => Ok(Some(v)),
            Some(Entry::Namespace(ns)) => {
                let keys: Vec<String> = ns
                    .entries
                    .borrow()
                    .keys()
                    .filter(|k| is_valid_name(k))
                    .cloned()
                    .collect();
                let mut items = Vec::new();
                for k in keys {
                    if let Ok(Some(v)) = self.lookup_property(&ns, &k, ctx) {
                        items.push((Value::Str(k.into()), v));
                    }
                }
                Ok(Some(Value::Dict(Rc::new(items))))
            }
            Some(Entry::Lazy(text, def)) => {
                if table.resolving.borrow().iter().any(|n| n == name) {
                    let mut chain = table.resolving.borrow().clone();
                    chain.push(name.to_string());
                    let e = XacroError::new(
                        ErrorKind::CircularProperty,
                        format!(
                            "circular variable definition: {}. Consider disabling lazy evaluation via lazy_eval=\"false\"",
                            chain.join(" -> ")
                        ),
                    );
                    return Err(match def {
                        Some(l) => self.locate(e, l, ctx),
                        None => e,
                    });
                }
                // Chains of lazy properties recurse: bound them like element nesting.
                self.check_stack()?;
                let depth = self.nesting.get() + 1;
                if depth > self.opts.limits.max_nesting {
                    return Err(XacroError::new(
                        ErrorKind::Limit,
                        format!(
                            "properties refer to each other more than {} levels deep",
                            self.opts.limits.max_nesting
                        ),
                    ));
                }
                self.nesting.set(depth);
                table.resolving.borrow_mut().push(name.to_string());
                let result = self.eval_text(&text, &table, ctx);
                table.resolving.borrow_mut().retain(|n| n != name);
                self.nesting.set(depth - 1);
                let value = match result {
                    Ok(v) => v,
                    Err(e) => {
                        return Err(match def {
                            Some(l) => self.locate(e, l, ctx),
                            None => e,
                        })
                    }
                };
                let value = match value {
                    Value::Str(s) => crate::properties::eval_literal(&s),
                    v => v,
                };
                table
                    .entries
                    .borrow_mut()
                    .insert(name.to_string(), Entry::Value(value.clone()));
                Ok(Some(value))
            }
        }
    }

    /// `name in symbols`, built-ins included.
    fn has_symbol(&self, symbols: &TableRef, name: &str) -> bool {
        symbols.find(name).is_some() || self.is_builtin(name)
    }

    fn is_builtin(&self, name: &str) -> bool {
        if let Some(&known) = self.builtins.borrow().get(name) {
            return known;
        }
        let builtin = is_valid_name(name)
            && expr::parse(name)
                .and_then(|e| expr::eval(&e, &NoScope))
                .is_ok();
        self.builtins.borrow_mut().insert(name.to_string(), builtin);
        builtin
    }

    /// Python xacro's warning when a property or parameter shadows a built-in name.
    fn warn_if_builtin(&self, name: &str, loc: Loc) {
        if self.is_builtin(name) {
            self.warn(format!("redefining global symbol: {name}"), Some(loc));
        }
    }

    fn call_host(
        &self,
        name: &str,
        args: &[Value],
        kwargs: &[(String, Value)],
        ctx: &Ctx,
    ) -> Option<Result<Value, EvalError>> {
        let name = name.strip_prefix("python.").unwrap_or(name);
        let result = match name {
            "xacro.load_yaml" | "load_yaml" => {
                let spec = str_arg(args, 0).unwrap_or_default();
                self.load_yaml(&spec).map_err(|e| self.stash(e))
            }
            "xacro.abs_filename" | "abs_filename" => {
                let spec = str_arg(args, 0).unwrap_or_default();
                Ok(Value::Str(
                    include::abs_filename(&spec, &self.current_file())
                        .display()
                        .to_string()
                        .into(),
                ))
            }
            "xacro.arg" | "xacro.eval_arg" => {
                let n = str_arg(args, 0).unwrap_or_default();
                match self.arg_value(&n) {
                    Ok(v) if name == "xacro.eval_arg" => Ok(substitution::convert_auto(&v)),
                    Ok(v) => Ok(Value::Str(v.into())),
                    Err(e) => Err(self.stash(e)),
                }
            }
            "xacro.message" | "xacro.warning" | "xacro.error" | "xacro.print_location" => {
                let text: Vec<String> = args.iter().map(Value::to_xacro_string).collect();
                let loc = ctx.frame.as_ref().map(|f| f.loc);
                if name != "xacro.print_location" {
                    self.warn(text.join(" "), loc);
                }
                Ok(Value::Str("".into()))
            }
            "xacro.fatal" => {
                let text: Vec<String> = args.iter().map(Value::to_xacro_string).collect();
                Err(self.stash(XacroError::new(ErrorKind::Fatal, text.join(" "))))
            }
            "xacro.dotify" | "dotify" => Ok(args.first().cloned().unwrap_or(Value::None)),
            "xacro.tokenize" => {
                let s = str_arg(args, 0).unwrap_or_default();
                let kw = |k: &str| kwargs.iter().find(|(n, _)| n == k).map(|(_, v)| v.clone());
                let sep = args
                    .get(1)
                    .cloned()
                    .or_else(|| kw("sep"))
                    .map_or(",; ".to_string(), |v| v.to_xacro_string());
                let skip_empty = args
                    .get(2)
                    .cloned()
                    .or_else(|| kw("skip_empty"))
                    .is_none_or(|v| v.is_truthy());
                let items = s
                    .split(|c| sep.contains(c))
                    .filter(|t| !skip_empty || !t.is_empty())
                    .map(|t| Value::Str(t.into()))
                    .collect();
                Ok(Value::List(Rc::new(items)))
            }
            "xacro.eval_dirname" => self
                .dirname()
                .map(|d| Value::Str(d.into()))
                .map_err(|e| self.stash(e)),
            "xacro.eval_env" => {
                let n = str_arg(args, 0).unwrap_or_default();
                match self.env_var(&n) {
                    Some(v) => Ok(Value::Str(v.into())),
                    None => Err(host_error("KeyError", format!("'{n}'"))),
                }
            }
            "xacro.eval_optenv" => {
                let n = str_arg(args, 0).unwrap_or_default();
                let default = str_arg(args, 1).unwrap_or_default();
                Ok(Value::Str(self.env_var(&n).unwrap_or(default).into()))
            }
            "xacro.eval_find" => {
                let n = str_arg(args, 0).unwrap_or_default();
                self.find_package(&n)
                    .map(|p| Value::Str(p.into()))
                    .map_err(|e| self.stash(e))
            }
            _ => return None,
        };
        Some(result)
    }

    fn load_yaml(&self, spec: &str) -> Result<Value, XacroError> {
        let path = include::abs_filename(spec, &self.current_file());
        if let Some(value) = self.yaml_files.borrow().get(&path) {
            return Ok(value.clone());
        }
        let text = std::fs::read_to_string(&path).map_err(|e| {
            XacroError::new(
                ErrorKind::Io,
                format!("cannot read YAML file {}: {e}", path.display()),
            )
        })?;
        self.sources
            .borrow_mut()
            .push(SourceFile::new(path.clone(), text.clone()));
        let eval = |s: &str| expr::parse(s.trim()).and_then(|e| expr::eval(&e, &NoScope));
        let value = crate::yaml::load(&text, &eval).map_err(|e| {
            XacroError::new(
                ErrorKind::Yaml,
                format!("{}: {} (in {})", e.kind, e.message, path.display()),
            )
        })?;
        self.yaml_files.borrow_mut().insert(path, value.clone());
        Ok(value)
    }

    // ----------------------------------------------------------------------------------------------------
    // eval_all

    /// The attributes of a xacro tag (`check_attrs`): the required ones (error if missing), the optional
    /// ones, and a warning for any other.
    fn check_attrs<'e>(
        &self,
        node: &NodeRef,
        el: &'e Element,
        required: &[&str],
        optional: &[&str],
        ctx: &Ctx,
    ) -> Result<Vec<Option<&'e Attr>>, XacroError> {
        let mut out = Vec::new();
        for name in required {
            match el.attrs.iter().find(|a| &*a.name == *name) {
                Some(a) => out.push(Some(a)),
                None => {
                    let e = XacroError::new(
                        ErrorKind::MissingAttribute,
                        format!("{}: missing attribute '{name}'", el.name),
                    );
                    return Err(self.locate(e, node.src.loc, ctx));
                }
            }
        }
        out.extend(
            optional
                .iter()
                .map(|name| el.attrs.iter().find(|a| &*a.name == *name)),
        );
        let extra: Vec<&str> = el
            .attrs
            .iter()
            .map(|a| &*a.name)
            .filter(|n| !required.contains(n) && !optional.contains(n) && !n.starts_with("xmlns:"))
            .collect();
        if !extra.is_empty() {
            self.warn(
                format!("{}: unknown attribute(s): {}", el.name, extra.join(", ")),
                Some(node.src.loc),
            );
        }
        Ok(out)
    }

    /// `reqd_attrs`: the required attributes, without warning about others.
    fn required_attrs<'e>(
        &self,
        node: &NodeRef,
        el: &'e Element,
        required: &[&str],
        ctx: &Ctx,
    ) -> Result<Vec<Option<&'e Attr>>, XacroError> {
        let mut out = Vec::with_capacity(required.len());
        for name in required {
            match el.attrs.iter().find(|a| &*a.name == *name) {
                Some(a) => out.push(Some(a)),
                None => {
                    let e = XacroError::new(
                        ErrorKind::MissingAttribute,
                        format!("{}: missing attribute '{name}'", el.name),
                    );
                    return Err(self.locate(e, node.src.loc, ctx));
                }
            }
        }
        Ok(out)
    }

    /// Evaluate an attribute's text, locating errors at the attribute.
    fn eval_attr(&self, attr: &Attr, symbols: &TableRef, ctx: &Ctx) -> Result<Value, XacroError> {
        self.eval_text(&attr.value, symbols, ctx)
            .map_err(|e| self.locate(e, attr.src.loc, ctx))
    }

    /// Python's `eval_all(node)` for an element: evaluate its attributes (dropping `xacro:*` ones and
    /// `xmlns:xacro`) and process its children.
    fn eval_element(
        &self,
        node: &NodeRef,
        macros: &MacroTableRef,
        symbols: &TableRef,
        ctx: &Ctx,
    ) -> Result<Built, XacroError> {
        let Kind::Element(el) = &node.kind else {
            return Err(XacroError::new(
                ErrorKind::Internal,
                "internal error: eval_element on a non-element",
            ));
        };
        self.check_stack()?;
        let depth = self.nesting.get() + 1;
        if depth > self.opts.limits.max_nesting {
            let e = XacroError::new(
                ErrorKind::Limit,
                format!(
                    "evaluation nested deeper than {} levels",
                    self.opts.limits.max_nesting
                ),
            );
            return Err(self.locate(e, node.src.loc, ctx));
        }
        self.nesting.set(depth);
        let result = self.eval_element_inner(node, el, macros, symbols, ctx);
        self.nesting.set(depth - 1);
        result
    }

    fn eval_element_inner(
        &self,
        node: &NodeRef,
        el: &Element,
        macros: &MacroTableRef,
        symbols: &TableRef,
        ctx: &Ctx,
    ) -> Result<Built, XacroError> {
        let mut attrs = Vec::with_capacity(el.attrs.len());
        for a in &el.attrs {
            if a.name.starts_with("xacro:") || &*a.name == "xmlns:xacro" {
                continue;
            }
            let value = if a.value.contains('$') {
                into_text(self.eval_attr(a, symbols, ctx)?)
            } else {
                a.value.clone()
            };
            self.count_node(value.len())?;
            attrs.push(Attr {
                name: a.name.clone(),
                value,
                name_loc: a.name_loc,
                src: a.src.placed(&ctx.frame),
            });
        }
        let mut children = Vec::with_capacity(el.children.len());
        self.process_children(
            &el.children,
            &mut children,
            &mut attrs,
            macros,
            symbols,
            ctx,
        )?;
        self.count_node(el.name.len())?;
        Ok(Built {
            name: el.name.clone(),
            attrs,
            children,
            src: node.src.placed(&ctx.frame),
        })
    }

    fn is_live_separator(&self, n: &NodeRef) -> bool {
        matches!(n.kind, Kind::Separator(g) if g == self.separator.get())
    }

    fn is_stale_separator(&self, n: &NodeRef) -> bool {
        matches!(n.kind, Kind::Separator(g) if g != self.separator.get())
    }

    /// `remove_previous_comments`: drop the comments right before a xacro tag (across single-newline
    /// whitespace). Returns whether Python would now move its separator text node after the tag.
    fn remove_previous_comments(&self, out: &mut Vec<NodeRef>, has_next: bool) -> bool {
        let mut i = out.len();
        let skip_stale = |i: &mut usize, out: &Vec<NodeRef>| {
            while *i > 0 && self.is_stale_separator(&out[*i - 1]) {
                *i -= 1;
            }
        };
        loop {
            skip_stale(&mut i, out);
            if i == 0 {
                return false;
            }
            if let Kind::Text(t) = &out[i - 1].kind {
                if !t.is_empty()
                    && t.chars().all(char::is_whitespace)
                    && t.matches('\n').count() <= 1
                {
                    i -= 1;
                    skip_stale(&mut i, out);
                }
            }
            if i > 0 && matches!(out[i - 1].kind, Kind::Comment(_)) {
                out.remove(i - 1);
                i -= 1;
                continue;
            }
            return has_next;
        }
    }

    /// Place Python's separator text node (moving it: older copies become stale).
    fn push_separator(&self, out: &mut Vec<NodeRef>, src: &Src) {
        let generation = self.separator.get() + 1;
        self.separator.set(generation);
        out.push(Rc::new(Node {
            kind: Kind::Separator(generation),
            src: src.clone(),
        }));
    }

    /// Lift `xmlns:*` attributes of an expanded macro body or included root to the parent element.
    fn import_namespaces(&self, parent_attrs: &mut Vec<Attr>, attrs: &[Attr], loc: Loc) {
        for a in attrs.iter().filter(|a| a.name.starts_with("xmlns:")) {
            match parent_attrs.iter().find(|p| p.name == a.name) {
                Some(old) if old.value != a.value => self.warn(
                    format!(
                        "inconsistent namespace redefinitions for {}: old: {} new: {}",
                        a.name, old.value, a.value
                    ),
                    Some(loc),
                ),
                Some(_) => {}
                None => parent_attrs.push(a.clone()),
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn process_children(
        &self,
        children: &[NodeRef],
        out: &mut Vec<NodeRef>,
        parent_attrs: &mut Vec<Attr>,
        macros: &MacroTableRef,
        symbols: &TableRef,
        ctx: &Ctx,
    ) -> Result<(), XacroError> {
        let mut eval_comments = false;
        for (i, child) in children.iter().enumerate() {
            let has_next = i + 1 < children.len();
            let mut node = child.clone();
            loop {
                match &node.kind {
                    Kind::Element(el) => {
                        eval_comments = false;
                        match self.element_child(
                            &node,
                            el,
                            out,
                            parent_attrs,
                            macros,
                            symbols,
                            ctx,
                            has_next,
                        )? {
                            Some(renamed) => {
                                node = renamed;
                                continue;
                            }
                            None => break,
                        }
                    }
                    Kind::Text(t) => {
                        let value = if t.contains('$') {
                            into_text(
                                self.eval_text(t, symbols, ctx)
                                    .map_err(|e| self.locate(e, node.src.loc, ctx))?,
                            )
                        } else {
                            t.clone()
                        };
                        if !value.trim().is_empty() {
                            eval_comments = false;
                        }
                        self.count_node(value.len())?;
                        out.push(Rc::new(Node {
                            kind: Kind::Text(value),
                            src: node.src.placed(&ctx.frame),
                        }));
                    }
                    Kind::Comment(c) => {
                        if c.contains("xacro:eval-comments") {
                            eval_comments = !c.contains("xacro:eval-comments:off");
                        } else if eval_comments {
                            let value = self
                                .eval_text(c, symbols, ctx)
                                .map_err(|e| self.locate(e, node.src.loc, ctx))
                                .map(into_text)?;
                            self.count_node(value.len())?;
                            out.push(Rc::new(Node {
                                kind: Kind::Comment(value),
                                src: node.src.placed(&ctx.frame),
                            }));
                        } else {
                            self.count_node(c.len())?;
                            out.push(node.clone());
                        }
                    }
                    Kind::Pi { .. } | Kind::CData(_) => out.push(node.clone()),
                    Kind::Separator(_) => {
                        // A block copied with the live separator in it holds a plain "\n\n" text there.
                        if self.is_live_separator(&node) {
                            out.push(Rc::new(Node {
                                kind: Kind::Text("\n\n".into()),
                                src: node.src.clone(),
                            }));
                        }
                    }
                }
                break;
            }
        }
        Ok(())
    }

    /// Process one element child. Returns a node to process again in its place (`xacro:element`).
    #[allow(clippy::too_many_arguments)]
    fn element_child(
        &self,
        node: &NodeRef,
        el: &Element,
        out: &mut Vec<NodeRef>,
        parent_attrs: &mut Vec<Attr>,
        macros: &MacroTableRef,
        symbols: &TableRef,
        ctx: &Ctx,
        has_next: bool,
    ) -> Result<Option<NodeRef>, XacroError> {
        let loc = node.src.loc;
        match &*el.name {
            "xacro:insert_block" => {
                let attrs = self.check_attrs(node, el, &["name"], &[], ctx)?;
                let name = attrs.first().copied().flatten().map_or("", |a| &*a.value);
                let (block, content_only) = match self.block(symbols, &format!("**{name}")) {
                    Some(b) => (b, true),
                    None => match self.block(symbols, &format!("*{name}")) {
                        Some(b) => (b, false),
                        None => {
                            let e = XacroError::new(
                                ErrorKind::Block,
                                format!("Undefined block \"{name}\""),
                            );
                            return Err(self.locate(e, loc, ctx));
                        }
                    },
                };
                let built = self.eval_element(&block, macros, symbols, ctx)?;
                if content_only {
                    out.extend(built.children);
                } else {
                    out.push(built.into_node());
                }
            }
            "xacro:include" => {
                self.include(node, el, out, parent_attrs, macros, symbols, ctx, has_next)?
            }
            "xacro:property" => {
                let sep = self.remove_previous_comments(out, has_next);
                self.property(node, el, symbols, ctx)?;
                if sep {
                    self.push_separator(out, &node.src);
                }
            }
            "xacro:macro" => {
                let sep = self.remove_previous_comments(out, has_next);
                self.define_macro(node, el, macros, ctx)?;
                if sep {
                    self.push_separator(out, &node.src);
                }
            }
            "xacro:arg" => {
                let attrs = self.check_attrs(node, el, &["name", "default"], &[], ctx)?;
                if let [Some(name), Some(default)] = attrs[..] {
                    if !self.args.borrow().contains_key(&*name.value) {
                        let value = self.eval_attr(default, symbols, ctx)?.to_xacro_string();
                        self.args.borrow_mut().insert(name.value.to_string(), value);
                    }
                }
                if self.remove_previous_comments(out, has_next) {
                    self.push_separator(out, &node.src);
                }
            }
            "xacro:element" => {
                let attrs = self.required_attrs(node, el, &["xacro:name"], ctx)?;
                let Some(name_attr) = attrs.first().copied().flatten() else {
                    return Ok(None);
                };
                let name = self.eval_attr(name_attr, symbols, ctx)?.to_xacro_string();
                if name.is_empty() {
                    return Err(self.locate(
                        XacroError::new(ErrorKind::Other, "xacro:element: empty name"),
                        loc,
                        ctx,
                    ));
                }
                let attrs = el
                    .attrs
                    .iter()
                    .filter(|a| &*a.name != "xacro:name")
                    .cloned()
                    .collect();
                return Ok(Some(Rc::new(Node {
                    kind: Kind::Element(Element {
                        name: name.into(),
                        attrs,
                        children: el.children.clone(),
                    }),
                    src: node.src.clone(),
                })));
            }
            "xacro:attribute" => {
                let attrs = self.required_attrs(node, el, &["name", "value"], ctx)?;
                if let [Some(name_attr), Some(value_attr)] = attrs[..] {
                    let name = into_text(self.eval_attr(name_attr, symbols, ctx)?);
                    let value = into_text(self.eval_attr(value_attr, symbols, ctx)?);
                    if name.is_empty() {
                        let e = XacroError::new(ErrorKind::Other, "xacro:attribute: empty name");
                        return Err(self.locate(e, loc, ctx));
                    }
                    let attr = Attr {
                        name,
                        value,
                        name_loc: name_attr.src.loc,
                        src: value_attr.src.placed(&ctx.frame),
                    };
                    match parent_attrs.iter_mut().find(|a| a.name == attr.name) {
                        Some(existing) => *existing = attr,
                        None => parent_attrs.push(attr),
                    }
                }
            }
            "xacro:if" | "xacro:unless" => {
                let sep = self.remove_previous_comments(out, has_next);
                let attrs = self.check_attrs(node, el, &["value"], &[], ctx)?;
                if let Some(cond) = attrs.first().copied().flatten() {
                    let value = self.eval_attr(cond, symbols, ctx)?;
                    let Some(mut keep) = boolean_value(&value) else {
                        let e = XacroError::new(
                            ErrorKind::BadCondition,
                            format!(
                                "Xacro conditional \"{}\" evaluated to \"{}\", which is not a boolean expression.",
                                cond.value,
                                value.to_xacro_string()
                            ),
                        );
                        return Err(self.locate(e, cond.src.loc, ctx));
                    };
                    if &*el.name == "xacro:unless" {
                        keep = !keep;
                    }
                    if keep {
                        let built = self.eval_element(node, macros, symbols, ctx)?;
                        out.extend(built.children);
                    }
                }
                if sep {
                    self.push_separator(out, &node.src);
                }
            }
            name if name.starts_with("xacro:") => {
                self.macro_call(node, el, out, parent_attrs, macros, symbols, ctx, has_next)?;
            }
            _ => {
                let built = self.eval_element(node, macros, symbols, ctx)?;
                out.push(built.into_node());
            }
        }
        Ok(None)
    }

    fn block(&self, symbols: &TableRef, key: &str) -> Option<NodeRef> {
        let table = symbols.find(key)?;
        let entry = table.entries.borrow().get(key).cloned();
        match entry {
            Some(Entry::Block(b)) => Some(b),
            _ => None,
        }
    }

    /// `grab_property`.
    fn property(
        &self,
        node: &NodeRef,
        el: &Element,
        symbols: &TableRef,
        ctx: &Ctx,
    ) -> Result<(), XacroError> {
        let loc = node.src.loc;
        let attrs = self.check_attrs(
            node,
            el,
            &["name"],
            &["value", "default", "remove", "scope", "lazy_eval"],
            ctx,
        )?;
        let [Some(name_attr), value, default, remove, scope, lazy_eval] = attrs[..] else {
            return Ok(());
        };
        let name = self.eval_attr(name_attr, symbols, ctx)?.to_xacro_string();
        if !is_valid_name(&name) {
            let e = XacroError::new(
                ErrorKind::InvalidName,
                format!("Property names must be valid python identifiers: {name}"),
            );
            return Err(self.locate(e, name_attr.src.loc, ctx));
        }
        if name.starts_with("__") {
            let e = XacroError::new(
                ErrorKind::InvalidName,
                format!("Property names must not start with double underscore:{name}"),
            );
            return Err(self.locate(e, name_attr.src.loc, ctx));
        }
        let bool_attr = |a: Option<&Attr>, default: bool| -> Result<bool, XacroError> {
            let Some(a) = a else { return Ok(default) };
            let v = self.eval_attr(a, symbols, ctx)?;
            boolean_value(&v).ok_or_else(|| {
                let e = XacroError::new(
                    ErrorKind::BadCondition,
                    format!(
                        "Xacro conditional \"{}\" evaluated to \"{}\", which is not a boolean expression.",
                        a.value,
                        v.to_xacro_string()
                    ),
                );
                self.locate(e, a.src.loc, ctx)
            })
        };
        let remove = bool_attr(remove, false)?;
        if usize::from(value.is_some()) + usize::from(default.is_some()) + usize::from(remove) > 1 {
            let e = XacroError::new(
                ErrorKind::Other,
                format!(
                    "Property attributes default, value, and remove are mutually exclusive: {name}"
                ),
            );
            return Err(self.locate(e, loc, ctx));
        }
        if remove && self.has_symbol(symbols, &name) {
            symbols.remove(&name);
            return Ok(());
        }
        let mut value = value;
        if let Some(d) = default {
            if scope.is_some() {
                self.warn(
                    format!("{name}: default property value can only be defined on local scope"),
                    Some(loc),
                );
            }
            if self.has_symbol(symbols, &name) {
                return Ok(());
            }
            value = Some(d);
        }
        let mut lazy = bool_attr(lazy_eval, true)?;
        let target = match scope.map(|a| &*a.value) {
            Some("global") => {
                lazy = false;
                symbols.top()
            }
            Some("parent") => match &symbols.parent {
                Some(parent) => {
                    lazy = false;
                    let mut target = parent.clone();
                    if !symbols.is_namespace {
                        while target.is_namespace {
                            match target.parent.clone() {
                                Some(p) => target = p,
                                None => break,
                            }
                        }
                    }
                    target
                }
                None => {
                    let e = XacroError::new(
                        ErrorKind::Other,
                        format!("{name}: scope=\"parent\" used at global scope, which has no parent scope"),
                    );
                    return Err(self.locate(e, loc, ctx));
                }
            },
            _ => symbols.clone(),
        };
        if value.is_some() {
            self.warn_if_builtin(&name, loc);
        }
        match value {
            None => target.set_entry(&format!("**{name}"), Entry::Block(node.clone())),
            Some(v) if !lazy => {
                let evaluated = self.eval_attr(v, symbols, ctx)?;
                target.set_value(&name, evaluated);
            }
            Some(v) => target.set_text(&name, &v.value, true, Some(v.src.loc)),
        }
        Ok(())
    }

    /// `grab_macro`.
    fn define_macro(
        &self,
        node: &NodeRef,
        el: &Element,
        macros: &MacroTableRef,
        ctx: &Ctx,
    ) -> Result<(), XacroError> {
        let loc = node.src.loc;
        let attrs = self.check_attrs(node, el, &["name"], &["params"], ctx)?;
        let [Some(name_attr), params] = attrs[..] else {
            return Ok(());
        };
        let mut name: &str = &name_attr.value;
        if name == "call" {
            return Err(self.locate(
                XacroError::new(ErrorKind::Other, "Invalid use of macro name 'call'"),
                loc,
                ctx,
            ));
        }
        if name.contains('.') {
            let e = XacroError::new(
                ErrorKind::Other,
                format!("macro names must not contain '.' (reserved for namespaces): {name}"),
            );
            return Err(self.locate(e, loc, ctx));
        }
        if let Some(stripped) = name.strip_prefix("xacro:") {
            self.warn(
                format!("macro names must not contain prefix 'xacro:': {name}"),
                Some(loc),
            );
            name = stripped;
        }
        let mut m = Macro {
            params: Vec::new(),
            defaults: HashMap::new(),
            body: node.clone(),
        };
        for (param, spec) in parse_params(params.map_or("", |p| &*p.value)) {
            if let Some(spec) = spec {
                m.defaults.insert(param.clone(), spec);
            }
            m.params.push(param);
        }
        macros
            .entries
            .borrow_mut()
            .insert(name.to_string(), MacroEntry::Macro(Rc::new(m)));
        Ok(())
    }

    /// `resolve_macro`: the macro, and the macro and symbol tables it is called with.
    fn resolve_macro(
        &self,
        fullname: &str,
        macros: &MacroTableRef,
        symbols: &TableRef,
    ) -> Option<(MacroTableRef, TableRef, Rc<Macro>)> {
        if let Some(MacroEntry::Macro(m)) = macros.get(fullname) {
            return Some((macros.clone(), symbols.clone(), m));
        }
        let mut parts: Vec<&str> = fullname.split('.').collect();
        let name = parts.pop()?;
        if parts.is_empty() {
            return None;
        }
        let (mut m, mut s) = (macros.clone(), symbols.clone());
        for ns in parts {
            let MacroEntry::Namespace(next_m) = m.get(ns)? else {
                return None;
            };
            let table = s.find(ns)?;
            let entry = table.entries.borrow().get(ns).cloned();
            let Some(Entry::Namespace(next_s)) = entry else {
                return None;
            };
            m = next_m;
            s = next_s;
        }
        match m.get(name)? {
            MacroEntry::Macro(found) => Some((m, s, found)),
            MacroEntry::Namespace(_) => None,
        }
    }

    /// `handle_macro_call` (and `handle_dynamic_macro_call`).
    #[allow(clippy::too_many_arguments)]
    fn macro_call(
        &self,
        node: &NodeRef,
        el: &Element,
        out: &mut Vec<NodeRef>,
        parent_attrs: &mut Vec<Attr>,
        macros: &MacroTableRef,
        symbols: &TableRef,
        ctx: &Ctx,
        has_next: bool,
    ) -> Result<(), XacroError> {
        let loc = node.src.loc;
        let (name, call_attrs): (String, Vec<&Attr>) = if &*el.name == "xacro:call" {
            let Some(macro_attr) = el.attrs.iter().find(|a| &*a.name == "macro") else {
                let e = XacroError::new(
                    ErrorKind::MissingAttribute,
                    "xacro:call: missing attribute 'macro'",
                );
                return Err(self.locate(e, loc, ctx));
            };
            if macro_attr.value.is_empty() {
                let e = XacroError::new(
                    ErrorKind::MissingAttribute,
                    "xacro:call is missing the 'macro' attribute",
                );
                return Err(self.locate(e, loc, ctx));
            }
            let name = self.eval_attr(macro_attr, symbols, ctx)?.to_xacro_string();
            if name == "call" {
                let e = XacroError::new(
                    ErrorKind::MissingAttribute,
                    "xacro:call: missing attribute 'macro'",
                );
                return Err(self.locate(e, loc, ctx));
            }
            (
                name,
                el.attrs.iter().filter(|a| &*a.name != "macro").collect(),
            )
        } else {
            (
                el.name["xacro:".len()..].to_string(),
                el.attrs.iter().collect(),
            )
        };
        let Some((ns_macros, ns_symbols, m)) = self.resolve_macro(&name, macros, symbols) else {
            let names = macros.visible_names();
            let hint = did_you_mean(&name, names.iter().map(String::as_str));
            let e = XacroError::new(
                ErrorKind::UnknownMacro,
                format!("unknown macro name: xacro:{name}{hint}"),
            );
            return Err(self.locate(e, loc, ctx));
        };
        if ctx.macro_depth >= self.opts.limits.max_macro_depth {
            let e = XacroError::new(
                ErrorKind::Limit,
                format!(
                    "macro calls nested deeper than {} levels (runaway recursion?) when calling '{name}'",
                    self.opts.limits.max_macro_depth
                ),
            );
            return Err(self.locate(e, loc, ctx));
        }
        let frame = Rc::new(FrameData {
            kind: FrameKind::Macro,
            name: name.clone(),
            loc,
            parent: ctx.frame.clone(),
        });
        let call_ctx = Ctx {
            frame: Some(frame),
            macro_depth: ctx.macro_depth + 1,
            include_depth: ctx.include_depth,
        };
        let scoped_symbols = Table::child(&ns_symbols, false);
        let scoped_macros = MacroTable::child(&ns_macros);
        let mut params = m.params.clone();
        for a in call_attrs {
            let Some(pos) = params.iter().position(|p| **p == *a.name) else {
                let hint = did_you_mean(&a.name, m.params.iter().map(String::as_str));
                let e = XacroError::new(
                    ErrorKind::UnknownParameter,
                    format!("Invalid parameter \"{}\" of macro '{name}'{hint}", a.name),
                );
                return Err(self.locate(e, a.name_loc, ctx));
            };
            params.remove(pos);
            let value = self.eval_attr(a, symbols, ctx)?;
            self.warn_if_builtin(&a.name, a.name_loc);
            scoped_symbols.set_value(&a.name, value);
        }
        // The call's children (blocks) are evaluated in the caller's scope.
        let mut call_children = Vec::new();
        let mut call_attrs_out = Vec::new();
        self.process_children(
            &el.children,
            &mut call_children,
            &mut call_attrs_out,
            macros,
            symbols,
            ctx,
        )?;
        let mut blocks = call_children
            .iter()
            .filter(|n| matches!(n.kind, Kind::Element(_)));
        for param in params.clone() {
            if param.starts_with('*') {
                let Some(block) = blocks.next() else {
                    let e = XacroError::new(
                        ErrorKind::Block,
                        format!("Not enough blocks for macro '{name}'"),
                    );
                    return Err(self.locate(e, loc, ctx));
                };
                params.retain(|p| *p != param);
                scoped_symbols.set_entry(&param, Entry::Block(block.clone()));
            }
        }
        if let Some(extra) = blocks.next() {
            let tag = match &extra.kind {
                Kind::Element(e) => e.name.to_string(),
                _ => String::new(),
            };
            let e = XacroError::new(
                ErrorKind::Block,
                format!("Unused block \"{tag}\" in call of macro '{name}'"),
            );
            return Err(self.locate(e, extra.src.loc, ctx));
        }
        for param in params.clone() {
            if param.starts_with('*') {
                continue;
            }
            if let Some((forward, default)) = m.defaults.get(&param) {
                let value = match forward {
                    None => self.eval_text(default.as_deref().unwrap_or(""), symbols, ctx),
                    Some(fwd) => match self.lookup_property(symbols, fwd, ctx)? {
                        Some(v) => Ok(v),
                        None => match default {
                            Some(d) => self.eval_text(d, symbols, ctx),
                            None => Err(XacroError::new(
                                ErrorKind::UndefinedProperty,
                                format!("Undefined property to forward: {fwd}"),
                            )),
                        },
                    },
                }
                .map_err(|e| self.locate(e, loc, ctx))?;
                self.warn_if_builtin(&param, loc);
                scoped_symbols.set_value(&param, value);
                params.retain(|p| *p != param);
            }
        }
        if !params.is_empty() {
            let e = XacroError::new(
                ErrorKind::MissingParameter,
                format!(
                    "Undefined parameters [{}] in call of macro '{name}'",
                    params.join(",")
                ),
            );
            return Err(self.locate(e, loc, ctx));
        }
        let body = self.eval_element(&m.body, &scoped_macros, &scoped_symbols, &call_ctx)?;
        let sep = self.remove_previous_comments(out, has_next);
        self.import_namespaces(parent_attrs, &body.attrs, loc);
        out.extend(body.children);
        if sep {
            self.push_separator(out, &node.src);
        }
        Ok(())
    }

    /// `process_include`.
    #[allow(clippy::too_many_arguments)]
    fn include(
        &self,
        node: &NodeRef,
        el: &Element,
        out: &mut Vec<NodeRef>,
        parent_attrs: &mut Vec<Attr>,
        macros: &MacroTableRef,
        symbols: &TableRef,
        ctx: &Ctx,
        has_next: bool,
    ) -> Result<(), XacroError> {
        let loc = node.src.loc;
        let attrs = self.check_attrs(node, el, &["filename"], &["ns", "optional"], ctx)?;
        let [Some(filename), ns, optional] = attrs[..] else {
            return Ok(());
        };
        let (ns_macros, ns_symbols) = match ns {
            Some(ns) => {
                let ns_name = self.eval_attr(ns, symbols, ctx)?.to_xacro_string();
                let ns_macros: MacroTableRef = Rc::default();
                macros
                    .entries
                    .borrow_mut()
                    .insert(ns_name.clone(), MacroEntry::Namespace(ns_macros.clone()));
                let ns_symbols = Table::child(symbols, true);
                symbols.set_entry(&ns_name, Entry::Namespace(ns_symbols.clone()));
                (ns_macros, ns_symbols)
            }
            None => (macros.clone(), symbols.clone()),
        };
        let optional = match optional {
            None => false,
            Some(a) => boolean_value(&Value::Str(a.value.clone())).ok_or_else(|| {
                let e = XacroError::new(
                    ErrorKind::BadCondition,
                    format!("Xacro conditional \"None\" evaluated to \"{}\", which is not a boolean expression.", a.value),
                );
                self.locate(e, a.src.loc, ctx)
            })?,
        };
        if el
            .children
            .iter()
            .any(|c| matches!(c.kind, Kind::Element(_)))
        {
            self.warn(
                "Child elements of a <xacro:include> tag are ignored".into(),
                Some(loc),
            );
        }
        let spec = self.eval_attr(filename, symbols, ctx)?.to_xacro_string();
        let path = include::abs_filename(&spec, &self.current_file());
        let path_text = path.display().to_string();
        let files = if include::is_glob(&path_text) {
            let files = include::glob_files(&path_text);
            if files.is_empty() {
                self.warn(
                    format!("Include tag's filename spec \"{path_text}\" matched no files."),
                    Some(loc),
                );
            }
            files
        } else {
            vec![path]
        };
        let mut included = Vec::new();
        for file in files {
            if ctx.include_depth >= self.opts.limits.max_include_depth {
                let e = XacroError::new(
                    ErrorKind::Limit,
                    format!(
                        "includes nested deeper than {} levels",
                        self.opts.limits.max_include_depth
                    ),
                );
                return Err(self.locate(e, loc, ctx));
            }
            let canonical = Some(lexical_absolute(&file));
            let cycle = canonical.is_some() && self.open_files.borrow().contains(&canonical);
            if cycle {
                let e = XacroError::new(
                    ErrorKind::IncludeCycle,
                    format!(
                        "include cycle: {} includes itself (directly or through other files)",
                        file.display()
                    ),
                );
                return Err(self.locate(e, loc, ctx));
            }
            let frame = Rc::new(FrameData {
                kind: FrameKind::Include,
                name: file.display().to_string(),
                loc,
                parent: ctx.frame.clone(),
            });
            let inc_ctx = Ctx {
                frame: Some(frame),
                macro_depth: ctx.macro_depth,
                include_depth: ctx.include_depth + 1,
            };
            let doc = match self.load(&file) {
                Ok(doc) => doc,
                Err(e)
                    if optional && matches!(e.kind, ErrorKind::IncludeNotFound | ErrorKind::Io) =>
                {
                    continue
                }
                // Invalid XML in the included file: located there, through this include.
                Err(mut e) if e.location.is_some() => {
                    e.stack = self.stack(&inc_ctx);
                    return Err(e);
                }
                Err(e) => return Err(self.locate(e, filename.src.loc, ctx)),
            };
            let Some(root) = doc.root().cloned() else {
                continue;
            };
            self.file_stack.borrow_mut().push(file);
            self.open_files.borrow_mut().push(canonical);
            let built = self.eval_element(&root, &ns_macros, &ns_symbols, &inc_ctx);
            self.file_stack.borrow_mut().pop();
            self.open_files.borrow_mut().pop();
            let built = built?;
            self.import_namespaces(parent_attrs, &built.attrs, loc);
            included.extend(built.children);
        }
        let sep = self.remove_previous_comments(out, has_next);
        out.extend(included);
        if sep {
            self.push_separator(out, &node.src);
        }
        Ok(())
    }
}

/// `$(...)` host: arguments, environment, packages, the current directory.
struct SubstHost<'a, 'o> {
    x: &'a Expander<'o>,
}

impl SubstitutionHost for SubstHost<'_, '_> {
    fn arg(&self, name: &str) -> Result<String, XacroError> {
        self.x.arg_value(name)
    }

    fn env(&self, name: &str) -> Option<String> {
        self.x.env_var(name)
    }

    fn find(&self, pkg: &str) -> Result<String, XacroError> {
        self.x.find_package(pkg)
    }

    fn dirname(&self) -> Result<String, XacroError> {
        self.x.dirname()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dunder_names_outside_strings() {
        assert_eq!(dunder_names("__import__('os').system('x')"), ["__import__"]);
        assert_eq!(dunder_names("a.__class__"), ["__class__"]);
        assert!(dunder_names("'__x__' + b").is_empty());
        assert!(is_valid_name("wheel_radius"));
        assert!(!is_valid_name("1a"));
        assert!(!is_valid_name("lambda"));
    }
}
