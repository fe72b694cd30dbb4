//! The crates every front end shares stay free of the front ends' machinery: neither the session crate
//! nor the Python module (whose wheel loads into every user's Python) links a command-line parser, an
//! async runtime or a protocol crate, or the command itself. Read from `cargo tree`, so a dependency
//! pulled in by another dependency counts too.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::collections::BTreeSet;
use std::process::Command;

/// What only the command, its MCP server and its language server may link.
const FRONT_END_ONLY: &[&str] = &[
    "urdf-validate-cli",
    "clap",
    "tokio",
    "rmcp",
    "lsp-server",
    "lsp-types",
    "crossbeam-channel",
    "indicatif",
    "anstream",
];

/// Every package `root` links (its normal dependencies, direct or not: not its dev-dependencies, which
/// the lock file would count too), from `cargo tree`.
fn linked(root: &str) -> BTreeSet<String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let output = Command::new(cargo)
        .args([
            "tree",
            "--offline",
            "-e",
            "normal",
            "--prefix",
            "none",
            "-f",
            "{p}",
            "-p",
            root,
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("cargo tree runs");
    assert!(
        output.status.success(),
        "cargo tree -p {root}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|line| line.split(' ').next())
        .map(str::to_string)
        .collect()
}

#[test]
fn shared_crates_link_no_front_end() {
    for root in [
        "urdf-validate-session",
        "urdf-validator-python",
        "urdf-validator",
    ] {
        let linked = linked(root);
        assert!(linked.len() > 3, "{root}: {linked:?}");
        let wrong: Vec<&&str> = FRONT_END_ONLY
            .iter()
            .filter(|name| linked.contains(**name))
            .collect();
        assert!(wrong.is_empty(), "{root} links {wrong:?}");
    }
    // The reader sees what the command links, so an empty answer above is not a blind one.
    let command = linked("urdf-validate-cli");
    assert!(
        command.contains("clap") && command.contains("tokio"),
        "{command:?}"
    );
}
