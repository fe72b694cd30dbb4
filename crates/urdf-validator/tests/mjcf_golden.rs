//! The MJCF reader against MuJoCo itself: for every model of two corpora MuJoCo compiles (dm_control's
//! suite, `tests/golden/mujoco/*.json`; gymnasium's MuJoCo environments, `tests/golden/gymnasium/*.json`),
//! our total mass, per-body mass, world centres of mass and gravity torques (statics at the same joint
//! values) agree with MuJoCo's (written by `scripts/oracle/mjcf_goldens.py` with MuJoCo 4.0.0:
//! `body_mass`, `xipos`, `subtree_com` of the world, `qfrc_bias` at zero velocity, under standard gravity
//! whatever the model sets) at `qpos0` and at two seeded random configurations.
//!
//! Agreement: |ours − MuJoCo's| ≤ 1e-9 · max(|ours|, |MuJoCo's|) + floor, with floors of 1e-12 kg for
//! masses, 1e-12 m for positions and 1e-10 N·m (N) for torques (forces); each body's principal moments of
//! inertia (`body_inertia`) to 1e-7 (see [`INERTIA_RELATIVE`]): values near zero (a COM on an
//! axis, a torque about a vertical axis) are rounding noise in both. The models come from the
//! `dm-control==1.0.50` wheel (`URDF_VALIDATOR_MJCF_CORPUS`, the wheel's `dm_control/suite` folder) and
//! the `gymnasium==1.2.2` wheel (`URDF_VALIDATOR_GYMNASIUM_CORPUS`, its `gymnasium/envs/mujoco/assets`);
//! `scripts/setup-test-env.sh` unpacks both; under `CI=true` a missing corpus fails.
//!
//! A second test writes models that use what the suite does not (nested classes and childclass,
//! `<frame>`, every orientation form, `eulerseq`, several joints in one body, `ref`, ball and free joints,
//! welded and free top-level bodies, `inertiafromgeom`, `inertiagrouprange`, `boundmass`,
//! `boundinertia`, `balanceinertia`, `settotalmass`, meshes with `scale` and legacy/exact inertia,
//! unnamed bodies and joints, keyframes: a named one turning the ball joint, an unnamed short one) and
//! compares them with MuJoCo run now (the venv's `mujoco`); a third runs every keyframe of the mesh-free
//! Menagerie variants through MuJoCo (`--pose key:NAME` against the key's `qpos`).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use nalgebra::Vector3;
use serde_json::Value;
use urdf_validator::analysis::pose::{PoseKind, PoseOptions};
use urdf_validator::analysis::statics::gravity::{evaluate, StaticsData};
use urdf_validator::analysis::statics::{analyse, StaticsOptions};
use urdf_validator::input::mesh::MeshCache;
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::input::Loaded;
use urdf_validator::model::{LinkMass, Model};
use urdf_validator::report::StaticsSection;

const RELATIVE: f64 = 1e-9;
const MASS_FLOOR: f64 = 1e-12;
const POSITION_FLOOR: f64 = 1e-12;
const TORQUE_FLOOR: f64 = 1e-10;
/// Principal moments of inertia: MuJoCo turns each mesh into its principal frame with an iterative 3×3
/// eigen-solver (`mjuu_eig3`) before it sums a body's geoms, which moves them by up to 2e-8 relative
/// (dog's lower arms, made of bone meshes); primitives agree to 1e-9.
const INERTIA_RELATIVE: f64 = 1e-7;
const INERTIA_FLOOR: f64 = 1e-12;

/// A folder of MJCF models and the goldens `scripts/oracle/mjcf_goldens.py --models` wrote for it.
struct Corpus {
    /// What the models are (for messages).
    what: &'static str,
    /// The environment variable naming the models' folder.
    var: &'static str,
    /// Where `scripts/setup-test-env.sh` unpacks the models, relative to the repository.
    default: &'static str,
    /// The goldens' folder, relative to the repository.
    goldens: &'static str,
    /// How many goldens there are at least (a lost folder is a failure, not a vacuous pass).
    at_least: usize,
    /// Models compared with MuJoCo but not expected to agree, with the reason.
    excluded: &'static [(&'static str, &'static str)],
}

/// dm_control's suite (`dm-control==1.0.50`): `tests/golden/mujoco`.
const DM_CONTROL: Corpus = Corpus {
    what: "the dm_control suite models (dm-control==1.0.50 wheel)",
    var: "URDF_VALIDATOR_MJCF_CORPUS",
    default: "target/dm-control/dm_control/suite",
    goldens: "crates/urdf-validator/tests/golden/mujoco",
    at_least: 19,
    excluded: &[],
};

