//! Embeds the seed models of the `mjcf` and `sdf` targets (`seeds/<format>/models/<seed>/`, every file of
//! each folder) in the binaries, so a target runs, and a finding reproduces, wherever the binary is.

use std::fmt::Write;
use std::path::{Path, PathBuf};

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("dir entry").path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            files(&path, out);
        } else {
            out.push(path);
        }
    }
}

fn main() {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("manifest dir")).join("seeds");
    let mut code = String::new();
    for (format, main) in [("mjcf", "model.xml"), ("sdf", "model.sdf")] {
        let dir = root.join(format).join("models");
        println!("cargo:rerun-if-changed={}", dir.display());
        let mut seeds: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.expect("dir entry").path())
            .filter(|p| p.is_dir())
            .collect();
        seeds.sort();
        writeln!(code, "pub static {}: &[Seed] = &[", format.to_uppercase()).unwrap();
        for seed in seeds {
            let name = seed.file_name().unwrap().to_str().expect("UTF-8 seed name");
            assert!(seed.join(main).is_file(), "{} has no {main}", seed.display());
            let mut all = Vec::new();
            files(&seed, &mut all);
            writeln!(code, "    Seed {{ name: {name:?}, main: {main:?}, files: &[").unwrap();
            for file in all {
                let rel = file.strip_prefix(&seed).unwrap().to_str().expect("UTF-8 path");
                let abs = file.to_str().expect("UTF-8 path");
                writeln!(code, "        ({rel:?}, include_bytes!({abs:?})),").unwrap();
            }
            writeln!(code, "    ] }},").unwrap();
        }
        writeln!(code, "];").unwrap();
    }
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("out dir")).join("seeds.rs");
    std::fs::write(out, code).expect("write seeds.rs");
}
