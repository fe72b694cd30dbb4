//! The stability panel: the support polygon with the centre of mass over it and the margin to its edge.

use std::fmt::Write;

use super::svg::{n, svg_open, Bounds, Frame};
use super::{escape, pill, status_class};
use crate::report::{Report, StabilitySection};

/// The point of the polygon's boundary nearest to `p`.
fn nearest_on_boundary(polygon: &[[f64; 2]], p: [f64; 2]) -> Option<[f64; 2]> {
    let mut best: Option<(f64, [f64; 2])> = None;
    for (i, &a) in polygon.iter().enumerate() {
        let b = polygon[(i + 1) % polygon.len()];
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = [a[0] + t * dx, a[1] + t * dy];
        let d = (q[0] - p[0]).hypot(q[1] - p[1]);
        if best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, q));
        }
    }
    best.map(|(_, q)| q)
}

pub(super) fn stability_panel(out: &mut String, report: &Report, stability: &StabilitySection) {
    let _ = write!(
        out,
        "<section id=\"stability\" class=\"panel\">\n<h2>Stability {}</h2>\n",
        pill(stability.status)
    );
    let mut facts: Vec<String> = Vec::new();
    if let Some(m) = stability.margin_mm {
        facts.push(format!(
            "margin <b>{m:.1} mm</b>{}",
            stability
                .tip_direction
                .as_deref()
                .map_or(String::new(), |d| format!(
                    " to the nearest edge ({})",
                    escape(d)
                ))
        ));
    }
    if let Some(a) = stability.tipping_angle_deg {
        facts.push(format!("tips at a <b>{a:.1}°</b> tilt"));
    }
    if let (Some(r), Some(c)) = (
        stability.com_height_ratio,
        &stability.com_height_ratio_class,
    ) {
        facts.push(format!("COM height ratio {r:.2} ({})", escape(c)));
    }
    if let Some(h) = stability.com_height {
        facts.push(format!("COM {h:.3} m above the ground"));
    }
    if let Some(source) = &stability.contact_source {
        facts.push(format!(
            "contacts: {} ({})",
            escape(source),
            stability.contact_confidence.label()
        ));
    }
    if !facts.is_empty() {
        let _ = writeln!(out, "<p class=\"facts\">{}</p>", facts.join(" · "));
    }
    if let Some(reason) = &stability.reason {
        let _ = writeln!(out, "<p class=\"note\">{}</p>", escape(reason));
    }
    let com = report
        .statics
        .as_ref()
        .and_then(|s| s.full_body_com)
        .map(|[x, y, _]| [x, y]);
    let polygon = &stability.support_polygon;
    let contacts = &stability.contact_points;
    if polygon.is_empty() && contacts.is_empty() {
        out.push_str("</section>\n");
        return;
    }
    let Some(bounds) = Bounds::of(
        polygon
            .iter()
            .copied()
            .chain(contacts.iter().map(|c| c.position))
            .chain(com)
            .chain([[0.0, 0.0]]),
    ) else {
        out.push_str("</section>\n");
        return;
    };
    out.push_str("<div class=\"plot-row\">\n<figure class=\"figure wide\">");
    let (w, h) = (560.0, 440.0);
    let frame = Frame::equal(bounds.padded(0.12, 0.05), 64.0, 16.0, w - 84.0, h - 64.0);
    svg_open(
        out,
        w,
        h,
        "Support polygon, top view, with the centre of mass",
        "stability-plot",
    );
    frame.axes(out, "x (m) — forward", "y (m) — left");
    let cls = status_class(stability.status);
    if polygon.len() >= 3 {
        let points: Vec<String> = polygon.iter().map(|&p| frame.p(p)).collect();
        let _ = write!(
            out,
            "<polygon class=\"support {cls}\" points=\"{}\"><title>support polygon ({} vertices)</title></polygon>",
            points.join(" "),
            polygon.len()
        );
    } else if polygon.len() == 2 {
        let _ = write!(
            out,
            "<polyline class=\"support {cls}\" points=\"{} {}\"/>",
            frame.p(polygon[0]),
            frame.p(polygon[1])
        );
    }
    for &p in polygon {
        let _ = write!(
            out,
            "<circle class=\"vertex\" cx=\"{}\" cy=\"{}\" r=\"2.5\"/>",
            n(frame.x(p[0])),
            n(frame.y(p[1]))
        );
    }
    // The root frame's origin.
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
    for (k, c) in contacts.iter().enumerate() {
        let (x, y) = (frame.x(c.position[0]), frame.y(c.position[1]));
        let _ = write!(
            out,
            "<g class=\"contact\"><circle cx=\"{}\" cy=\"{}\" r=\"8\"/><text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text><title>{} at ({:.3}, {:.3}) m</title></g>",
            n(x),
            n(y),
            n(x),
            n(y + 3.5),
            k + 1,
            escape(&c.link),
            c.position[0],
            c.position[1]
        );
    }
    if let Some(com) = com {
        let (x, y) = (frame.x(com[0]), frame.y(com[1]));
        if let (Some(foot), Some(m)) = (
            (polygon.len() >= 3)
                .then(|| nearest_on_boundary(polygon, com))
                .flatten(),
            stability.margin_mm,
        ) {
            let (fx, fy) = (frame.x(foot[0]), frame.y(foot[1]));
            let _ = write!(
                out,
                "<line class=\"margin {cls}\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/><text class=\"margin-label {cls}\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{m:.0} mm</text>",
                n(x),
                n(y),
                n(fx),
                n(fy),
                n((x + fx) / 2.0),
                n((y + fy) / 2.0 - 6.0),
            );
        }
        let _ = write!(
            out,
            "<g class=\"com\"><circle cx=\"{x}\" cy=\"{y}\" r=\"7\"/><path d=\"M{x} {} A7 7 0 0 1 {} {y} L{x} {y} Z M{x} {} A7 7 0 0 1 {} {y} L{x} {y} Z\"/><text x=\"{}\" y=\"{}\">COM</text><title>centre of mass projected on the ground: ({:.3}, {:.3}) m</title></g>",
            n(y - 7.0),
            n(frame.x(com[0]) + 7.0),
            n(y + 7.0),
            n(frame.x(com[0]) - 7.0),
            n(frame.x(com[0]) + 10.0),
            n(y - 9.0),
            com[0],
            com[1],
            x = n(x),
            y = n(y),
        );
    }
    out.push_str(if com.is_some() {
        "</svg>\n<figcaption>Support polygon seen from above (root frame), the centre of mass projected on the ground, and the margin to the nearest edge.</figcaption></figure>\n"
    } else {
        "</svg>\n<figcaption>Support polygon seen from above (root frame); the centre of mass is unknown (no declared mass).</figcaption></figure>\n"
    });
    // Legend: numbered contacts, raised contacts.
    out.push_str("<div class=\"legend\">\n");
    if !contacts.is_empty() {
        out.push_str("<h3>Ground contacts</h3>\n<ol class=\"contacts\">");
        for c in contacts {
            let _ = write!(
                out,
                "<li><span class=\"name\">{}</span> <span class=\"muted\">({:.3}, {:.3})</span></li>",
                escape(&c.link),
                c.position[0],
                c.position[1]
            );
        }
        out.push_str("</ol>\n");
    }
    if !stability.raised_contacts.is_empty() {
        out.push_str("<h3>Not touching (the robot rocks)</h3>\n<ul class=\"contacts\">");
        for r in &stability.raised_contacts {
            let _ = write!(
                out,
                "<li><span class=\"name\">{}</span> <span class=\"muted\">{:.1} mm up</span></li>",
                escape(&r.link),
                r.height_mm
            );
        }
        out.push_str("</ul>\n");
    }
    if com.is_some() {
        out.push_str("<p class=\"key\"><span class=\"key-com\"></span> centre of mass <span class=\"key-origin\">+</span> root origin</p>\n");
    } else {
        out.push_str("<p class=\"key\"><span class=\"key-origin\">+</span> root origin</p>\n");
    }
    out.push_str("</div>\n</div>\n</section>\n");
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    #[test]
    fn the_margin_foot_is_the_nearest_boundary_point() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(nearest_on_boundary(&square, [0.5, 0.2]), Some([0.5, 0.0]));
        assert_eq!(nearest_on_boundary(&square, [2.0, 2.0]), Some([1.0, 1.0]));
        assert_eq!(nearest_on_boundary(&[], [0.0, 0.0]), None);
    }
}
