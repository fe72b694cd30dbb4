//! The surface of a convex hull as a triangulation: checking that it is closed and convex, and its edges
//! as adjacency lists (what a support-map climb walks along).
//!
//! The mesh loader checks a mesh's hull triangulation once, when the mesh is read (before it goes into
//! the disk cache); every collision shape made from that mesh then only builds the adjacency lists, in
//! time linear in the triangles.

use parry3d_f64::math::Vector as DVec3;

/// Tolerance of the convexity test: a point more than this outside a face's plane breaks convexity.
const OUTSIDE: f64 = 1e-9;

/// The edges of a triangulated surface: `neighbours[offsets[v]..offsets[v + 1]]` are the vertices joined
/// to vertex `v` by an edge, in increasing order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SurfaceEdges {
    /// Per vertex, where its neighbours start in `neighbours` (one more entry than vertices).
    pub offsets: Vec<usize>,
    /// Every vertex's neighbours, vertex after vertex.
    pub neighbours: Vec<u32>,
}

impl SurfaceEdges {
    /// The edges of `triangles` over `vertices` vertices; `None` when a triangle names a vertex out of
    /// range.
    pub fn of(vertices: usize, triangles: &[[u32; 3]]) -> Option<SurfaceEdges> {
        let mut degree = vec![0usize; vertices];
        for t in triangles {
            for &v in t {
                *degree.get_mut(v as usize)? += 2;
            }
        }
        let mut offsets = Vec::with_capacity(vertices + 1);
        let mut total = 0;
        offsets.push(0);
        for d in &degree {
            total += d;
            offsets.push(total);
        }
        // Every edge of a closed surface is seen from both of its triangles: fill, then sort and dedup
        // each vertex's list in place.
        let mut fill = offsets.clone();
        let mut all = vec![0u32; total];
        for t in triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                for (from, to) in [(a, b), (b, a)] {
                    let slot = &mut fill[from as usize];
                    all[*slot] = to;
                    *slot += 1;
                }
            }
        }
        // Each vertex's list without repeats (a neighbour is kept where first seen: `seen` holds the last
        // vertex it was seen from), then sorted: half as many to sort as with the repeats.
        let mut neighbours = Vec::with_capacity(total / 2);
        let mut compact = Vec::with_capacity(vertices + 1);
        let mut seen = vec![u32::MAX; vertices];
        compact.push(0);
        for v in 0..vertices {
            let start = neighbours.len();
            for &n in &all[offsets[v]..offsets[v + 1]] {
                let last = &mut seen[n as usize];
                if *last != v as u32 {
                    *last = v as u32;
                    neighbours.push(n);
                }
            }
            neighbours[start..].sort_unstable();
            compact.push(neighbours.len());
        }
        Some(SurfaceEdges {
            offsets: compact,
            neighbours,
        })
    }
}

/// Per triangle of a surface around `vertices` (indices in range): its plane as (unit normal turned away
/// from the vertices' centroid, its first corner), or `None` when it is too thin to have a normal. For a
/// closed convex surface the normals point outwards, whatever the triangles' winding.
pub fn face_planes(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Vec<Option<(DVec3, DVec3)>> {
    let centroid = vertices.iter().copied().sum::<DVec3>() / vertices.len().max(1) as f64;
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| vertices[v as usize]);
            let mut normal = (b - a).cross(c - a);
            if normal.dot(centroid - a) > 0.0 {
                normal = -normal;
            }
            normal.try_normalize().map(|normal| (normal, a))
        })
        .collect()
}

