//! The HTML view of the `deep` section (MuJoCo): its summary card, and a panel with the drop test (the
//! root link's tilt over the 2 s plotted from `drop_test.tilt_trace`, what touches the ground at the end,
//! whether it agrees with the stability section), MuJoCo's gravity torques and centre of mass against
//! ours, and what MuJoCo refused or changed.

use std::fmt::Write;

use super::page::card;
use super::svg::{n, svg_open, Bounds, Frame};
use super::{escape, pill, shorten, status_class};
use crate::analysis::deep::verdict::TIP_OVER_DEG;
use crate::report::{DeepSection, DropTest, Status};

/// Rows of the torque and change tables; the rest are counted in a note.
const MAX_ROWS: usize = 200;

/// The panel's own style rules (appended to the page's).
pub(super) const CSS: &str = r#"
svg .tilt{fill:none;stroke-width:2;stroke-linejoin:round}
svg .tilt.pass{stroke:var(--pass)}svg .tilt.warn{stroke:var(--warn)}svg .tilt.fail{stroke:var(--fail)}svg .tilt.unknown,svg .tilt.na{stroke:var(--unknown)}
svg .threshold-line{stroke:var(--fail);stroke-width:1.2;stroke-dasharray:6 4}
svg .threshold-label{fill:var(--fail);font-size:11px}
svg .end circle{fill:var(--card);stroke:var(--fg);stroke-width:1.6}
svg .end text{fill:var(--fg);font-size:12px;font-weight:700;paint-order:stroke;stroke:var(--card);stroke-width:4px}
.fallen{color:var(--fail);font-weight:700}
table.deep td.num{font-variant-numeric:tabular-nums;white-space:nowrap}
"#;

/// The summary card of the deep section.
pub(super) fn deep_card(out: &mut String, deep: &DeepSection) {
    let main = match (&deep.drop_test, &deep.reason) {
        (Some(drop), _) => format!(
            "drop test {}{}",
            drop.status.label(),
            drop.reason
                .as_deref()
                .map_or(String::new(), |r| format!(" — {r}"))
        ),
        (None, Some(reason)) => reason.clone(),
        (None, None) => "MuJoCo did not run".to_string(),
    };
    let agreed = deep.joints.iter().filter(|j| j.agrees).count();
    let mut detail = format!(
        "MuJoCo {} ({})",
        deep.simulator_version.as_deref().unwrap_or("?"),
        deep.trigger
    );
    if !deep.joints.is_empty() {
        let _ = write!(detail, " · torques {agreed}/{} agree", deep.joints.len());
    }
    if let Some(d) = deep.com_abs_diff {
        let _ = write!(detail, " · COM Δ {d:.1e} m");
    }
    card(
        out,
        "Deep (MuJoCo)",
        "#deep",
        deep.status,
        &shorten(&main, 70),
        &detail,
    );
}

/// The deep section's panel.
pub(super) fn deep_panel(out: &mut String, deep: &DeepSection) {
    let _ = write!(
        out,
        "<section id=\"deep\" class=\"panel\">\n<h2>Deep (MuJoCo) {}</h2>\n",
        pill(deep.status)
    );
    // (The Python interpreter's path is in the JSON report: a path of the machine that ran it.)
    let _ = writeln!(
        out,
        "<p class=\"facts\">MuJoCo <b>{}</b> ({}) · the robot loaded as a user would load it, its gravity forces and centre of mass compared with statics, and a 2-second drop test</p>",
        escape(deep.simulator_version.as_deref().unwrap_or("?")),
        escape(&deep.trigger)
    );
    if let Some(reason) = &deep.reason {
        let _ = writeln!(out, "<p class=\"note\">{}</p>", escape(reason));
    }
    if let Some(drop) = &deep.drop_test {
        drop_test(out, drop);
    }
    torques(out, deep);
    changes(out, deep);
    out.push_str("</section>\n");
}