/// gymnasium's MuJoCo environments (`gymnasium==1.2.2`): `tests/golden/gymnasium`.
const GYMNASIUM: Corpus = Corpus {
    what: "gymnasium's MuJoCo models (gymnasium==1.2.2 wheel)",
    var: "URDF_VALIDATOR_GYMNASIUM_CORPUS",
    default: "target/gymnasium/gymnasium/envs/mujoco/assets",
    goldens: "crates/urdf-validator/tests/golden/gymnasium",
    at_least: 14,
    excluded: &[],
};

impl Corpus {
    fn goldens(&self) -> Vec<PathBuf> {
        let dir = common::repo_root().join(self.goldens);
        let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
            .expect("the MuJoCo goldens are committed")
            .map(|e| e.expect("entry").path())
            .filter(|p| p.extension().is_some_and(|e| e == "json"))
            .collect();
        files.sort();
        files
    }

    fn models(&self) -> Option<PathBuf> {
        common::data_dir(
            self.var,
            Some(common::repo_root().join(self.default)),
            self.what,
        )
    }

    /// Every golden's model agrees with MuJoCo, but the excluded ones (which must still differ).
    fn check(&self) {
        let Some(models) = self.models() else { return };
        let goldens = self.goldens();
        assert!(
            goldens.len() >= self.at_least,
            "expected {} goldens in {}, found {}",
            self.at_least,
            self.goldens,
            goldens.len()
        );
        let mut failures = Vec::new();
        let mut compared = 0;
        for golden_path in goldens {
            let golden: Value =
                serde_json::from_str(&std::fs::read_to_string(&golden_path).expect("read"))
                    .expect("json");
            let source = golden["source"].as_str().expect("source");
            let stem = golden_path
                .file_stem()
                .and_then(|s| s.to_str())
                .expect("stem");
            let model_path = models.join(source);
            assert!(model_path.is_file(), "{} is missing", model_path.display());
            let differences = compare(&model_path, &golden);
            let excluded = self.excluded.iter().find(|(name, _)| *name == stem);
            match (excluded, differences.is_empty()) {
                (None, true) => compared += 1,
                (None, false) => failures.push(format!(
                    "{stem}: {} difference(s):\n  {}",
                    differences.len(),
                    differences.join("\n  ")
                )),
                (Some((_, why)), true) => failures.push(format!(
                    "{stem} is excluded ({why}) but agrees now: take it off the list"
                )),
                (Some(_), false) => {}
            }
        }
        assert!(failures.is_empty(), "{}", failures.join("\n"));
        eprintln!("{compared} models of {} agree with MuJoCo", self.what);
    }
}

/// Our name of a MuJoCo body or joint (MuJoCo's `#N` for an unnamed one is our `body#N` / `joint#N`).
fn ours(name: &str, kind: &str) -> String {
    match name.strip_prefix('#') {
        Some(id) => format!("{kind}#{id}"),
        None => name.to_string(),
    }
}

fn agrees(ours: f64, theirs: f64, floor: f64) -> bool {
    (ours - theirs).abs() <= RELATIVE * ours.abs().max(theirs.abs()) + floor
}

fn vector(value: &Value) -> Vector3<f64> {
    let v: Vec<f64> = value
        .as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect();
    Vector3::new(v[0], v[1], v[2])
}

