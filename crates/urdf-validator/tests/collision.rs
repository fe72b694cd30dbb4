//! Self-collision engine on analytic robots (exact distances, a known colliding fraction, every rule of
//! the allowed-collision matrix), a mesh hull, degenerate input, and PR2 with its real meshes.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
use std::fs;
use std::path::{Path, PathBuf};

use nalgebra::Isometry3;
use urdf_validator::analysis::collision::{
    Allowed, CheckScratch, CollisionModel, PairSet, PoseCheck,
};
use urdf_validator::analysis::pose::ConfigurationSampler;
use urdf_validator::input::mesh::MeshCache;
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::input::srdf::srdf_collisions;
use urdf_validator::model::kinematics::{forward_kinematics, Data};
use urdf_validator::model::{JointId, LinkId, Model};
use urdf_validator::urdf::robot::Robot;

/// A parsed robot with its tree and collision model.
struct Setup {
    robot: Robot,
    model: Model,
    collision: CollisionModel,
}

impl Setup {
    /// Meshes are loaded from `dir` (relative paths) when given.
    fn new(urdf: &str, dir: Option<&Path>) -> Setup {
        let path = dir.unwrap_or(Path::new(".")).join("robot.urdf");
        let (robot, _) = urdf_validator::urdf::parse::parse_urdf(urdf, &path).expect("parses");
        let (model, findings) = Model::build(&robot);
        assert!(findings.is_empty(), "{findings:?}");
        let resolver = PackageResolver::default();
        let meshes = MeshCache::new();
        let assets = urdf_validator::assets::Assets::load(
            &robot,
            &urdf_validator::assets::AssetSource {
                urdf_path: &path,
                resolver: &resolver,
                meshes: &meshes,
                srdf: None,
            },
        );
        let collision = CollisionModel::build(&robot, &model, &assets.supports);
        Setup {
            robot,
            model,
            collision,
        }
    }

    fn link(&self, name: &str) -> LinkId {
        self.model
            .link(name)
            .unwrap_or_else(|| panic!("no link {name}"))
    }

    fn joint(&self, name: &str) -> JointId {
        self.model
            .joint(name)
            .unwrap_or_else(|| panic!("no joint {name}"))
    }

    fn name(&self, link: LinkId) -> &str {
        &self.robot.links[link.0].name.value
    }

    fn names(&self, pairs: &[(LinkId, LinkId)]) -> Vec<(String, String)> {
        pairs
            .iter()
            .map(|&(a, b)| (self.name(a).to_string(), self.name(b).to_string()))
            .collect()
    }

    /// Link placements with the named joints set (others at 0).
    fn placements(&self, joints: &[(&str, f64)]) -> Vec<Isometry3<f64>> {
        let mut q = self.model.zero_configuration();
        for (name, value) in joints {
            q[self.joint(name).0] = *value;
        }
        self.model.apply_mimic(&mut q);
        let mut data = Data::new(&self.model);
        forward_kinematics(&self.model, &q, &mut data);
        data.link_placement
    }

    /// Every pair moved by the named joints.
    fn moved_by(&self, joints: &[&str]) -> PairSet {
        let ids: Vec<JointId> = joints.iter().map(|j| self.joint(j)).collect();
        self.collision.pairs_moved_by(&self.model.motion_of(&ids))
    }

    fn check(&self, pairs: &PairSet, joints: &[(&str, f64)], cutoff: f64) -> PoseCheck {
        let placements = self.placements(joints);
        let mut scratch = CheckScratch::new(&self.collision);
        self.collision
            .check(pairs, &placements, cutoff, &mut scratch)
    }

    /// The clearance of a collision-free pose, with no cutoff.
    fn clearance(&self, pairs: &PairSet, joints: &[(&str, f64)]) -> f64 {
        let check = self.check(pairs, joints, f64::INFINITY);
        assert!(check.is_free(), "{:?} collides", check.contact);
        check.min_clearance.expect("a pair is in range").0
    }
}

const INERTIAL: &str = r#"<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>"#;

/// A link with one collision shape (`geometry` is the inside of `<geometry>`), at `origin` (xyz, rpy).
fn link(name: &str, geometry: &str, origin: &str) -> String {
    format!(
        r#"<link name="{name}">{INERTIAL}<collision><origin {origin}/><geometry>{geometry}</geometry></collision></link>"#
    )
}

fn joint(name: &str, kind: &str, parent: &str, child: &str, extra: &str) -> String {
    format!(
        r#"<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>{extra}</joint>"#
    )
}

const LIMITS: &str = r#"<limit lower="-3.14159" upper="3.14159" effort="10" velocity="1"/>"#;

fn robot(parts: &[String]) -> String {
    format!(
        "<robot name=\"r\" version=\"1.1\">{}</robot>",
        parts.concat()
    )
}