/// The drop test: the disagreement with statics first, then the tilt plot and the facts beside it.
fn drop_test(out: &mut String, drop: &DropTest) {
    let _ = writeln!(
        out,
        "<h3 id=\"drop-test\">Drop test {} <span class=\"muted\">({:.1} s, {} base)</span></h3>",
        pill(drop.status),
        drop.simulated_s,
        escape(&drop.base)
    );
    if let Some(disagreement) = &drop.stability_disagreement {
        let _ = writeln!(out, "<p class=\"note\">{}</p>", escape(disagreement));
    }
    out.push_str("<div class=\"plot-row\">\n");
    if drop.base == "fixed" {
        out.push_str("<p class=\"empty\">The root link is held (a fixed-base arm): it cannot tilt, nothing to plot.</p>\n");
    } else if drop.tilt_trace.len() < 2 {
        out.push_str("<p class=\"empty\">No tilt trace in this report.</p>\n");
    } else {
        tilt_plot(out, drop);
    }
    out.push_str("<div class=\"legend\">\n<h3>At the end</h3>\n<ul class=\"contacts\">");
    if let Some(tilt) = drop.final_tilt_deg {
        let _ = write!(
            out,
            "<li>tilt <b>{tilt:.1}°</b> <span class=\"muted\">(max {:.1}°)</span></li>",
            drop.max_tilt_deg.unwrap_or(tilt)
        );
    }
    if let Some(drift) = drop.com_drift_m {
        let _ = write!(
            out,
            "<li>COM drift {:.0} mm <span class=\"muted\">(horizontal)</span></li>",
            drift * 1000.0
        );
    }
    if let Some(reason) = &drop.reason {
        let _ = write!(out, "<li>{}</li>", escape(reason));
    }
    out.push_str("</ul>\n");
    if !drop.ground_links.is_empty() {
        out.push_str("<h3>On the ground</h3>\n<ul class=\"contacts\">");
        for link in &drop.ground_links {
            if drop.fallen_onto.contains(link) {
                let _ = write!(
                    out,
                    "<li><span class=\"name fallen\">{}</span> <span class=\"fallen\">not a support: fallen onto</span></li>",
                    escape(link)
                );
            } else {
                let _ = write!(out, "<li><span class=\"name\">{}</span></li>", escape(link));
            }
        }
        out.push_str("</ul>\n");
    }
    if !drop.support_links.is_empty() {
        let _ = writeln!(
            out,
            "<p class=\"key\">Support contacts: {}</p>",
            escape(&drop.support_links.join(", "))
        );
    }
    if !drop.joints_sagging.is_empty() {
        out.push_str("<h3>Joints that sag</h3>\n<ul class=\"contacts\">");
        for joint in &drop.joints_sagging {
            let _ = write!(
                out,
                "<li><span class=\"name\">{}</span> <span class=\"muted\">{:.3} from target{}</span></li>",
                escape(&joint.name),
                joint.deviation,
                joint
                    .declared_effort
                    .map_or(String::new(), |e| format!(", effort {e}"))
            );
        }
        out.push_str("</ul>\n");
    }
    out.push_str("</div>\n</div>\n");
}

/// The root link's tilt over time, with the 15° tip-over line and the end marked.
fn tilt_plot(out: &mut String, drop: &DropTest) {
    let trace = &drop.tilt_trace;
    let Some(data) = Bounds::of(trace.iter().copied()) else {
        return;
    };
    let top = data.y1.max(TIP_OVER_DEG) * 1.15;
    let (w, h) = (560.0, 300.0);
    let frame = Frame {
        b: Bounds {
            x0: 0.0,
            x1: data.x1.max(drop.simulated_s),
            y0: 0.0,
            y1: top,
        },
        left: 62.0,
        top: 14.0,
        width: w - 80.0,
        height: h - 62.0,
    };
    out.push_str("<figure class=\"figure wide\">");
    svg_open(
        out,
        w,
        h,
        "tilt of the root link over the drop test",
        "drop-tilt-plot",
    );
    frame.axes(out, "time (s)", "tilt from upright (°)");
    let threshold = frame.y(TIP_OVER_DEG);
    let _ = write!(
        out,
        "<line class=\"threshold-line\" x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\"/><text class=\"threshold-label\" x=\"{}\" y=\"{}\" text-anchor=\"end\">tips over beyond {TIP_OVER_DEG}°</text>",
        n(frame.left),
        n(frame.left + frame.width),
        n(frame.left + frame.width - 4.0),
        n(threshold - 4.0),
        y = n(threshold)
    );
    let points: Vec<String> = trace.iter().map(|&p| frame.p(p)).collect();
    let _ = write!(
        out,
        "<polyline class=\"tilt {}\" points=\"{}\"/>",
        status_class(drop.status),
        points.join(" ")
    );
    if let Some(&[t, tilt]) = trace.last() {
        let (x, y) = (frame.x(t), frame.y(tilt));
        let _ = write!(
            out,
            "<g class=\"end\"><circle cx=\"{}\" cy=\"{}\" r=\"4.5\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">{tilt:.1}°{}</text></g>",
            n(x),
            n(y),
            n(x - 8.0),
            n(y - 9.0),
            if drop.fallen_onto.is_empty() {
                String::new()
            } else {
                format!(" on {}", escape(&drop.fallen_onto.join(", ")))
            }
        );
    }
    let caption = match drop.status {
        Status::Pass => "stands",
        Status::Fail if !drop.fallen_onto.is_empty() => "falls onto a link that is not a support",
        Status::Fail => "fails",
        _ => "is not steady",
    };
    let _ = write!(
        out,
        "</svg>\n<figcaption>The root link's tilt from upright after release, {} samples over {:.1} s: the robot {caption}.</figcaption></figure>\n",
        trace.len(),
        drop.simulated_s
    );
}

