//! Stability on robots whose answers are known on paper: a box chassis on four wheels, the same rocking on
//! three, a biped on box feet, a tripod on spheres; declarations and capability profiles.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::Path;

use urdf_validator::analysis::classify::RobotType;
use urdf_validator::analysis::Overrides;
use urdf_validator::report::{Confidence, Report, Status};
use urdf_validator::{validate_text, Options};

/// An `<inertial>` of `mass` at `xyz`, with the tensor of a wheel (the only moving links here: their
/// tensor fits their geometry, so U208/U209 stay quiet): axle along y, radius 0.1 m, width 0.04 m.
fn inertial(mass: f64, xyz: [f64; 3]) -> String {
    let (across, axle) = (0.0026 * mass, 0.005 * mass);
    format!(
        r#"<inertial><origin xyz="{} {} {}"/><mass value="{mass}"/><inertia ixx="{across}" ixy="0" ixz="0" iyy="{axle}" iyz="0" izz="{across}"/></inertial>"#,
        xyz[0], xyz[1], xyz[2]
    )
}

const WHEEL_RADIUS: f64 = 0.1;
const WHEEL_WIDTH: f64 = 0.04;

/// A 40 kg box chassis (COM offset by `com`) on four 1 kg wheels at x = ±0.25, y = ±0.22; wheel `raised`
/// (index 0..4) sits `lift` higher.
fn cart(com: [f64; 3], raised: Option<usize>, lift: f64) -> String {
    let mut urdf = format!(
        r#"<robot name="cart"><link name="chassis">{}<collision><origin xyz="0 0 0.2"/><geometry><box size="0.6 0.4 0.1"/></geometry></collision></link>"#,
        inertial(40.0, com)
    );
    for (i, (x, y)) in [(0.25, 0.22), (0.25, -0.22), (-0.25, 0.22), (-0.25, -0.22)]
        .iter()
        .enumerate()
    {
        let z = WHEEL_RADIUS + if raised == Some(i) { lift } else { 0.0 };
        urdf.push_str(&format!(
            r#"<joint name="wheel_{i}_joint" type="continuous"><parent link="chassis"/><child link="wheel_{i}"/>
  <origin xyz="{x} {y} {z}"/><axis xyz="0 1 0"/><limit effort="20" velocity="10"/></joint>
<link name="wheel_{i}">{}<collision><origin rpy="1.5707963267948966 0 0"/><geometry><cylinder radius="{WHEEL_RADIUS}" length="{WHEEL_WIDTH}"/></geometry></collision></link>"#,
            inertial(1.0, [0.0; 3])
        ));
    }
    urdf + "</robot>"
}

fn report_with(urdf: &str, overrides: Overrides) -> Report {
    let options = Options {
        overrides,
        ..Options::default()
    };
    validate_text(urdf.to_string(), Path::new("t.urdf"), &options)
        .expect("loads")
        .report
}

fn report(urdf: &str) -> Report {
    report_with(urdf, Overrides::default())
}

#[test]
fn cart_margin_direction_and_tipping_angle_are_exact() {
    let (cx, cy, cz) = (0.1, -0.05, 0.2);
    let report = report(&cart([cx, cy, cz], None, 0.0));
    assert_eq!(report.robot_type, Some(RobotType::Wheeled));
    let s = report.stability.expect("stability");
    assert_eq!(s.status, Status::Pass);
    // Whole-body COM: the 4 wheel masses sit at the wheel centres (z = 0.1), symmetric in x and y.
    let total = 44.0;
    let com = [
        40.0 * cx / total,
        40.0 * cy / total,
        (40.0 * cz + 4.0 * WHEEL_RADIUS) / total,
    ];
    // Support rectangle: rim bottoms at x = ±0.25, y = ±(0.22 + width/2).
    let half_y = 0.22 + WHEEL_WIDTH / 2.0;
    let to_front = 0.25 - com[0];
    let to_right = half_y + com[1];
    let margin = to_front.min(to_right);
    assert!(
        (s.margin_mm.unwrap() - 1000.0 * margin).abs() < 1e-6,
        "{:?} vs {}",
        s.margin_mm,
        1000.0 * margin
    );
    assert_eq!(
        s.tip_direction.as_deref(),
        Some(if to_front < to_right {
            "front"
        } else {
            "right"
        })
    );
    let height = com[2];
    assert!((s.com_height.unwrap() - height).abs() < 1e-9);
    assert!((s.tipping_angle_deg.unwrap() - margin.atan2(height).to_degrees()).abs() < 1e-6);
    let width = 2.0 * half_y;
    assert!((s.com_height_ratio.unwrap() - height / width).abs() < 1e-9);
    assert_eq!(s.com_height_ratio_class.as_deref(), Some("very_stable"));
    assert_eq!(s.contact_links.len(), 4);
    assert!(s.raised_contacts.is_empty());
    assert_eq!(s.contact_confidence, Confidence::Estimated);
}

