//! The library's filtering (`Options::settings`): select/ignore/per-file-ignores, severity overrides,
//! inline `<!-- urdf-validate: ignore ... -->` comments in URDF and xacro, U801 and U802.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::{Path, PathBuf};

use urdf_validator::diagnostics::settings::{
    Origin, PerFileIgnore, Selector, Settings, SeverityOverride,
};
use urdf_validator::diagnostics::Severity;
use urdf_validator::report::{Report, Status};
use urdf_validator::{validate, validate_text, Options};

/// One WARN finding: U201 on `arm` (line 4), and an INFO U303 on the joint.
const WARNING: &str = r#"<robot name="warn">
  <link name="base"/>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
  <link name="arm"/>
</robot>
"#;

fn report_with(urdf: &str, settings: Settings) -> Report {
    let options = Options {
        settings,
        ..Options::default()
    };
    validate_text(urdf.to_string(), Path::new("t.urdf"), &options)
        .unwrap()
        .report
}

fn report(urdf: &str) -> Report {
    report_with(urdf, Settings::default())
}

fn codes(report: &Report) -> Vec<&str> {
    report.findings.iter().map(|f| f.rule.as_str()).collect()
}

fn sel(text: &str) -> Selector {
    Selector::new(text, Origin::Api)
}

#[test]
fn without_settings_the_robot_warns() {
    let report = report(WARNING);
    assert_eq!(report.overall_status, Status::Warn);
    assert!(codes(&report).contains(&"U201"));
}

#[test]
fn a_comment_before_the_element_or_on_its_line_suppresses() {
    let before = WARNING.replace(
        "  <link name=\"arm\"/>",
        "  <!-- urdf-validate: ignore U201 -->\n  <link name=\"arm\"/>",
    );
    let trailing = WARNING.replace(
        "  <link name=\"arm\"/>",
        "  <link name=\"arm\"/> <!-- urdf-validate: ignore missing-inertial -->",
    );
    let file_wide = format!("<!-- urdf-validate: ignore-file U201 -->\n{WARNING}");
    for urdf in [before, trailing, file_wide] {
        let report = report(&urdf);
        assert_eq!(
            report.overall_status,
            Status::Pass,
            "{urdf}\n{:?}",
            codes(&report)
        );
        assert!(!codes(&report).contains(&"U201"));
        assert!(!codes(&report).contains(&"U801"), "{urdf}");
        assert!(report.suppressed.is_empty(), "kept only when asked for");
        assert!(report.warnings.is_empty());
    }
}

#[test]
fn a_comment_covers_only_the_next_element() {
    // The comment sits before the joint: U201 on the link below is not covered, and the comment is unused.
    let urdf = WARNING.replace(
        "  <joint",
        "  <!-- urdf-validate: ignore U201 -->\n  <joint",
    );
    let report = report(&urdf);
    assert_eq!(report.overall_status, Status::Warn);
    let unused: Vec<_> = report
        .findings
        .iter()
        .filter(|f| f.rule == "U801")
        .collect();
    assert_eq!(unused.len(), 1, "{:?}", codes(&report));
    assert_eq!(unused[0].severity, Severity::Info);
    assert_eq!((unused[0].line, unused[0].column), (Some(3), Some(30)));
}

#[test]
fn show_suppressed_keeps_them_with_the_reason() {
    let settings = Settings {
        ignore: vec![sel("U201")],
        show_suppressed: true,
        ..Settings::default()
    };
    let report = report_with(WARNING, settings);
    assert_eq!(report.overall_status, Status::Pass);
    assert_eq!(report.suppressed.len(), 1);
    let suppressed = &report.suppressed[0];
    assert_eq!(suppressed.finding.rule, "U201");
    assert_eq!(suppressed.finding.line, Some(4));
    assert_eq!(suppressed.suppressed_by, "ignore (API)");
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["suppressed"][0]["rule"], "U201");
    assert_eq!(json["suppressed"][0]["suppressed_by"], "ignore (API)");
}

#[test]
fn select_and_per_file_ignores() {
    let report = report_with(
        WARNING,
        Settings {
            select: Some(vec![sel("U1"), sel("U3")]),
            ..Settings::default()
        },
    );
    assert_eq!(report.overall_status, Status::Pass);
    assert_eq!(codes(&report), vec!["U303"]);

    let per_file = |pattern: &str| Settings {
        per_file_ignores: vec![PerFileIgnore::new(pattern, vec![sel("U2")], Origin::Api).unwrap()],
        ..Settings::default()
    };
    assert_eq!(
        report_with(WARNING, per_file("*.urdf")).overall_status,
        Status::Pass
    );
    assert_eq!(
        report_with(WARNING, per_file("other/*.urdf")).overall_status,
        Status::Warn
    );
}

