//! GitHub Actions: one workflow command per finding (`::error file=…,line=…::message`), which GitHub shows
//! as an annotation on the line, and a Markdown summary for `$GITHUB_STEP_SUMMARY`.
//!
//! Severities: `::error` for CRITICAL and FAIL, `::warning` for WARN, `::notice` for INFO. Values are
//! escaped as the Actions toolkit does: `%`, `\r` and `\n` in the message; also `:` and `,` in properties.

use std::fmt::Write;

use crate::diagnostics::finding::Severity;
use crate::render::location::{DisplayPath, Place};
use crate::render::{FormatOptions, Unreported};
use crate::report::{FindingReport, Report, Status};
use crate::Validation;

/// How many findings of each robot the step summary lists.
const TOP_FINDINGS: usize = 5;

/// The workflow command of a severity.
pub fn command(severity: Severity) -> &'static str {
    match severity {
        Severity::Critical | Severity::Fail => "error",
        Severity::Warn => "warning",
        Severity::Info => "notice",
    }
}

/// A workflow-command message, escaped (`%`, `\r`, `\n`).
pub fn escape_data(text: &str) -> String {
    text.replace('%', "%25")
        .replace('\r', "%0D")
        .replace('\n', "%0A")
}

/// A workflow-command property value, escaped (`%`, `\r`, `\n`, `:`, `,`).
pub fn escape_property(text: &str) -> String {
    escape_data(text).replace(':', "%3A").replace(',', "%2C")
}

/// One annotation line per finding of every validation, and one `::error` per input that gave no report.
pub fn render_github(
    validations: &[&Validation],
    unreported: &[Unreported],
    options: &FormatOptions,
) -> String {
    let base = options.base_dir.as_deref();
    let mut out = String::new();
    for validation in validations {
        let report = &validation.report;
        for finding in &report.findings {
            let place = Place::of(finding, &report.urdf_path);
            let mut properties = vec![format!(
                "file={}",
                escape_property(DisplayPath::new(place.file, base).as_str())
            )];
            if let Some((line, column, end_line, end_column)) = place.region {
                properties.push(format!("line={line}"));
                properties.push(format!("col={column}"));
                properties.push(format!("endLine={end_line}"));
                properties.push(format!("endColumn={end_column}"));
            }
            properties.push(format!(
                "title={}",
                escape_property(&format!("{} {}", finding.rule, finding.name))
            ));
            let mut message = finding.message.clone();
            if let Some(help) = &finding.help {
                message.push_str("\nhelp: ");
                message.push_str(help);
            }
            let _ = writeln!(
                out,
                "::{} {}::{}",
                command(finding.severity),
                properties.join(","),
                escape_data(&message)
            );
        }
    }
    for input in unreported {
        let file = if input.file.is_empty() {
            String::new()
        } else {
            format!(
                "file={},",
                escape_property(DisplayPath::new(&input.file, base).as_str())
            )
        };
        let _ = writeln!(
            out,
            "::error {file}title=urdf_validate::{}",
            escape_data(&input.error)
        );
    }
    out
}

/// The Markdown summary of a run: a table with each robot's verdict and counts, then each robot's worst
/// findings.
pub fn render_step_summary(
    validations: &[&Validation],
    unreported: &[Unreported],
    options: &FormatOptions,
) -> String {
    let base = options.base_dir.as_deref();
    let mut out = String::from("## urdf_validate\n\n");
    out.push_str("| Robot | File | Verdict | CRITICAL | FAIL | WARN | INFO |\n");
    out.push_str("|---|---|---|---:|---:|---:|---:|\n");
    for validation in validations {
        let report = &validation.report;
        let count = |s: Severity| report.findings.iter().filter(|f| f.severity == s).count();
        let _ = writeln!(
            out,
            "| {} | `{}` | {} | {} | {} | {} | {} |",
            cell(&report.robot_name),
            cell(DisplayPath::new(&report.urdf_path, base).as_str()),
            verdict(report.overall_status),
            count(Severity::Critical),
            count(Severity::Fail),
            count(Severity::Warn),
            count(Severity::Info),
        );
    }
    for input in unreported {
        let file = if input.file.is_empty() {
            String::new()
        } else {
            format!("`{}`", cell(DisplayPath::new(&input.file, base).as_str()))
        };
        let _ = writeln!(
            out,
            "| — | {file} | ❌ ERROR: {} | | | | |",
            cell(&input.error)
        );
    }
    for validation in validations {
        top_findings(&mut out, &validation.report, base);
    }
    out
}

fn top_findings(out: &mut String, report: &Report, base: Option<&std::path::Path>) {
    let mut worst: Vec<&FindingReport> = report
        .findings
        .iter()
        .filter(|f| f.severity > Severity::Info)
        .collect();
    if worst.is_empty() {
        return;
    }
    // Worst first; findings of one severity keep the report's order.
    worst.sort_by_key(|f| std::cmp::Reverse(f.severity));
    let name = if report.robot_name.is_empty() {
        DisplayPath::new(&report.urdf_path, base)
            .as_str()
            .to_string()
    } else {
        report.robot_name.clone()
    };
    let _ = writeln!(out, "\n### {} — top findings\n", cell(&name));
    out.push_str("| Severity | Rule | Where | Message |\n|---|---|---|---|\n");
    for finding in worst.iter().take(TOP_FINDINGS) {
        let _ = writeln!(
            out,
            "| {} | {} `{}` | `{}` | {} |",
            finding.severity.label(),
            finding.rule,
            finding.name,
            cell(&Place::of(finding, &report.urdf_path).label(base)),
            cell(&finding.message)
        );
    }
    if worst.len() > TOP_FINDINGS {
        let _ = writeln!(
            out,
            "\n{} more CRITICAL/FAIL/WARN findings in the report.",
            worst.len() - TOP_FINDINGS
        );
    }
}

fn verdict(status: Status) -> String {
    let mark = match status {
        Status::Pass | Status::NotApplicable => "✅",
        Status::Warn => "⚠️",
        Status::Fail | Status::Unknown => "❌",
    };
    format!("{mark} {}", status.label())
}

/// Text for a Markdown table cell: pipes escaped, line breaks as spaces, no backticks breaking code spans.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
        .replace(['\r', '\n'], " ")
        .replace('`', "'")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_follow_the_actions_toolkit() {
        assert_eq!(escape_data("50% a\r\nb: c, d"), "50%25 a%0D%0Ab: c, d");
        assert_eq!(escape_property("C:/x,y%\n"), "C%3A/x%2Cy%25%0A");
    }

    #[test]
    fn commands_follow_severities() {
        assert_eq!(command(Severity::Critical), "error");
        assert_eq!(command(Severity::Fail), "error");
        assert_eq!(command(Severity::Warn), "warning");
        assert_eq!(command(Severity::Info), "notice");
    }

    #[test]
    fn table_cells_cannot_break_the_table() {
        assert_eq!(cell("a|b\nc`d`"), "a\\|b c'd'");
    }
}
