//! Parse + tree + every check on real robots (`cargo bench -p urdf-validator`).
//!
//! The whole pipeline runs (rules, statics, classification, stability); mesh resolution and loading are
//! included, as in a real run.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::{Path, PathBuf};

use urdf_validator::analysis::workspace::chain::{ArmChain, Samples, BATCH};
use urdf_validator::analysis::workspace::{CollisionSetup, Scene, WorkspaceOptions};
use urdf_validator::model::kinematics::{forward_kinematics, Data};
use urdf_validator::model::Model;
use urdf_validator::urdf::parse::parse_urdf;
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

/// A 7-DOF serial arm written out in code: alternating z / y axes, 0.15 m links, 1.5 kg each.
fn seven_dof_arm() -> String {
    let mut urdf = String::from(r#"<robot name="arm7"><link name="base"/>"#);
    let mut parent = "base".to_string();
    for i in 1..=7 {
        let axis = if i % 2 == 1 { "0 0 1" } else { "0 1 0" };
        urdf.push_str(&format!(
            r#"<joint name="j{i}" type="revolute"><parent link="{parent}"/><child link="l{i}"/>
  <origin xyz="0 0 0.15" rpy="0 0.1 0"/><axis xyz="{axis}"/><limit lower="-2.9" upper="2.9" effort="80" velocity="2"/></joint>
<link name="l{i}"><inertial><origin xyz="0.01 0 0.07"/><mass value="1.5"/>
  <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.005"/></inertial></link>"#
        ));
        parent = format!("l{i}");
    }
    urdf.push_str("</robot>");
    urdf
}

fn bench_gravity(bencher: divan::Bencher, text: &str) {
    let (robot, _) =
        urdf_validator::urdf::parse::parse_urdf(text, Path::new("bench.urdf")).expect("parses");
    let (model, _) = urdf_validator::model::Model::build(&robot);
    let mut data = urdf_validator::analysis::statics::gravity::StaticsData::new(&model);
    let mut q = model.zero_configuration();
    q.iter_mut()
        .enumerate()
        .for_each(|(i, v)| *v = 0.1 * i as f64);
    bencher.bench_local(|| {
        urdf_validator::analysis::statics::gravity::evaluate(
            &model,
            divan::black_box(&q),
            &mut data,
        );
        data.torque[0]
    });
}

/// Forward kinematics + subtree sums + gravity torques of every joint, one configuration.
#[divan::bench]
fn gravity_torques_7dof(bencher: divan::Bencher) {
    bench_gravity(bencher, &seven_dof_arm());
}

/// The same on PR2 (88 links, 87 joints).
#[divan::bench]
fn gravity_torques_pr2(bencher: divan::Bencher) {
    let (_, text) = robot("pr2/pr2_description/robots/pr2.urdf");
    bench_gravity(bencher, &text);
}

/// PR2 with a cold mesh cache: every mesh read, parsed and reduced to its hull (the other robot benches
/// reuse one `Options`, so their meshes are cached after the first iteration, as in a batch run).
#[divan::bench(sample_count = 10)]
fn pr2_with_meshes_cold(bencher: divan::Bencher) {
    let (path, text) = robot("pr2/pr2_description/robots/pr2.urdf");
    bencher.bench(|| {
        validate_text(divan::black_box(text.clone()), &path, &Options::default())
            .map(|v| v.report.findings.len())
    });
}

/// Random configurations of `chain`'s sampled joints, uniform within their intervals.
fn chain_samples(chain: &ArmChain, count: usize) -> Vec<Vec<f64>> {
    let mut rng = urdf_validator::rng::SplitMix64::new(1);
    (0..count)
        .map(|_| {
            chain
                .sampled
                .iter()
                .map(|(_, lo, hi)| rng.uniform(*lo, *hi))
                .collect()
        })
        .collect()
}

/// Workspace forward kinematics of a 7-DOF chain, 1,000 configurations per iteration (divan reports the
/// throughput per core): the tip position (reach), or with the approach axis too (orientation queries).
#[divan::bench(counters = [divan::counter::ItemsCount::new(1000usize)], args = [false, true])]
fn tip_kinematics_7dof(bencher: divan::Bencher, with_approach: bool) {
    let text = seven_dof_arm();
    let (robot, _) = parse_urdf(&text, Path::new("bench.urdf")).expect("parses");
    let (model, _) = Model::build(&robot);
    let q = model.zero_configuration();
    let mut data = Data::new(&model);
    forward_kinematics(&model, &q, &mut data);
    let (base, tip) = (model.link("base").unwrap(), model.link("l7").unwrap());
    let arm = urdf_validator::analysis::arms::declared(&robot, &model, base, tip).expect("an arm");
    let chain = ArmChain::new(&model, &arm, &data, &q);
    let samples = chain_samples(&chain, 1000);
    let approach = nalgebra::Vector3::z();
    bencher.bench_local(|| {
        samples
            .chunks(BATCH)
            .map(|batch| {
                let lanes: [&[f64]; BATCH] =
                    std::array::from_fn(|k| divan::black_box(batch[k % batch.len()].as_slice()));
                let poses = chain.tips(&Samples::Rows(&lanes), with_approach.then_some(&approach));
                poses
                    .iter()
                    .map(|p| p.position.x + p.approach.x)
                    .sum::<f64>()
            })
            .sum::<f64>()
    });
}

/// The whole PR2 workspace: both arms, 30,000 samples each, reach metrics and self-collision of every
/// moving pair (the collision model and mesh hulls are built once, outside the timing, as the other
/// sections share them); `false`: reach metrics only.
#[divan::bench(sample_count = 10, args = [true, false])]
fn pr2_workspace(bencher: divan::Bencher, self_collision: bool) {
    let (path, text) = robot("pr2/pr2_description/robots/pr2.urdf");
    let (robot, _) = parse_urdf(&text, &path).expect("parses");
    let (model, _) = Model::build(&robot);
    let options = Options::default();
    let assets = urdf_validator::assets::Assets::load(
        &robot,
        &urdf_validator::assets::AssetSource {
            urdf_path: &path,
            resolver: &options.resolver,
            meshes: &options.meshes,
            srdf: None,
        },
    );
    let q = model.zero_configuration();
    let mut data = Data::new(&model);
    forward_kinematics(&model, &q, &mut data);
    let classification =
        urdf_validator::analysis::classify::classify(&robot, &model, &data, &assets.supports);
    let collision =
        CollisionSetup::new(&robot, &model, &data, &assets.supports, &Default::default());
    let scene = Scene {
        robot: &robot,
        model: &model,
        q: &q,
        data: &data,
        ground: classification.ground_z.unwrap_or(0.0),
        support_polygon: &[],
        robot_type: classification.robot_type,
        payload: None,
    };
    let workspace = WorkspaceOptions::default();
    bencher.bench_local(|| {
        urdf_validator::analysis::workspace::analyse(
            &scene,
            &classification.arms,
            self_collision.then_some(&collision),
            &workspace,
        )
        .self_collision_free_fraction
    });
}

/// The stages of PR2 one by one: parse (XML → Robot), model (tree, mimic order, joint data), assets (every
/// mesh resolved, read and hulled: a fresh in-memory cache per iteration, no disk cache).
mod pr2_stages {
    use super::*;
    use urdf_validator::assets::{AssetSource, Assets};
    use urdf_validator::input::mesh::MeshCache;

    const PR2: &str = "pr2/pr2_description/robots/pr2.urdf";

    #[divan::bench]
    fn parse(bencher: divan::Bencher) {
        let (path, text) = robot(PR2);
        bencher.bench(|| parse_urdf(divan::black_box(&text), &path).map(|(r, _)| r.links.len()));
    }

    #[divan::bench]
    fn model(bencher: divan::Bencher) {
        let (path, text) = robot(PR2);
        let (robot, _) = parse_urdf(&text, &path).expect("parses");
        bencher.bench(|| {
            Model::build(divan::black_box(&robot))
                .0
                .topological_order
                .len()
        });
    }

    #[divan::bench(sample_count = 10)]
    fn assets_cold(bencher: divan::Bencher) {
        let (path, text) = robot(PR2);
        let (robot, _) = parse_urdf(&text, &path).expect("parses");
        let options = Options::default();
        bencher.bench(|| {
            let meshes = MeshCache::new();
            let source = AssetSource {
                urdf_path: &path,
                resolver: &options.resolver,
                meshes: &meshes,
                srdf: None,
            };
            Assets::load(&robot, &source).supports.len()
        });
    }
}

/// A chain of `links` revolute joints (limits ±1 rad) from `l{i}` to `l{i+1}`: every link holds `body`,
/// every joint `joint` (its origin and axis).
fn chain(links: usize, body: &str, joint: &str) -> String {
    let mut urdf = String::from("<robot name=\"chain\">");
    for i in 0..=links {
        urdf.push_str(&format!("<link name=\"l{i}\">{body}</link>"));
    }
    for i in 0..links {
        urdf.push_str(&format!(
            "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{i}\"/><child link=\"l{}\"/>\
             {joint}<limit lower=\"-1\" upper=\"1\" effort=\"100\" velocity=\"1\"/></joint>",
            i + 1
        ));
    }
    urdf.push_str("</robot>");
    urdf
}

/// The whole pipeline on `text`, as `chain.urdf`.
fn bench_pipeline(bencher: divan::Bencher, text: String) {
    let options = Options::default();
    bencher.bench(|| {
        validate_text(text.clone(), Path::new("chain.urdf"), &options)
            .map(|v| v.report.findings.len())
    });
}

/// A chain of 1 cm boxes 2 cm apart, bending by up to 1 rad: the whole pipeline should cost about linearly
/// more with the links (self-collision uses sweep-and-prune).
#[divan::bench(args = [100, 1000], sample_count = 5)]
fn box_chain_pipeline(bencher: divan::Bencher, links: usize) {
    let body = "<inertial><mass value=\"0.1\"/><inertia ixx=\"1e-4\" ixy=\"0\" ixz=\"0\" iyy=\"1e-4\" iyz=\"0\" izz=\"1e-4\"/></inertial>\
                <collision><geometry><box size=\"0.01 0.01 0.01\"/></geometry></collision>";
    let joint = "<origin xyz=\"0 0 0.02\"/><axis xyz=\"0 1 0\"/>";
    bench_pipeline(bencher, chain(links, body, joint));
}

/// A chain of 10 g links lying on the ground, joints 1 mm apart along x, no geometry (issue 26:
/// classification walked every link's names up to the body, quadratic). Budget: 1,000 and 20,000 links ≤ 25×
/// apart, the long one in ≤ 2 s on two cores.
#[divan::bench(args = [1000, 20000], sample_count = 3)]
fn lying_chain_pipeline(bencher: divan::Bencher, links: usize) {
    let body = "<inertial><mass value=\"0.01\"/><inertia ixx=\"1e-6\" ixy=\"0\" ixz=\"0\" iyy=\"1e-6\" iyz=\"0\" izz=\"1e-6\"/></inertial>";
    let joint = "<origin xyz=\"0.001 0 0\"/><axis xyz=\"0 0 1\"/>";
    bench_pipeline(bencher, chain(links, body, joint));
}
