//! JUnit XML: one `<testsuite>` per robot, one `<testcase>` per check.
//!
//! The checks, named by the report section they belong to: `schema`; `statics: <joint>` for every actuated
//! joint (`statics` alone when the robot has none, or for statics findings naming no joint); `statics:
//! payload` with `--payload-mass`; `stability`; `workspace: <tip>` for every arm (`workspace` alone without
//! arms, or for the workspace findings: reach, self-collision, task); `workspace: self-collision` and
//! `workspace: task` when they ran; `symmetry` and `deep` with findings. A check fails (`<failure>`, listing
//! `file:line:col` of each) when
//! it has a CRITICAL or FAIL finding; otherwise it is skipped (`<skipped>`) when its status is UNKNOWN or
//! N/A, and passes otherwise. WARN and INFO findings, and the numbers behind a verdict, go to the test
//! case's `<system-out>`. An input that gave no report is a suite with one errored test case `load`.

use std::fmt::Write;
use std::path::Path;

use crate::diagnostics::finding::{Section, Severity};
use crate::render::location::{DisplayPath, Place};
use crate::render::{FormatOptions, Unreported};
use crate::report::{FindingReport, Report, Status};
use crate::Validation;

/// The JUnit XML of every validation (one suite each) and every input that gave none.
pub fn render_junit(
    validations: &[&Validation],
    unreported: &[Unreported],
    options: &FormatOptions,
) -> String {
    let base = options.base_dir.as_deref();
    let mut suites: Vec<Suite> = validations.iter().map(|v| suite(&v.report, base)).collect();
    suites.extend(unreported.iter().map(|input| {
        let file = if input.file.is_empty() {
            String::new()
        } else {
            DisplayPath::new(&input.file, base).as_str().to_string()
        };
        let name = match stem(&input.file) {
            name if name.is_empty() => "input".to_string(),
            name => name,
        };
        Suite {
            name,
            file: file.clone(),
            timestamp: None,
            properties: Vec::new(),
            cases: vec![Case {
                name: "load".into(),
                outcome: Outcome::Error {
                    message: input.error.clone(),
                    body: input.error.clone(),
                },
                out: String::new(),
            }],
        }
    }));

    let count = |f: fn(&Outcome) -> bool| -> usize {
        suites
            .iter()
            .map(|s| s.cases.iter().filter(|c| f(&c.outcome)).count())
            .sum()
    };
    let mut xml = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        xml,
        "<testsuites name=\"urdf_validate\" tests=\"{}\" failures=\"{}\" errors=\"{}\" skipped=\"{}\">",
        count(|_| true),
        count(|o| matches!(o, Outcome::Failure { .. })),
        count(|o| matches!(o, Outcome::Error { .. })),
        count(|o| matches!(o, Outcome::Skipped { .. })),
    );
    for suite in &suites {
        suite.write(&mut xml);
    }
    xml.push_str("</testsuites>\n");
    xml
}