/// The differences between our reading of `model` and MuJoCo's `golden`, one line each.
fn compare(model_path: &Path, golden: &Value) -> Vec<String> {
    let mut out = Vec::new();
    // MuJoCo's numbers are under standard gravity (on even where the model turns it off: the oracle
    // turns it back on, and records the model's own); our statics follow the model's gravity, which must
    // be MuJoCo's, and are compared here under the standard one (torques are linear in gravity).
    let gravity = vector(&golden["gravity"]);
    if (gravity - Vector3::new(0.0, 0.0, -9.81)).norm() > 0.0 {
        out.push(format!(
            "gravity {gravity:?} is not (0, 0, -9.81): not comparable"
        ));
    }
    let resolver = PackageResolver::default();
    let loaded = Loaded::read(model_path, &[], &resolver).expect("the model loads");
    let files = loaded.mjcf().expect("an MJCF model");
    let (robot, _) = urdf_validator::mjcf::parse_mjcf(files, &MeshCache::new(), &resolver);
    let (mut model, _) = Model::build(&robot);
    let declared = if golden["gravity_disabled"].as_bool() == Some(true) {
        Vector3::zeros()
    } else {
        vector(&golden["model_gravity"])
    };
    if (model.gravity - declared).norm() > 0.0 {
        out.push(format!(
            "gravity read as {:?}, MuJoCo's model has {declared:?}",
            model.gravity
        ));
    }
    model.gravity = urdf_validator::analysis::statics::gravity::GRAVITY;
    let mass_of = |name: &str| {
        model
            .link(name)
            .map(|l| model.link_mass[l.0].mass())
            .unwrap_or(f64::NAN)
    };
    let total: f64 = model.link_mass.iter().map(LinkMass::mass).sum();
    let golden_total = golden["total_mass"].as_f64().expect("total_mass");
    if !agrees(total, golden_total, MASS_FLOOR) {
        out.push(format!("total mass {total} kg, MuJoCo {golden_total} kg"));
    }
    let bodies = golden["bodies"].as_array().expect("bodies");
    for body in bodies {
        let name = ours(body["name"].as_str().expect("name"), "body");
        let mass = body["mass"].as_f64().expect("mass");
        let ours = mass_of(&name);
        if !agrees(ours, mass, MASS_FLOOR) {
            out.push(format!("body '{name}': mass {ours} kg, MuJoCo {mass} kg"));
        }
        if mass <= 0.0 {
            continue;
        }
        let moments = robot
            .links
            .iter()
            .find(|l| l.name.value == name)
            .and_then(|l| l.inertial.as_ref()?.inertia.as_ref()?.principal_moments());
        let mut theirs: Vec<f64> = body["inertia"]
            .as_array()
            .expect("inertia")
            .iter()
            .map(|v| v.as_f64().expect("number"))
            .collect();
        theirs.sort_by(f64::total_cmp);
        let close = moments.is_some_and(|m| {
            (0..3).all(|i| {
                (m[i] - theirs[i]).abs()
                    <= INERTIA_RELATIVE * m[i].abs().max(theirs[i].abs()) + INERTIA_FLOOR
            })
        });
        if !close {
            out.push(format!(
                "body '{name}': principal moments {moments:?}, MuJoCo {theirs:?}"
            ));
        }
    }
    for (name, theirs) in expected_efforts(golden) {
        let ours = model
            .joint(&name)
            .and_then(|j| robot.joints[j.0].limit.as_ref())
            .and_then(|l| l.effort.as_ref())
            .map(|e| e.value);
        let same = match (ours, theirs) {
            (Some(a), Some(b)) => agrees(a, b, TORQUE_FLOOR),
            (a, b) => a == b,
        };
        if !same {
            out.push(format!(
                "joint '{name}': effort {ours:?}, from MuJoCo's actuators {theirs:?}"
            ));
        }
    }
    // MuJoCo's qpos layout: free 7, ball 4, slide and hinge 1 number, in joint order.
    let mut address = HashMap::new();
    let mut next = 0;
    for joint in golden["joints"].as_array().expect("joints") {
        let kind = joint["type"].as_i64().expect("type");
        address.insert(ours(joint["name"].as_str().expect("name"), "joint"), next);
        next += match kind {
            0 => 7,
            1 => 4,
            _ => 1,
        };
    }
    let configurations = golden["configurations"].as_array().expect("configurations");
    let qpos0: Vec<f64> = configurations[0]["qpos"]
        .as_array()
        .expect("qpos")
        .iter()
        .map(|v| v.as_f64().expect("number"))
        .collect();
    let mut data = StaticsData::new(&model);
    for configuration in configurations {
        let label = configuration["label"].as_str().expect("label");
        let qpos: Vec<f64> = configuration["qpos"]
            .as_array()
            .expect("qpos")
            .iter()
            .map(|v| v.as_f64().expect("number"))
            .collect();
        let key = label.strip_prefix("key:").map(|name| StaticsOptions {
            pose: PoseOptions {
                kind: PoseKind::Key(name.to_string()),
                ..PoseOptions::default()
            },
            ..StaticsOptions::default()
        });
        // A keyframe: the configuration `--pose key:NAME` analyses, made from the model by our reader.
        let statics = key
            .as_ref()
            .map(|options| analyse(&robot, &model, None, options));
        let q = match &statics {
            Some(Ok(outcome)) => outcome.q.clone(),
            Some(Err(why)) => {
                out.push(format!("{label}: {why}"));
                continue;
            }
            None => {
                let mut q = model.zero_configuration();
                for (name, &at) in &address {
                    if let Some(joint) = model.joint(name) {
                        q[joint.0] = qpos[at] - qpos0[at];
                    }
                }
                q
            }
        };
        evaluate(&model, &q, &mut data);
        for body in bodies {
            let name = ours(body["name"].as_str().expect("name"), "body");
            if body["mass"].as_f64().expect("mass") <= 0.0 {
                continue; // A massless body's xipos is its frame, not a centre of mass.
            }
            let Some(link) = model.link(&name) else {
                out.push(format!("{label}: body '{name}' is not a link"));
                continue;
            };
            let LinkMass::Declared { com, .. } = model.link_mass[link.0] else {
                out.push(format!("{label}: body '{name}' has no mass here"));
                continue;
            };
            let world = data.kinematics.link_placement[link.0]
                .transform_point(&com.into())
                .coords;
            let theirs = vector(&configuration["body_com"][body["name"].as_str().expect("name")]);
            if (0..3).any(|i| !agrees(world[i], theirs[i], POSITION_FLOOR)) {
                out.push(format!(
                    "{label}: body '{name}' centre of mass {world:?}, MuJoCo {theirs:?}"
                ));
            }
        }
        if golden_total > 0.0 {
            let (_, centre) =
                urdf_validator::analysis::statics::gravity::mass_and_com(&model, &data);
            let theirs = vector(&configuration["total_com"]);
            match centre {
                Some(c) if (0..3).all(|i| agrees(c[i], theirs[i], POSITION_FLOOR)) => {}
                other => out.push(format!(
                    "{label}: centre of mass {other:?}, MuJoCo {theirs:?}"
                )),
            }
        }
        let forces = configuration["gravity_force"]
            .as_object()
            .expect("gravity_force");
        for (name, force) in forces {
            let theirs = force.as_f64().expect("number");
            let name = ours(name, "joint");
            let Some(joint) = model.joint(&name) else {
                out.push(format!("{label}: joint '{name}' is not a joint here"));
                continue;
            };
            let torque = data.raw_torque[joint.0];
            if !agrees(torque, theirs, TORQUE_FLOOR) {
                out.push(format!(
                    "{label}: joint '{name}' gravity torque {torque}, MuJoCo {theirs}"
                ));
            }
        }
        if let Some(Ok(outcome)) = &statics {
            out.extend(required_torques(
                label,
                &robot,
                &model,
                forces,
                &outcome.section,
            ));
        }
    }
    out
}

