//! Meshes for the 3-D view: decimated by vertex clustering to a triangle budget, then quantised to
//! 16 bits per coordinate within their bounds and base64-encoded, so a robot's meshes fit in a page.

use serde::Serialize;

/// A triangle mesh ready to draw: positions quantised within `min`..`max`, little-endian, base64.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EncodedMesh {
    /// Lower corner of the bounds, mesh frame, metres (before the URDF `scale`).
    pub min: [f64; 3],
    /// Upper corner.
    pub max: [f64; 3],
    /// Vertex count.
    pub vertices: usize,
    /// Triangle count.
    pub triangles: usize,
    /// Positions: 3 × u16 per vertex, `min + (max − min) · v / 65535`, base64.
    pub positions: String,
    /// Triangle corners: u16 per index when `vertices` ≤ 65536, else u32, base64.
    pub indices: String,
}

/// Triangles of `vertices` (indices into it), clustered on a grid coarse enough to leave at most `budget`
/// triangles: every vertex moves to the mean of its cell, triangles that collapse are dropped. The grid
/// starts at 256 cells along the longest side and halves until the budget is met (2 cells at the least).
/// Out-of-range indices are dropped.
pub fn decimate(
    vertices: &[[f64; 3]],
    triangles: &[[u32; 3]],
    budget: usize,
) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let valid: Vec<[u32; 3]> = triangles
        .iter()
        .copied()
        .filter(|t| t.iter().all(|&i| (i as usize) < vertices.len()))
        .collect();
    if valid.len() <= budget {
        return compact(vertices, &valid);
    }
    let (min, max) = bounds(vertices);
    let extent = (0..3).map(|k| max[k] - min[k]).fold(0.0, f64::max);
    let mut cells = 256usize;
    loop {
        let (v, t) = cluster(vertices, &valid, min, extent / cells as f64);
        if t.len() <= budget || cells <= 2 {
            return (v, t);
        }
        cells /= 2;
    }
}

/// `vertices` and `triangles` keeping only the vertices some triangle uses.
fn compact(vertices: &[[f64; 3]], triangles: &[[u32; 3]]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut map = vec![u32::MAX; vertices.len()];
    let mut out = Vec::new();
    let remapped = triangles
        .iter()
        .map(|t| {
            t.map(|i| {
                let slot = &mut map[i as usize];
                if *slot == u32::MAX {
                    *slot = out.len() as u32;
                    out.push(vertices[i as usize]);
                }
                *slot
            })
        })
        .collect();
    (out, remapped)
}

fn cluster(
    vertices: &[[f64; 3]],
    triangles: &[[u32; 3]],
    min: [f64; 3],
    cell: f64,
) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let cell = if cell > 0.0 && cell.is_finite() {
        cell
    } else {
        1.0
    };
    let mut cells: std::collections::HashMap<[i64; 3], u32> = std::collections::HashMap::new();
    let mut sums: Vec<([f64; 3], f64)> = Vec::new();
    let key_of = |v: &[f64; 3]| [0, 1, 2].map(|k| ((v[k] - min[k]) / cell).floor() as i64);
    let mut map = vec![u32::MAX; vertices.len()];
    let mut out = Vec::new();
    for t in triangles {
        let c = t.map(|i| {
            let i = i as usize;
            if map[i] == u32::MAX {
                let next = sums.len() as u32;
                let id = *cells.entry(key_of(&vertices[i])).or_insert(next);
                if id == next {
                    sums.push(([0.0; 3], 0.0));
                }
                let (sum, n) = &mut sums[id as usize];
                for k in 0..3 {
                    sum[k] += vertices[i][k];
                }
                *n += 1.0;
                map[i] = id;
            }
            map[i]
        });
        if c[0] != c[1] && c[1] != c[2] && c[0] != c[2] {
            out.push(c);
        }
    }
    let points = sums
        .iter()
        .map(|(sum, n)| sum.map(|s| s / n))
        .collect::<Vec<_>>();
    out.sort_unstable();
    out.dedup();
    compact(&points, &out)
}

