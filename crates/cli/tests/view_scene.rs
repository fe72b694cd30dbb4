//! The 3-D view's scene and poses (`render::view`): the placements are the library's forward kinematics,
//! the overlays at the report's pose are the report's numbers, a slider pose re-evaluates them, meshes
//! are decimated and encoded within a size budget, and a mesh that cannot be read is drawn as a box.
//! (Here rather than in the library's tests: these need no dependency the command's build lacks.)

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::collections::BTreeMap;
use std::path::Path;

use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::model::{forward_kinematics, Data};
use urdf_validator::render::render_html;
use urdf_validator::render::view::{scene, Poser};
use urdf_validator::urdf::robot::Geometry;
use urdf_validator::{inspect, validate, Options};

fn options() -> Options {
    Options {
        resolver: PackageResolver::from_env(Vec::new()),
        ..Options::default()
    }
}

fn poser(path: &Path) -> Poser {
    let options = options();
    Poser::new(inspect(path, &options).expect("it validates"), &options)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn the_pr2_scene_is_the_reports_robot_at_the_reports_pose() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let poser = poser(&robots.join("pr2/pr2_description/robots/pr2.urdf"));
    let scene = scene::build(&poser);
    let report = &poser.inspection().validation.report;
    let statics = report.statics.as_ref().unwrap();
    let stability = report.stability.as_ref().unwrap();
    let reference = &scene.reference;
    assert_eq!(reference.com, statics.full_body_com);
    assert_eq!(reference.margin_mm, stability.margin_mm);
    assert_eq!(reference.tip_direction, stability.tip_direction);
    assert_eq!(reference.support_polygon, stability.support_polygon);
    assert_eq!(reference.stability, stability.status.label());
    assert_eq!(reference.joints.len(), statics.joints.len());
    for (load, joint) in reference.joints.iter().zip(&statics.joints) {
        assert_eq!(load.name, joint.name);
        assert_eq!(load.torque, joint.required_torque_gravity, "{}", joint.name);
        assert_eq!(load.margin, joint.margin, "{}", joint.name);
    }
    assert_eq!(scene.links.len(), poser.inspection().robot.links.len());
    assert!(!scene.meshes.is_empty(), "the PR2's meshes are drawn");
    assert!(scene
        .meshes
        .iter()
        .all(|m| m.triangles <= scene::MESH_TRIANGLE_BUDGET));
    assert!(scene.workspace_points.len() >= 400, "both arms' tips");
    assert!(scene
        .findings
        .iter()
        .any(|f| f.joint.is_some() || f.link.is_some()));
    let json = serde_json::to_string(&scene).unwrap();
    assert!(json.len() < 2_500_000, "PR2 scene is {} bytes", json.len());
}

#[test]
fn the_pr2s_collada_meshes_are_drawn_as_their_triangles_and_its_report_stays_under_3_mb() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let path = robots.join("pr2/pr2_description/robots/pr2.urdf");
    let poser = poser(&path);
    let scene = scene::build(&poser);
    let robot = &poser.inspection().robot;
    let mut collada = 0;
    for (link, drawn) in robot.links.iter().zip(&scene.links) {
        assert_eq!(link.name.value, drawn.name);
        assert_eq!(link.visuals.len(), drawn.visuals.len(), "{}", drawn.name);
        for (visual, geometry) in link.visuals.iter().zip(&drawn.visuals) {
            let Some(Geometry::Mesh { filename, .. }) = visual.geometry.as_ref().map(|g| &g.value)
            else {
                continue;
            };
            if !filename.value.to_ascii_lowercase().ends_with(".dae") {
                continue;
            }
            collada += 1;
            assert_ne!(
                geometry.approximation,
                Some("convex_hull"),
                "{}: {}",
                link.name.value,
                filename.value
            );
            let mesh = &scene.meshes[geometry.mesh.expect("drawn as a mesh")];
            assert!(mesh.triangles > 0, "{}", filename.value);
        }
    }
    assert!(collada >= 35, "the PR2's COLLADA visuals: {collada}");
    // Its triangles, not their hulls: the hulls made 14,446 triangles, the triangles 24,772.
    let drawn: usize = scene.meshes.iter().map(|m| m.triangles).sum();
    assert!(drawn > 20_000, "{drawn} triangles drawn");

    let options = Options {
        view: true,
        ..options()
    };
    let html = render_html(&validate(&path, &options).expect("it validates"));
    assert!(
        html.len() <= 3_000_000,
        "PR2 report is {} bytes",
        html.len()
    );
    eprintln!(
        "PR2: {} triangles drawn, scene {} bytes, report {} bytes",
        drawn,
        serde_json::to_string(&scene).unwrap().len(),
        html.len()
    );
}

