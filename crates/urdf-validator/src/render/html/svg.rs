//! The SVG chart kit the plots share: number formats, data bounds, a frame with axes and ticks.

use std::fmt::Write;

use super::escape;

/// A number for SVG coordinates: one decimal, 0 when not finite.
pub(super) fn n(v: f64) -> String {
    if v.is_finite() {
        let s = format!("{v:.1}");
        if s == "-0.0" {
            "0.0".to_string()
        } else {
            s
        }
    } else {
        "0".to_string()
    }
}

/// A length in metres for labels: 3 decimals.
pub(super) fn metres(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.3} m")
    } else {
        "?".to_string()
    }
}

/// Data bounds of a plot.
#[derive(Clone, Copy, Debug)]
pub(super) struct Bounds {
    pub(super) x0: f64,
    pub(super) x1: f64,
    pub(super) y0: f64,
    pub(super) y1: f64,
}

impl Bounds {
    pub(super) fn of(points: impl IntoIterator<Item = [f64; 2]>) -> Option<Bounds> {
        let mut b: Option<Bounds> = None;
        for [x, y] in points {
            if !(x.is_finite() && y.is_finite()) {
                continue;
            }
            b = Some(match b {
                None => Bounds {
                    x0: x,
                    x1: x,
                    y0: y,
                    y1: y,
                },
                Some(b) => Bounds {
                    x0: b.x0.min(x),
                    x1: b.x1.max(x),
                    y0: b.y0.min(y),
                    y1: b.y1.max(y),
                },
            });
        }
        b
    }

    /// Grown by `fraction` of the larger side on every side (at least `min` metres).
    pub(super) fn padded(self, fraction: f64, min: f64) -> Bounds {
        let pad = ((self.x1 - self.x0).max(self.y1 - self.y0) * fraction).max(min);
        Bounds {
            x0: self.x0 - pad,
            x1: self.x1 + pad,
            y0: self.y0 - pad,
            y1: self.y1 + pad,
        }
    }
}

/// A plot area in pixels over data bounds with equal scales on both axes.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame {
    pub(super) b: Bounds,
    pub(super) left: f64,
    pub(super) top: f64,
    pub(super) width: f64,
    pub(super) height: f64,
}

impl Frame {
    /// The largest plot of `bounds` at equal scale fitting in `width` × `height` pixels at (`left`, `top`);
    /// the data bounds grow on the short side so the plot fills the area.
    pub(super) fn equal(bounds: Bounds, left: f64, top: f64, width: f64, height: f64) -> Frame {
        let dx = (bounds.x1 - bounds.x0).max(1e-6);
        let dy = (bounds.y1 - bounds.y0).max(1e-6);
        let scale = (width / dx).min(height / dy);
        let (cx, cy) = ((bounds.x0 + bounds.x1) / 2.0, (bounds.y0 + bounds.y1) / 2.0);
        let (hx, hy) = (width / scale / 2.0, height / scale / 2.0);
        Frame {
            b: Bounds {
                x0: cx - hx,
                x1: cx + hx,
                y0: cy - hy,
                y1: cy + hy,
            },
            left,
            top,
            width,
            height,
        }
    }

    pub(super) fn x(&self, v: f64) -> f64 {
        self.left + (v - self.b.x0) / (self.b.x1 - self.b.x0) * self.width
    }

    pub(super) fn y(&self, v: f64) -> f64 {
        self.top + self.height - (v - self.b.y0) / (self.b.y1 - self.b.y0) * self.height
    }

    pub(super) fn p(&self, [x, y]: [f64; 2]) -> String {
        format!("{},{}", n(self.x(x)), n(self.y(y)))
    }

