//! The MJCF reader on its own: how it tells MJCF from URDF, how it names and chains what it reads, and bad
//! input (include problems, unknown elements and classes, malformed values) as findings at the MJCF line,
//! never a panic. Agreement with MuJoCo's numbers is `mjcf_golden.rs`.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::path::Path;

use common::Scratch;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use urdf_validator::analysis::pose::PoseKind;
use urdf_validator::input::mesh::MeshCache;
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::input::sandbox::Sandbox;
use urdf_validator::input::Loaded;
use urdf_validator::report::FindingReport;
use urdf_validator::urdf::robot::{JointKind, Robot};
use urdf_validator::{validate, Options, Validation};

fn options() -> Options {
    let mut options = Options::default();
    options.workspace.samples = 200;
    options.deep.automatic = false;
    options
}

fn run(path: &Path) -> Validation {
    validate(path, &options()).unwrap()
}

fn robot(path: &Path) -> Robot {
    let resolver = PackageResolver::default();
    let loaded = Loaded::read(path, &[], &resolver).unwrap();
    urdf_validator::mjcf::parse_mjcf(loaded.mjcf().unwrap(), &MeshCache::new(), &resolver).0
}

/// The findings of `rule`, as (file name, line, message).
fn findings(v: &Validation, rule: &str) -> Vec<(String, u32, String)> {
    v.report
        .findings
        .iter()
        .filter(|f| f.rule == rule)
        .map(|f: &FindingReport| {
            let file = f.file.as_deref().unwrap_or("");
            let name = Path::new(file)
                .file_name()
                .map_or(String::new(), |n| n.to_string_lossy().into_owned());
            (name, f.line.unwrap_or(0), f.message.clone())
        })
        .collect()
}

fn has(v: &Validation, rule: &str, file: &str, line: u32, words: &str) {
    let found = findings(v, rule);
    assert!(
        found
            .iter()
            .any(|(f, l, m)| f == file && *l == line && m.contains(words)),
        "no {rule} at {file}:{line} saying '{words}': {:#?}",
        v.report
            .findings
            .iter()
            .map(|f| (&f.rule, &f.file, f.line, &f.message))
            .collect::<Vec<_>>()
    );
}

#[test]
fn a_mujoco_root_is_mjcf_whatever_the_file_is_called() {
    let dir = Scratch::new("mjcf-root");
    let path = dir.file(
        "robot.urdf",
        "<mujoco model=\"m\"><worldbody><body name=\"b\"><joint name=\"j\"/><geom size=\"0.1\"/></body></worldbody></mujoco>",
    );
    let v = run(&path);
    assert!(findings(&v, "U001").is_empty());
    let r = robot(&path);
    assert_eq!(r.format, urdf_validator::input::Format::Mjcf);
    assert_eq!(r.name.as_ref().unwrap().value, "m");
    let names: Vec<&str> = r.links.iter().map(|l| l.name.value.as_str()).collect();
    assert_eq!(names, ["world", "b"]);
}

#[test]
fn joints_of_one_body_are_chained_through_massless_links_and_the_last_reaches_the_body() {
    let dir = Scratch::new("mjcf-chain");
    let path = dir.file(
        "m.xml",
        r#"<mujoco>
  <worldbody>
    <body name="torso">
      <joint name="rootx" type="slide" axis="1 0 0"/>
      <joint name="rooty" axis="0 1 0" pos="0 0 0.3" range="-30 30"/>
      <joint name="ball" type="ball"/>
      <geom size="0.1"/>
    </body>
    <body name="prop" pos="1 0 0"><freejoint/><geom size="0.1"/></body>
  </worldbody>
</mujoco>"#,
    );
    let r = robot(&path);
    let chain: Vec<(&str, &str, &str, JointKind)> = r
        .joints
        .iter()
        .map(|j| {
            (
                j.name.value.as_str(),
                j.parent.as_ref().unwrap().value.as_str(),
                j.child.as_ref().unwrap().value.as_str(),
                j.kind.as_ref().unwrap().value,
            )
        })
        .collect();
    assert_eq!(
        chain,
        [
            ("rootx", "world", "torso:rootx", JointKind::Prismatic),
            ("rooty", "torso:rootx", "torso:rooty", JointKind::Revolute),
            (
                "ball_x",
                "torso:rooty",
                "torso:ball_x",
                JointKind::Continuous
            ),
            (
                "ball_y",
                "torso:ball_x",
                "torso:ball_y",
                JointKind::Continuous
            ),
            ("ball_z", "torso:ball_y", "torso", JointKind::Continuous),
            ("joint#3", "world", "prop", JointKind::Floating),
        ]
    );
    // The range is in degrees (the compiler's default) and the hinge turns about its pos.
    let rooty = &r.joints[1];
    let limit = rooty.limit.as_ref().unwrap();
    assert!((limit.upper.as_ref().unwrap().value - 30f64.to_radians()).abs() < 1e-15);
    assert!((rooty.origin.xyz[2] - 0.3).abs() < 1e-15);
    let v = run(&path);
    has(&v, "U033", "m.xml", 6, "three hinges");
    // The chain's links are the reader's, not the author's: no missing-inertial warning on them, and
    // [PHYSICS] counts them as frames (with the world), not as links whose mass is missing.
    assert!(
        findings(&v, "U201").is_empty(),
        "{:?}",
        findings(&v, "U201")
    );
    let physics = &v.report.physics;
    assert_eq!(
        (physics.frames, physics.mass_missing),
        (5, 0),
        "{physics:?}"
    );
}

#[test]
fn the_only_top_level_body_with_a_free_joint_is_the_root() {
    let dir = Scratch::new("mjcf-floating");
    let path = dir.file(
        "m.xml",
        r#"<mujoco><worldbody><body name="pelvis" pos="0 0 1"><freejoint/><geom size="0.1"/>
<body name="leg"><joint name="hip"/><geom size="0.05" pos="0 0 -0.2"/></body></body></worldbody></mujoco>"#,
    );
    let r = robot(&path);
    let names: Vec<&str> = r.links.iter().map(|l| l.name.value.as_str()).collect();
    assert_eq!(names, ["pelvis", "leg"]);
    // The root link's frame is the world frame at qpos0: the body's mass sits 1 m up.
    let inertial = r.links[0].inertial.as_ref().unwrap();
    assert!((inertial.origin.xyz[2] - 1.0).abs() < 1e-15);
}

#[test]
fn include_problems_are_findings_at_the_include() {
    let dir = Scratch::new("mjcf-includes");
    dir.file("loop.xml", "<mujoco><include file=\"loop.xml\"/></mujoco>");
    dir.file("robot.urdf.xml", "<robot name=\"r\"/>");
    dir.file("broken.xml", "<mujoco><default>");
    let path = dir.file(
        "m.xml",
        r#"<mujoco>
  <include file="missing.xml"/>
  <include file="loop.xml"/>
  <include file="robot.urdf.xml"/>
  <include file="broken.xml"/>
  <include/>
  <worldbody><body name="b"><joint/><geom size="0.1"/></body></worldbody>
</mujoco>"#,
    );
    let v = run(&path);
    has(&v, "U031", "m.xml", 2, "no such file");
    has(&v, "U031", "loop.xml", 1, "include cycle");
    has(&v, "U031", "m.xml", 4, "not <mujoco>");
    has(&v, "U031", "m.xml", 5, "not well-formed");
    has(&v, "U031", "m.xml", 6, "no file attribute");
    // The rest of the model is still read.
    assert_eq!(v.report.statics.as_ref().unwrap().joints.len(), 1);
}

#[test]
fn an_include_outside_the_sandbox_is_refused() {
    let dir = Scratch::new("mjcf-sandbox");
    let outside = Scratch::new("mjcf-sandbox-outside");
    let secret = outside.file("secret.xml", "<mujoco><default/></mujoco>");
    let path = dir.file(
        "m.xml",
        &format!(
            "<mujoco>\n<include file=\"{}\"/>\n<worldbody/></mujoco>",
            secret.display()
        ),
    );
    let options = Options {
        sandbox: Sandbox::untrusted(Vec::new(), Vec::new()),
        ..options()
    };
    let v = validate(&path, &options).unwrap();
    has(&v, "U031", "m.xml", 2, "refused");
}

