//! The solid a mesh bounds: its volume integrals (volume, first and second moments) by the divergence
//! theorem, summing signed tetrahedra from a reference point to each triangle, as Drake's
//! `CalcSpatialInertia` does for a triangle surface mesh.
//!
//! The theorem holds for any closed surface: every edge walked once in each direction (so a surface's
//! triangles, wound consistently, cancel on every edge). A surface that is not closed (holes, flipped
//! triangles, a soup of separate pieces with open borders) has no inside: the loader then integrates its
//! convex hull instead and says so ([`SolidSource`]).

use std::collections::HashMap;

/// ∫dV, ∫x dV and ∫x xᵀ dV over a solid, in the frame its points are given in (metres).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct VolumeIntegrals {
    /// Volume, m³.
    pub volume: f64,
    /// First moments ∫x dV, m⁴ (the centroid times the volume).
    pub first: [f64; 3],
    /// Second moments ∫xᵢxⱼ dV, m⁵ (symmetric).
    pub second: [[f64; 3]; 3],
}

/// Which solid a mesh's [`VolumeIntegrals`] are of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolidSource {
    /// The mesh's own surface, closed and consistently wound.
    ClosedSurface,
    /// The convex hull of its vertices: the surface is not closed (or not consistently wound).
    HullOfOpenSurface,
    /// The convex hull of its vertices: the format's triangles are not read (COLLADA).
    HullSurfaceNotRead,
}

impl SolidSource {
    /// A few words on what was integrated, for messages (`its closed surface`).
    pub fn describe(self) -> &'static str {
        match self {
            SolidSource::ClosedSurface => "its closed surface",
            SolidSource::HullOfOpenSurface => {
                "its convex hull (the surface is not closed, so it encloses no volume of its own)"
            }
            SolidSource::HullSurfaceNotRead => {
                "its convex hull (COLLADA triangles are not read, only its vertices)"
            }
        }
    }
}

/// A mesh's solid: its volume integrals, and what they integrate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshSolid {
    /// The integrals, in the mesh file's frame (metres, before the URDF `scale`).
    pub integrals: VolumeIntegrals,
    /// What was integrated.
    pub source: SolidSource,
}

impl VolumeIntegrals {
    /// The integrals over the solid bounded by `triangles` (indices into `points`, wound
    /// counter-clockwise seen from outside), relative to the frame of `points`. A surface wound inwards
    /// throughout gives a negative volume; the caller decides what to make of it.
    pub fn of_surface(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Option<VolumeIntegrals> {
        // Tetrahedra from a point near the surface keep the terms small (rounding), then shift back.
        let reference = centre(points)?;
        let mut out = VolumeIntegrals::default();
        for t in triangles {
            let [a, b, c] = t.map(|i| points.get(i as usize).map(|p| sub(*p, reference)));
            let (a, b, c) = (a?, b?, c?);
            let det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]);
            let volume = det / 6.0;
            out.volume += volume;
            let sum = [a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]];
            for i in 0..3 {
                out.first[i] += volume * sum[i] / 4.0;
                for j in 0..3 {
                    // ∫ xᵢxⱼ over a tetrahedron with a vertex at the origin: V/20 (Σ vᵢvⱼ + sᵢsⱼ).
                    let products = a[i] * a[j] + b[i] * b[j] + c[i] * c[j];
                    out.second[i][j] += volume / 20.0 * (products + sum[i] * sum[j]);
                }
            }
        }
        Some(out.translated(reference))
    }

    /// The same solid moved by `offset` (every point x becomes x + offset).
    pub fn translated(&self, offset: [f64; 3]) -> VolumeIntegrals {
        let mut out = *self;
        for i in 0..3 {
            out.first[i] = self.first[i] + self.volume * offset[i];
            for j in 0..3 {
                out.second[i][j] = self.second[i][j]
                    + offset[i] * self.first[j]
                    + self.first[i] * offset[j]
                    + self.volume * offset[i] * offset[j];
            }
        }
        out
    }

    /// The same solid under the linear map `m` (x becomes m x): a rotation, a scale, a mirror. The
    /// volume scales by |det m| (a mirrored solid is still a solid).
    pub fn transformed(&self, m: [[f64; 3]; 3]) -> VolumeIntegrals {
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        let jacobian = det.abs();
        let mut out = VolumeIntegrals {
            volume: self.volume * jacobian,
            ..VolumeIntegrals::default()
        };
        for i in 0..3 {
            out.first[i] = jacobian * (0..3).map(|k| m[i][k] * self.first[k]).sum::<f64>();
            for j in 0..3 {
                let mut s = 0.0;
                for k in 0..3 {
                    for l in 0..3 {
                        s += m[i][k] * self.second[k][l] * m[j][l];
                    }
                }
                out.second[i][j] = jacobian * s;
            }
        }
        out
    }

    /// The sum of two solids' integrals (their union when they do not overlap).
    pub fn plus(&self, other: &VolumeIntegrals) -> VolumeIntegrals {
        let mut out = *self;
        out.volume += other.volume;
        for i in 0..3 {
            out.first[i] += other.first[i];
            for j in 0..3 {
                out.second[i][j] += other.second[i][j];
            }
        }
        out
    }

    /// Whether every number is finite.
    pub fn is_finite(&self) -> bool {
        self.volume.is_finite()
            && self.first.iter().all(|v| v.is_finite())
            && self.second.iter().flatten().all(|v| v.is_finite())
    }
}

