//! Terminal view of a report: the spec's boxed layout, findings with rustc-style source snippets, similar
//! notices grouped. Output carries ANSI styles; the caller's stream strips them when colour is off.

use std::collections::BTreeMap;
use std::fmt::Write;

use anstyle::{AnsiColor, Style};

use crate::diagnostics::finding::{Section, Severity};
use crate::diagnostics::fix::Applicability;
use crate::report::{
    ArmWorkspace, Confidence, DeepSection, FindingReport, JointStatics, Report, StabilitySection,
    StaticsSection, Status, Timings, WorkspaceSection,
};
use crate::Validation;

/// How much to show.
#[derive(Clone, Debug, Default)]
pub struct TextOptions {
    /// List every finding, with a snippet for each CRITICAL and WARN.
    pub verbose: bool,
    /// Print the per-arm workspace table.
    pub detailed: bool,
    /// Where the JSON report was written, for the closing line.
    pub report_path: Option<String>,
}

/// Findings of one rule beyond this many are grouped into one line (unless verbose).
const LIST_LIMIT_INFO: usize = 4;
/// CRITICAL/WARN findings of one rule shown with a snippet before the rest are grouped (unless verbose).
const LIST_LIMIT_PROBLEMS: usize = 12;

const BOLD: Style = Style::new().bold();
const DIM: Style = Style::new().dimmed();
const GREEN: Style = AnsiColor::Green.on_default().bold();
const YELLOW: Style = AnsiColor::Yellow.on_default().bold();
const RED: Style = AnsiColor::Red.on_default().bold();
const BLUE: Style = AnsiColor::Blue.on_default().bold();
const CYAN: Style = AnsiColor::Cyan.on_default();

fn paint(style: Style, text: &str) -> String {
    format!("{style}{text}{style:#}")
}

fn status_style(status: Status) -> Style {
    match status {
        Status::Pass => GREEN,
        Status::Warn => YELLOW,
        Status::Fail | Status::Unknown => RED,
        Status::NotApplicable => DIM,
    }
}

fn severity_style(severity: Severity) -> Style {
    match severity {
        Severity::Critical | Severity::Fail => RED,
        Severity::Warn => YELLOW,
        Severity::Info => BLUE,
    }
}

/// The full text of one validation.
pub fn render_text(validation: &Validation, options: &TextOptions) -> String {
    let report = &validation.report;
    let mut out = String::new();
    header(&mut out, report);
    schema_section(&mut out, validation, options);
    physics_line(&mut out, report);
    findings_block(&mut out, validation, options, &[Section::Symmetry]);
    if let Some(statics) = &report.statics {
        statics_section(&mut out, statics, options.verbose);
    }
    findings_block(&mut out, validation, options, &[Section::Statics]);
    if let Some(stability) = &report.stability {
        stability_section(&mut out, report, stability);
    }
    findings_block(&mut out, validation, options, &[Section::Stability]);
    if let Some(workspace) = &report.workspace {
        workspace_section(&mut out, workspace, options.detailed);
    }
    findings_block(&mut out, validation, options, &[Section::Workspace]);
    if let Some(deep) = &report.deep {
        deep_section(&mut out, deep);
        findings_block(&mut out, validation, options, &[Section::Deep]);
    }
    suppressed_block(&mut out, report);
    baseline_line(&mut out, report);
    overrides_line(&mut out, report);
    fixable_line(&mut out, report);
    let overall = report.overall_status;
    let _ = writeln!(
        out,
        "{}  {}  confidence: {}",
        paint(BOLD, "[OVERALL]"),
        paint(status_style(overall), overall.label()),
        report.confidence_level.label()
    );
    if let Some(path) = &options.report_path {
        let _ = writeln!(out, "Full report: {path}");
    }
    if let Some(timings) = &report.timings_ms {
        timings_line(&mut out, timings);
    }
    out
}

/// `Timings: 12.3 ms = load 0.1 + parse 1.2 + …` (phases below 0.05 ms are left out).
fn timings_line(out: &mut String, timings: &Timings) {
    let phases: Vec<String> = timings
        .phases()
        .iter()
        .filter(|(_, ms)| *ms >= 0.05)
        .map(|(phase, ms)| format!("{phase} {ms:.1}"))
        .collect();
    let _ = writeln!(
        out,
        "{}  {:.1} ms = {}",
        paint(BOLD, "[TIMINGS]"),
        timings.total_ms(),
        phases.join(" + ")
    );
}