#[test]
fn unknown_elements_classes_and_meshes_and_bad_values_are_findings_at_their_line() {
    let dir = Scratch::new("mjcf-bad");
    let path = dir.file(
        "m.xml",
        r#"<mujoco>
  <compiler angle="gradians"/>
  <worldbody>
    <body name="a" pos="0 0 nan">
      <joint name="j" axis="0 0 0"/>
      <geom class="nope" size="0.1"/>
      <geom type="mesh" mesh="ghost"/>
      <geom size="0.1" quat="1 0 0 0" euler="0 0 1"/>
      <widget/>
      <body name="b"><freejoint/><geom size="0.1" pos="1 2"/></body>
      <body name="c" childclass="missing"><joint/><geom size="0.1"/></body>
    </body>
  </worldbody>
  <equality><gizmo/></equality>
</mujoco>"#,
    );
    let v = run(&path);
    has(&v, "U030", "m.xml", 11, "childclass 'missing'");
    // The body's own elements still take the top-level defaults (a sphere of 0.1 m: 4.19 kg).
    let c = robot(&path);
    let mass = c
        .links
        .iter()
        .find(|l| l.name.value == "c")
        .unwrap()
        .inertial
        .as_ref()
        .unwrap();
    assert!((mass.mass.as_ref().unwrap().value - 4.0 / 3.0 * std::f64::consts::PI).abs() < 1e-12);
    has(&v, "U032", "m.xml", 2, "angle");
    has(&v, "U032", "m.xml", 4, "not finite");
    has(&v, "U030", "m.xml", 5, "axis is zero");
    has(&v, "U030", "m.xml", 6, "'nope'");
    has(&v, "U030", "m.xml", 7, "'ghost'");
    has(&v, "U030", "m.xml", 8, "more than one orientation");
    has(&v, "U030", "m.xml", 9, "<widget>");
    has(&v, "U030", "m.xml", 10, "only a body of the <worldbody>");
    has(&v, "U032", "m.xml", 10, "3 numbers expected");
    has(
        &v,
        "U030",
        "m.xml",
        14,
        "<gizmo> is not an equality constraint",
    );
}

#[test]
fn hostile_values_never_panic() {
    let hostile = ["", "nan", "1e400", "-1", "0 0 0 0 0 0 0", "x y z", "ghost"];
    let dir = Scratch::new("mjcf-hostile");
    let text = r#"<mujoco model="m">
  <compiler angle="radian" eulerseq="xyz" inertiafromgeom="auto" boundmass="0" settotalmass="-1"/>
  <default><default class="c"><geom type="capsule" size="0.02"/><joint range="-1 1"/></default></default>
  <asset><mesh name="n" file="none.stl" scale="1 1 1"/></asset>
  <worldbody>
    <body name="a" pos="0 0 1" quat="1 0 0 0" childclass="c">
      <freejoint/>
      <inertial pos="0 0 0" mass="1" diaginertia="0.1 0.1 0.1"/>
      <frame pos="0.1 0 0" euler="0 0 0.5">
        <body name="b" axisangle="0 0 1 0.3">
          <joint name="h" type="hinge" axis="0 1 0" pos="0 0 0.1" ref="0.2" limited="true"/>
          <joint name="s" type="slide" axis="1 0 0"/>
          <geom fromto="0 0 0 0.2 0 0" mass="0.5"/>
          <geom type="mesh" mesh="n" xyaxes="1 0 0 0 1 0"/>
          <geom type="box" size="0.1 0.1 0.1" zaxis="0 0 1" group="2"/>
        </body>
      </frame>
    </body>
  </worldbody>
</mujoco>"#;
    let path = dir.file("m.xml", text);
    let doc = roxmltree::Document::parse(text).unwrap();
    let ranges: Vec<std::ops::Range<usize>> = doc
        .descendants()
        .flat_map(|n| n.attributes().map(|a| a.range_value()).collect::<Vec<_>>())
        .collect();
    let resolver = PackageResolver::default();
    let meshes = MeshCache::new();
    let mut variants = 0;
    for range in ranges {
        for value in hostile {
            let mutated = format!("{}{value}{}", &text[..range.start], &text[range.end..]);
            let files = urdf_validator::input::xml_files::XmlFiles::load(
                &path,
                mutated,
                urdf_validator::input::xml_files::IncludeSyntax::Mjcf,
                &resolver,
            )
            .unwrap();
            let (robot, _) = urdf_validator::mjcf::parse_mjcf(&files, &meshes, &resolver);
            let _ = urdf_validator::model::Model::build(&robot);
            variants += 1;
        }
    }
    assert!(variants > 250, "{variants}");
}

/// The effort limit the reader gave joint `name`.
fn effort_of(r: &Robot, name: &str) -> Option<f64> {
    r.joints
        .iter()
        .find(|j| j.name.value == name)
        .and_then(|j| j.limit.as_ref()?.effort.as_ref())
        .map(|e| e.value)
}

#[test]
fn actuators_give_joints_their_effort_and_a_weak_one_fails_at_its_forcerange() {
    let dir = Scratch::new("mjcf-actuators");
    let path = dir.file(
        "m.xml",
        r#"<mujoco>
  <compiler angle="radian"/>
  <default><motor ctrlrange="-1 1"/></default>
  <worldbody>
    <body name="arm">
      <joint name="shoulder" axis="0 1 0" range="-1 1"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.05" mass="2"/>
    </body>
    <body name="strong" pos="0 2 0">
      <joint name="elbow" axis="0 1 0" actuatorfrcrange="-50 50"/>
      <geom type="sphere" size="0.05" pos="0.3 0 0" mass="1"/>
    </body>
    <body name="swing" pos="0 1 0">
      <joint name="passive" axis="0 1 0"/>
      <geom type="sphere" size="0.05" pos="0.3 0 0" mass="1"/>
    </body>
  </worldbody>
  <actuator>
    <motor joint="shoulder" gear="10" forcerange="-0.3 0.3"/>
    <position joint="elbow" kp="100" ctrlrange="-1 1"/>
    <motor tendon="t"/>
  </actuator>
</mujoco>"#,
    );
    let r = robot(&path);
    let effort = |name: &str| effort_of(&r, name);
    // The motor's ctrlrange comes from the class default; its forcerange caps it: 0.3 N × gear 10.
    assert_eq!(effort("shoulder"), Some(3.0));
    // kp 100 over a ctrl range of 2: 200 N·m, capped by the joint's actuatorfrcrange.
    assert_eq!(effort("elbow"), Some(50.0));
    assert_eq!(effort("passive"), None);
    let v = run(&path);
    // 2 kg at 0.25 m needs 4.905 N·m: undersized, at the forcerange that limits it.
    has(&v, "U701", "m.xml", 19, "shoulder");
    assert!(
        !findings(&v, "U701")
            .iter()
            .any(|(_, _, m)| m.contains("passive")),
        "{:?}",
        findings(&v, "U701")
    );
    has(&v, "U033", "m.xml", 21, "tendon");
}

