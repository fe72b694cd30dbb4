//! Test data locations shared by the CLI's integration tests.

#![allow(dead_code)] // Each test binary uses a different subset.
#![allow(clippy::expect_used)] // a test may panic on what it did not expect

use std::path::{Path, PathBuf};

/// The repository root, canonical so the paths the binary prints can be found and redacted.
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("repository root")
}

/// `../shared/robots`, canonical; `None` (with a message) when absent outside CI.
pub fn shared_robots() -> Option<PathBuf> {
    const VAR: &str = "URDF_VALIDATOR_SHARED_ROBOTS";
    let dir = std::env::var_os(VAR)
        .map(PathBuf::from)
        .unwrap_or_else(|| repo_root().join("../shared/robots"));
    match dir.canonicalize() {
        Ok(dir) if dir.is_dir() => Some(dir),
        _ if std::env::var_os("CI").is_some() => panic!(
            "../shared/robots is absent under CI ({} not found; set {VAR}, or run scripts/test.sh)",
            dir.display()
        ),
        _ => {
            eprintln!(
                "skipping: ../shared/robots is absent ({} not found; set {VAR}, or run scripts/test.sh)",
                dir.display()
            );
            None
        }
    }
}

/// example-robot-data's robots folder (`$URDF_VALIDATOR_CORPUS`, else inside the test venv); `None` (with
/// a message) when absent outside CI.
pub fn corpus() -> Option<PathBuf> {
    const VAR: &str = "URDF_VALIDATOR_CORPUS";
    let dir = std::env::var_os(VAR).map(PathBuf::from).or_else(|| {
        std::fs::read_dir(repo_root().join(".venv/lib"))
            .ok()?
            .flatten()
            .map(|e| {
                e.path()
                    .join("site-packages/cmeel.prefix/share/example-robot-data/robots")
            })
            .find(|p| p.is_dir())
    });
    match dir {
        Some(dir) if dir.is_dir() => Some(dir),
        _ if std::env::var_os("CI").is_some() => {
            panic!("the example-robot-data corpus is absent under CI (set {VAR}, or run scripts/test.sh)")
        }
        _ => {
            eprintln!("skipping: the example-robot-data corpus is absent (set {VAR}, or run scripts/test.sh)");
            None
        }
    }
}

/// The first of `names` on PATH (or `$var`); `None` (with a message) when absent outside CI, a panic
/// under CI.
pub fn on_path(names: &[&str], var: &str) -> Option<PathBuf> {
    let found = std::env::var_os(var).map(PathBuf::from).or_else(|| {
        let path = std::env::var_os("PATH")?;
        std::env::split_paths(&path)
            .flat_map(|dir| names.iter().map(move |n| dir.join(n)))
            .find(|p| p.is_file())
    });
    match found {
        Some(p) => Some(p),
        None if std::env::var_os("CI").is_some() => {
            panic!("{} is absent under CI (install it, or set {var})", names[0])
        }
        None => {
            eprintln!("skipping: no {} on PATH (or set {var})", names[0]);
            None
        }
    }
}

/// Chromium and Node for the browser tests (`view_browser/cdp.mjs` drives Chromium from Node).
pub fn browser_tools() -> Option<(PathBuf, PathBuf)> {
    let chromium = on_path(
        &["chromium", "chromium-browser", "google-chrome"],
        "URDF_VALIDATOR_CHROMIUM",
    )?;
    let node = on_path(&["node"], "URDF_VALIDATOR_NODE")?;
    Some((chromium, node))
}

/// Copy the folder `from` to `to`, leaving out reports (`*_validation.json`) a run may have left there.
pub fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("create dir");
    for entry in std::fs::read_dir(from).expect("read dir").flatten() {
        let target = to.join(entry.file_name());
        if entry.path().is_dir() {
            copy_dir(&entry.path(), &target);
        } else if !entry
            .file_name()
            .to_string_lossy()
            .ends_with("_validation.json")
        {
            std::fs::copy(entry.path(), &target).expect("copy");
        }
    }
}