fn header(out: &mut String, report: &Report) {
    let name = std::path::Path::new(&report.urdf_path)
        .file_name()
        .map_or(report.urdf_path.clone(), |n| {
            n.to_string_lossy().into_owned()
        });
    let title = format!("  urdf_validate — {name}");
    let width = title.chars().count().max(52) + 2;
    let _ = writeln!(out, "╔{}╗", "═".repeat(width));
    let _ = writeln!(
        out,
        "║{title}{}║",
        " ".repeat(width - title.chars().count())
    );
    let _ = writeln!(out, "╚{}╝", "═".repeat(width));
}

fn schema_section(out: &mut String, validation: &Validation, options: &TextOptions) {
    let report = &validation.report;
    let schema = &report.schema;
    let problems = schema.critical_issues.len() + schema.warnings.len();
    let total = problems + schema.infos.len();
    let verdict = match schema.status {
        Status::Pass if schema.infos.is_empty() => paint(GREEN, "✓ PASS"),
        Status::Pass => format!("{} ({} infos)", paint(GREEN, "✓ PASS"), schema.infos.len()),
        Status::Warn => format!("{} — {total} issues", paint(YELLOW, "⚠ WARN")),
        _ => format!("{} — {total} issues", paint(RED, "✗ FAIL")),
    };
    let _ = writeln!(out, "{}  {verdict}", paint(BOLD, "[SCHEMA]"));
    findings_block(out, validation, options, &[Section::Schema]);
}

/// The findings of `sections`, worst first: each with a snippet (INFO only with --verbose), the many of
/// one rule grouped into one line.
fn findings_block(
    out: &mut String,
    validation: &Validation,
    options: &TextOptions,
    sections: &[Section],
) {
    let report = &validation.report;
    for severity in [
        Severity::Critical,
        Severity::Fail,
        Severity::Warn,
        Severity::Info,
    ] {
        let mut grouped: Vec<String> = Vec::new();
        let mut by_rule: BTreeMap<(&str, &str), Vec<&FindingReport>> = BTreeMap::new();
        for finding in report
            .findings
            .iter()
            .filter(|f| f.severity == severity && sections.contains(&f.section))
        {
            by_rule
                .entry((finding.rule.as_str(), finding.name.as_str()))
                .or_default()
                .push(finding);
        }
        for ((_, name), findings) in by_rule {
            let limit = match (options.verbose, severity) {
                (true, _) => usize::MAX,
                (false, Severity::Info) => LIST_LIMIT_INFO,
                (false, _) => LIST_LIMIT_PROBLEMS,
            };
            let shown = if findings.len() > limit && severity == Severity::Info {
                0
            } else {
                findings.len().min(limit)
            };
            for finding in &findings[..shown] {
                finding_lines(
                    out,
                    validation,
                    finding,
                    severity != Severity::Info || options.verbose,
                );
            }
            let rest = findings.len() - shown;
            if rest > 0 {
                let more = if shown > 0 { "more " } else { "" };
                let noun = if name == "mesh-not-found" {
                    "mesh resolution".to_string()
                } else {
                    name.to_string()
                };
                grouped.push(format!("{rest} {more}{noun} {}", plural(severity, rest)));
            }
        }
        if !grouped.is_empty() {
            let padded = format!("{:<11}", format!("[{}]", severity.label()));
            let _ = writeln!(
                out,
                "  {}({} — --verbose lists all)",
                paint(severity_style(severity), &padded),
                grouped.join(" + ")
            );
        }
    }
}

/// `--baseline`: how many known findings it hid, and which of its entries match nothing any more.
fn baseline_line(out: &mut String, report: &Report) {
    let Some(baseline) = &report.baseline else {
        return;
    };
    let stale: usize = baseline.stale.iter().map(|e| e.count).sum();
    let _ = write!(
        out,
        "{}  {} known finding(s) hidden ({}), {} new",
        paint(BOLD, "[BASELINE]"),
        baseline.matched,
        baseline.file,
        baseline.new
    );
    if stale == 0 {
        let _ = writeln!(out);
        return;
    }
    let _ = writeln!(out, ", {stale} stale — rewrite with --write-baseline");
    for entry in &baseline.stale {
        let _ = writeln!(
            out,
            "  {} {} {}: {}",
            paint(DIM, "stale:"),
            entry.severity.label(),
            entry.rule,
            truncate(&entry.message, 160)
        );
    }
}