/// `inheritrange` gives a position servo its joint's range (scaled about its middle) as ctrlrange, as
/// MuJoCo 4.0 compiles it (checked there: `actuator_ctrlrange` -1.7..1.7 for `inheritrange="1"`, half for
/// 0.5, ±π/2 for a range of ±90 in degrees), so the servo's effort is kp × that width. Menagerie's arx_l5
/// and berkeley_humanoid use it; before, their servos were bounded by `forcerange` alone (arx_l5's joint5:
/// 100 N·m instead of MuJoCo's 34). Both ranges on one actuator, or a joint without a range, MuJoCo refuses.
#[test]
fn inheritrange_gives_a_position_servo_its_joints_range_as_mujoco_compiles_it() {
    let dir = Scratch::new("mjcf-inheritrange");
    let path = dir.file(
        "m.xml",
        r#"<mujoco>
  <compiler angle="radian"/>
  <default><position inheritrange="1" forcerange="-100 100"/></default>
  <worldbody>
    <body name="a">
      <joint name="whole" axis="0 1 0" range="-1.7 1.7"/>
      <geom type="sphere" size="0.05" pos="0.3 0 0" mass="1"/>
      <body name="b">
        <joint name="half" axis="1 0 0" range="0.2 1"/>
        <geom type="sphere" size="0.05" pos="0.3 0 0" mass="1"/>
      </body>
    </body>
  </worldbody>
  <actuator>
    <position joint="whole" kp="10"/>
    <position joint="half" kp="10" inheritrange="0.5"/>
  </actuator>
</mujoco>"#,
    );
    let r = robot(&path);
    let effort = |name: &str| effort_of(&r, name);
    assert!(
        (effort("whole").unwrap() - 34.0).abs() < 1e-12,
        "{:?}",
        effort("whole")
    );
    // MuJoCo: mean 0.6, radius 0.4 × 0.5: ctrlrange [0.4, 0.8], kp 10 × 0.4.
    assert!(
        (effort("half").unwrap() - 4.0).abs() < 1e-12,
        "{:?}",
        effort("half")
    );
    let degrees = dir.file(
        "deg.xml",
        r#"<mujoco>
  <worldbody>
    <body name="a">
      <joint name="j" axis="0 1 0" range="-90 90"/>
      <geom type="sphere" size="0.05" pos="0.3 0 0" mass="1"/>
    </body>
  </worldbody>
  <actuator><position joint="j" kp="10" inheritrange="1"/></actuator>
</mujoco>"#,
    );
    let r = robot(&degrees);
    let effort = r.joints[0].limit.as_ref().and_then(|l| l.effort.as_ref());
    assert!((effort.unwrap().value - 10.0 * std::f64::consts::PI).abs() < 1e-12);
    let refused = dir.file(
        "refused.xml",
        r#"<mujoco>
  <worldbody>
    <body name="a">
      <joint name="free_turn" axis="0 1 0"/>
      <geom type="sphere" size="0.05" pos="0.3 0 0" mass="1"/>
    </body>
  </worldbody>
  <actuator>
    <position joint="free_turn" kp="10" inheritrange="1"/>
    <position joint="free_turn" kp="10" inheritrange="1" ctrlrange="-1 1"/>
  </actuator>
</mujoco>"#,
    );
    let v = run(&refused);
    has(&v, "U030", "refused.xml", 9, "has none");
    has(
        &v,
        "U030",
        "refused.xml",
        10,
        "both ctrlrange and inheritrange",
    );
}

/// An unlimited slide (tidybot's base in MuJoCo Menagerie) moves freely: no U305 "lower == upper == 0: it
/// cannot move", which is URDF's reading of a prismatic joint without limits (failed before: U305 on `x`).
#[test]
fn an_unlimited_slide_is_free_not_stuck_at_zero() {
    let dir = Scratch::new("mjcf-slide");
    let path = dir.file(
        "cart.xml",
        "<mujoco model=\"cart\"><worldbody><body name=\"base\"><joint name=\"x\" type=\"slide\" axis=\"1 0 0\"/>\
         <geom type=\"box\" size=\"0.1 0.1 0.1\"/><body name=\"arm\" pos=\"0 0 0.2\">\
         <joint name=\"lift\" type=\"slide\" axis=\"0 0 1\" limited=\"true\" range=\"0 0\"/>\
         <geom type=\"box\" size=\"0.05 0.05 0.05\"/></body></body></worldbody></mujoco>",
    );
    let v = run(&path);
    let stuck = findings(&v, "U305");
    assert_eq!(
        stuck.len(),
        1,
        "only the slide limited to [0, 0] is stuck: {stuck:?}"
    );
    assert!(stuck[0].2.contains("lift"), "{stuck:?}");
}

/// The 1-based line of the first line of `text` holding `needle`.
fn line_of(text: &str, needle: &str) -> u32 {
    let index = text
        .lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("'{needle}' is not in the model"));
    u32::try_from(index + 1).unwrap()
}

/// Each MJCF-only rule fires once, at the line to edit.
const MJCF_RULES: &str = r#"<mujoco>
  <compiler angle="degree" autolimits="true" balanceinertia="true" boundinertia="1e-6"/>
  <worldbody>
    <body name="arm">
      <joint name="shoulder" axis="0 1 0" range="-90 90"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.05" mass="2"/>
      <body name="fore" pos="0.5 0 0">
        <joint name="elbow" axis="0 1 0" range="-90 90" armature="0.1"/>
        <inertial pos="0.2 0 0" mass="1" diaginertia="0.01 0.01 0.05"/>
        <body name="rod" pos="0.4 0 0">
          <joint name="wrist" axis="0 1 0" range="-90 90" damping="1"/>
          <inertial pos="0.1 0 0" mass="0.5" diaginertia="0 0.001 0.001"/>
        </body>
        <body name="wheel" pos="0 0.2 0">
          <joint name="spin" axis="0 1 0" damping="1"/>
          <geom type="sphere" size="0.05" pos="0.1 0 0" mass="0.5"/>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
    <motor joint="shoulder" gear="50" ctrlrange="-1 1"/>
    <position joint="elbow" kp="100" ctrlrange="-1 1"/>
    <position joint="wrist" kp="10" ctrlrange="-1.6 1.6" forcerange="-5 5"/>
    <motor name="spinner" joint="spin"/>
  </actuator>
</mujoco>"#;

#[test]
fn the_mjcf_only_rules_fire_at_the_line_to_edit_and_not_on_the_repaired_model() {
    let dir = Scratch::new("mjcf-rules");
    let path = dir.file("m.xml", MJCF_RULES);
    let v = run(&path);
    let at = |needle| line_of(MJCF_RULES, needle);
    // A position servo's ctrlrange is in radians whatever <compiler angle> says: ±1 rad < ±90°.
    has(&v, "U034", "m.xml", at("kp=\"100\""), "elbow");
    assert_eq!(findings(&v, "U034").len(), 1, "{:?}", findings(&v, "U034"));
    // No forcerange, no ctrlrange, no actuatorfrcrange: at the actuator.
    has(&v, "U035", "m.xml", at("spinner"), "spin");
    assert_eq!(findings(&v, "U035").len(), 1, "{:?}", findings(&v, "U035"));
    // Gear 50 on a joint with neither armature nor damping: at the joint (elbow has armature, wrist
    // damping, and their actuators no gear).
    has(&v, "U036", "m.xml", at("name=\"shoulder\""), "reflected");
    assert_eq!(findings(&v, "U036").len(), 1, "{:?}", findings(&v, "U036"));
    // 0.01 + 0.01 < 0.05, and a zero moment: at each <inertial>.
    has(&v, "U037", "m.xml", at("0.01 0.01 0.05"), "balanceinertia");
    has(&v, "U037", "m.xml", at("0 0.001 0.001"), "boundinertia");
    assert_eq!(findings(&v, "U037").len(), 2, "{:?}", findings(&v, "U037"));

    let repaired = MJCF_RULES
        .replace("range=\"-90 90\"/>", "range=\"-90 90\" armature=\"0.01\"/>")
        .replace(
            "kp=\"100\" ctrlrange=\"-1 1\"",
            "kp=\"100\" ctrlrange=\"-1.6 1.6\"",
        )
        .replace("0.01 0.01 0.05", "0.03 0.03 0.05")
        .replace("0 0.001 0.001", "0.0001 0.001 0.001")
        .replace("joint=\"spin\"/>", "joint=\"spin\" ctrlrange=\"-1 1\"/>");
    let clean = dir.file("clean.xml", &repaired);
    let v = run(&clean);
    for rule in ["U034", "U035", "U036", "U037"] {
        assert!(
            findings(&v, rule).is_empty(),
            "{rule}: {:?}",
            findings(&v, rule)
        );
    }
}

#[test]
fn a_body_inside_an_ancestor_of_its_own_name_is_refused_and_does_not_hang() {
    // dm_control's reacher with its `finger` renamed `hand`, the name of the body it hangs from (MuJoCo:
    // "repeated name 'hand' in body"). Before: the weld-group walk followed the name back to itself forever.
    let dir = Scratch::new("mjcf-repeated_body");
    let path = dir.file(
        "reacher.xml",
        r#"<mujoco><worldbody><body name="arm"><joint name="shoulder" axis="0 0 1"/><geom type="capsule" fromto="0 0 0 0.1 0 0" size="0.01"/><body name="hand" pos="0.1 0 0"><joint name="wrist" axis="0 0 1"/><geom type="capsule" fromto="0 0 0 0.1 0 0" size="0.01"/><body name="hand" pos="0.1 0 0"><geom type="sphere" size="0.01"/></body></body></body></worldbody></mujoco>"#,
    );
    let v = run(&path);
    let repeated = findings(&v, "U101");
    assert_eq!(repeated.len(), 1, "{repeated:?}");
    assert!(repeated[0].2.contains("'hand'"), "{repeated:?}");
}

