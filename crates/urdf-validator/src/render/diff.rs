//! Views of a [`ReportDiff`]: aligned text tables for the terminal, Markdown tables for pull-request
//! comments. Both come from the same rows.

use std::fmt::Write;

use crate::report::diff::{Change, JointFigures, ReportDiff};

/// One table: a title, column headers and rows.
struct Table {
    title: &'static str,
    header: [&'static str; 4],
    rows: Vec<[String; 4]>,
}

/// The tables of a diff, in reading order; tables with no row are left out.
fn tables(diff: &ReportDiff) -> Vec<Table> {
    let verdicts = diff
        .verdicts
        .iter()
        .filter(|v| v.status.old.is_some() || v.status.new.is_some())
        .map(|v| {
            let trend = if v.worse {
                "worse"
            } else if v.status.changed() {
                "changed"
            } else {
                ""
            };
            [
                v.check.clone(),
                opt(&v.status.old),
                opt(&v.status.new),
                trend.to_string(),
            ]
        })
        .collect();
    let mut mass = vec![number_row("total mass (kg)", &diff.total_mass, 3)];
    mass.push([
        "centre of mass (m)".to_string(),
        vector(&diff.com.old),
        vector(&diff.com.new),
        if diff.com.changed() { "changed" } else { "" }.to_string(),
    ]);
    mass.extend(
        diff.link_masses
            .iter()
            .map(|l| number_row(&format!("link {} (kg)", l.name), &l.value, 3)),
    );
    let joints = diff
        .joints
        .iter()
        .map(|j| {
            let margin = |f: &Option<JointFigures>| f.as_ref().and_then(|f| f.margin);
            let trend = match (margin(&j.figures.old), margin(&j.figures.new)) {
                (Some(a), Some(b)) if a > 0.0 => format!("margin {:+.0}%", (b / a - 1.0) * 100.0),
                _ => String::new(),
            };
            [
                j.joint.clone(),
                figures(&j.figures.old),
                figures(&j.figures.new),
                trend,
            ]
        })
        .collect();
    let mut stability = Vec::new();
    if diff.stability_margin_mm.old.is_some() || diff.stability_margin_mm.new.is_some() {
        stability.push(number_row(
            "stability margin (mm)",
            &diff.stability_margin_mm,
            1,
        ));
    }
    let reach = diff
        .reach
        .iter()
        .map(|r| number_row(&format!("reach of {} (m)", r.name), &r.value, 3))
        .collect();
    let findings = diff
        .findings_added
        .iter()
        .map(|f| ("added", f))
        .chain(diff.findings_removed.iter().map(|f| ("removed", f)))
        .map(|(what, f)| {
            [
                what.to_string(),
                f.rule.clone(),
                f.severity.label().to_string(),
                f.message.clone(),
            ]
        })
        .collect();
    [
        Table {
            title: "Verdicts",
            header: ["check", "old", "new", ""],
            rows: verdicts,
        },
        Table {
            title: "Mass and centre of mass",
            header: ["", "old", "new", "change"],
            rows: mass,
        },
        Table {
            title: "Gravity torques (joints that changed)",
            header: ["joint", "old", "new", "change"],
            rows: joints,
        },
        Table {
            title: "Stability",
            header: ["", "old", "new", "change"],
            rows: stability,
        },
        Table {
            title: "Reach (arms that changed)",
            header: ["", "old", "new", "change"],
            rows: reach,
        },
        Table {
            title: "Findings",
            header: ["", "rule", "severity", "message"],
            rows: findings,
        },
    ]
    .into_iter()
    .filter(|t| !t.rows.is_empty())
    .collect()
}

fn opt(value: &Option<String>) -> String {
    value.clone().unwrap_or_else(|| "—".to_string())
}

fn vector(value: &Option<Vec<f64>>) -> String {
    match value {
        Some(v) => {
            let parts: Vec<String> = v.iter().map(|x| format!("{x:.3}")).collect();
            format!("({})", parts.join(", "))
        }
        None => "—".to_string(),
    }
}

/// `label | old | new | +delta` with `digits` decimals.
fn number_row(label: &str, change: &Change<f64>, digits: usize) -> [String; 4] {
    let show = |v: Option<f64>| v.map_or_else(|| "—".to_string(), |v| format!("{v:.digits$}"));
    let delta = match (change.old, change.new) {
        (Some(a), Some(b)) if change.changed() => format!("{:+.digits$}", b - a),
        _ => String::new(),
    };
    [label.to_string(), show(change.old), show(change.new), delta]
}

/// `11.77 N·m / 5 → 0.42× FAIL (needs ≥ 17.66)`.
fn figures(figures: &Option<JointFigures>) -> String {
    let Some(f) = figures else {
        return "—".to_string();
    };
    let torque = f.torque.map_or("?".to_string(), |t| format!("{t:.2} N·m"));
    let effort = f.effort.map_or("none".to_string(), |e| format!("{e}"));
    let margin = f.margin.map_or("—".to_string(), |m| format!("{m:.2}×"));
    let needed = f
        .effort_needed
        .filter(|_| matches!(f.status.as_str(), "FAIL" | "WARN"))
        .map_or(String::new(), |e| format!(" (needs ≥ {e:.2})"));
    format!("{torque} / {effort} → {margin} {}{needed}", f.status)
}

/// The first line: what is compared and whether NEW is worse.
fn headline(diff: &ReportDiff) -> String {
    format!(
        "{} → {}: {}",
        diff.old,
        diff.new,
        if diff.worse {
            "WORSE (a verdict got worse or a new WARN/FAIL finding appeared)"
        } else {
            "no verdict got worse"
        }
    )
}

/// The diff as aligned text tables.
pub fn render_diff_text(diff: &ReportDiff) -> String {
    let mut out = headline(diff) + "\n";
    for table in tables(diff) {
        let mut widths = table.header.map(|h| h.chars().count());
        for row in &table.rows {
            for (width, cell) in widths.iter_mut().zip(row) {
                *width = (*width).max(cell.chars().count());
            }
        }
        let _ = writeln!(out, "\n[{}]", table.title);
        for row in std::iter::once(table.header.map(str::to_string)).chain(table.rows) {
            let cells: Vec<String> = row
                .iter()
                .zip(widths)
                .map(|(cell, width)| {
                    let pad = width.saturating_sub(cell.chars().count());
                    format!("{cell}{}", " ".repeat(pad))
                })
                .collect();
            let _ = writeln!(out, "  {}", cells.join("  ").trim_end());
        }
    }
    out
}

/// The diff as Markdown (for a pull-request comment).
pub fn render_diff_markdown(diff: &ReportDiff) -> String {
    let mut out = format!("### urdf_validate diff\n\n{}\n", cell(&headline(diff)));
    for table in tables(diff) {
        let _ = writeln!(out, "\n**{}**\n", table.title);
        let _ = writeln!(out, "| {} |", table.header.join(" | "));
        let _ = writeln!(out, "|{}", "---|".repeat(4));
        for row in &table.rows {
            let cells: Vec<String> = row.iter().map(|c| cell(c)).collect();
            let _ = writeln!(out, "| {} |", cells.join(" | "));
        }
    }
    out
}

/// Text safe inside a Markdown table cell of a pull-request comment: no column break, no line break, no
/// mention (`@team`), no HTML tag, no code span or emphasis started by the file's names.
fn cell(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '|' | '@' | '<' | '>' | '`' | '*' | '[' | ']' | '\\' => {
                out.push('\\');
                out.push(c);
            }
            '\n' | '\r' => out.push(' '),
            _ => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::cell;

    #[test]
    fn markdown_cells_cannot_break_the_table_mention_or_inject_html() {
        assert_eq!(
            cell("joint|x @org/team <img src=x> `code` *b* [l](u)\nnext"),
            "joint\\|x \\@org/team \\<img src=x\\> \\`code\\` \\*b\\* \\[l\\](u) next"
        );
        assert_eq!(cell("r_elbow_flex_joint"), "r_elbow_flex_joint");
    }
}
