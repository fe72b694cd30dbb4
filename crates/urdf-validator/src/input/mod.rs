//! The load stage: a file's text with the size limit applied, xacro expansion, SDFormat and MJCF includes,
//! `package://` and `model://` resolution, SRDF files and meshes. Nothing here knows what a robot is; it hands text and geometry to the stages after it.

pub mod interpreter;
pub mod mesh;
pub mod resolve;
pub mod sandbox;
pub mod source;
pub mod srdf;
pub mod unbound_prefixes;
pub mod xacro;
pub mod xml_files;

use std::path::{Path, PathBuf};

use crate::diagnostics::span::Span;
use source::SourceText;
use xacro::SourceLocation;

/// Largest input accepted (bounded memory on untrusted input).
pub const MAX_FILE_BYTES: u64 = 128 * 1024 * 1024;

/// Largest number of XML nodes accepted in a robot description (URDF or SDFormat).
pub(crate) const MAX_NODES: u32 = 5_000_000;

/// The XML options every robot description (URDF or SDFormat) is parsed with: DTDs allowed, at most
/// 5,000,000 nodes (bounded memory on untrusted input).
pub fn xml_options<'o>() -> roxmltree::ParsingOptions<'o> {
    roxmltree::ParsingOptions {
        allow_dtd: true,
        nodes_limit: MAX_NODES,
        ..roxmltree::ParsingOptions::default()
    }
}

/// Why a file could not be turned into a document at all (exit code 2, one line).
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file could not be read.
    #[error("{}: cannot read file: {error}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        error: std::io::Error,
    },
    /// The file is larger than [`MAX_FILE_BYTES`].
    #[error("{}: file is {bytes} bytes; the limit is {MAX_FILE_BYTES} bytes (expected a URDF document)", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size in bytes.
        bytes: u64,
    },
    /// The file is not UTF-8 text.
    #[error("{}: not UTF-8 text (expected a URDF XML document)", path.display())]
    NotUtf8 {
        /// The file.
        path: PathBuf,
    },
    /// A xacro source could not be expanded.
    #[error("{}", prefixed(path, message))]
    Xacro {
        /// The file.
        path: PathBuf,
        /// The expander's error: `file:line:col: message`, then the macro / include stack.
        message: String,
        /// Where the expander found the problem, when it knows.
        location: Option<::xacro::Location>,
    },
    /// The sandbox refused to read the file (`--untrusted`: outside the roots, not a regular file).
    #[error("{}: {message}", path.display())]
    Refused {
        /// The file.
        path: PathBuf,
        /// Why, as the sandbox says.
        message: String,
    },
    /// The text is not well-formed XML.
    #[error("{}:{line}:{column}: not well-formed XML: {message} (expected a URDF XML document)", path.display())]
    Xml {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: u32,
        /// 1-based column.
        column: u32,
        /// roxmltree's description.
        message: String,
    },
}

/// `message` with the file name in front, unless it already starts with it.
fn prefixed(path: &Path, message: &str) -> String {
    let name = path.display().to_string();
    if message.starts_with(&name) {
        message.to_string()
    } else {
        format!("{name}: {message}")
    }
}

/// Read a file's text with the size limit applied.
pub fn read_text(path: &Path) -> Result<String, LoadError> {
    let io = |error| LoadError::Io {
        path: path.to_path_buf(),
        error,
    };
    let bytes = std::fs::metadata(path).map_err(io)?.len();
    if bytes > MAX_FILE_BYTES {
        return Err(LoadError::TooLarge {
            path: path.to_path_buf(),
            bytes,
        });
    }
    let raw = std::fs::read(path).map_err(io)?;
    String::from_utf8(raw).map_err(|_| LoadError::NotUtf8 {
        path: path.to_path_buf(),
    })
}

/// A robot description read from disk: the URDF text (expanded first when the file is xacro) and how
/// positions in that text map to the files the user edits.
#[derive(Debug)]
pub struct Loaded {
    /// The file as given.
    pub path: PathBuf,
    origin: Origin,
}