/// Whether `triangles` form a closed, consistently wound surface: every edge is walked as often in one
/// direction as in the other (triangles with a repeated vertex bound nothing and are left out). This is
/// exactly when the divergence theorem applies: the triangles bound a volume.
pub fn is_closed(triangles: &[[u32; 3]]) -> bool {
    let mut balance: HashMap<(u32, u32), i64> = HashMap::with_capacity(triangles.len() * 3 / 2);
    let mut any = false;
    for &[a, b, c] in triangles {
        if a == b || b == c || a == c {
            continue;
        }
        any = true;
        for (u, v) in [(a, b), (b, c), (c, a)] {
            // Count u→v as +1 on the unordered edge {u, v} keyed low→high, v→u as −1.
            let (key, step) = if u < v { ((u, v), 1) } else { ((v, u), -1) };
            *balance.entry(key).or_insert(0) += step;
        }
    }
    any && balance.values().all(|&b| b == 0)
}

fn centre(points: &[[f64; 3]]) -> Option<[f64; 3]> {
    let first = points.first()?;
    let (mut low, mut high) = (*first, *first);
    for p in points {
        for k in 0..3 {
            low[k] = low[k].min(p[k]);
            high[k] = high[k].max(p[k]);
        }
    }
    Some([0, 1, 2].map(|k| 0.5 * (low[k] + high[k])))
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cube [0, 1]³, wound outwards.
    fn cube() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        let points = (0..8)
            .map(|i| {
                [
                    f64::from(i & 1),
                    f64::from((i >> 1) & 1),
                    f64::from((i >> 2) & 1),
                ]
            })
            .collect();
        #[rustfmt::skip]
        let triangles = vec![
            [0, 2, 1], [1, 2, 3], // z = 0
            [4, 5, 6], [5, 7, 6], // z = 1
            [0, 1, 4], [1, 5, 4], // y = 0
            [2, 6, 3], [3, 6, 7], // y = 1
            [0, 4, 2], [2, 4, 6], // x = 0
            [1, 3, 5], [3, 7, 5], // x = 1
        ];
        (points, triangles)
    }

    #[test]
    fn a_unit_cube_integrates_exactly() {
        let (points, triangles) = cube();
        assert!(is_closed(&triangles));
        let s = VolumeIntegrals::of_surface(&points, &triangles).unwrap();
        assert!((s.volume - 1.0).abs() < 1e-15);
        for i in 0..3 {
            assert!((s.first[i] - 0.5).abs() < 1e-15);
            for j in 0..3 {
                let expected = if i == j { 1.0 / 3.0 } else { 0.25 };
                assert!((s.second[i][j] - expected).abs() < 1e-15, "{i}{j}");
            }
        }
    }

    #[test]
    fn a_missing_or_flipped_triangle_opens_the_surface() {
        let (_, mut triangles) = cube();
        triangles.pop();
        assert!(!is_closed(&triangles));
        let (_, mut flipped) = cube();
        flipped[0].swap(1, 2);
        assert!(!is_closed(&flipped));
        assert!(!is_closed(&[]));
    }

    #[test]
    fn a_mirror_keeps_the_volume_positive_and_mirrors_the_moments() {
        let (points, triangles) = cube();
        let s = VolumeIntegrals::of_surface(&points, &triangles).unwrap();
        let m = s.transformed([[-2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        assert!((m.volume - 2.0).abs() < 1e-15);
        assert!((m.first[0] + 2.0).abs() < 1e-15, "centroid at x = -1");
        assert!((m.second[0][0] - 2.0 * 4.0 / 3.0).abs() < 1e-14);
        assert!((m.second[0][1] + 2.0 * 2.0 * 0.25).abs() < 1e-15);
    }
}