/// `--show-suppressed`: the findings that do not count, each marked with what suppressed it.
fn suppressed_block(out: &mut String, report: &Report) {
    if report.suppressed.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "{}  {} finding(s) suppressed (not counted in the status or the exit code)",
        paint(BOLD, "[SUPPRESSED]"),
        report.suppressed.len()
    );
    for suppressed in &report.suppressed {
        let finding = &suppressed.finding;
        let padded = format!("{:<11}", format!("[{}]", finding.severity.label()));
        let at = match (&finding.file, finding.line, finding.column) {
            (Some(file), Some(line), Some(column)) => format!("{file}:{line}:{column} "),
            _ => String::new(),
        };
        let _ = writeln!(
            out,
            "  {}{} {}",
            paint(DIM, &padded),
            paint(DIM, "suppressed:"),
            finding.message
        );
        let _ = writeln!(
            out,
            "     {} {at}{}  {}",
            paint(CYAN, "-->"),
            paint(DIM, &format!("{} {}", finding.rule, finding.name)),
            paint(DIM, &format!("by {}", suppressed.suppressed_by))
        );
    }
}

fn plural(severity: Severity, count: usize) -> &'static str {
    match (severity, count) {
        (Severity::Info, 1) => "notice",
        (Severity::Info, _) => "notices",
        (Severity::Warn, 1) => "warning",
        (Severity::Warn, _) => "warnings",
        (Severity::Fail, 1) => "failure",
        (Severity::Fail, _) => "failures",
        (Severity::Critical, 1) => "error",
        (Severity::Critical, _) => "errors",
    }
}

fn finding_lines(
    out: &mut String,
    validation: &Validation,
    finding: &FindingReport,
    snippet: bool,
) {
    let label = format!("[{}]", finding.severity.label());
    let padded = format!("{label:<11}");
    let fixable = finding.fix.as_ref().filter(|f| !f.edits.is_empty());
    let _ = writeln!(
        out,
        "  {}{}{}",
        paint(severity_style(finding.severity), &padded),
        if fixable.is_some() { "[*] " } else { "" },
        finding.message
    );
    if !snippet {
        return;
    }
    let (Some(file), Some(line), Some(column)) = (&finding.file, finding.line, finding.column)
    else {
        return;
    };
    let gutter = line.to_string().len();
    let pad = " ".repeat(gutter);
    let _ = writeln!(
        out,
        "  {pad}{} {file}:{line}:{column}  {}",
        paint(CYAN, "-->"),
        paint(DIM, &format!("{} {}", finding.rule, finding.name))
    );
    if let Some(text) = validation.source_line(file, line) {
        let text = text.replace('\t', " ");
        let start = (column as usize).saturating_sub(1);
        let end = match (finding.end_line, finding.end_column) {
            (Some(end_line), Some(end_column)) if end_line == line => {
                (end_column as usize).saturating_sub(1)
            }
            _ => text.chars().count(),
        };
        let width = end.saturating_sub(start).clamp(1, 80);
        let _ = writeln!(out, "  {pad} {}", paint(CYAN, "|"));
        let _ = writeln!(
            out,
            "  {} {} {}",
            paint(CYAN, &line.to_string()),
            paint(CYAN, "|"),
            truncate(&text, 160)
        );
        let _ = writeln!(
            out,
            "  {pad} {} {}{}",
            paint(CYAN, "|"),
            " ".repeat(start.min(160)),
            paint(severity_style(finding.severity), &"^".repeat(width))
        );
    }
    for frame in &finding.expanded_from {
        let _ = writeln!(out, "  {pad} {} note: {frame}", paint(CYAN, "="));
    }
    if let Some(help) = &finding.help {
        let _ = writeln!(
            out,
            "  {pad} {} {}",
            paint(CYAN, "="),
            paint(BOLD, &format!("help: {help}"))
        );
    }
    if let Some(fix) = &finding.fix {
        let how = match (fix.applicability, &fix.not_applicable) {
            (_, Some(why)) => format!("fix (not applicable here: {why})"),
            (Applicability::Safe, None) => "fix".to_string(),
            (Applicability::Unsafe, None) => "unsafe fix".to_string(),
        };
        let _ = writeln!(
            out,
            "  {pad} {} {how}: {}",
            paint(CYAN, "="),
            fix.description
        );
    }
}

