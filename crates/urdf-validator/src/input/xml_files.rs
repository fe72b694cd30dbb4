//! XML inputs made of several files (SDFormat, MJCF): the entry file and every file its `<include>`s pull
//! in, read once with bounded depth, count and size, laid end to end in one span space so a [`Span`] names
//! a file and a place in it.
//!
//! Findings inside an included file are located in that file, with the `<include>` chain as their stack
//! (`in model://arm included at world.sdf:12:5`), as xacro findings carry their include stack.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use roxmltree::Node;

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules::Rule;
use crate::diagnostics::span::Span;
use crate::input::resolve::{IncludeFailure, PackageResolver};
use crate::input::source::SourceText;
use crate::input::xacro::SourceLocation;
use crate::input::{read_text, xml_options, LoadError, MAX_FILE_BYTES};

/// Deepest chain of `<include>`s followed (entry file at depth 0).
pub const MAX_INCLUDE_DEPTH: usize = 16;

/// Most files read for one input (the entry file and its includes).
pub const MAX_INCLUDED_FILES: usize = 256;

/// True when `text`'s root element is `<sdf>` (whatever the file is called).
pub fn is_sdf(text: &str) -> bool {
    root_element_is(text, "sdf")
}

/// True when `text`'s root element is `<mujoco>`: an MJCF model (whatever the file is called).
pub fn is_mjcf(text: &str) -> bool {
    root_element_is(text, "mujoco")
}

/// True when the first element of `text` (after the XML declaration, comments and a DOCTYPE) is `<name`.
fn root_element_is(text: &str, name: &str) -> bool {
    let mut rest = text.trim_start_matches('\u{feff}');
    loop {
        rest = rest.trim_start();
        let skip_to = |rest: &str, end: &str| rest.find(end).map(|i| i + end.len());
        let skipped = if rest.starts_with("<?") {
            skip_to(rest, "?>")
        } else if rest.starts_with("<!--") {
            skip_to(rest, "-->")
        } else if rest.starts_with("<!") {
            skip_to(rest, ">")
        } else {
            let Some(after) = rest.strip_prefix('<').and_then(|r| r.strip_prefix(name)) else {
                return false;
            };
            return after.starts_with(|c: char| c.is_whitespace() || c == '>' || c == '/');
        };
        match skipped.and_then(|i| rest.get(i..)) {
            Some(after) => rest = after,
            None => return false,
        }
    }
}

/// How a format writes its includes, and where it looks for the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IncludeSyntax {
    /// SDFormat: `<include><uri>model://arm</uri></include>`, resolved as Gazebo does (`model://`,
    /// `package://`, paths relative to the including file).
    Sdf,
    /// MJCF: `<include file="arm.xml"/>`, a path: relative to the including file's folder, else to the
    /// entry file's (MuJoCo tries both); the included file's root must be `<mujoco>`.
    Mjcf,
}

/// One file of the set.
#[derive(Debug)]
struct XmlFile {
    source: SourceText,
    /// Where its byte 0 is in the shared span space.
    base: u32,
    /// The file and `<include>` element (span in the shared space) that pulled it in, and the URI.
    included_at: Option<(usize, Span, String)>,
}

/// What one `<include>` element resolved to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum IncludeTarget {
    /// The index of the included file.
    File(usize),
    /// Why it could not be read (not found, unreadable, malformed, a cycle, too deep).
    Unresolved(String),
    /// The sandbox refused to read it (untrusted mode); why.
    Refused(String),
}

/// An element and the file holding it: what the MJCF and SDFormat readers walk.
#[derive(Clone, Copy, Debug)]
pub struct El<'a> {
    /// Index of the file in [`XmlFiles`].
    pub file: usize,
    /// The element.
    pub node: Node<'a, 'a>,
}

impl<'a> El<'a> {
    /// The tag name.
    pub fn tag(&self) -> &'a str {
        self.node.tag_name().name()
    }

    /// Attribute `name` as written.
    pub fn attr(&self, name: &str) -> Option<&'a str> {
        self.node.attribute(name)
    }

    /// The first child element named `tag`.
    pub fn child(&self, tag: &str) -> Option<El<'a>> {
        self.node
            .children()
            .find(|n| n.is_element() && n.has_tag_name(tag))
            .map(|node| El {
                file: self.file,
                node,
            })
    }

    /// Every child element named `tag`.
    pub fn children(&self, tag: &'a str) -> impl Iterator<Item = El<'a>> + 'a {
        let file = self.file;
        self.node
            .children()
            .filter(move |n| n.is_element() && n.has_tag_name(tag))
            .map(move |node| El { file, node })
    }

    /// The trimmed text of the element.
    pub fn text(&self) -> &'a str {
        self.node.text().unwrap_or("").trim()
    }
}

