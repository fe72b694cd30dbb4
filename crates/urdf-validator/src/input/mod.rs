//! The load stage: a file's text with the size limit applied, xacro expansion, `package://` resolution,
//! SRDF files and meshes. Nothing here knows what a robot is; it hands text and geometry to the stages after it.

pub mod mesh;
pub mod resolve;
pub mod source;
pub mod srdf;
pub mod xacro;

use std::path::{Path, PathBuf};

/// Largest input accepted (bounded memory on untrusted input).
pub const MAX_FILE_BYTES: u64 = 128 * 1024 * 1024;

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
    },
    /// The options do not fit this robot (an unknown joint or link name, an unreadable SRDF).
    #[error("{}: {message}", path.display())]
    Usage {
        /// The file.
        path: PathBuf,
        /// What is wrong, with suggestions.
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
