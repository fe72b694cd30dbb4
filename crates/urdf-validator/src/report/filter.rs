//! Applying the [`Settings`] and the inline suppression comments to the positioned findings: severity
//! overrides, `select`/`ignore`/`per-file-ignores`, `<!-- urdf-validate: ignore ... -->`; then the
//! findings about the suppressions themselves (unused: U801, unknown codes: U802).
//!
//! What is suppressed leaves the verdict and the exit code; it is kept (as [`SuppressedFinding`]s) only
//! when [`Settings::show_suppressed`] asks for it.

use std::path::Path;

use schemars::JsonSchema;
use serde::Serialize;

use crate::diagnostics::inline::{self, InlineSuppression};
use crate::diagnostics::settings::{self, Origin, Selector, Suppression};
use crate::diagnostics::{rules, Finding, Settings};
use crate::report::FindingReport;

/// A finding that does not count: suppressed by the configuration or an inline comment.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct SuppressedFinding {
    /// The finding, as it would have been reported.
    #[serde(flatten)]
    pub finding: FindingReport,
    /// What suppressed it: `ignore (urdf-validate.toml:3)`, `not in select (command line)`,
    /// `per-file-ignores "legacy/*.urdf" (pyproject.toml:12)`, `urdf-validate: ignore comment (robot.urdf:40)`.
    pub suppressed_by: String,
}

/// The findings that count, and those suppressed (empty unless `show_suppressed`).
pub struct Filtered {
    /// Findings that count, with their positioned reports.
    pub kept: Vec<(Finding, FindingReport)>,
    /// Suppressed findings (only when the settings keep them).
    pub suppressed: Vec<SuppressedFinding>,
}

/// One comment of one file, and which of its codes suppressed something.
struct Comment {
    file: String,
    entry_file: bool,
    parsed: InlineSuppression,
    used: Vec<bool>,
}

/// Apply `settings` and the suppression comments of `sources` (path as findings name it, text; the entry
/// file first) to the findings of the robot read from `input`.
pub fn apply(
    findings: Vec<(Finding, FindingReport)>,
    settings: &Settings,
    input: &Path,
    sources: &[(String, &str)],
) -> Filtered {
    let mut comments: Vec<Comment> = if settings.no_inline {
        Vec::new()
    } else {
        sources
            .iter()
            .enumerate()
            .flat_map(|(index, (file, text))| {
                inline::parse(text).into_iter().map(move |parsed| Comment {
                    file: file.clone(),
                    entry_file: index == 0,
                    used: vec![false; parsed.codes.len()],
                    parsed,
                })
            })
            .collect()
    };
    let mut kept = Vec::new();
    let mut suppressed = Vec::new();
    let mut suppress = |finding: FindingReport, why: Suppression| {
        if settings.show_suppressed {
            suppressed.push(SuppressedFinding {
                finding,
                suppressed_by: why.to_string(),
            });
        }
    };
    for (finding, report) in findings {
        let (finding, report) = with_severity(finding, report, settings);
        if let Some(why) = settings.suppression_for(finding.rule, input) {
            suppress(report, why);
        } else if let Some(why) = suppress_inline(&mut comments, &finding, &report) {
            suppress(report, why);
        } else {
            kept.push((finding, report));
        }
    }
    // Findings about the settings and the comments: filtered by the configuration, not by comments.
    let mut own = unknown_selector_findings(settings);
    own.extend(comment_findings(&comments, settings, input));
    for (finding, report) in own {
        let (finding, report) = with_severity(finding, report, settings);
        match settings.suppression_for(finding.rule, input) {
            Some(why) => suppress(report, why),
            None => kept.push((finding, report)),
        }
    }
    Filtered { kept, suppressed }
}

/// The finding with its severity as the settings say.
fn with_severity(
    mut finding: Finding,
    mut report: FindingReport,
    settings: &Settings,
) -> (Finding, FindingReport) {
    let severity = settings.severity_of(finding.rule);
    if severity != finding.rule.severity {
        finding.severity_override = Some(severity);
    }
    report.severity = finding.severity();
    (finding, report)
}

/// The first comment covering the finding (marked used), as a suppression.
fn suppress_inline(
    comments: &mut [Comment],
    finding: &Finding,
    report: &FindingReport,
) -> Option<Suppression> {
    for comment in comments.iter_mut() {
        let same_file = report.file.as_deref() == Some(comment.file.as_str());
        let covers = if comment.parsed.whole_file {
            // `ignore-file` in the file given covers the whole robot; in an included xacro, that file.
            same_file || comment.entry_file
        } else {
            same_file
                && report.line.is_some_and(|line| {
                    (comment.parsed.lines.0..=comment.parsed.lines.1).contains(&line)
                })
        };
        if !covers {
            continue;
        }
        let hit = comment
            .parsed
            .codes
            .iter()
            .position(|(code, _)| settings::selector_matches(code, finding.rule));
        if let Some(index) = hit {
            if let Some(used) = comment.used.get_mut(index) {
                *used = true;
            }
            return Some(Suppression::Comment {
                file: comment.file.clone(),
                line: comment.parsed.line,
                whole_file: comment.parsed.whole_file,
            });
        }
    }
    None
}

