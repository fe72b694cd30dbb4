//! Print the detected robot type and arm chains of each URDF given on the command line (a development aid
//! for the classification and arm-detection heuristics): `cargo run --example classify -- a.urdf b.urdf`.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::Path;

use urdf_validator::analysis::classify;
use urdf_validator::assets::{AssetSource, Assets};
use urdf_validator::model::kinematics::{forward_kinematics, Data};
use urdf_validator::{input, model::Model, urdf::parse, Options};

fn main() {
    let options = Options {
        resolver: urdf_validator::input::resolve::PackageResolver::from_env(Vec::new()),
        ..Options::default()
    };
    for arg in std::env::args().skip(1) {
        let path = Path::new(&arg);
        let text = match input::read_text(path) {
            Ok(text) => text,
            Err(e) => {
                eprintln!("{e}");
                continue;
            }
        };
        let Ok((robot, _)) = parse::parse_urdf(&text, path) else {
            eprintln!("{arg}: not parsed");
            continue;
        };
        let (model, _) = Model::build(&robot);
        let assets = Assets::load(
            &robot,
            &AssetSource {
                urdf_path: path,
                resolver: &options.resolver,
                meshes: &options.meshes,
                srdf: None,
            },
        );
        let mut data = Data::new(&model);
        forward_kinematics(&model, &model.zero_configuration(), &mut data);
        let c = classify::classify(&robot, &model, &data, &assets.supports);
        println!("{arg}: {} ({})", c.robot_type.as_str(), c.evidence);
        for w in &c.wheels {
            println!("  wheel {}", robot.links[w.0].name.value);
        }
        for leg in &c.legs {
            println!("  leg from {}", robot.joints[leg.top_joint.0].name.value);
        }
        for arm in &c.arms {
            let first = arm
                .first_joint(&model)
                .map_or("-", |j| robot.joints[j.0].name.value.as_str());
            println!(
                "  arm {} -> {} (first joint {first}, {} dof, hand {}, {} finger links)",
                robot.links[arm.base.0].name.value,
                robot.links[arm.tip.0].name.value,
                arm.sampled_joints(&model).len(),
                arm.hand
                    .map_or("-", |h| robot.links[h.0].name.value.as_str()),
                arm.fingers.len()
            );
        }
    }
}