#[test]
fn severity_overrides_decide_the_status() {
    let with = |severity| Settings {
        severity: vec![SeverityOverride {
            rule: sel("U201"),
            severity,
        }],
        ..Settings::default()
    };
    let report = report_with(WARNING, with(Severity::Info));
    assert_eq!(report.overall_status, Status::Pass);
    let u201 = report.findings.iter().find(|f| f.rule == "U201").unwrap();
    assert_eq!(u201.severity, Severity::Info);
    let report = report_with(WARNING, with(Severity::Critical));
    assert_eq!(report.overall_status, Status::Fail);
    assert_eq!(report.overall_status.exit_code(), 2);
    assert_eq!(report.critical_issues.len(), 1);
    assert_eq!(report.schema.status, Status::Fail);
}

#[test]
fn unknown_codes_are_u802_at_their_place() {
    let settings = Settings {
        ignore: vec![Selector::new(
            "U2O1",
            Origin::File {
                path: PathBuf::from("cfg/urdf-validate.toml"),
                line: 3,
                column: 12,
            },
        )],
        ..Settings::default()
    };
    let report = report_with(WARNING, settings);
    assert_eq!(report.overall_status, Status::Warn);
    let u802 = report.findings.iter().find(|f| f.rule == "U802").unwrap();
    assert_eq!(u802.severity, Severity::Warn);
    assert_eq!(u802.file.as_deref(), Some("cfg/urdf-validate.toml"));
    assert_eq!((u802.line, u802.column), (Some(3), Some(12)));
    assert!(u802.help.as_deref().unwrap().contains("'U201'"));

    let urdf = WARNING.replace(
        "  <link name=\"arm\"/>",
        "  <!-- urdf-validate: ignroe U201 -->\n  <link name=\"arm\"/>",
    );
    let report = self::report(&urdf);
    let u802 = report.findings.iter().find(|f| f.rule == "U802").unwrap();
    assert!(
        u802.message.contains("'urdf-validate: ignroe'"),
        "{}",
        u802.message
    );
    assert!(codes(&report).contains(&"U201"));
}

#[test]
fn u801_can_be_ignored_by_the_configuration() {
    let urdf = WARNING.replace(
        "  <link name=\"arm\"/>",
        "  <!-- urdf-validate: ignore U201 U105 -->\n  <link name=\"arm\"/>",
    );
    assert!(codes(&report(&urdf)).contains(&"U801"));
    let report = report_with(
        &urdf,
        Settings {
            ignore: vec![sel("unused-suppression")],
            ..Settings::default()
        },
    );
    assert!(!codes(&report).contains(&"U801"));
    assert!(!codes(&report).contains(&"U201"));
}

#[test]
fn comments_in_xacro_sources_suppress_expanded_findings() {
    let dir = std::env::temp_dir().join(format!("urdf_validator_suppress_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("parts.xacro"),
        r#"<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="bare_link" params="name">
    <!-- urdf-validate: ignore U201 -->
    <link name="${name}"/>
  </xacro:macro>
</robot>
"#,
    )
    .unwrap();
    let entry = dir.join("robot.urdf.xacro");
    std::fs::write(
        &entry,
        r#"<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <link name="base"/>
  <joint name="j1" type="continuous"><parent link="base"/><child link="a"/></joint>
  <xacro:bare_link name="a"/>
  <joint name="j2" type="continuous"><parent link="a"/><child link="b"/></joint>
  <xacro:bare_link name="b"/>
</robot>
"#,
    )
    .unwrap();
    let report = validate(&entry, &Options::default()).unwrap().report;
    assert!(!codes(&report).contains(&"U201"), "{:?}", codes(&report));
    // Both expansions are suppressed; without the comment both warn.
    let parts = std::fs::read_to_string(dir.join("parts.xacro")).unwrap();
    std::fs::write(
        dir.join("parts.xacro"),
        parts.replace("<!-- urdf-validate: ignore U201 -->", ""),
    )
    .unwrap();
    let bare = validate(&entry, &Options::default()).unwrap().report;
    let u201: Vec<_> = bare.findings.iter().filter(|f| f.rule == "U201").collect();
    assert_eq!(u201.len(), 2, "{:?}", codes(&bare));
    assert!(u201.iter().all(|f| f
        .file
        .as_deref()
        .is_some_and(|p| p.ends_with("parts.xacro"))));
    assert!(!codes(&report).contains(&"U801"), "{:?}", codes(&report));
    assert_ne!(report.overall_status, Status::Warn, "{:?}", report.findings);
}

#[test]
fn no_inline_turns_the_comments_off() {
    let urdf = WARNING.replace(
        "  <link name=\"arm\"/>",
        "  <!-- urdf-validate: ignore U201 U1O5 -->\n  <link name=\"arm\"/>",
    );
    let report = report_with(
        &urdf,
        Settings {
            no_inline: true,
            ..Settings::default()
        },
    );
    assert_eq!(report.overall_status, Status::Warn);
    assert!(codes(&report).contains(&"U201"));
    assert!(
        !codes(&report).contains(&"U802"),
        "comments are not read at all"
    );
}
