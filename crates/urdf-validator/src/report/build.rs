//! Assembling the [`Report`] from the stages' results: findings positioned in the files the user edits,
//! the schema section and the overall verdict.

use crate::analysis::{mass, Physics};
use crate::diagnostics::fix::Fix;
use crate::diagnostics::{overall_status, rules, Finding, Section, Settings, Severity};
use crate::input::Loaded;
use crate::model::overrides::Applied;
use crate::model::Model;
use crate::report::baseline::{self, Baseline, ElementPaths};
use crate::report::AppliedOverride;
use crate::report::{filter, FileEdit, FindingReport, FixReport, Report, SchemaSection, Status};
use crate::urdf::Robot;

/// What the stages produced for one robot.
pub struct Outcome<'a> {
    /// The file as loaded (positions, xacro warnings).
    pub loaded: &'a Loaded,
    /// The XML document of a URDF as the parse stage read it (element paths come from it); `None` for
    /// SDFormat, whose entry file is read again here.
    pub document: Option<&'a roxmltree::Document<'a>>,
    /// The parsed robot.
    pub robot: &'a Robot,
    /// Its tree.
    pub model: &'a Model,
    /// Every finding of the parse, model, checks and analyses.
    pub findings: Vec<Finding>,
    /// The analyses' sections (`None` when the file is not a robot).
    pub analyses: Option<Physics>,
    /// Rule selection, severity overrides and suppressions.
    pub settings: &'a Settings,
    /// `--baseline`: the findings it holds are not reported.
    pub baseline: Option<&'a Baseline>,
    /// The `--override`s applied.
    pub overrides: Vec<Applied>,
}

/// The report of one robot.
pub fn build(outcome: Outcome) -> Report {
    let Outcome {
        loaded,
        document,
        robot,
        model,
        findings,
        analyses,
        settings,
        baseline,
        overrides,
    } = outcome;
    let reread = match document {
        Some(_) => None,
        None => baseline::document(loaded.text()),
    };
    let paths = ElementPaths::of(document.or(reread.as_ref()));
    let mut pairs: Vec<(Finding, FindingReport)> = findings
        .into_iter()
        .map(|finding| {
            let mut report = finding_report(&finding);
            report.fix = finding.fix.as_ref().map(|fix| fix_report(fix, loaded));
            if let Some(span) = finding.span {
                report.element = paths.at(span);
                if let Some(at) = loaded.locate(span) {
                    report.place(at);
                }
            }
            (finding, report)
        })
        .collect();
    // Expander warnings are located in the xacro sources already (not in the expanded text).
    for warning in loaded.warnings() {
        let rule = if warning.refused {
            &rules::ACCESS_REFUSED
        } else {
            &rules::XACRO_WARNING
        };
        let finding = Finding::new(rule, None, warning.message);
        let mut report = finding_report(&finding);
        if let Some(at) = warning.location {
            report.place(at);
        }
        pairs.push((finding, report));
    }
    let filtered = filter::apply(pairs, settings, &loaded.path, &loaded.source_texts());
    let robot_name = robot
        .name
        .as_ref()
        .map(|n| n.value.clone())
        .unwrap_or_default();
    let (kept, baseline) = match baseline {
        Some(b) => {
            let (new, summary) =
                baseline::apply(filtered.kept, b.robot(&loaded.path, &robot_name), &b.path);
            (new, Some(summary))
        }
        None => (filtered.kept, None),
    };
    let (findings, finding_reports): (Vec<Finding>, Vec<FindingReport>) = kept.into_iter().unzip();
    let schema: Vec<&Finding> = findings
        .iter()
        .filter(|f| f.section == Section::Schema)
        .collect();
    let schema_critical = messages(schema.iter().copied(), &[Severity::Critical]);
    let schema_warnings = messages(schema.iter().copied(), &[Severity::Warn]);
    let schema_status = if !schema_critical.is_empty() {
        Status::Fail
    } else if !schema_warnings.is_empty() {
        Status::Warn
    } else {
        Status::Pass
    };
    let links = mass::link_reports(robot, model);
    let summary = mass::summarize(&links);
    Report {
        urdf_path: loaded.path.display().to_string(),
        robot_name,
        timestamp: super::timestamp::now(),
        validator_version: crate::report::VERSION.to_string(),
        overall_status: overall_status(&findings),
        robot_type: analyses.as_ref().map(|a| a.robot_type),
        robot_type_confidence: analyses.as_ref().map(|a| a.robot_type_confidence),
        robot_type_detected: analyses.as_ref().map(|a| a.detected),
        robot_type_evidence: analyses.as_ref().map(|a| a.evidence.clone()),
        confidence_level: mass::confidence_level(&summary),
        critical_issues: messages(&findings, &[Severity::Critical, Severity::Fail]),
        warnings: messages(&findings, &[Severity::Warn]),
        unknowns: analyses.iter().flat_map(unknowns).collect(),
        schema: SchemaSection {
            status: schema_status,
            critical_issues: schema_critical,
            warnings: schema_warnings,
            infos: messages(schema.iter().copied(), &[Severity::Info]),
        },
        physics: summary,
        links,
        statics: analyses.as_ref().map(|a| a.statics.clone()),
        workspace: analyses.as_ref().map(|a| a.workspace.clone()),
        symmetry: analyses.as_ref().map(|a| a.symmetry.clone()),
        deep: analyses.as_ref().and_then(|a| a.deep.clone()),
        stability: analyses.map(|a| a.stability),
        findings: finding_reports,
        suppressed: filtered.suppressed,
        baseline,
        overrides: overrides
            .into_iter()
            .map(|applied| AppliedOverride {
                fix: applied.fix.as_ref().map(|fix| fix_report(fix, loaded)),
                key: applied.key,
                value: applied.value,
                was: applied.was,
            })
            .collect(),
        timings_ms: None,
    }
}