/// `[OVERRIDES]  joint.j1.effort = 80 (file: 30); payload.mass = 2`: what the robot was evaluated with
/// instead of the file's values.
fn overrides_line(out: &mut String, report: &Report) {
    if report.overrides.is_empty() {
        return;
    }
    let items: Vec<String> = report
        .overrides
        .iter()
        .map(|o| match &o.was {
            Some(was) => format!("{} = {} (file: {was})", o.key, o.value),
            None => format!("{} = {}", o.key, o.value),
        })
        .collect();
    let _ = writeln!(
        out,
        "{}  evaluated with {}; the file is unchanged",
        paint(BOLD, "[OVERRIDES]"),
        items.join("; ")
    );
}

/// `[FIX]  2 fixable with --fix (1 more with --unsafe-fixes)`, when any finding has a fix to apply.
fn fixable_line(out: &mut String, report: &Report) {
    let count = |applicability| {
        report
            .findings
            .iter()
            .filter_map(|f| f.fix.as_ref())
            .filter(|f| f.applicability == applicability && !f.edits.is_empty())
            .count()
    };
    let (safe, unsafe_) = (count(Applicability::Safe), count(Applicability::Unsafe));
    if safe + unsafe_ == 0 {
        return;
    }
    let more = if unsafe_ > 0 {
        format!(" ({unsafe_} more with --unsafe-fixes)")
    } else {
        String::new()
    };
    let _ = writeln!(
        out,
        "{}  [*] {safe} fixable with --fix{more}",
        paint(BOLD, "[FIX]")
    );
}

fn truncate(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        text.to_string()
    } else {
        text.chars().take(max).collect::<String>() + "…"
    }
}

fn physics_line(out: &mut String, report: &Report) {
    let p = &report.physics;
    let frames = match p.frames {
        0 => String::new(),
        1 => " (1 frame)".to_string(),
        n => format!(" ({n} frames)"),
    };
    let body = if p.links > 0 && p.mass_missing == 0 && p.inertia_missing == 0 && p.mass_exact > 0 {
        format!(
            "{} {} links{frames} — all mass & inertia declared",
            paint(GREEN, "✓"),
            p.links
        )
    } else {
        format!(
            "{} links{frames} — mass: {} exact, {} missing · inertia: {} exact, {} missing",
            p.links, p.mass_exact, p.mass_missing, p.inertia_exact, p.inertia_missing
        )
    };
    let _ = writeln!(out, "{}  {body}", paint(BOLD, "[PHYSICS]"));
    if let Some(symmetry) = report.symmetry.as_ref().filter(|s| !s.pairs.is_empty()) {
        let count = symmetry.pairs.len();
        let differing: Vec<String> = symmetry
            .pairs
            .iter()
            .filter(|p| p.status != Status::Pass)
            .map(|p| format!("{} / {}", p.joints[0], p.joints[1]))
            .collect();
        let verdict = if differing.is_empty() {
            paint(GREEN, "all agree")
        } else {
            paint(
                YELLOW,
                &format!("{} differ: {}", differing.len(), differing.join(", ")),
            )
        };
        let _ = writeln!(
            out,
            "{}symmetry: {count} mirrored pair{} — {verdict}",
            " ".repeat(11),
            if count == 1 { "" } else { "s" }
        );
    }
}

