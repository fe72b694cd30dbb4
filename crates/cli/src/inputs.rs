//! Command-line inputs → the list of files to validate.

use std::path::{Path, PathBuf};

/// Deepest directory level searched below a directory input.
const MAX_DEPTH: usize = 32;

/// Files named directly are kept as given; directories contribute every `*.urdf` below them, sorted.
/// Inputs that do not exist come back as error lines.
pub fn expand(inputs: &[PathBuf]) -> (Vec<PathBuf>, Vec<String>) {
    let mut files = Vec::new();
    let mut errors = Vec::new();
    for input in inputs {
        if input.is_dir() {
            let before = files.len();
            collect_urdfs(input, 0, &mut files);
            files[before..].sort();
            if files.len() == before {
                errors.push(format!(
                    "{}: directory holds no *.urdf file",
                    input.display()
                ));
            }
        } else if input.exists() {
            files.push(input.clone());
        } else {
            errors.push(format!(
                "{}: no such file or directory (expected a URDF file or a directory)",
                input.display()
            ));
        }
    }
    (files, errors)
}

fn collect_urdfs(dir: &Path, depth: usize, files: &mut Vec<PathBuf>) {
    if depth > MAX_DEPTH {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        if kind.is_dir() {
            collect_urdfs(&path, depth + 1, files);
        } else if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("urdf"))
        {
            files.push(path);
        }
    }
}
