//! The task sweep over the example robot that ships with the repository: answers in order, a request
//! that cannot run isolated, each robot with its own configuration file.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::{Path, PathBuf};

use urdf_validate_session::tasks::pick_sweep;
use urdf_validate_session::Request;
use urdf_validator::input::mesh::MeshCache;
use urdf_validator::task_query::{TargetOrientation, TaskQueryRequest};

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/robots/mobile_manipulator.urdf")
}

fn pick(urdf_path: PathBuf, target: [f64; 3]) -> TaskQueryRequest {
    TaskQueryRequest {
        urdf_path,
        task_type: "pick".into(),
        target_position: Some(target),
        target_orientation: Some(TargetOrientation::Named("top_down".into())),
        object_mass_kg: None,
        terrain_angle_deg: 0.0,
    }
}

#[test]
fn a_sweep_keeps_order_and_isolates_a_missing_file() {
    let request = Request {
        samples: Some(3000),
        no_config: true,
        ..Request::default()
    };
    let queries = vec![
        pick(example(), [0.5, 0.0, 0.75]),
        pick(PathBuf::from("/nonexistent/robot.urdf"), [0.5, 0.0, 0.75]),
        pick(example(), [3.0, 0.0, 0.75]),
    ];
    let responses = pick_sweep(&request, &queries, &MeshCache::new()).expect("responses");
    assert_eq!(responses.len(), 3);
    assert_eq!(responses[0].overall_status, "PASS");
    assert_eq!(responses[1].overall_status, "UNKNOWN");
    assert_eq!(responses[1].sub_checks[0].name, "urdf_load");
    assert!(responses[1].sub_checks[0]
        .reason
        .contains("/nonexistent/robot.urdf"));
    assert_eq!(responses[2].overall_status, "FAIL");
}

#[test]
fn each_robot_is_answered_with_its_own_configuration_file() {
    let dir = std::env::temp_dir().join(format!("pick-sweep-config-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let copy = dir.join("robot.urdf");
    let text = std::fs::read_to_string(example()).unwrap();
    // The example's meshes are primitives: the copy validates as the original does.
    std::fs::write(&copy, text).unwrap();
    // Beside the copy, a configuration that makes the sampling too coarse for the reach to be found.
    std::fs::write(dir.join("urdf-validate.toml"), "samples = 1\n").unwrap();
    let request = Request::default();
    let queries = vec![
        pick(example(), [0.5, 0.0, 0.75]),
        pick(copy.clone(), [0.5, 0.0, 0.75]),
    ];
    let responses = pick_sweep(&request, &queries, &MeshCache::new()).expect("responses");
    assert_eq!(responses[0].overall_status, "PASS", "{:?}", responses[0]);
    assert_ne!(
        responses[0], responses[1],
        "the copy's configuration (samples = 1) applies to it alone"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