fn statics_section(out: &mut String, statics: &StaticsSection, verbose: bool) {
    let head = paint(BOLD, "[STATICS]");
    let indent = " ".repeat(11);
    match (statics.full_body_com, statics.total_mass) {
        (Some([x, y, z]), Some(mass)) => {
            let height = statics.com_height_above_ground.unwrap_or(z);
            let _ = writeln!(
                out,
                "{head}  COM [{x:.3}, {y:.3}, {z:.3}] m  height {height:.3} m  total mass {mass:.3} kg  ({})",
                statics.com_confidence.label()
            );
            if let (Some(name), Some(pct)) =
                (&statics.heaviest_link_name, statics.heaviest_link_pct)
            {
                let _ = writeln!(out, "{indent}Heaviest: {name} ({pct:.1}%)");
            }
        }
        _ => {
            let _ = writeln!(out, "{head}  COM unknown (missing)");
        }
    }
    let mut line = format!(
        "{head}  joints: {}",
        paint(status_style(statics.status), statics.status.label())
    );
    if let Some(weakest) = &statics.weakest_joint_name {
        line.push_str(&format!("  weakest: {weakest}"));
    }
    if statics.pose != "zero" {
        line.push_str(&format!("  (pose: {}", statics.pose));
        if let Some(samples) = statics.samples {
            line.push_str(&format!(
                ", {samples} samples, seed {}",
                statics.seed.unwrap_or_default()
            ));
        }
        line.push(')');
    }
    let _ = writeln!(out, "{line}");
    // Rows worth reading: joints that fail, warn or cannot be assessed (all of them with --verbose). When
    // no mass is declared at all, the reason line says it once instead of one row per joint.
    let masses_known = statics.total_mass.is_some();
    let shown: Vec<&JointStatics> = statics
        .joints
        .iter()
        .filter(|j| {
            verbose
                || (masses_known
                    && matches!(j.status, Status::Warn | Status::Fail | Status::Unknown))
        })
        .collect();
    for joint in &shown {
        joint_row(out, joint);
    }
    let hidden = statics
        .joints
        .iter()
        .filter(|j| j.status != Status::NotApplicable)
        .count()
        .saturating_sub(shown.len());
    if !shown.is_empty() && hidden > 0 {
        let _ = writeln!(
            out,
            "  {}",
            paint(
                DIM,
                &format!("({hidden} more joints pass — --verbose lists all)")
            )
        );
    }
    let payload_asked = statics.payload_mass.is_some();
    if let Some(mass) = statics.payload_mass {
        let link = statics.payload_link.as_deref().unwrap_or("?");
        let _ = writeln!(out, "{indent}payload {mass:.3} kg at {link}");
    }
    if let (Some(capacity), Some(link), true) = (
        statics.payload_capacity_kg,
        &statics.payload_link,
        payload_asked || verbose,
    ) {
        let pass = crate::analysis::statics::gravity::PASS_MARGIN;
        let _ = writeln!(out, "{indent}payload capacity {capacity:.3} kg at {link} (every joint on its path at margin ≥ {pass}×)");
    }
    let unresolved = matches!(statics.status, Status::Unknown | Status::NotApplicable);
    if let Some(reason) = statics
        .reason
        .as_ref()
        .filter(|_| unresolved || payload_asked || verbose)
    {
        let _ = writeln!(out, "{indent}{}", paint(DIM, reason));
    }
    for note in &statics.notes {
        let _ = writeln!(out, "{indent}note: {note}");
    }
}

fn joint_row(out: &mut String, joint: &JointStatics) {
    let required = joint
        .required_torque_gravity
        .map_or("?".to_string(), |t| format!("{:.1} Nm", t.abs()));
    let declared = joint
        .declared_effort
        .map_or("none".to_string(), |e| format!("{e:.1} Nm"));
    let margin = joint
        .margin
        .map_or("no margin".to_string(), |m| format!("{m:.2}×"));
    // The effort that would PASS, beside the rows that do not.
    let needed = joint
        .effort_needed
        .filter(|_| matches!(joint.status, Status::Fail | Status::Warn))
        .map_or(String::new(), |e| {
            format!(
                " → declare effort ≥ {:.2}",
                crate::analysis::statics::gravity::round_up_to_hundredth(e)
            )
        });
    let _ = writeln!(
        out,
        "  {:<30}req {:<12}declared {:<14}{:>10}  {}  — {}{needed}",
        joint.name,
        required,
        declared,
        margin,
        paint(status_style(joint.status), joint.status.label()),
        joint.summary
    );
}

