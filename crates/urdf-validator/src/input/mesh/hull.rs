//! A mesh's convex hull: the vertices whitened, filtered and thinned, then a checked quickhull.

use std::collections::{HashMap, HashSet};

use nalgebra::SymmetricEigen;

use super::{bits, bounds, surface, HULL_EXACT_LIMIT};

/// Above this many vertices, points provably inside the hull are dropped before quickhull.
const HULL_PREFILTER_MIN: usize = 64;
/// Largest points × hull faces product for which every point is checked to be inside the hull.
const HULL_CONTAINMENT_CHECK_LIMIT: usize = 2_000_000;
/// Grid resolution (cells per axis) of the first thinning step above [`HULL_EXACT_LIMIT`].
const HULL_GRID_CELLS: u32 = 128;
/// A point cloud whose smallest principal variance is below this fraction of the largest is flat.
const FLAT_VARIANCE_RATIO: f64 = 1e-12;

/// See [`MeshData::hull`](super::MeshData::hull).
pub(super) fn convex_hull(vertices: &[[f64; 3]], aabb: ([f64; 3], [f64; 3])) -> Vec<[f64; 3]> {
    if vertices.len() < 4 {
        return Vec::new();
    }
    let Some(white) = whiten(vertices, aabb) else {
        return Vec::new();
    };
    let mut candidates: Vec<usize> = if white.len() > HULL_PREFILTER_MIN {
        prefilter(&white, (0..white.len()).collect())
    } else {
        (0..white.len()).collect()
    };
    let mut cells = HULL_GRID_CELLS;
    while candidates.len() > HULL_EXACT_LIMIT && cells >= 2 {
        candidates = prefilter(&white, thin_on_grid(&white, &candidates, cells));
        cells /= 2;
    }
    // parry's quickhull is not robust to exactly coplanar points (it can return a broken surface
    // that leaves true hull vertices out), so the points are joggled (as qhull's `QJ` does) and the
    // result is checked; a second, larger joggle is the fallback.
    for jitter in [1e-9, 1e-7] {
        let points: Vec<[f64; 3]> = joggle(candidates.iter().map(|&i| white[i]), jitter);
        let parry_points: Vec<parry3d_f64::math::Vector> =
            points.iter().map(|&p| to_parry(p)).collect();
        let Some((hull_points, faces)) = run_hull(&parry_points) else {
            continue;
        };
        let corners: Vec<[f64; 3]> = hull_points.iter().map(|p| [p.x, p.y, p.z]).collect();
        let Some(normals) = convex_hull_planes(&corners, &faces, &points, 10.0 * jitter) else {
            continue;
        };
        // parry returns copies of its input points: map them back to the original vertices.
        let index: HashMap<[u64; 3], usize> = candidates
            .iter()
            .zip(&points)
            .map(|(&i, &p)| (bits(p), i))
            .collect();
        let hull: Vec<[f64; 3]> = extreme_corners(corners.len(), &faces, &normals)
            .into_iter()
            .filter_map(|c| index.get(&bits(corners[c])))
            .map(|&i| vertices[i])
            .collect();
        if hull.len() >= 4 {
            return hull;
        }
    }
    Vec::new()
}

/// The points moved by up to ±`jitter`/2 per coordinate (deterministic pseudo-random).
fn joggle(points: impl Iterator<Item = [f64; 3]>, jitter: f64) -> Vec<[f64; 3]> {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        // xorshift64
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * jitter
    };
    points
        .map(|p| [p[0] + next(), p[1] + next(), p[2] + next()])
        .collect()
}

