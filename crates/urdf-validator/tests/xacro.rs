//! `.xacro` input end to end: findings point into the xacro sources through macros and includes, xacro
//! errors are load errors with their location, and nothing in an expression can run code.

mod common;

use std::path::{Path, PathBuf};

use urdf_validator::parse::LoadError;
use urdf_validator::{validate, Options};

/// A fresh directory under the target dir for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

const LEG_MACRO: &str = r#"<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="leg" params="name mass:=1.0 ixx">
    <link name="${name}_link">
      <inertial>
        <mass value="${mass}"/>
        <inertia ixx="${ixx}" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
      </inertial>
    </link>
    <joint name="${name}_joint" type="revolute">
      <parent link="body"/><child link="${name}_link"/>
      <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"#;

const ROBOT: &str = r#"<?xml version="1.0"?>
<robot name="walker" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="bad_ixx" default="0.01"/>
  <xacro:include filename="leg.xacro"/>
  <link name="body">
    <inertial><mass value="5"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
  </link>
  <xacro:leg name="left" ixx="0.01"/>
  <xacro:leg name="right" ixx="$(arg bad_ixx)"/>
</robot>
"#;

fn write_robot(dir: &Path) -> PathBuf {
    std::fs::write(dir.join("leg.xacro"), LEG_MACRO).unwrap();
    let robot = dir.join("walker.urdf.xacro");
    std::fs::write(&robot, ROBOT).unwrap();
    robot
}

fn options(args: &[(&str, &str)]) -> Options {
    Options {
        xacro_args: args
            .iter()
            .map(|(n, v)| (n.to_string(), v.to_string()))
            .collect(),
        ..Options::default()
    }
}

#[test]
fn a_broken_inertia_inside_a_macro_is_reported_at_the_macro_line_with_the_call_site() {
    let dir = scratch("xacro_macro_finding");
    let robot = write_robot(&dir);
    // Clean with the default argument.
    let clean = validate(&robot, &options(&[])).expect("expands");
    assert!(clean.report.findings.iter().all(|f| f.rule != "U205"));
    // A negative ixx given on the command line breaks the right leg only.
    let broken = validate(&robot, &options(&[("bad_ixx", "-0.5")])).expect("expands");
    let finding = broken
        .report
        .findings
        .iter()
        .find(|f| f.rule == "U205" || f.rule == "U206")
        .expect("an inertia finding");
    assert!(
        finding.message.contains("right_link"),
        "{}",
        finding.message
    );
    // Where the <inertia> is written: leg.xacro line 7, inside the macro body.
    assert!(
        finding.file.as_deref().unwrap().ends_with("leg.xacro"),
        "{:?}",
        finding.file
    );
    assert_eq!(finding.line, Some(7));
    // The call site: walker.urdf.xacro line 9, column 3.
    assert_eq!(
        finding.expanded_from.len(),
        1,
        "{:?}",
        finding.expanded_from
    );
    let call = &finding.expanded_from[0];
    assert!(call.starts_with("in macro 'leg' called at "), "{call}");
    assert!(call.ends_with("walker.urdf.xacro:9:3"), "{call}");
    // The snippet shows the xacro source.
    let text = urdf_validator::render::render_text(
        &broken,
        &urdf_validator::render::TextOptions {
            verbose: true,
            ..Default::default()
        },
    );
    assert!(text.contains(r#"<inertia ixx="${ixx}""#), "{text}");
    assert!(text.contains("note: in macro 'leg' called at"), "{text}");
}

#[test]
fn the_report_names_the_xacro_file_and_counts_its_physics() {
    let dir = scratch("xacro_report");
    let robot = write_robot(&dir);
    let validation = validate(&robot, &options(&[])).expect("expands");
    let report = &validation.report;
    assert_eq!(report.robot_name, "walker");
    assert!(report.urdf_path.ends_with("walker.urdf.xacro"));
    assert_eq!(report.statics.as_ref().unwrap().total_mass, Some(7.0));
}

#[test]
fn xacro_errors_are_load_errors_with_their_location() {
    let dir = scratch("xacro_errors");
    let robot = dir.join("typo.urdf.xacro");
    std::fs::write(
        &robot,
        r#"<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="wheel_radius" value="0.1"/>
  <link name="a"><visual><geometry><sphere radius="${wheel_radus}"/></geometry></visual></link>
</robot>"#,
    )
    .unwrap();
    let error = validate(&robot, &Options::default()).expect_err("undefined property");
    assert!(matches!(error, LoadError::Xacro { .. }));
    let message = error.to_string();
    assert!(message.contains("typo.urdf.xacro:3:"), "{message}");
    assert!(message.contains("wheel_radius"), "{message}");
    // A missing include names what it looked for.
    let missing = dir.join("missing.urdf.xacro");
    std::fs::write(
        &missing,
        r#"<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include filename="nowhere.xacro"/></robot>"#,
    )
    .unwrap();
    let message = validate(&missing, &Options::default())
        .expect_err("missing include")
        .to_string();
    assert!(message.contains("nowhere.xacro"), "{message}");
}

#[test]
fn expressions_cannot_run_code() {
    let dir = scratch("xacro_safety");
    let marker = dir.join("pwned");
    for expression in [
        format!("__import__('os').system('touch {}')", marker.display()),
        format!("open('{}', 'w')", marker.display()),
        "().__class__.__bases__[0].__subclasses__()".to_string(),
        format!(
            "eval(\"__import__('os').system('touch {}')\")",
            marker.display()
        ),
    ] {
        let robot = dir.join("evil.urdf.xacro");
        std::fs::write(
            &robot,
            format!(
                r#"<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="${{{expression}}}"/></robot>"#
            ),
        )
        .unwrap();
        let error = validate(&robot, &Options::default()).expect_err(&expression);
        assert!(matches!(error, LoadError::Xacro { .. }), "{expression}");
        assert!(!marker.exists(), "{expression} ran");
    }
}

#[test]
fn pr2_xacro_validates_like_its_expanded_urdf() {
    let Some(shared) = common::shared_robots() else {
        return;
    };
    let options = Options {
        workspace: urdf_validator::workspace::WorkspaceOptions {
            samples: 2000,
            ..Default::default()
        },
        ..Options::default()
    };
    let from_xacro = validate(
        &shared.join("pr2/pr2_description/robots/pr2.urdf.xacro"),
        &options,
    )
    .expect("PR2 xacro expands")
    .report;
    let from_urdf = validate(
        &shared.join("pr2/pr2_description/robots/pr2.urdf"),
        &options,
    )
    .expect("PR2 URDF loads")
    .report;
    let statics = |r: &urdf_validator::report::Report| {
        let s = r.statics.as_ref().unwrap();
        (s.total_mass, s.status, s.weakest_joint_name.clone())
    };
    assert_eq!(statics(&from_xacro), statics(&from_urdf));
    // Every finding of the xacro run points into a xacro file.
    for finding in &from_xacro.findings {
        if let Some(file) = &finding.file {
            assert!(file.ends_with(".xacro"), "{file}");
        }
    }
}
