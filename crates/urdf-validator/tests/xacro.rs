//! `.xacro` input end to end: findings point into the xacro sources through macros and includes, xacro
//! errors are load errors with their location, and nothing in an expression can run code.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};

use urdf_validator::input::LoadError;
use urdf_validator::Error;
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
    assert!(matches!(error, Error::Load(LoadError::Xacro { .. })));
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
        assert!(
            matches!(error, Error::Load(LoadError::Xacro { .. })),
            "{expression}"
        );
        assert!(!marker.exists(), "{expression} ran");
    }
}

#[test]
fn pr2_xacro_validates_like_its_expanded_urdf() {
    let Some(shared) = common::shared_robots() else {
        return;
    };
    let options = Options {
        workspace: urdf_validator::analysis::workspace::WorkspaceOptions {
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

#[test]
fn a_misspelled_xacro_argument_is_a_u010_warning_with_the_close_name() {
    let dir = scratch("xacro_misspelled_arg");
    let robot = write_robot(&dir);
    let validation = validate(&robot, &options(&[("bad_ixxx", "-0.5")])).expect("expands");
    let u010: Vec<_> = validation
        .report
        .findings
        .iter()
        .filter(|f| f.rule == "U010")
        .collect();
    assert_eq!(u010.len(), 1, "{u010:?}");
    let finding = u010[0];
    assert!(
        finding.message.contains("'bad_ixxx'"),
        "{}",
        finding.message
    );
    assert!(
        finding.message.contains("did you mean 'bad_ixx'?"),
        "{}",
        finding.message
    );
    assert!(
        finding
            .file
            .as_deref()
            .unwrap()
            .ends_with("walker.urdf.xacro"),
        "{:?}",
        finding.file
    );
    // The declared argument given correctly: no U010.
    let fine = validate(&robot, &options(&[("bad_ixx", "0.02")])).expect("expands");
    assert!(fine.report.findings.iter().all(|f| f.rule != "U010"));
}

#[test]
fn xacro_warnings_inside_macros_carry_the_call_stack() {
    let dir = scratch("xacro_warning_stack");
    std::fs::write(
        dir.join("leg.xacro"),
        r#"<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="leg" params="name">
    <xacro:if value="true" bogus="1">
      <link name="${name}_link"/>
    </xacro:if>
  </xacro:macro>
</robot>"#,
    )
    .unwrap();
    let robot = dir.join("legs.urdf.xacro");
    std::fs::write(
        &robot,
        r#"<robot name="legs" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="leg.xacro"/>
  <link name="body"/>
  <xacro:leg name="left"/>
  <xacro:leg name="right"/>
  <joint name="l" type="fixed"><parent link="body"/><child link="left_link"/></joint>
  <joint name="r" type="fixed"><parent link="body"/><child link="right_link"/></joint>
</robot>"#,
    )
    .unwrap();
    let resolver = urdf_validator::input::resolve::PackageResolver::new(Vec::new(), None, None);
    let expanded =
        urdf_validator::input::xacro::expand(&robot, &[], &resolver, false).expect("expands");
    let stacks: Vec<Vec<String>> = expanded
        .warnings()
        .into_iter()
        .filter(|w| w.message.contains("bogus"))
        .map(|w| w.location.expect("located").stack)
        .collect();
    assert_eq!(stacks.len(), 2, "{stacks:?}");
    assert!(
        stacks[0][0].starts_with("in macro 'leg' called at ")
            && stacks[0][0].ends_with("legs.urdf.xacro:4:3"),
        "{stacks:?}"
    );
    assert!(stacks[1][0].ends_with("legs.urdf.xacro:5:3"), "{stacks:?}");
    // The U010 findings of the report carry it too, so the two calls are told apart.
    let report = validate(&robot, &Options::default()).unwrap().report;
    let from: Vec<&Vec<String>> = report
        .findings
        .iter()
        .filter(|f| f.rule == "U010" && f.message.contains("bogus"))
        .map(|f| &f.expanded_from)
        .collect();
    assert_eq!(from.len(), 2);
    assert_ne!(from[0], from[1], "{from:?}");
}

#[test]
fn a_missing_package_names_the_package_paths_searched() {
    let dir = scratch("xacro_missing_package");
    let robot = dir.join("pkg.urdf.xacro");
    std::fs::write(
        &robot,
        r#"<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include filename="$(find nopkg)/x.xacro"/></robot>"#,
    )
    .unwrap();
    let pp = dir.join("pp");
    std::fs::create_dir_all(&pp).unwrap();
    let with_path = Options {
        resolver: urdf_validator::input::resolve::PackageResolver::new(
            vec![pp.clone()],
            None,
            None,
        ),
        ..Options::default()
    };
    let message = validate(&robot, &with_path)
        .expect_err("package not found")
        .to_string();
    assert!(
        message.contains(&pp.join("nopkg").display().to_string()),
        "{message}"
    );
    assert!(
        !message.contains("the caller's package finder"),
        "{message}"
    );
    assert!(message.contains("--package-path DIR"), "{message}");
    // Nothing configured: say so.
    let bare = Options {
        resolver: urdf_validator::input::resolve::PackageResolver::new(Vec::new(), None, None),
        ..Options::default()
    };
    let message = validate(&robot, &bare)
        .expect_err("package not found")
        .to_string();
    assert!(
        message.contains("no --package-path given; ROS_PACKAGE_PATH and AMENT_PREFIX_PATH unset"),
        "{message}"
    );
    assert!(message.contains("--package-path DIR"), "{message}");
}

#[test]
fn a_missing_include_names_the_resolved_path() {
    let dir = scratch("xacro_missing_include_path");
    let robot = dir.join("inc.urdf.xacro");
    std::fs::write(
        &robot,
        r#"<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include filename="sub/missing_file.xacro"/></robot>"#,
    )
    .unwrap();
    // Validated through a relative path, as a user in that folder would.
    let cwd = std::env::current_dir().unwrap();
    let relative = pathdiff(&robot, &cwd);
    let message = validate(&relative, &Options::default())
        .expect_err("missing include")
        .to_string();
    let abs = dir.join("sub/missing_file.xacro");
    assert!(message.contains(&abs.display().to_string()), "{message}");
}

/// `path` relative to `base` (both absolute), through `..` as needed.
fn pathdiff(path: &Path, base: &Path) -> PathBuf {
    let path: Vec<_> = path.components().collect();
    let base: Vec<_> = base.components().collect();
    let common = path.iter().zip(&base).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..base.len() {
        out.push("..");
    }
    for c in &path[common..] {
        out.push(c);
    }
    out
}

#[test]
fn unsaved_xacro_text_is_validated_in_place_of_the_file() {
    let dir = scratch("unsaved_xacro");
    let robot = write_robot(&dir);
    // The editor's buffer gives the right leg a bad inertia the file on disk does not have.
    let unsaved = ROBOT.replace(
        r#"<xacro:leg name="right" ixx="$(arg bad_ixx)"/>"#,
        r#"<xacro:leg name="right" ixx="-1"/>"#,
    );
    let on_disk = validate(&robot, &options(&[])).expect("validates");
    let in_editor = urdf_validator::validate_unsaved(unsaved.clone(), &robot, &options(&[]))
        .expect("validates");
    let negative = |v: &urdf_validator::Validation| {
        v.report
            .findings
            .iter()
            .filter(|f| f.message.contains("right_link"))
            .map(|f| (f.rule.clone(), f.file.clone()))
            .collect::<Vec<_>>()
    };
    assert!(negative(&on_disk).is_empty(), "{:?}", negative(&on_disk));
    let found = negative(&in_editor);
    assert!(
        !found.is_empty(),
        "the unsaved text was not the one validated"
    );
    // Located in the macro's file (read from disk), as for a saved file.
    let leg = dir.join("leg.xacro").display().to_string();
    assert!(
        found
            .iter()
            .all(|(_, file)| file.as_deref() == Some(leg.as_str())),
        "{found:?}"
    );
    // The entry file's source is the unsaved text.
    let entry = in_editor
        .sources
        .iter()
        .find(|s| s.path() == robot)
        .expect("entry source");
    assert_eq!(entry.text(), unsaved);
}

#[test]
fn structure_only_stops_before_the_physics() {
    let dir = scratch("structure_only");
    let robot = write_robot(&dir);
    let full = validate(&robot, &options(&[])).expect("validates");
    let structure = validate(
        &robot,
        &Options {
            structure_only: true,
            ..options(&[])
        },
    )
    .expect("validates");
    assert!(full.report.statics.is_some());
    assert!(structure.report.statics.is_none() && structure.report.workspace.is_none());
    let schema = |v: &urdf_validator::Validation| {
        v.report
            .findings
            .iter()
            .filter(|f| f.section == urdf_validator::diagnostics::Section::Schema)
            .map(|f| f.rule.clone())
            .collect::<Vec<_>>()
    };
    assert_eq!(schema(&structure), schema(&full));
    assert!(structure
        .report
        .findings
        .iter()
        .all(|f| f.section == urdf_validator::diagnostics::Section::Schema));
}