/// The outward unit normals of `faces` (in order) if they form, over `corners`, a closed,
/// consistently oriented, locally convex surface (hence a convex polyhedron) that, when that is
/// cheap enough to check, contains every one of `points` (within `tolerance`).
fn convex_hull_planes(
    corners: &[[f64; 3]],
    faces: &[[u32; 3]],
    points: &[[f64; 3]],
    tolerance: f64,
) -> Option<Vec<[f64; 3]>> {
    let ok = |b: bool| b.then_some(());
    ok(corners.len() >= 4 && faces.len() >= 4)?;
    let corner = |i: u32| corners.get(i as usize).copied();
    let mut centroid = [0.0; 3];
    for &c in corners {
        centroid = add(centroid, c);
    }
    let centroid = scale(centroid, 1.0 / corners.len() as f64);
    // Normals oriented by the winding; all must agree on which side the centroid is.
    let mut planes = Vec::with_capacity(faces.len());
    let mut edges: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * faces.len());
    let mut sign = 0.0;
    for (f, face) in faces.iter().enumerate() {
        let (a, b, c) = (corner(face[0])?, corner(face[1])?, corner(face[2])?);
        let normal = cross(sub(b, a), sub(c, a));
        let length = norm(normal);
        let normal = if length > 0.0 {
            scale(normal, 1.0 / length)
        } else {
            [0.0; 3]
        };
        let side = dot(normal, sub(centroid, a));
        if length > 0.0 && side.abs() > tolerance {
            if sign == 0.0 {
                sign = side.signum();
            } else {
                ok(side.signum() == sign)?;
            }
        }
        planes.push((normal, a));
        for k in 0..3 {
            // A directed edge used twice: not a consistently oriented manifold.
            ok(edges.insert((face[k], face[(k + 1) % 3]), f).is_none())?;
        }
    }
    ok(sign != 0.0)?;
    // Outward normals point away from the centroid.
    let planes: Vec<([f64; 3], [f64; 3])> = planes
        .into_iter()
        .map(|(normal, a)| (scale(normal, -sign), a))
        .collect();
    // Closed (every edge has its reverse) and locally convex (each neighbour's far corner is behind).
    for (&(from, to), &f) in &edges {
        let g = *edges.get(&(to, from))?;
        let far = faces[g].iter().copied().find(|&v| v != from && v != to)?;
        let (normal, a) = planes[f];
        ok(dot(normal, sub(corner(far)?, a)) <= tolerance)?;
    }
    // Euler characteristic of a sphere.
    let used: HashSet<u32> = faces.iter().flatten().copied().collect();
    ok(used.len() as i64 - (edges.len() / 2) as i64 + faces.len() as i64 == 2)?;
    // Every point inside, when affordable (otherwise the surface checks above stand alone).
    if points.len().saturating_mul(planes.len()) <= HULL_CONTAINMENT_CHECK_LIMIT {
        for &p in points {
            ok(planes
                .iter()
                .all(|&(normal, a)| dot(normal, sub(p, a)) <= tolerance))?;
        }
    }
    Some(planes.into_iter().map(|(normal, _)| normal).collect())
}

/// Indices of the corners that are vertices of the polyhedron: those whose incident faces' normals
/// span three dimensions. Corners inside a flat facet or on a straight edge (as joggling can leave)
/// are dropped.
fn extreme_corners(count: usize, faces: &[[u32; 3]], normals: &[[f64; 3]]) -> Vec<usize> {
    // Sine of the smallest angle between facets that still makes a corner.
    const DISTINCT: f64 = 1e-6;
    let mut incident: Vec<Vec<[f64; 3]>> = vec![Vec::new(); count];
    for (face, &normal) in faces.iter().zip(normals) {
        if norm(normal) > 0.5 {
            for &v in face {
                if let Some(list) = incident.get_mut(v as usize) {
                    list.push(normal);
                }
            }
        }
    }
    (0..count)
        .filter(|&c| {
            let list = &incident[c];
            let Some(&first) = list.first() else {
                return false;
            };
            let Some(second) = list
                .iter()
                .copied()
                .find(|&n| norm(cross(first, n)) > DISTINCT)
            else {
                return false;
            };
            let edge = cross(first, second);
            let edge = scale(edge, 1.0 / norm(edge));
            list.iter().any(|&n| dot(edge, n).abs() > DISTINCT)
        })
        .collect()
}