/// True when `triangles` (indices into `vertices`) form a closed surface that is convex across every edge
/// and holds every one of `points` (the points the hull was built from; the vertices are among them).
pub fn is_closed_convex(points: &[DVec3], vertices: &[DVec3], triangles: &[[u32; 3]]) -> bool {
    let n = vertices.len();
    let mut edges: Vec<(u32, u32)> = Vec::with_capacity(triangles.len() * 3);
    for t in triangles {
        if t.iter().any(|&v| v as usize >= n) {
            return false;
        }
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b)));
        }
    }
    edges.sort_unstable();
    // Closed: every edge is shared by exactly two triangles.
    let closed = edges
        .chunks(2)
        .all(|pair| pair.len() == 2 && pair[0] == pair[1])
        && edges.windows(3).all(|w| w[0] != w[2]);
    if !closed || n < 4 {
        return false;
    }
    let planes = face_planes(vertices, triangles);
    let outside = |plane: &Option<(DVec3, DVec3)>, p: DVec3| {
        plane.is_some_and(|(normal, a)| normal.dot(p - a) > OUTSIDE)
    };
    if planes.iter().all(Option::is_some) {
        // A closed surface convex across every edge is convex: checked in O(faces). Its vertices are
        // then inside every face's plane; only the input points that are not vertices (quickhull drops
        // points on edges and faces) are checked against every plane. A degenerate (zero-area) face
        // could hide a fold from its neighbours: then every point is checked.
        let mut sides: Vec<((u32, u32), usize)> = Vec::with_capacity(triangles.len() * 3);
        for (index, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                sides.push(((a.min(b), a.max(b)), index));
            }
        }
        sides.sort_unstable();
        for pair in sides.chunks(2) {
            let [(edge, first), (_, second)] = [pair[0], pair[1]];
            let opposite = |t: usize| {
                let v = triangles[t]
                    .into_iter()
                    .find(|&v| v != edge.0 && v != edge.1);
                vertices[v.unwrap_or(edge.0) as usize]
            };
            if outside(&planes[first], opposite(second))
                || outside(&planes[second], opposite(first))
            {
                return false;
            }
        }
        if vertices.len() != points.len() {
            let bits = |p: &DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
            let mut on_surface: Vec<[u64; 3]> = vertices.iter().map(bits).collect();
            on_surface.sort_unstable();
            let inner = points
                .iter()
                .filter(|p| on_surface.binary_search(&bits(p)).is_err());
            for &p in inner {
                if planes.iter().any(|plane| outside(plane, p)) {
                    return false;
                }
            }
        }
        true
    } else {
        !planes
            .iter()
            .any(|plane| points.iter().any(|&p| outside(plane, p)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tetrahedron's four faces, outward.
    const TETRA: [[u32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];

    fn tetra() -> Vec<DVec3> {
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z]
    }

    #[test]
    fn edges_are_sorted_and_unique_per_vertex() {
        let edges = SurfaceEdges::of(4, &TETRA).unwrap();
        assert_eq!(edges.offsets, vec![0, 3, 6, 9, 12]);
        assert_eq!(edges.neighbours, vec![1, 2, 3, 0, 2, 3, 0, 1, 3, 0, 1, 2]);
        assert_eq!(SurfaceEdges::of(3, &TETRA), None, "vertex 3 out of range");
    }

    /// On random triangle soups (repeated edges, vertices joined to themselves, vertices in no triangle),
    /// each vertex's list is the sorted set of vertices an edge joins it to.
    #[test]
    fn edges_of_any_triangles_are_each_vertexs_sorted_neighbour_set() {
        let mut rng = crate::rng::SplitMix64::new(3);
        for vertices in [1, 2, 5, 12, 40] {
            for _ in 0..50 {
                let triangles: Vec<[u32; 3]> = (0..rng.next_u64() % 60)
                    .map(|_| std::array::from_fn(|_| (rng.next_u64() % vertices) as u32))
                    .collect();
                let edges = SurfaceEdges::of(vertices as usize, &triangles).unwrap();
                let mut expected = vec![std::collections::BTreeSet::new(); vertices as usize];
                for t in &triangles {
                    for k in 0..3 {
                        let (a, b) = (t[k], t[(k + 1) % 3]);
                        expected[a as usize].insert(b);
                        expected[b as usize].insert(a);
                    }
                }
                for (v, set) in expected.iter().enumerate() {
                    let list = &edges.neighbours[edges.offsets[v]..edges.offsets[v + 1]];
                    assert_eq!(list, set.iter().copied().collect::<Vec<_>>(), "vertex {v}");
                }
            }
        }
    }

    #[test]
    fn a_tetrahedron_is_closed_and_convex_and_an_open_or_dented_one_is_not() {
        let v = tetra();
        assert!(is_closed_convex(&v, &v, &TETRA));
        assert!(!is_closed_convex(&v, &v, &TETRA[..3]), "open");
        let mut outside = v.clone();
        outside.push(DVec3::splat(1.0));
        assert!(!is_closed_convex(&outside, &v, &TETRA), "a point outside");
        let mut inside = v.clone();
        inside.push(DVec3::splat(0.1));
        assert!(is_closed_convex(&inside, &v, &TETRA), "a point inside");
    }
}
