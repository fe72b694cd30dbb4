//! Mesh bytes → `load_mesh_with` through a temporary file. The first byte picks the format (extension)
//! the COLLADA up-axis policy and whose OBJ reading (Drake's or MuJoCo's); the rest is the file.
#![no_main]

use std::path::PathBuf;

use libfuzzer_sys::fuzz_target;
use urdf_validator::input::mesh::{load_mesh_with, MeshOptions, ObjReading, UpAxisPolicy};

fn path(ext: &str) -> PathBuf {
    std::env::temp_dir().join(format!("urdf-fuzz-mesh-{}.{ext}", std::process::id()))
}

fuzz_target!(|data: &[u8]| {
    let Some((&selector, bytes)) = data.split_first() else {
        return;
    };
    let ext = ["stl", "obj", "dae"][usize::from(selector % 3)];
    let up_axis = if selector & 0x80 == 0 {
        UpAxisPolicy::Honour
    } else {
        UpAxisPolicy::Ignore
    };
    let obj_reading = if selector & 0x40 == 0 {
        ObjReading::Drake
    } else {
        ObjReading::MuJoCo
    };
    let file = path(ext);
    std::fs::write(&file, bytes).expect("write temp mesh");
    let _ = load_mesh_with(
        &file,
        &MeshOptions {
            up_axis,
            obj_reading,
        },
    );
});