/// base (box 0.2) —j1 (revolute about z)→ hub (sphere 0.01) —fixed, 1 m along x→ far (box 0.2).
fn two_boxes() -> String {
    let axis_z = format!(r#"<axis xyz="0 0 1"/>{LIMITS}"#);
    robot(&[
        link("base", r#"<box size="0.2 0.2 0.2"/>"#, r#"xyz="0 0 0""#),
        link("hub", r#"<sphere radius="0.01"/>"#, r#"xyz="0 0 0""#),
        link("far", r#"<box size="0.2 0.2 0.2"/>"#, r#"xyz="0 0 0""#),
        joint("j1", "revolute", "base", "hub", &axis_z),
        joint("fix", "fixed", "hub", "far", r#"<origin xyz="1 0 0"/>"#),
    ])
}

#[test]
fn two_boxes_have_their_exact_clearance() {
    let setup = Setup::new(&two_boxes(), None);
    let pairs = setup.moved_by(&["j1"]);
    let (base, far) = (setup.link("base"), setup.link("far"));
    assert_eq!(pairs.pairs(), &[(base, far)], "hub is adjacent to both");
    // Faces 0.8 apart; at 90° the same by symmetry.
    for angle in [0.0, FRAC_PI_2, -PI / 2.0] {
        let d = setup.clearance(&pairs, &[("j1", angle)]);
        assert!((d - 0.8).abs() < 1e-9, "{angle}: {d}");
    }
    // At 45° the far box turns a face to base's corner (0.1, 0.1): 0.9 − 0.1·√2.
    let d = setup.clearance(&pairs, &[("j1", FRAC_PI_4)]);
    assert!((d - (0.9 - 0.1 * 2f64.sqrt())).abs() < 1e-9, "{d}");
    let check = setup.check(&pairs, &[("j1", 0.0)], f64::INFINITY);
    assert_eq!(check.min_clearance.map(|c| c.1), Some((base, far)));
    // A cutoff below the clearance: nothing to report, and no contact either.
    let check = setup.check(&pairs, &[("j1", 0.0)], 0.5);
    assert_eq!(check, PoseCheck::default());
    // A cutoff above it: reported.
    let check = setup.check(&pairs, &[("j1", 0.0)], 0.81);
    assert!((check.min_clearance.expect("below the cutoff").0 - 0.8).abs() < 1e-9);
}

/// base (sphere 0.1) —slide (prismatic along x)→ carriage (sphere 0.01, 0.5 m back) —fixed→ rod: a capsule
/// (radius 0.05, length 0.4) 0.5 m along x, lying along x when `lying`, else upright.
fn sphere_and_capsule(lying: bool) -> String {
    let rpy = if lying {
        "0 1.5707963267948966 0"
    } else {
        "0 0 0"
    };
    let slide = r#"<axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/>"#;
    robot(&[
        link("base", r#"<sphere radius="0.1"/>"#, r#"xyz="0 0 0""#),
        link(
            "carriage",
            r#"<sphere radius="0.01"/>"#,
            r#"xyz="-0.5 0 0""#,
        ),
        link(
            "rod",
            r#"<capsule radius="0.05" length="0.4"/>"#,
            &format!(r#"xyz="0.5 0 0" rpy="{rpy}""#),
        ),
        joint("slide", "prismatic", "base", "carriage", slide),
        joint("fix", "fixed", "carriage", "rod", ""),
    ])
}

#[test]
fn sphere_and_capsule_distances_are_exact() {
    let upright = Setup::new(&sphere_and_capsule(false), None);
    let pairs = upright.moved_by(&["slide"]);
    assert_eq!(pairs.len(), 1);
    // Side of the capsule: 0.5 − 0.05 − 0.1.
    let d = upright.clearance(&pairs, &[("slide", 0.0)]);
    assert!((d - 0.35).abs() < 1e-9, "{d}");
    let lying = Setup::new(&sphere_and_capsule(true), None);
    let pairs = lying.moved_by(&["slide"]);
    // Rounded end: 0.5 − 0.2 − 0.05 − 0.1, then slid closer.
    for (slide, expected) in [(0.0, 0.15), (-0.1, 0.05), (0.25, 0.4)] {
        let d = lying.clearance(&pairs, &[("slide", slide)]);
        assert!((d - expected).abs() < 1e-9, "{slide}: {d}");
    }
    let check = lying.check(&pairs, &[("slide", -0.2)], f64::INFINITY);
    assert_eq!(check.contact, Some((lying.link("base"), lying.link("rod"))));
    assert_eq!(
        check.min_clearance, None,
        "a colliding pose has no clearance"
    );
}

/// base carries a wall (a box whose near face is the plane y = `wall`) and, rigidly, a pedestal; the arm
/// swings about z on the pedestal over [−π/2, π/2]; its capsule (radius 0.02) runs from 0.1 to 0.9 m
/// along its x axis, so it reaches y = 0.9·sin θ + 0.02: it hits the wall exactly when θ > θ0 with
/// 0.9·sin θ0 + 0.02 = wall.
fn swinging_arm(theta0: f64) -> String {
    let wall = 0.9 * theta0.sin() + 0.02;
    let swing = r#"<axis xyz="0 0 1"/><limit lower="-1.5707963267948966" upper="1.5707963267948966" effort="10" velocity="1"/>"#;
    robot(&[
        link(
            "base",
            r#"<box size="2 1 1"/>"#,
            &format!(r#"xyz="0 {} 0""#, wall + 0.5),
        ),
        link("pedestal", r#"<sphere radius="0.05"/>"#, r#"xyz="0 0 0""#),
        link(
            "arm",
            r#"<capsule radius="0.02" length="0.8"/>"#,
            r#"xyz="0.5 0 0" rpy="0 1.5707963267948966 0""#,
        ),
        joint("mount", "fixed", "base", "pedestal", ""),
        joint("swing", "revolute", "pedestal", "arm", swing),
    ])
}

#[test]
fn a_swinging_arm_collides_in_the_analytic_fraction_of_poses() {
    let theta0: f64 = 0.5;
    let setup = Setup::new(&swinging_arm(theta0), None);
    let (base, arm) = (setup.link("base"), setup.link("arm"));
    assert_eq!(
        setup.collision.allowed(base, setup.link("pedestal")),
        Some(Allowed::Adjacent),
        "joined by a fixed joint: adjacent comes first"
    );
    let pairs = setup.moved_by(&["swing"]);
    assert_eq!(pairs.pairs(), &[(base, arm)]);
    // Either side of θ0.
    let d = setup.clearance(&pairs, &[("swing", theta0 - 1e-3)]);
    assert!(
        (d - 0.9 * (theta0.sin() - (theta0 - 1e-3).sin())).abs() < 1e-9,
        "{d}"
    );
    assert!(!setup
        .check(&pairs, &[("swing", theta0 + 1e-6)], 0.0)
        .is_free());
    // Uniform samples: the colliding fraction is (π/2 − θ0)/π = 0.3408. With N = 20,000 its standard
    // error is √(p(1−p)/N) = 0.0034; the bound is five of them.
    let expected = (FRAC_PI_2 - theta0) / PI;
    let n = 20_000;
    let mut sampler = ConfigurationSampler::new(&setup.model, 11);
    let mut q = setup.model.zero_configuration();
    let mut data = Data::new(&setup.model);
    let mut scratch = CheckScratch::new(&setup.collision);
    let (mut colliding, mut clearance) = (0, f64::INFINITY);
    for _ in 0..n {
        sampler.sample_into(&mut q);
        forward_kinematics(&setup.model, &q, &mut data);
        let check = setup
            .collision
            .check(&pairs, &data.link_placement, clearance, &mut scratch);
        match check.contact {
            Some(pair) => {
                assert_eq!(pair, (base, arm));
                colliding += 1;
            }
            None => {
                // Collision-free means θ ≤ θ0 (to the contact tolerance).
                assert!(q[setup.joint("swing").0] < theta0 + 1e-5);
            }
        }
        if let Some((d, _)) = check.min_clearance {
            assert!(d < clearance);
            clearance = d;
        }
    }
    let fraction = colliding as f64 / n as f64;
    let bound = 5.0 * (expected * (1.0 - expected) / n as f64).sqrt();
    assert!(
        (fraction - expected).abs() < bound,
        "{fraction} vs {expected} ± {bound}"
    );
    // The closest free pose is just short of θ0: its clearance is tiny but positive.
    assert!(clearance > 0.0 && clearance < 1e-3, "{clearance}");
}

#[test]
fn adjacent_links_are_never_checked_even_through_frames_without_geometry() {
    let axis = format!(r#"<axis xyz="0 0 1"/>{LIMITS}"#);
    let overlapping = r#"<box size="0.5 0.5 0.5"/>"#;
    let urdf = robot(&[
        link("base", overlapping, r#"xyz="0 0 0""#),
        link("a", overlapping, r#"xyz="0 0 0""#),
        // A frame with no geometry, then one whose only shape is a 1 mm marker: both are walked through.
        r#"<link name="frame"/>"#.to_string(),
        link(
            "marker",
            r#"<box size="0.001 0.001 0.001"/>"#,
            r#"xyz="0 0 0""#,
        ),
        link("b", overlapping, r#"xyz="0 0 0""#),
        link("c", overlapping, r#"xyz="0 0 0""#),
        joint("ja", "revolute", "base", "a", &axis),
        joint("jf", "revolute", "a", "frame", &axis),
        joint("jm", "revolute", "frame", "marker", &axis),
        joint("jb", "revolute", "marker", "b", &axis),
        joint("jc", "revolute", "b", "c", &axis),
    ]);
    let setup = Setup::new(&urdf, None);
    let [base, a, b, c] = ["base", "a", "b", "c"].map(|n| setup.link(n));
    let allowed = |x, y| setup.collision.allowed(x, y);
    assert_eq!(allowed(base, a), Some(Allowed::Adjacent));
    assert_eq!(
        allowed(a, b),
        Some(Allowed::Adjacent),
        "through frame and marker"
    );
    assert_eq!(allowed(b, a), Some(Allowed::Adjacent), "symmetric");
    assert_eq!(allowed(b, c), Some(Allowed::Adjacent));
    assert_eq!(allowed(base, b), None, "a has geometry: not adjacent");
    assert_eq!(allowed(a, c), None);
    assert!(!setup.collision.has_geometry(setup.link("marker")));
    // Every box overlaps every other at the zero pose: the touching pairs are exactly the non-adjacent.
    let placements = setup.placements(&[]);
    let mut touching = setup.collision.touching_pairs(&placements);
    touching.sort();
    assert_eq!(touching, vec![(base, b), (base, c), (a, c)]);
    let all = setup.collision.all_pairs();
    assert_eq!(all.len(), 3);
    assert!(setup
        .moved_by(&["ja", "jf", "jm", "jb", "jc"])
        .pairs()
        .iter()
        .all(|&(x, y)| allowed(x, y).is_none()));
}

#[test]
fn rigidly_attached_pairs_are_excluded() {
    let axis = format!(r#"<axis xyz="0 0 1"/>{LIMITS}"#);
    let shape = r#"<sphere radius="0.1"/>"#;
    let urdf = robot(&[
        link("base", shape, r#"xyz="0 0 0""#),
        link("left", shape, r#"xyz="0 0.5 0""#),
        link("right", shape, r#"xyz="0 -0.5 0""#),
        link("arm", shape, r#"xyz="1 0 0""#),
        link("tool", shape, r#"xyz="2 0 0""#),
        link("camera", shape, r#"xyz="3 0 0""#),
        joint("fl", "fixed", "base", "left", ""),
        joint("fr", "fixed", "base", "right", ""),
        joint("j", "revolute", "base", "arm", &axis),
        joint("ft", "fixed", "arm", "tool", ""),
        joint("fc", "fixed", "tool", "camera", ""),
    ]);
    let setup = Setup::new(&urdf, None);
    let l = |n| setup.link(n);
    let allowed = |x, y| setup.collision.allowed(l(x), l(y));
    // Siblings on fixed joints: rigid (not adjacent: base has geometry between them).
    assert_eq!(allowed("left", "right"), Some(Allowed::Rigid));
    assert_eq!(allowed("arm", "camera"), Some(Allowed::Rigid));
    assert_eq!(allowed("base", "left"), Some(Allowed::Adjacent));
    assert_eq!(allowed("left", "tool"), None);
    // Only pairs across the revolute joint move: {base, left, right} against {arm, tool, camera}, but
    // base–arm (adjacent).
    let mut moved: Vec<String> = setup
        .names(setup.moved_by(&["j"]).pairs())
        .iter()
        .map(|(a, b)| format!("{a}-{b}"))
        .collect();
    moved.sort();
    assert_eq!(
        moved,
        [
            "base-camera",
            "base-tool",
            "left-arm",
            "left-camera",
            "left-tool",
            "right-arm",
            "right-camera",
            "right-tool"
        ]
    );
    assert!(setup.moved_by(&[]).is_empty());
}

#[test]
fn mimic_followers_move_with_their_leader() {
    let axis = format!(r#"<axis xyz="0 0 1"/>{LIMITS}"#);
    let mimic = format!(r#"{axis}<mimic joint="lead" multiplier="-1"/>"#);
    let shape = r#"<box size="0.05 0.05 0.05"/>"#;
    let urdf = robot(&[
        link("palm", shape, r#"xyz="0 0 0""#),
        link("f1", shape, r#"xyz="0.1 0 0""#),
        link("f2", shape, r#"xyz="0.1 0 0""#),
        link("post", shape, r#"xyz="-1 0 0""#),
        joint("lead", "revolute", "palm", "f1", &axis),
        joint("follow", "revolute", "palm", "f2", &mimic),
        joint("fix", "fixed", "palm", "post", ""),
    ]);
    let setup = Setup::new(&urdf, None);
    // post–f2 is moved by the leader only through its follower.
    let pairs = setup.moved_by(&["lead"]);
    let [f1, f2, post] = ["f1", "f2", "post"].map(|n| setup.link(n));
    let mut moved = pairs.pairs().to_vec();
    moved.sort();
    assert_eq!(moved, vec![(f1, f2), (f1, post), (f2, post)]);
    // At 0 both fingers overlap; apart once the leader opens them (the follower turns the other way).
    assert!(!setup.check(&pairs, &[("lead", 0.0)], 0.0).is_free());
    assert!(setup.check(&pairs, &[("lead", 1.0)], 0.0).is_free());
}

#[test]
fn pairs_touching_at_the_reference_pose_are_found_then_allowed() {
    let mut setup = Setup::new(&two_boxes(), None);
    let (base, far) = (setup.link("base"), setup.link("far"));
    assert!(setup
        .collision
        .touching_pairs(&setup.placements(&[]))
        .is_empty());
    // The far box moved in to 0.15 m from the hub overlaps base at the zero pose.
    let overlapping =
        two_boxes().replace(r#"<origin xyz="1 0 0"/>"#, r#"<origin xyz="0.15 0 0"/>"#);
    setup = Setup::new(&overlapping, None);
    let touching = setup.collision.touching_pairs(&setup.placements(&[]));
    assert_eq!(touching, vec![(base, far)]);
    setup.collision.allow(&touching, Allowed::Touching);
    assert_eq!(setup.collision.allowed(far, base), Some(Allowed::Touching));
    assert!(setup.moved_by(&["j1"]).is_empty());
    assert!(setup.collision.all_pairs().is_empty());
    // A pair keeps its first reason.
    setup.collision.allow(&[(base, far)], Allowed::Disabled);
    assert_eq!(setup.collision.allowed(base, far), Some(Allowed::Touching));
}

#[test]
fn srdf_disable_collisions_are_read_and_excluded() {
    let srdf = r#"<?xml version="1.0"?>
<robot name="r">
  <group name="arm"><joint name="j1"/></group>
  <disable_collisions link1="base" link2="far" reason="Never"/>
  <disable_collisions link1="base" link2="nowhere" reason="Default"/>
</robot>"#;
    let collisions = srdf_collisions(srdf).expect("parses");
    let pairs = &collisions.disabled;
    assert_eq!(pairs.len(), 2);
    assert_eq!(
        (pairs[0].line, pairs[0].column, pairs[0].reason.as_deref()),
        (4, 3, Some("Never"))
    );
    let mut setup = Setup::new(&two_boxes(), None);
    assert_eq!(setup.moved_by(&["j1"]).len(), 1);
    let problems = setup.collision.allow_srdf(&setup.model, &collisions);
    assert_eq!(
        problems,
        vec!["5:3: <disable_collisions> names unknown link 'nowhere'".to_string()]
    );
    assert_eq!(
        setup
            .collision
            .allowed(setup.link("far"), setup.link("base")),
        Some(Allowed::Disabled)
    );
    assert!(setup.moved_by(&["j1"]).is_empty());
    let error = srdf_collisions("<robot>\n  <disable_collisions link2=\"a\"/>\n</robot>")
        .expect_err("link1 is required");
    assert_eq!(error, "2:3: <disable_collisions> has no link1 attribute");
}

/// MoveIt's precedence: `disable_collisions` beats `enable_collisions`, which beats
/// `disable_default_collisions`.
#[test]
fn srdf_default_disabled_links_collide_only_with_enabled_pairs() {
    let axis = format!(r#"<axis xyz="0 0 1"/>{LIMITS}"#);
    let cube = r#"<box size="0.1 0.1 0.1"/>"#;
    let urdf = robot(&[
        link("base", cube, r#"xyz="0 0 0""#),
        link("upper", cube, r#"xyz="0 0 0""#),
        link("lower", cube, r#"xyz="0 0 0""#),
        link("hand", cube, r#"xyz="0 0 0""#),
        joint(
            "j1",
            "revolute",
            "base",
            "upper",
            &format!(r#"<origin xyz="1 0 0"/>{axis}"#),
        ),
        joint(
            "j2",
            "revolute",
            "upper",
            "lower",
            &format!(r#"<origin xyz="1 0 0"/>{axis}"#),
        ),
        joint(
            "j3",
            "revolute",
            "lower",
            "hand",
            &format!(r#"<origin xyz="1 0 0"/>{axis}"#),
        ),
    ]);
    let srdf = r#"<robot name="r">
  <disable_default_collisions link="hand"/>
  <enable_collisions link1="base" link2="hand" reason="Testing"/>
  <enable_collisions link1="hand" link2="upper"/>
  <disable_collisions link1="upper" link2="hand" reason="Never"/>
  <enable_collisions link1="hand" link2="ghost"/>
  <disable_default_collisions link="phantom"/>
</robot>"#;
    let collisions = srdf_collisions(srdf).expect("parses");
    let mut setup = Setup::new(&urdf, None);
    let [base, upper, lower, hand] = ["base", "upper", "lower", "hand"].map(|n| setup.link(n));
    assert_eq!(setup.collision.allowed(base, hand), None, "before the SRDF");
    let problems = setup.collision.allow_srdf(&setup.model, &collisions);
    assert_eq!(
        problems,
        [
            "6:3: <enable_collisions> names unknown link 'ghost'",
            "7:3: <disable_default_collisions> names unknown link 'phantom'"
        ]
    );
    let allowed = |x, y| setup.collision.allowed(x, y);
    assert_eq!(allowed(base, hand), None, "enabled again");
    assert_eq!(allowed(hand, base), None, "symmetric");
    assert_eq!(
        allowed(upper, hand),
        Some(Allowed::Disabled),
        "disable wins"
    );
    assert_eq!(
        allowed(lower, hand),
        Some(Allowed::Adjacent),
        "first reason kept"
    );
    assert_eq!(
        allowed(base, lower),
        None,
        "neither link is default-disabled"
    );
    assert_eq!(setup.moved_by(&["j1", "j2", "j3"]).len(), 2);
}

/// Temporary folder removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> Self {
        let dir = std::env::temp_dir().join(format!(
            "urdf-validator-collision-{}-{tag}",
            std::process::id()
        ));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("create temp dir");
        TempDir(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

/// ASCII STL of a UV sphere of radius 1: poles on ±z, `rings` latitude bands, `2·rings` meridians.
fn uv_sphere_stl(rings: usize) -> String {
    let point = |i: usize, j: usize| {
        let lat = PI * i as f64 / rings as f64;
        let lon = PI * j as f64 / rings as f64;
        [lat.sin() * lon.cos(), lat.sin() * lon.sin(), lat.cos()]
    };
    let mut stl = String::from("solid sphere\n");
    let mut facet = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
        stl.push_str("facet normal 0 0 0\nouter loop\n");
        for v in [a, b, c] {
            stl.push_str(&format!("vertex {} {} {}\n", v[0], v[1], v[2]));
        }
        stl.push_str("endloop\nendfacet\n");
    };
    for i in 0..rings {
        for j in 0..2 * rings {
            let (p00, p10, p11, p01) = (
                point(i, j),
                point(i + 1, j),
                point(i + 1, j + 1),
                point(i, j + 1),
            );
            if i > 0 {
                facet(p00, p10, p01);
            }
            if i + 1 < rings {
                facet(p10, p11, p01);
            }
        }
    }
    stl.push_str("endsolid sphere\n");
    stl
}

#[test]
fn meshes_collide_as_their_scaled_convex_hull() {
    let dir = TempDir::new("mesh");
    fs::write(dir.0.join("ball.stl"), uv_sphere_stl(12)).expect("write");
    let slide = r#"<axis xyz="0 0 1"/><limit lower="-5" upper="5" effort="10" velocity="1"/>"#;
    // The mesh ball (radius 1, scaled to 0.2 across and 0.6 tall) on base; a 0.1 ball rides on a slider
    // along z above it.
    let urdf = robot(&[
        link(
            "base",
            r#"<mesh filename="ball.stl" scale="0.2 0.2 0.6"/>"#,
            r#"xyz="0 0 0""#,
        ),
        link("slider", r#"<sphere radius="0.01"/>"#, r#"xyz="0 0 -3""#),
        link("probe", r#"<sphere radius="0.1"/>"#, r#"xyz="0 0 0""#),
        joint("lift", "prismatic", "base", "slider", slide),
        joint(
            "fix",
            "fixed",
            "slider",
            "probe",
            r#"<origin xyz="0 0 1"/>"#,
        ),
    ]);
    let setup = Setup::new(&urdf, Some(&dir.0));
    assert!(setup.collision.has_geometry(setup.link("base")));
    let pairs = setup.moved_by(&["lift"]);
    assert_eq!(pairs.len(), 1);
    // The pole (a hull vertex) at z = 0.6 is nearest to a point above it: 1 − 0.6 − 0.1.
    let d = setup.clearance(&pairs, &[("lift", 0.0)]);
    assert!((d - 0.3).abs() < 1e-9, "{d}");
    assert!(!setup.check(&pairs, &[("lift", -0.35)], 0.0).is_free());
}

#[test]
fn degenerate_input_is_skipped_without_panicking() {
    let axis = format!(r#"<axis xyz="0 0 1"/>{LIMITS}"#);
    let dir = TempDir::new("degenerate");
    // A mesh whose vertices all coincide, and one that is flat.
    let point_mesh = "solid p\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 0 0 0\nendloop\nendfacet\nendsolid p\n";
    fs::write(dir.0.join("point.stl"), point_mesh).expect("write");
    let flat = "solid f\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid f\n";
    fs::write(dir.0.join("flat.stl"), flat).expect("write");
    let urdf = robot(&[
        link("base", r#"<box size="0.2 0.2 0"/>"#, r#"xyz="0 0 0""#),
        link("zero", r#"<sphere radius="0"/>"#, r#"xyz="0 0 0""#),
        link("nan", r#"<sphere radius="nan"/>"#, r#"xyz="0 0 0""#),
        link("huge", r#"<box size="1e300 1 1"/>"#, r#"xyz="0 0 0""#),
        link(
            "point",
            r#"<mesh filename="point.stl"/>"#,
            r#"xyz="0 0 0.5""#,
        ),
        link("flat", r#"<mesh filename="flat.stl"/>"#, r#"xyz="0 0 0.5""#),
        link(
            "missing",
            r#"<mesh filename="missing.stl"/>"#,
            r#"xyz="0 0 0""#,
        ),
        link(
            "arm",
            r#"<cylinder radius="0.05" length="0"/>"#,
            r#"xyz="0 0 0""#,
        ),
        joint("j1", "revolute", "base", "zero", &axis),
        joint("j2", "revolute", "zero", "nan", &axis),
        joint("j3", "revolute", "nan", "huge", &axis),
        joint("j4", "revolute", "huge", "point", &axis),
        joint("j5", "revolute", "point", "flat", &axis),
        joint("j6", "revolute", "flat", "missing", &axis),
        joint("j7", "revolute", "missing", "arm", &axis),
    ]);
    let (robot, _) =
        urdf_validator::urdf::parse::parse_urdf(&urdf, &dir.0.join("robot.urdf")).expect("parses");
    let (model, _) = Model::build(&robot);
    let resolver = PackageResolver::default();
    let meshes = MeshCache::new();
    let assets = urdf_validator::assets::Assets::load(
        &robot,
        &urdf_validator::assets::AssetSource {
            urdf_path: &dir.0.join("robot.urdf"),
            resolver: &resolver,
            meshes: &meshes,
            srdf: None,
        },
    );
    let collision = CollisionModel::build(&robot, &model, &assets.supports);
    let has = |name: &str| collision.has_geometry(model.link(name).expect("link"));
    assert!(
        has("base") && has("arm"),
        "a flat box and a flat cylinder are usable"
    );
    assert!(!has("zero") && !has("nan") && !has("huge") && !has("missing"));
    let joints: Vec<JointId> = (0..robot.joints.len()).map(JointId).collect();
    let pairs = collision.pairs_moved_by(&model.motion_of(&joints));
    assert!(!pairs.is_empty());
    let mut scratch = CheckScratch::new(&collision);
    let mut data = Data::new(&model);
    forward_kinematics(&model, &model.zero_configuration(), &mut data);
    let fine = collision.check(&pairs, &data.link_placement, f64::INFINITY, &mut scratch);
    assert_eq!(fine.skipped, 0);
    // Non-finite and absurd placements, and too few of them: those pairs are skipped and counted.
    let mut broken = data.link_placement.clone();
    broken[model.link("flat").expect("link").0]
        .translation
        .vector
        .x = f64::NAN;
    broken[model.link("point").expect("link").0]
        .translation
        .vector
        .y = 1e30;
    let check = collision.check(&pairs, &broken, f64::INFINITY, &mut scratch);
    assert!(check.skipped > 0);
    let check = collision.check(&pairs, &broken[..1], f64::INFINITY, &mut scratch);
    assert_eq!(check.skipped, pairs.len());
    assert!(collision.touching_pairs(&[]).is_empty());
}

#[test]
fn the_model_is_shareable_across_threads() {
    fn sync_and_send<T: Sync + Send>() {}
    sync_and_send::<CollisionModel>();
    sync_and_send::<PairSet>();
    sync_and_send::<CheckScratch>();
}

/// PR2 with its real meshes (convex hulls), or `None` when the reference robots are absent.
fn pr2() -> Option<Setup> {
    let dir = common::shared_robots()?;
    let path = dir.join("pr2/pr2_description/robots/pr2.urdf");
    let text = fs::read_to_string(&path).expect("pr2.urdf");
    let (robot, _) = urdf_validator::urdf::parse::parse_urdf(&text, &path).expect("parses");
    let (model, _) = Model::build(&robot);
    let resolver = PackageResolver::default();
    let meshes = MeshCache::new();
    let assets = urdf_validator::assets::Assets::load(
        &robot,
        &urdf_validator::assets::AssetSource {
            urdf_path: &path,
            resolver: &resolver,
            meshes: &meshes,
            srdf: None,
        },
    );
    let collision = CollisionModel::build(&robot, &model, &assets.supports);
    Some(Setup {
        robot,
        model,
        collision,
    })
}

const PR2_ARM_JOINTS: [&str; 7] = [
    "shoulder_pan",
    "shoulder_lift",
    "upper_arm_roll",
    "elbow_flex",
    "forearm_roll",
    "wrist_flex",
    "wrist_roll",
];

#[test]
fn pr2_touching_pairs_at_the_zero_pose() {
    let Some(setup) = pr2() else { return };
    let touching = setup.names(&setup.collision.touching_pairs(&setup.placements(&[])));
    for (a, b) in &touching {
        println!("touching at zero: {a} — {b}");
    }
    // The truth with these hulls: the base against its caster wheels (their hulls reach into the base),
    // against the shoulder pans (the torso is down at zero), the bellow against the torso, the torso
    // against the shoulder lifts, the head plate, and within each arm the shoulder, elbow and wrist hulls
    // that overlap their second neighbours; and the gripper fingertips, closed at zero. No pair joins the
    // two arms, and every pair of one arm has its twin in the other.
    let arm_pairs = [
        ("shoulder_pan_link", "upper_arm_roll_link"),
        ("shoulder_pan_link", "upper_arm_link"),
        ("shoulder_lift_link", "upper_arm_link"),
        ("upper_arm_link", "forearm_roll_link"),
        ("forearm_link", "wrist_roll_link"),
        ("forearm_link", "gripper_palm_link"),
        ("gripper_l_finger_tip_link", "gripper_r_finger_tip_link"),
    ];
    let mut expected: Vec<(String, String)> = ["fl", "fr", "bl", "br"]
        .iter()
        .flat_map(|c| {
            ["l", "r"].map(|w| {
                (
                    "base_link".to_string(),
                    format!("{c}_caster_{w}_wheel_link"),
                )
            })
        })
        .collect();
    for side in ["l", "r"] {
        expected.push(("base_link".into(), format!("{side}_shoulder_pan_link")));
        expected.push((
            "torso_lift_link".into(),
            format!("{side}_shoulder_lift_link"),
        ));
        for (a, b) in arm_pairs {
            expected.push((format!("{side}_{a}"), format!("{side}_{b}")));
        }
    }
    expected.push(("base_bellow_link".into(), "torso_lift_link".into()));
    expected.push(("head_pan_link".into(), "head_plate_frame".into()));
    let normalise = |mut pairs: Vec<(String, String)>| {
        for pair in &mut pairs {
            if pair.1 < pair.0 {
                std::mem::swap(&mut pair.0, &mut pair.1);
            }
        }
        pairs.sort();
        pairs
    };
    assert_eq!(normalise(touching), normalise(expected));
}

#[test]
fn pr2_arms_are_symmetric_in_sampled_self_collision() {
    let Some(mut setup) = pr2() else { return };
    let touching = setup.collision.touching_pairs(&setup.placements(&[]));
    setup.collision.allow(&touching, Allowed::Touching);
    let mut fractions = Vec::new();
    for side in ["l", "r"] {
        let names: Vec<String> = PR2_ARM_JOINTS
            .iter()
            .map(|j| format!("{side}_{j}_joint"))
            .collect();
        let joints: Vec<JointId> = names.iter().map(|n| setup.joint(n)).collect();
        let pairs = setup
            .collision
            .pairs_moved_by(&setup.model.motion_of(&joints));
        // Each arm's links against the body, the other arm and its own non-adjacent links.
        assert!(pairs.len() > 400, "{}", pairs.len());
        let n = 4000;
        let mut rng = urdf_validator::rng::SplitMix64::new(3);
        let mut data = Data::new(&setup.model);
        let mut scratch = CheckScratch::new(&setup.collision);
        let mut free = 0;
        for _ in 0..n {
            let mut q = setup.model.zero_configuration();
            for joint in &joints {
                let (lo, hi) = setup.model.joint_data[joint.0].range().unwrap_or((-PI, PI));
                q[joint.0] = rng.uniform(lo, hi);
            }
            forward_kinematics(&setup.model, &q, &mut data);
            let check = setup
                .collision
                .check(&pairs, &data.link_placement, 0.0, &mut scratch);
            free += usize::from(check.is_free());
        }
        fractions.push(free as f64 / n as f64);
    }
    println!("PR2 collision-free fractions (left, right): {fractions:?}");
    // The arms are mirror images: equal fractions within sampling error (4 standard errors of the
    // difference of two independent fractions near 1/3 with 4000 samples each: 0.042).
    assert!((fractions[0] - fractions[1]).abs() < 0.042, "{fractions:?}");
    assert!(
        fractions.iter().all(|f| (0.2..0.5).contains(f)),
        "{fractions:?}"
    );
}