/// Where a reader's findings go, with the files their spans point into (the MJCF and SDFormat readers
/// build on it).
pub struct FindingSink<'a> {
    /// The files.
    pub files: &'a XmlFiles,
    /// Findings so far.
    pub findings: Vec<Finding>,
}

impl<'a> FindingSink<'a> {
    /// A sink for findings in `files`.
    pub fn new(files: &'a XmlFiles) -> Self {
        FindingSink {
            files,
            findings: Vec::new(),
        }
    }

    /// The span of an element in the shared span space.
    pub fn span(&self, el: El<'_>) -> Span {
        self.files.span(el.file, el.node.range())
    }

    /// The span of attribute `name`'s value, or the element's when it is not written.
    pub fn attr_span(&self, el: El<'_>, name: &str) -> Span {
        self.files.attr_span(el.file, el.node, name)
    }

    /// Record a finding.
    pub fn report(&mut self, rule: &'static Rule, span: Span, message: String) {
        self.findings.push(Finding::new(rule, span, message));
    }
}

/// The entry file (SDFormat or MJCF) and its includes.
#[derive(Debug)]
pub struct XmlFiles {
    syntax: IncludeSyntax,
    files: Vec<XmlFile>,
    /// `<include>` element start (shared span space) → what it resolved to.
    includes: HashMap<u32, IncludeTarget>,
    /// Canonical path → index of the files read, so a model included twice is read once.
    read: HashMap<PathBuf, usize>,
}

impl XmlFiles {
    /// Read the entry file's `text` (from `path`) and, transitively, every file an `<include>` names.
    /// A malformed entry file is an error; a problem with an included file is recorded for its
    /// `<include>` ([`XmlFiles::include`]).
    pub fn load(
        path: &Path,
        text: String,
        syntax: IncludeSyntax,
        resolver: &PackageResolver,
    ) -> Result<Self, LoadError> {
        if let Err(e) = roxmltree::Document::parse_with_options(&text, xml_options()) {
            let pos = e.pos();
            return Err(LoadError::Xml {
                path: path.to_path_buf(),
                line: pos.row,
                column: pos.col,
                message: e.to_string(),
            });
        }
        let mut set = XmlFiles {
            syntax,
            files: Vec::new(),
            includes: HashMap::new(),
            read: HashMap::new(),
        };
        set.push(path.to_path_buf(), text, None);
        set.read.insert(canonical(path), 0);
        set.follow(0, &[canonical(path)], resolver);
        Ok(set)
    }

    fn push(&mut self, path: PathBuf, text: String, included_at: Option<(usize, Span, String)>) {
        let base = self.files.last().map_or(0, |f| {
            f.base
                .saturating_add(len32(f.source.text()))
                .saturating_add(1)
        });
        self.files.push(XmlFile {
            source: SourceText::new(path, text),
            base,
            included_at,
        });
    }

    /// Resolve and read the includes of file `index`; `chain` holds the canonical paths from the entry
    /// file down to it (a cycle is an include of one of them).
    fn follow(&mut self, index: usize, chain: &[PathBuf], resolver: &PackageResolver) {
        let Some(file) = self.files.get(index) else {
            return;
        };
        let dir = parent_dir(file.source.path()).to_path_buf();
        let base = file.base;
        let Ok(doc) = roxmltree::Document::parse_with_options(file.source.text(), xml_options())
        else {
            return;
        };
        let syntax = self.syntax;
        let includes: Vec<(Span, String)> = doc
            .descendants()
            .filter(|n| n.has_tag_name("include"))
            .map(|n| {
                let uri = match syntax {
                    IncludeSyntax::Sdf => n
                        .children()
                        .find(|c| c.has_tag_name("uri"))
                        .and_then(|u| u.text()),
                    IncludeSyntax::Mjcf => n.attribute("file"),
                };
                let uri = uri.unwrap_or("").trim().to_string();
                (shift(Span::from_range(n.range()), base), uri)
            })
            .collect();
        drop(doc);
        for (at, uri) in includes {
            let target = self.read_include(index, at, &uri, &dir, chain, resolver);
            self.includes.insert(at.start, target);
        }
    }

    /// Where file `index` was first included, as " (first at FILE:LINE:COL)", or nothing for the entry
    /// file.
    fn first_include_site(&self, index: usize) -> String {
        let Some((from, at, _)) = self.files.get(index).and_then(|f| f.included_at.clone()) else {
            return String::new();
        };
        let Some(file) = self.files.get(from) else {
            return String::new();
        };
        let (line, column) = file
            .source
            .line_col(at.start.saturating_sub(file.base) as usize);
        format!(
            " (first at {}:{line}:{column})",
            file.source.path().display()
        )
    }