#[test]
fn a_file_included_twice_is_refused_at_the_second_include() {
    // MuJoCo 4.0: "File 'part.xml' already included". Before: read once, and only the duplicate names
    // it seemed to define said something was wrong.
    let dir = Scratch::new("mjcf-included_twice");
    dir.file(
        "part.xml",
        r#"<mujoco><worldbody><body name="b"><joint name="j" axis="0 1 0"/><geom type="box" size=".1 .1 .1"/></body></worldbody></mujoco>"#,
    );
    let path = dir.file(
        "twice.xml",
        "<mujoco>\n  <include file=\"part.xml\"/>\n  <include file=\"part.xml\"/>\n</mujoco>\n",
    );
    let v = run(&path);
    has(&v, "U031", "twice.xml", 3, "already included (first at ");
    assert_eq!(findings(&v, "U031").len(), 1, "{:?}", findings(&v, "U031"));
    assert!(
        findings(&v, "U101").is_empty(),
        "{:?}",
        findings(&v, "U101")
    );
}

#[test]
fn an_inertial_without_a_tensor_is_accepted_as_mujoco_accepts_it() {
    // MuJoCo 4.0 takes a zero tensor for an <inertial> with neither diaginertia nor fullinertia: a welded
    // body loads (checked with MjModel.from_xml_path), a moving one is refused for mjMINVAL. Before: a
    // CRITICAL "needs diaginertia" on both.
    let dir = Scratch::new("mjcf-inertial_without_tensor");
    let welded = dir.file(
        "welded.xml",
        r#"<mujoco><worldbody><body name="a"><joint name="j" axis="0 1 0"/><geom type="box" size=".1 .1 .1"/><body name="b" pos="0 0 .3"><inertial pos="0 0 0" mass="1"/></body></body></worldbody></mujoco>"#,
    );
    let v = run(&welded);
    assert!(
        findings(&v, "U030").is_empty(),
        "{:?}",
        findings(&v, "U030")
    );
    let moving = dir.file(
        "moving.xml",
        r#"<mujoco><worldbody><body name="b"><joint name="j" axis="0 1 0"/><inertial pos="0 0 0" mass="1"/><geom type="box" size=".1 .1 .1"/></body></worldbody></mujoco>"#,
    );
    let v = run(&moving);
    let refused = findings(&v, "U030");
    assert_eq!(refused.len(), 1, "{refused:?}");
    assert!(refused[0].2.contains("mjMINVAL"), "{refused:?}");
}

#[test]
fn gravcomp_bodies_weigh_on_no_motor() {
    // MuJoCo 4.0 on this model: qfrc_bias (-16.1865, -3.924), qfrc_gravcomp (-8.3385, -0.981); what the
    // motors hold is the difference, (-7.848, -2.943). Before: the full -16.1865 and -3.924.
    let dir = Scratch::new("mjcf-gravcomp");
    let path = dir.file(
        "arm.xml",
        r#"<mujoco><worldbody><body name="upper" gravcomp="1"><joint name="shoulder" axis="0 1 0"/><geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.02" mass="2"/><body name="fore" pos="0.5 0 0" gravcomp="0.5"><joint name="elbow" axis="0 1 0"/><geom type="capsule" fromto="0 0 0 0.4 0 0" size="0.02" mass="1"/><body name="hand" pos="0.4 0 0"><geom type="sphere" size="0.03" mass="0.5"/></body></body></body></worldbody><actuator><motor joint="shoulder" ctrlrange="-50 50"/><motor joint="elbow" ctrlrange="-50 50"/></actuator></mujoco>"#,
    );
    let v = run(&path);
    let statics = v.report.statics.as_ref().unwrap();
    let torque = |name: &str| {
        let joint = statics.joints.iter().find(|j| j.name == name).unwrap();
        (
            joint.required_torque_gravity.unwrap(),
            joint.summary.clone(),
        )
    };
    let (shoulder, summary) = torque("shoulder");
    assert!((shoulder + 7.848).abs() < 1e-9, "{shoulder}");
    assert!(
        summary.contains("gravcomp carries 2.500 of the 3.500 kg below"),
        "{summary}"
    );
    let (elbow, _) = torque("elbow");
    assert!((elbow + 2.943).abs() < 1e-9, "{elbow}");
    assert!(
        statics
            .notes
            .iter()
            .any(|n| n.contains("upper (100 %), fore (50 %)")),
        "{:?}",
        statics.notes
    );
    // The robot's mass and centre of mass are the whole robot's.
    assert!((statics.total_mass.unwrap() - 3.5).abs() < 1e-12);
}

#[test]
fn a_huge_nkey_is_refused_not_built() {
    // Found by the mjcf fuzz target: <size nkey="1e308"> made the reader build keys without end (3.7 GB in
    // 6 s). MuJoCo reads nkey as an int and refuses the model.
    let model = |nkey: &str| {
        format!(
            r#"<mujoco><size nkey="{nkey}"/><worldbody><body name="b"><joint name="j"/><geom type="sphere" size="0.1" mass="1"/></body></worldbody></mujoco>"#
        )
    };
    let dir = Scratch::new("mjcf-nkey");
    for huge in ["1e308", "4294967296", "1.5"] {
        let v = run(&dir.file("huge.xml", &model(huge)));
        assert_eq!(
            findings(&v, "U032").len(),
            1,
            "{huge}: {:?}",
            findings(&v, "U032")
        );
    }
    // A large int: the first 1,000 keys are poses, with a note.
    let v = run(&dir.file("large.xml", &model("100000")));
    has(&v, "U033", "large.xml", 1, "only the first 1000");
}

