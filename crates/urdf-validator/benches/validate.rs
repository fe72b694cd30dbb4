//! Parse + tree + every check on real robots (`cargo bench -p urdf-validator`).
//!
//! Mesh resolution is part of the checks, so file-system lookups are included, as in a real run.

use std::path::{Path, PathBuf};

use urdf_validator::{validate_text, Options};

fn main() {
    divan::main();
}

/// The reference robots, or the repo's example robot when `../shared` is absent.
fn robot(relative: &str) -> (PathBuf, String) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let shared = root.join("../shared/robots").join(relative);
    let path = if shared.is_file() {
        shared
    } else {
        root.join("examples/robots/mobile_manipulator.urdf")
    };
    let text = std::fs::read_to_string(&path).unwrap_or_default();
    (path, text)
}

fn bench_robot(bencher: divan::Bencher, relative: &str) {
    let (path, text) = robot(relative);
    let options = Options::default();
    bencher.bench(|| {
        validate_text(divan::black_box(text.clone()), &path, &options)
            .map(|v| v.report.findings.len())
    });
}

#[divan::bench]
fn pr2(bencher: divan::Bencher) {
    bench_robot(bencher, "pr2/pr2_description/robots/pr2.urdf");
}

#[divan::bench]
fn fetch(bencher: divan::Bencher) {
    bench_robot(bencher, "fetch/fetch_description/robots/fetch.urdf");
}

#[divan::bench]
fn turtlebot3(bencher: divan::Bencher) {
    bench_robot(
        bencher,
        "turtlebot3/turtlebot3_description/urdf/turtlebot3_burger.urdf",
    );
}