/// MuJoCo's gravity forces and centre of mass against ours.
fn torques(out: &mut String, deep: &DeepSection) {
    if deep.joints.is_empty() && deep.mujoco_com.is_none() {
        return;
    }
    let verdict = match deep.agreement {
        Some(true) => "agree: statics' torques and centre of mass are labelled simulated",
        Some(false) => "differ (see the findings)",
        None => "not compared",
    };
    let _ = writeln!(
        out,
        "<h3>Gravity torques and centre of mass</h3>\n<p class=\"facts\">MuJoCo against statics within {:e} relative: {verdict}.</p>",
        deep.tolerance
    );
    out.push_str("<div class=\"table-wrap\"><table class=\"findings deep\"><thead><tr><th>Joint</th><th>MuJoCo</th><th>Statics</th><th>|Δ|</th><th>Agrees</th><th>Configuration</th></tr></thead><tbody>\n");
    for joint in deep.joints.iter().take(MAX_ROWS) {
        let _ = writeln!(
            out,
            "<tr><td><code>{}</code></td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td><td>{}</td></tr>",
            escape(&joint.name),
            joint.mujoco_torque.map_or("—".to_string(), torque),
            torque(joint.our_torque),
            joint.abs_diff.map_or("—".to_string(), |d| format!("{d:.1e}")),
            pill(if joint.agrees {
                Status::Pass
            } else {
                Status::Fail
            }),
            escape(&joint.configuration)
        );
    }
    if let (Some(theirs), Some(ours)) = (deep.mujoco_com, deep.our_com) {
        let v = |c: [f64; 3]| format!("({:.4}, {:.4}, {:.4})", c[0], c[1], c[2]);
        let _ = writeln!(
            out,
            "<tr><td><b>centre of mass</b> (m)</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td></td><td></td></tr>",
            v(theirs),
            v(ours),
            deep.com_abs_diff
                .map_or("—".to_string(), |d| format!("{d:.1e}"))
        );
    }
    out.push_str("</tbody></table></div>\n");
    more(out, deep.joints.len(), "joints");
}

/// What MuJoCo refused or changed while loading the file.
fn changes(out: &mut String, deep: &DeepSection) {
    if deep.simulator_changes.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "<h3>What MuJoCo changed ({})</h3>",
        deep.simulator_changes.len()
    );
    out.push_str("<div class=\"table-wrap\"><table class=\"findings deep\"><thead><tr><th>Kind</th><th>Element</th><th>What MuJoCo did</th></tr></thead><tbody>\n");
    for change in deep.simulator_changes.iter().take(MAX_ROWS) {
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td><code>{}</code></td><td class=\"msg\">{}</td></tr>",
            escape(&change.kind),
            escape(&change.element),
            escape(&change.message)
        );
    }
    out.push_str("</tbody></table></div>\n");
    more(out, deep.simulator_changes.len(), "changes");
}

/// A gravity force to the µN·m, without a minus sign on zero.
fn torque(t: f64) -> String {
    let s = format!("{t:.6}");
    match s.strip_prefix('-') {
        Some(magnitude) if magnitude.bytes().all(|b| b == b'0' || b == b'.') => {
            magnitude.to_string()
        }
        _ => s,
    }
}