/// The statics section's `required_torque_gravity` against MuJoCo's `qfrc_bias` (`forces`, by MJCF joint
/// name): a joint's own, plus, for a joint others follow (an `<equality><joint>` read as mimic), each
/// follower's times d q_follower / d q_joint (what the joint's drive holds through the coupling).
fn required_torques(
    label: &str,
    robot: &urdf_validator::urdf::robot::Robot,
    model: &Model,
    forces: &serde_json::Map<String, Value>,
    section: &StaticsSection,
) -> Vec<String> {
    let mut expected: HashMap<String, f64> = HashMap::new();
    for (name, force) in forces {
        let name = ours(name, "joint");
        let (Some(joint), Some(force)) = (model.joint(&name), force.as_f64()) else {
            continue;
        };
        *expected.entry(name.clone()).or_default() += force;
        if model.mimic[joint.0].is_some() {
            let (leader, factor) = model.independent_leader[joint.0];
            *expected
                .entry(robot.joints[leader.0].name.value.clone())
                .or_default() += factor * force;
        }
    }
    let mut out = Vec::new();
    for joint in &section.joints {
        let Some(theirs) = expected.get(&joint.name) else {
            continue;
        };
        match joint.required_torque_gravity {
            Some(torque) if agrees(torque, *theirs, TORQUE_FLOOR) => {}
            other => out.push(format!(
                "{label}: joint '{}' required_torque_gravity {other:?}, MuJoCo {theirs}",
                joint.name
            )),
        }
    }
    out
}

fn pair(value: &Value) -> Option<(f64, f64)> {
    let v = value.as_array()?;
    Some((v[0].as_f64()?, v[1].as_f64()?))
}

