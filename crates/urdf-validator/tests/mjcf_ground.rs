//! World `<geom type="plane">`s as the ground: the stability analysis stands a floating robot on
//! horizontal ground under its lowest point, so a horizontal plane (at any height: the robot settles onto
//! it) changes nothing, and a tilted one gets a U033 note that its tilt is not used.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use urdf_validator::{validate, Options};

/// A four-legged table, floating, over `floor`.
fn table(floor: &str) -> String {
    let leg = |x: f64, y: f64| {
        format!(r#"<geom type="capsule" size="0.03" fromto="{x} {y} 0 {x} {y} -0.4"/>"#)
    };
    format!(
        r#"<mujoco>
  <worldbody>
    {floor}
    <body name="table" pos="0 0 0.43">
      <freejoint/>
      <geom type="box" size="0.3 0.2 0.02"/>
      {}{}{}{}
    </body>
  </worldbody>
</mujoco>
"#,
        leg(0.25, 0.15),
        leg(-0.25, 0.15),
        leg(0.25, -0.15),
        leg(-0.25, -0.15)
    )
}

/// The stability margin (mm) and the U033 notes about planes.
fn run(floor: &str) -> (f64, Vec<(Option<u32>, String)>) {
    let dir = std::env::temp_dir().join(format!(
        "urdf-validator-mjcf-ground-{}-{}",
        std::process::id(),
        floor.len()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("table.xml");
    std::fs::write(&path, table(floor)).unwrap();
    let mut options = Options::default();
    options.workspace.samples = 50;
    options.deep.automatic = false;
    // (A body without joints is no legged or wheeled robot: its contacts are declared.)
    options.overrides.contact_links = Some(vec!["table".to_string()]);
    let report = validate(&path, &options).unwrap().report;
    let _ = std::fs::remove_dir_all(&dir);
    let margin = report.stability.as_ref().unwrap().margin_mm.unwrap();
    let notes = report
        .findings
        .iter()
        .filter(|f| f.rule == "U033" && f.message.contains("plane"))
        .map(|f| (f.line, f.message.clone()))
        .collect();
    (margin, notes)
}

#[test]
fn a_horizontal_plane_changes_nothing_and_a_tilted_one_is_noted() {
    let (bare, notes) = run("");
    assert!(notes.is_empty());
    assert!(bare > 100.0, "the table stands: {bare} mm");
    let (raised, notes) = run(r#"<geom name="floor" type="plane" size="5 5 0.1" pos="0 0 0.2"/>"#);
    assert!(notes.is_empty(), "{notes:?}");
    assert!((raised - bare).abs() < 1e-9, "{raised} vs {bare}");
    let (tilted, notes) = run(r#"<geom name="slope" type="plane" size="5 5 0.1" euler="0 20 0"/>"#);
    assert!(
        (tilted - bare).abs() < 1e-9,
        "the tilt is not used: {tilted} vs {bare}"
    );
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert_eq!(notes[0].0, Some(3), "at the plane");
    assert!(
        notes[0].1.contains("'slope' is tilted by 20.0°"),
        "{}",
        notes[0].1
    );
}
