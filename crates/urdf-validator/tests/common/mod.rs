//! Test data locations shared by the integration tests.
//!
//! Outside CI a missing data set skips its tests with a message; under `CI=true` a missing data set fails,
//! so no check is quietly skipped there.

#![allow(dead_code)] // Each test binary uses a different subset.

use std::path::{Path, PathBuf};

/// The repository root.
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A data set directory, from `var` or `default`; `None` (with a message) when absent outside CI.
pub fn data_dir(var: &str, default: Option<PathBuf>, what: &str) -> Option<PathBuf> {
    let dir = std::env::var_os(var).map(PathBuf::from).or(default);
    match dir {
        Some(dir) if dir.is_dir() => Some(dir),
        _ if std::env::var_os("CI").is_some() => {
            panic!(
                "{what} is absent under CI (set {var}, or run scripts/test.sh which installs it)"
            )
        }
        _ => {
            eprintln!("skipping: {what} is absent (set {var}, or run scripts/test.sh)");
            None
        }
    }
}

/// `../shared/robots`.
pub fn shared_robots() -> Option<PathBuf> {
    data_dir(
        "URDF_VALIDATOR_SHARED_ROBOTS",
        Some(repo_root().join("../shared/robots")),
        "../shared/robots",
    )
}

/// example-robot-data's robots folder inside the test venv.
pub fn corpus() -> Option<PathBuf> {
    let default = std::fs::read_dir(repo_root().join(".venv/lib"))
        .ok()
        .and_then(|entries| {
            entries
                .flatten()
                .map(|e| {
                    e.path()
                        .join("site-packages/cmeel.prefix/share/example-robot-data/robots")
                })
                .find(|p| p.is_dir())
        });
    data_dir(
        "URDF_VALIDATOR_CORPUS",
        default,
        "the example-robot-data corpus",
    )
}

/// PyBullet's `pybullet_data` folder inside the test venv (PyPI `pybullet`, `scripts/setup-test-env.sh`).
pub fn pybullet_data() -> Option<PathBuf> {
    let default = std::fs::read_dir(repo_root().join(".venv/lib"))
        .ok()
        .and_then(|entries| {
            entries
                .flatten()
                .map(|e| e.path().join("site-packages/pybullet_data"))
                .find(|p| p.is_dir())
        });
    data_dir(
        "URDF_VALIDATOR_PYBULLET_DATA",
        default,
        "PyBullet's pybullet_data",
    )
}

/// Every `*.urdf` below `dir`, sorted.
pub fn urdfs_below(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "urdf") {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

/// The venv's Python when it can import MuJoCo; `None` (skip) outside CI, a failure under CI.
pub fn mujoco_python() -> Option<PathBuf> {
    let python = std::env::var_os("URDF_VALIDATOR_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo_root().join(".venv/bin/python"));
    let works = std::process::Command::new(&python)
        .args(["-c", "import mujoco"])
        .output()
        .is_ok_and(|o| o.status.success());
    if works {
        return Some(python);
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "MuJoCo is not importable by {} under CI (run scripts/setup-test-env.sh, which installs it)",
        python.display()
    );
    eprintln!(
        "skipping: MuJoCo is not importable by {} (run scripts/test.sh)",
        python.display()
    );
    None
}

/// A scratch folder of a test, removed when dropped.
pub struct Scratch(pub PathBuf);

impl Scratch {
    /// A fresh folder for test `name` of this process.
    pub fn new(name: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("urdf-validator-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
        Scratch(dir)
    }

    /// `text` written to `name` (folders made as needed) in the scratch folder.
    pub fn file(&self, name: &str, text: &str) -> PathBuf {
        let path = self.0.join(name);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).unwrap_or_else(|e| panic!("{}: {e}", parent.display()));
        }
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        path
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
