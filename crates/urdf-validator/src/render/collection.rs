//! The collection summary of a batch (a directory validated with `--format html`): every robot with its
//! verdict, finding counts by severity and by rule, mass, degrees of freedom, worst joint margin,
//! stability margin and time, and a link to its own report. Written as `index.json` and `index.md` here and
//! as `index.html` by [`crate::render::html::render_collection_html`].
//!
//! Like every renderer it computes no physics: each row is read off a [`Report`].

use std::collections::BTreeMap;
use std::fmt::Write;

use serde::Serialize;

use crate::diagnostics::Severity;
use crate::report::{Report, Status};
use crate::Validation;

/// The summary of a batch.
#[derive(Clone, Debug, Serialize)]
pub struct Collection {
    /// `urdf_validate`'s version.
    pub validator_version: String,
    /// The folder every row's `file` is relative to (the working directory when it holds them all), as
    /// an absolute path; null when the files are named as given.
    pub root: Option<String>,
    /// One row per input, in input order.
    pub robots: Vec<CollectionRobot>,
    /// Counts over every row.
    pub totals: CollectionTotals,
}

/// One input of the batch.
#[derive(Clone, Debug, Serialize)]
pub struct CollectionRobot {
    /// The input, relative to the collection's `root`.
    pub file: String,
    /// The robot's name (empty when the file could not be loaded).
    pub robot_name: String,
    /// PASS, WARN, FAIL, UNKNOWN, or ERROR when the file gave no report.
    pub status: String,
    /// The robot's HTML report, relative to the collection page (null when none was written).
    pub report: Option<String>,
    /// Findings by severity.
    pub findings: SeverityCounts,
    /// Findings by rule code.
    pub rules: BTreeMap<String, usize>,
    /// Sum of declared masses, kg.
    pub total_mass_kg: Option<f64>,
    /// Independent actuated joints (mimic followers not counted).
    pub dof: Option<usize>,
    /// The lowest gravity-torque margin (effort / |torque|) of any joint.
    pub worst_joint_margin: Option<f64>,
    /// The joint that has it.
    pub worst_joint: Option<String>,
    /// Signed distance of the centre of mass to the support polygon's edge, mm (positive inside).
    pub stability_margin_mm: Option<f64>,
    /// Wall-clock time of the validation, milliseconds.
    pub time_ms: Option<f64>,
    /// Why there is no report.
    pub error: Option<String>,
}

/// Findings counted by severity.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct SeverityCounts {
    /// CRITICAL findings.
    pub critical: usize,
    /// FAIL findings.
    pub fail: usize,
    /// WARN findings.
    pub warn: usize,
    /// INFO findings.
    pub info: usize,
}

impl SeverityCounts {
    fn add(&mut self, severity: Severity, count: usize) {
        match severity {
            Severity::Critical => self.critical += count,
            Severity::Fail => self.fail += count,
            Severity::Warn => self.warn += count,
            Severity::Info => self.info += count,
        }
    }

    /// The counts, most severe first, with their severities.
    pub fn by_severity(&self) -> [(Severity, usize); 4] {
        [
            (Severity::Critical, self.critical),
            (Severity::Fail, self.fail),
            (Severity::Warn, self.warn),
            (Severity::Info, self.info),
        ]
    }
}

/// Counts over the whole batch.
#[derive(Clone, Debug, Default, Serialize)]
pub struct CollectionTotals {
    /// Inputs.
    pub robots: usize,
    /// Inputs by verdict (PASS, WARN, FAIL, UNKNOWN, ERROR).
    pub by_status: BTreeMap<String, usize>,
    /// Findings by severity.
    pub by_severity: SeverityCounts,
    /// Findings by rule, the most frequent first.
    pub by_rule: Vec<RuleCount>,
}

/// How often one rule fired over the batch.
#[derive(Clone, Debug, Serialize)]
pub struct RuleCount {
    /// Rule code, e.g. `U205`.
    pub rule: String,
    /// Rule name.
    pub name: String,
    /// Its severity (the most severe it was reported with).
    pub severity: Severity,
    /// Findings.
    pub findings: usize,
    /// Inputs with at least one.
    pub robots: usize,
}

/// The verdicts in the order the page lists them.
pub const STATUSES: [&str; 5] = ["PASS", "WARN", "FAIL", "UNKNOWN", "ERROR"];

