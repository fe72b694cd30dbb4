//! The page's text: the verdict hero, the summary cards, the findings table and the source snippets.

use std::fmt::Write;

use super::{deep, display_name, escape, pill, shorten, status_class};
use crate::diagnostics::finding::Severity;
use crate::diagnostics::fix::Applicability;
use crate::report::{Confidence, FindingReport, FixReport, Report, Status};
use crate::Validation;

/// Source snippets beyond this many findings are left out (their rows show the position as text).
const MAX_SNIPPETS: usize = 1000;

/// Context lines shown above and below a finding's line.
const SNIPPET_CONTEXT: u32 = 2;

/// Characters of one source line shown in a snippet.
const SNIPPET_WIDTH: usize = 240;

/// The CSS class of a severity (`critical`, `fail`, `warn`, `info`).
pub(super) fn severity_class(severity: Severity) -> &'static str {
    match severity {
        Severity::Critical => "critical",
        Severity::Fail => "fail",
        Severity::Warn => "warn",
        Severity::Info => "info",
    }
}

pub(super) fn hero(out: &mut String, report: &Report) {
    let status = report.overall_status;
    let icon = match status {
        Status::Pass => "✓",
        Status::Warn => "!",
        Status::Fail => "✕",
        Status::Unknown => "?",
        Status::NotApplicable => "–",
    };
    let kind = report.robot_type.map_or("unknown", |t| t.as_str());
    let kind_confidence = report
        .robot_type_confidence
        .map_or("estimated", Confidence::label);
    let _ = write!(
        out,
        "<header class=\"hero {cls}\">\n<div class=\"badge {cls}\" aria-label=\"overall status\"><span class=\"icon\">{icon}</span><span>{label}</span></div>\n\
         <div class=\"who\"><p class=\"eyebrow\">urdf_validate report</p><h1>{name}</h1><p class=\"path\" title=\"{path}\">{path}</p></div>\n\
         <dl class=\"meta\">\
         <div><dt>Robot type</dt><dd>{kind} <span class=\"muted\">({kind_confidence})</span></dd></div>\
         <div><dt>Physics data</dt><dd>{confidence} confidence</dd></div>\
         <div><dt>Validator</dt><dd>{version}</dd></div>\
         <div><dt>Generated</dt><dd>{time}</dd></div>\
         </dl>\n",
        cls = status_class(status),
        label = status.label(),
        name = escape(&display_name(report)),
        path = escape(&report.urdf_path),
        kind = escape(kind),
        confidence = report.confidence_level.label(),
        version = escape(&report.validator_version),
        time = escape(&report.timestamp),
    );
    if let (Some(detected), Some(declared)) = (report.robot_type_detected, report.robot_type) {
        if detected != declared {
            let _ = writeln!(
                out,
                "<p class=\"note\">Declared as <b>{}</b>; the structure looks <b>{}</b>{}.</p>",
                escape(declared.as_str()),
                escape(detected.as_str()),
                report
                    .robot_type_evidence
                    .as_deref()
                    .map_or(String::new(), |e| format!(" ({})", escape(e)))
            );
        }
    }
    out.push_str("</header>\n");
}

