//! The README's "Three commands" run as written: each `$ urdf_validate` line of that block, in a scratch copy
//! of the repository's example robots (so `robots/` and `examples/robots/...` both exist), exits 0 and
//! writes what it says it writes.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The commands of the README's console block under `## Three commands` (its `$ ` lines), comments dropped;
/// `tests/book_examples.rs` also compares their output with the lines after each.
fn readme_commands() -> Vec<Vec<String>> {
    let readme = std::fs::read_to_string(repo_root().join("README.md")).expect("README.md");
    let section = readme
        .split("\n## Three commands\n")
        .nth(1)
        .expect("a '## Three commands' section");
    let block = section
        .split("```console\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("a console block in it");
    block
        .lines()
        .filter_map(|line| line.strip_prefix("$ "))
        .map(|line| line.split('#').next().unwrap_or_default().trim())
        .filter(|line| !line.is_empty())
        .map(|line| line.split_whitespace().map(str::to_string).collect())
        .collect()
}

#[test]
fn the_readme_three_commands_run_as_written() {
    let commands = readme_commands();
    assert_eq!(commands.len(), 3, "{commands:?}");
    let scratch =
        std::env::temp_dir().join(format!("urdf-validator-readme-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&scratch);
    let examples = repo_root().join("examples/robots");
    common::copy_dir(&examples, &scratch.join("examples/robots"));
    common::copy_dir(&examples, &scratch.join("robots"));
    for command in &commands {
        assert_eq!(command[0], "urdf_validate", "{command:?}");
        let output = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
            .args(&command[1..])
            .current_dir(&scratch)
            .env(
                "URDF_VALIDATOR_CACHE_DIR",
                std::env::var_os("URDF_VALIDATOR_CACHE_DIR")
                    .unwrap_or_else(|| scratch.join("cache").into_os_string()),
            )
            .env("NO_COLOR", "1")
            .output()
            .expect("run urdf_validate");
        assert_eq!(
            output.status.code(),
            Some(0),
            "{command:?}\nstdout:\n{}\nstderr:\n{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        );
    }
    assert!(scratch
        .join("examples/robots/mobile_manipulator_validation.json")
        .exists());
    assert!(scratch.join("results.sarif").exists());
    let _ = std::fs::remove_dir_all(&scratch);
}
