//! The expansion itself: a port of Python xacro 2.1.1's `eval_all` and helpers (in-order processing) over
//! the immutable [`crate::document`] tree, building new output nodes.

use std::cell::{Cell, RefCell};
use std::collections::{HashMap, HashSet};
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
use crate::substitution::{self, Refused, SubstitutionHost};
use crate::{Expansion, Options, Warning};

mod tags;
mod text;

use text::host_error;

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
    /// Argument names declared by `xacro:arg` or read by `$(arg)` / `xacro.arg()` (given arguments not
    /// in here are reported: likely misspelled).
    known_args: RefCell<HashSet<String>>,
    /// Python's `filestack`: the files being processed (includes), innermost last.
    file_stack: RefCell<Vec<PathBuf>>,
    /// The canonical paths of `file_stack` (include cycles).
    open_files: RefCell<Vec<Option<PathBuf>>>,
    /// The detailed error behind an `EvalError` returned to the evaluator through [`Scope`].
    pending: RefCell<Option<XacroError>>,
    warnings: RefCell<Vec<Warning>>,
    /// The attribute or text being evaluated: where a refused `$(env)` or `load_yaml` is reported.
    at: Cell<Option<Loc>>,
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
        known_args: RefCell::default(),
        file_stack: RefCell::new(vec![path.to_path_buf()]),
        open_files: RefCell::new(vec![Some(lexical_absolute(path))]),
        pending: RefCell::default(),
        warnings: RefCell::default(),
        at: Cell::new(None),
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

/// `e` with the gate's refusals noted: a refused include or YAML file often makes a later step fail, and
/// the error then says why.
fn with_refusals(mut e: XacroError, warnings: &[Warning]) -> XacroError {
    let refused: Vec<&str> = warnings
        .iter()
        .filter(|w| w.refused)
        .map(|w| w.message.as_str())
        .collect();
    if !refused.is_empty() {
        e.message = format!("{} (after: {})", e.message, refused.join("; "));
    }
    e
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
        let built = x
            .eval_element(&root, &macros, &symbols, &ctx)
            .map_err(|e| with_refusals(e, &x.warnings.borrow()))?;
        x.warn_unknown_args(root.src.loc);
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
        let limit = self.opts.limits.max_output_bytes;
        let text = include::read_text(path, limit).map_err(|e| {
            if e.kind() == std::io::ErrorKind::NotFound {
                // Name the absolute path looked for: the written name is relative to the including file.
                let abs = lexical_absolute(path);
                let looked = if abs == path {
                    String::new()
                } else {
                    format!("looked for {}: ", abs.display())
                };
                XacroError::new(
                    ErrorKind::IncludeNotFound,
                    format!(
                        "No such file or directory: {} ({looked}{e})",
                        path.display()
                    ),
                )
            } else {
                XacroError::new(
                    ErrorKind::Io,
                    format!("cannot read {}: {e}", path.display()),
                )
            }
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

    /// Record a warning at `loc`, with the macro calls and includes of `ctx` that led there.
    fn warn(&self, message: String, loc: Option<Loc>, ctx: &Ctx) {
        let location = loc.and_then(|l| self.location(l));
        let stack = self.stack(ctx);
        self.warnings.borrow_mut().push(Warning {
            message,
            location,
            stack,
            refused: false,
        });
    }

    /// Record an access the gate refused, at the attribute or text being evaluated.
    fn refuse(&self, message: String) {
        let location = self.at.get().and_then(|l| self.location(l));
        self.warnings.borrow_mut().push(Warning {
            message,
            location,
            stack: Vec::new(),
            refused: true,
        });
    }

    /// Record an access the gate refused, at `loc`, with the macro calls and includes that led there.
    fn warn_refused(&self, message: String, loc: Loc, ctx: &Ctx) {
        self.warn(message, Some(loc), ctx);
        if let Some(last) = self.warnings.borrow_mut().last_mut() {
            last.refused = true;
        }
    }

    /// Warn about each given argument that no `xacro:arg` declared and no `$(arg)` read (Python xacro
    /// ignores them silently; usually a misspelling), at `loc` (the root element).
    fn warn_unknown_args(&self, loc: Loc) {
        let known = self.known_args.borrow();
        let mut reported = HashSet::new();
        for (name, _) in &self.opts.args {
            if known.contains(name) || !reported.insert(name) {
                continue;
            }
            let hint = did_you_mean(name, known.iter().map(String::as_str));
            self.warn(
                format!("argument '{name}' was given but no <xacro:arg> declares it and no $(arg) reads it{hint}"),
                Some(loc),
                &Ctx::default(),
            );
        }
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
                ctx,
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
        self.at.set(Some(attr.src.loc));
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
    fn import_namespaces(&self, parent_attrs: &mut Vec<Attr>, attrs: &[Attr], loc: Loc, ctx: &Ctx) {
        for a in attrs.iter().filter(|a| a.name.starts_with("xmlns:")) {
            match parent_attrs.iter().find(|p| p.name == a.name) {
                Some(old) if old.value != a.value => self.warn(
                    format!(
                        "inconsistent namespace redefinitions for {}: old: {} new: {}",
                        a.name, old.value, a.value
                    ),
                    Some(loc),
                    ctx,
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
                            self.at.set(Some(node.src.loc));
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
                    self.known_args.borrow_mut().insert(name.value.to_string());
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
}

#[cfg(test)]
mod tests {
    use super::text::dunder_names;
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