pub(super) fn summary_cards(out: &mut String, report: &Report) {
    out.push_str("<section class=\"cards\" aria-label=\"summary\">\n");
    let counts = |severity: Severity| {
        report
            .findings
            .iter()
            .filter(|f| f.severity == severity)
            .count()
    };
    let schema = &report.schema;
    let p = &report.physics;
    card(
        out,
        "Structure",
        "#findings",
        schema.status,
        &format!("{} links · {} findings", p.links, report.findings.len()),
        &format!(
            "{} critical · {} fail · {} warn · {} info",
            counts(Severity::Critical),
            counts(Severity::Fail),
            counts(Severity::Warn),
            counts(Severity::Info)
        ),
    );
    if let Some(statics) = &report.statics {
        let main = statics
            .total_mass
            .map_or("mass unknown".to_string(), |mass| format!("{mass:.1} kg"));
        let mut detail = statics
            .com_height_above_ground
            .map_or(String::new(), |h| format!("COM {h:.2} m up · "));
        detail.push_str(&statics.weakest_joint_name.as_deref().map_or_else(
            || format!("pose {}", statics.pose),
            |w| format!("weakest: {w}"),
        ));
        card(out, "Statics", "#statics", statics.status, &main, &detail);
    }
    if let Some(stability) = &report.stability {
        let main = match (stability.margin_mm, &stability.tip_direction) {
            (Some(m), Some(d)) => format!("margin {m:.1} mm ({d})"),
            (Some(m), None) => format!("margin {m:.1} mm"),
            _ => stability
                .reason
                .as_deref()
                .map_or("not assessed".to_string(), |r| shorten(r, 60)),
        };
        let detail = match (
            stability.tipping_angle_deg,
            &stability.com_height_ratio_class,
        ) {
            (Some(a), Some(c)) => format!("tips at {a:.1}° · {c}"),
            (Some(a), None) => format!("tips at {a:.1}°"),
            _ => format!("{} contact links", stability.contact_links.len()),
        };
        card(
            out,
            "Stability",
            "#stability",
            stability.status,
            &main,
            &detail,
        );
    }
    if let Some(workspace) = &report.workspace {
        let main = workspace.max_reach.map_or_else(
            || {
                workspace
                    .reason
                    .as_deref()
                    .map_or("no arm".to_string(), |r| shorten(r, 60))
            },
            |r| format!("reach {r:.3} m"),
        );
        let detail = format!(
            "{} arm{} · {} samples each",
            workspace.arms.len(),
            if workspace.arms.len() == 1 { "" } else { "s" },
            workspace.samples
        );
        card(
            out,
            "Workspace",
            "#workspace",
            workspace.status,
            &main,
            &detail,
        );
    }
    if let Some(section) = &report.deep {
        deep::deep_card(out, section);
    }
    out.push_str("</section>\n");
}

pub(super) fn card(
    out: &mut String,
    title: &str,
    href: &str,
    status: Status,
    main: &str,
    detail: &str,
) {
    let _ = writeln!(
        out,
        "<a class=\"card {}\" href=\"{href}\"><span class=\"card-title\">{title}</span>{}<span class=\"card-main\">{}</span><span class=\"card-detail\">{}</span></a>",
        status_class(status),
        pill(status),
        escape(main),
        escape(detail)
    );
}

/// Indices of the findings, worst first (stable: the report's order within a severity).
pub(super) fn findings_order(findings: &[FindingReport]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..findings.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(findings[i].severity));
    order
}

/// The findings that get a snippet: positioned, in a known source, among the first [`MAX_SNIPPETS`].
fn has_snippet(validation: &Validation, finding: &FindingReport, rank: usize) -> bool {
    rank < MAX_SNIPPETS
        && matches!((&finding.file, finding.line), (Some(file), Some(_)) if source_lines(validation, file).is_some())
}

fn source_lines<'a>(validation: &'a Validation, file: &str) -> Option<&'a str> {
    validation
        .sources
        .iter()
        .find(|s| s.path().display().to_string() == file)
        .map(|s| s.text())
}

/// A finding's fix under its message: what it does and the flags that apply it, or why it cannot be made.
fn fix_note(fix: &FixReport) -> String {
    let how = match (&fix.not_applicable, fix.applicability) {
        (Some(why), _) => format!("no automatic fix here: {}", escape(why)),
        (None, Applicability::Safe) => "<code>--fix</code>".to_string(),
        (None, Applicability::Unsafe) => "<code>--fix --unsafe-fixes</code>".to_string(),
    };
    let class = match fix.applicability {
        Applicability::Safe => "safe",
        Applicability::Unsafe => "unsafe",
    };
    format!(
        "<div class=\"fix {class}\">[*] fix: {} ({how})</div>",
        escape(&fix.description)
    )
}