/// What could not be assessed, one line per section.
fn unknowns(analyses: &Physics) -> Vec<String> {
    let sections = [
        (
            "Statics",
            &analyses.statics.status,
            &analyses.statics.reason,
            "a joint cannot be assessed",
        ),
        (
            "Stability",
            &analyses.stability.status,
            &analyses.stability.reason,
            "no result",
        ),
        (
            "Workspace",
            &analyses.workspace.status,
            &analyses.workspace.reason,
            "no result",
        ),
    ];
    let deep = analyses
        .deep
        .as_ref()
        .filter(|d| d.status == Status::Unknown)
        .map(|d| {
            format!(
                "Deep: {}",
                d.reason.as_deref().unwrap_or("MuJoCo did not run")
            )
        });
    sections
        .into_iter()
        .filter(|(_, status, _, _)| **status == Status::Unknown)
        .map(|(name, _, reason, fallback)| {
            format!("{name}: {}", reason.as_deref().unwrap_or(fallback))
        })
        .chain(deep)
        .collect()
}

fn messages<'a>(
    findings: impl IntoIterator<Item = &'a Finding>,
    severities: &[Severity],
) -> Vec<String> {
    findings
        .into_iter()
        .filter(|f| severities.contains(&f.severity()))
        .map(|f| f.message.clone())
        .collect()
}

/// The report of a finding, not yet positioned.
pub(super) fn finding_report(finding: &Finding) -> FindingReport {
    FindingReport {
        rule: finding.rule.code.to_string(),
        name: finding.rule.name.to_string(),
        severity: finding.severity(),
        section: finding.section,
        message: finding.message.clone(),
        file: None,
        line: None,
        column: None,
        end_line: None,
        end_column: None,
        help: finding.help.clone(),
        element: None,
        expanded_from: Vec::new(),
        fix: None,
    }
}

/// `fix` as edits of the files the user edits (none, with the reason, when one of them cannot be made).
fn fix_report(fix: &Fix, loaded: &Loaded) -> FixReport {
    let mut notes: Vec<String> = Vec::new();
    let edits: Result<Vec<FileEdit>, String> = fix
        .edits
        .iter()
        .map(|edit| {
            let target = loaded.edit_target(edit.anchor(), edit.is_textual(), fix.mjcf)?;
            let text_edit = edit
                .resolve(target.text(), target.span)
                .ok_or("the text there is not the attribute the fix expects")?;
            notes.extend(target.note.clone());
            let (line, column) = target.line_col(text_edit.start);
            let (end_line, end_column) = target.line_col(text_edit.end);
            Ok(FileEdit {
                file: target.path().display().to_string(),
                line,
                column,
                end_line,
                end_column,
                edit: text_edit,
            })
        })
        .collect();
    let (edits, not_applicable) = match edits {
        Ok(edits) => (edits, None),
        Err(why) => (Vec::new(), Some(why)),
    };
    notes.dedup();
    let description = std::iter::once(fix.description.clone())
        .chain(notes)
        .collect::<Vec<_>>()
        .join("; ");
    FixReport {
        applicability: fix.applicability,
        description,
        edits,
        not_applicable,
    }
}
