//! Forward kinematics, mass, centre of mass and gravity torques against Pinocchio's golden values
//! (`scripts/oracle/pinocchio_goldens.py`, pin 4.1.0) on every example-robot-data robot Pinocchio loads:
//! the zero pose and 10 seeded random configurations each, to 1e-9.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::path::Path;

use serde_json::Value;
use urdf_validator::analysis::statics::gravity::{evaluate, mass_and_com, StaticsData};
use urdf_validator::model::Model;
use urdf_validator::urdf::parse::parse_urdf;

const TOLERANCE: f64 = 1e-9;

fn close(ours: f64, golden: f64) -> bool {
    (ours - golden).abs() <= TOLERANCE * golden.abs().max(1.0)
}

fn golden_files() -> Vec<std::path::PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/pinocchio");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .expect("golden folder")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "json") && !p.ends_with("index.json"))
        .collect();
    files.sort();
    files
}

/// Compare one golden file; returns the number of values checked.
fn check_golden(corpus: &Path, golden_path: &Path) -> usize {
    let golden: Value =
        serde_json::from_str(&std::fs::read_to_string(golden_path).unwrap()).unwrap();
    let source = golden["source"].as_str().unwrap();
    let urdf = corpus.join(source);
    let text = std::fs::read_to_string(&urdf).unwrap();
    let (robot, _) = parse_urdf(&text, &urdf).unwrap();
    let (model, _) = Model::build(&robot);
    let mut data = StaticsData::new(&model);
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
                "{source} [{label}] joint {name}: ours {ours}, Pinocchio {theirs}"
            );
            checked += 1;
        }
        if let Some(positions) = configuration["link_positions"].as_object() {
            for (name, value) in positions {
                let link = model.link(name).unwrap();
                let ours = data.kinematics.link_placement[link.0].translation.vector;
                for axis in 0..3 {
                    let theirs = value[axis].as_f64().unwrap();
                    assert!(
                        close(ours[axis], theirs),
                        "{source} [{label}] link {name}[{axis}]: {} vs {theirs}",
                        ours[axis]
                    );
                }
                checked += 1;
            }
        }
        let (mass, com) = mass_and_com(&model, &data);
        let golden_mass = configuration["total_mass"].as_f64().unwrap();
        assert!(
            close(mass, golden_mass),
            "{source} [{label}] total mass {mass} vs {golden_mass}"
        );
        if let (Some(com), Some(golden_com)) = (com, configuration["total_com"].as_array()) {
            for axis in 0..3 {
                let theirs = golden_com[axis].as_f64().unwrap();
                assert!(
                    close(com[axis], theirs),
                    "{source} [{label}] COM[{axis}] {} vs {theirs}",
                    com[axis]
                );
            }
        }
        checked += 2;
    }
    checked
}

#[test]
fn statics_equal_pinocchio_on_the_corpus() {
    let Some(corpus) = common::corpus() else {
        return;
    };
    let files = golden_files();
    assert_eq!(files.len(), 68, "goldens for the 68 robots Pinocchio loads");
    let checked: usize = files.iter().map(|f| check_golden(&corpus, f)).sum();
    assert!(checked > 10_000, "only {checked} values compared");
    eprintln!("compared {checked} values against Pinocchio");
}