/// The vertices whitened (centred, then scaled along the principal axes to unit variance), or `None`
/// if they are flat (smallest principal variance below [`FLAT_VARIANCE_RATIO`] of the largest) or
/// not finite.
fn whiten(vertices: &[[f64; 3]], aabb: ([f64; 3], [f64; 3])) -> Option<Vec<[f64; 3]>> {
    // Hot loops use plain arrays: nalgebra is slow in unoptimised (test) builds.
    let (min, max) = aabb;
    let center = [
        0.5 * (min[0] + max[0]),
        0.5 * (min[1] + max[1]),
        0.5 * (min[2] + max[2]),
    ];
    let diag = norm(sub(max, min));
    if !diag.is_finite() || diag <= 0.0 || !center.iter().all(|c| c.is_finite()) {
        return None;
    }
    // Normalised coordinates (within ±0.5) keep the covariance from overflowing.
    let normalised = |v: &[f64; 3]| scale(sub(*v, center), 1.0 / diag);
    let n = vertices.len() as f64;
    let mut mean = [0.0; 3];
    for v in vertices {
        mean = add(mean, normalised(v));
    }
    let mean = scale(mean, 1.0 / n);
    let mut c = [[0.0; 3]; 3];
    for v in vertices {
        let d = sub(normalised(v), mean);
        for (row, &di) in c.iter_mut().zip(&d) {
            for (cell, &dj) in row.iter_mut().zip(&d) {
                *cell += di * dj;
            }
        }
    }
    let covariance = nalgebra::Matrix3::from_fn(|i, j| c[i][j] / n);
    // Bounded iterations (the default is unbounded); a 3×3 matrix converges in a handful.
    let eigen = SymmetricEigen::try_new(covariance, f64::EPSILON, 10_000)?;
    let largest = eigen.eigenvalues.max();
    let smallest = eigen.eigenvalues.min();
    if !(largest > 0.0 && smallest > largest * FLAT_VARIANCE_RATIO) {
        return None;
    }
    // Whitening: an invertible affine map, so hull vertices map to hull vertices. Row k of `w` is
    // eigenvector k divided by the square root of its eigenvalue.
    let w: [[f64; 3]; 3] = std::array::from_fn(|k| {
        let axis = eigen.eigenvectors.column(k);
        let s = 1.0 / eigen.eigenvalues[k].sqrt();
        [axis[0] * s, axis[1] * s, axis[2] * s]
    });
    let white: Vec<[f64; 3]> = vertices
        .iter()
        .map(|v| {
            let d = sub(normalised(v), mean);
            [dot(w[0], d), dot(w[1], d), dot(w[2], d)]
        })
        .collect();
    if !white.iter().all(|p| p.iter().all(|c| c.is_finite())) {
        return None;
    }
    Some(white)
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn to_parry(p: [f64; 3]) -> parry3d_f64::math::Vector {
    parry3d_f64::math::Vector::new(p[0], p[1], p[2])
}

/// A hull's vertices and triangles, as parry's quickhull gives them.
pub(crate) type HullResult = (Vec<parry3d_f64::math::Vector>, Vec<[u32; 3]>);

/// The triangles of the hull of `hull` (its vertices), by index into `hull`; empty when quickhull fails,
/// returns a point it was not given, or gives a surface that is not closed and convex around every
/// point of `hull` ([`surface::is_closed_convex`]).
pub(super) fn triangulate(hull: &[[f64; 3]]) -> Vec<[u32; 3]> {
    if hull.len() < 4 {
        return Vec::new();
    }
    let points: Vec<parry3d_f64::math::Vector> = hull.iter().map(|&p| to_parry(p)).collect();
    let Some((vertices, triangles)) = run_hull(&points) else {
        return Vec::new();
    };
    if !surface::is_closed_convex(&points, &vertices, &triangles) {
        return Vec::new();
    }
    let index: HashMap<[u64; 3], u32> = hull
        .iter()
        .enumerate()
        .map(|(i, &p)| (bits(p), i as u32))
        .collect();
    let Some(of_vertex) = vertices
        .iter()
        .map(|v| index.get(&bits([v.x, v.y, v.z])).copied())
        .collect::<Option<Vec<u32>>>()
    else {
        return Vec::new();
    };
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| of_vertex.get(v as usize).copied());
            Some([a?, b?, c?])
        })
        .collect::<Option<Vec<_>>>()
        .unwrap_or_default()
}

