//! Snapshot tests of the `urdf_validate` reports on the reference robots: the text report (`--no-write`,
//! no colour) with its exit code, and the JSON report (`--format json`), for each robot of the seed README
//! plus the repository's example. They pin the report content so a refactor can prove it changes nothing.
//!
//! The robots come from `../shared/robots` (`URDF_VALIDATOR_SHARED_ROBOTS`, set by scripts/test.sh). When
//! it is absent the tests skip with a message, except under `CI` where they fail.
//!
//! Redacted: the timestamp, and the robots and repository directories (`[ROBOTS]`, `[REPO]`). Nothing else
//! varies: the workspace sampling is seeded (default seed) and gives the same numbers on any thread count.
//! Update with `INSTA_UPDATE=always cargo test -p urdf-validate-cli --test snapshots` (or `cargo insta`).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

use common::{repo_root, shared_robots};

/// Where a robot file lives.
enum Base {
    SharedRobots,
    Repo,
}

/// Runs the binary on one file with a clean environment (no colour, no ROS paths, no xacro `optenv`
/// variables); returns the exit code and stdout. Nothing may go to stderr.
fn run(file: &Path, args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .arg(file)
        .args(args)
        .env_clear()
        .env("NO_COLOR", "1")
        .output()
        .expect("urdf_validate runs");
    let stdout = String::from_utf8(out.stdout).expect("stdout is UTF-8");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.trim().is_empty(),
        "{}: unexpected stderr:\n{stderr}",
        file.display()
    );
    assert!(
        !stdout.contains('\x1b'),
        "{}: colour codes in the output",
        file.display()
    );
    (
        out.status.code().expect("an exit code, not a signal"),
        stdout,
    )
}

/// The directories replaced by placeholders in the reports.
struct Dirs {
    robots: Option<PathBuf>,
    repo: PathBuf,
}

impl Dirs {
    /// `text` with each directory replaced by its placeholder.
    fn redact(&self, text: &str) -> String {
        let mut pairs = vec![(self.repo.display().to_string(), "[REPO]")];
        if let Some(robots) = &self.robots {
            pairs.push((robots.display().to_string(), "[ROBOTS]"));
        }
        // Longest first, in case one directory holds the other.
        pairs.sort_by_key(|(dir, _)| std::cmp::Reverse(dir.len()));
        pairs
            .iter()
            .fold(text.to_owned(), |text, (dir, placeholder)| {
                text.replace(dir.as_str(), placeholder)
            })
    }

    /// Every string (not key) of a JSON value redacted.
    fn redact_json(&self, value: &mut serde_json::Value) {
        match value {
            serde_json::Value::String(s) => *s = self.redact(s),
            serde_json::Value::Array(items) => {
                items.iter_mut().for_each(|item| self.redact_json(item))
            }
            serde_json::Value::Object(map) => {
                map.values_mut().for_each(|item| self.redact_json(item))
            }
            _ => {}
        }
    }
}

/// Snapshots `<name>__text` (exit code and text report) and `<name>__json` (the JSON report) for `file`
/// (below `base`) run with `flags`; the JSON run must exit with the same code as the text run.
fn check(name: &str, base: Base, file: &str, flags: &[&str]) {
    let (root, robots) = match base {
        Base::SharedRobots => match shared_robots() {
            Some(dir) => (dir.clone(), Some(dir)),
            None => return,
        },
        Base::Repo => (repo_root(), None),
    };
    let dirs = Dirs {
        robots,
        repo: repo_root(),
    };
    let path = root.join(file);
    assert!(path.is_file(), "{} is missing", path.display());
    let command = std::iter::once(file)
        .chain(flags.iter().copied())
        .collect::<Vec<_>>()
        .join(" ");

    let mut args = flags.to_vec();
    args.push("--no-write");
    let (code, text) = run(&path, &args);
    insta::with_settings!({
        description => format!("urdf_validate {command} --no-write"),
        omit_expression => true,
    }, {
        insta::assert_snapshot!(
            format!("{name}__text"),
            format!("exit code: {code}\n\n{}", dirs.redact(&text))
        );
    });

    args.extend(["--format", "json"]);
    let (json_code, json) = run(&path, &args);
    assert_eq!(
        json_code, code,
        "{name}: --format json changed the exit code"
    );
    let mut report: serde_json::Value = serde_json::from_str(&json).expect("stdout is JSON");
    assert!(report.is_object(), "{name}: one report object");
    assert!(
        report["timestamp"].is_string(),
        "{name}: the report has a timestamp to redact"
    );
    dirs.redact_json(&mut report);
    insta::with_settings!({
        description => format!("urdf_validate {command} --no-write --format json (exit code {code})"),
        omit_expression => true,
    }, {
        insta::assert_json_snapshot!(format!("{name}__json"), report, {
            ".timestamp" => "[TIMESTAMP]",
        });
    });
}

#[test]
fn turtlebot3_burger() {
    check(
        "turtlebot3_burger",
        Base::SharedRobots,
        "turtlebot3/turtlebot3_description/urdf/turtlebot3_burger.urdf",
        &[],
    );
}

#[test]
fn fetch() {
    check(
        "fetch",
        Base::SharedRobots,
        "fetch/fetch_description/robots/fetch.urdf",
        &[],
    );
}

#[test]
fn pr2() {
    check(
        "pr2",
        Base::SharedRobots,
        "pr2/pr2_description/robots/pr2.urdf",
        &[],
    );
}

#[test]
fn anymal() {
    check(
        "anymal",
        Base::SharedRobots,
        "anymal/anymal_b_simple_description/urdf/anymal.urdf",
        &[],
    );
}

#[test]
fn spot() {
    check(
        "spot",
        Base::SharedRobots,
        "spot/spot_description/model.urdf",
        &[],
    );
}

#[test]
fn franka_frankie_arm_hand() {
    check(
        "franka_frankie_arm_hand",
        Base::SharedRobots,
        "franka_panda/franka_description/robots/frankie_arm_hand.urdf",
        &[],
    );
}

/// The xacro source, expanded by the tool (default arguments; `lms1xx` is a sibling package).
#[test]
fn husky() {
    check(
        "husky",
        Base::SharedRobots,
        "husky/husky_description/urdf/husky.urdf.xacro",
        &[],
    );
}

#[test]
fn ground_vehicle() {
    check(
        "ground_vehicle",
        Base::SharedRobots,
        "samples/ground_vehicle.urdf",
        &["--robot-type", "ground_vehicle"],
    );
}

#[test]
fn aerial_drone() {
    check(
        "aerial_drone",
        Base::SharedRobots,
        "samples/aerial_drone.urdf",
        &["--robot-type", "aerial"],
    );
}

#[test]
fn mobile_manipulator() {
    check(
        "mobile_manipulator",
        Base::Repo,
        "examples/robots/mobile_manipulator.urdf",
        &[],
    );
}
