//! The statics panel: each joint's gravity torque against its effort limit, as a log-scale bullet chart.

use std::fmt::Write;

use super::svg::{n, svg_open};
use super::{escape, pill, shorten, status_class};
use crate::report::{JointStatics, StaticsSection, Status};

/// Joints drawn in the torque chart (worst first); the rest are counted in a note.
const MAX_JOINT_ROWS: usize = 120;

/// Gravity torques below this are negligible (no margin), N·m (the statics definition).
const NEGLIGIBLE: f64 = 1e-3;

/// Torque ratios at or above this pass (the statics definition).
const PASS_MARGIN: f64 = crate::analysis::statics::gravity::PASS_MARGIN;

/// Order of statuses in the torque chart: the ones to act on first.
fn status_rank(status: Status) -> u8 {
    match status {
        Status::Fail => 0,
        Status::Warn => 1,
        Status::Unknown => 2,
        Status::Pass => 3,
        Status::NotApplicable => 4,
    }
}

pub(super) fn statics_panel(out: &mut String, statics: &StaticsSection) {
    let _ = write!(
        out,
        "<section id=\"statics\" class=\"panel\">\n<h2>Statics {}</h2>\n",
        pill(statics.status)
    );
    let mut facts: Vec<String> = Vec::new();
    if let Some(mass) = statics.total_mass {
        facts.push(format!(
            "total mass <b>{mass:.3} kg</b> ({})",
            statics.mass_confidence.label()
        ));
    }
    if let Some([x, y, z]) = statics.full_body_com {
        facts.push(format!(
            "COM ({x:.3}, {y:.3}, {z:.3}) m ({})",
            statics.com_confidence.label()
        ));
    }
    if let (Some(name), Some(pct)) = (&statics.heaviest_link_name, statics.heaviest_link_pct) {
        facts.push(format!("heaviest link {} ({pct:.1}%)", escape(name)));
    }
    facts.push(format!("pose <b>{}</b>", escape(&statics.pose)));
    if let (Some(capacity), Some(link)) = (statics.payload_capacity_kg, &statics.payload_link) {
        facts.push(format!(
            "payload capacity {capacity:.2} kg at {}",
            escape(link)
        ));
    }
    let _ = writeln!(out, "<p class=\"facts\">{}</p>", facts.join(" · "));
    if let Some(reason) = &statics.reason {
        let _ = writeln!(out, "<p class=\"note\">{}</p>", escape(reason));
    }
    let mut joints: Vec<&JointStatics> = statics
        .joints
        .iter()
        .filter(|j| j.status != Status::NotApplicable)
        .collect();
    if !joints.iter().any(|j| j.required_torque_gravity.is_some()) {
        out.push_str("<p class=\"empty\">No gravity torque to plot (no joint could be assessed).</p>\n</section>\n");
        return;
    }
    // Joints whose gravity torque is negligible are counted, not drawn (their bars would be empty).
    let negligible = |j: &JointStatics| {
        j.status == Status::Pass
            && j.required_torque_gravity
                .is_some_and(|t| t.abs() < NEGLIGIBLE)
    };
    let quiet = joints.iter().filter(|j| negligible(j)).count();
    joints.retain(|j| !negligible(j));
    joints.sort_by(|a, b| {
        status_rank(a.status).cmp(&status_rank(b.status)).then(
            a.margin
                .unwrap_or(f64::INFINITY)
                .total_cmp(&b.margin.unwrap_or(f64::INFINITY)),
        )
    });
    let hidden = joints.len().saturating_sub(MAX_JOINT_ROWS);
    joints.truncate(MAX_JOINT_ROWS);
    torque_chart(out, &joints);
    if hidden > 0 {
        let _ = writeln!(
            out,
            "<p class=\"key\">{hidden} more joints not drawn (they pass with the largest margins).</p>"
        );
    }
    if quiet > 0 {
        let _ = writeln!(
            out,
            "<p class=\"key\">{quiet} more joint{} carr{} a negligible gravity torque (below {NEGLIGIBLE} N·m) at this pose: not drawn.</p>",
            if quiet == 1 { "" } else { "s" },
            if quiet == 1 { "ies" } else { "y" },
        );
    }
    let _ = write!(
        out,
        "<p class=\"key\"><span class=\"swatch pass\"></span>PASS margin ≥ {PASS_MARGIN}× <span class=\"swatch warn\"></span>WARN 1–{PASS_MARGIN}× <span class=\"swatch fail\"></span>FAIL &lt; 1× <span class=\"swatch unknown\"></span>UNKNOWN <span class=\"key-limit\"></span>effort limit (the shaded band before it: WARN)</p>\n</section>\n"
    );
}