/// Axis-aligned bounds of the finite `vertices` (zero when there are none).
pub fn bounds(vertices: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    for v in vertices.iter().filter(|v| v.iter().all(|c| c.is_finite())) {
        for k in 0..3 {
            min[k] = min[k].min(v[k]);
            max[k] = max[k].max(v[k]);
        }
    }
    if min[0] > max[0] {
        ([0.0; 3], [0.0; 3])
    } else {
        (min, max)
    }
}

/// Quantise and encode a mesh (indices must be in range, as [`decimate`] leaves them).
pub fn encode(vertices: &[[f64; 3]], triangles: &[[u32; 3]]) -> EncodedMesh {
    let (min, max) = bounds(vertices);
    let mut positions = Vec::with_capacity(vertices.len() * 6);
    for v in vertices {
        for k in 0..3 {
            let span = max[k] - min[k];
            let t = if span > 0.0 && v[k].is_finite() {
                ((v[k] - min[k]) / span).clamp(0.0, 1.0)
            } else {
                0.0
            };
            positions.extend_from_slice(&((t * 65535.0).round() as u16).to_le_bytes());
        }
    }
    let wide = vertices.len() > 65536;
    let mut indices = Vec::with_capacity(triangles.len() * if wide { 12 } else { 6 });
    for &i in triangles.iter().flatten() {
        if wide {
            indices.extend_from_slice(&i.to_le_bytes());
        } else {
            indices.extend_from_slice(&(i as u16).to_le_bytes());
        }
    }
    EncodedMesh {
        min,
        max,
        vertices: vertices.len(),
        triangles: triangles.len(),
        positions: base64(&positions),
        indices: base64(&indices),
    }
}

/// Standard base64 with padding.
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for (k, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[((n >> shift) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A UV sphere of `n` × `n` quads.
    fn sphere(n: u32) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        let mut v = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let (th, ph) = (
                    std::f64::consts::PI * f64::from(i) / f64::from(n),
                    2.0 * std::f64::consts::PI * f64::from(j) / f64::from(n),
                );
                v.push([th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()]);
            }
        }
        let mut t = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let a = i * (n + 1) + j;
                t.push([a, a + n + 1, a + 1]);
                t.push([a + 1, a + n + 1, a + n + 2]);
            }
        }
        (v, t)
    }

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }

    #[test]
    fn decimation_meets_the_budget_and_keeps_the_bounds() {
        let (v, t) = sphere(200);
        assert_eq!(t.len(), 80_000);
        let (dv, dt) = decimate(&v, &t, 2_000);
        assert!(dt.len() <= 2_000 && dt.len() > 200, "{}", dt.len());
        assert!(dt.iter().flatten().all(|&i| (i as usize) < dv.len()));
        let (min, max) = bounds(&dv);
        for k in 0..3 {
            assert!(min[k] < -0.9 && max[k] > 0.9, "{min:?} {max:?}");
        }
    }

    #[test]
    fn small_meshes_are_kept_and_bad_indices_dropped() {
        let v = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [9.0; 3]];
        let (dv, dt) = decimate(&v, &[[0, 1, 2], [0, 1, 7]], 10);
        assert_eq!(dt, vec![[0, 1, 2]]);
        assert_eq!(dv.len(), 3, "the unused vertex is dropped");
    }

    #[test]
    fn encoded_sizes_follow_the_layout() {
        let (v, t) = sphere(10);
        let e = encode(&v, &t);
        assert_eq!((e.vertices, e.triangles), (v.len(), t.len()));
        // 6 bytes per vertex, 4 base64 characters per 3 bytes.
        assert_eq!(e.positions.len(), (v.len() * 6).div_ceil(3) * 4);
        assert_eq!(e.indices.len(), (t.len() * 6).div_ceil(3) * 4);
    }
}