/// Where the URDF text came from.
#[derive(Debug)]
enum Origin {
    /// The text is the file.
    Urdf(SourceText),
    /// The text was expanded from xacro sources.
    Xacro(xacro::Expanded),
    /// An SDFormat file (root element `<sdf>`) and the files it includes.
    Sdf(xml_files::XmlFiles),
    /// An MJCF file (root element `<mujoco>`) and the files it includes.
    Mjcf(xml_files::XmlFiles),
}

/// The description format of a loaded file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Format {
    /// URDF, possibly expanded from xacro.
    #[default]
    Urdf,
    /// SDFormat.
    Sdf,
    /// MJCF (MuJoCo's XML).
    Mjcf,
}

impl Loaded {
    /// Read `path` (expanding `.xacro` files with `xacro_args`, finding `$(find)` packages with `resolver`).
    pub fn read(
        path: &Path,
        xacro_args: &[(String, String)],
        resolver: &resolve::PackageResolver,
    ) -> Result<Loaded, LoadError> {
        if xacro::is_xacro(path) {
            let expanded = xacro::expand(path, xacro_args, resolver, false)?;
            return Ok(Loaded {
                path: path.to_path_buf(),
                origin: Origin::Xacro(expanded),
            });
        }
        Loaded::from_document(read_text(path)?, path, resolver)
    }

    /// `text` standing for the file at `path` (an editor's unsaved buffer): expanded with `xacro_args` when
    /// `path` is a xacro file, else a URDF or SDFormat document as [`Loaded::from_document`] reads it.
    pub fn from_unsaved(
        text: String,
        path: &Path,
        xacro_args: &[(String, String)],
        resolver: &resolve::PackageResolver,
    ) -> Result<Loaded, LoadError> {
        if xacro::is_xacro(path) {
            return Ok(Loaded {
                path: path.to_path_buf(),
                origin: Origin::Xacro(xacro::expand_text(&text, path, xacro_args, resolver)?),
            });
        }
        Loaded::from_document(text, path, resolver)
    }

    /// A URDF, SDFormat or MJCF document `text` read from `path` (SDFormat by its `<sdf>` root, MJCF by
    /// its `<mujoco>` root: their includes are read from `path`'s folder and through `resolver`).
    pub fn from_document(
        text: String,
        path: &Path,
        resolver: &resolve::PackageResolver,
    ) -> Result<Loaded, LoadError> {
        let syntax = if xml_files::is_sdf(&text) {
            xml_files::IncludeSyntax::Sdf
        } else if xml_files::is_mjcf(&text) {
            xml_files::IncludeSyntax::Mjcf
        } else {
            return Ok(Loaded::from_text(text, path));
        };
        let files = xml_files::XmlFiles::load(path, text, syntax, resolver)?;
        Ok(Loaded {
            path: path.to_path_buf(),
            origin: match syntax {
                xml_files::IncludeSyntax::Sdf => Origin::Sdf(files),
                xml_files::IncludeSyntax::Mjcf => Origin::Mjcf(files),
            },
        })
    }

    /// URDF, SDFormat or MJCF.
    pub fn format(&self) -> Format {
        match &self.origin {
            Origin::Urdf(_) | Origin::Xacro(_) => Format::Urdf,
            Origin::Sdf(_) => Format::Sdf,
            Origin::Mjcf(_) => Format::Mjcf,
        }
    }

    /// The SDFormat files, when the input is SDFormat.
    pub fn sdf(&self) -> Option<&xml_files::XmlFiles> {
        match &self.origin {
            Origin::Sdf(files) => Some(files),
            _ => None,
        }
    }

    /// The MJCF files, when the input is MJCF.
    pub fn mjcf(&self) -> Option<&xml_files::XmlFiles> {
        match &self.origin {
            Origin::Mjcf(files) => Some(files),
            _ => None,
        }
    }

    /// URDF `text` as read from `path` (used for positions, relative meshes and the report).
    pub fn from_text(text: String, path: &Path) -> Loaded {
        Loaded {
            path: path.to_path_buf(),
            origin: Origin::Urdf(SourceText::new(path, text)),
        }
    }