#[test]
fn com_outside_the_wheels_fails_with_a_negative_margin() {
    let s = report(&cart([0.4, 0.0, 0.2], None, 0.0)).stability.unwrap();
    let com_x = 40.0 * 0.4 / 44.0;
    assert_eq!(s.status, Status::Fail);
    assert_eq!(s.stable, Some(false));
    assert!((s.margin_mm.unwrap() - 1000.0 * (0.25 - com_x)).abs() < 1e-6);
    assert_eq!(s.tip_direction.as_deref(), Some("front"));
}

#[test]
fn a_raised_wheel_is_reported_and_does_not_support() {
    let s = report(&cart([0.0, 0.0, 0.2], Some(0), 0.02))
        .stability
        .unwrap();
    assert_eq!(s.raised_contacts.len(), 1);
    assert_eq!(s.raised_contacts[0].link, "wheel_0");
    assert!((s.raised_contacts[0].height_mm - 20.0).abs() < 1e-6);
    assert_eq!(s.contact_links.len(), 3);
    // Supports: rim points of the other three wheels; the hull's diagonal edge runs from the front-right
    // wheel's inner rim (0.25, −0.2) to the rear-left wheel's outer rim (−0.25, 0.24).
    assert_eq!(s.support_polygon.len(), 4);
    let (b, c): ([f64; 2], [f64; 2]) = ([0.25, -0.2], [-0.25, 0.24]);
    let diagonal = ((c[0] - b[0]) * (0.0 - b[1]) - (c[1] - b[1]) * (0.0 - b[0])).abs()
        / (c[0] - b[0]).hypot(c[1] - b[1]);
    assert!(
        (s.margin_mm.unwrap() - 1000.0 * diagonal).abs() < 1e-6,
        "{:?} vs {}",
        s.margin_mm,
        1000.0 * diagonal
    );
    assert_eq!(s.tip_direction.as_deref(), Some("front-left"));
    assert_eq!(s.status, Status::Pass);
}

/// A 30 kg pelvis 0.6 m up on two legs (hip and knee revolute) with 0.2 × 0.1 box feet at y = ±0.1.
fn biped() -> String {
    let mut urdf = format!(
        r#"<robot name="biped"><link name="pelvis">{}<collision><geometry><box size="0.2 0.3 0.1"/></geometry></collision></link>"#,
        inertial(30.0, [0.0; 3])
    );
    for (side, y) in [("left", 0.1), ("right", -0.1)] {
        urdf.push_str(&format!(
            r#"<joint name="{side}_hip" type="revolute"><parent link="pelvis"/><child link="{side}_thigh"/><origin xyz="0 {y} -0.05"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="200" velocity="5"/></joint>
<link name="{side}_thigh">{}</link>
<joint name="{side}_knee" type="revolute"><parent link="{side}_thigh"/><child link="{side}_shin"/><origin xyz="0 0 -0.25"/><axis xyz="0 1 0"/><limit lower="0" upper="2" effort="200" velocity="5"/></joint>
<link name="{side}_shin">{}</link>
<joint name="{side}_ankle" type="fixed"><parent link="{side}_shin"/><child link="{side}_foot"/><origin xyz="0 0 -0.29"/></joint>
<link name="{side}_foot">{}<collision><geometry><box size="0.2 0.1 0.02"/></geometry></collision></link>"#,
            inertial(3.0, [0.0, 0.0, -0.12]),
            inertial(2.0, [0.0, 0.0, -0.12]),
            inertial(1.0, [0.0; 3])
        ));
    }
    urdf + "</robot>"
}

