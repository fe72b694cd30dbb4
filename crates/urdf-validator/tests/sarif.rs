//! The SARIF output validated against the official SARIF 2.1.0 JSON Schema (`tests/data/sarif/`, see its
//! SOURCES.md) with the `boon` validator, formats checked (`uri`), plus what GitHub code scanning needs beyond the schema: every
//! result has a rule, a level and a location with a start line.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};

use serde_json::Value;
use urdf_validator::render::{render_sarif, FormatOptions, Unreported};
use urdf_validator::{validate, validate_text, Options, Validation};

/// The SARIF schema's `id`: the location it is compiled under (its references are all internal).
const SCHEMA_ID: &str =
    "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json";

/// The compiled SARIF schema, with format assertions (`uri`, `date-time`) on.
fn schema() -> (boon::Schemas, boon::SchemaIndex) {
    let path =
        common::repo_root().join("crates/urdf-validator/tests/data/sarif/sarif-schema-2.1.0.json");
    let schema: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut schemas = boon::Schemas::new();
    let mut compiler = boon::Compiler::new();
    compiler.enable_format_assertions();
    compiler.add_resource(SCHEMA_ID, schema).unwrap();
    let index = compiler
        .compile(SCHEMA_ID, &mut schemas)
        .expect("the SARIF schema compiles");
    (schemas, index)
}

fn is_valid(value: &Value) -> Result<(), String> {
    let (schemas, index) = schema();
    schemas.validate(value, index).map_err(|e| format!("{e:#}"))
}

fn options() -> Options {
    let mut options = Options::default();
    options.workspace.samples = 300;
    options
}

/// Validates `sarif` against the schema; panics listing every violation.
fn assert_valid(sarif: &str) -> Value {
    let value: Value = serde_json::from_str(sarif).expect("SARIF is JSON");
    if let Err(errors) = is_valid(&value) {
        panic!("SARIF violates the schema:\n{errors}");
    }
    value
}

