//! Expansion speed on PR2 (`../shared/robots/pr2`, 53 files, ~2,000 output elements).
//! `scripts/bench-xacro.sh` compares it with Python xacro.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::PathBuf;

fn pr2() -> Option<PathBuf> {
    let robots = std::env::var_os("URDF_VALIDATOR_SHARED_ROBOTS")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/robots")
        });
    let file = robots.join("pr2/pr2_description/robots/pr2.urdf.xacro");
    file.is_file().then_some(file)
}

fn main() {
    if pr2().is_none() {
        eprintln!("SKIP: pr2.urdf.xacro not found (set URDF_VALIDATOR_SHARED_ROBOTS)");
        return;
    }
    divan::main();
}

#[divan::bench(sample_count = 50)]
fn expand_pr2(bencher: divan::Bencher) {
    let Some(file) = pr2() else { return };
    let opts = xacro::Options::default();
    bencher.bench(|| xacro::expand_file(divan::black_box(&file), &opts).map(|x| x.xml.len()));
}