fn stability_section(out: &mut String, report: &Report, stability: &StabilitySection) {
    let head = paint(BOLD, "[STABILITY]");
    let indent = " ".repeat(13);
    let kind = report.robot_type.map_or("unknown", |t| t.as_str());
    let label = report
        .robot_type_confidence
        .map_or("estimated", Confidence::label);
    match stability.status {
        Status::NotApplicable => {
            let reason = stability.reason.as_deref().unwrap_or("not applicable");
            let _ = writeln!(out, "{head}  N/A — not applicable — {reason}");
            return;
        }
        Status::Pass | Status::Fail => {
            let verdict = if stability.status == Status::Pass {
                paint(GREEN, "✓ STABLE")
            } else {
                paint(RED, "✗ TIPS OVER")
            };
            let margin = stability.margin_mm.unwrap_or_default();
            let direction = stability.tip_direction.as_deref().unwrap_or("?");
            let _ = writeln!(out, "{head}  {verdict}  margin {margin:.1} mm  (nearest edge: {direction})  type {kind} ({label})");
            let mut line = String::new();
            if let (Some(ratio), Some(class)) = (
                stability.com_height_ratio,
                &stability.com_height_ratio_class,
            ) {
                line.push_str(&format!("COM height ratio {ratio:.2} — {class}"));
            }
            if let Some(angle) = stability.tipping_angle_deg {
                line.push_str(&format!("  tips at {angle:.1}°"));
            }
            if !line.is_empty() {
                let _ = writeln!(out, "{indent}{}", line.trim_start());
            }
        }
        _ => {
            let reason = stability.reason.as_deref().unwrap_or("no result");
            let _ = writeln!(
                out,
                "{head}  {} — {reason}  type {kind} ({label})",
                paint(RED, "UNKNOWN")
            );
        }
    }
    if !stability.contact_links.is_empty() {
        let source = stability.contact_source.as_deref().unwrap_or("?");
        let _ = writeln!(
            out,
            "{indent}contacts ({source}, {}): {}",
            stability.contact_confidence.label(),
            stability.contact_links.join(", ")
        );
    }
    for raised in &stability.raised_contacts {
        let _ = writeln!(
            out,
            "{indent}{}",
            paint(
                YELLOW,
                &format!(
                    "{} is {:.1} mm above the ground: it does not support (the robot rocks)",
                    raised.link, raised.height_mm
                )
            )
        );
    }
}

/// The tool approach axes the orientation was tested with: `approach axis +z (default)` when every arm
/// uses the same, else one per arm tip; a hint when the default (`z`) was used.
fn approach_axes(workspace: &WorkspaceSection) -> String {
    let axis = |arm: &ArmWorkspace| {
        let [x, y, z] = arm.approach_axis.map(|v| if v == 0.0 { 0.0 } else { v });
        let unit = [(x, "x"), (y, "y"), (z, "z")]
            .into_iter()
            .find(|&(v, _)| (v.abs() - 1.0).abs() < 1e-9);
        let text = match unit {
            Some((v, name)) => format!("{}{name}", if v > 0.0 { "+" } else { "-" }),
            None => format!("({x:.3}, {y:.3}, {z:.3})"),
        };
        let source = match arm.approach_axis_source.as_str() {
            "fingers" => "hand → fingers",
            "declared" => "--approach-axis",
            _ => "default",
        };
        format!("{text} ({source})")
    };
    let mut axes: Vec<String> = workspace.arms.iter().map(axis).collect();
    axes.dedup();
    let listed = match axes.as_slice() {
        [one] => format!("approach axis {one}"),
        _ => workspace
            .arms
            .iter()
            .map(|arm| format!("{}: {}", arm.tip_link, axis(arm)))
            .collect::<Vec<_>>()
            .join(", "),
    };
    if workspace
        .arms
        .iter()
        .any(|arm| arm.approach_axis_source == "z")
    {
        format!("{listed}; set it with --approach-axis")
    } else {
        listed
    }
}

