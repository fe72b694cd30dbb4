//! The workspace panel: each arm's sampled reach, in a side and a top view.

use std::fmt::Write;

use super::svg::{horizontal_line, metres, n, svg_open, Bounds, Frame};
use super::{escape, pill};
use crate::analysis::stability::support_polygon::convex_hull;
use crate::report::{ArmWorkspace, Report, WorkspaceSection};

/// Colours of the arms (CSS classes `arm0`…).
const ARM_COLOURS: usize = 6;

pub(super) fn workspace_panel(out: &mut String, report: &Report, workspace: &WorkspaceSection) {
    let _ = write!(
        out,
        "<section id=\"workspace\" class=\"panel\">\n<h2>Workspace {}</h2>\n",
        pill(workspace.status)
    );
    let mut facts: Vec<String> = Vec::new();
    if let Some(r) = workspace.max_reach {
        facts.push(format!("max reach <b>{}</b>", metres(r)));
    }
    if let Some(v) = workspace.vertical_reach {
        facts.push(format!("vertical {}", metres(v)));
    }
    if let Some(h) = workspace.horizontal_reach {
        facts.push(format!("horizontal {}", metres(h)));
    }
    if let Some(f) = workspace.self_collision_free_fraction {
        facts.push(format!("{:.1}% of poses free of self-collision", f * 100.0));
    }
    facts.push(format!(
        "{} samples per arm, seed {} ({})",
        workspace.samples,
        workspace.seed,
        workspace.reach_confidence.label()
    ));
    let _ = writeln!(out, "<p class=\"facts\">{}</p>", facts.join(" · "));
    if let Some(reason) = &workspace.reason {
        let _ = writeln!(out, "<p class=\"note\">{}</p>", escape(reason));
    }
    let arms: Vec<&ArmWorkspace> = workspace
        .arms
        .iter()
        .filter(|a| !a.tip_samples.is_empty())
        .collect();
    if arms.is_empty() {
        out.push_str("</section>\n");
        return;
    }
    let ground = report.stability.as_ref().and_then(|s| s.ground_height);
    let task_z = match (ground, workspace.task_target_height_m) {
        (Some(g), Some(h)) => Some(g + h),
        (None, Some(h)) => Some(h),
        _ => None,
    };
    let polygon = report
        .stability
        .as_ref()
        .map_or(&[][..], |s| s.support_polygon.as_slice());
    let all = || arms.iter().flat_map(|a| a.tip_samples.iter().copied());
    // One scale for every arm, so their envelopes compare.
    let side = Bounds::of(
        all()
            .map(|[x, _, z]| [x, z])
            .chain([[0.0, 0.0]])
            .chain(ground.map(|g| [0.0, g]))
            .chain(task_z.map(|t| [0.0, t])),
    );
    let top = Bounds::of(
        all()
            .map(|[x, y, _]| [x, y])
            .chain([[0.0, 0.0]])
            .chain(polygon.iter().copied()),
    );
    let (Some(side), Some(top)) = (side, top) else {
        out.push_str("</section>\n");
        return;
    };
    let (side, top) = (side.padded(0.06, 0.05), top.padded(0.06, 0.05));
    for (k, arm) in arms.iter().enumerate() {
        let colour = format!("arm{}", k % ARM_COLOURS);
        let _ = write!(
            out,
            "<div class=\"arm\"><h3><span class=\"dot {colour}\"></span>{} <span class=\"muted\">from {} · {} joints · {}</span></h3>\n<p class=\"facts\">reach <b>{}</b> · vertical {} · horizontal {} · from base {}{}</p>\n<div class=\"plot-row\">",
            escape(&arm.tip_link),
            escape(arm.first_joint.as_deref().unwrap_or(&arm.root_link)),
            arm.joints.len(),
            arm.confidence.label(),
            metres(arm.max_reach),
            metres(arm.vertical_reach),
            metres(arm.horizontal_reach),
            metres(arm.reach_from_base),
            arm.self_collision_free_fraction
                .map_or(String::new(), |f| format!(
                    " · {:.1}% free of self-collision",
                    f * 100.0
                )),
        );
        let others: Vec<&ArmWorkspace> = arms
            .iter()
            .copied()
            .filter(|o| !std::ptr::eq(*o, *arm))
            .collect();
        reach_view(
            out,
            &ReachView {
                id: format!("reach-side-{k}"),
                title: "Side view (x–z)",
                bounds: side,
                axes: ("x (m) — forward", "z (m) — up"),
                project: |[x, _, z]| [x, z],
                colour: &colour,
                arm,
                others: &others,
            },
            |frame, out| {
                if let Some(g) = ground {
                    horizontal_line(out, frame, g, "ground", "ground");
                }
                if let (Some(t), Some(name)) = (task_z, &workspace.task) {
                    horizontal_line(
                        out,
                        frame,
                        t,
                        "task",
                        &format!(
                            "task: {name} ({:.2} m)",
                            workspace.task_target_height_m.unwrap_or_default()
                        ),
                    );
                }
            },
        );
        reach_view(
            out,
            &ReachView {
                id: format!("reach-top-{k}"),
                title: "Top view (x–y)",
                bounds: top,
                axes: ("x (m) — forward", "y (m) — left"),
                project: |[x, y, _]| [x, y],
                colour: &colour,
                arm,
                others: &others,
            },
            |frame, out| {
                if polygon.len() >= 3 {
                    let points: Vec<String> = polygon.iter().map(|&p| frame.p(p)).collect();
                    let _ = write!(
                        out,
                        "<polygon class=\"support-ghost\" points=\"{}\"><title>support polygon</title></polygon>",
                        points.join(" ")
                    );
                }
            },
        );
        out.push_str("</div></div>\n");
    }
    let stride = workspace
        .samples
        .div_ceil(crate::analysis::workspace::MAX_TIP_SAMPLES)
        .max(1);
    let which = if stride == 1 {
        "every sampled pose".to_string()
    } else {
        format!("one sampled pose in {stride}")
    };
    let _ = writeln!(
        out,
        "<p class=\"key\">Dots: the tip of {which} (at most {} per arm), in the root frame; the outline is their convex hull{}.</p>",
        crate::analysis::workspace::MAX_TIP_SAMPLES,
        if arms.len() > 1 {
            "; grey dots are the other arms"
        } else {
            ""
        }
    );
    out.push_str("</section>\n");
}