#[test]
fn a_slider_pose_moves_the_links_by_the_librarys_kinematics_and_re_evaluates_statics() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let poser = poser(&robots.join("pr2/pr2_description/robots/pr2.urdf"));
    let model = &poser.inspection().model;
    let reference = poser.evaluate(&BTreeMap::new());
    let mut values = BTreeMap::new();
    values.insert("r_shoulder_lift_joint".to_string(), 0.9);
    values.insert("l_elbow_flex_joint".to_string(), -100.0); // clamped into its limits
    values.insert("no_such_joint".to_string(), 1.0);
    let moved = poser.evaluate(&values);
    assert_eq!(moved.configuration["r_shoulder_lift_joint"], 0.9);
    let elbow = model.joint("l_elbow_flex_joint").unwrap();
    let (lower, _) = model.joint_data[elbow.0].range().unwrap();
    assert_eq!(moved.configuration["l_elbow_flex_joint"], lower);

    let mut q = model.zero_configuration();
    for (name, value) in &moved.configuration {
        q[model.joint(name).unwrap().0] = *value;
    }
    model.apply_mimic(&mut q);
    let mut data = Data::new(model);
    forward_kinematics(model, &q, &mut data);
    for (placed, expected) in moved.links.iter().zip(&data.link_placement) {
        let t = expected.translation.vector;
        let r = expected.rotation.coords;
        let want = [t.x, t.y, t.z, r.x, r.y, r.z, r.w];
        assert!(
            placed.iter().zip(want).all(|(a, b)| close(*a, b)),
            "{placed:?} vs {want:?}"
        );
    }
    let torque = |pose: &urdf_validator::render::view::PoseView, name: &str| {
        pose.joints
            .iter()
            .find(|j| j.name == name)
            .unwrap()
            .torque
            .unwrap()
    };
    assert!(
        (torque(&moved, "r_shoulder_lift_joint") - torque(&reference, "r_shoulder_lift_joint"))
            .abs()
            > 0.1,
        "lifting the arm changes the torque its shoulder holds"
    );
    assert_ne!(moved.com, reference.com);
}

#[test]
fn anymal_has_a_support_polygon_and_a_menagerie_model_draws() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let anymal = poser(&robots.join("anymal/anymal_b_simple_description/urdf/anymal.urdf"));
    let scene = scene::build(&anymal);
    assert!(scene.reference.support_polygon.len() >= 3);
    assert!(scene.reference.com.is_some());
    let go2 = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../urdf-validator/tests/data/menagerie/unitree_go2/go2.xml");
    let scene = scene::build(&poser(&go2));
    assert!(scene
        .links
        .iter()
        .any(|l| !l.visuals.is_empty() || !l.collisions.is_empty()));
    assert!(scene.reference.com.is_some());
}

#[test]
fn a_mesh_that_cannot_be_read_is_drawn_as_a_box_with_why() {
    let dir = std::env::temp_dir().join(format!("urdf-view-broken-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("broken.stl"),
        "solid nothing here\nthis is not an STL\n",
    )
    .unwrap();
    let urdf = dir.join("robot.urdf");
    std::fs::write(
        &urdf,
        r#"<robot name="r">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><mesh filename="broken.stl"/></geometry></visual>
    <visual><geometry><mesh filename="missing.stl"/></geometry></visual>
    <visual><geometry><box size="0.1 0.2 0.3"/></geometry></visual>
  </link>
</robot>"#,
    )
    .unwrap();
    let scene = scene::build(&poser(&urdf));
    let _ = std::fs::remove_dir_all(&dir);
    let visuals = &scene.links[0].visuals;
    assert_eq!(visuals.len(), 3);
    for broken in &visuals[..2] {
        assert_eq!(broken.kind, "box");
        assert!(broken.problem.is_some(), "{broken:?}");
        assert!(matches!(
            broken.approximation,
            Some("placeholder" | "bounding_box")
        ));
    }
    assert_eq!(visuals[2].size, Some([0.1, 0.2, 0.3]));
    assert!(visuals[2].problem.is_none());
}

#[test]
fn an_untrusted_view_draws_a_mesh_outside_the_roots_as_a_box_and_says_it_was_refused() {
    let dir = std::env::temp_dir().join(format!("urdf-view-untrusted-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("robot")).unwrap();
    let stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    std::fs::write(dir.join("outside.stl"), stl).unwrap();
    std::fs::write(dir.join("robot/inside.stl"), stl).unwrap();
    let urdf = dir.join("robot/r.urdf");
    std::fs::write(
        &urdf,
        r#"<robot name="r"><link name="a">
  <visual><geometry><mesh filename="../outside.stl"/></geometry></visual>
  <visual><geometry><mesh filename="inside.stl"/></geometry></visual>
</link></robot>"#,
    )
    .unwrap();
    let options = Options {
        sandbox: urdf_validator::input::sandbox::Sandbox::untrusted(Vec::new(), Vec::new()),
        ..options()
    };
    let scene = scene::build(&Poser::new(inspect(&urdf, &options).unwrap(), &options));
    let _ = std::fs::remove_dir_all(&dir);
    let [outside, inside] = &scene.links[0].visuals[..] else {
        panic!("two visuals: {:?}", scene.links[0].visuals)
    };
    assert_eq!(outside.kind, "box");
    assert!(
        outside
            .problem
            .as_deref()
            .is_some_and(|p| p.contains("refused")),
        "{outside:?}"
    );
    assert_eq!((inside.kind, inside.mesh), ("mesh", Some(0)), "{inside:?}");
    assert_eq!(
        scene.meshes.len(),
        1,
        "only the mesh inside the roots was read"
    );
}