/// U802 for every selector of the settings that names no rule, at its place in the configuration.
fn unknown_selector_findings(settings: &Settings) -> Vec<(Finding, FindingReport)> {
    settings
        .unknown_selectors()
        .into_iter()
        .map(|selector| {
            let finding = Finding::new(
                &rules::UNKNOWN_RULE_CODE,
                None,
                format!(
                    "'{}' ({}) names no rule, so this setting does nothing",
                    selector.text,
                    describe_origin(selector)
                ),
            )
            .with_help(settings::suggest_rule(&selector.text));
            let mut report = super::build::finding_report(&finding);
            if let Origin::File { path, line, column } = &selector.origin {
                report.file = Some(path.display().to_string());
                report.line = Some(*line);
                report.column = Some(*column);
                report.end_line = Some(*line);
                report.end_column =
                    Some(column.saturating_add(u32::try_from(selector.text.len()).unwrap_or(0)));
            }
            (finding, report)
        })
        .collect()
}

fn describe_origin(selector: &Selector) -> String {
    match &selector.origin {
        Origin::CommandLine => "on the command line".to_string(),
        other => format!("in {other}"),
    }
}

/// U801 for the codes of a comment that suppressed nothing, U802 for those that name no rule.
fn comment_findings(
    comments: &[Comment],
    settings: &Settings,
    input: &Path,
) -> Vec<(Finding, FindingReport)> {
    let mut out = Vec::new();
    for comment in comments {
        let at = |column: u32, width: usize, finding: Finding| {
            let mut report = super::build::finding_report(&finding);
            report.file = Some(comment.file.clone());
            report.line = Some(comment.parsed.line);
            report.column = Some(column);
            report.end_line = Some(comment.parsed.line);
            report.end_column = Some(column.saturating_add(u32::try_from(width).unwrap_or(0)));
            (finding, report)
        };
        if let Some(directive) = &comment.parsed.malformed {
            let finding = Finding::new(
                &rules::UNKNOWN_RULE_CODE,
                None,
                format!("'urdf-validate: {directive}' is not a suppression: nothing is suppressed"),
            )
            .with_help("write `<!-- urdf-validate: ignore CODE -->` or `<!-- urdf-validate: ignore-file CODE -->`");
            out.push(at(comment.parsed.column, 4, finding));
            continue;
        }
        if comment.parsed.codes.is_empty() {
            let finding = Finding::new(
                &rules::UNKNOWN_RULE_CODE,
                None,
                "this suppression comment names no rule: nothing is suppressed",
            )
            .with_help("name the codes to suppress: `<!-- urdf-validate: ignore U201 -->`");
            out.push(at(comment.parsed.column, 4, finding));
            continue;
        }
        let mut unused = Vec::new();
        for ((code, column), used) in comment.parsed.codes.iter().zip(&comment.used) {
            let matching: Vec<&rules::Rule> = rules::ALL
                .iter()
                .copied()
                .filter(|rule| settings::selector_matches(code, rule))
                .collect();
            if matching.is_empty() {
                let finding = Finding::new(
                    &rules::UNKNOWN_RULE_CODE,
                    None,
                    format!("'{code}' in this suppression comment names no rule"),
                )
                .with_help(settings::suggest_rule(code));
                out.push(at(*column, code.len(), finding));
            } else if !used {
                let disabled = matching
                    .iter()
                    .all(|rule| settings.suppression_for(rule, input).is_some());
                unused.push((code, *column, disabled));
            }
        }
        if let Some(&(_, column, _)) = unused.first() {
            let names: Vec<String> = unused.iter().map(|(c, _, _)| format!("'{c}'")).collect();
            let disabled: Vec<String> = unused
                .iter()
                .filter(|(_, _, d)| *d)
                .map(|(c, _, _)| format!("'{c}'"))
                .collect();
            let place = if comment.parsed.whole_file {
                "in this file".to_string()
            } else if comment.parsed.lines.0 == comment.parsed.lines.1 {
                format!("on line {}", comment.parsed.lines.0)
            } else {
                format!(
                    "on lines {}-{}",
                    comment.parsed.lines.0, comment.parsed.lines.1
                )
            };
            let mut message = format!(
                "unused suppression: {} suppresses no finding {place}",
                names.join(", ")
            );
            if !disabled.is_empty() {
                message.push_str(&format!(
                    " ({} not enabled by the configuration)",
                    disabled.join(", ")
                ));
            }
            let width = unused.last().map_or(4, |(c, col, _)| {
                (col.saturating_sub(column) as usize) + c.len()
            });
            let finding = Finding::new(&rules::UNUSED_SUPPRESSION, None, message).with_help(
                "remove the code from the comment; an `ignore` comment covers its own line when it follows an element, else the start tag of the next element",
            );
            out.push(at(column, width, finding));
        }
    }
    out
}
