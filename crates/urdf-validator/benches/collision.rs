//! Self-collision checks on PR2 arm poses (`cargo bench -p urdf-validator --bench collision`).
//!
//! Each arm's 7 joints are sampled uniformly within their limits (continuous joints over a full turn), the
//! rest of the robot stays at the zero pose. Forward kinematics is done up front, so `check_*` measures the
//! collision check alone; `fk_and_check` measures both, as a sampling loop runs them. One iteration runs
//! all the poses of a set: divide the time by 1024, or read the throughput.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::{Path, PathBuf};

use nalgebra::Isometry3;
use urdf_validator::analysis::collision::{Allowed, CheckScratch, CollisionModel, PairSet};
use urdf_validator::input::mesh::MeshCache;
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::model::kinematics::{forward_kinematics, Configuration, Data};
use urdf_validator::model::{JointId, Model};
use urdf_validator::rng::SplitMix64;

fn main() {
    divan::main();
}

/// Poses per benchmark set (the iterations cycle through them).
const POSES: usize = 1024;

/// `pr2.urdf` from `URDF_VALIDATOR_SHARED_ROBOTS` or `../shared/robots`.
fn pr2_path() -> Option<PathBuf> {
    let root = std::env::var_os("URDF_VALIDATOR_SHARED_ROBOTS")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/robots"));
    let path = root.join("pr2/pr2_description/robots/pr2.urdf");
    path.is_file().then_some(path)
}

struct Arm {
    model: Model,
    collision: CollisionModel,
    pairs: PairSet,
    configurations: Vec<Configuration>,
    placements: Vec<Vec<Isometry3<f64>>>,
    /// The smallest clearance over the poses: the cutoff a long sampling run converges to.
    steady_cutoff: f64,
}

fn arm(side: &str) -> Option<Arm> {
    let Some(path) = pr2_path() else {
        eprintln!("skipping: ../shared/robots/pr2 is absent (set URDF_VALIDATOR_SHARED_ROBOTS)");
        return None;
    };
    let text = std::fs::read_to_string(&path).ok()?;
    let (robot, _) = urdf_validator::urdf::parse::parse_urdf(&text, &path).ok()?;
    let (model, _) = Model::build(&robot);
    let meshes = MeshCache::new();
    let resolver = PackageResolver::default();
    let assets = urdf_validator::assets::Assets::load(
        &robot,
        &urdf_validator::assets::AssetSource {
            urdf_path: &path,
            resolver: &resolver,
            meshes: &meshes,
            srdf: None,
        },
    );
    let mut collision = CollisionModel::build(&robot, &model, &assets.supports);
    let mut data = Data::new(&model);
    forward_kinematics(&model, &model.zero_configuration(), &mut data);
    let touching = collision.touching_pairs(&data.link_placement);
    collision.allow(&touching, Allowed::Touching);
    let joints: Vec<JointId> = [
        "shoulder_pan",
        "shoulder_lift",
        "upper_arm_roll",
        "elbow_flex",
        "forearm_roll",
        "wrist_flex",
        "wrist_roll",
    ]
    .iter()
    .filter_map(|j| model.joint(&format!("{side}_{j}_joint")))
    .collect();
    let pairs = collision.pairs_moved_by(&model.motion_of(&joints));
    let mut rng = SplitMix64::new(7);
    let mut configurations = Vec::with_capacity(POSES);
    let mut placements = Vec::with_capacity(POSES);
    for _ in 0..POSES {
        let mut q = model.zero_configuration();
        for joint in &joints {
            let (lo, hi) = model.joint_data[joint.0]
                .range()
                .unwrap_or((-std::f64::consts::PI, std::f64::consts::PI));
            q[joint.0] = rng.uniform(lo, hi);
        }
        forward_kinematics(&model, &q, &mut data);
        placements.push(data.link_placement.clone());
        configurations.push(q);
    }
    let mut scratch = CheckScratch::new(&collision);
    let mut steady_cutoff = f64::INFINITY;
    let mut free = 0;
    for p in &placements {
        let check = collision.check(&pairs, p, steady_cutoff, &mut scratch);
        free += usize::from(check.is_free());
        if let Some((d, _)) = check.min_clearance {
            steady_cutoff = d;
        }
    }
    eprintln!(
        "PR2 {side} arm: {} pairs, {} touching at zero, {free}/{POSES} poses free, min clearance {:.4} m",
        pairs.len(),
        touching.len(),
        steady_cutoff
    );
    Some(Arm {
        model,
        collision,
        pairs,
        configurations,
        placements,
        steady_cutoff,
    })
}

fn bench_check(bencher: divan::Bencher, cutoff: impl Fn(&Arm) -> f64) {
    let Some(arm) = arm("l") else { return };
    let cutoff = cutoff(&arm);
    let mut scratch = CheckScratch::new(&arm.collision);
    bencher
        .counter(divan::counter::ItemsCount::new(POSES))
        .bench_local(|| {
            arm.placements
                .iter()
                .map(|p| {
                    arm.collision
                        .check(&arm.pairs, p, cutoff, &mut scratch)
                        .is_free()
                })
                .filter(|free| *free)
                .count()
        });
}

/// One left-arm pose, with the cutoff a long run converges to (the usual case).
#[divan::bench]
fn check_pr2_arm_steady(bencher: divan::Bencher) {
    bench_check(bencher, |arm| arm.steady_cutoff);
}

/// One left-arm pose with no cutoff: every pair's distance is computed (the first poses of a run).
#[divan::bench]
fn check_pr2_arm_no_cutoff(bencher: divan::Bencher) {
    bench_check(bencher, |_| f64::INFINITY);
}

/// One left-arm pose, contacts only (no clearance).
#[divan::bench]
fn check_pr2_arm_contacts_only(bencher: divan::Bencher) {
    bench_check(bencher, |_| 0.0);
}

/// Forward kinematics of the whole robot plus the check, as a sampling loop runs them.
#[divan::bench]
fn fk_and_check_pr2_arm(bencher: divan::Bencher) {
    let Some(arm) = arm("r") else { return };
    let mut scratch = CheckScratch::new(&arm.collision);
    let mut data = Data::new(&arm.model);
    bencher
        .counter(divan::counter::ItemsCount::new(POSES))
        .bench_local(|| {
            arm.configurations
                .iter()
                .map(|q| {
                    forward_kinematics(&arm.model, q, &mut data);
                    arm.collision
                        .check(
                            &arm.pairs,
                            &data.link_placement,
                            arm.steady_cutoff,
                            &mut scratch,
                        )
                        .is_free()
                })
                .filter(|free| *free)
                .count()
        });
}

/// Building the collision model of PR2 (meshes already cached) and its allowed-collision matrix.
#[divan::bench(sample_count = 20)]
fn build_pr2(bencher: divan::Bencher) {
    let Some(path) = pr2_path() else { return };
    let text = std::fs::read_to_string(&path).unwrap_or_default();
    let Ok((robot, _)) = urdf_validator::urdf::parse::parse_urdf(&text, &path) else {
        return;
    };
    let (model, _) = Model::build(&robot);
    let meshes = MeshCache::new();
    let resolver = PackageResolver::default();
    let Some(urdf_dir) = path.parent() else {
        return;
    };
    let assets = urdf_validator::assets::Assets::load(
        &robot,
        &urdf_validator::assets::AssetSource {
            urdf_path: &urdf_dir.join("robot.urdf"),
            resolver: &resolver,
            meshes: &meshes,
            srdf: None,
        },
    );
    bencher.bench_local(|| CollisionModel::build(&robot, &model, &assets.supports));
}
