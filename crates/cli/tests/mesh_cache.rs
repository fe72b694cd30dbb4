//! The on-disk mesh cache: a second run reads the hulls kept by the first and gives the same report as a
//! run without the cache; damaged entries are ignored; `--no-cache` neither reads nor writes it.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::{Path, PathBuf};
use std::process::Command;

/// `../shared/robots`; `None` (with a message) when absent outside CI.
fn shared_robots() -> Option<PathBuf> {
    const VAR: &str = "URDF_VALIDATOR_SHARED_ROBOTS";
    let dir = std::env::var_os(VAR)
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/robots"));
    if dir.is_dir() {
        return Some(dir);
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "../shared/robots is absent under CI ({} not found; set {VAR})",
        dir.display()
    );
    eprintln!(
        "skipping: ../shared/robots is absent ({} not found; set {VAR})",
        dir.display()
    );
    None
}

/// The JSON report of `urdf` (timestamp removed) with the mesh cache in `cache`.
fn report(urdf: &Path, cache: &Path, extra: &[&str]) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .arg(urdf)
        .args(["--no-write", "--format", "json"])
        .args(extra)
        .env("URDF_VALIDATOR_CACHE_DIR", cache)
        .output()
        .expect("runs");
    let text = String::from_utf8(output.stdout).expect("UTF-8");
    text.lines()
        .filter(|line| !line.trim_start().starts_with("\"timestamp\""))
        .collect::<Vec<_>>()
        .join("\n")
}

fn entries(cache: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(cache)
        .map(|dir| dir.flatten().map(|e| e.path()).collect())
        .unwrap_or_default()
}

#[test]
fn cached_meshes_give_the_same_report() {
    let Some(robots) = shared_robots() else {
        return;
    };
    // Fetch: COLLADA and STL meshes found through package://.
    let urdf = robots.join("fetch/fetch_description/robots/fetch.urdf");
    let cache =
        std::env::temp_dir().join(format!("urdf_validate_mesh_cache_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&cache);

    let uncached = report(&urdf, &cache, &["--no-cache"]);
    assert!(uncached.contains("\"overall_status\""), "{uncached}");
    assert!(entries(&cache).is_empty(), "--no-cache writes nothing");

    let first = report(&urdf, &cache, &[]);
    let kept = entries(&cache);
    assert!(
        kept.len() >= 10,
        "one entry per mesh file, got {}",
        kept.len()
    );
    let second = report(&urdf, &cache, &[]);
    assert_eq!(first, uncached);
    assert_eq!(second, uncached, "the report from cached hulls");

    for entry in &kept {
        std::fs::write(entry, b"UVMESH01 damaged").unwrap();
    }
    assert_eq!(
        report(&urdf, &cache, &[]),
        uncached,
        "damaged entries are misses"
    );
    let _ = std::fs::remove_dir_all(&cache);
}
