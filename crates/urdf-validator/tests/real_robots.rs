//! The validator on real robot descriptions: the reference robots in `../shared/robots` and the
//! example-robot-data corpus (installed by `scripts/setup-test-env.sh`).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::path::Path;

use common::{corpus, shared_robots, urdfs_below};
use urdf_validator::report::{FindingReport, Report};
use urdf_validator::{validate, Options};

fn report(path: &Path) -> Report {
    match validate(path, &Options::default()) {
        Ok(validation) => validation.report,
        Err(error) => panic!("{} failed to load: {error}", path.display()),
    }
}

fn with_rule<'a>(report: &'a Report, code: &str) -> Vec<&'a FindingReport> {
    report.findings.iter().filter(|f| f.rule == code).collect()
}

/// The report as JSON, re-read by serde_json (which rejects NaN and Infinity).
fn assert_strict_json(report: &Report, path: &Path) {
    let text = serde_json::to_string(report).expect("serialises");
    assert!(
        !text.contains("NaN") && !text.contains("Infinity"),
        "{}: non-finite number in JSON",
        path.display()
    );
    let value: serde_json::Value = serde_json::from_str(&text).expect("strict JSON");
    for key in [
        "urdf_path",
        "robot_name",
        "overall_status",
        "confidence_level",
        "schema",
        "links",
        "findings",
    ] {
        assert!(
            value.get(key).is_some(),
            "{}: report lacks '{key}'",
            path.display()
        );
    }
}

#[test]
fn every_shared_robot_validates_to_strict_json() {
    let Some(robots) = shared_robots() else {
        return;
    };
    let files = urdfs_below(&robots);
    assert!(
        files.len() >= 8,
        "expected the reference robots, found {files:?}"
    );
    for file in files {
        assert_strict_json(&report(&file), &file);
    }
}

#[test]
fn fetch_finger_links_have_singular_inertia() {
    let Some(robots) = shared_robots() else {
        return;
    };
    let report = report(&robots.join("fetch/fetch_description/robots/fetch.urdf"));
    let mut flagged: Vec<&str> = with_rule(&report, "U205")
        .iter()
        .map(|f| f.message.split('\'').nth(1).unwrap_or_default())
        .collect();
    flagged.sort_unstable();
    assert_eq!(flagged, ["l_gripper_finger_link", "r_gripper_finger_link"]);
    assert!(with_rule(&report, "U205").iter().all(|f| f.line.is_some()));
    assert_eq!(report.overall_status.label(), "WARN");
}

#[test]
fn turtlebot3_wheels_lack_limits_and_its_meshes_resolve() {
    let Some(robots) = shared_robots() else {
        return;
    };
    let report =
        report(&robots.join("turtlebot3/turtlebot3_description/urdf/turtlebot3_burger.urdf"));
    let joints: Vec<&str> = with_rule(&report, "U303")
        .iter()
        .map(|f| f.message.split('\'').nth(1).unwrap_or_default())
        .collect();
    assert_eq!(joints, ["wheel_left_joint", "wheel_right_joint"]);
    assert!(
        with_rule(&report, "U501").is_empty(),
        "package:// meshes should resolve by walking up to package.xml"
    );
    // Three U209s, true of the file: base_link's inertial origin is left at the bottom edge of its
    // collision box, and caster_back_link and base_scan declare I = 0.001 kg·m² on 3 cm and 11 cm parts
    // (together as much as the base's own, which every simulator lumps them into).
    assert_eq!(report.overall_status.label(), "WARN");
    let u209: Vec<&str> = with_rule(&report, "U209")
        .iter()
        .map(|f| f.message.split('\'').nth(1).unwrap_or_default())
        .collect();
    assert_eq!(u209, ["base_link", "caster_back_link", "base_scan"]);
    assert_eq!(
        report.physics.frames, 2,
        "base_footprint and imu_link are frames"
    );
}

#[test]
fn pr2_package_meshes_resolve() {
    let Some(robots) = shared_robots() else {
        return;
    };
    let report = report(&robots.join("pr2/pr2_description/robots/pr2.urdf"));
    assert!(with_rule(&report, "U501").is_empty());
    assert_eq!(report.physics.links, 88);
    assert_eq!(with_rule(&report, "U105").len(), 1, "more than 50 links");
}

#[test]
fn every_corpus_urdf_validates_to_strict_json() {
    let Some(corpus) = corpus() else { return };
    let files = urdfs_below(&corpus);
    assert_eq!(files.len(), 69, "example-robot-data should ship 69 URDFs");
    for file in &files {
        assert_strict_json(&report(file), file);
    }
}

#[test]
fn files_the_python_tool_cannot_parse_validate_here() {
    let Some(corpus) = corpus() else { return };
    for relative in [
        "pr2_description/urdf/pr2.urdf",
        "icub_description/robots/icub.urdf",
        "icub_description/robots/icub_reduced.urdf",
        "romeo_description/urdf/romeo_laas_small.urdf",
    ] {
        let report = report(&corpus.join(relative));
        assert!(report.links.len() > 10, "{relative}: links were parsed");
        assert!(
            report.schema.critical_issues.is_empty(),
            "{relative}: {:?}",
            report.schema.critical_issues
        );
    }
}

#[test]
fn empty_ur3_stub_is_critical_not_a_crash() {
    let Some(corpus) = corpus() else { return };
    let report = report(&corpus.join("ur_description/urdf/ur3.urdf"));
    assert_eq!(with_rule(&report, "U009").len(), 1, "no links");
    assert_eq!(report.overall_status.exit_code(), 2);
}
