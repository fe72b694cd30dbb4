//! With the `wheel-binary` feature (the wheel's build, `[tool.maturin] features` in pyproject.toml): put the
//! `urdf_validate` binary into `wheel-data/scripts/`, which maturin installs as the wheel's console
//! command. maturin builds one cargo target per wheel (PyO3/maturin#368), so this script builds the
//! command with a cargo of its own, in a target folder of its own (the outer build holds the lock on its
//! folder). `URDF_VALIDATE_WHEEL_BINARY` names a binary built from this same checkout to ship instead
//! (the test scripts, which have just built it). Without the feature (`cargo build`, clippy, tests) it
//! does nothing.

use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-env-changed=URDF_VALIDATE_WHEEL_BINARY");
    if std::env::var_os("CARGO_FEATURE_WHEEL_BINARY").is_none() {
        return;
    }
    let manifest_dir = PathBuf::from(env_var("CARGO_MANIFEST_DIR"));
    for crate_dir in ["../cli", "../session", "../urdf-validator", "../xacro"] {
        println!(
            "cargo:rerun-if-changed={}",
            manifest_dir.join(crate_dir).display()
        );
    }
    let name = format!("urdf_validate{}", std::env::consts::EXE_SUFFIX);
    let binary = match std::env::var_os("URDF_VALIDATE_WHEEL_BINARY") {
        Some(prebuilt) => PathBuf::from(prebuilt),
        None => build_command(&manifest_dir, &name),
    };
    let scripts = manifest_dir.join("wheel-data").join("scripts");
    if let Err(error) = std::fs::create_dir_all(&scripts)
        .and_then(|()| std::fs::copy(&binary, scripts.join(&name)).map(|_| ()))
    {
        fail(&format!(
            "cannot copy {} into {}: {error}",
            binary.display(),
            scripts.display()
        ));
    }
}

/// `cargo build --release -p urdf-validate-cli` into a target folder under `OUT_DIR`; the binary built.
fn build_command(manifest_dir: &Path, name: &str) -> PathBuf {
    let target_dir = PathBuf::from(env_var("OUT_DIR")).join("command");
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut command = Command::new(cargo);
    command
        .current_dir(manifest_dir)
        .args([
            "build",
            "--release",
            "--locked",
            "-p",
            "urdf-validate-cli",
            "--bin",
            "urdf_validate",
        ])
        .arg("--target-dir")
        .arg(&target_dir);
    if let Ok(target) = std::env::var("TARGET") {
        command.args(["--target", &target]);
    }
    // The outer build's settings for the extension (RUSTFLAGS for a shared library) are not the binary's.
    for variable in ["CARGO_ENCODED_RUSTFLAGS", "RUSTFLAGS", "CARGO_TARGET_DIR"] {
        command.env_remove(variable);
    }
    match command.status() {
        Ok(status) if status.success() => {}
        Ok(status) => fail(&format!(
            "building the urdf_validate command failed ({status})"
        )),
        Err(error) => fail(&format!(
            "cannot run cargo to build the urdf_validate command: {error}"
        )),
    }
    let profile_dir = match std::env::var("TARGET") {
        Ok(target) => target_dir.join(target).join("release"),
        Err(_) => target_dir.join("release"),
    };
    profile_dir.join(name)
}

fn env_var(name: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| fail(&format!("{name} is not set (not run by cargo?)")))
}

fn fail(message: &str) -> ! {
    eprintln!("error: crates/python/build.rs: {message}");
    std::process::exit(1)
}
