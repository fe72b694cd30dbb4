//! A closed stdout (`urdf_validate --list-rules | head -1`) ends the program quietly: no panic message,
//! the usual exit status. Each run closes the pipe's read end before the program writes.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::Path;
use std::process::{Command, Stdio};

/// Exit code and stderr of `urdf_validate args` whose stdout is closed from the start.
fn with_closed_stdout(args: &[&str]) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs");
    drop(child.stdout.take());
    let output = child.wait_with_output().expect("finishes");
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn every_output_ends_quietly_on_a_closed_pipe() {
    let example =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/robots/mobile_manipulator.urdf");
    let example = example.to_str().expect("UTF-8 path");
    let cases: [(&[&str], i32); 7] = [
        (&["--list-rules"], 0),
        (&["--list-rules-markdown"], 0),
        (&["--json-schema"], 0),
        (&["--explain", "U103"], 0),
        (&[example, "--no-write", "--samples", "64"], 0),
        (
            &[example, "--no-write", "--samples", "64", "--format", "json"],
            0,
        ),
        (&[example, "--expand-only"], 2),
    ];
    for (args, expected) in cases {
        for _ in 0..3 {
            let (code, stderr) = with_closed_stdout(args);
            assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
            assert_eq!(code, Some(expected), "{args:?}: {stderr}");
        }
    }
}
