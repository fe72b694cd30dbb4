//! MJCF, structure-aware: the input picks a seed model of `seeds/mjcf/models/` and a program of edits to
//! its XML tree (`urdf_validator_fuzz::mutate`); the mutated `model.xml` is validated in a folder holding
//! the seed's includes and meshes (the whole pipeline: MJCF reading, rules, physics, statics, stability,
//! workspace with 16 samples, self-collision), with a resolver without package paths.
#![no_main]

use libfuzzer_sys::fuzz_target;
use urdf_validator_fuzz::{run, Format};

fuzz_target!(|data: &[u8]| run(Format::Mjcf, data));