/// parry's quickhull, with its known panics on degenerate input (dimforge/parry#49) turned into `None`
/// as a last resort (this module's inputs are whitened and non-flat, so it is not expected to trigger
/// here; the collision shapes use it too).
pub(crate) fn run_hull(points: &[parry3d_f64::math::Vector]) -> Option<HullResult> {
    std::panic::catch_unwind(|| parry3d_f64::transformation::try_convex_hull(points))
        .ok()?
        .ok()
}

/// Of the `candidates` (indices into `points`), those that may be hull vertices: all but the points
/// strictly inside the polytope spanned by the extreme points along fixed directions (Akl–Toussaint
/// heuristic; exact).
fn prefilter(points: &[[f64; 3]], candidates: Vec<usize>) -> Vec<usize> {
    let directions = directions();
    let mut best = vec![(f64::NEG_INFINITY, usize::MAX); directions.len()];
    for &i in &candidates {
        let p = points[i];
        for (d, slot) in directions.iter().zip(best.iter_mut()) {
            let s = dot(*d, p);
            if s > slot.0 {
                *slot = (s, i);
            }
        }
    }
    if best.iter().any(|&(_, i)| i == usize::MAX) {
        return candidates;
    }
    let mut extreme: Vec<usize> = best.iter().map(|&(_, i)| i).collect();
    extreme.sort_unstable();
    extreme.dedup();
    // The inner polytope, joggled and checked like the hull itself (see `convex_hull`).
    let inner = joggle(extreme.iter().map(|&i| points[i]), 1e-9);
    let parry_inner: Vec<parry3d_f64::math::Vector> = inner.iter().map(|&p| to_parry(p)).collect();
    let Some((vertices, faces)) = run_hull(&parry_inner) else {
        return candidates;
    };
    let corners: Vec<[f64; 3]> = vertices.iter().map(|v| [v.x, v.y, v.z]).collect();
    let Some(normals) = convex_hull_planes(&corners, &faces, &inner, 1e-8) else {
        return candidates;
    };
    let mut planes = Vec::with_capacity(faces.len());
    for (face, &normal) in faces.iter().zip(&normals) {
        if let Some(&a) = corners.get(face[0] as usize) {
            if norm(normal) > 0.5 {
                planes.push((normal, dot(normal, a)));
            }
        }
    }
    // Whitened points have unit variance, so an absolute margin is meaningful (it also covers the
    // joggle).
    const MARGIN: f64 = 1e-7;
    let mut keep: Vec<usize> = candidates
        .into_iter()
        .filter(|&i| {
            planes
                .iter()
                .any(|&(n, offset)| dot(n, points[i]) > offset - MARGIN)
        })
        .collect();
    keep.extend(&extreme);
    keep.sort_unstable();
    keep.dedup();
    keep
}

/// Of the `candidates`, one per occupied cell of a `cells`³ grid over their bounds: the point
/// farthest from the origin (the whitened centroid). Approximate (see
/// [`MeshData::hull`](super::MeshData::hull)).
fn thin_on_grid(points: &[[f64; 3]], candidates: &[usize], cells: u32) -> Vec<usize> {
    let (min, max) = bounds(&candidates.iter().map(|&i| points[i]).collect::<Vec<_>>());
    let size = sub(max, min).into_iter().fold(0.0, f64::max);
    if !(size.is_finite() && size > 0.0) {
        return candidates.to_vec();
    }
    let top = f64::from(cells - 1);
    let cell = |c: f64| ((c / size * f64::from(cells)).floor()).clamp(0.0, top) as u64;
    let mut best: HashMap<u64, (f64, usize)> = HashMap::new();
    for &i in candidates {
        let d = sub(points[i], min);
        let key = (cell(d[0]) << 42) | (cell(d[1]) << 21) | cell(d[2]);
        let r = dot(points[i], points[i]);
        let slot = best.entry(key).or_insert((r, i));
        if r > slot.0 {
            *slot = (r, i);
        }
    }
    let mut kept: Vec<usize> = best.into_values().map(|(_, i)| i).collect();
    kept.sort_unstable();
    kept
}

