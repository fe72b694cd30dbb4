//! Several files at once, as a directory, a pre-commit run or a CI job hands them over: every file gets
//! its report and the process exits, at one, two or the machine's number of threads, with and without
//! `--timeout`. (Files with meshes once hung here: the file loop ran on the pool its mesh loading needed.)

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Longer than any of these runs takes (a few seconds each in a debug build), far shorter than the
/// 60 s default `--timeout` a hung run waited for.
const DEADLINE: Duration = Duration::from_secs(45);

fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("urdf_validate_batch_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A closed box `size` m across as ASCII STL.
fn box_stl(size: f64) -> String {
    let corner =
        |i: usize| [i & 1, (i >> 1) & 1, (i >> 2) & 1].map(|b| b as f64 * size - size / 2.0);
    let mut out = String::from("solid box\n");
    for [a, b, c] in [
        [0, 1, 3],
        [0, 3, 2],
        [4, 6, 7],
        [4, 7, 5],
        [0, 4, 5],
        [0, 5, 1],
        [2, 3, 7],
        [2, 7, 6],
        [0, 2, 6],
        [0, 6, 4],
        [1, 5, 7],
        [1, 7, 3],
    ] {
        out.push_str("facet normal 0 0 0\nouter loop\n");
        for v in [a, b, c].map(corner) {
            out.push_str(&format!("vertex {} {} {}\n", v[0], v[1], v[2]));
        }
        out.push_str("endloop\nendfacet\n");
    }
    out + "endsolid box\n"
}

/// A two-link arm whose links are made of two mesh files (so its meshes load in parallel).
fn arm_with_meshes(name: &str) -> String {
    let inertial = r#"<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>"#;
    format!(
        r#"<robot name="{name}">
  <link name="base">{inertial}<collision><geometry><mesh filename="meshes/base.stl"/></geometry></collision></link>
  <link name="arm">{inertial}<collision><origin xyz="0 0 0.3"/><geometry><mesh filename="meshes/arm.stl"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="50" velocity="1"/></joint>
</robot>"#
    )
}

/// A folder of `count` robots sharing two mesh files.
fn robots_with_meshes(count: usize) -> (PathBuf, Vec<PathBuf>) {
    let dir = scratch(&format!("robots_{count}"));
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    std::fs::write(dir.join("meshes/base.stl"), box_stl(0.2)).unwrap();
    std::fs::write(dir.join("meshes/arm.stl"), box_stl(0.1)).unwrap();
    let files = (0..count)
        .map(|i| {
            let path = dir.join(format!("arm_{i}.urdf"));
            std::fs::write(&path, arm_with_meshes(&format!("arm_{i}"))).unwrap();
            path
        })
        .collect();
    (dir, files)
}

/// How a run ended: exit code and stderr, or `None` when it was still running at [`DEADLINE`] (then killed).
fn run_within_deadline(args: &[&str], env: &[(&str, &str)]) -> Option<(Option<i32>, String)> {
    let mut command = Command::new(env!("CARGO_BIN_EXE_urdf_validate"));
    command
        .args(args)
        .env("NO_COLOR", "1")
        .env_remove("RAYON_NUM_THREADS")
        .envs(env.iter().copied())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    let mut child = command.spawn().expect("starts");
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            let mut stderr = String::new();
            std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut stderr).unwrap();
            return Some((status.code(), stderr));
        }
        if started.elapsed() > DEADLINE {
            let _ = child.kill();
            let _ = child.wait();
            return None;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Flags and environment variables of a run.
type Setting = (
    &'static [&'static str],
    &'static [(&'static str, &'static str)],
);

/// The thread settings a run is tried with: `--jobs 1`, `--jobs 2`, and the default pool under
/// `RAYON_NUM_THREADS` 1 and 2 and unset (the machine's core count).
const THREADS: [Setting; 5] = [
    (&["--jobs", "1"], &[]),
    (&["--jobs", "2"], &[]),
    (&[], &[("RAYON_NUM_THREADS", "1")]),
    (&[], &[("RAYON_NUM_THREADS", "2")]),
    (&[], &[]),
];

/// `--timeout` as the default (60 s), a short one, and none.
const TIMEOUTS: [&[&str]; 3] = [&[], &["--timeout", "40"], &["--timeout", "0"]];

/// Run `inputs` with `settings` into a fresh folder: the names of the reports written, or a failure
/// naming the setting when the run did not exit before the deadline or a file did not finish.
fn reports_written(inputs: &[&Path], settings: &[&str], env: &[(&str, &str)]) -> Vec<String> {
    static RUNS: AtomicUsize = AtomicUsize::new(0);
    let out = scratch(&format!("reports_{}", RUNS.fetch_add(1, Ordering::Relaxed)));
    let mut args: Vec<&str> = inputs.iter().map(|p| p.to_str().unwrap()).collect();
    args.extend(["--output-dir", out.to_str().unwrap(), "--samples", "500"]);
    args.extend(settings);
    let setting = format!("{settings:?} {env:?}");
    let Some((code, stderr)) = run_within_deadline(&args, env) else {
        panic!("{setting}: still running after {DEADLINE:?}");
    };
    assert!(
        !stderr.contains("did not finish"),
        "{setting}: exit {code:?}\n{stderr}"
    );
    assert!(
        matches!(code, Some(0..=2)),
        "{setting}: exit {code:?}\n{stderr}"
    );
    let mut written: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    written.sort();
    let _ = std::fs::remove_dir_all(&out);
    written
}

/// Validate `inputs` with every thread setting and timeout: each run exits before the deadline and
/// writes exactly the reports `expected`, none of them of a run that did not finish.
fn every_file_is_reported(inputs: &[&Path], expected: &[String]) {
    for (jobs, env) in THREADS {
        for timeout in TIMEOUTS {
            let settings = [jobs, timeout].concat();
            let written = reports_written(inputs, &settings, env);
            assert_eq!(written, expected, "{settings:?} {env:?}");
        }
    }
}

/// The report names of `files` (`arm_0.urdf` → `arm_0_validation.json`), sorted.
fn report_names(files: &[PathBuf]) -> Vec<String> {
    let mut names: Vec<String> = files
        .iter()
        .map(|f| {
            let name = f.file_name().unwrap().to_string_lossy();
            format!("{}_validation.json", name.trim_end_matches(".urdf"))
        })
        .collect();
    names.sort();
    names
}

#[test]
fn two_files_with_meshes_are_each_reported() {
    let (dir, files) = robots_with_meshes(2);
    let inputs: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    every_file_is_reported(&inputs, &report_names(&files));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn ten_files_with_meshes_are_each_reported() {
    let (dir, files) = robots_with_meshes(10);
    let inputs: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    every_file_is_reported(&inputs, &report_names(&files));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_directory_of_robots_with_meshes_is_reported_file_by_file() {
    let (dir, files) = robots_with_meshes(4);
    every_file_is_reported(&[&dir], &report_names(&files));
    let _ = std::fs::remove_dir_all(dir);
}

/// The reference robots (`../shared/robots`: PR2, Fetch, ANYmal, Spot, ... with their meshes and xacro) as
/// one directory: every setting writes the reports a run of one file at a time without a watchdog writes.
#[test]
fn the_reference_robots_directory_is_reported_file_by_file() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let one_at_a_time = reports_written(&[&robots], &["--jobs", "1", "--timeout", "0"], &[]);
    assert!(one_at_a_time.len() >= 10, "{one_at_a_time:?}");
    every_file_is_reported(&[&robots], &one_at_a_time);
}