fn workspace_section(out: &mut String, workspace: &WorkspaceSection, detailed: bool) {
    let head = paint(BOLD, "[WORKSPACE]");
    let indent = " ".repeat(13);
    let (Some(reach), Some(vertical), Some(horizontal), Some(from_base)) = (
        workspace.max_reach,
        workspace.vertical_reach,
        workspace.horizontal_reach,
        workspace.reach_from_base,
    ) else {
        let reason = workspace.reason.as_deref().unwrap_or("no arm");
        let _ = writeln!(out, "{head}  {} — {reason}", workspace.status.label());
        return;
    };
    let _ = writeln!(
        out,
        "{head}  max reach {reach:.3} m  vertical {vertical:.3} m  horizontal {horizontal:.3} m  ({})",
        workspace.reach_confidence.label()
    );
    let tips: Vec<&str> = workspace.arms.iter().map(|a| a.tip_link.as_str()).collect();
    let _ = writeln!(
        out,
        "{indent}from base {from_base:.3} m  {} arm{}: {}  ({} samples each)",
        tips.len(),
        if tips.len() == 1 { "" } else { "s" },
        tips.join(", "),
        workspace.samples
    );
    if let (Some(task), Some(height), Some(reachable)) = (
        &workspace.task,
        workspace.task_target_height_m,
        workspace.task_height_reachable,
    ) {
        let verdict = if reachable {
            paint(GREEN, "✓ reachable")
        } else {
            paint(RED, "✗ out of reach")
        };
        let mut line = format!("task {task} ({height:.2} m): {verdict}");
        match (
            workspace.task_com_stable_during_reach,
            workspace.task_com_margin_mm,
        ) {
            (Some(stable), Some(margin)) => {
                let shift = workspace.task_com_shift_estimate_m.unwrap_or_default();
                let style = if stable { GREEN } else { RED };
                line.push_str(&format!(
                    "  COM margin {} at full reach (COM shift {shift:.3} m)",
                    paint(style, &format!("{margin:.1} mm"))
                ));
                if let Some(worst) = workspace.task_com_worst_margin_mm {
                    let style = if worst >= 0.0 { GREEN } else { YELLOW };
                    line.push_str(&format!(
                        ", worst {} over the poses at that height",
                        paint(style, &format!("{worst:.1} mm"))
                    ));
                }
            }
            _ => {
                if let Some(why) = &workspace.task_com_not_assessed {
                    line.push_str(&format!("  COM not assessed: {why}"));
                }
            }
        }
        let _ = writeln!(out, "{indent}{line}");
        let held = workspace.body_joints_held();
        if workspace.task_height_reachable == Some(false) && !held.is_empty() {
            let _ = writeln!(
                out,
                "{indent}body joints held at the --pose values: {} (move them with --pose custom --joint-angles)",
                held.join(", ")
            );
        }
    }
    let assessed = workspace.status != Status::NotApplicable;
    if let (Some(orientation), None, true) = (
        &workspace.orientation,
        workspace.orientation_reachable,
        assessed,
    ) {
        let why = if workspace.task.is_some() {
            "no feasible sampled pose within 5 cm of the task height"
        } else {
            "no feasible sampled pose (each in self-collision or below the ground)"
        };
        let _ = writeln!(
            out,
            "{indent}orientation {orientation}: {} — {why}",
            paint(YELLOW, "not assessed")
        );
    }
    if let (Some(orientation), Some(reachable)) =
        (&workspace.orientation, workspace.orientation_reachable)
    {
        let fraction = workspace.orientation_fraction.unwrap_or(0.0) * 100.0;
        let verdict = if reachable {
            paint(GREEN, "✓")
        } else {
            paint(YELLOW, "⚠ < 5%")
        };
        let _ = writeln!(
            out,
            "{indent}orientation {orientation} ±{:.0}°: {fraction:.1}% of samples {verdict}  {}",
            workspace.orientation_tolerance_deg,
            approach_axes(workspace)
        );
    }
    if let Some(free) = workspace.self_collision_free_fraction {
        let style = if free >= crate::analysis::workspace::COLLISION_FREE_PASS_FRACTION {
            GREEN
        } else {
            YELLOW
        };
        let mut line = format!(
            "self-collision: {} of sampled poses free",
            paint(style, &format!("{:.1}%", free * 100.0))
        );
        if let Some(clearance) = workspace.self_collision_min_clearance_mm {
            line.push_str(&format!("  min clearance {clearance:.1} mm"));
        }
        if let Some([a, b]) = &workspace.self_collision_worst_pair {
            line.push_str(&format!("  worst pair {a} × {b}"));
        }
        let _ = writeln!(out, "{indent}{line}");
    } else if let Some(why) = &workspace.self_collision_not_assessed {
        let _ = writeln!(
            out,
            "{indent}self-collision: {} — {why}",
            paint(YELLOW, "not assessed")
        );
    }
    let touching = workspace.self_collision_touching_at_reference.len();
    if touching > 0 {
        let _ = writeln!(
            out,
            "{indent}{touching} link pair(s) already in contact at the zero pose: not checked (U601)"
        );
    }
    // The verdict line; why it is not PASS is told by the findings listed below the section.
    if workspace.status != Status::Pass {
        let _ = writeln!(
            out,
            "{indent}{}",
            paint(
                status_style(workspace.status),
                &format!("{} — why: the findings below", workspace.status.label())
            )
        );
    }
    if detailed {
        let _ = writeln!(
            out,
            "{indent}{:<28} {:<24} {:>3} {:>7} {:>7} {:>7} {:>7} {:>6}",
            "arm tip", "first joint", "dof", "reach", "vert", "horiz", "base", "free"
        );
        for arm in &workspace.arms {
            let free = arm
                .self_collision_free_fraction
                .map_or("-".to_string(), |f| format!("{:.1}%", f * 100.0));
            let _ = writeln!(
                out,
                "{indent}{:<28} {:<24} {:>3} {:>7.3} {:>7.3} {:>7.3} {:>7.3} {:>6}",
                truncate(&arm.tip_link, 28),
                truncate(arm.first_joint.as_deref().unwrap_or("-"), 24),
                arm.joints.len(),
                arm.max_reach,
                arm.vertical_reach,
                arm.horizontal_reach,
                arm.reach_from_base,
                free
            );
        }
    }
}