impl Collection {
    /// An empty collection.
    pub fn new() -> Collection {
        Collection {
            validator_version: env!("CARGO_PKG_VERSION").to_string(),
            root: None,
            robots: Vec::new(),
            totals: CollectionTotals::default(),
        }
    }

    /// Add a validated input: `file` as displayed, `report` its HTML report's link, `time_ms` how long it
    /// took.
    pub fn push_validation(
        &mut self,
        validation: &Validation,
        file: String,
        report: Option<String>,
        time_ms: Option<f64>,
    ) {
        self.robots
            .push(robot_row(&validation.report, file, report, time_ms));
    }

    /// Add an input that gave no report.
    pub fn push_error(&mut self, file: String, error: String) {
        self.robots.push(CollectionRobot {
            file,
            robot_name: String::new(),
            status: "ERROR".to_string(),
            report: None,
            findings: SeverityCounts::default(),
            rules: BTreeMap::new(),
            total_mass_kg: None,
            dof: None,
            worst_joint_margin: None,
            worst_joint: None,
            stability_margin_mm: None,
            time_ms: None,
            error: Some(error),
        });
    }

    /// Count the totals over the rows; `reports` gives each rule's name and severity.
    pub fn finish(&mut self, reports: &[&Report]) {
        let mut totals = CollectionTotals {
            robots: self.robots.len(),
            ..CollectionTotals::default()
        };
        for robot in &self.robots {
            *totals.by_status.entry(robot.status.clone()).or_default() += 1;
            for (severity, count) in robot.findings.by_severity() {
                totals.by_severity.add(severity, count);
            }
        }
        let mut by_rule: BTreeMap<&str, RuleCount> = BTreeMap::new();
        for report in reports {
            let mut seen = Vec::new();
            for finding in &report.findings {
                let entry = by_rule
                    .entry(finding.rule.as_str())
                    .or_insert_with(|| RuleCount {
                        rule: finding.rule.clone(),
                        name: finding.name.clone(),
                        severity: finding.severity,
                        findings: 0,
                        robots: 0,
                    });
                entry.findings += 1;
                entry.severity = entry.severity.max(finding.severity);
                if !seen.contains(&finding.rule.as_str()) {
                    seen.push(finding.rule.as_str());
                    entry.robots += 1;
                }
            }
        }
        totals.by_rule = by_rule.into_values().collect();
        totals.by_rule.sort_by(|a, b| {
            b.findings
                .cmp(&a.findings)
                .then(b.severity.cmp(&a.severity))
                .then(a.rule.cmp(&b.rule))
        });
        self.totals = totals;
    }
}

impl Default for Collection {
    fn default() -> Self {
        Collection::new()
    }
}

fn robot_row(
    report: &Report,
    file: String,
    link: Option<String>,
    time_ms: Option<f64>,
) -> CollectionRobot {
    let mut findings = SeverityCounts::default();
    let mut rules = BTreeMap::new();
    for finding in &report.findings {
        findings.add(finding.severity, 1);
        *rules.entry(finding.rule.clone()).or_default() += 1;
    }
    let statics = report.statics.as_ref();
    let worst = statics.and_then(|s| {
        s.joints
            .iter()
            .filter_map(|j| j.margin.filter(|m| m.is_finite()).map(|m| (m, &j.name)))
            .min_by(|a, b| a.0.total_cmp(&b.0))
    });
    CollectionRobot {
        file,
        robot_name: report.robot_name.clone(),
        status: status_label(report.overall_status).to_string(),
        report: link,
        findings,
        rules,
        total_mass_kg: statics.and_then(|s| s.total_mass),
        dof: statics.map(|s| s.joints.iter().filter(|j| j.mimics.is_none()).count()),
        worst_joint_margin: worst.map(|(m, _)| m),
        worst_joint: worst.map(|(_, name)| name.clone()),
        stability_margin_mm: report.stability.as_ref().and_then(|s| s.margin_mm),
        time_ms,
        error: None,
    }
}

/// A verdict's label on the collection page (N/A, which no overall verdict is, reads as PASS as its
/// exit code does).
fn status_label(status: Status) -> &'static str {
    match status {
        Status::NotApplicable => "PASS",
        other => other.label(),
    }
}

/// The collection as pretty JSON (`index.json`), with a final newline.
pub fn render_collection_json(collection: &Collection) -> String {
    serde_json::to_string_pretty(collection).unwrap_or_default() + "\n"
}