/// A bullet chart on a log scale: per joint, |gravity torque| as a bar coloured by its status, the effort
/// limit as a tick, the WARN band (limit / 1.5 to limit) and the FAIL band (beyond the limit) shaded.
fn torque_chart(out: &mut String, joints: &[&JointStatics]) {
    let values = joints.iter().flat_map(|j| {
        [
            j.required_torque_gravity
                .map(f64::abs)
                .filter(|t| *t >= NEGLIGIBLE),
            j.declared_effort.filter(|e| *e > 0.0),
        ]
        .into_iter()
        .flatten()
    });
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    let (mut d0, mut d1) = if lo.is_finite() && hi.is_finite() {
        (lo.log10().floor(), (hi * 1.05).log10().ceil())
    } else {
        (-1.0, 1.0)
    };
    d0 = d0.max(d1 - 8.0).max(-3.0);
    if d1 <= d0 {
        d1 = d0 + 1.0;
    }
    let (label_w, plot_w, text_w, row_h, top) = (230.0, 620.0, 230.0, 22.0, 30.0);
    let width = label_w + plot_w + text_w;
    let height = top + row_h * joints.len() as f64 + 46.0;
    let x = |v: f64| {
        let l = v.max(10f64.powf(d0)).log10();
        label_w + (l - d0) / (d1 - d0) * plot_w
    };
    svg_open(
        out,
        width,
        height,
        "Gravity torque of each joint against its effort limit",
        "statics-plot",
    );
    let bottom = top + row_h * joints.len() as f64;
    // Decades.
    let mut decade = d0;
    while decade <= d1 + 1e-9 {
        let v = 10f64.powf(decade);
        let px = x(v);
        let _ = write!(
            out,
            "<line class=\"grid\" x1=\"{px}\" y1=\"{}\" x2=\"{px}\" y2=\"{}\"/><text class=\"tick\" x=\"{px}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            n(top - 4.0),
            n(bottom),
            n(bottom + 14.0),
            decade_label(decade),
            px = n(px)
        );
        decade += 1.0;
    }
    let _ = write!(
        out,
        "<text class=\"axis-title\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">|gravity torque| and effort limit — N·m (N for prismatic joints), log scale</text>\
         <text class=\"col-title\" x=\"{}\" y=\"16\" text-anchor=\"end\">joint</text><text class=\"col-title\" x=\"{}\" y=\"16\">torque / limit · margin</text>",
        n(label_w + plot_w / 2.0),
        n(bottom + 34.0),
        n(label_w - 10.0),
        n(label_w + plot_w + 10.0),
    );
    for (row, joint) in joints.iter().enumerate() {
        let y = top + row_h * row as f64;
        let cy = y + row_h / 2.0;
        let cls = status_class(joint.status);
        let torque = joint.required_torque_gravity.map(f64::abs);
        let effort = joint.declared_effort.filter(|e| *e > 0.0);
        let _ = write!(out, "<g class=\"jrow {cls}\">");
        if row % 2 == 0 {
            let _ = write!(
                out,
                "<rect class=\"stripe\" x=\"0\" y=\"{}\" width=\"{}\" height=\"{}\"/>",
                n(y),
                n(width),
                n(row_h)
            );
        }
        let _ = write!(
            out,
            "<rect class=\"track\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"10\" rx=\"2\"/>",
            n(label_w),
            n(cy - 5.0),
            n(plot_w)
        );
        if let Some(e) = effort {
            let (warn_from, limit) = (x(e / PASS_MARGIN), x(e));
            let _ = write!(
                out,
                "<rect class=\"zone-warn\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"10\"/>",
                n(warn_from),
                n(cy - 5.0),
                n((limit - warn_from).max(0.0)),
            );
        }
        if let Some(t) = torque {
            let end = if t >= NEGLIGIBLE { x(t) } else { label_w + 2.0 };
            let _ = write!(
                out,
                "<rect class=\"bar {cls}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"10\" rx=\"2\"/>",
                n(label_w),
                n(cy - 5.0),
                n((end - label_w).max(2.0))
            );
        }
        if let Some(e) = effort {
            let px = x(e);
            let _ = write!(
                out,
                "<line class=\"limit\" x1=\"{px}\" y1=\"{}\" x2=\"{px}\" y2=\"{}\"/>",
                n(cy - 8.0),
                n(cy + 8.0),
                px = n(px)
            );
        }
        let name = shorten(&joint.name, 30);
        let torque_text = match torque {
            Some(t) if t < NEGLIGIBLE => "negligible".to_string(),
            Some(t) => sig(t),
            None => "?".to_string(),
        };
        let effort_text = effort.map_or("no limit".to_string(), sig);
        let margin_text = joint
            .margin
            .map_or(String::new(), |m| format!(" · {}×", sig(m)));
        let _ = write!(
            out,
            "<text class=\"jname\" x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text><text class=\"jval\" x=\"{}\" y=\"{}\">{torque_text} / {effort_text}<tspan class=\"{cls}-text\">{margin_text}</tspan></text>\
             <title>{} — {}: |τ| {torque_text}, limit {effort_text}{margin_text} ({})</title></g>",
            n(label_w - 10.0),
            n(cy + 4.0),
            escape(&name),
            n(label_w + plot_w + 10.0),
            n(cy + 4.0),
            escape(&joint.name),
            joint.status.label(),
            escape(&joint.summary),
        );
    }
    out.push_str("</svg>\n");
}

/// Three significant figures, without exponent for everyday values.
fn sig(v: f64) -> String {
    let a = v.abs();
    if !v.is_finite() {
        "?".to_string()
    } else if a >= 100.0 {
        format!("{v:.0}")
    } else if a >= 10.0 {
        format!("{v:.1}")
    } else if a >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}

fn decade_label(decade: f64) -> String {
    match decade.round() as i32 {
        d if d < 0 => format!("{}", 10f64.powi(d)),
        0 => "1".to_string(),
        1 => "10".to_string(),
        2 => "100".to_string(),
        3 => "1k".to_string(),
        4 => "10k".to_string(),
        5 => "100k".to_string(),
        d => format!("1e{d}"),
    }
}