#[test]
fn biped_stands_on_the_hull_of_its_two_feet() {
    let report = report(&biped());
    assert_eq!(
        report.robot_type,
        Some(RobotType::Legged),
        "{:?}",
        report.robot_type_evidence
    );
    let s = report.stability.unwrap();
    assert_eq!(s.contact_source.as_deref(), Some("feet"));
    assert_eq!(s.contact_links, ["left_foot", "right_foot"]);
    assert_eq!(s.support_polygon.len(), 4, "outer corners of the two feet");
    // Feet span x ∈ [−0.1, 0.1], y ∈ [−0.15, 0.15]; the COM is on x = 0, y = 0.
    assert!((s.margin_mm.unwrap() - 100.0).abs() < 1e-6);
    assert_eq!(s.tip_direction.as_deref(), Some("front"));
}

#[test]
fn tripod_on_three_spheres_has_the_triangle_inradius_as_margin() {
    let radius = 0.3;
    let mut urdf = format!(
        r#"<robot name="tripod"><link name="body">{}</link>"#,
        inertial(10.0, [0.0, 0.0, 0.5])
    );
    for i in 0..3 {
        let angle = std::f64::consts::TAU * i as f64 / 3.0;
        urdf.push_str(&format!(
            r#"<joint name="leg_{i}" type="fixed"><parent link="body"/><child link="foot_{i}"/><origin xyz="{} {} 0.05"/></joint>
<link name="foot_{i}">{}<collision><geometry><sphere radius="0.05"/></geometry></collision></link>"#,
            radius * angle.cos(),
            radius * angle.sin(),
            inertial(0.1, [0.0; 3])
        ));
    }
    urdf.push_str("</robot>");
    // Nothing moves, so the structure says `object` and stability is N/A; declared a robot of unknown
    // type, it stands on its lowest geometry: the three feet.
    assert_eq!(report(&urdf).robot_type, Some(RobotType::Object));
    let declared = Overrides {
        robot_type: Some(RobotType::Unknown),
        ..Overrides::default()
    };
    let report = report_with(&urdf, declared);
    let s = report.stability.unwrap();
    assert_eq!(s.contact_links.len(), 3);
    // Equilateral triangle with circumradius R: inradius R/2, and the COM sits on the centroid.
    assert!(
        (s.margin_mm.unwrap() - 1000.0 * radius / 2.0).abs() < 1e-6,
        "{:?}",
        s.margin_mm
    );
    assert!(s.ground_height.unwrap().abs() < 1e-12);
}

#[test]
fn declared_contacts_are_exact_and_unknown_names_are_errors() {
    let declared = Overrides {
        contact_links: Some(vec!["wheel_0".into(), "wheel_1".into(), "wheel_2".into()]),
        ..Overrides::default()
    };
    let s = report_with(&cart([0.0; 3], None, 0.0), declared)
        .stability
        .unwrap();
    assert_eq!(s.contact_confidence, Confidence::Exact);
    assert_eq!(s.contact_source.as_deref(), Some("declared"));
    assert_eq!(s.contact_links.len(), 3);
    let wrong = Overrides {
        contact_links: Some(vec!["wheel_9".into()]),
        ..Overrides::default()
    };
    let options = Options {
        overrides: wrong,
        ..Options::default()
    };
    let error = validate_text(cart([0.0; 3], None, 0.0), Path::new("t.urdf"), &options)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("unknown link 'wheel_9'") && error.contains("did you mean"),
        "{error}"
    );
}

#[test]
fn declared_type_wins_and_a_disagreement_is_told() {
    let declared = Overrides {
        robot_type: Some(RobotType::Aerial),
        ..Overrides::default()
    };
    // The centre of mass inside the chassis box (else U209 warns about the root's tensor).
    let report = report_with(&cart([0.0, 0.0, 0.2], None, 0.0), declared);
    assert_eq!(
        (report.robot_type, report.robot_type_confidence),
        (Some(RobotType::Aerial), Some(Confidence::Exact))
    );
    assert_eq!(report.robot_type_detected, Some(RobotType::Wheeled));
    // U730, an INFO: the declaration wins and the verdict does not change.
    let told: Vec<&str> = report
        .findings
        .iter()
        .filter(|f| f.rule == "U730")
        .map(|f| f.message.as_str())
        .collect();
    assert!(
        told.iter()
            .any(|w| w.contains("--robot-type=aerial") && w.contains("wheeled")),
        "{told:?}"
    );
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    let s = report.stability.unwrap();
    assert_eq!(
        s.status,
        Status::NotApplicable,
        "aerial robots have no ground contact"
    );
    assert_eq!(
        report.overall_status,
        Status::Pass,
        "N/A is excluded from the overall status"
    );
}

