//! `.xacro` input: expansion with the native expander (the `xacro` crate: no Python, no code execution),
//! and every position in the expanded URDF mapped back to the xacro source line that wrote it, with the
//! macro calls and includes that produced it.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::parse::LoadError;
use crate::resolve::PackageResolver;
use crate::source::{SourceText, Span};

/// True for `*.xacro` files.
pub fn is_xacro(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xacro"))
}

/// An expanded xacro file.
#[derive(Debug)]
pub struct Expanded {
    expansion: xacro::Expansion,
}

/// Where a finding is, in the sources the user edits.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceLocation {
    /// The file.
    pub file: String,
    /// 1-based line of the start.
    pub line: u32,
    /// 1-based column of the start.
    pub column: u32,
    /// 1-based line of the end.
    pub end_line: u32,
    /// 1-based column just past the end.
    pub end_column: u32,
    /// The macro calls and includes that produced it, innermost first
    /// (`in macro 'wheel' called at robot.urdf.xacro:40:3`).
    pub stack: Vec<String>,
}

/// Expand the xacro file at `path` with `args` (`name:=value`), finding `$(find pkg)` packages with
/// `resolver` (as `package://` URIs are found).
pub fn expand(
    path: &Path,
    args: &[(String, String)],
    resolver: &PackageResolver,
) -> Result<Expanded, LoadError> {
    let start_dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_path_buf();
    let finder = resolver.clone();
    let options = xacro::Options {
        args: args.to_vec(),
        find_package: Some(Arc::new(move |package: &str| -> Option<PathBuf> {
            finder.find_package(package, &start_dir)
        })),
        ..xacro::Options::default()
    };
    let expansion = xacro::expand_file(path, &options).map_err(|error| LoadError::Xacro {
        path: path.to_path_buf(),
        message: error.to_string(),
    })?;
    Ok(Expanded { expansion })
}

impl Expanded {
    /// The expanded URDF.
    pub fn xml(&self) -> &str {
        &self.expansion.xml
    }

    /// The xacro sources read (entry file first), for snippets.
    pub fn sources(&self) -> Vec<SourceText> {
        self.expansion
            .sources
            .iter()
            .map(|s| SourceText::new(&s.path, s.text.clone()))
            .collect()
    }

    /// Warnings of the expansion, with where they are.
    pub fn warnings(&self) -> Vec<(String, Option<SourceLocation>)> {
        self.expansion
            .warnings
            .iter()
            .map(|w| {
                let location = w.location.as_ref().map(|l| SourceLocation {
                    file: l.path.display().to_string(),
                    line: to_u32(l.line),
                    column: to_u32(l.col),
                    end_line: to_u32(l.line),
                    end_column: to_u32(l.col),
                    stack: Vec::new(),
                });
                (w.message.clone(), location)
            })
            .collect()
    }

    /// The xacro source of a span of the expanded URDF: where the text at its start was written.
    pub fn locate(&self, span: Span) -> Option<SourceLocation> {
        let map = &self.expansion.map;
        let origin = map.origin(span.start as usize)?;
        let file = self.expansion.sources.get(origin.file)?;
        let (line, column) = file.line_col(origin.span.start);
        let (end_line, end_column) = file.line_col(origin.span.end);
        let stack = map
            .stack(origin)
            .filter_map(|frame| {
                let at = self.expansion.sources.get(frame.file)?;
                let (line, col) = at.line_col(frame.span.start);
                let place = format!("{}:{line}:{col}", at.path.display());
                Some(match frame.kind {
                    xacro::FrameKind::Macro => {
                        format!("in macro '{}' called at {place}", frame.name)
                    }
                    xacro::FrameKind::Include => {
                        format!("in {} included at {place}", frame.name)
                    }
                })
            })
            .collect();
        Some(SourceLocation {
            file: file.path.display().to_string(),
            line: to_u32(line),
            column: to_u32(column),
            end_line: to_u32(end_line),
            end_column: to_u32(end_column),
            stack,
        })
    }
}

fn to_u32(v: usize) -> u32 {
    u32::try_from(v).unwrap_or(u32::MAX)
}