    fn read_include(
        &mut self,
        from: usize,
        at: Span,
        uri: &str,
        dir: &Path,
        chain: &[PathBuf],
        resolver: &PackageResolver,
    ) -> IncludeTarget {
        if uri.is_empty() {
            return IncludeTarget::Unresolved(match self.syntax {
                IncludeSyntax::Sdf => "<include> has no <uri>".to_string(),
                IncludeSyntax::Mjcf => "<include> has no file attribute".to_string(),
            });
        }
        let found = match self.syntax {
            IncludeSyntax::Sdf => resolver.resolve_include(uri, dir),
            IncludeSyntax::Mjcf => self.mjcf_include(uri, dir, resolver),
        };
        let path = match found {
            Ok(path) => path,
            Err(IncludeFailure::Unresolved(why)) => {
                return IncludeTarget::Unresolved(format!("cannot resolve '{uri}': {why}"))
            }
            Err(IncludeFailure::Refused(why)) => {
                return IncludeTarget::Refused(format!("refused to read include '{uri}': {why}"))
            }
        };
        let key = canonical(&path);
        if chain.contains(&key) {
            return IncludeTarget::Unresolved(format!(
                "'{uri}' ({}) includes itself: an include cycle",
                path.display()
            ));
        }
        if let Some(&index) = self.read.get(&key) {
            // MuJoCo refuses a file included twice ("File 'part.xml' already included"); SDFormat
            // includes a model as often as it is asked.
            if self.syntax == IncludeSyntax::Mjcf {
                return IncludeTarget::Unresolved(format!(
                    "'{uri}' is already included{}: MuJoCo refuses a file included twice (\"File '{uri}' already included\")",
                    self.first_include_site(index)
                ));
            }
            return IncludeTarget::File(index);
        }
        if chain.len() > MAX_INCLUDE_DEPTH {
            return IncludeTarget::Unresolved(format!(
                "'{uri}' is more than {MAX_INCLUDE_DEPTH} includes deep"
            ));
        }
        if self.files.len() >= MAX_INCLUDED_FILES {
            return IncludeTarget::Unresolved(format!(
                "more than {MAX_INCLUDED_FILES} files included; '{uri}' is not read"
            ));
        }
        let text = match read_text(&path) {
            Ok(text) => text,
            Err(e) => return IncludeTarget::Unresolved(e.to_string()),
        };
        let total: u64 = self
            .files
            .iter()
            .map(|f| f.source.text().len() as u64)
            .sum();
        if total + text.len() as u64 > MAX_FILE_BYTES {
            return IncludeTarget::Unresolved(format!(
                "the included files exceed {MAX_FILE_BYTES} bytes; '{uri}' is not read"
            ));
        }
        if let Err(e) = roxmltree::Document::parse_with_options(&text, xml_options()) {
            let pos = e.pos();
            return IncludeTarget::Unresolved(format!(
                "{}:{}:{}: not well-formed XML: {e}",
                path.display(),
                pos.row,
                pos.col
            ));
        }
        if self.syntax == IncludeSyntax::Mjcf && !is_mjcf(&text) {
            return IncludeTarget::Unresolved(format!(
                "{}: the root element is not <mujoco> (MuJoCo includes only MJCF files)",
                path.display()
            ));
        }
        self.push(path, text, Some((from, at, uri.to_string())));
        let index = self.files.len() - 1;
        self.read.insert(key.clone(), index);
        let mut deeper = chain.to_vec();
        deeper.push(key);
        self.follow(index, &deeper, resolver);
        IncludeTarget::File(index)
    }

    /// An MJCF `<include file>`: the path as written when absolute, else relative to the including
    /// file's folder `dir`, else to the entry file's folder (MuJoCo finds it in either), through the
    /// sandbox.
    fn mjcf_include(
        &self,
        file: &str,
        dir: &Path,
        resolver: &PackageResolver,
    ) -> Result<PathBuf, IncludeFailure> {
        let entry_dir = parent_dir(self.path(0));
        let candidates = [dir.join(file), entry_dir.join(file)];
        let Some(path) = candidates.iter().find(|p| p.is_file()) else {
            return Err(IncludeFailure::Unresolved(format!(
                "no such file beside the including file ({}) or the model file ({})",
                dir.display(),
                entry_dir.display()
            )));
        };
        resolver
            .sandbox()
            .check_file(path)
            .map_err(IncludeFailure::Refused)?;
        Ok(path.clone())
    }

    /// How many files were read (the entry file is index 0).
    pub fn len(&self) -> usize {
        self.files.len()
    }