pub(super) fn findings_table(out: &mut String, validation: &Validation, order: &[usize]) {
    let report = &validation.report;
    out.push_str("<section id=\"findings\" class=\"panel\">\n<h2>Findings</h2>\n");
    if report.findings.is_empty() {
        out.push_str("<p class=\"empty\">No findings: nothing to report.</p>\n</section>\n");
        return;
    }
    // Filters: checkboxes styled as chips; CSS hides the rows of an unchecked severity (no script).
    out.push_str("<div class=\"filters\" role=\"group\" aria-label=\"show severities\">");
    for severity in [
        Severity::Critical,
        Severity::Fail,
        Severity::Warn,
        Severity::Info,
    ] {
        let count = report
            .findings
            .iter()
            .filter(|f| f.severity == severity)
            .count();
        if count == 0 {
            continue;
        }
        let cls = severity_class(severity);
        let _ = write!(
            out,
            "<input type=\"checkbox\" id=\"show-{cls}\" checked><label for=\"show-{cls}\" class=\"chip {cls}\">{} <b>{count}</b></label>",
            severity.label()
        );
    }
    out.push_str("</div>\n<div class=\"table-wrap\"><table class=\"findings\">\n<thead><tr><th>Severity</th><th>Rule</th><th>Section</th><th>Message</th><th>Location</th></tr></thead>\n<tbody>\n");
    for (rank, &i) in order.iter().enumerate() {
        let Some(f) = report.findings.get(i) else {
            continue;
        };
        let cls = severity_class(f.severity);
        let location = match (&f.file, f.line, f.column) {
            (Some(file), Some(line), column) => {
                let short = std::path::Path::new(file)
                    .file_name()
                    .map_or(file.clone(), |n| n.to_string_lossy().into_owned());
                let col = column.map_or(String::new(), |c| format!(":{c}"));
                let text = format!("{}:{line}{col}", escape(&short));
                if has_snippet(validation, f, rank) {
                    format!("<a href=\"#src-{i}\" title=\"{}\">{text}</a>", escape(file))
                } else {
                    format!("<span title=\"{}\">{text}</span>", escape(file))
                }
            }
            _ => "<span class=\"muted\">—</span>".to_string(),
        };
        let help = f.help.as_deref().map_or(String::new(), |h| {
            format!("<div class=\"help\">{}</div>", escape(h))
        });
        let fix = f.fix.as_ref().map_or(String::new(), fix_note);
        let _ = writeln!(
            out,
            "<tr id=\"finding-{i}\" class=\"sev-{cls}\"><td><span class=\"sev {cls}\">{}</span></td><td class=\"rule\"><code>{}</code><span>{}</span></td><td>{}</td><td class=\"msg\">{}{help}{fix}</td><td class=\"loc\">{location}</td></tr>",
            f.severity.label(),
            escape(&f.rule),
            escape(&f.name),
            f.section.as_str(),
            escape(&f.message),
        );
    }
    out.push_str("</tbody></table></div>\n</section>\n");
}