/// Each hinge and slide joint's effort from MuJoCo's compiled actuators (gear, ctrlrange, forcerange,
/// gainprm, biasprm, the joint's actfrcrange) by the rule of `mjcf/build/actuators.rs`: per actuator on a
/// joint, |gain| · max |ctrl| (a position bias: |gain| · ctrl range width), clamped by max |force|, times
/// |gear|; summed, clamped by max |actfrcrange|; `None` when unbounded or without actuator.
fn expected_efforts(golden: &Value) -> Vec<(String, Option<f64>)> {
    let joints = golden["joints"].as_array().expect("joints");
    let mut sums: HashMap<usize, Option<f64>> = HashMap::new();
    for actuator in golden["actuators"].as_array().expect("actuators") {
        // mjTRN_JOINT and mjTRN_JOINTINPARENT.
        if actuator["trntype"].as_i64().expect("trntype") > 1 {
            continue;
        }
        let joint = actuator["target"].as_u64().expect("target") as usize;
        let gain = actuator["gainprm"][0].as_f64().expect("gain");
        let position_like = actuator["biasprm"][1].as_f64().expect("bias") != 0.0;
        let from_ctrl = pair(&actuator["ctrlrange"]).map(|(lo, hi)| {
            gain.abs()
                * if position_like {
                    hi - lo
                } else {
                    lo.abs().max(hi.abs())
                }
        });
        let from_force = pair(&actuator["forcerange"]).map(|(lo, hi)| lo.abs().max(hi.abs()));
        let most = match (from_ctrl, from_force) {
            (Some(c), Some(f)) => Some(c.min(f)),
            (c, f) => c.or(f),
        };
        let effort = most.map(|m| m * actuator["gear"].as_f64().expect("gear").abs());
        let sum = match sums.get(&joint) {
            None => effort,
            Some(previous) => previous.zip(effort).map(|(a, b)| a + b),
        };
        sums.insert(joint, sum);
    }
    joints
        .iter()
        .enumerate()
        .filter(|(_, j)| j["type"].as_i64().expect("type") >= 2)
        .map(|(i, j)| {
            let name = ours(j["name"].as_str().expect("name"), "joint");
            let clamp = pair(&j["actfrcrange"]).map(|(lo, hi)| lo.abs().max(hi.abs()));
            let effort = match (sums.get(&i), clamp) {
                (None, _) => None,
                (Some(Some(sum)), Some(most)) => Some(sum.min(most)),
                (Some(None), Some(most)) => Some(most),
                (Some(sum), None) => *sum,
            };
            (name, effort)
        })
        .collect()
}

#[test]
fn every_dm_control_model_agrees_with_mujoco() {
    DM_CONTROL.check();
}

#[test]
fn every_gymnasium_model_agrees_with_mujoco() {
    GYMNASIUM.check();
}

/// A binary STL of `triangles`.
fn binary_stl(triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut out = vec![0u8; 80];
    out.extend((triangles.len() as u32).to_le_bytes());
    for t in triangles {
        out.extend([0u8; 12]);
        for v in t {
            for c in v {
                out.extend(c.to_le_bytes());
            }
        }
        out.extend([0u8; 2]);
    }
    out
}