    /// Grid lines, tick labels and axis titles.
    pub(super) fn axes(&self, out: &mut String, x_title: &str, y_title: &str) {
        let _ = write!(
            out,
            "<rect class=\"plot-bg\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>",
            n(self.left),
            n(self.top),
            n(self.width),
            n(self.height)
        );
        let target = |px: f64| ((px / 70.0).round() as usize).clamp(2, 10);
        for (v, major) in ticks(self.b.x0, self.b.x1, target(self.width)) {
            let x = self.x(v);
            let _ = write!(
                out,
                "<line class=\"{}\" x1=\"{x}\" y1=\"{}\" x2=\"{x}\" y2=\"{}\"/><text class=\"tick\" x=\"{x}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
                if major { "axis0" } else { "grid" },
                n(self.top),
                n(self.top + self.height),
                n(self.top + self.height + 14.0),
                tick_label(v),
                x = n(x)
            );
        }
        for (v, major) in ticks(self.b.y0, self.b.y1, target(self.height)) {
            let y = self.y(v);
            let _ = write!(
                out,
                "<line class=\"{}\" x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\"/><text class=\"tick\" x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>",
                if major { "axis0" } else { "grid" },
                n(self.left),
                n(self.left + self.width),
                n(self.left - 6.0),
                n(y + 4.0),
                tick_label(v),
                y = n(y)
            );
        }
        let _ = write!(
            out,
            "<rect class=\"frame\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>\
             <text class=\"axis-title\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\
             <text class=\"axis-title\" transform=\"translate({} {}) rotate(-90)\" text-anchor=\"middle\">{}</text>",
            n(self.left),
            n(self.top),
            n(self.width),
            n(self.height),
            n(self.left + self.width / 2.0),
            n(self.top + self.height + 32.0),
            escape(x_title),
            n(self.left - 44.0),
            n(self.top + self.height / 2.0),
            escape(y_title)
        );
    }
}

/// Tick values over `[lo, hi]` at a 1-2-5 step giving about `target` ticks; `true` marks zero.
fn ticks(lo: f64, hi: f64, target: usize) -> Vec<(f64, bool)> {
    let range = hi - lo;
    if !(range.is_finite() && range > 0.0) {
        return Vec::new();
    }
    let raw = range / target.max(1) as f64;
    let magnitude = 10f64.powf(raw.log10().floor());
    let step = match raw / magnitude {
        r if r < 1.5 => 1.0,
        r if r < 3.0 => 2.0,
        r if r < 7.0 => 5.0,
        _ => 10.0,
    } * magnitude;
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last)
        .take(50)
        .map(|k| {
            let v = k as f64 * step;
            (v, k == 0)
        })
        .collect()
}

fn tick_label(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

pub(super) fn svg_open(out: &mut String, width: f64, height: f64, label: &str, id: &str) {
    let _ = write!(
        out,
        "<svg id=\"{id}\" class=\"plot\" viewBox=\"0 0 {} {}\" role=\"img\" aria-label=\"{}\" style=\"max-width:{}px\">",
        n(width),
        n(height),
        escape(label),
        n(width)
    );
}

pub(super) fn horizontal_line(
    out: &mut String,
    frame: &Frame,
    value: f64,
    class: &str,
    label: &str,
) {
    let y = frame.y(value);
    let _ = write!(
        out,
        "<line class=\"{class}-line\" x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\"/><text class=\"{class}-label\" x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>",
        n(frame.left),
        n(frame.left + frame.width),
        n(frame.left + frame.width - 4.0),
        n(frame.y(value) - 4.0),
        escape(label),
        y = n(y)
    );
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    #[test]
    fn ticks_are_round_and_cover_the_range() {
        let t: Vec<f64> = ticks(-0.23, 0.41, 6).into_iter().map(|t| t.0).collect();
        assert_eq!(t, [-0.2, -0.1, 0.0, 0.1, 0.2, 0.30000000000000004, 0.4]);
        assert!(ticks(1.0, 1.0, 5).is_empty());
        assert!(ticks(f64::NAN, 1.0, 5).is_empty());
        assert_eq!(tick_label(0.30000000000000004), "0.3");
        assert_eq!(tick_label(-0.0), "0");
    }
}