/// One projection of an arm's sampled tips.
struct ReachView<'a, P: Fn([f64; 3]) -> [f64; 2]> {
    id: String,
    title: &'a str,
    bounds: Bounds,
    axes: (&'a str, &'a str),
    project: P,
    colour: &'a str,
    arm: &'a ArmWorkspace,
    others: &'a [&'a ArmWorkspace],
}

fn reach_view<P: Fn([f64; 3]) -> [f64; 2]>(
    out: &mut String,
    view: &ReachView<P>,
    extra: impl FnOnce(&Frame, &mut String),
) {
    let (w, h) = (460.0, 380.0);
    let frame = Frame::equal(view.bounds, 60.0, 12.0, w - 76.0, h - 60.0);
    let _ = write!(
        out,
        "<figure class=\"figure\"><figcaption class=\"view-title\">{}</figcaption>",
        escape(view.title)
    );
    svg_open(
        out,
        w,
        h,
        &format!(
            "{} of the tip positions of {}",
            view.title, view.arm.tip_link
        ),
        &view.id,
    );
    frame.axes(out, view.axes.0, view.axes.1);
    extra(&frame, out);
    out.push_str("<g class=\"ghost\">");
    for other in view.others {
        for &p in &other.tip_samples {
            let [x, y] = (view.project)(p);
            let _ = write!(
                out,
                "<circle cx=\"{}\" cy=\"{}\" r=\"1.4\"/>",
                n(frame.x(x)),
                n(frame.y(y))
            );
        }
    }
    out.push_str("</g>");
    let projected: Vec<[f64; 2]> = view
        .arm
        .tip_samples
        .iter()
        .map(|&p| (view.project)(p))
        .collect();
    let hull = convex_hull(&projected);
    if hull.len() >= 3 {
        let points: Vec<String> = hull.iter().map(|&p| frame.p(p)).collect();
        let _ = write!(
            out,
            "<polygon class=\"envelope {}\" points=\"{}\"/>",
            view.colour,
            points.join(" ")
        );
    }
    let _ = write!(out, "<g class=\"tips {}\">", view.colour);
    for [x, y] in &projected {
        let _ = write!(
            out,
            "<circle cx=\"{}\" cy=\"{}\" r=\"1.8\"/>",
            n(frame.x(*x)),
            n(frame.y(*y))
        );
    }
    out.push_str("</g>");
    let (ox, oy) = (frame.x(0.0), frame.y(0.0));
    let _ = write!(
        out,
        "<g class=\"origin\"><line x1=\"{}\" y1=\"{oy}\" x2=\"{}\" y2=\"{oy}\"/><line x1=\"{ox}\" y1=\"{}\" x2=\"{ox}\" y2=\"{}\"/><title>root frame origin</title></g>",
        n(ox - 6.0),
        n(ox + 6.0),
        n(oy - 6.0),
        n(oy + 6.0),
        ox = n(ox),
        oy = n(oy)
    );
    out.push_str("</svg></figure>");
}