/// A unit cube whose top face is dented down to its centre: closed, wound outwards, not convex (so
/// MuJoCo's legacy volume, which counts every pyramid positive, is not the volume it encloses).
fn dented_cube() -> Vec<[[f32; 3]; 3]> {
    let v =
        |i: usize| -> [f32; 3] { [(i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32] };
    let faces = [
        [0, 2, 1],
        [1, 2, 3],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    let mut out: Vec<[[f32; 3]; 3]> = faces.iter().map(|f| f.map(v)).collect();
    let dent = [0.5, 0.5, 0.4];
    for (a, b) in [(4, 5), (5, 7), (7, 6), (6, 4)] {
        out.push([v(a), v(b), dent]);
    }
    out
}

const FEATURES: &str = r#"<mujoco model="features">
  <compiler angle="radian" eulerseq="zyx" boundmass="0.01" boundinertia="1e-5" balanceinertia="true"
            inertiagrouprange="0 3"/>
  <default>
    <geom density="500"/>
    <default class="limb">
      <geom type="capsule" size="0.03"/>
      <joint axis="0 1 0" range="-1 1"/>
      <default class="fat"><geom size="0.06" density="800"/></default>
    </default>
  </default>
  <worldbody>
    <geom type="plane" size="1 1 0.1"/>
    <body name="base" pos="0.1 0.2 1" euler="0.1 0.2 0.3">
      <freejoint name="root"/>
      <geom type="box" size="0.2 0.1 0.05"/>
      <geom type="ellipsoid" size="0.05 0.06 0.07" pos="0 0 0.1" xyaxes="0 1 0 -1 0 0"/>
      <frame pos="0.2 0 0" zaxis="1 0 1">
        <body name="arm" childclass="limb" quat="0.9 0.1 0.2 0.3">
          <joint name="j1" pos="0 0 0.05" ref="0.3"/>
          <joint name="j2" type="slide" axis="1 0 0" range="-0.1 0.1"/>
          <joint name="j3" axis="0 0 1" pos="0.01 0 0"/>
          <geom fromto="0 0 0 0.3 0 0"/>
          <geom class="fat" fromto="0.3 0 0 0.3 0 0.2"/>
          <body name="hand" pos="0.3 0 0.2" axisangle="1 1 0 0.5">
            <joint name="wrist" class="main" type="ball" pos="0 0 0.02"/>
            <inertial pos="0.01 0.02 0.03" mass="0.5" diaginertia="0.001 0.002 0.0025" quat="1 0 0.3 0"/>
            <geom type="sphere" size="0.04"/>
            <body pos="0.05 0 0">
              <joint axis="1 0 0"/>
              <geom type="cylinder" size="0.01 0.05" euler="0.3 0.2 0.1"/>
            </body>
          </body>
          <body name="light" pos="0 0.1 0">
            <joint name="flap" axis="1 0 0"/>
            <geom type="cylinder" size="0.01 0.02" group="4" mass="0.2"/>
          </body>
        </body>
      </frame>
    </body>
  </worldbody>
  <keyframe>
    <key name="bent" qpos="0.1 0.2 1.5 0.9 0.1 0.2 0.3  0.9 0.05 -0.4  0.6 0.2 -0.3 0.5  0.7 -0.2"/>
    <key qpos="0 0 1 1 0 0 0 0.5"/>
  </keyframe>
</mujoco>
"#;

const ASSEMBLY: &str = r#"<mujoco model="assembly">
  <compiler angle="degree" eulerseq="XYZ" inertiafromgeom="true" settotalmass="7" meshdir="meshes"/>
  <asset>
    <mesh name="dent" file="dented.stl" scale="0.2 0.4 0.1"/>
    <mesh file="dented.stl" name="dent_exact" inertia="exact" scale="0.1 0.1 0.1"/>
    <mesh file="dented.stl" name="dent_mirrored" inertia="exact" scale="-0.1 0.2 0.1"/>
  </asset>
  <worldbody>
    <body name="post" pos="0 0 0.5" euler="10 20 30">
      <inertial pos="0 0 0" mass="100" diaginertia="1 1 1"/>
      <geom type="cylinder" fromto="0 0 -0.5 0 0 0.5" size="0.05"/>
      <body name="boom" pos="0 0 0.5">
        <joint name="yaw" axis="0 0 1" range="-90 90" ref="30"/>
        <geom type="mesh" mesh="dent" pos="0.2 0 0"/>
        <body name="bracket" pos="0.4 0 0">
          <geom type="mesh" mesh="dent_exact" euler="0 90 0"/>
          <body name="tip" pos="0.1 0 0">
            <joint name="pitch" axis="0 1 0"/>
            <joint name="roll" axis="1 0 0" pos="0.05 0 0"/>
            <geom type="box" size="0.02 0.03 0.04" pos="0.1 0 0" mass="0.3"/>
            <body name="mirrored" pos="0.2 0 0">
              <joint name="flip" axis="0 0 1"/>
              <geom type="mesh" mesh="dent_mirrored" pos="0.05 0 0"/>
            </body>
          </body>
        </body>
      </body>
    </body>
    <body name="ball" pos="1 0 0.2">
      <freejoint/>
      <geom type="sphere" size="0.1"/>
    </body>
  </worldbody>
</mujoco>
"#;

/// Primitives fitted to a turned, unevenly scaled mesh (`type="capsule" mesh=…`), one of each type,
/// `fitscale` on one; `FITAABB` is in the `<compiler>` of the variant fitted to bounding boxes.
const FITTED: &str = r#"<mujoco model="fitted">
  <compiler angle="radian" meshdir="meshes" FITAABB/>
  <asset>
    <mesh name="dent" file="dented.stl" scale="0.2 0.4 0.1" refquat="0.9 0.2 0.3 0.1"/>
  </asset>
  <default>
    <default class="fit"><geom mesh="dent" density="700"/></default>
  </default>
  <worldbody>
    <body name="base" pos="0 0 0.5">
      <geom class="fit" type="capsule"/>
      <body name="upper" pos="0.3 0 0">
        <joint name="shoulder" axis="0 1 0"/>
        <geom class="fit" type="cylinder" pos="0.1 0 0" euler="0.3 0.2 0.1"/>
        <geom class="fit" type="sphere" pos="0.2 0.05 0" fitscale="1.3"/>
        <body name="lower" pos="0.4 0 0">
          <joint name="elbow" axis="0 0 1"/>
          <geom class="fit" type="box" pos="0.1 0 0"/>
          <geom class="fit" type="ellipsoid" pos="0.2 0 0.1" quat="0.8 0.1 0.5 0.2"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
"#;

/// An OBJ file of two objects, as MuJoCo reads only the first: a prism on a star-shaped hexagon (a
/// polygon MuJoCo clips into ears) whose top is not flat (its sides are quads that are not planar), then
/// a cube far away.
fn two_object_obj() -> String {
    let mut text = String::from("o prism\n");
    for level in 0..2 {
        for k in 0..6 {
            let angle = std::f64::consts::PI / 3.0 * k as f64;
            let radius = if k % 2 == 0 { 0.1 } else { 0.06 };
            let z = if level == 0 {
                0.0
            } else {
                0.1 + 0.03 * (k % 2) as f64
            };
            text += &format!("v {} {} {z}\n", radius * angle.cos(), radius * angle.sin());
        }
    }
    text += "f 6 5 4 3 2 1\nf 7 8 9 10 11 12\n";
    for k in 1..=6 {
        let next = k % 6 + 1;
        text += &format!("f {k} {next} {} {}\n", next + 6, k + 6);
    }
    text += "o cube\n";
    for i in 0..8 {
        let c = |bit: i32| if i & bit == 0 { 1.0 } else { 1.2 };
        text += &format!("v {} {} {}\n", c(1), c(2), c(4));
    }
    for face in [
        "1 3 4 2", "5 6 8 7", "1 2 6 5", "3 7 8 4", "1 5 7 3", "2 4 8 6",
    ] {
        let corners: Vec<usize> = face
            .split(' ')
            .map(|n| n.parse::<usize>().unwrap() + 12)
            .collect();
        text += &format!(
            "f {} {} {} {}\n",
            corners[0], corners[1], corners[2], corners[3]
        );
    }
    text
}

/// A model whose only mass is [`two_object_obj`]'s.
const OBJECTS: &str = r#"<mujoco model="objects">
  <compiler meshdir="meshes"/>
  <asset><mesh name="two" file="two_objects.obj"/></asset>
  <worldbody>
    <body name="arm" pos="0 0 1">
      <joint name="hinge" axis="0 1 0"/>
      <geom type="mesh" mesh="two" pos="0.3 0 0" density="900"/>
    </body>
  </worldbody>
</mujoco>
"#;

/// Mass spread over surfaces: each primitive with `shellinertia` (from a class), a mesh asset with
/// `inertia="shell"`, and a capsule fitted to that mesh with a shell of its own.
const SHELLS: &str = r#"<mujoco model="shells">
  <compiler meshdir="meshes"/>
  <asset><mesh name="skin" file="dented.stl" inertia="shell" scale="0.2 0.3 0.1"/></asset>
  <default>
    <default class="thin"><geom shellinertia="true" density="300"/></default>
  </default>
  <worldbody>
    <body name="base" pos="0 0 0.5">
      <geom class="thin" type="box" size="0.1 0.2 0.05"/>
      <body name="upper" pos="0.3 0 0">
        <joint name="shoulder" axis="0 1 0"/>
        <geom class="thin" type="sphere" size="0.05" pos="0.1 0 0"/>
        <geom class="thin" type="capsule" fromto="0 0 0 0.3 0.1 0" size="0.03"/>
        <geom class="thin" type="cylinder" size="0.04 0.08" pos="0.2 0 0.1" euler="0.3 0.2 0.1"/>
        <body name="lower" pos="0.4 0 0">
          <joint name="elbow" axis="0 0 1"/>
          <geom class="thin" type="ellipsoid" size="0.05 0.08 0.03" pos="0.1 0 0" quat="0.8 0.1 0.5 0.2"/>
          <geom type="mesh" mesh="skin" pos="0.2 0.05 0"/>
          <geom class="thin" type="capsule" mesh="skin" pos="0.3 0 0"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
"#;

#[test]
fn models_using_every_feature_read_agree_with_mujoco_run_now() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("mjcf-features-{}", std::process::id()));
    let out = dir.join("golden");
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    std::fs::write(dir.join("features.xml"), FEATURES).unwrap();
    std::fs::write(dir.join("assembly.xml"), ASSEMBLY).unwrap();
    std::fs::write(dir.join("fitted.xml"), FITTED.replace("FITAABB", "")).unwrap();
    std::fs::write(dir.join("objects.xml"), OBJECTS).unwrap();
    std::fs::write(dir.join("shells.xml"), SHELLS).unwrap();
    std::fs::write(dir.join("meshes/two_objects.obj"), two_object_obj()).unwrap();
    std::fs::write(
        dir.join("fitted_aabb.xml"),
        FITTED.replace("FITAABB", "fitaabb=\"true\""),
    )
    .unwrap();
    std::fs::write(dir.join("meshes/dented.stl"), binary_stl(&dented_cube())).unwrap();
    let script = common::repo_root().join("scripts/oracle/mjcf_goldens.py");
    let run = std::process::Command::new(&python)
        .arg(&script)
        .arg("--models")
        .arg(&dir)
        .arg("--out")
        .arg(&out)
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}{}",
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr)
    );
    let report = String::from_utf8_lossy(&run.stdout).into_owned();
    let mut failures = Vec::new();
    for stem in [
        "features",
        "assembly",
        "fitted",
        "fitted_aabb",
        "objects",
        "shells",
    ] {
        let golden: Value = serde_json::from_str(
            &std::fs::read_to_string(out.join(format!("{stem}.json")))
                .unwrap_or_else(|e| panic!("no golden for {stem}.xml ({e}):\n{report}")),
        )
        .unwrap();
        let differences = compare(&dir.join(format!("{stem}.xml")), &golden);
        if !differences.is_empty() {
            failures.push(format!("{stem}:\n  {}", differences.join("\n  ")));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The mesh-free Menagerie variants with keyframes (`tests/data/menagerie`), each key run through MuJoCo
/// now (`mjcf_goldens.py --models` on the variant's folder): at `--pose key:NAME` (the key's qpos, its free
/// joints left at qpos0) every body's centre of mass, the robot's and each joint's gravity torque agree
/// with MuJoCo's, and so does the statics report's `required_torque_gravity` (a coupled joint's with its
/// followers' folded in).
#[test]
fn menagerie_keyframes_agree_with_mujoco_run_now() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let data = common::repo_root().join("crates/urdf-validator/tests/data/menagerie");
    let script = common::repo_root().join("scripts/oracle/mjcf_goldens.py");
    let scratch = std::env::temp_dir().join(format!("mjcf-keys-{}", std::process::id()));
    let mut folders: Vec<PathBuf> = std::fs::read_dir(&data)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    folders.sort();
    let (mut failures, mut keys) = (Vec::new(), 0);
    for folder in folders {
        let models: Vec<PathBuf> = std::fs::read_dir(&folder)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| {
                p.extension().is_some_and(|e| e == "xml")
                    && std::fs::read_to_string(p).unwrap().contains("<key ")
            })
            .collect();
        if models.is_empty() {
            continue;
        }
        let out = scratch.join(folder.file_name().unwrap());
        let run = std::process::Command::new(&python)
            .arg(&script)
            .arg("--models")
            .arg(&folder)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        for model in models {
            let stem = model.file_stem().unwrap().to_string_lossy().into_owned();
            // A variant MuJoCo refuses (see docs/menagerie.md) has no golden: nothing to compare.
            let Ok(text) = std::fs::read_to_string(out.join(format!("{stem}.json"))) else {
                continue;
            };
            let golden: Value = serde_json::from_str(&text).unwrap();
            keys += golden["configurations"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|c| c["label"].as_str().unwrap().starts_with("key:"))
                .count();
            // The keyframes only: the variants' qpos0 is menagerie.py's, and their actuators use what
            // `expected_efforts` does not model (e.g. `actuatorfrcrange` on position servos).
            let differences: Vec<String> = compare(&model, &golden)
                .into_iter()
                .filter(|d| d.starts_with("key:"))
                .collect();
            if !differences.is_empty() {
                failures.push(format!("{stem}:\n  {}", differences.join("\n  ")));
            }
        }
    }
    std::fs::remove_dir_all(&scratch).ok();
    assert!(
        keys >= 15,
        "only {keys} keyframes compared (15 in 13 variants)"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