pub(super) fn snippets(out: &mut String, validation: &Validation, order: &[usize]) {
    let report = &validation.report;
    let shown: Vec<(usize, &FindingReport)> = order
        .iter()
        .enumerate()
        .filter_map(|(rank, &i)| {
            let f = report.findings.get(i)?;
            has_snippet(validation, f, rank).then_some((i, f))
        })
        .collect();
    if shown.is_empty() {
        return;
    }
    out.push_str("<section id=\"sources\" class=\"panel\">\n<h2>Source</h2>\n");
    let positioned = report.findings.iter().filter(|f| f.line.is_some()).count();
    if positioned > shown.len() {
        let _ = writeln!(
            out,
            "<p class=\"muted\">Snippets of the first {} positioned findings (worst first).</p>",
            shown.len()
        );
    }
    // Lines per source file, counted once.
    let mut line_counts: Vec<(&str, u32)> = Vec::new();
    for (i, f) in shown {
        let (Some(file), Some(line)) = (&f.file, f.line) else {
            continue;
        };
        let total = match line_counts.iter().find(|(name, _)| *name == file.as_str()) {
            Some(&(_, total)) => total,
            None => {
                let Some(text) = source_lines(validation, file) else {
                    continue;
                };
                let total = u32::try_from(text.lines().count()).unwrap_or(u32::MAX);
                line_counts.push((file.as_str(), total));
                total
            }
        };
        let cls = severity_class(f.severity);
        let _ = write!(
            out,
            "<figure class=\"snippet\" id=\"src-{i}\">\n<figcaption><span class=\"sev {cls}\">{}</span> <code>{}</code> {} <span class=\"path\">{}:{line}:{}</span> <a class=\"back\" href=\"#finding-{i}\">↑ finding</a></figcaption>\n<pre class=\"code\">",
            f.severity.label(),
            escape(&f.rule),
            escape(&shorten(&f.message, 200)),
            escape(file),
            f.column.unwrap_or(1),
        );
        let first = line.saturating_sub(SNIPPET_CONTEXT).max(1);
        let last = line.saturating_add(SNIPPET_CONTEXT).min(total);
        let width = last.to_string().len();
        for number in first..=last {
            let source = validation.source_line(file, number).unwrap_or("");
            let flagged = number == line;
            let mark = flagged.then(|| {
                let start = f.column.unwrap_or(1).saturating_sub(1) as usize;
                let end = match (f.end_line, f.end_column) {
                    (Some(end_line), Some(end_column)) if end_line == line => {
                        (end_column as usize).saturating_sub(1)
                    }
                    _ => source.chars().count(),
                };
                (start, end.max(start + 1))
            });
            let _ = write!(
                out,
                "<span class=\"line{}\"><span class=\"ln\">{number:>width$}</span>{}</span>",
                if flagged { " hl" } else { "" },
                code_line(source, mark)
            );
        }
        out.push_str("</pre>\n");
        for frame in &f.expanded_from {
            let _ = writeln!(out, "<p class=\"snote\">note: {}</p>", escape(frame));
        }
        if let Some(help) = &f.help {
            let _ = writeln!(out, "<p class=\"snote help\">help: {}</p>", escape(help));
        }
        out.push_str("</figure>\n");
    }
    out.push_str("</section>\n");
}

/// One source line, escaped, windowed to [`SNIPPET_WIDTH`] characters around the mark, the marked
/// characters (`[start, end)`, 0-based) in `<mark>`.
fn code_line(source: &str, mark: Option<(usize, usize)>) -> String {
    let chars: Vec<char> = source.chars().collect();
    let begin = match mark {
        Some((start, _)) if start > SNIPPET_WIDTH / 2 => start - SNIPPET_WIDTH / 4,
        _ => 0,
    }
    .min(chars.len());
    let end = (begin + SNIPPET_WIDTH).min(chars.len());
    let piece = |a: usize, b: usize| -> String {
        let (a, b) = (a.clamp(begin, end), b.clamp(begin, end));
        escape(&chars[a..b.max(a)].iter().collect::<String>())
    };
    let mut out = String::new();
    if begin > 0 {
        out.push('…');
    }
    match mark {
        Some((start, stop)) if start < chars.len() => {
            out.push_str(&piece(begin, start));
            out.push_str("<mark>");
            out.push_str(&piece(start, stop));
            out.push_str("</mark>");
            out.push_str(&piece(stop, end));
        }
        _ => out.push_str(&piece(begin, end)),
    }
    if end < chars.len() {
        out.push('…');
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    #[test]
    fn code_lines_mark_the_flagged_text_and_window_long_lines() {
        assert_eq!(
            code_line("<link name=\"a\">", Some((6, 14))),
            "&lt;link <mark>name=&quot;a&quot;</mark>&gt;"
        );
        assert_eq!(code_line("abc", None), "abc");
        // A mark past the end of the line marks nothing and does not panic.
        assert_eq!(code_line("abc", Some((10, 12))), "abc");
        let long = format!("{}<x/>{}", "a".repeat(1000), "b".repeat(1000));
        let line = code_line(&long, Some((1000, 1004)));
        assert!(line.starts_with('…') && line.ends_with('…'));
        assert!(line.contains("<mark>&lt;x/&gt;</mark>"));
        assert!(line.chars().count() < SNIPPET_WIDTH + 40);
    }
}