#[test]
fn statics_follow_the_models_gravity() {
    // gymnasium's pusher declares gravity="0 0 0": MuJoCo's motors hold nothing, and U701 failed the arm
    // under standard gravity. A 1 kg, 0.5 m arm on a 2 N·m motor.
    let model = |option: &str| {
        format!(
            r#"<mujoco>{option}<worldbody><body name="arm"><joint name="shoulder" axis="0 1 0"/><geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.02" mass="1"/></body></worldbody><actuator><motor joint="shoulder" ctrlrange="-2 2"/></actuator></mujoco>"#
        )
    };
    let dir = Scratch::new("mjcf-gravity");
    let torque = |v: &Validation| {
        let statics = v.report.statics.as_ref().unwrap();
        statics.joints[0].required_torque_gravity.unwrap().abs()
    };
    let earth = run(&dir.file("earth.xml", &model("")));
    assert_eq!(findings(&earth, "U701").len(), 1);
    assert!(findings(&earth, "U040").is_empty());
    assert!(
        (torque(&earth) - 0.25 * 9.81).abs() < 1e-9,
        "{}",
        torque(&earth)
    );
    for (name, option) in [
        ("zero", r#"<option gravity="0 0 0"/>"#),
        ("disabled", r#"<option><flag gravity="disable"/></option>"#),
    ] {
        let v = run(&dir.file(&format!("{name}.xml"), &model(option)));
        assert!(
            findings(&v, "U701").is_empty(),
            "{name}: {:?}",
            findings(&v, "U701")
        );
        assert_eq!(torque(&v), 0.0, "{name}");
        has(&v, "U040", &format!("{name}.xml"), 1, "not the standard");
    }
    // The moon's gravity: a sixth of the torque, and the motor holds it.
    let moon = run(&dir.file("moon.xml", &model(r#"<option gravity="0 0 -1.62"/>"#)));
    assert!(
        (torque(&moon) - 0.25 * 1.62).abs() < 1e-9,
        "{}",
        torque(&moon)
    );
    assert!(findings(&moon, "U701").is_empty());
    has(&moon, "U040", "moon.xml", 1, "(0, 0, -1.62) m/s²");
}

#[test]
fn a_ctrlrange_short_of_the_range_by_rounding_is_no_u034() {
    // SO-ARM101 (TheRobotStudio/SO-ARM100, so101_new_calib.xml): range ±1.919862, ctrlrange ±1.91986.
    // Before: U034 for a 2 µrad shortfall.
    let model = |ctrl: &str| {
        format!(
            r#"<mujoco><compiler angle="radian"/><worldbody><body name="a"><joint name="j" axis="0 1 0" range="-1.919862 1.919862"/><geom type="box" size="0.1 0.1 0.1"/></body></worldbody><actuator><position joint="j" kp="10" ctrlrange="{ctrl}"/></actuator></mujoco>"#
        )
    };
    let dir = Scratch::new("mjcf-rounding");
    let rounded = run(&dir.file("rounded.xml", &model("-1.91986 1.91986")));
    assert!(
        findings(&rounded, "U034").is_empty(),
        "{:?}",
        findings(&rounded, "U034")
    );
    // A thousandth of a radian short is a real shortfall.
    let short = run(&dir.file("short.xml", &model("-1.918 1.918")));
    assert_eq!(findings(&short, "U034").len(), 1);
    // Past the range by rounding (ur5e's 9e-5 rad): no U041 either.
    let over = run(&dir.file("over.xml", &model("-1.91995 1.91995")));
    assert!(
        findings(&over, "U041").is_empty(),
        "{:?}",
        findings(&over, "U041")
    );
}

#[test]
fn a_ctrlrange_past_the_joint_range_is_u041() {
    // Menagerie's anymal_c: HAA servos with ctrlrange ±6.28 on a joint of range [-0.72, 0.49]. Before:
    // only the opposite direction (U034) was checked.
    let dir = Scratch::new("mjcf-beyond");
    let path = dir.file(
        "anymal.xml",
        r#"<mujoco><compiler angle="radian"/><worldbody><body name="hip"><joint name="LF_HAA" axis="1 0 0" range="-0.72 0.49"/><geom type="box" size="0.1 0.1 0.1"/></body></worldbody><actuator><position joint="LF_HAA" kp="100" ctrlrange="-6.28 6.28"/></actuator></mujoco>"#,
    );
    let v = run(&path);
    has(&v, "U041", "anymal.xml", 1, "90 % of the control range");
    assert!(findings(&v, "U034").is_empty());
    // Menagerie's kinova_gen3: ±2.2497 rad on joints of ±2.24, 0.4 % past: INFO (U043), not a WARN.
    // Before: U041 saying "0 % of the control range".
    let kinova = run(&dir.file(
        "gen3.xml",
        r#"<mujoco><compiler angle="radian"/><worldbody><body name="l"><joint name="joint_2" axis="0 1 0" range="-2.24 2.24"/><geom type="box" size="0.1 0.1 0.1"/></body></worldbody><actuator><position joint="joint_2" kp="100" ctrlrange="-2.2497 2.2497"/></actuator></mujoco>"#,
    ));
    assert!(findings(&kinova, "U041").is_empty());
    has(&kinova, "U043", "gen3.xml", 1, "0.4 % of the control range");
}

#[test]
fn an_explicit_geom_mass_counts_when_its_mesh_cannot_be_read() {
    // psyonicinc/ability-hand-api's MJCF hands name meshes the repository lacks, each geom with an
    // explicit mass. Before: the mass was dropped (U203 "mass 0", a total mass too low) and MuJoCo's
    // mjMINVAL refusal (U030 CRITICAL) was claimed for a body whose inertia is unknown, not zero.
    let dir = Scratch::new("mjcf-unread_mesh");
    let path = dir.file(
        "hand.xml",
        r#"<mujoco><asset><mesh name="m" file="absent.stl"/></asset><worldbody><body name="base"><geom type="box" size=".05 .05 .05"/>
<body name="finger" pos="0 0 .1"><joint name="j" type="hinge" axis="0 1 0"/><geom type="mesh" mesh="m" mass="0.01"/></body></body></worldbody></mujoco>"#,
    );
    let v = run(&path);
    for rule in ["U030", "U203", "U204"] {
        assert!(
            findings(&v, rule).is_empty(),
            "{rule}: {:?}",
            findings(&v, rule)
        );
    }
    let statics = v.report.statics.as_ref().unwrap();
    assert!(
        (statics.total_mass.unwrap() - 1.01).abs() < 1e-12,
        "{statics:?}"
    );
    // The missing mesh itself is still said.
    assert_eq!(findings(&v, "U501").len(), 1, "{:?}", findings(&v, "U501"));
}

/// Two sibling links overlapping at qpos0, and an arm (so that self-collision is assessed) with a bracket
/// welded to its forearm overlapping the upper arm the forearm hangs from; `CONTACT` is replaced by each test's filter.
const OVERLAPPING: &str = r#"<mujoco>
  <worldbody>
    <body name="base">
      <geom type="box" size="0.1 0.1 0.05"/>
      <body name="left" pos="0 0.04 0.3">
        <joint name="l" axis="1 0 0"/>
        <geom name="left_geom" type="box" size="0.05 0.05 0.1"/>
      </body>
      <body name="right" pos="0 -0.04 0.3">
        <joint name="r" axis="1 0 0"/>
        <geom type="box" size="0.05 0.05 0.1"/>
      </body>
      <body name="upper" pos="1 0 0.3">
        <joint name="shoulder" axis="0 1 0"/>
        <geom type="box" size="0.05 0.05 0.1"/>
        <body name="fore" pos="0 0 0.3">
          <joint name="elbow" axis="0 1 0"/>
          <geom type="box" size="0.05 0.05 0.1"/>
          <body name="bracket" pos="0 0 -0.2">
            <geom type="box" size="0.02 0.02 0.02"/>
          </body>
          <body name="hand" pos="0 0 0.3">
            <joint name="wrist" axis="0 1 0"/>
            <geom type="box" size="0.03 0.03 0.05"/>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
  CONTACT
</mujoco>"#;

/// The link pairs in contact at the zero pose, as "a b" (names sorted): U601 (left out of self-collision
/// sampling) and U042 (MuJoCo collides them), which names the pairs MuJoCo collides instead of U601.
fn touching(dir: &Scratch, name: &str, contact: &str, replace: (&str, &str)) -> Vec<String> {
    let text = OVERLAPPING
        .replace("CONTACT", contact)
        .replace(replace.0, replace.1);
    let v = run(&dir.file(name, &text));
    let mut pairs: Vec<String> = findings(&v, "U601")
        .into_iter()
        .chain(findings(&v, "U042"))
        .map(|(_, _, m)| {
            let mut names: Vec<&str> = m.split('\'').skip(1).step_by(2).take(2).collect();
            names.sort();
            names.join(" ")
        })
        .collect();
    pairs.sort();
    pairs
}

#[test]
fn self_collision_pairs_follow_mujocos_contact_filter() {
    let dir = Scratch::new("mjcf-contacts");
    let none = ("", "");
    // Unfiltered, the siblings touch; the bracket welded to 'fore' is filtered against 'upper', the body
    // 'fore' hangs from (MuJoCo's parent filter), so it is not a contact.
    assert_eq!(touching(&dir, "plain.xml", "", none), ["left right"]);
    // An exclusion.
    let exclude = r#"<contact><exclude body1="right" body2="left"/></contact>"#;
    assert!(touching(&dir, "exclude.xml", exclude, none).is_empty());
    // contype 2 / conaffinity 2 against 1 / 1: (2 & 1) | (1 & 2) = 0.
    let bits = (
        r#"name="left_geom""#,
        r#"name="left_geom" contype="2" conaffinity="2""#,
    );
    assert!(touching(&dir, "bits.xml", "", bits).is_empty());
    // contype 3 meets conaffinity 1: they collide again.
    let overlap = (
        r#"name="left_geom""#,
        r#"name="left_geom" contype="3" conaffinity="2""#,
    );
    assert_eq!(touching(&dir, "overlap.xml", "", overlap), ["left right"]);
    // Without MuJoCo's parent filter the bracket touches the upper arm.
    let no_parent = r#"<option><flag filterparent="disable"/></option>"#;
    assert_eq!(
        touching(&dir, "noparent.xml", no_parent, none),
        ["bracket upper", "left right"]
    );
}

#[test]
fn an_include_problem_inside_a_section_is_reported_once() {
    let dir = Scratch::new("mjcf-include-once");
    let path = dir.file(
        "m.xml",
        r#"<mujoco>
  <worldbody><include file="missing.xml"/><body name="b"><joint/><geom size="0.1"/></body></worldbody>
  <contact><include file="gone.xml"/></contact>
</mujoco>"#,
    );
    let v = run(&path);
    let found = findings(&v, "U031");
    assert_eq!(found.len(), 2, "{found:?}");
    has(&v, "U031", "m.xml", 2, "no such file");
    has(&v, "U031", "m.xml", 3, "no such file");
}

/// A moving body that has, with the bodies welded to it, no mass is U030 at the body: MuJoCo 4.0 refuses
/// these models ("mass and inertia of moving bodies must be larger than mjMINVAL"), and accepts a massless
/// moving body whose welded child carries mass. (Failed before: no U030.)
/// MuJoCo refuses `shellinertia` on a mesh geom (a mesh's shell is `<mesh inertia="shell">`); on a
/// primitive it is read (its mass against MuJoCo's: `tests/mjcf_golden.rs`, the shells model).
#[test]
fn shellinertia_on_a_mesh_geom_is_refused_as_mujoco_refuses_it() {
    let dir = Scratch::new("mjcf-shellmesh");
    let text = r#"<mujoco>
  <asset><mesh name="m" file="m.stl"/></asset>
  <worldbody>
    <body name="a">
      <joint axis="0 1 0"/>
      <geom type="mesh" mesh="m" shellinertia="true"/>
      <geom type="box" size="0.1 0.1 0.1" shellinertia="true"/>
    </body>
  </worldbody>
</mujoco>"#;
    let path = dir.file("m.xml", text);
    let v = run(&path);
    has(
        &v,
        "U030",
        "m.xml",
        line_of(text, "type=\"mesh\""),
        "shellinertia on a mesh geom",
    );
    assert_eq!(findings(&v, "U030").len(), 1, "{:?}", findings(&v, "U030"));
}

#[test]
fn a_moving_body_without_mass_is_refused_as_mujoco_refuses_it() {
    let dir = Scratch::new("mjcf-massless");
    let refused = dir.file(
        "refused.xml",
        "<mujoco>\n<worldbody>\n<body name=\"upper\">\n<joint name=\"a\"/>\n\
         <body name=\"lower\" pos=\"1 0 0\">\n<joint name=\"b\"/>\n<geom size=\"0.1\" mass=\"0\"/>\n\
         <body name=\"tip\"><geom size=\"0.1\"/></body>\n</body>\n</body>\n</worldbody>\n</mujoco>",
    );
    let v = run(&refused);
    let found = findings(&v, "U030");
    assert_eq!(found.len(), 1, "{found:?}");
    has(&v, "U030", "refused.xml", 3, "body 'upper' moves");
    let accepted = dir.file(
        "accepted.xml",
        "<mujoco>\n<worldbody>\n<body name=\"upper\">\n<joint name=\"a\"/>\n\
         <body name=\"bracket\" pos=\"1 0 0\">\n<geom size=\"0.1\"/>\n</body>\n</body>\n</worldbody>\n</mujoco>",
    );
    assert!(findings(&run(&accepted), "U030").is_empty());
}

/// A floating base, a hinge with `ref` (degrees), a slide with `ref` and a ball joint, with keyframes.
const KEYFRAMES: &str = r#"<mujoco>
  <compiler angle="degree"/>
  <worldbody>
    <body name="base" pos="0 0 1">
      <freejoint name="root"/>
      <geom type="box" size="0.1 0.1 0.1" mass="5"/>
      <body name="upper" pos="0 0 0.1">
        <joint name="hinge" axis="0 1 0" ref="30"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02" mass="1"/>
        <body name="slider" pos="0.3 0 0">
          <joint name="slide" type="slide" axis="1 0 0" ref="0.05"/>
          <geom type="sphere" size="0.03" mass="0.5"/>
          <body name="wrist" pos="0.1 0 0">
            <joint name="ball" type="ball"/>
            <geom type="sphere" size="0.02" pos="0.05 0 0" mass="0.2"/>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
  <keyframe>
    <key name="home" qpos="0 0 1 1 0 0 0  0.7  0.15  0.5 0.5 0.5 0.5" ctrl=""/>
    <key name="short" qpos="0 0 1 1 0 0 0  0.2"/>
    <key name="tilted" time="1" qpos="0 0 1 0.7071068 0.7071068 0 0"/>
    <key qpos="0 0 0.5"/>
    <key name="long" qpos="0 0 1 1 0 0 0 0 0 1 0 0 0 7"/>
  </keyframe>
</mujoco>"#;

fn at_pose(path: &Path, kind: PoseKind) -> Result<Validation, String> {
    let mut options = options();
    options.statics.pose.kind = kind;
    validate(path, &options).map_err(|e| e.to_string())
}

fn configuration(v: &Validation) -> std::collections::BTreeMap<String, f64> {
    v.report.statics.as_ref().unwrap().configuration.clone()
}

/// `<size nkey="N">` gives a model N keys at least, those not written at `qpos0` and named by index, as
/// MuJoCo compiles it (dm_control's dog: `nkey="1"` and no `<key>`; its golden has MuJoCo's `key:0`, and
/// `--pose key:0` was a usage error before: "the model has no keyframe '0'").
#[test]
fn size_nkey_adds_keys_at_qpos0_named_by_index() {
    let dir = Scratch::new("mjcf-nkey");
    let path = dir.file(
        "m.xml",
        r#"<mujoco>
  <compiler angle="radian"/>
  <size nkey="3"/>
  <worldbody>
    <body name="a">
      <joint name="j" axis="0 1 0" range="-1 1" ref="0.2"/>
      <geom type="sphere" size="0.05" pos="0.3 0 0" mass="1"/>
    </body>
  </worldbody>
  <keyframe><key name="bent" qpos="0.7"/></keyframe>
</mujoco>"#,
    );
    let bent = at_pose(&path, PoseKind::Key("bent".to_string())).unwrap();
    assert!((configuration(&bent)["j"] - 0.5).abs() < 1e-12);
    for index in ["1", "2"] {
        let v = at_pose(&path, PoseKind::Key(index.to_string())).unwrap();
        assert_eq!(configuration(&v)["j"], 0.0, "key {index} is at qpos0");
    }
    assert!(at_pose(&path, PoseKind::Key("3".to_string())).is_err());
}

/// Menagerie's G1 with hands (its issue #296): a key that puts a joint past its range and a control past
/// its actuator's `ctrlrange`. Checked in `qpos` terms, `ref` and degrees included; a key inside the
/// ranges, a slide's exact limit and an unlimited joint give nothing.
#[test]
fn a_keyframe_outside_a_joints_range_or_a_ctrlrange_is_a_u039() {
    let dir = Scratch::new("mjcf-keyrange");
    let path = dir.file(
        "m.xml",
        r#"<mujoco>
  <worldbody>
    <body name="a">
      <joint name="hinge" axis="0 1 0" range="-30 60" ref="10"/>
      <geom type="sphere" size="0.05" pos="0.3 0 0" mass="1"/>
      <body name="b" pos="0.3 0 0">
        <joint name="slide" type="slide" axis="1 0 0" range="0 0.1"/>
        <joint name="free_spin" axis="0 0 1"/>
        <geom type="sphere" size="0.05" mass="1"/>
      </body>
    </body>
  </worldbody>
  <actuator>
    <position name="servo" joint="hinge" ctrlrange="-0.5 1" kp="10"/>
    <motor joint="slide" ctrlrange="-1 1"/>
  </actuator>
  <keyframe>
    <key name="inside" qpos="1.0 0.1 5" ctrl="1 -1"/>
    <key name="past" qpos="1.1 0.1 5" ctrl="0.2 1.5"/>
  </keyframe>
</mujoco>"#,
    );
    let v = run(&path);
    let found = findings(&v, "U039");
    assert_eq!(found.len(), 2, "{found:?}");
    // 60° is 1.047 rad: 1.1 is past it (the ref does not move the range in qpos terms).
    assert!(
        found[0].2.contains("keyframe 'past'") && found[0].2.contains("joint 'hinge' at 1.1"),
        "{found:?}"
    );
    assert!(found[0].2.contains("1.047198"), "{found:?}");
    assert!(
        found[1].2.contains("actuator 'actuator#1' at 1.5"),
        "{found:?}"
    );
    assert_eq!(
        found[0].1,
        line_of(&std::fs::read_to_string(&path).unwrap(), "name=\"past\"")
    );
}

#[test]
fn keyframes_are_poses_in_mujocos_qpos_order() {
    let dir = Scratch::new("mjcf-keys");
    let path = dir.file("m.xml", KEYFRAMES);
    let v = at_pose(&path, PoseKind::Key("home".to_string())).unwrap();
    let statics = v.report.statics.as_ref().unwrap();
    assert_eq!(statics.pose, "key:home");
    let q = configuration(&v);
    // q = qpos − ref: the hinge's ref is 30°, the slide's 0.05 m.
    assert!(
        (q["hinge"] - (0.7 - 30f64.to_radians())).abs() < 1e-12,
        "{q:?}"
    );
    assert!((q["slide"] - 0.1).abs() < 1e-12, "{q:?}");
    // The ball's quaternion as the chained hinges x, y, z: exactly its rotation.
    let turn = |axis: Vector3<f64>, angle: f64| {
        UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle)
    };
    let chained = turn(Vector3::x(), q["ball_x"])
        * turn(Vector3::y(), q["ball_y"])
        * turn(Vector3::z(), q["ball_z"]);
    let key = UnitQuaternion::from_quaternion(Quaternion::new(0.5, 0.5, 0.5, 0.5));
    assert!(chained.angle_to(&key) < 1e-12, "{q:?}");
    assert!(
        statics
            .notes
            .iter()
            .any(|n| n.contains("ball joint 'ball'")),
        "{:?}",
        statics.notes
    );

    // A short key leaves the rest at qpos0 (q = 0), as MuJoCo does.
    let q = configuration(&at_pose(&path, PoseKind::Key("short".to_string())).unwrap());
    assert!(
        (q["hinge"] - (0.2 - 30f64.to_radians())).abs() < 1e-12,
        "{q:?}"
    );
    assert_eq!((q["slide"], q["ball_x"], q["ball_y"]), (0.0, 0.0, 0.0));

    // The base is not moved: a tilted or moved free joint is a note; an unnamed key is named by its index.
    let v = at_pose(&path, PoseKind::Key("tilted".to_string())).unwrap();
    let notes = &v.report.statics.as_ref().unwrap().notes;
    assert!(
        notes
            .iter()
            .any(|n| n.contains("'root' is not moved nor turned")),
        "{notes:?}"
    );
    let v = at_pose(&path, PoseKind::Key("3".to_string())).unwrap();
    let notes = &v.report.statics.as_ref().unwrap().notes;
    assert!(
        notes.iter().any(|n| n.contains("'root' is not moved:")),
        "{notes:?}"
    );

    // A key longer than the model's qpos is refused by MuJoCo: U030 at it, and it is no pose.
    has(
        &v,
        "U030",
        "m.xml",
        line_of(KEYFRAMES, "name=\"long\""),
        "invalid qpos size",
    );
    let why = at_pose(&path, PoseKind::Key("long".to_string())).unwrap_err();
    assert!(why.contains("no keyframe 'long'"), "{why}");
    let why = at_pose(&path, PoseKind::Key("nope".to_string())).unwrap_err();
    assert!(why.contains("its keys: home, short, tilted, 3"), "{why}");

    // --pose home without an SRDF: the model's keyframe 'home'.
    let v = at_pose(&path, PoseKind::Home).unwrap();
    let statics = v.report.statics.as_ref().unwrap();
    assert_eq!(statics.pose, "home");
    assert!((statics.configuration["slide"] - 0.1).abs() < 1e-12);
    assert!(statics.notes.iter().any(|n| n.contains("keyframe 'home'")));

    // key: on a URDF is a usage error saying why.
    let urdf = dir.file("r.urdf", r#"<robot name="r"><link name="a"/></robot>"#);
    let why = at_pose(&urdf, PoseKind::Key("home".to_string())).unwrap_err();
    assert!(
        why.contains("keyframes are MJCF's") && why.contains("URDF"),
        "{why}"
    );
}

/// Two fingers coupled by a joint equality, a held joint, a nonlinear coupling, a four-bar closed by a
/// connect, a weld to the world, and what is not read or switched off.
const EQUALITY: &str = r#"<mujoco>
  <compiler angle="radian" autolimits="true"/>
  <default>
    <default class="off"><equality active="false"/></default>
  </default>
  <worldbody>
    <body name="palm" pos="0 0 0.5">
      <joint name="lift" type="slide" axis="0 0 1" range="-0.1 0.1"/>
      <geom type="box" size="0.05 0.05 0.02" mass="1"/>
      <body name="left" pos="0 0.03 0">
        <joint name="left_finger" type="slide" axis="0 1 0" range="0 0.04"/>
        <geom type="box" size="0.01 0.01 0.04" pos="0 0 -0.04" mass="0.1"/>
      </body>
      <body name="right" pos="0 -0.03 0">
        <joint name="right_finger" type="slide" axis="0 -1 0" range="0 0.04"/>
        <geom type="box" size="0.01 0.01 0.04" pos="0 0 -0.04" mass="0.1"/>
      </body>
      <body name="crank" pos="0.1 0 0">
        <joint name="crank_joint" axis="0 1 0" range="-1 1"/>
        <geom type="capsule" fromto="0 0 0 0.1 0 0" size="0.01" mass="0.2"/>
        <body name="rocker" pos="0.1 0 0">
          <joint name="rocker_joint" axis="0 1 0" range="-1 1"/>
          <geom type="capsule" fromto="0 0 0 0 0 -0.1" size="0.01" mass="0.2"/>
        </body>
      </body>
      <body name="wheel" pos="0 0 0.1">
        <joint name="locked" axis="0 0 1" range="-1 1"/>
        <geom type="box" size="0.05 0.01 0.01" pos="0.05 0 0" mass="0.1"/>
      </body>
    </body>
  </worldbody>
  <equality>
    <joint joint1="right_finger" joint2="left_finger" polycoef="0.001 1 0 0 0"/>
    <joint joint1="rocker_joint" joint2="crank_joint" polycoef="0 -0.5 0.2 0 0"/>
    <joint joint1="locked" polycoef="0.5 0 0 0 0"/>
    <connect body1="rocker" body2="palm" anchor="0 0 -0.1"/>
    <weld body1="palm"/>
    <tendon tendon1="t"/>
    <connect body1="left" body2="right" anchor="0 0 0" active="false"/>
    <connect class="off" body1="left" body2="crank" anchor="0 0 0"/>
    <joint joint1="nothing" joint2="left_finger"/>
  </equality>
  <actuator>
    <motor joint="lift" ctrlrange="-100 100"/>
    <motor joint="left_finger" ctrlrange="-10 10"/>
    <motor joint="crank_joint" ctrlrange="-10 10"/>
  </actuator>
  <keyframe>
    <key name="k" qpos="0.05 0.02 0.03 0.3 -0.15 0.5"/>
  </keyframe>
</mujoco>"#;

#[test]
fn equality_constraints_are_couplings_held_joints_and_reported_loops() {
    let dir = Scratch::new("mjcf-equality");
    let path = dir.file("m.xml", EQUALITY);
    let r = robot(&path);
    let joint = |name: &str| r.joints.iter().find(|j| j.name.value == name).unwrap();
    // joint1 follows joint2: q1 = a0 + a1·q2, in qpos − qpos0 of both (this reader's q).
    let mimic = joint("right_finger").mimic.as_ref().unwrap();
    assert_eq!(mimic.joint.value, "left_finger");
    assert_eq!((mimic.multiplier, mimic.offset), (1.0, 0.001));
    let mimic = joint("rocker_joint").mimic.as_ref().unwrap();
    assert_eq!((mimic.multiplier, mimic.offset), (-0.5, 0.0));
    // Without joint2 the joint is held at a0: fixed, its child turned by 0.5 rad about the axis.
    let locked = joint("locked");
    assert_eq!(locked.kind.as_ref().unwrap().value, JointKind::Fixed);
    let [x, y, z, w] = locked.origin.quat_xyzw.unwrap();
    let turn = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
    assert!((turn.angle() - 0.5).abs() < 1e-12 && (z - (0.25f64).sin()).abs() < 1e-12);

    let v = run(&path);
    let line = |needle: &str| line_of(EQUALITY, needle);
    has(
        &v,
        "U033",
        "m.xml",
        line("polycoef=\"0 -0.5 0.2"),
        "linear part",
    );
    has(
        &v,
        "U038",
        "m.xml",
        line("<connect body1=\"rocker\""),
        "body 'rocker' and body 'palm' closes a kinematic loop",
    );
    has(
        &v,
        "U038",
        "m.xml",
        line("<weld body1=\"palm\""),
        "body 'palm' and the world",
    );
    has(&v, "U033", "m.xml", line("<tendon tendon1"), "not read");
    has(
        &v,
        "U030",
        "m.xml",
        line("joint1=\"nothing\""),
        "no hinge or slide joint",
    );
    // Switched off (written, or by class): nothing.
    assert_eq!(findings(&v, "U038").len(), 2, "{:?}", findings(&v, "U038"));
    // The coupled fingers are one drive: the follower's gravity load is its leader's to hold, and the
    // pair is not a mirrored pair differing in effort.
    let statics = v.report.statics.as_ref().unwrap();
    let follower = statics
        .joints
        .iter()
        .find(|j| j.name == "right_finger")
        .unwrap();
    assert_eq!(follower.mimics.as_deref(), Some("left_finger"));
    assert!(
        findings(&v, "U770").is_empty(),
        "{:?}",
        findings(&v, "U770")
    );
    assert!(!statics.joints.iter().any(|j| j.name == "locked"));

    // A keyframe sets the leaders; followers follow them, the held joint stays held.
    let v = at_pose(&path, PoseKind::Key("k".to_string())).unwrap();
    let q = configuration(&v);
    assert_eq!(
        (q["lift"], q["left_finger"], q["crank_joint"]),
        (0.05, 0.02, 0.3)
    );
    assert!(
        !q.contains_key("locked") && !q.contains_key("right_finger"),
        "{q:?}"
    );
}

/// MuJoCo reads an OBJ mesh's vertices as single-precision floats (tinyobjloader's `real_t`), so a mesh
/// whose coordinates are not floats (0.1 here) has the volume of its vertices rounded to f32: MuJoCo 4.0
/// gives this cube 8.000000357627876 kg, 1000 × (2 · 0.1f32)³, not 8 kg. Found on the full Menagerie
/// (flexiv_rizon4's OBJ links differed from MuJoCo by 3e-9 of their mass); STL meshes are floats already.
#[test]
fn an_obj_mesh_has_the_mass_of_its_vertices_rounded_to_floats_as_mujoco_reads_them() {
    let dir = Scratch::new("mjcf-obj-f32");
    let mut obj = String::new();
    for x in [-0.1, 0.1] {
        for y in [-0.1, 0.1] {
            for z in [-0.1, 0.1] {
                obj.push_str(&format!("v {x} {y} {z}\n"));
            }
        }
    }
    obj.push_str("f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n");
    dir.file("assets/cube.obj", &obj);
    let path = dir.file(
        "cube.xml",
        "<mujoco model=\"cube\"><compiler meshdir=\"assets\"/><asset><mesh name=\"cube\" file=\"cube.obj\"/>\
         </asset><worldbody><body name=\"box\"><joint name=\"hinge\" axis=\"1 0 0\"/>\
         <geom type=\"mesh\" mesh=\"cube\"/></body></worldbody></mujoco>",
    );
    let robot = robot(&path);
    let link = robot.links.iter().find(|l| l.name.value == "box").unwrap();
    let mass = link.inertial.as_ref().unwrap().mass.as_ref().unwrap().value;
    let side = 2.0 * f64::from(0.1_f32);
    let expected = 1000.0 * side * side * side;
    assert!(
        ((mass - expected) / expected).abs() < 1e-12,
        "mass {mass}, MuJoCo's {expected} (not {})",
        1000.0 * 0.2_f64.powi(3)
    );
}

/// The vertices of a box mesh, x in [0, 0.2], y in [-0.05, 0.05], z in [-0.1, 0.1] (centre 0.1, 0, 0).
fn off_centre_box() -> String {
    let mut obj = String::new();
    for x in [0.0, 0.2] {
        for y in [-0.05, 0.05] {
            for z in [-0.1, 0.1] {
                obj.push_str(&format!("v {x} {y} {z}\n"));
            }
        }
    }
    obj + "f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n"
}

/// The mass and centre of mass (in its body's frame) of body `box` of the model `text` in `dir`.
fn box_mass(dir: &Scratch, text: &str) -> (f64, [f64; 3]) {
    let path = dir.file("model.xml", text);
    let robot = robot(&path);
    let link = robot.links.iter().find(|l| l.name.value == "box").unwrap();
    let inertial = link.inertial.as_ref().unwrap();
    (inertial.mass.as_ref().unwrap().value, inertial.origin.xyz)
}

/// A mesh's `refpos`/`refquat` is the frame its vertices are written in: MuJoCo moves them by its inverse
/// and then scales them (MuJoCo 4.0 puts this box's centre at x = -0.05, and at -0.1 with `scale="2 1 1"`;
/// read without them it was at x = +0.1). Found on the full Menagerie (shadow_dexee's fingers).
#[test]
fn a_mesh_reference_frame_moves_its_vertices_before_the_scale() {
    let dir = Scratch::new("mjcf-refquat");
    dir.file("offbox.obj", &off_centre_box());
    for (scale, x) in [("1 1 1", -0.05), ("2 1 1", -0.1)] {
        let (_, com) = box_mass(
            &dir,
            &format!(
                "<mujoco><asset><mesh name=\"m\" file=\"offbox.obj\" refpos=\"0.1 0.05 0\" refquat=\"1 0 0 1\" \
                 scale=\"{scale}\"/></asset><worldbody><body name=\"box\"><joint axis=\"1 0 0\"/>\
                 <geom type=\"mesh\" mesh=\"m\"/></body></worldbody></mujoco>"
            ),
        );
        assert!(
            (com[0] - x).abs() < 1e-7 && com[1].abs() < 1e-7 && com[2].abs() < 1e-7,
            "scale {scale}: centre of mass {com:?}, MuJoCo's ({x}, 0, 0)"
        );
    }
}

/// A mesh declared in an included file that is not under `meshdir` is looked for in the included file's
/// folder, as MuJoCo 4.0 does (ms_human_700's `assets/asset/*.xml` name `../geometry/*.stl`): the body
/// gets the mesh's mass, not none with a "mesh not found".
#[test]
fn a_mesh_of_an_included_file_is_found_beside_that_file() {
    let dir = Scratch::new("mjcf-include-mesh");
    dir.file("parts/offbox.obj", &off_centre_box());
    dir.file(
        "parts/assets.xml",
        "<mujoco><asset><mesh name=\"m\" file=\"offbox.obj\"/></asset></mujoco>",
    );
    let (mass, _) = box_mass(
        &dir,
        "<mujoco><compiler meshdir=\"meshes\"/><include file=\"parts/assets.xml\"/><worldbody>\
         <body name=\"box\"><joint axis=\"1 0 0\"/><geom type=\"mesh\" mesh=\"m\"/></body></worldbody></mujoco>",
    );
    assert!(
        (mass - 4.0).abs() < 1e-6,
        "mass {mass}: the 4 kg mesh was not found"
    );
}

#[test]
fn the_saved_path_is_only_given_for_the_text_on_disk() {
    // `--deep` hands MuJoCo the file itself: an editor's unsaved buffer is another model.
    let dir = Scratch::new("mjcf-saved");
    let text = r#"<mujoco><worldbody><body name="a"><joint axis="0 0 1"/><geom size="0.1"/></body></worldbody></mujoco>"#;
    let path = dir.file("m.xml", text);
    let resolver = PackageResolver::default();
    let saved = Loaded::read(&path, &[], &resolver).unwrap();
    assert_eq!(
        saved.saved_path(),
        Some(std::path::absolute(&path).unwrap())
    );
    let edited = text.replace("0.1", "0.2");
    let unsaved = Loaded::from_unsaved(edited, &path, &[], &resolver).unwrap();
    assert_eq!(unsaved.saved_path(), None);
}
