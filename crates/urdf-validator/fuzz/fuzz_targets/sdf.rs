//! SDFormat, structure-aware: the input picks a seed model of `seeds/sdf/models/` and a program of edits
//! to its XML tree (`urdf_validator_fuzz::mutate`); the mutated `model.sdf` is validated in a folder
//! holding the seed's included models (`model://` folders beside it, relative paths) and meshes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use urdf_validator_fuzz::{run, Format};

fuzz_target!(|data: &[u8]| run(Format::Sdf, data));
