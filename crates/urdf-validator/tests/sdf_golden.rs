//! The SDFormat reader against Drake (`scripts/oracle/sdf_golden.py`, drake 1.51.1): total mass, centre of
//! mass in the world frame and the gravity torque of every revolute and prismatic joint, at the zero
//! configuration and two seeded random ones, on every model under `tests/data/sdf/golden`, to 1e-9. Drake
//! reads the SDF with libsdformat, so this checks our pose semantics (relative_to, frames, expressed_in,
//! legacy 1.4–1.6 axes, nested models) end to end. A golden may carry `mass_com_not_compared` with the
//! reason its mass and COM differ by design; its torques are compared.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::{Path, PathBuf};

use serde_json::Value;
use urdf_validator::analysis::statics::gravity::{evaluate, mass_and_com, StaticsData};
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::input::Loaded;
use urdf_validator::model::Model;

const TOLERANCE: f64 = 1e-9;

fn close(ours: f64, golden: f64) -> bool {
    (ours - golden).abs() <= TOLERANCE * golden.abs().max(1.0)
}

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/sdf")
}

/// Compare `sdf` (read by us, `model://` found in `model_paths`) with the configurations of `golden`,
/// after moving the world by `shift`; returns the number of values compared.
fn compare(sdf: &Path, golden: &Value, shift: [f64; 3], model_paths: Vec<PathBuf>) -> usize {
    let loaded = Loaded::read(sdf, &[], &PackageResolver::new(model_paths, None, None)).unwrap();
    let (robot, findings) =
        urdf_validator::sdf::parse_sdf(loaded.sdf().expect("SDFormat"), None).unwrap();
    let critical: Vec<_> = findings
        .iter()
        .filter(|f| f.severity() == urdf_validator::diagnostics::Severity::Critical)
        .map(|f| &f.message)
        .collect();
    assert!(critical.is_empty(), "{}: {critical:?}", sdf.display());
    let (model, _) = Model::build(&robot);
    let mut data = StaticsData::new(&model);
    let source = sdf.display();
    let mut checked = 0;
    for configuration in golden["configurations"].as_array().unwrap() {
        let label = configuration["label"].as_str().unwrap();
        let mut q = model.zero_configuration();
        for (name, value) in configuration["q"].as_object().unwrap() {
            let joint = model
                .joint(name)
                .unwrap_or_else(|| panic!("{source}: no joint {name}"));
            q[joint.0] = value.as_f64().unwrap();
        }
        evaluate(&model, &q, &mut data);
        for (name, value) in configuration["gravity_torque"].as_object().unwrap() {
            let joint = model.joint(name).unwrap();
            let (ours, theirs) = (data.raw_torque[joint.0], value.as_f64().unwrap());
            assert!(
                close(ours, theirs),
                "{source} [{label}] joint {name}: ours {ours}, Drake {theirs}"
            );
            checked += 1;
        }
        if golden["mass_com_not_compared"].is_string() {
            continue; // A documented difference (see the golden file); the torques were compared.
        }
        let (mass, com) = mass_and_com(&model, &data);
        let golden_mass = configuration["total_mass"].as_f64().unwrap();
        assert!(
            close(mass, golden_mass),
            "{source} [{label}] mass {mass} vs {golden_mass}"
        );
        let com = com.expect("a centre of mass");
        for axis in 0..3 {
            let theirs = configuration["com"][axis].as_f64().unwrap() + shift[axis];
            assert!(
                close(com[axis], theirs),
                "{source} [{label}] COM[{axis}] ours {} vs Drake {theirs}",
                com[axis]
            );
        }
        checked += 4;
    }
    checked
}

fn golden(stem: &str) -> Value {
    let path = data().join("golden").join(format!("{stem}.json"));
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

#[test]
fn mass_com_and_gravity_torques_equal_drake() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(data().join("golden"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "goldens: {files:?}");
    let mut checked = 0;
    for file in &files {
        let stem = file.file_stem().unwrap().to_str().unwrap();
        let golden = golden(stem);
        let sdf = data().join(golden["source"].as_str().unwrap());
        checked += compare(&sdf, &golden, [0.0; 3], Vec::new());
    }
    eprintln!("compared {checked} values against Drake");
}

#[test]
fn an_included_model_reads_as_the_model_itself_moved_by_the_include_pose() {
    // includes/world.sdf includes models/nested_arm_model (model.config → model.sdf, a copy of
    // nested_arm.sdf) with <pose>0.5 -1 0.25 0 0 0</pose> and a new <name>: the same torques, the COM
    // moved by the pose.
    let golden = golden("nested_arm");
    let includes = data().join("includes");
    let checked = compare(
        &includes.join("world.sdf"),
        &golden,
        [0.5, -1.0, 0.25],
        vec![includes.join("models")],
    );
    assert!(checked > 0);
}
