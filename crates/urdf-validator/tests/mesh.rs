//! The mesh loader (`urdf_validator::input::mesh`) on generated files (STL binary/ASCII, OBJ, COLLADA with
//! units, up axes and node hierarchies, broken files) and on every mesh of the reference robots.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use urdf_validator::input::mesh::{
    load_mesh, load_mesh_with, ColladaUpAxis, MeshCache, MeshData, MeshOptions, UpAxisPolicy,
};

/// A fresh directory for one test, removed when dropped.
struct TempDir(PathBuf);

impl std::ops::Deref for TempDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn temp_dir(test: &str) -> TempDir {
    let dir =
        std::env::temp_dir().join(format!("urdf-validator-mesh-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create temp dir");
    TempDir(dir)
}

fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write test file");
    path
}

fn load(path: &Path) -> MeshData {
    load_mesh(path).unwrap_or_else(|e| panic!("{e}"))
}

fn error(path: &Path) -> String {
    match load_mesh(path) {
        Ok(_) => panic!("{} loaded, expected an error", path.display()),
        Err(e) => {
            assert_eq!(e.path, path);
            let shown = e.to_string();
            assert_eq!(shown, format!("{}: {}", path.display(), e.message));
            e.message
        }
    }
}

fn assert_close(actual: [f64; 3], expected: [f64; 3]) {
    for k in 0..3 {
        assert!(
            (actual[k] - expected[k]).abs() < 1e-12,
            "{actual:?} != {expected:?}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Unit cube fixtures

const CUBE_CORNERS: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
    [0.0, 1.0, 1.0],
];
/// Quads of the unit cube (indices into `CUBE_CORNERS`), outward.
const CUBE_QUADS: [[usize; 4]; 6] = [
    [0, 3, 2, 1],
    [4, 5, 6, 7],
    [0, 1, 5, 4],
    [1, 2, 6, 5],
    [2, 3, 7, 6],
    [3, 0, 4, 7],
];

fn cube_triangles() -> Vec<[[f64; 3]; 3]> {
    CUBE_QUADS
        .iter()
        .flat_map(|q| {
            let c = |i: usize| CUBE_CORNERS[q[i]];
            [[c(0), c(1), c(2)], [c(0), c(2), c(3)]]
        })
        .collect()
}

/// Binary STL of the unit cube whose header starts with "solid" (as many exporters write it).
fn binary_cube_stl() -> Vec<u8> {
    let triangles = cube_triangles();
    let mut out = Vec::new();
    let mut header = b"solid cube exported by a CAD tool".to_vec();
    header.resize(80, b' ');
    out.extend(header);
    out.extend((triangles.len() as u32).to_le_bytes());
    for t in &triangles {
        out.extend([0u8; 12]);
        for v in t {
            for c in v {
                out.extend((*c as f32).to_le_bytes());
            }
        }
        out.extend([0u8; 2]);
    }
    out
}

fn ascii_cube_stl() -> String {
    let mut s = String::from("solid cube\n");
    for t in cube_triangles() {
        s.push_str("  facet normal 0 0 0\n    outer loop\n");
        for v in t {
            s.push_str(&format!("      vertex {} {} {}\n", v[0], v[1], v[2]));
        }
        s.push_str("    endloop\n  endfacet\n");
    }
    s.push_str("endsolid cube\n");
    s
}

fn cube_obj() -> String {
    let mut s = String::from("# unit cube\nmtllib missing.mtl\no cube\n");
    for (i, c) in CUBE_CORNERS.iter().enumerate() {
        if i == 0 {
            s.push_str(&format!("v {} {} {} 1.0\n", c[0], c[1], c[2])); // with w
        } else if i == 1 {
            s.push_str(&format!("v {} {} {} 0.5 0.5 0.5\n", c[0], c[1], c[2])); // vertex colour
        } else {
            s.push_str(&format!("v\t{} {} {}\r\n", c[0], c[1], c[2]));
        }
    }
    s.push_str("vt 0 0\nvn 0 0 1\ng faces\nusemtl steel\ns off\n");
    for (i, q) in CUBE_QUADS.iter().enumerate() {
        if i == 0 {
            // negative (relative) indices
            let r = |k: usize| q[k] as i64 - 8;
            s.push_str(&format!("f {} {} {} {}\n", r(0), r(1), r(2), r(3)));
        } else {
            s.push_str(&format!(
                "f {}/1/1 {}/1/1 {}/1/1 {}/1/1\n",
                q[0] + 1,
                q[1] + 1,
                q[2] + 1,
                q[3] + 1
            ));
        }
    }
    s
}

fn assert_unit_cube(mesh: &MeshData, triangles: usize) {
    assert_eq!(mesh.vertices.len(), 8, "{:?}", mesh.vertices);
    assert_eq!(mesh.triangles, triangles);
    assert_eq!(mesh.aabb, ([0.0; 3], [1.0; 3]));
    assert_eq!(mesh.hull.len(), 8, "{:?}", mesh.hull);
    for h in &mesh.hull {
        assert!(mesh.vertices.contains(h));
        assert!(CUBE_CORNERS.contains(h));
    }
    assert_eq!(mesh.declared_up_axis, None);
}

#[test]
fn binary_stl_with_solid_header() {
    let dir = temp_dir("binary_stl");
    let bytes = binary_cube_stl();
    assert!(bytes.starts_with(b"solid"));
    assert_eq!(bytes.len(), 84 + 50 * 12);
    let mesh = load(&write(&dir, "cube.stl", &bytes));
    assert_unit_cube(&mesh, 12);
    assert!(
        mesh.binary_stl,
        "a binary STL of its declared size: MuJoCo reads it"
    );
    // Extension matching is case-insensitive.
    assert_unit_cube(&load(&write(&dir, "CUBE.STL", &bytes)), 12);
    // Trailing bytes: read here, refused by MuJoCo's reader.
    let mut longer = bytes.clone();
    longer.extend_from_slice(&[0; 7]);
    let mesh = load(&write(&dir, "longer.stl", &longer));
    assert_unit_cube(&mesh, 12);
    assert!(!mesh.binary_stl);
}

#[test]
fn ascii_stl() {
    let dir = temp_dir("ascii_stl");
    let mesh = load(&write(&dir, "cube.stl", ascii_cube_stl()));
    assert_unit_cube(&mesh, 12);
    assert!(!mesh.binary_stl, "MuJoCo reads no ASCII STL");
}

#[test]
fn obj_with_quads_w_colours_and_negative_indices() {
    let dir = temp_dir("obj");
    // The .mtl it names does not exist and is never opened.
    assert_unit_cube(&load(&write(&dir, "cube.obj", cube_obj())), 12);
}

#[test]
fn truncated_binary_stl_names_the_byte_offset() {
    let dir = temp_dir("truncated_stl");
    let mut bytes = binary_cube_stl();
    bytes.truncate(84 + 50 * 5 + 20); // triangle 5 is cut
                                      // A header starting with "solid" but binary bytes: still treated as binary.
    let message = error(&write(&dir, "cut.stl", &bytes));
    assert!(message.contains("byte offset 334"), "{message}");
    assert!(message.contains("truncated"), "{message}");
    assert!(message.contains("12 triangles"), "{message}");

    let message = error(&write(&dir, "short.stl", [0u8; 40]));
    assert!(message.contains("too short"), "{message}");
}

#[test]
fn ascii_stl_bad_number_names_the_line() {
    let dir = temp_dir("ascii_stl_bad");
    let text = ascii_cube_stl().replacen("vertex 0 0 0", "vertex 0 zero 0", 1);
    let message = error(&write(&dir, "bad.stl", text));
    assert!(message.starts_with("line 4:"), "{message}");
    assert!(message.contains("'zero'"), "{message}");
    let message = error(&write(
        &dir,
        "nan.stl",
        ascii_cube_stl().replacen("vertex 0 0 0", "vertex 0 0 nan", 1),
    ));
    assert!(message.starts_with("line 4:"), "{message}");
}

#[test]
fn garbage_obj_number_names_the_line() {
    let dir = temp_dir("obj_bad");
    let message = error(&write(
        &dir,
        "bad.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1e0x 0\nf 1 2 3\n",
    ));
    assert!(message.starts_with("line 3:"), "{message}");
    assert!(message.contains("'1e0x'"), "{message}");
    let message = error(&write(&dir, "short.obj", "v 0 0\n"));
    assert!(
        message.starts_with("line 1: expected 3 numbers"),
        "{message}"
    );
    let message = error(&write(&dir, "none.obj", "# nothing\nf 1 2 3\n"));
    assert!(message.contains("no vertices"), "{message}");
}

#[test]
fn unsupported_empty_and_missing_files() {
    let dir = temp_dir("unsupported");
    let message = error(&write(&dir, "mesh.xyz", "1 2 3"));
    assert_eq!(
        message,
        "unsupported mesh format '.xyz' (expected .stl, .obj or .dae)"
    );
    let message = error(&write(&dir, "mesh", "1 2 3"));
    assert!(message.contains("no extension"), "{message}");
    for name in ["empty.stl", "empty.obj", "empty.dae"] {
        let message = error(&write(&dir, name, ""));
        assert!(message.starts_with("empty file"), "{name}: {message}");
    }
    let message = error(&dir.join("missing.stl"));
    assert!(message.starts_with("cannot read file"), "{message}");
}

#[test]
fn hull_of_a_cube_has_eight_vertices_and_flat_meshes_have_none() {
    let dir = temp_dir("hull");
    // A cube with its face centres and body centre: still 8 hull vertices.
    let mut obj = cube_obj();
    obj.push_str("v 0.5 0.5 0.5\nv 0.5 0.5 1\nv 0 0.5 0.5\n");
    let mesh = load(&write(&dir, "cube.obj", obj));
    assert_eq!(mesh.vertices.len(), 11);
    assert_eq!(mesh.hull.len(), 8);
    // A flat square: no hull, callers use the vertices.
    let mesh = load(&write(
        &dir,
        "plane.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
    ));
    assert_eq!(mesh.triangles, 2);
    assert!(mesh.hull.is_empty());
    // A tetrahedron: 4.
    let mesh = load(&write(
        &dir,
        "tet.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n",
    ));
    assert_eq!(mesh.hull.len(), 4);
}

#[test]
fn cache_returns_the_same_arc_per_path() {
    let dir = temp_dir("cache");
    let cube = write(&dir, "cube.stl", binary_cube_stl());
    let broken = write(&dir, "broken.obj", "v x y z\n");
    let cache = MeshCache::new();
    let a = cache.get(&cube);
    let b = cache.clone().get(&cube);
    assert!(Arc::ptr_eq(&a, &b));
    assert!(a.is_ok());
    let e1 = cache.get(&broken);
    let e2 = cache.get(&broken);
    assert!(Arc::ptr_eq(&e1, &e2));
    assert!(e1.is_err());
    assert_eq!(cache.len(), 2);
    // Shared across threads.
    let handles: Vec<_> = (0..4)
        .map(|_| {
            let cache = cache.clone();
            let cube = cube.clone();
            std::thread::spawn(move || cache.get(&cube))
        })
        .collect();
    for h in handles {
        assert!(Arc::ptr_eq(&h.join().expect("thread"), &a));
    }
    // The file is not read again.
    std::fs::remove_file(&cube).expect("remove");
    assert!(Arc::ptr_eq(&cache.get(&cube), &a));
}

// ---------------------------------------------------------------------------------------------
// COLLADA

/// A COLLADA document with a 1×1×1 cube geometry `cube` (positions 0..1 in file units), the given
/// `<asset>` content, extra libraries and visual scene body.
fn dae(asset: &str, libraries: &str, scene_nodes: &str) -> String {
    let positions: Vec<String> = CUBE_CORNERS
        .iter()
        .map(|c| format!("{} {} {}", c[0], c[1], c[2]))
        .collect();
    let indices: Vec<String> = CUBE_QUADS
        .iter()
        .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
        .map(|i| i.to_string())
        .collect();
    format!(
        r##"<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>{asset}</asset>
  <library_geometries>
    <geometry id="cube" name="cube">
      <mesh>
        <source id="cube-pos">
          <float_array id="cube-pos-array" count="24">{positions}</float_array>
          <technique_common>
            <accessor source="#cube-pos-array" count="8" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="cube-vtx"><input semantic="POSITION" source="#cube-pos"/></vertices>
        <triangles count="12"><input semantic="VERTEX" source="#cube-vtx" offset="0"/><p>{indices}</p></triangles>
      </mesh>
    </geometry>
  </library_geometries>
  {libraries}
  <library_visual_scenes>
    <visual_scene id="scene">{scene_nodes}</visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
"##,
        positions = positions.join(" "),
        indices = indices.join(" "),
    )
}

const MM_Y_UP: &str = r#"<unit name="millimeter" meter="0.001"/><up_axis>Y_UP</up_axis>"#;

#[test]
fn dae_unit_and_y_up_apply_to_node_translations() {
    let dir = temp_dir("dae_translate");
    let text = dae(
        MM_Y_UP,
        "",
        r##"<node id="n"><translate>5000 0 0</translate><instance_geometry url="#cube"/></node>"##,
    );
    let mesh = load(&write(&dir, "t.dae", text));
    // File frame (mm): x 5000..5001, y 0..1, z 0..1 → metres: x 5..5.001 → Y_UP (x, −z, y).
    assert_close(mesh.aabb.0, [5.0, -0.001, 0.0]);
    assert_close(mesh.aabb.1, [5.001, 0.0, 0.001]);
    assert_eq!(mesh.triangles, 12);
    assert_eq!(mesh.vertices.len(), 8);
    assert_eq!(mesh.hull.len(), 8);
    assert_eq!(mesh.declared_up_axis, Some(ColladaUpAxis::Y));
    // The corner (1, 1, 0) mm + 5000 mm x → (5.001, 0.001, 0) m → Y_UP → (5.001, 0, 0.001).
    assert!(mesh.vertices.iter().any(|v| (v[0] - 5.001).abs() < 1e-12
        && v[1].abs() < 1e-12
        && (v[2] - 0.001).abs() < 1e-12));

    // Ignoring the up axis (what RViz does) keeps the file's axes; the unit still applies.
    let ignored = load_mesh_with(
        &dir.join("t.dae"),
        &MeshOptions {
            up_axis: UpAxisPolicy::Ignore,
            ..MeshOptions::default()
        },
    )
    .expect("loads");
    assert_close(ignored.aabb.0, [5.0, 0.0, 0.0]);
    assert_close(ignored.aabb.1, [5.001, 0.001, 0.001]);
    assert_eq!(ignored.declared_up_axis, Some(ColladaUpAxis::Y));
}

#[test]
fn dae_matrix_is_row_major() {
    let dir = temp_dir("dae_matrix");
    let text = dae(
        MM_Y_UP,
        "",
        r##"<node><matrix>1 0 0 0  0 1 0 0  0 0 1 2000  0 0 0 1</matrix><instance_geometry url="#cube"/></node>"##,
    );
    let mesh = load(&write(&dir, "m.dae", text));
    // z 2000..2001 mm → 2..2.001 m → Y_UP: y = −z.
    assert_close(mesh.aabb.0, [0.0, -2.001, 0.0]);
    assert_close(mesh.aabb.1, [0.001, -2.0, 0.001]);
}

#[test]
fn dae_nested_nodes_compose_in_document_order() {
    let dir = temp_dir("dae_nested");
    // Parent: translate x by 10. Child: rotate 90° about z, then scale x by 2.
    let text = dae(
        r#"<unit meter="1"/><up_axis>Z_UP</up_axis>"#,
        "",
        r##"<node id="parent"><translate>10 0 0</translate>
              <node id="child"><rotate>0 0 1 90</rotate><scale>2 1 1</scale>
                <instance_geometry url="#cube"/>
              </node>
            </node>"##,
    );
    let mesh = load(&write(&dir, "n.dae", text));
    // p → T(10,0,0) · Rz(90°) · S(2,1,1) · p: (x, y, z) → (10 − y, 2x, z).
    assert_close(mesh.aabb.0, [9.0, 0.0, 0.0]);
    assert_close(mesh.aabb.1, [10.0, 2.0, 1.0]);
    assert!(mesh.vertices.iter().any(|v| (v[0] - 9.0).abs() < 1e-12
        && (v[1] - 2.0).abs() < 1e-12
        && (v[2] - 1.0).abs() < 1e-12));
    assert_eq!(mesh.declared_up_axis, Some(ColladaUpAxis::Z));
}

#[test]
fn dae_instance_node_and_x_up() {
    let dir = temp_dir("dae_instance_node");
    let library = r##"<library_nodes>
        <node id="part"><translate>0 0 3</translate><instance_geometry url="#cube"/></node>
      </library_nodes>"##;
    let text = dae(
        r#"<unit meter="0.01"/><up_axis>X_UP</up_axis>"#,
        library,
        r##"<node><translate>100 0 0</translate><instance_node url="#part"/></node>
            <node><instance_node url="#part"/></node>"##,
    );
    let mesh = load(&write(&dir, "i.dae", text));
    // Two instances (cm): x 100..101 and 0..1, y 0..1, z 3..4 → m ×0.01 → X_UP (−y, −z, x).
    assert_eq!(mesh.vertices.len(), 16);
    assert_eq!(mesh.triangles, 24);
    assert_close(mesh.aabb.0, [-0.01, -0.04, 0.0]);
    assert_close(mesh.aabb.1, [0.0, -0.03, 1.01]);
    assert_eq!(mesh.declared_up_axis, Some(ColladaUpAxis::X));
}

#[test]
fn dae_without_visual_scene_takes_geometries_untransformed() {
    let dir = temp_dir("dae_no_scene");
    let text = dae(r#"<unit meter="0.001"/>"#, "", "")
        .replace(
            r##"<scene><instance_visual_scene url="#scene"/></scene>"##,
            "",
        )
        .replace(r#"<visual_scene id="scene"></visual_scene>"#, "");
    let mesh = load(&write(&dir, "g.dae", text));
    assert_close(mesh.aabb.0, [0.0; 3]);
    assert_close(mesh.aabb.1, [0.001; 3]);
    assert_eq!(mesh.declared_up_axis, None);
}

#[test]
fn dae_polylist_and_stride() {
    let dir = temp_dir("dae_polylist");
    // Positions with stride 4 (a padding value) and a polylist of 2 quads and 1 triangle.
    let text = r##"<COLLADA xmlns="http://www.collada.org/2008/03/COLLADASchema" version="1.5.0">
      <library_geometries><geometry id="g"><mesh>
        <source id="s"><float_array id="a">0 0 0 9  1 0 0 9  1 1 0 9  0 1 0 9  0 0 1 9</float_array>
          <technique_common><accessor source="#a" count="5" stride="4">
            <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/><param type="float"/>
          </accessor></technique_common></source>
        <vertices id="v"><input semantic="POSITION" source="#s"/></vertices>
        <polylist count="3"><input semantic="VERTEX" source="#v" offset="0"/>
          <vcount>4 4 3</vcount><p>0 1 2 3 0 1 4 4 0 1 4</p></polylist>
      </mesh></geometry></library_geometries>
    </COLLADA>"##;
    let mesh = load(&write(&dir, "p.dae", text));
    assert_eq!(mesh.vertices.len(), 5);
    assert_eq!(mesh.triangles, 5);
    assert_eq!(mesh.aabb, ([0.0; 3], [1.0; 3]));
    assert_eq!(mesh.hull.len(), 5);
}

#[test]
fn dae_errors_name_the_line() {
    let dir = temp_dir("dae_errors");
    let good = dae(
        MM_Y_UP,
        "",
        r##"<node><instance_geometry url="#cube"/></node>"##,
    );
    let line_of = |text: &str, needle: &str| {
        text[..text.find(needle).expect("needle")]
            .matches('\n')
            .count()
            + 1
    };

    let bad = good.replacen("1 0 0 1 1 0", "1 0 0 1 x 0", 1);
    let message = error(&write(&dir, "number.dae", &bad));
    assert!(
        message.starts_with(&format!("line {}, column", line_of(&bad, "<float_array"))),
        "{message}"
    );
    assert!(message.contains("'x'"), "{message}");

    let bad = good.replace("Y_UP", "W_UP");
    let message = error(&write(&dir, "axis.dae", &bad));
    assert!(message.contains("expected X_UP, Y_UP or Z_UP"), "{message}");
    assert!(
        message.starts_with(&format!("line {}:", line_of(&bad, "<up_axis"))),
        "{message}"
    );

    let bad = good.replace(r##"url="#cube""##, r##"url="#nothing""##);
    let message = error(&write(&dir, "ref.dae", &bad));
    assert!(
        message.contains("no element with id 'nothing'"),
        "{message}"
    );

    let bad = good.replace(r#"count="8" stride="3""#, r#"count="9" stride="3""#);
    let message = error(&write(&dir, "accessor.dae", &bad));
    assert!(message.contains("has 24 numbers"), "{message}");

    let message = error(&write(&dir, "xml.dae", "<COLLADA><asset></COLLADA>"));
    assert!(message.starts_with("line 1, column"), "{message}");
    assert!(message.contains("invalid XML"), "{message}");

    let message = error(&write(&dir, "root.dae", "<robot/>"));
    assert!(
        message.contains("expected a <COLLADA> root element"),
        "{message}"
    );

    let message = error(&write(&dir, "latin1.dae", b"<COLLADA>\xe9</COLLADA>"));
    assert!(message.starts_with("byte offset 9: not UTF-8"), "{message}");

    let bad = good.replace(
        r##"<node><instance_geometry url="#cube"/></node>"##,
        r##"<node id="loop"><instance_node url="#loop"/></node>"##,
    );
    let message = error(&write(&dir, "cycle.dae", &bad));
    assert!(message.contains("deeper than 32"), "{message}");

    let bad = good.replace(
        r##"<node><instance_geometry url="#cube"/></node>"##,
        r##"<node><instance_geometry url="other.dae#cube"/></node>"##,
    );
    let message = error(&write(&dir, "external.dae", &bad));
    assert!(
        message.contains("only references inside the file"),
        "{message}"
    );
}

#[test]
fn dae_instance_node_fan_out_is_bounded() {
    let dir = temp_dir("dae_fan_out");
    // Each level instantiates the next one 4 times: 4^20 instances unless stopped.
    let mut library = String::from("<library_nodes>");
    for level in 0..20 {
        library.push_str(&format!("<node id=\"n{level}\">"));
        for _ in 0..4 {
            library.push_str(&format!("<instance_node url=\"#n{}\"/>", level + 1));
        }
        library.push_str("</node>");
    }
    library.push_str(r##"<node id="n20"><instance_geometry url="#cube"/></node></library_nodes>"##);
    let text = dae("", &library, r##"<node><instance_node url="#n0"/></node>"##);
    let started = Instant::now();
    let message = error(&write(&dir, "bomb.dae", text));
    assert!(
        message.contains("more than") && message.contains("limit"),
        "{message}"
    );
    assert!(started.elapsed().as_secs() < 60);
}

// ---------------------------------------------------------------------------------------------
// Real meshes

fn meshes_below(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| {
                ["stl", "obj", "dae"].contains(&e.to_string_lossy().to_ascii_lowercase().as_str())
            }) {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

fn extent(mesh: &MeshData) -> [f64; 3] {
    let (min, max) = mesh.aabb;
    [max[0] - min[0], max[1] - min[1], max[2] - min[2]]
}

/// Load every mesh below `root`; print a table (slowest last) and return the loaded meshes.
fn load_all(root: &Path) -> Vec<(PathBuf, MeshData)> {
    let files = meshes_below(root);
    let mut rows = Vec::new();
    let mut failures = Vec::new();
    for file in &files {
        let started = Instant::now();
        let result = load_mesh(file);
        let elapsed = started.elapsed();
        match result {
            Ok(mesh) => rows.push((elapsed, file.clone(), mesh)),
            Err(e) => failures.push(e.to_string()),
        }
    }
    rows.sort_by_key(|(elapsed, _, _)| *elapsed);
    println!(
        "{:>9}  {:>8}  {:>6}  {:>26}  file (below {})",
        "ms",
        "tris",
        "hull",
        "bbox extent",
        root.display()
    );
    for (elapsed, file, mesh) in &rows {
        let e = extent(mesh);
        println!(
            "{:>9.1}  {:>8}  {:>6}  {:>8.3} {:>8.3} {:>8.3}  {}",
            elapsed.as_secs_f64() * 1e3,
            mesh.triangles,
            mesh.hull.len(),
            e[0],
            e[1],
            e[2],
            file.strip_prefix(root).unwrap_or(file).display()
        );
    }
    assert!(
        failures.is_empty(),
        "meshes failed to load:\n{}",
        failures.join("\n")
    );
    rows.into_iter()
        .map(|(_, file, mesh)| (file, mesh))
        .collect()
}

#[test]
fn every_reference_robot_mesh_loads() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let meshes = load_all(&robots);
    assert!(
        meshes.len() >= 100,
        "expected the reference meshes, found {}",
        meshes.len()
    );
    for (file, mesh) in &meshes {
        assert!(mesh.triangles > 0, "{}", file.display());
        assert!(mesh.hull.is_empty() || mesh.hull.len() >= 4);
    }

    // TurtleBot3's burger_base.stl is in millimetres (±68.8 × 141.5): the URDF's
    // `scale="0.001 0.001 0.001"` fixes it, the loader does not.
    let (_, burger) = meshes
        .iter()
        .find(|(f, _)| f.ends_with("turtlebot3_description/meshes/bases/burger_base.stl"))
        .expect("burger_base.stl");
    let e = extent(burger);
    assert!(e.iter().all(|&x| x > 100.0), "{e:?}");
    assert!((burger.aabb.1[2] - 141.5).abs() < 0.01, "{:?}", burger.aabb);

    // Husky's COLLADA meshes are in metres, Z up.
    let husky: Vec<_> = meshes
        .iter()
        .filter(|(f, _)| {
            f.parent()
                .is_some_and(|p| p.ends_with("husky/husky_description/meshes"))
                && f.extension().is_some_and(|e| e == "dae")
        })
        .collect();
    assert!(husky.len() >= 6, "{}", husky.len());
    for (file, mesh) in husky {
        let e = extent(mesh);
        assert!(
            e.iter().all(|&x| x < 2.0) && e.iter().any(|&x| x > 0.05),
            "{}: {e:?}",
            file.display()
        );
        assert_eq!(mesh.declared_up_axis, Some(ColladaUpAxis::Z));
    }
}

#[test]
fn pr2_collada_meshes_declare_y_up_but_are_modelled_z_up() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    // PR2's base: 0.67 × 0.67 m footprint, 0.66 m tall in the file's own axes (scale 0.1 on the node),
    // but it declares Y_UP, so honouring the tag lays it on its side (tall along −y). RViz, MoveIt and
    // Gazebo ignore the tag.
    let base = robots.join("pr2/pr2_description/meshes/base_v0/base.dae");
    let honoured = load(&base);
    let ignored = load_mesh_with(
        &base,
        &MeshOptions {
            up_axis: UpAxisPolicy::Ignore,
            ..MeshOptions::default()
        },
    )
    .expect("loads");
    assert_eq!(honoured.declared_up_axis, Some(ColladaUpAxis::Y));
    let (h, i) = (extent(&honoured), extent(&ignored));
    assert!(
        (i[2] - 0.656).abs() < 0.01 && i[0] < 0.7 && i[1] < 0.7,
        "{i:?}"
    );
    assert!((h[1] - 0.656).abs() < 0.01, "{h:?}");
}

#[test]
fn every_corpus_mesh_loads() {
    let Some(corpus) = common::corpus() else {
        return;
    };
    let meshes = load_all(&corpus);
    assert!(
        meshes.len() >= 700,
        "expected the corpus meshes, found {}",
        meshes.len()
    );
    for (file, mesh) in &meshes {
        assert_hull_holds_the_extremes(file, mesh);
    }
}

/// The hull must reach as far as the vertices in every direction: along 200 directions spread over the
/// sphere, the farthest hull vertex is as far as the farthest vertex (within 1e-7 of the mesh size). A
/// hull that lost a true corner fails this.
fn assert_hull_holds_the_extremes(file: &Path, mesh: &MeshData) {
    if mesh.hull.is_empty() {
        return;
    }
    let e = extent(mesh);
    let size = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
    let count = 200;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    for i in 0..count {
        let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
        let r = (1.0 - z * z).sqrt();
        let d = [
            r * (golden * i as f64).cos(),
            r * (golden * i as f64).sin(),
            z,
        ];
        let reach = |points: &[[f64; 3]]| {
            points
                .iter()
                .map(|p| p[0] * d[0] + p[1] * d[1] + p[2] * d[2])
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let gap = reach(&mesh.vertices) - reach(&mesh.hull);
        assert!(
            gap <= 1e-7 * size,
            "{}: the hull misses the extreme along {d:?} by {gap:e} m",
            file.display()
        );
    }
}
