//! The support polygon and the stability metrics over it: signed COM margin, tip direction, tipping angle,
//! minimum width.

/// A point on the ground plane (x forward, y left).
pub type Point2 = [f64; 2];

/// Width below which a hull is a line, m: supports collinear up to rounding (two wheels on one axle whose
/// contact points differ by nanometres) carry no area, whatever their length.
const MIN_LINE_WIDTH: f64 = 1e-3;

/// Width below which a hull is a line, as a fraction of its diameter (large robots round coarser).
const LINE_WIDTH_PER_DIAMETER: f64 = 1e-3;

/// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain). Fewer than three
/// points come back as they are (deduplicated).
pub fn convex_hull(points: &[Point2]) -> Vec<Point2> {
    let mut sorted: Vec<Point2> = points
        .iter()
        .copied()
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .collect();
    sorted.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    sorted.dedup_by(|a, b| (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
    if sorted.len() < 3 {
        return sorted;
    }
    let cross = |o: Point2, a: Point2, b: Point2| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<Point2> = Vec::with_capacity(2 * sorted.len());
    for pass in [sorted.clone(), sorted.iter().rev().copied().collect()] {
        let start = hull.len();
        for p in pass {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 1e-15
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// The largest distance between two of the hull's points, metres.
fn diameter(hull: &[Point2]) -> f64 {
    hull.iter()
        .flat_map(|a| hull.iter().map(move |b| (a[0] - b[0]).hypot(a[1] - b[1])))
        .fold(0.0, f64::max)
}

/// The smallest distance between two parallel lines enclosing the hull (0 for fewer than three points).
fn width(hull: &[Point2]) -> f64 {
    if hull.len() < 3 {
        return 0.0;
    }
    edges(hull)
        .map(|(a, _, n)| {
            hull.iter()
                .map(|q| -((q[0] - a[0]) * n[0] + (q[1] - a[1]) * n[1]))
                .fold(0.0, f64::max)
        })
        .min_by(f64::total_cmp)
        .unwrap_or(0.0)
}

/// The width below which supports count as a line: 1 mm, or a thousandth of the hull's diameter when
/// that is more.
fn line_tolerance(hull: &[Point2]) -> f64 {
    MIN_LINE_WIDTH.max(LINE_WIDTH_PER_DIAMETER * diameter(hull))
}

/// True when the hull encloses an area: at least three points, wider than [`line_tolerance`].
pub fn is_polygon(hull: &[Point2]) -> bool {
    hull.len() >= 3 && width(hull) > line_tolerance(hull)
}

/// The width of a hull that [`is_polygon`] refuses (points on a line up to rounding), metres.
pub fn degenerate_width(hull: &[Point2]) -> f64 {
    width(hull)
}

/// Edges as (start, end, outward unit normal).
fn edges(hull: &[Point2]) -> impl Iterator<Item = (Point2, Point2, Point2)> + '_ {
    (0..hull.len()).filter_map(move |i| {
        let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let length = dx.hypot(dy);
        (length > 0.0).then_some((a, b, [dy / length, -dx / length]))
    })
}

/// Where the COM's projection sits relative to a support polygon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Margin {
    /// Signed distance to the boundary, metres: positive inside.
    pub distance: f64,
    /// Outward normal of the nearest edge: the direction the robot would tip.
    pub tip_normal: Point2,
}

/// Signed distance from `p` to the boundary of a counter-clockwise convex polygon, and the nearest edge's
/// outward normal.
pub fn margin(hull: &[Point2], p: Point2) -> Option<Margin> {
    if !is_polygon(hull) {
        return None;
    }
    let inside = edges(hull).all(|(a, _, n)| (p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1] <= 0.0);
    let nearest = edges(hull)
        .map(|(a, b, n)| {
            // Distance to the segment (outside) or to the edge's line (inside: the nearest line is on the boundary).
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let t =
                (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
            let segment = (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy);
            let line = -((p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1]);
            (if inside { line } else { segment }, n)
        })
        .min_by(|x, y| x.0.total_cmp(&y.0))?;
    Some(Margin {
        distance: if inside { nearest.0 } else { -nearest.0 },
        tip_normal: nearest.1,
    })
}

/// The smallest angle the robot must be tilted by to bring its COM over an edge: min over edges of
/// atan(d / h), with `d` the distance from the COM projection to the edge line and `h` the COM height.
pub fn tipping_angle(hull: &[Point2], p: Point2, height: f64) -> Option<f64> {
    if !is_polygon(hull) || height <= 0.0 {
        return None;
    }
    edges(hull)
        .map(|(a, _, n)| (-((p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1])).atan2(height))
        .min_by(f64::total_cmp)
}

/// The polygon's minimum width (smallest distance between two parallel supporting lines).
pub fn min_width(hull: &[Point2]) -> Option<f64> {
    is_polygon(hull).then(|| width(hull))
}

/// Compass name of a ground-plane direction in the robot frame (x front, y left).
pub fn direction_name(normal: Point2) -> &'static str {
    const NAMES: [&str; 8] = [
        "front",
        "front-left",
        "left",
        "back-left",
        "back",
        "back-right",
        "right",
        "front-right",
    ];
    let angle = normal[1].atan2(normal[0]).to_degrees().rem_euclid(360.0);
    NAMES[((angle + 22.5) / 45.0) as usize % 8]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<Point2> {
        convex_hull(&[
            [-0.3, -0.2],
            [0.3, -0.2],
            [0.3, 0.2],
            [-0.3, 0.2],
            [0.0, 0.0],
        ])
    }

    #[test]
    fn hull_drops_interior_and_collinear_points() {
        assert_eq!(square().len(), 4);
        assert!(!is_polygon(&convex_hull(&[
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0]
        ])));
    }

    #[test]
    fn supports_on_a_line_up_to_rounding_are_no_polygon() {
        // Two wheels on one axle, their rim points 88 nm off the line (the area, 2.6e-8 m², passed the old
        // area test and gave a margin of -5 mm): a line, like exactly collinear points.
        let wheels = convex_hull(&[[0.0, -0.16], [0.0, -0.14], [88e-9, 0.14], [88e-9, 0.16]]);
        assert!(!is_polygon(&wheels));
        assert!(margin(&wheels, [0.05, 0.0]).is_none());
        assert!(degenerate_width(&wheels) < 1e-6);
        // A narrow but real polygon (2 mm by 30 cm) stays one; a 30 m one must be 3 cm wide.
        assert!(is_polygon(&convex_hull(&[
            [0.0, -0.15],
            [0.002, -0.15],
            [0.0, 0.15],
            [0.002, 0.15]
        ])));
        assert!(!is_polygon(&convex_hull(&[
            [0.0, -15.0],
            [0.02, -15.0],
            [0.0, 15.0],
            [0.02, 15.0]
        ])));
    }

    #[test]
    fn margin_inside_and_outside() {
        let hull = square();
        let m = margin(&hull, [0.1, 0.0]).unwrap();
        assert!(
            (m.distance - 0.2).abs() < 1e-12,
            "nearest edges are y = ±0.2 and x = 0.3"
        );
        let m = margin(&hull, [0.25, 0.0]).unwrap();
        assert!((m.distance - 0.05).abs() < 1e-12);
        assert_eq!(direction_name(m.tip_normal), "front");
        let m = margin(&hull, [0.4, 0.3]).unwrap();
        assert!(
            (m.distance + 0.1f64.hypot(0.1)).abs() < 1e-12,
            "outside: distance to the corner"
        );
    }

    #[test]
    fn tipping_angle_and_width() {
        let hull = square();
        let angle = tipping_angle(&hull, [0.0, 0.0], 0.4).unwrap();
        assert!((angle - (0.2f64 / 0.4).atan()).abs() < 1e-12);
        assert!((min_width(&hull).unwrap() - 0.4).abs() < 1e-12);
    }

    #[test]
    fn compass_names() {
        assert_eq!(direction_name([0.0, 1.0]), "left");
        assert_eq!(direction_name([-1.0, -1.0]), "back-right");
        assert_eq!(direction_name([1.0, -0.1]), "front");
    }
}