/// A number with `digits` decimals, or `—`.
pub(crate) fn number(value: Option<f64>, digits: usize) -> String {
    value.map_or_else(|| "—".to_string(), |v| format!("{v:.digits$}"))
}

/// The collection as Markdown (`index.md`): the verdict counts, one row per robot, the rules by count.
pub fn render_collection_markdown(collection: &Collection) -> String {
    let totals = &collection.totals;
    let mut out = String::from("# urdf_validate: collection summary\n\n");
    let counts: Vec<String> = STATUSES
        .iter()
        .map(|s| format!("{} {s}", totals.by_status.get(*s).copied().unwrap_or(0)))
        .collect();
    if let Some(root) = &collection.root {
        let _ = writeln!(out, "Files in `{}`.\n", cell(root));
    }
    let _ = writeln!(
        out,
        "{} file(s): {}. Findings: {} CRITICAL · {} FAIL · {} WARN · {} INFO.\n",
        totals.robots,
        counts.join(" · "),
        totals.by_severity.critical,
        totals.by_severity.fail,
        totals.by_severity.warn,
        totals.by_severity.info
    );
    out.push_str("| Robot | File | Verdict | CRITICAL | FAIL | WARN | INFO | Mass (kg) | DOF | Worst margin | Stability margin (mm) | Time (ms) |\n");
    out.push_str("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for robot in &collection.robots {
        let name = if robot.robot_name.is_empty() {
            "—".to_string()
        } else {
            cell(&robot.robot_name)
        };
        let file = match &robot.report {
            Some(link) => format!(
                "[`{}`]({})",
                cell(&robot.file),
                link_href(link).replace('(', "%28").replace(')', "%29")
            ),
            None => format!("`{}`", cell(&robot.file)),
        };
        let verdict = match &robot.error {
            Some(error) => format!("ERROR: {}", cell(error)),
            None => robot.status.clone(),
        };
        let f = &robot.findings;
        let margin = match (&robot.worst_joint_margin, &robot.worst_joint) {
            (Some(m), Some(joint)) => format!("{m:.2} ({})", cell(joint)),
            _ => "—".to_string(),
        };
        let _ = writeln!(
            out,
            "| {name} | {file} | {verdict} | {} | {} | {} | {} | {} | {} | {margin} | {} | {} |",
            f.critical,
            f.fail,
            f.warn,
            f.info,
            number(robot.total_mass_kg, 2),
            robot.dof.map_or("—".to_string(), |d| d.to_string()),
            number(robot.stability_margin_mm, 0),
            number(robot.time_ms, 0),
        );
    }
    if !totals.by_rule.is_empty() {
        out.push_str("\n## Findings by rule\n\n| Rule | Name | Severity | Findings | Robots |\n|---|---|---|---:|---:|\n");
        for rule in &totals.by_rule {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {} |",
                rule.rule,
                cell(&rule.name),
                rule.severity.label(),
                rule.findings,
                rule.robots
            );
        }
    }
    out
}

/// A relative file path as a URL path: separators as `/`, and the characters that would end or change it
/// (`%`, `#`, `?`, space) percent-encoded.
pub(crate) fn link_href(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    for c in path.chars() {
        match c {
            '\\' => out.push('/'),
            '%' => out.push_str("%25"),
            '#' => out.push_str("%23"),
            '?' => out.push_str("%3F"),
            ' ' => out.push_str("%20"),
            c => out.push(c),
        }
    }
    out
}

/// `text` safe in a Markdown table cell: one line, pipes escaped.
fn cell(text: &str) -> String {
    text.replace(['\n', '\r'], " ").replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markdown_cells_cannot_break_the_table() {
        let mut collection = Collection::new();
        collection.push_error("a|b.urdf".into(), "line one\nline | two".into());
        collection.finish(&[]);
        let markdown = render_collection_markdown(&collection);
        let row = markdown
            .lines()
            .find(|l| l.contains("a\\|b.urdf"))
            .expect("the row");
        assert!(row.contains("ERROR: line one line \\| two"), "{row}");
        assert_eq!(row.matches(" | ").count(), 11, "{row}");
        assert_eq!(collection.totals.by_status.get("ERROR"), Some(&1));
        assert_eq!(link_href("a b\\c#1.html"), "a%20b/c%231.html");
    }
}