/// What code scanning needs beyond the schema.
fn assert_code_scanning_ready(value: &Value, findings: usize) {
    assert_eq!(value["version"], "2.1.0");
    let runs = value["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 1, "one run");
    let rules = runs[0]["tool"]["driver"]["rules"].as_array().unwrap();
    assert_eq!(rules.len(), urdf_validator::diagnostics::rules::ALL.len());
    let results = runs[0]["results"].as_array().unwrap();
    assert_eq!(results.len(), findings, "one result per finding");
    for result in results {
        let index = result["ruleIndex"].as_u64().unwrap() as usize;
        assert_eq!(
            rules[index]["id"], result["ruleId"],
            "ruleIndex points at ruleId"
        );
        assert!(["error", "warning", "note"].contains(&result["level"].as_str().unwrap()));
        let location = &result["locations"][0]["physicalLocation"];
        assert!(location["artifactLocation"]["uri"]
            .as_str()
            .is_some_and(|u| !u.is_empty()));
        assert!(location["region"]["startLine"].as_u64().unwrap() >= 1);
    }
}

/// A robot with findings of every severity, with and without positions.
const BROKEN: &str = r#"<?xml version="1.0"?>
<robot name="broken">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm"><inertial><mass value="-1"/><inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/><limit effort="0.001" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="j2" type="revolute"><parent link="base"/><child link="nowhere"/></joint>
  <link name="odd" efort="3"/>
</robot>
"#;

#[test]
fn sarif_of_a_broken_robot_and_an_unreadable_input_is_valid() {
    let dir = tempdir();
    let path = dir.join("my robot.urdf");
    let validation = validate_text(BROKEN.to_string(), &path, &options()).unwrap();
    assert!(
        validation.report.findings.len() >= 4,
        "{:?}",
        validation.report.findings
    );
    let unreported = [
        Unreported {
            file: dir.join("missing.urdf").display().to_string(),
            error: "cannot read: No such file or directory".into(),
        },
        Unreported {
            file: String::new(),
            error: "robots/: no URDF or xacro file below it".into(),
        },
    ];
    let options = FormatOptions {
        base_dir: Some(dir.clone()),
        rules_url: Some("https://example.org/urdf-validator/rules/".into()),
    };
    let sarif = render_sarif(&[&validation], &unreported, &options);
    let value = assert_valid(&sarif);
    assert_code_scanning_ready(&value, validation.report.findings.len());
    let run = &value["runs"][0];
    assert_eq!(run["invocations"][0]["executionSuccessful"], false);
    // Relative to the base directory, percent-encoded.
    let artifact = &run["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"];
    assert_eq!(artifact["uri"], "my%20robot.urdf");
    assert_eq!(artifact["uriBaseId"], "%SRCROOT%");
    let rule = &run["tool"]["driver"]["rules"][0];
    assert_eq!(
        rule["helpUri"],
        "https://example.org/urdf-validator/rules/u001.html"
    );
    // Outside the base directory: an absolute file URI.
    let elsewhere = render_sarif(
        &[&validation],
        &[],
        &FormatOptions {
            base_dir: Some(PathBuf::from("/nonexistent/base")),
            rules_url: None,
        },
    );
    let value = assert_valid(&elsewhere);
    let uri = value["runs"][0]["results"][0]["locations"][0]["physicalLocation"]
        ["artifactLocation"]["uri"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(
        uri.starts_with("file:///") && uri.ends_with("my%20robot.urdf"),
        "{uri}"
    );
    assert!(value["runs"][0]["tool"]["driver"]["rules"][0]
        .get("helpUri")
        .is_none());
}

/// The schema test can fail: a result without a message is refused.
#[test]
fn the_schema_refuses_a_result_without_message() {
    let bad = r#"{"version":"2.1.0","runs":[{"tool":{"driver":{"name":"x"}},"results":[{"ruleId":"U001"}]}]}"#;
    let value: Value = serde_json::from_str(bad).unwrap();
    assert!(is_valid(&value).is_err());
    // Formats are checked: a helpUri must be a URI.
    let bad_uri = r#"{"version":"2.1.0","runs":[{"tool":{"driver":{"name":"x","rules":[{"id":"U001","helpUri":"not a uri"}]}}}]}"#;
    let value: Value = serde_json::from_str(bad_uri).unwrap();
    assert!(is_valid(&value).is_err());
}

#[test]
fn sarif_of_the_example_and_reference_robots_is_valid() {
    let mut files = vec![common::repo_root().join("examples/robots/mobile_manipulator.urdf")];
    if let Some(robots) = common::shared_robots() {
        for file in [
            "pr2/pr2_description/robots/pr2.urdf",
            "husky/husky_description/urdf/husky.urdf.xacro",
            "spot/spot_description/model.urdf",
        ] {
            files.push(robots.join(file));
        }
    }
    let validations: Vec<Validation> = files
        .iter()
        .map(|f| validate(f, &options()).unwrap())
        .collect();
    let refs: Vec<&Validation> = validations.iter().collect();
    let base = common::repo_root();
    let sarif = render_sarif(
        &refs,
        &[],
        &FormatOptions {
            base_dir: Some(base),
            rules_url: None,
        },
    );
    let value = assert_valid(&sarif);
    let findings = validations.iter().map(|v| v.report.findings.len()).sum();
    assert_code_scanning_ready(&value, findings);
    if files.len() > 1 {
        // PR2's undersized shoulders carry fixes: `fixes[].artifactChanges` are schema-valid too.
        let results = value["runs"][0]["results"].as_array().unwrap();
        let fix = results
            .iter()
            .find_map(|r| r.get("fixes"))
            .expect("a result with fixes");
        assert!(
            fix[0]["artifactChanges"][0]["replacements"][0]["deletedRegion"]["byteOffset"].is_u64()
        );
    }
    assert_eq!(
        value["runs"][0]["invocations"][0]["executionSuccessful"],
        true
    );
}

/// A fresh directory under the target directory's temp folder.
fn tempdir() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("sarif-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