/// 98 unit directions: the 26 of the 3×3×3 lattice and 72 on a Fibonacci sphere.
fn directions() -> Vec<[f64; 3]> {
    let mut out = Vec::with_capacity(98);
    for x in -1i32..=1 {
        for y in -1i32..=1 {
            for z in -1i32..=1 {
                let d = [f64::from(x), f64::from(y), f64::from(z)];
                let length = norm(d);
                if length > 0.0 {
                    out.push(scale(d, 1.0 / length));
                }
            }
        }
    }
    let n = 72;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    for i in 0..n {
        let z = 1.0 - 2.0 * (f64::from(i) + 0.5) / f64::from(n);
        let r = (1.0 - z * z).sqrt();
        let phi = golden * f64::from(i);
        out.push([r * phi.cos(), r * phi.sin(), z]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Point3, Rotation3};

    fn cube() -> Vec<[f64; 3]> {
        let mut v = Vec::new();
        for x in [0.0, 1.0] {
            for y in [0.0, 1.0] {
                for z in [0.0, 1.0] {
                    v.push([x, y, z]);
                }
            }
        }
        v
    }

    #[test]
    fn hull_of_cube_with_interior_and_face_points() {
        let mut v = cube();
        v.push([0.5, 0.5, 0.5]);
        v.push([0.5, 0.5, 1.0]);
        v.push([0.25, 0.0, 0.75]);
        let aabb = bounds(&v);
        let hull = convex_hull(&v, aabb);
        assert_eq!(hull.len(), 8, "{hull:?}");
        for h in &hull {
            assert!(cube().contains(h));
        }
    }

    #[test]
    fn flat_and_tiny_inputs_have_no_hull() {
        let square = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.5, 0.0],
        ];
        assert!(convex_hull(&square, bounds(&square)).is_empty());
        let tilted: Vec<[f64; 3]> = (0..50)
            .map(|i| {
                let (a, b) = ((i % 7) as f64, (i / 7) as f64);
                [a, b, 0.3 * a - 0.2 * b]
            })
            .collect();
        assert!(convex_hull(&tilted, bounds(&tilted)).is_empty());
        let three = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert!(convex_hull(&three, bounds(&three)).is_empty());
        let same = vec![[1.0; 3]; 10];
        assert!(convex_hull(&same, bounds(&same)).is_empty());
    }

    #[test]
    fn thin_plate_keeps_all_eight_corners() {
        // 1 m × 1 m × 10 µm: parry alone would see a flat cloud and return 4 corners.
        let mut v = Vec::new();
        for x in [0.0, 1.0] {
            for y in [0.0, 1.0] {
                for z in [0.0, 1e-5] {
                    v.push([x, y, z]);
                }
            }
        }
        // tilt it so that it is not axis-aligned
        let r = Rotation3::from_euler_angles(0.3, -0.4, 0.5);
        let v: Vec<[f64; 3]> = v
            .iter()
            .map(|p| {
                let q = r * Point3::new(p[0], p[1], p[2]);
                [q.x, q.y, q.z]
            })
            .collect();
        assert_eq!(convex_hull(&v, bounds(&v)).len(), 8);
    }

    #[test]
    fn prefilter_keeps_every_hull_vertex() {
        // Points on a sphere and inside it: the filter drops only interior points.
        let mut pts = Vec::new();
        let mut state = 12345u64;
        let mut rand = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        for i in 0..5000 {
            let v = [rand(), rand(), rand()];
            let v = if i % 10 == 0 {
                scale(v, 1.5 / norm(v))
            } else {
                scale(v, 0.5)
            };
            pts.push(v);
        }
        let kept = prefilter(&pts, (0..pts.len()).collect());
        assert!(kept.len() < pts.len() / 2, "{}", kept.len());
        for (i, p) in pts.iter().enumerate() {
            if (norm(*p) - 1.5).abs() < 1e-12 {
                assert!(kept.contains(&i));
            }
        }
    }
}