#[test]
fn arm_declarations_are_validated() {
    let urdf = cart([0.0; 3], None, 0.0);
    let check = |root: &str, tip: &str| {
        let overrides = Overrides {
            arms: vec![(root.into(), tip.into())],
            ..Overrides::default()
        };
        validate_text(
            urdf.clone(),
            Path::new("t.urdf"),
            &Options {
                overrides,
                ..Options::default()
            },
        )
        .map(|_| ())
    };
    assert!(check("chassis", "wheel_0").is_ok());
    let error = check("wheel_0", "wheel_1").unwrap_err().to_string();
    assert!(error.contains("not below"), "{error}");
    let error = check("chasis", "wheel_0").unwrap_err().to_string();
    assert!(error.contains("did you mean 'chassis'"), "{error}");
}

/// Three capsule feet (radius 0.05, length 0.2) at the corners of an equilateral triangle of circumradius
/// 0.3, each hanging 0.05 m below the body origin; `rpy` orients them (upright along z, or lying).
fn tripod_on_capsules(rpy: &str) -> String {
    let radius = 0.3;
    let mut urdf = format!(
        r#"<robot name="tripod" version="1.1"><link name="body">{}</link>"#,
        inertial(10.0, [0.0, 0.0, 0.5])
    );
    for i in 0..3 {
        let angle = std::f64::consts::TAU * i as f64 / 3.0;
        urdf.push_str(&format!(
            r#"<joint name="leg_{i}" type="fixed"><parent link="body"/><child link="foot_{i}"/><origin xyz="{} {} 0.05"/></joint>
<link name="foot_{i}">{}<collision><origin rpy="{rpy}"/><geometry><capsule radius="0.05" length="0.2"/></geometry></collision></link>"#,
            radius * angle.cos(),
            radius * angle.sin(),
            inertial(0.1, [0.0; 3])
        ));
    }
    urdf + "</robot>"
}

#[test]
fn capsule_feet_touch_at_their_rounded_ends() {
    // Three fixed feet and nothing that moves: an object, whose stability is N/A. Declared a robot of
    // unknown type, it stands on its lowest geometry: the three capsules.
    let declared = || Overrides {
        robot_type: Some(RobotType::Unknown),
        ..Overrides::default()
    };
    // Upright: the lowest point is the bottom of the lower cap, 0.05 − 0.1 − 0.05 = −0.1.
    let report = report_with(&tripod_on_capsules("0 0 0"), declared());
    assert!(
        report.findings.iter().all(|f| f.rule != "U011"),
        "capsules in a 1.1 file are fine"
    );
    let s = report.stability.unwrap();
    assert_eq!(s.contact_links.len(), 3, "{:?}", s.contact_links);
    assert!(
        (s.ground_height.unwrap() + 0.1).abs() < 1e-9,
        "{:?}",
        s.ground_height
    );
    assert!(
        (s.margin_mm.unwrap() - 150.0).abs() < 1e-6,
        "{:?}",
        s.margin_mm
    );
    // Lying along x: the lowest points are the whole bottom line of the cylinder part, at 0.05 − 0.05 = 0;
    // the support hull grows by the half-length on each foot, so the margin is at least the point-foot one.
    let s = report_with(&tripod_on_capsules("0 1.5707963267948966 0"), declared())
        .stability
        .unwrap();
    assert!(
        s.ground_height.unwrap().abs() < 1e-9,
        "{:?}",
        s.ground_height
    );
    assert!(s.margin_mm.unwrap() >= 150.0 - 1e-6, "{:?}", s.margin_mm);
}

#[test]
fn a_link_below_the_declared_ground_starts_inside_it() {
    // Wheel 3 hangs 30 mm below the three declared ones, which the ground is put under.
    let lowered = cart([0.0; 3], Some(3), -0.03);
    let declared = Overrides {
        contact_links: Some(vec!["wheel_0".into(), "wheel_1".into(), "wheel_2".into()]),
        ..Overrides::default()
    };
    let inside: Vec<String> = report_with(&lowered, declared)
        .findings
        .into_iter()
        .filter(|f| f.rule == "U603")
        .map(|f| f.message)
        .collect();
    assert_eq!(inside.len(), 1, "{inside:#?}");
    assert!(
        inside[0].starts_with("link 'wheel_3' starts 30.0 mm deep at the evaluated pose inside the ground the stability section stands the robot on"),
        "{inside:#?}"
    );
    // Found by the structure, the ground goes under the lowest wheel: nothing is inside it.
    assert!(report(&lowered).findings.iter().all(|f| f.rule != "U603"));
}