/// A test suite: one robot.
struct Suite {
    name: String,
    file: String,
    timestamp: Option<String>,
    properties: Vec<(&'static str, String)>,
    cases: Vec<Case>,
}

/// A test case: one check.
struct Case {
    name: String,
    outcome: Outcome,
    /// `<system-out>`: WARN/INFO findings and the numbers behind the verdict.
    out: String,
}

enum Outcome {
    Passed,
    Failure {
        message: String,
        kind: String,
        body: String,
    },
    Skipped {
        message: String,
    },
    Error {
        message: String,
        body: String,
    },
}

impl Suite {
    fn write(&self, xml: &mut String) {
        let failures = self
            .cases
            .iter()
            .filter(|c| matches!(c.outcome, Outcome::Failure { .. }))
            .count();
        let errors = self
            .cases
            .iter()
            .filter(|c| matches!(c.outcome, Outcome::Error { .. }))
            .count();
        let skipped = self
            .cases
            .iter()
            .filter(|c| matches!(c.outcome, Outcome::Skipped { .. }))
            .count();
        let _ = write!(
            xml,
            "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{failures}\" errors=\"{errors}\" skipped=\"{skipped}\" file=\"{}\"",
            attr(&self.name),
            self.cases.len(),
            attr(&self.file),
        );
        if let Some(timestamp) = &self.timestamp {
            let _ = write!(xml, " timestamp=\"{}\"", attr(timestamp));
        }
        xml.push_str(">\n");
        if !self.properties.is_empty() {
            xml.push_str("    <properties>\n");
            for (name, value) in &self.properties {
                let _ = writeln!(
                    xml,
                    "      <property name=\"{name}\" value=\"{}\"/>",
                    attr(value)
                );
            }
            xml.push_str("    </properties>\n");
        }
        for case in &self.cases {
            let _ = write!(
                xml,
                "    <testcase name=\"{}\" classname=\"{}\" file=\"{}\"",
                attr(&case.name),
                attr(&self.name),
                attr(&self.file)
            );
            if matches!(case.outcome, Outcome::Passed) && case.out.is_empty() {
                xml.push_str("/>\n");
                continue;
            }
            xml.push_str(">\n");
            match &case.outcome {
                Outcome::Passed => {}
                Outcome::Failure {
                    message,
                    kind,
                    body,
                } => {
                    let _ = writeln!(
                        xml,
                        "      <failure message=\"{}\" type=\"{}\">{}</failure>",
                        attr(message),
                        attr(kind),
                        text(body)
                    );
                }
                Outcome::Skipped { message } => {
                    let _ = writeln!(xml, "      <skipped message=\"{}\"/>", attr(message));
                }
                Outcome::Error { message, body } => {
                    let _ = writeln!(
                        xml,
                        "      <error message=\"{}\" type=\"load\">{}</error>",
                        attr(message),
                        text(body)
                    );
                }
            }
            if !case.out.is_empty() {
                let _ = writeln!(xml, "      <system-out>{}</system-out>", text(&case.out));
            }
            xml.push_str("    </testcase>\n");
        }
        xml.push_str("  </testsuite>\n");
    }
}

/// The suite of one report.
fn suite(report: &Report, base: Option<&Path>) -> Suite {
    let name = if report.robot_name.is_empty() {
        stem(&report.urdf_path)
    } else {
        report.robot_name.clone()
    };
    let findings_in = |sections: &[Section]| -> Vec<&FindingReport> {
        report
            .findings
            .iter()
            .filter(|f| sections.contains(&f.section))
            .collect()
    };
    let mut cases = Vec::new();
    cases.push(case(
        "schema".into(),
        report.schema.status,
        None,
        &findings_in(&[Section::Schema]),
        String::new(),
        report,
        base,
    ));

    if let Some(statics) = &report.statics {
        let findings = findings_in(&[Section::Statics]);
        let mut claimed = vec![false; findings.len()];
        for joint in &statics.joints {
            let quoted = format!("'{}'", joint.name);
            let mine: Vec<&FindingReport> = findings
                .iter()
                .zip(claimed.iter_mut())
                .filter(|(f, _)| f.message.contains(&quoted))
                .map(|(f, claimed)| {
                    *claimed = true;
                    *f
                })
                .collect();
            let out = format!("{}\n", joint.summary);
            cases.push(case(
                format!("statics: {}", joint.name),
                joint.status,
                Some(joint.summary.clone()),
                &mine,
                out,
                report,
                base,
            ));
        }
        let rest: Vec<&FindingReport> = findings
            .iter()
            .zip(&claimed)
            .filter(|(_, claimed)| !**claimed)
            .map(|(f, _)| *f)
            .collect();
        if statics.joints.is_empty() || !rest.is_empty() {
            let status = if statics.joints.is_empty() {
                statics.status
            } else {
                Status::Pass
            };
            cases.push(case(
                "statics".into(),
                status,
                statics.reason.clone(),
                &rest,
                String::new(),
                report,
                base,
            ));
        }
        if statics.payload_mass.is_some() {
            let mut out = String::new();
            if let (Some(mass), Some(link)) = (statics.payload_mass, &statics.payload_link) {
                let _ = writeln!(out, "payload: {mass} kg at {link}");
            }
            if let Some(capacity) = statics.payload_capacity_kg {
                let _ = writeln!(out, "payload capacity: {capacity:.2} kg");
            }
            cases.push(case(
                "statics: payload".into(),
                Status::Pass,
                None,
                &[],
                out,
                report,
                base,
            ));
        }
    }

    if let Some(stability) = &report.stability {
        let mut out = String::new();
        if let Some(margin) = stability.margin_mm {
            let _ = writeln!(out, "stability margin: {margin:.1} mm");
        }
        if let Some(angle) = stability.tipping_angle_deg {
            let _ = writeln!(out, "tipping angle: {angle:.1}°");
        }
        cases.push(case(
            "stability".into(),
            stability.status,
            stability.reason.clone(),
            &findings_in(&[Section::Stability]),
            out,
            report,
            base,
        ));
    }

    if let Some(workspace) = &report.workspace {
        for arm in &workspace.arms {
            let out = format!(
                "arm {} → {}: max reach {:.3} m, vertical {:.3} m, horizontal {:.3} m\n",
                arm.root_link,
                arm.tip_link,
                arm.max_reach,
                arm.vertical_reach,
                arm.horizontal_reach
            );
            cases.push(case(
                format!("workspace: {}", arm.tip_link),
                Status::Pass,
                None,
                &[],
                out,
                report,
                base,
            ));
        }
        let general = findings_in(&[Section::Workspace]);
        if workspace.arms.is_empty() || !general.is_empty() {
            let status = if workspace.arms.is_empty() {
                workspace.status
            } else {
                Status::Pass
            };
            cases.push(case(
                "workspace".into(),
                status,
                workspace.reason.clone(),
                &general,
                String::new(),
                report,
                base,
            ));
        }
        if !workspace.arms.is_empty() {
            let (status, reason) = match workspace.self_collision_free_fraction {
                Some(_) => (Status::Pass, None),
                None => (
                    Status::Unknown,
                    workspace.self_collision_not_assessed.clone(),
                ),
            };
            let mut out = String::new();
            if let Some(free) = workspace.self_collision_free_fraction {
                let _ = writeln!(out, "collision-free poses: {:.1}%", free * 100.0);
            }
            cases.push(case(
                "workspace: self-collision".into(),
                status,
                reason,
                &[],
                out,
                report,
                base,
            ));
        }
        if workspace.task.is_some() || workspace.orientation.is_some() {
            let status = if workspace.task_height_reachable.is_none()
                && workspace.orientation_reachable.is_none()
            {
                Status::Unknown
            } else {
                Status::Pass
            };
            cases.push(case(
                "workspace: task".into(),
                status,
                workspace.task_com_not_assessed.clone(),
                &[],
                String::new(),
                report,
                base,
            ));
        }
    }
    // Findings of a section the report does not hold (`--task` on a file that is not a robot) and of the
    // sections without cases of their own: one case per section.
    let sections = [
        (Section::Statics, report.statics.is_some()),
        (Section::Stability, report.stability.is_some()),
        (Section::Workspace, report.workspace.is_some()),
        (Section::Symmetry, false),
        (Section::Deep, false),
    ];
    for (section, has_case) in sections {
        let findings = findings_in(&[section]);
        if !has_case && !findings.is_empty() {
            cases.push(case(
                section.as_str().into(),
                Status::Pass,
                None,
                &findings,
                String::new(),
                report,
                base,
            ));
        }
    }

    Suite {
        name,
        file: DisplayPath::new(&report.urdf_path, base)
            .as_str()
            .to_string(),
        timestamp: Some(report.timestamp.trim_end_matches('Z').to_string()),
        properties: vec![
            ("overall_status", report.overall_status.label().to_string()),
            (
                "confidence_level",
                report.confidence_level.label().to_string(),
            ),
            ("validator_version", report.validator_version.clone()),
        ],
        cases,
    }
}

/// One check: failed by its CRITICAL/FAIL findings, else skipped when UNKNOWN or N/A, else passed.
fn case(
    name: String,
    status: Status,
    reason: Option<String>,
    findings: &[&FindingReport],
    mut out: String,
    report: &Report,
    base: Option<&Path>,
) -> Case {
    let line = |f: &FindingReport| {
        format!(
            "{}: {} {} {}: {}",
            Place::of(f, &report.urdf_path).label(base),
            f.severity.label(),
            f.rule,
            f.name,
            f.message
        )
    };
    let failing: Vec<&&FindingReport> = findings
        .iter()
        .filter(|f| matches!(f.severity, Severity::Critical | Severity::Fail))
        .collect();
    for finding in findings
        .iter()
        .filter(|f| matches!(f.severity, Severity::Warn | Severity::Info))
    {
        out.push_str(&line(finding));
        out.push('\n');
    }
    let outcome = match failing.first() {
        Some(first) => Outcome::Failure {
            message: if failing.len() == 1 {
                first.message.clone()
            } else {
                format!("{} (and {} more)", first.message, failing.len() - 1)
            },
            kind: format!("{} {}", first.rule, first.name),
            body: failing
                .iter()
                .map(|f| {
                    let mut text = line(f);
                    if let Some(help) = &f.help {
                        text.push_str("\n  help: ");
                        text.push_str(help);
                    }
                    text
                })
                .collect::<Vec<_>>()
                .join("\n"),
        },
        None => match status {
            Status::Unknown | Status::NotApplicable => Outcome::Skipped {
                message: match reason {
                    Some(reason) => format!("{}: {reason}", status.label()),
                    None => status.label().to_string(),
                },
            },
            _ => Outcome::Passed,
        },
    };
    Case { name, outcome, out }
}

/// `robot.urdf.xacro` → `robot`.
fn stem(path: &str) -> String {
    let name = Path::new(path)
        .file_name()
        .map_or_else(|| path.to_string(), |n| n.to_string_lossy().into_owned());
    let name = name.strip_suffix(".xacro").unwrap_or(&name);
    name.strip_suffix(".urdf").unwrap_or(name).to_string()
}

/// Text escaped for an XML attribute value.
fn attr(value: &str) -> String {
    escape(value, true)
}

/// Text escaped for XML character data.
fn text(value: &str) -> String {
    escape(value, false)
}

/// Escapes markup characters; drops characters XML 1.0 cannot hold (control characters but tab, line
/// feed and carriage return). In attributes, line breaks and tabs become character references so they
/// survive attribute-value normalisation.
fn escape(value: &str, attribute: bool) -> String {
    let mut out = String::with_capacity(value.len());
    for c in value.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' if attribute => out.push_str("&quot;"),
            '\n' if attribute => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            '\t' if attribute => out.push_str("&#9;"),
            '\t' | '\n' => out.push(c),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => {}
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escaping_keeps_the_xml_well_formed() {
        assert_eq!(
            attr("a<b>&\"c\"\nd\u{1}"),
            "a&lt;b&gt;&amp;&quot;c&quot;&#10;d"
        );
        assert_eq!(text("x < y\n\"z\""), "x &lt; y\n\"z\"");
        let xml = format!("<a b=\"{}\">{}</a>", attr("\"<&>\u{0}"), text("]]>&\u{8}"));
        assert!(roxmltree::Document::parse(&xml).is_ok(), "{xml}");
    }

    #[test]
    fn stems() {
        assert_eq!(stem("/a/husky.urdf.xacro"), "husky");
        assert_eq!(stem("r.urdf"), "r");
    }
}
