//! The task-query API on the example robot that ships with the repository.

mod common;

use std::path::PathBuf;

use urdf_validator::task_query::{run_pick_task, TargetOrientation, TaskQueryRequest};
use urdf_validator::Options;

fn example() -> PathBuf {
    common::repo_root().join("examples/robots/mobile_manipulator.urdf")
}

fn options() -> Options {
    let mut options = Options::default();
    options.workspace.samples = 3000;
    options
}

fn pick(target: [f64; 3], mass: Option<f64>) -> TaskQueryRequest {
    TaskQueryRequest {
        urdf_path: example(),
        task_type: "pick".into(),
        target_position: Some(target),
        target_orientation: Some(TargetOrientation::Named("top_down".into())),
        object_mass_kg: mass,
        terrain_angle_deg: 0.0,
    }
}

fn status<'a>(response: &'a urdf_validator::task_query::TaskQueryResponse, name: &str) -> &'a str {
    &response
        .sub_checks
        .iter()
        .find(|c| c.name == name)
        .unwrap_or_else(|| panic!("no sub-check {name}: {response:?}"))
        .status
}

#[test]
fn a_table_pick_within_reach_passes_every_sub_check() {
    let response = run_pick_task(&pick([0.5, 0.0, 0.75], Some(0.5)), &options());
    let names: Vec<&str> = response
        .sub_checks
        .iter()
        .map(|c| c.name.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "reach",
            "reach_orientation",
            "payload_strength",
            "stability_during_reach",
            "self_collision"
        ]
    );
    for check in &response.sub_checks {
        assert_eq!(check.status, "PASS", "{check:?}");
    }
    assert_eq!(response.overall_status, "PASS");
}

#[test]
fn a_target_beyond_reach_fails_reach_with_the_deficit() {
    let response = run_pick_task(&pick([3.0, 0.0, 0.75], None), &options());
    assert_eq!(status(&response, "reach"), "FAIL");
    assert!(
        response.sub_checks[0].reason.contains("deficit="),
        "{response:?}"
    );
    assert_eq!(status(&response, "payload_strength"), "N/A");
    assert_eq!(response.overall_status, "FAIL");
}

#[test]
fn a_heavy_object_fails_payload_strength_naming_the_weakest_joint() {
    let response = run_pick_task(&pick([0.5, 0.0, 0.75], Some(500.0)), &options());
    let payload = &response.sub_checks[2];
    assert_eq!(payload.status, "FAIL", "{payload:?}");
    assert!(payload.bottleneck.is_some(), "{payload:?}");
}

#[test]
fn bad_requests_are_unknown_with_the_reason() {
    let mut place = pick([0.5, 0.0, 0.75], None);
    place.task_type = "place".into();
    let response = run_pick_task(&place, &options());
    assert_eq!(response.overall_status, "UNKNOWN");
    assert!(response.sub_checks[0].reason.contains("'place'"));

    let mut orientation = pick([0.5, 0.0, 0.75], None);
    orientation.target_orientation = Some(TargetOrientation::Values(vec![1.0, 2.0]));
    let response = run_pick_task(&orientation, &options());
    assert_eq!(response.overall_status, "UNKNOWN");
    assert!(
        response.sub_checks[0].reason.contains("2 numbers"),
        "{response:?}"
    );
}

#[test]
fn a_sloped_terrain_is_flagged_as_not_analysed() {
    let mut request = pick([0.5, 0.0, 0.75], None);
    request.terrain_angle_deg = 10.0;
    let response = run_pick_task(&request, &options());
    assert_eq!(status(&response, "terrain_gravity"), "UNKNOWN");
    assert!(response.terrain_note.is_some());
    assert_eq!(response.overall_status, "UNKNOWN");
}

#[test]
fn requests_and_responses_use_the_spec_field_names() {
    let request: TaskQueryRequest = serde_json::from_str(
        r#"{"urdf_path": "r.urdf", "task_type": "pick", "target_position": [0.5, 0, 0.8],
            "target_orientation": [1, 0, 0, 0], "object_mass_kg": 0.5}"#,
    )
    .expect("request");
    assert_eq!(
        request.target_orientation,
        Some(TargetOrientation::Values(vec![1.0, 0.0, 0.0, 0.0]))
    );
    assert_eq!(request.terrain_angle_deg, 0.0);
    let untyped: TaskQueryRequest =
        serde_json::from_str(r#"{"urdf_path": "r.urdf"}"#).expect("request without task_type");
    assert_eq!(untyped.task_type, "pick");
    let response = serde_json::to_value(run_pick_task(&request, &options())).expect("json");
    for key in [
        "task_type",
        "overall_status",
        "sub_checks",
        "terrain_angle_deg",
        "terrain_note",
    ] {
        assert!(response.get(key).is_some(), "{key} missing: {response}");
    }
}
