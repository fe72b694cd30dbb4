//! Paths and positions as the machine formats write them.

use std::path::{Component, Path, PathBuf};

use crate::report::FindingReport;

/// A path made relative to `base` when it lies below it (or already is relative), else absolute.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum DisplayPath {
    /// Relative to the base directory, `/`-separated, without `./`.
    Relative(String),
    /// Absolute, `/`-separated.
    Absolute(String),
}

impl DisplayPath {
    /// `file` relative to `base` when possible.
    pub(crate) fn new(file: &str, base: Option<&Path>) -> Self {
        let path = normalize(Path::new(file));
        let Some(base) = base.filter(|b| b.is_absolute()).map(normalize) else {
            return if path.is_relative() {
                DisplayPath::Relative(slashes(&path))
            } else {
                DisplayPath::Absolute(slashes(&path))
            };
        };
        // A relative path is relative to the base (the working directory); one leaving it is absolute.
        let path = normalize(&base.join(path));
        match path.strip_prefix(&base) {
            Ok(rest) if !rest.as_os_str().is_empty() => DisplayPath::Relative(slashes(rest)),
            _ => DisplayPath::Absolute(slashes(&path)),
        }
    }

    /// The path as text (relative or absolute).
    pub(crate) fn as_str(&self) -> &str {
        match self {
            DisplayPath::Relative(p) | DisplayPath::Absolute(p) => p,
        }
    }
}

/// `a/./b/../c` → `a/c` (lexically; a leading `..` is kept).
fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for component in path.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                let last = out.components().next_back();
                match last {
                    Some(Component::Normal(_)) => {
                        out.pop();
                    }
                    Some(Component::RootDir | Component::Prefix(_)) => {}
                    _ => out.push(".."),
                }
            }
            other => out.push(other.as_os_str()),
        }
    }
    out
}

fn slashes(path: &Path) -> String {
    path.to_string_lossy().replace('\\', "/")
}

/// Percent-encodes a `/`-separated path for a URI: everything but unreserved characters and `/`.
pub(crate) fn uri_path(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    for byte in path.bytes() {
        match byte {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'.' | b'_' | b'~' | b'/' => {
                out.push(char::from(byte))
            }
            _ => out.push_str(&format!("%{byte:02X}")),
        }
    }
    out
}

/// `file:///abs/path` for an absolute `/`-separated path (`C:/x` → `file:///C:/x`).
pub(crate) fn file_uri(absolute: &str) -> String {
    let path = uri_path(absolute);
    if path.starts_with('/') {
        format!("file://{path}")
    } else {
        // A Windows drive letter: keep its colon.
        format!("file:///{}", path.replacen("%3A", ":", 1))
    }
}

/// Where a finding points: its own place, else the validated file.
pub(crate) struct Place<'a> {
    /// The file.
    pub file: &'a str,
    /// 1-based line, column, end line, end column (end column just past the text).
    pub region: Option<(u32, u32, u32, u32)>,
}

impl<'a> Place<'a> {
    /// The place of `finding`, falling back to `validated` (the report's `urdf_path`).
    pub(crate) fn of(finding: &'a FindingReport, validated: &'a str) -> Self {
        match (&finding.file, finding.line) {
            (Some(file), Some(line)) => {
                let line = line.max(1);
                let column = finding.column.unwrap_or(1).max(1);
                let end_line = finding.end_line.unwrap_or(line).max(line);
                let end_column = match finding.end_column {
                    Some(end) if end_line > line || end > column => end,
                    _ => column,
                };
                Place {
                    file,
                    region: Some((line, column, end_line, end_column)),
                }
            }
            (Some(file), None) => Place { file, region: None },
            (None, _) => Place {
                file: validated,
                region: None,
            },
        }
    }

    /// `file:line:col`, or `file` without a position.
    pub(crate) fn label(&self, base: Option<&Path>) -> String {
        let file = DisplayPath::new(self.file, base);
        match self.region {
            Some((line, column, ..)) => format!("{}:{line}:{column}", file.as_str()),
            None => file.as_str().to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_below_the_base_become_relative() {
        let base = Path::new("/work/repo");
        assert_eq!(
            DisplayPath::new("/work/repo/urdf/r.urdf", Some(base)),
            DisplayPath::Relative("urdf/r.urdf".into())
        );
        assert_eq!(
            DisplayPath::new("/work/other/r.urdf", Some(base)),
            DisplayPath::Absolute("/work/other/r.urdf".into())
        );
        assert_eq!(
            DisplayPath::new("./urdf/../r.urdf", Some(base)),
            DisplayPath::Relative("r.urdf".into())
        );
        assert_eq!(
            DisplayPath::new("../r.urdf", None),
            DisplayPath::Relative("../r.urdf".into())
        );
        assert_eq!(
            DisplayPath::new("../r.urdf", Some(base)),
            DisplayPath::Absolute("/work/r.urdf".into())
        );
        assert_eq!(
            DisplayPath::new("/work/repo/../repo/x.urdf", Some(Path::new("/work/repo/"))),
            DisplayPath::Relative("x.urdf".into())
        );
    }

    #[test]
    fn uris_are_percent_encoded() {
        assert_eq!(uri_path("my robot/a#b.urdf"), "my%20robot/a%23b.urdf");
        assert_eq!(file_uri("/a b/c.urdf"), "file:///a%20b/c.urdf");
        assert_eq!(file_uri("C:/r.urdf"), "file:///C:/r.urdf");
        assert_eq!(uri_path("ü"), "%C3%BC");
    }
}
