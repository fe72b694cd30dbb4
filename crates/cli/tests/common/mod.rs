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