fn more(out: &mut String, total: usize, what: &str) {
    if total > MAX_ROWS {
        let _ = writeln!(
            out,
            "<p class=\"key\">{} more {what} in the JSON report.</p>",
            total - MAX_ROWS
        );
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use crate::report::{DeepJoint, SimulatorChange};

    /// A deep section as a cart falling onto its boom would give.
    fn section() -> DeepSection {
        DeepSection {
            status: Status::Fail,
            trigger: "automatic".to_string(),
            simulator: "mujoco".to_string(),
            simulator_version: Some("4.0.0".to_string()),
            python: Some("/usr/bin/python3".to_string()),
            reason: None,
            simulator_changes: vec![SimulatorChange {
                kind: "fused".to_string(),
                element: "boom<1>".to_string(),
                message: "MuJoCo fuses link 'boom' into 'base_link'".to_string(),
            }],
            joints: vec![DeepJoint {
                name: "left_wheel_joint".to_string(),
                mujoco_torque: Some(0.0),
                our_torque: 0.0,
                abs_diff: Some(0.0),
                agrees: true,
                configuration: "zero".to_string(),
            }],
            mujoco_com: Some([0.81, 0.0, 0.155]),
            our_com: Some([0.81, 0.0, 0.155]),
            com_abs_diff: Some(1e-16),
            agreement: Some(true),
            tolerance: 1e-6,
            drop_test: Some(DropTest {
                status: Status::Fail,
                simulated_s: 2.0,
                timestep_s: 0.001,
                base: "free".to_string(),
                max_tilt_deg: Some(12.6),
                final_tilt_deg: Some(11.9),
                com_drift_m: Some(0.034),
                joints_sagging: Vec::new(),
                support_links: vec!["left_wheel".to_string(), "caster".to_string()],
                ground_links: vec!["left_wheel".to_string(), "boom".to_string()],
                fallen_onto: vec!["boom".to_string()],
                agrees_with_stability: Some(false),
                stability_disagreement: Some("Statics and the drop test disagree: <x>".to_string()),
                tilt_trace: (0..=100)
                    .map(|k| [k as f64 * 0.02, 11.9 * (k as f64 / 100.0)])
                    .collect(),
                reason: Some("falls onto boom (11.9° from upright)".to_string()),
            }),
        }
    }

    #[test]
    fn the_panel_plots_the_tilt_names_the_fallen_link_and_says_statics_disagrees() {
        let deep = section();
        let mut html = String::new();
        deep_panel(&mut html, &deep);
        assert!(html.contains("id=\"deep\""));
        assert!(html.contains("id=\"drop-tilt-plot\""));
        // One polyline vertex per trace sample, the last at the end of the plot.
        let at = html
            .find("<polyline class=\"tilt fail\" points=\"")
            .unwrap();
        let points = html[at..].split('"').nth(3).unwrap();
        assert_eq!(points.split(' ').count(), 101);
        assert!(html.contains("11.9° on boom"));
        assert!(html.contains("<span class=\"name fallen\">boom</span>"));
        assert!(html.contains("Statics and the drop test disagree: &lt;x&gt;"));
        assert!(html.contains("<code>boom&lt;1&gt;</code>"), "escaped");
        assert!(html.contains("<code>left_wheel_joint</code>"));
        assert!(html.contains("tips over beyond 15°"));
        let mut card_html = String::new();
        deep_card(&mut card_html, &deep);
        assert!(card_html.contains("href=\"#deep\"") && card_html.contains("drop test FAIL"));
    }

    #[test]
    fn a_torque_rounded_to_zero_has_no_sign() {
        assert_eq!(torque(-1e-9), "0.000000");
        assert_eq!(torque(-0.5), "-0.500000");
        assert_eq!(torque(2.0), "2.000000");
    }

    #[test]
    fn without_a_trace_or_a_drop_test_the_panel_still_renders() {
        let mut deep = section();
        deep.drop_test.as_mut().unwrap().tilt_trace.clear();
        let mut html = String::new();
        deep_panel(&mut html, &deep);
        assert!(!html.contains("drop-tilt-plot") && html.contains("No tilt trace"));
        deep.drop_test = None;
        deep.status = Status::Unknown;
        deep.reason = Some("MuJoCo was not found".to_string());
        let mut html = String::new();
        deep_panel(&mut html, &deep);
        assert!(html.contains("MuJoCo was not found") && html.ends_with("</section>\n"));
    }
}