    /// Always false: the entry file is always there.
    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// The text of file `index`.
    pub fn text(&self, index: usize) -> &str {
        self.files.get(index).map_or("", |f| f.source.text())
    }

    /// The path of file `index` as read.
    pub fn path(&self, index: usize) -> &Path {
        self.files
            .get(index)
            .map_or(Path::new(""), |f| f.source.path())
    }

    /// A span of file `index` (as roxmltree gives it) in the shared span space.
    pub fn span(&self, index: usize, range: std::ops::Range<usize>) -> Span {
        shift(
            Span::from_range(range),
            self.files.get(index).map_or(0, |f| f.base),
        )
    }

    /// The span of attribute `name`'s value on `node` of file `index`, or the element's when it is not
    /// written.
    pub fn attr_span(&self, index: usize, node: roxmltree::Node<'_, '_>, name: &str) -> Span {
        node.attribute_node(name).map_or_else(
            || self.span(index, node.range()),
            |a| self.span(index, a.range_value()),
        )
    }

    /// What the `<include>` element at `span` (shared span space) resolved to.
    pub fn include(&self, span: Span) -> Option<&IncludeTarget> {
        self.includes.get(&span.start)
    }

    /// The file holding shared-space byte `at`, and the offset inside it.
    fn file_at(&self, at: u32) -> Option<(&XmlFile, usize)> {
        let index = self
            .files
            .partition_point(|f| f.base <= at)
            .checked_sub(1)?;
        let file = self.files.get(index)?;
        Some((file, (at - file.base) as usize))
    }

    /// Where `span` is: file, line, column, and the chain of `<include>`s that read the file.
    pub fn locate(&self, span: Span) -> Option<SourceLocation> {
        let (file, start) = self.file_at(span.start)?;
        let end = (span.end.saturating_sub(file.base) as usize).max(start);
        let (line, column) = file.source.line_col(start);
        let (end_line, end_column) = file.source.line_col(end);
        let mut stack = Vec::new();
        let mut at = file.included_at.as_ref();
        while let Some((from, include, uri)) = at {
            let Some(parent) = self.files.get(*from) else {
                break;
            };
            let (line, col) = parent
                .source
                .line_col((include.start.saturating_sub(parent.base)) as usize);
            stack.push(format!(
                "in {uri} included at {}:{line}:{col}",
                parent.source.path().display()
            ));
            at = parent.included_at.as_ref();
            if stack.len() > MAX_INCLUDE_DEPTH + 1 {
                break;
            }
        }
        Some(SourceLocation {
            file: file.source.path().display().to_string(),
            line,
            column,
            end_line,
            end_column,
            stack,
        })
    }

    /// Where an edit anchored at `span` (shared span space) goes: the file holding it and the span there.
    pub fn edit_target(&self, span: Span) -> Option<crate::input::xacro::EditTarget<'_>> {
        let (file, start) = self.file_at(span.start)?;
        let end = span.end.checked_sub(file.base)? as usize;
        Some(crate::input::xacro::EditTarget::in_file(
            &file.source,
            Span::from_range(start..end.max(start)),
        ))
    }

    /// The files as (path as findings name it, text), entry file first.
    pub fn source_texts(&self) -> Vec<(String, &str)> {
        self.files
            .iter()
            .map(|f| (f.source.path().display().to_string(), f.source.text()))
            .collect()
    }

    /// The files' texts, for snippets.
    pub fn into_sources(self) -> Vec<SourceText> {
        self.files.into_iter().map(|f| f.source).collect()
    }
}

fn shift(span: Span, base: u32) -> Span {
    Span {
        start: span.start.saturating_add(base),
        end: span.end.saturating_add(base),
    }
}

fn len32(text: &str) -> u32 {
    u32::try_from(text.len()).unwrap_or(u32::MAX)
}

fn parent_dir(path: &Path) -> &Path {
    path.parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// The path with symlinks and `..` resolved when it exists (for cycle detection).
fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sdf_root_is_found_after_the_prolog() {
        assert!(is_sdf(
            "<?xml version='1.0'?>\n<!-- c -->\n<sdf version='1.9'/>"
        ));
        assert!(is_sdf("<sdf>"));
        assert!(!is_sdf("<robot name='r'/>"));
        assert!(!is_sdf("<sdfx/>"));
        assert!(!is_sdf("<?xml"));
    }

    #[test]
    fn mjcf_root_is_found_after_the_prolog() {
        assert!(is_mjcf(
            "<?xml version='1.0'?>\n<!-- c -->\n<mujoco model='m'>"
        ));
        assert!(is_mjcf("<mujoco/>"));
        assert!(!is_mjcf("<mujocox/>"));
        assert!(!is_mjcf("<robot name='r'/>"));
        assert!(!is_sdf("<mujoco/>"));
    }
}