    /// The entry file's absolute path when the file on disk holds the text read (`None` for an unsaved
    /// buffer, or a file that cannot be read back): what a tool reading the file itself would see.
    pub fn saved_path(&self) -> Option<PathBuf> {
        let path = std::path::absolute(&self.path).ok()?;
        let saved = std::fs::read_to_string(&path).ok()?;
        (saved == self.text()).then_some(path)
    }

    /// The URDF text the parser reads (for SDFormat: the entry file's text).
    pub fn text(&self) -> &str {
        match &self.origin {
            Origin::Urdf(source) => source.text(),
            Origin::Xacro(expanded) => expanded.xml(),
            Origin::Sdf(files) | Origin::Mjcf(files) => files.text(0),
        }
    }

    /// The folder relative paths are resolved from (`.` for a bare file name).
    pub fn dir(&self) -> &Path {
        self.path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
    }

    /// Where `span` of the URDF text (or of the SDFormat files) is in the files the user edits (`None`
    /// when a xacro position cannot be traced back).
    pub fn locate(&self, span: Span) -> Option<SourceLocation> {
        match &self.origin {
            Origin::Urdf(source) => {
                let start = source.location(span);
                let (end_line, end_column) = source.line_col(span.end as usize);
                Some(SourceLocation {
                    file: start.file,
                    line: start.line,
                    column: start.column,
                    end_line,
                    end_column,
                    stack: Vec::new(),
                })
            }
            Origin::Xacro(expanded) => expanded.locate(span),
            Origin::Sdf(files) | Origin::Mjcf(files) => files.locate(span),
        }
    }

    /// Where an edit anchored at `span` of the parsed text goes: the file the user edits, its text and the
    /// span in it. A `textual` edit (a deletion) goes only into the file the parser read itself; an MJCF
    /// file only takes edits written for `mjcf`. Otherwise why the edit cannot be made in a file (a xacro
    /// value computed from an expression; SDFormat; a URDF fix on an MJCF model).
    pub fn edit_target(
        &self,
        span: Span,
        textual: bool,
        mjcf: bool,
    ) -> Result<xacro::EditTarget<'_>, String> {
        match &self.origin {
            Origin::Urdf(source) => Ok(xacro::EditTarget::in_file(source, span)),
            Origin::Xacro(_) if textual => {
                Err("the text was produced by the xacro expansion: edit the xacro source".into())
            }
            Origin::Xacro(expanded) => expanded.literal_source(span),
            Origin::Sdf(_) => Err("fixes are not written into SDFormat files".into()),
            Origin::Mjcf(files) if mjcf => files
                .edit_target(span)
                .ok_or_else(|| "the edit's place is in none of the model's files".into()),
            Origin::Mjcf(_) => {
                Err("this fix is written for URDF: edit the MJCF file by hand".into())
            }
        }
    }

    /// The xacro expander's warnings, located in the xacro sources (none for a URDF).
    pub fn warnings(&self) -> Vec<xacro::Warning> {
        match &self.origin {
            Origin::Urdf(_) | Origin::Sdf(_) | Origin::Mjcf(_) => Vec::new(),
            Origin::Xacro(expanded) => expanded.warnings(),
        }
    }

    /// The files the user edits, as (path as findings name it, text): the URDF, or the xacro sources
    /// (entry file first).
    pub fn source_texts(&self) -> Vec<(String, &str)> {
        match &self.origin {
            Origin::Urdf(source) => vec![(source.path().display().to_string(), source.text())],
            Origin::Xacro(expanded) => expanded.source_texts(),
            Origin::Sdf(files) | Origin::Mjcf(files) => files.source_texts(),
        }
    }

    /// The source texts findings point into (for snippets).
    pub fn into_sources(self) -> Vec<SourceText> {
        match self.origin {
            Origin::Urdf(source) => vec![source],
            Origin::Xacro(expanded) => expanded.sources(),
            Origin::Sdf(files) | Origin::Mjcf(files) => files.into_sources(),
        }
    }
}
