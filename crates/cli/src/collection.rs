//! The collection page of a batch: when a directory (or several files) is validated with `--format html`,
//! `index.html`, `index.json` and `index.md` are written beside the reports — every robot with its verdict
//! and a link to its own HTML report (see `urdf_validator::render::collection`).

use std::path::{Component, Path, PathBuf};

use urdf_validator::render::{
    render_collection_html, render_collection_json, render_collection_markdown, Collection,
};
use urdf_validator::Validation;

use crate::outputs::{self, Outcome};

/// The collection's file names, in the folder [`index_dir`] picks.
pub const FILES: [&str; 3] = ["index.html", "index.json", "index.md"];

/// Where the collection page goes: `--output-dir`, else the one folder validated, else the deepest folder
/// holding every HTML report.
pub fn index_dir(
    output_dir: Option<&Path>,
    inputs: &[PathBuf],
    outcomes: &[Outcome],
) -> Option<PathBuf> {
    if let Some(dir) = output_dir {
        return Some(dir.to_path_buf());
    }
    if let [only] = inputs {
        if only.is_dir() {
            return Some(only.clone());
        }
    }
    let mut folders = outcomes
        .iter()
        .filter_map(html_report)
        .filter_map(|report| absolute(&report)?.parent().map(Path::to_path_buf));
    let first = folders.next()?;
    Some(folders.fold(first, |common, folder| common_ancestor(&common, &folder)))
}

/// Write the collection page of `outcomes` (and of the inputs that could not be read, `input_errors`) into
/// `dir`; the paths written, or the first error.
pub fn write(
    dir: &Path,
    outcomes: &[Outcome],
    input_errors: &[String],
) -> Result<Vec<PathBuf>, String> {
    let dir_abs = absolute(dir).unwrap_or_else(|| dir.to_path_buf());
    let root = files_root(outcomes);
    let mut collection = Collection::new();
    collection.root = root.as_ref().map(|r| r.display().to_string());
    for outcome in outcomes {
        let file = display(&outcome.file, root.as_deref());
        match &outcome.validation {
            Ok(validation) => {
                let link = html_report(outcome)
                    .and_then(|report| absolute(&report))
                    .map(|report| relative(&dir_abs, &report).display().to_string());
                collection.push_validation(
                    validation,
                    file,
                    link,
                    Some(outcome.elapsed.as_secs_f64() * 1e3),
                );
            }
            Err(error) => collection.push_error(file, error.to_string()),
        }
    }
    for error in input_errors {
        collection.push_error(String::new(), error.clone());
    }
    let reports: Vec<_> = outcomes
        .iter()
        .filter_map(|o| o.validation.as_ref().ok())
        .map(|v: &Validation| &v.report)
        .collect();
    collection.finish(&reports);
    let documents = [
        render_collection_html(&collection),
        render_collection_json(&collection),
        render_collection_markdown(&collection),
    ];
    let mut written = Vec::new();
    for (name, text) in FILES.iter().zip(&documents) {
        let path = dir.join(name);
        outputs::write_file(&path, text)
            .map_err(|error| format!("{}: cannot write: {error}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}

/// The HTML report written for `outcome`.
fn html_report(outcome: &Outcome) -> Option<PathBuf> {
    outcome
        .also_written
        .iter()
        .find(|path| path.ends_with(".html"))
        .map(PathBuf::from)
}

/// The folder the page's file paths are relative to: the working directory when it holds every input,
/// else the deepest folder that does (`None`: no common folder but `/`).
fn files_root(outcomes: &[Outcome]) -> Option<PathBuf> {
    let mut folders = outcomes
        .iter()
        .filter_map(|o| absolute(&o.file)?.parent().map(Path::to_path_buf));
    let first = folders.next()?;
    let common = folders.fold(first, |common, folder| common_ancestor(&common, &folder));
    let cwd = std::env::current_dir().ok().and_then(|cwd| absolute(&cwd));
    match cwd {
        Some(cwd) if common.starts_with(&cwd) => Some(cwd),
        _ if common.parent().is_some() => Some(common),
        _ => None,
    }
}

/// `path` relative to `root` when it is inside it, else as given.
fn display(path: &Path, root: Option<&Path>) -> String {
    let shown = absolute(path)
        .zip(root)
        .and_then(|(abs, root)| abs.strip_prefix(root).ok().map(Path::to_path_buf))
        .unwrap_or_else(|| path.to_path_buf());
    shown.display().to_string()
}

/// `path` made absolute against the working directory, `.` and `..` resolved lexically.
fn absolute(path: &Path) -> Option<PathBuf> {
    let joined = std::path::absolute(path).ok()?;
    let mut out = PathBuf::new();
    for component in joined.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    Some(out)
}

fn common_ancestor(a: &Path, b: &Path) -> PathBuf {
    a.components()
        .zip(b.components())
        .take_while(|(x, y)| x == y)
        .map(|(x, _)| x)
        .collect()
}

/// The path from folder `from` to `to` (both absolute): `../` for each folder of `from` below their
/// common ancestor, then the rest of `to`.
fn relative(from: &Path, to: &Path) -> PathBuf {
    let common = common_ancestor(from, to);
    let ups = from.components().count() - common.components().count();
    let mut out: PathBuf = std::iter::repeat_n(Component::ParentDir, ups).collect();
    out.extend(to.components().skip(common.components().count()));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_are_relative_to_the_page() {
        assert_eq!(
            relative(Path::new("/a/out"), Path::new("/a/out/r_validation.html")),
            PathBuf::from("r_validation.html")
        );
        assert_eq!(
            relative(Path::new("/a/out"), Path::new("/a/robots/x/r.html")),
            PathBuf::from("../robots/x/r.html")
        );
        assert_eq!(
            common_ancestor(Path::new("/a/b/c"), Path::new("/a/b/d/e")),
            PathBuf::from("/a/b")
        );
        assert_eq!(
            absolute(Path::new("/a/b/../c/./d")),
            Some(PathBuf::from("/a/c/d"))
        );
    }
}
