//! The report formats (`--format sarif,junit,github,html`, `--output`): insta snapshots of each over the
//! reference robots, the JUnit XML read by a real consumer (Python `junitparser`, pinned in
//! scripts/setup-test-env.sh, found through `URDF_VALIDATOR_PYTHON`), and the routing rules of
//! `--format`/`--output`/`--no-write`/`GITHUB_ACTIONS`. The SARIF schema test is
//! `crates/urdf-validator/tests/sarif.rs`.
//!
//! Each robot runs once with its own folder as the working directory, so paths come out relative to it
//! (as in a checkout); redacted: the timestamps and the absolute working directory (`[CWD]`).
//! Update with `INSTA_UPDATE=always cargo test -p urdf-validate-cli --test formats`.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

mod common;

use common::{repo_root, shared_robots};

/// The venv Python with junitparser (`URDF_VALIDATOR_PYTHON`, else `.venv/bin/python`); `None` (with a
/// message) when it is missing outside CI.
fn junit_python() -> Option<PathBuf> {
    let python = std::env::var_os("URDF_VALIDATOR_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo_root().join(".venv/bin/python"));
    let has_junitparser = Command::new(&python)
        .args(["-c", "import junitparser"])
        .output()
        .is_ok_and(|o| o.status.success());
    match has_junitparser {
        true => Some(python),
        false if std::env::var_os("CI").is_some() => panic!(
            "{} with junitparser is missing under CI (run scripts/setup-test-env.sh)",
            python.display()
        ),
        false => {
            eprintln!(
                "skipping the junitparser check: {} cannot import junitparser",
                python.display()
            );
            None
        }
    }
}

struct Run {
    code: i32,
    stdout: String,
    stderr: String,
}

/// Runs the binary in `cwd` with a clean environment plus `env`.
fn run(cwd: &Path, args: &[&str], env: &[(&str, &str)]) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .current_dir(cwd)
        .args(args)
        .env_clear()
        .env("NO_COLOR", "1")
        .envs(env.iter().copied())
        .output()
        .expect("urdf_validate runs");
    Run {
        code: out.status.code().expect("an exit code"),
        stdout: String::from_utf8(out.stdout).expect("UTF-8 stdout"),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// A fresh empty folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("formats-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `text` with each `(directory, placeholder)` replaced, longest directory first.
fn redact(text: &str, dirs: &[(&Path, &str)]) -> String {
    let mut pairs: Vec<(String, &str)> = dirs
        .iter()
        .map(|(d, p)| (d.display().to_string(), *p))
        .collect();
    pairs.sort_by_key(|(d, _)| std::cmp::Reverse(d.len()));
    pairs
        .iter()
        .fold(text.to_owned(), |text, (dir, placeholder)| {
            text.replace(dir.as_str(), placeholder)
        })
}

/// Every `timestamp="…"` attribute replaced by `timestamp="[TIMESTAMP]"`.
fn redact_timestamps(xml: &str) -> String {
    let mut out = String::new();
    let mut rest = xml;
    while let Some(start) = rest.find("timestamp=\"") {
        let value = start + "timestamp=\"".len();
        out.push_str(&rest[..value]);
        let end = rest[value..].find('"').map_or(rest.len(), |e| value + e);
        out.push_str("[TIMESTAMP]");
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// junitparser's reading of a JUnit file: suites with their counts and each case's result.
fn junitparser_read(python: &Path, file: &Path) -> Value {
    const SCRIPT: &str = r#"
import json, sys
from junitparser import JUnitXml, TestSuite
xml = JUnitXml.fromfile(sys.argv[1])
suites = [xml] if isinstance(xml, TestSuite) else list(xml)
out = []
for suite in suites:
    cases = []
    for case in suite:
        cases.append({
            "name": case.name,
            "classname": case.classname,
            "results": [type(r).__name__ for r in case.result],
            "texts": [(r.message or "") + "\n" + (r.text or "") for r in case.result],
        })
    out.append({"name": suite.name, "tests": suite.tests, "failures": suite.failures,
                "errors": suite.errors, "skipped": suite.skipped, "cases": cases})
print(json.dumps(out))
"#;
    let out = Command::new(python)
        .args(["-c", SCRIPT])
        .arg(file)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "junitparser cannot read {}: {}",
        file.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("junitparser output is JSON")
}

/// Checks junitparser's reading against the report: the counts agree with the cases, every CRITICAL or
/// FAIL finding is in a failure, and a case fails only with such a finding.
fn check_junit_with_consumer(python: &Path, junit: &Path, reports: &[Value]) {
    let suites = junitparser_read(python, junit);
    let suites = suites.as_array().unwrap();
    assert_eq!(suites.len(), reports.len(), "one suite per robot");
    for (suite, report) in suites.iter().zip(reports) {
        let cases = suite["cases"].as_array().unwrap();
        let count = |kind: &str| {
            cases
                .iter()
                .filter(|c| c["results"].as_array().unwrap().iter().any(|r| r == kind))
                .count() as u64
        };
        assert_eq!(suite["tests"].as_u64(), Some(cases.len() as u64));
        assert_eq!(suite["failures"].as_u64(), Some(count("Failure")));
        assert_eq!(suite["skipped"].as_u64(), Some(count("Skipped")));
        assert_eq!(suite["errors"].as_u64(), Some(count("Error")));
        let failure_texts: String = cases
            .iter()
            .flat_map(|c| c["texts"].as_array().unwrap().iter())
            .map(|t| t.as_str().unwrap().to_string())
            .collect::<Vec<_>>()
            .join("\n");
        let failing: Vec<&str> = report["findings"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|f| f["severity"] == "CRITICAL" || f["severity"] == "FAIL")
            .map(|f| f["message"].as_str().unwrap())
            .collect();
        for message in &failing {
            assert!(
                failure_texts.contains(message),
                "{}: failing finding not in a <failure>: {message}",
                suite["name"]
            );
        }
        assert_eq!(
            count("Failure") > 0,
            !failing.is_empty(),
            "{}: failures iff CRITICAL/FAIL findings",
            suite["name"]
        );
    }
}

/// Snapshots the SARIF, JUnit, GitHub annotations and step summary of one robot, and has junitparser
/// read the JUnit file. The robot runs with `dir` as working directory, with `file` relative to it.
fn check(name: &str, dir: &Path, file: &str, flags: &[&str]) {
    let out_dir = scratch(name);
    let summary = out_dir.join("summary.md");
    let mut args = vec![file, "--format", "sarif,junit,github,html", "--output-dir"];
    let out_dir_str = out_dir.display().to_string();
    args.push(&out_dir_str);
    args.extend(flags);
    let summary_str = summary.display().to_string();
    let result = run(dir, &args, &[("GITHUB_STEP_SUMMARY", summary_str.as_str())]);
    assert!(
        result.stderr.trim().is_empty(),
        "{name}: stderr:\n{}",
        result.stderr
    );
    let repo = repo_root();
    let redactions = [
        (dir, "[CWD]"),
        (repo.as_path(), "[REPO]"),
        (out_dir.as_path(), "[OUT]"),
    ];
    let stem = Path::new(file)
        .file_name()
        .unwrap()
        .to_string_lossy()
        .trim_end_matches(".xacro")
        .trim_end_matches(".urdf")
        .to_string();
    let base = out_dir.join(format!("{stem}_validation"));
    let read = |ext: &str| {
        std::fs::read_to_string(format!("{}.{ext}", base.display()))
            .unwrap_or_else(|e| panic!("{name}: {ext} not written: {e}"))
    };
    let report: Value = serde_json::from_str(&read("json")).unwrap();
    let expected_code = match report["overall_status"].as_str().unwrap() {
        "PASS" => 0,
        "WARN" => 1,
        _ => 2,
    };
    assert_eq!(
        result.code, expected_code,
        "{name}: exit code follows the report"
    );

    let description = format!(
        "urdf_validate {} --format sarif,junit,github,html",
        [file]
            .iter()
            .chain(flags)
            .copied()
            .collect::<Vec<_>>()
            .join(" ")
    );
    let mut sarif: Value = serde_json::from_str(&read("sarif")).unwrap();
    redact_json(&mut sarif, &redactions);
    // The rule descriptors are the same for every robot: snapshotted once (`sarif_rules`), counted here.
    let rules = sarif["runs"][0]["tool"]["driver"]["rules"].take();
    let count = rules.as_array().map_or(0, Vec::len);
    sarif["runs"][0]["tool"]["driver"]["rules"] =
        Value::String(format!("[{count} rules: see formats__sarif_rules.snap]"));
    insta::with_settings!({ description => description.clone(), omit_expression => true }, {
        if name == "mobile_manipulator" {
            insta::assert_json_snapshot!("sarif_rules", rules);
        }
        insta::assert_json_snapshot!(format!("{name}__sarif"), sarif);
        insta::assert_snapshot!(format!("{name}__junit"), redact_timestamps(&redact(&read("xml"), &redactions)));
        insta::assert_snapshot!(format!("{name}__github"), redact(&result.stdout, &redactions));
        insta::assert_snapshot!(
            format!("{name}__step_summary"),
            redact(&std::fs::read_to_string(&summary).unwrap(), &redactions)
        );
        // The page's text (what a reader sees, the plots' labels included), not its markup.
        let timestamp = report["timestamp"].as_str().unwrap_or_default();
        insta::assert_snapshot!(
            format!("{name}__html_text"),
            redact(&html_text(&read("html")), &redactions).replace(timestamp, "[TIMESTAMP]")
        );
    });
    if let Some(python) = junit_python() {
        check_junit_with_consumer(
            &python,
            Path::new(&format!("{}.xml", base.display())),
            &[report],
        );
    }
}

/// The text of an HTML page, one text node a line: tags, `<style>` and `<script>` blocks and blank lines
/// left out.
fn html_text(html: &str) -> String {
    let mut lines = Vec::new();
    let mut rest = html;
    while let Some(start) = rest.find('<') {
        let text = rest[..start].trim();
        if !text.is_empty() {
            lines.push(text.split_whitespace().collect::<Vec<_>>().join(" "));
        }
        let tag = &rest[start..];
        let skip_to = if tag.starts_with("<style") {
            tag.find("</style>").map(|i| i + "</style>".len())
        } else if tag.starts_with("<script") {
            // The 3-D view's bundle and scene: code and data, not text of the page.
            tag.find("</script>").map(|i| i + "</script>".len())
        } else {
            tag.find('>').map(|i| i + 1)
        };
        rest = &tag[skip_to.unwrap_or(tag.len())..];
    }
    lines.join("\n") + "\n"
}

fn redact_json(value: &mut Value, dirs: &[(&Path, &str)]) {
    match value {
        Value::String(s) => *s = redact(s, dirs),
        Value::Array(items) => items.iter_mut().for_each(|v| redact_json(v, dirs)),
        Value::Object(map) => map.values_mut().for_each(|v| redact_json(v, dirs)),
        _ => {}
    }
}

fn shared(name: &str, file: &str, flags: &[&str]) {
    if let Some(robots) = shared_robots() {
        check(name, &robots, file, flags);
    }
}

#[test]
fn turtlebot3_burger() {
    shared(
        "turtlebot3_burger",
        "turtlebot3/turtlebot3_description/urdf/turtlebot3_burger.urdf",
        &[],
    );
}

#[test]
fn fetch() {
    shared("fetch", "fetch/fetch_description/robots/fetch.urdf", &[]);
}

#[test]
fn pr2() {
    shared("pr2", "pr2/pr2_description/robots/pr2.urdf", &[]);
}

#[test]
fn anymal() {
    shared(
        "anymal",
        "anymal/anymal_b_simple_description/urdf/anymal.urdf",
        &[],
    );
}

#[test]
fn spot() {
    shared("spot", "spot/spot_description/model.urdf", &[]);
}

#[test]
fn franka_frankie_arm_hand() {
    shared(
        "franka_frankie_arm_hand",
        "franka_panda/franka_description/robots/frankie_arm_hand.urdf",
        &[],
    );
}

#[test]
fn husky() {
    shared(
        "husky",
        "husky/husky_description/urdf/husky.urdf.xacro",
        &[],
    );
}

#[test]
fn ground_vehicle() {
    shared(
        "ground_vehicle",
        "samples/ground_vehicle.urdf",
        &["--robot-type", "ground_vehicle"],
    );
}

#[test]
fn aerial_drone() {
    shared(
        "aerial_drone",
        "samples/aerial_drone.urdf",
        &["--robot-type", "aerial"],
    );
}

/// With a task and a payload, so the task and payload test cases appear.
#[test]
fn mobile_manipulator() {
    check(
        "mobile_manipulator",
        &repo_root(),
        "examples/robots/mobile_manipulator.urdf",
        &["--task", "pick_from_table", "--payload-mass", "2"],
    );
}

const BROKEN: &str = r#"<robot name="broken">
  <link name="base"/>
  <link name="arm"><inertial><mass value="-1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="nowhere"/></joint>
</robot>
"#;

/// A batch to one document: one SARIF run with the results of every robot (the example has none), one JUnit file with a suite
/// per robot plus an errored one for an unreadable input, each read back (junitparser for JUnit).
#[test]
fn a_batch_goes_to_one_document() {
    let dir = scratch("batch");
    std::fs::write(dir.join("broken.urdf"), BROKEN).unwrap();
    std::fs::write(dir.join("not_xml.urdf"), "<robot").unwrap();
    let example = repo_root().join("examples/robots/mobile_manipulator.urdf");
    std::fs::copy(&example, dir.join("example.urdf")).unwrap();
    let inputs = ["broken.urdf", "example.urdf", "not_xml.urdf"];

    let mut args = inputs.to_vec();
    args.extend([
        "--format",
        "sarif",
        "--output",
        "-",
        "--samples",
        "300",
        "--no-write",
    ]);
    let sarif = run(&dir, &args, &[]);
    assert_eq!(sarif.code, 2, "{}", sarif.stderr);
    let value: Value = serde_json::from_str(&sarif.stdout).expect("stdout is one SARIF document");
    let runs = value["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 1);
    let uris: std::collections::BTreeSet<&str> = runs[0]["results"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]
                .as_str()
                .unwrap()
        })
        .collect();
    // The example robot passes without findings: every result is the broken one's.
    assert_eq!(uris, ["broken.urdf"].into_iter().collect());
    assert_eq!(runs[0]["invocations"][0]["executionSuccessful"], false);
    let notifications = runs[0]["invocations"][0]["toolExecutionNotifications"]
        .as_array()
        .unwrap();
    assert_eq!(notifications.len(), 1, "the unreadable input");
    assert!(
        std::fs::read_dir(&dir).unwrap().count() == 3,
        "--no-write wrote nothing"
    );

    let mut args = inputs.to_vec();
    args.extend([
        "--format",
        "junit",
        "--output",
        "all.xml",
        "--samples",
        "300",
    ]);
    let junit = run(&dir, &args, &[]);
    assert_eq!(junit.code, 2);
    assert!(
        junit.stdout.is_empty(),
        "--output FILE prints nothing: {}",
        junit.stdout
    );
    let xml = std::fs::read_to_string(dir.join("all.xml")).unwrap();
    let doc = roxmltree::Document::parse(&xml).expect("well-formed XML");
    let suites: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name("testsuite"))
        .collect();
    assert_eq!(suites.len(), 3);
    assert!(
        dir.join("broken_validation.json").is_file(),
        "the JSON reports are still written"
    );
    if let Some(python) = junit_python() {
        let read = junitparser_read(&python, &dir.join("all.xml"));
        let names: Vec<&str> = read
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["name"].as_str().unwrap())
            .collect();
        assert_eq!(names, ["broken", "mobile_manipulator", "not_xml"]);
        let last = &read[2]["cases"][0];
        assert_eq!(
            last["results"][0], "Error",
            "the unreadable input is an errored case"
        );
        let broken = &read[0]["cases"][0];
        assert_eq!(broken["name"], "schema");
        assert_eq!(broken["results"][0], "Failure");
    }
}

/// `--format json` keeps printing the JSON report on stdout; listed with text, text wins stdout.
#[test]
fn json_on_stdout_as_before() {
    let dir = scratch("json");
    std::fs::write(dir.join("broken.urdf"), BROKEN).unwrap();
    let json = run(
        &dir,
        &["broken.urdf", "--format", "json", "--no-write"],
        &[],
    );
    let value: Value = serde_json::from_str(&json.stdout).expect("JSON on stdout");
    assert_eq!(value["robot_name"], "broken");
    let both = run(&dir, &["broken.urdf", "--format", "text,json,sarif"], &[]);
    assert!(both.stdout.contains("[OVERALL]"), "{}", both.stdout);
    assert!(
        both.stdout
            .contains("Also written: broken_validation.sarif"),
        "{}",
        both.stdout
    );
    assert!(dir.join("broken_validation.json").is_file());
    assert!(dir.join("broken_validation.sarif").is_file());
    assert!(!dir.join("broken_validation.xml").exists());
}

/// Under GitHub Actions annotations come without being asked: after the text on stdout, on stderr when
/// stdout carries JSON; the step summary is appended.
#[test]
fn github_actions_get_annotations_and_a_summary() {
    let dir = scratch("actions");
    std::fs::write(dir.join("broken.urdf"), BROKEN).unwrap();
    let summary = dir.join("summary.md");
    std::fs::write(&summary, "earlier step\n").unwrap();
    let env = [
        ("GITHUB_ACTIONS", "true"),
        ("GITHUB_STEP_SUMMARY", summary.to_str().unwrap()),
    ];
    let text = run(&dir, &["broken.urdf", "--no-write"], &env);
    assert!(text.stdout.contains("[OVERALL]"));
    assert!(
        text.stdout.contains("::error file=broken.urdf,line=4,col="),
        "{}",
        text.stdout
    );
    let written = std::fs::read_to_string(&summary).unwrap();
    assert!(
        written.starts_with("earlier step\n## urdf_validate"),
        "appended: {written}"
    );
    assert!(
        written.contains("| broken | `broken.urdf` | ❌ FAIL |"),
        "{written}"
    );

    let json = run(
        &dir,
        &["broken.urdf", "--no-write", "--format", "json"],
        &env,
    );
    serde_json::from_str::<Value>(&json.stdout).expect("stdout stays JSON");
    assert!(
        json.stderr.contains("::error file=broken.urdf"),
        "{}",
        json.stderr
    );
}

#[test]
fn usage_errors() {
    let dir = scratch("usage");
    std::fs::write(dir.join("broken.urdf"), BROKEN).unwrap();
    let two = run(
        &dir,
        &["broken.urdf", "--format", "sarif,junit", "--output", "-"],
        &[],
    );
    assert_eq!(two.code, 2);
    assert!(
        two.stderr.contains("--output takes one --format"),
        "{}",
        two.stderr
    );
    std::fs::write(dir.join("b2.urdf"), BROKEN).unwrap();
    let html = run(
        &dir,
        &[
            "broken.urdf",
            "b2.urdf",
            "--format",
            "html",
            "--output",
            "-",
        ],
        &[],
    );
    assert_eq!(html.code, 2);
    assert!(html.stderr.contains("takes one input"), "{}", html.stderr);
    let bad = run(&dir, &["broken.urdf", "--format", "yaml"], &[]);
    assert_eq!(bad.code, 2);
    let note = run(
        &dir,
        &["broken.urdf", "--format", "sarif", "--no-write"],
        &[],
    );
    assert!(
        note.stderr.contains("no sarif file written"),
        "{}",
        note.stderr
    );
    assert!(!dir.join("broken_validation.sarif").exists());
}
