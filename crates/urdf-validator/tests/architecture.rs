//! The library's pipeline flows one way: a stage imports only the stages before it. Read from the
//! sources (`use crate::…` and `crate::…` paths outside comments and `#[cfg(test)]` modules), so a
//! back-import fails here with the file that made it.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The stages in pipeline order; a module may import its own stage's modules and earlier ones.
const STAGES: &[&[&str]] = &[
    // What every stage reports with, and leaf utilities.
    &["diagnostics", "rng", "timings"],
    // The load stage: files, packages, meshes, the sandbox.
    &["input"],
    // Readers: the typed robot and the formats read into it.
    &["urdf", "mjcf", "sdf"],
    // The kinematic model.
    &["model"],
    // Shapes and masses of the assets, for the analyses.
    &["assets"],
    &["analysis"],
    &["checks"],
    &["report"],
    // Front ends inside the library: renderers and the task query (which calls `validate`).
    &["render", "task_query"],
];

fn stage_of(module: &str) -> Option<usize> {
    STAGES.iter().position(|stage| stage.contains(&module))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The crate modules `text` refers to through `crate::NAME`, outside comments and test modules.
fn imported_modules(text: &str) -> BTreeSet<String> {
    let code = text.split("#[cfg(test)]").next().unwrap_or("");
    let mut found = BTreeSet::new();
    for line in code.lines() {
        let line = line.trim_start();
        if line.starts_with("//") {
            continue;
        }
        let mut rest = line;
        while let Some(at) = rest.find("crate::") {
            rest = &rest[at + "crate::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                found.insert(name);
            }
        }
    }
    found
}

#[test]
fn no_stage_imports_a_later_one() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut back_imports = Vec::new();
    for file in &files {
        let relative = file.strip_prefix(&src).unwrap();
        let top = relative.components().next().unwrap().as_os_str();
        let module = top.to_string_lossy().trim_end_matches(".rs").to_string();
        if module == "lib" {
            continue; // the conductor: it calls every stage
        }
        let stage = stage_of(&module)
            .unwrap_or_else(|| panic!("module '{module}' is in no stage of STAGES"));
        let text = std::fs::read_to_string(file).unwrap();
        for imported in imported_modules(&text) {
            if imported == module {
                continue;
            }
            let allowed = match stage_of(&imported) {
                Some(other) => other <= stage,
                // The crate root's items (`validate`, `Options`) only for the front ends.
                None => stage + 1 == STAGES.len(),
            };
            if !allowed {
                back_imports.push(format!("{} imports crate::{imported}", relative.display()));
            }
        }
    }
    assert!(
        back_imports.is_empty(),
        "imports against the pipeline's order: {back_imports:#?}"
    );
}

#[test]
fn the_import_reader_sees_paths_and_skips_comments_and_tests() {
    let text = "use crate::model::Model;\n// crate::report is a comment\nlet g = crate::urdf::robot::STANDARD_GRAVITY;\n#[cfg(test)]\nmod tests { use crate::render; }\n";
    let found: Vec<String> = imported_modules(text).into_iter().collect();
    assert_eq!(found, ["model", "urdf"]);
}

/// What reads the disk or the environment: only the load stage (`input/`) may, so that every later stage
/// is a function of what was loaded (an editor's unsaved text validates as the file would).
const DISK_OR_ENVIRONMENT: &[&str] = &[
    "std::fs",
    "fs::read",
    "File::open",
    "File::create",
    "env::var",
    "env::current_dir",
    "read_dir(",
    "metadata(",
    ".exists()",
    ".is_file()",
    ".is_dir()",
    "canonicalize(",
];

/// The files of later stages that still touch the disk, and why: known departures, each to move into the
/// load stage, not a list to add to.
const DISK_EXCEPTIONS: &[(&str, &str)] = &[
    (
        "analysis/deep/bridge.rs",
        "the MuJoCo pass runs MuJoCo in a process of its own, handing it files in a scratch folder",
    ),
    (
        "report/baseline.rs",
        "--baseline: loaded by the front ends (Baseline::load); entries name files by canonical path",
    ),
];

#[test]
fn only_the_load_stage_touches_disk_or_environment() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut touching = Vec::new();
    for file in &files {
        let relative = file
            .strip_prefix(&src)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if relative.starts_with("input/")
            || DISK_EXCEPTIONS.iter().any(|(file, _)| relative == *file)
        {
            continue;
        }
        let text = std::fs::read_to_string(file).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        for (number, line) in code.lines().enumerate() {
            let trimmed = line.trim_start();
            if trimmed.starts_with("//") {
                continue;
            }
            for call in DISK_OR_ENVIRONMENT {
                if line.contains(call) {
                    touching.push(format!("{relative}:{}: {}", number + 1, trimmed));
                }
            }
        }
    }
    assert!(
        touching.is_empty(),
        "disk or environment outside input/: {touching:#?}"
    );
}