/// `[DEEP]`: MuJoCo's version and trigger, the cross-check, the drop test.
fn deep_section(out: &mut String, deep: &DeepSection) {
    let version = deep.simulator_version.as_deref().unwrap_or("?");
    let head = match deep.status {
        Status::Unknown => format!(
            "{}  {}",
            paint(RED, "UNKNOWN"),
            deep.reason.as_deref().unwrap_or("MuJoCo did not run")
        ),
        status => format!(
            "{}  MuJoCo {version} ({})",
            paint(status_style(status), status.label()),
            deep.trigger
        ),
    };
    let _ = writeln!(out, "{}  {head}", paint(BOLD, "[DEEP]"));
    if deep.status == Status::Unknown && deep.drop_test.is_none() {
        return;
    }
    let compared = deep.joints.len();
    let worst = deep
        .joints
        .iter()
        .filter_map(|j| {
            j.abs_diff.map(|d| {
                d / j
                    .our_torque
                    .abs()
                    .max(j.mujoco_torque.unwrap_or(0.0).abs())
                    .max(1e-3)
            })
        })
        .fold(0.0f64, f64::max);
    let agreed = deep.joints.iter().filter(|j| j.agrees).count();
    let com = deep
        .com_abs_diff
        .map_or("COM not compared".to_string(), |d| {
            format!("COM Δ {d:.1e} m")
        });
    let verdict = match deep.agreement {
        Some(true) => paint(GREEN, "agree — statics and COM simulated"),
        Some(false) => paint(YELLOW, "differ — see below"),
        None => paint(DIM, "not compared"),
    };
    let _ = writeln!(
        out,
        "        torques: {agreed}/{compared} joints within {:e} relative (worst {worst:.1e})  {com}  {verdict}",
        deep.tolerance
    );
    if let Some(drop) = &deep.drop_test {
        let tilt = drop.final_tilt_deg.map_or(String::new(), |t| {
            format!(
                "  tilt {t:.1}° (max {:.1}°)",
                drop.max_tilt_deg.unwrap_or(t)
            )
        });
        let drift = drop.com_drift_m.map_or(String::new(), |d| {
            format!("  COM drift {:.0} mm", d * 1000.0)
        });
        let why = drop
            .reason
            .as_deref()
            .map_or(String::new(), |r| format!(" — {r}"));
        let _ = writeln!(
            out,
            "        drop test ({:.1} s, {} base): {}{why}{tilt}{drift}",
            drop.simulated_s,
            drop.base,
            paint(status_style(drop.status), drop.status.label())
        );
        if !drop.ground_links.is_empty() {
            let _ = writeln!(
                out,
                "        on the ground at the end: {}",
                drop.ground_links.join(", ")
            );
        }
        if let Some(disagreement) = &drop.stability_disagreement {
            let _ = writeln!(out, "        {}", paint(YELLOW, disagreement));
        }
    }
    if !deep.simulator_changes.is_empty() {
        let _ = writeln!(
            out,
            "        {} thing(s) MuJoCo refuses or changes in this file (simulator_changes)",
            deep.simulator_changes.len()
        );
    }
}
