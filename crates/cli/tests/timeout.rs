//! `--timeout`: a file that does not finish in time is reported as not finished, naming the stage that was
//! running, and a batch goes on with the next file.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::PathBuf;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "urdf_validate_timeout_{}_{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A chain of `links` revolute joints with a box on every link.
fn chain(links: usize) -> String {
    let body = "<inertial><mass value=\"0.1\"/><inertia ixx=\"1e-4\" ixy=\"0\" ixz=\"0\" iyy=\"1e-4\" iyz=\"0\" izz=\"1e-4\"/></inertial>\
                <collision><geometry><box size=\"0.01 0.01 0.01\"/></geometry></collision>";
    let mut urdf = String::from("<robot name=\"chain\">");
    for i in 0..=links {
        urdf.push_str(&format!("<link name=\"l{i}\">{body}</link>"));
    }
    for i in 0..links {
        urdf.push_str(&format!(
            "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{i}\"/><child link=\"l{}\"/>\
             <origin xyz=\"0 0 0.02\"/><axis xyz=\"0 1 0\"/>\
             <limit lower=\"-0.01\" upper=\"0.01\" effort=\"100\" velocity=\"1\"/></joint>",
            i + 1
        ));
    }
    urdf.push_str("</robot>");
    urdf
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("runs")
}

#[test]
fn a_file_past_its_time_is_reported_and_the_batch_goes_on() {
    let dir = scratch("batch");
    // 1,000 links × 20,000,000 samples: most of a minute of workspace sampling even on a fast machine (the
    // sampler does 30,000 in ~70 ms here), so the 1 s limit always falls inside it.
    let slow = dir.join("a_slow.urdf");
    std::fs::write(&slow, chain(1000)).unwrap();
    let quick = dir.join("b_quick.urdf");
    std::fs::write(&quick, chain(3)).unwrap();
    let started = Instant::now();
    let output = run(&[
        slow.to_str().unwrap(),
        quick.to_str().unwrap(),
        "--no-write",
        "--samples",
        "20000000",
        "--timeout",
        "1",
        "--jobs",
        "2",
    ]);
    let elapsed = started.elapsed();
    let stderr = String::from_utf8_lossy(&output.stderr);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    // The stage it was in depends on the machine's load (workspace, or collision_setup before it).
    assert!(
        stderr.contains("a_slow.urdf: analysis did not finish within 1 s (stage running: "),
        "{stderr}"
    );
    assert!(
        stdout.contains("b_quick.urdf"),
        "the next file is reported: {stdout}"
    );
    assert!(
        elapsed < Duration::from_secs(50),
        "the batch waited {elapsed:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn zero_means_no_limit_and_bad_values_are_refused() {
    let dir = scratch("values");
    let quick = dir.join("quick.urdf");
    std::fs::write(&quick, chain(3)).unwrap();
    let path = quick.to_str().unwrap();
    let unlimited = run(&[path, "--no-write", "--timeout", "0"]);
    assert!(
        unlimited.status.code().is_some_and(|c| c < 2),
        "{unlimited:?}"
    );
    let huge = run(&[path, "--no-write", "--timeout", "1e300"]);
    assert!(huge.status.code().is_some_and(|c| c < 2), "{huge:?}");
    let negative = run(&[path, "--no-write", "--timeout=-1"]);
    assert_eq!(negative.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&negative.stderr).contains("--timeout -1"));
    let _ = std::fs::remove_dir_all(&dir);
}
