//! Convex collision shapes and the narrow phase.
//!
//! Every shape is a convex *core* (a point, a segment, a cylinder or a point cloud standing for its convex
//! hull) grown by a radius: a sphere is a point grown by its radius, a capsule a segment. GJK runs on the
//! cores (parry's implementation, statically dispatched over [`Core`]) and the radii are subtracted
//! afterwards, which is exact for rounded shapes and converges faster than GJK on curved support maps.

use std::cell::Cell;

use nalgebra::{Isometry3, Matrix3, Point3, SymmetricEigen, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::math::{Pose, Rotation, Vector};
use parry3d_f64::query::details::closest_points_support_map_support_map_with_params;
use parry3d_f64::query::epa::EPA;
use parry3d_f64::query::gjk::{self, CsoPoint, GJKResult, VoronoiSimplex};
use parry3d_f64::shape::SupportMap;

use super::enclose::{enclose, Enclosure};
use super::inside::Inside;
use crate::analysis::memo::Fingerprint;
use crate::assets::supports::Support;
use crate::input::mesh::hull;
use crate::input::mesh::surface::{self, SurfaceEdges};

/// Two shapes closer than this (metres) are in contact: touching counts as colliding.
pub const CONTACT_DISTANCE: f64 = 1e-6;

/// Shapes or placements farther than this from the link origin (metres) are treated as unusable: no robot
/// is ten kilometres wide, and bounded coordinates keep every GJK quantity finite.
pub const MAX_EXTENT: f64 = 1e4;

/// The convex part of a shape, in the shape frame.
#[derive(Clone, Debug)]
pub enum Core {
    /// The origin (sphere core).
    Point,
    /// The segment from `-half` to `+half` along z (capsule core).
    Segment {
        /// Half length.
        half: f64,
    },
    /// A solid cylinder along z.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Half length.
        half: f64,
    },
    /// A convex hull.
    Hull(Hull),
}

/// A convex hull as its vertices, with the edges between them when a closed convex triangulation could be
/// built: support queries then climb along edges from a starting vertex instead of scanning every vertex.
#[derive(Clone, Debug)]
pub struct Hull {
    points: Vec<Vector>,
    /// `neighbours[offsets[v]..offsets[v + 1]]` are joined to vertex `v` by an edge; empty: scan.
    offsets: Vec<usize>,
    neighbours: Vec<u32>,
    /// Cells per cube face side of `starts` ([`cube_cells`]).
    cells: usize,
    /// Per cell of a cube map of directions (see [`cube_cell`]): the vertex furthest along the cell's
    /// centre direction, where climbs start; empty when the hull is scanned.
    starts: Vec<u32>,
    /// The vertices by coordinate, for a hull small enough that scanning them all in vector registers
    /// is faster than climbing (and a CPU that has the registers).
    lanes: Option<VertexLanes>,
    /// The planes of the faces of a checked closed convex triangulation, as (outward unit normal,
    /// offset): a point `p` is inside when `normal · p <= offset` for every face. Empty when no such
    /// triangulation could be built (then no sphere is known to be inside, see [`Inside`]), and once a
    /// [`ConvexShape`] has found its inner spheres (their only use).
    faces: Vec<(Vector, f64)>,
}

/// Up to this many vertices, a hull's support queries scan every vertex four at a time (AVX2) instead of
/// climbing: a climb's steps wait on each other and on memory, a scan does not.
#[cfg(target_arch = "x86_64")]
const SCAN_UP_TO: usize = 96;

/// A hull's vertices as coordinate arrays padded to a multiple of 4 with copies of the last vertex (never
/// made off x86_64, where no scan exists).
#[derive(Clone, Debug)]
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
struct VertexLanes {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
}

impl VertexLanes {
    /// The lanes of `points` when they are few enough and this CPU has AVX2.
    fn of(points: &[Vector]) -> Option<VertexLanes> {
        #[cfg(target_arch = "x86_64")]
        if (1..=SCAN_UP_TO).contains(&points.len()) && std::arch::is_x86_feature_detected!("avx2") {
            let padded = points.len().next_multiple_of(4);
            let at = |i: usize| points[i.min(points.len() - 1)];
            return Some(VertexLanes {
                x: (0..padded).map(|i| at(i).x).collect(),
                y: (0..padded).map(|i| at(i).y).collect(),
                z: (0..padded).map(|i| at(i).z).collect(),
            });
        }
        let _ = points;
        None
    }

    /// The first vertex furthest along `dir` (the first one when `dir` is not a number).
    fn furthest(&self, dir: Vector) -> usize {
        #[cfg(target_arch = "x86_64")]
        {
            // SAFETY: lanes exist only where AVX2 was detected (`VertexLanes::of`).
            unsafe { self.furthest_avx2(dir) }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            let _ = dir;
            0
        }
    }

    /// [`VertexLanes::furthest`]: the largest of the dot products, four at a time, then the first lane
    /// holding it (the dot products computed again the same way, so equal to the bit).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn furthest_avx2(&self, dir: Vector) -> usize {
        use std::arch::x86_64::*;
        let (dx, dy, dz) = (
            _mm256_set1_pd(dir.x),
            _mm256_set1_pd(dir.y),
            _mm256_set1_pd(dir.z),
        );
        let dot = |i: usize| {
            // SAFETY: `i + 4 <= len` for every `i` the loops below pass (the lengths are multiples of 4
            // and equal).
            let (x, y, z) = unsafe {
                (
                    _mm256_loadu_pd(self.x.as_ptr().add(i)),
                    _mm256_loadu_pd(self.y.as_ptr().add(i)),
                    _mm256_loadu_pd(self.z.as_ptr().add(i)),
                )
            };
            _mm256_add_pd(
                _mm256_add_pd(_mm256_mul_pd(x, dx), _mm256_mul_pd(y, dy)),
                _mm256_mul_pd(z, dz),
            )
        };
        let len = self.x.len();
        let mut best = _mm256_set1_pd(f64::NEG_INFINITY);
        for i in (0..len).step_by(4) {
            best = _mm256_max_pd(best, dot(i));
        }
        let mut lanes = [0.0; 4];
        // SAFETY: `lanes` holds four doubles.
        unsafe { _mm256_storeu_pd(lanes.as_mut_ptr(), best) };
        let top = _mm256_set1_pd(lanes[0].max(lanes[1]).max(lanes[2]).max(lanes[3]));
        for i in (0..len).step_by(4) {
            let equal = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_EQ_OQ>(dot(i), top));
            if equal != 0 {
                return i + equal.trailing_zeros() as usize;
            }
        }
        0
    }
}

/// Cells per cube face side of [`Hull::starts`] for a hull of `vertices` vertices: about one cell per 4
/// vertices (6 to 24 per side), so a climb starts within a few edges of its end on hulls of every size.
fn cube_cells(vertices: usize) -> usize {
    ((vertices as f64 / 24.0).sqrt().ceil() as usize).clamp(6, 24)
}

/// The cube-map cell of `dir`: the face of its largest component (axis and sign), and where `dir` crosses
/// that face, in `cells × cells` cells.
fn cube_cell(dir: Vector, cells: usize) -> usize {
    let a = [dir.x, dir.y, dir.z];
    let abs = a.map(f64::abs);
    let axis = if abs[0] >= abs[1] && abs[0] >= abs[2] {
        0
    } else if abs[1] >= abs[2] {
        1
    } else {
        2
    };
    let major = abs[axis];
    if major.is_nan() || major <= 0.0 {
        return 0;
    }
    let bin = |v: f64| (((v / major + 1.0) * 0.5 * cells as f64) as usize).min(cells - 1);
    let (u, v) = (a[(axis + 1) % 3], a[(axis + 2) % 3]);
    let face = axis * 2 + usize::from(a[axis] > 0.0);
    (face * cells + bin(u)) * cells + bin(v)
}

/// The centre direction of cube-map cell `cell` (the inverse of [`cube_cell`]).
fn cube_direction(cell: usize, cells: usize) -> Vector {
    let (face, rest) = (cell / (cells * cells), cell % (cells * cells));
    let centre = |bin: usize| (bin as f64 + 0.5) / cells as f64 * 2.0 - 1.0;
    let (axis, sign) = (face / 2, if face % 2 == 1 { 1.0 } else { -1.0 });
    let mut d = [0.0; 3];
    d[axis] = sign;
    d[(axis + 1) % 3] = centre(rest / cells);
    d[(axis + 2) % 3] = centre(rest % cells);
    Vector::new(d[0], d[1], d[2])
}

/// Below this many vertices a scan is as fast as a climb.
const CLIMB_FROM: usize = 16;

impl Hull {
    /// The hull of `points` (its vertices or more; the support map is the same). `surface`: a closed
    /// convex triangulation of the hull by index into `points`, already checked (the mesh loader checks
    /// one per mesh file, see [`MeshData::hull_triangles`](crate::input::mesh::MeshData)); without one,
    /// parry's quickhull builds it here and it is checked before it is used.
    pub fn new(points: Vec<Vector>, surface: Option<&[[u32; 3]]>) -> Hull {
        let built = if points.len() >= CLIMB_FROM {
            match surface.filter(|t| !t.is_empty()) {
                Some(triangles) => Self::from_surface(&points, triangles),
                None => Self::triangulated(&points),
            }
        } else {
            None
        };
        let mut hull = built.unwrap_or_else(|| {
            // Too few points to climb (or no usable triangulation): scanned, with the faces of a
            // triangulation when one can be built.
            let faces = hull_surface(&points).map_or_else(Vec::new, |(vertices, triangles)| {
                faces_of(&vertices, &triangles)
            });
            Hull {
                points,
                offsets: Vec::new(),
                neighbours: Vec::new(),
                starts: Vec::new(),
                cells: 0,
                lanes: None,
                faces,
            }
        });
        hull.lanes = VertexLanes::of(&hull.points);
        hull
    }

    /// How deep each of `points` (shape frame) is inside the hull: the distance to the nearest face
    /// plane, at most the distance to the surface; negative or zero outside, `-inf` when the faces are
    /// unknown. Faces outer, points inner: the inner loop runs over the points' coordinates side by
    /// side, so it is vectorised (hulls have thousands of faces), four points at a time with AVX2.
    fn depths<const N: usize>(&self, points: &[Vector; N]) -> [f64; N] {
        if self.faces.is_empty() {
            return [f64::NEG_INFINITY; N];
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: `depths_avx2` needs AVX2, and this CPU has it (checked just above).
            return unsafe { self.depths_avx2(points) };
        }
        self.plane_depths(points)
    }

    /// [`Hull::depths`] compiled for AVX2 (no fused multiply-add: the same bits as the portable code).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn depths_avx2<const N: usize>(&self, points: &[Vector; N]) -> [f64; N] {
        self.plane_depths(points)
    }

    /// The work of [`Hull::depths`] for a hull with faces, inlined into each instruction set's copy.
    #[inline(always)]
    fn plane_depths<const N: usize>(&self, points: &[Vector; N]) -> [f64; N] {
        let [x, y, z] = [0, 1, 2].map(|axis| points.map(|p| p[axis]));
        let mut depth = [f64::INFINITY; N];
        for (normal, offset) in &self.faces {
            for k in 0..N {
                // As `offset - normal.dot(point)`, term for term.
                let dot = normal.x * x[k] + normal.y * y[k] + normal.z * z[k];
                // `f64::min` on non-NaN depths (a NaN plane is skipped as `min` skips it), written as a
                // comparison the vector minimum instruction computes.
                let on_plane = offset - dot;
                depth[k] = if on_plane < depth[k] {
                    on_plane
                } else {
                    depth[k]
                };
            }
        }
        depth
    }

    /// The vertices and edges of a triangulation of the hull by parry's quickhull ([`hull_surface`]).
    fn triangulated(points: &[Vector]) -> Option<Hull> {
        let (vertices, triangles) = hull_surface(points)?;
        Self::with_edges(vertices, &triangles)
    }

    /// The hull of a checked closed convex triangulation given by index into `points`: the points no
    /// triangle names (inside, as the check found) are left out of the vertices.
    fn from_surface(points: &[Vector], triangles: &[[u32; 3]]) -> Option<Hull> {
        let mut slot = vec![u32::MAX; points.len()];
        let mut vertices = Vec::new();
        let mut renumbered = Vec::with_capacity(triangles.len());
        for t in triangles {
            let mut corner = [0; 3];
            for (k, &v) in t.iter().enumerate() {
                let index = slot.get_mut(v as usize)?;
                if *index == u32::MAX {
                    *index = vertices.len() as u32;
                    vertices.push(points[v as usize]);
                }
                corner[k] = *index;
            }
            renumbered.push(corner);
        }
        Self::with_edges(vertices, &renumbered)
    }

    /// The hull of `vertices` with the edges of `triangles`, a closed convex triangulation of them.
    fn with_edges(vertices: Vec<Vector>, triangles: &[[u32; 3]]) -> Option<Hull> {
        let SurfaceEdges {
            offsets,
            neighbours,
        } = SurfaceEdges::of(vertices.len(), triangles)?;
        let faces = faces_of(&vertices, triangles);
        let mut hull = Hull {
            points: vertices,
            offsets,
            neighbours,
            starts: Vec::new(),
            cells: 0,
            lanes: None,
            faces,
        };
        // Each cell's start, climbed to from its neighbour's (cells in order are mostly adjacent).
        let mut previous = 0;
        let cells = cube_cells(hull.points.len());
        hull.cells = cells;
        hull.starts = (0..6 * cells * cells)
            .map(|cell| {
                previous = hull.climb(cube_direction(cell, cells), previous);
                previous as u32
            })
            .collect();
        Some(hull)
    }

    /// The index of a vertex furthest along `dir`, climbing from vertex `start` when edges are known
    /// (or from the cube map's start for `dir` when that is further along, or `start` is out of range).
    fn support_index(&self, dir: Vector, start: usize) -> usize {
        if let Some(lanes) = &self.lanes {
            return lanes.furthest(dir);
        }
        if self.offsets.is_empty() {
            let mut best = 0;
            let mut best_dot = f64::NEG_INFINITY;
            for (i, p) in self.points.iter().enumerate() {
                let d = p.dot(dir);
                if d > best_dot {
                    best_dot = d;
                    best = i;
                }
            }
            return best;
        }
        // Start from the better of the cube map's vertex for `dir` and `start` (the last query's answer).
        let mapped = self
            .starts
            .get(cube_cell(dir, self.cells))
            .map_or(0, |&v| v as usize);
        let vertex = match self.points.get(start) {
            Some(p) if p.dot(dir) > self.points[mapped].dot(dir) => start,
            _ => mapped,
        };
        self.climb(dir, vertex)
    }

    /// Steepest ascent along edges from `vertex` to a vertex furthest along `dir` (on a convex hull, a
    /// local maximum is a global one).
    fn climb(&self, dir: Vector, mut vertex: usize) -> usize {
        let mut best_dot = self.points[vertex].dot(dir);
        loop {
            let from = vertex;
            for &next in &self.neighbours[self.offsets[from]..self.offsets[from + 1]] {
                let d = self.points[next as usize].dot(dir);
                if d > best_dot {
                    best_dot = d;
                    vertex = next as usize;
                }
            }
            if vertex == from {
                return vertex;
            }
        }
    }
}

/// A closed convex triangulation of the hull of `points` by parry's quickhull (its vertices and
/// triangles), when it contains every point to within a nanometre (quickhull can fail on coplanar points).
fn hull_surface(points: &[Vector]) -> Option<(Vec<Vector>, Vec<[u32; 3]>)> {
    let (vertices, triangles) = hull::run_hull(points)?;
    surface::is_closed_convex(points, &vertices, &triangles).then_some((vertices, triangles))
}

/// The face planes of a closed convex triangulation as [`Hull::faces`] keeps them (faces too thin to
/// have a normal left out: their neighbours bound the hull there).
fn faces_of(vertices: &[Vector], triangles: &[[u32; 3]]) -> Vec<(Vector, f64)> {
    surface::face_planes(vertices, triangles)
        .into_iter()
        .flatten()
        .map(|(normal, corner)| (normal, normal.dot(corner)))
        .collect()
}

/// A core whose hull support queries start from the vertex the previous query ended at (successive GJK
/// directions are close, so the climb is short).
struct Warm<'a> {
    core: &'a Core,
    vertex: Cell<usize>,
}

impl SupportMap for Warm<'_> {
    #[inline]
    fn local_support_point(&self, dir: Vector) -> Vector {
        match self.core {
            Core::Hull(hull) => {
                let vertex = hull.support_index(dir, self.vertex.get());
                self.vertex.set(vertex);
                hull.points[vertex]
            }
            core => core.local_support_point(dir),
        }
    }
}

impl Core {
    /// A box core with half extents `half`, centred on the origin (for tests).
    #[cfg(test)]
    pub fn cuboid(half: Vector) -> Core {
        let corners = (0..8)
            .map(|i| {
                let corner = |bit: i32, half: f64| if i & bit == 0 { -half } else { half };
                Vector::new(corner(1, half.x), corner(2, half.y), corner(4, half.z))
            })
            .collect();
        Core::Hull(Hull::new(corners, None))
    }

    /// How deep each of `points` (shape frame) is inside the core: at most the distance to its surface;
    /// negative or zero outside (`-inf` for a hull whose faces are unknown).
    pub fn depths<const N: usize>(&self, points: &[Vector; N]) -> [f64; N] {
        match self {
            Core::Point => points.map(|point| -point.length()),
            Core::Segment { half } => points.map(|point| {
                -(point - Vector::new(0.0, 0.0, point.z.clamp(-half, *half))).length()
            }),
            Core::Cylinder { radius, half } => {
                points.map(|point| (radius - point.x.hypot(point.y)).min(half - point.z.abs()))
            }
            Core::Hull(hull) => hull.depths(points),
        }
    }
}

impl SupportMap for Core {
    #[inline]
    fn local_support_point(&self, dir: Vector) -> Vector {
        match self {
            Core::Point => Vector::ZERO,
            Core::Segment { half } => Vector::new(0.0, 0.0, half.copysign(dir.z)),
            Core::Cylinder { radius, half } => {
                let planar = (dir.x * dir.x + dir.y * dir.y).sqrt();
                let (x, y) = if planar > 0.0 {
                    (dir.x * radius / planar, dir.y * radius / planar)
                } else {
                    (0.0, 0.0)
                };
                Vector::new(x, y, half.copysign(dir.z))
            }
            Core::Hull(hull) if hull.points.is_empty() => Vector::ZERO,
            Core::Hull(hull) => hull.points[hull.support_index(dir, usize::MAX)],
        }
    }
}

/// One collision shape of a link: a core grown by `radius`, placed at `frame` in the link frame, inside the
/// sphere (`centre`, `bound`) of the link frame.
#[derive(Clone, Debug)]
pub struct ConvexShape {
    /// The convex core.
    pub core: Core,
    /// How much the core is grown (sphere and capsule radius; 0 otherwise).
    pub radius: f64,
    /// Shape frame in the link frame.
    pub frame: Isometry3<f64>,
    /// Centre of a bounding sphere, in the link frame.
    pub centre: Vector3<f64>,
    /// Radius of that bounding sphere.
    pub bound: f64,
    /// A box around the grown core, in the link frame.
    pub obb: Obb,
    /// The centre of that box in the shape frame: where a separating axis between two shapes is first
    /// looked for.
    pub inner: Vector,
    /// Spheres inside the grown core, along the box's longest axis: when they meet another shape's,
    /// the shapes are in contact without GJK.
    pub inside: Inside,
}

/// An oriented box: `frame` places its centre and axes, `half` its half extents along them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obb {
    /// Centre and axes.
    pub frame: Isometry3<f64>,
    /// Half extents.
    pub half: Vector3<f64>,
}

impl Obb {
    /// The box placed by `placement`, as (centre, axes as columns).
    pub fn placed(&self, placement: &Isometry3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
        let frame = placement * self.frame;
        (
            frame.translation.vector,
            *frame.rotation.to_rotation_matrix().matrix(),
        )
    }

    /// The volume, for choosing the tighter of two boxes.
    fn volume(&self) -> f64 {
        self.half.x * self.half.y * self.half.z
    }
}

/// The tighter of the axis-aligned and the principal-axes box of points of the link frame.
fn fitted_box(points: &[Vector3<f64>]) -> Option<Obb> {
    let aligned = box_along(points, UnitQuaternion::identity())?;
    let n = points.len() as f64;
    let mean = points.iter().sum::<Vector3<f64>>() / n;
    let covariance = points
        .iter()
        .map(|p| (p - mean) * (p - mean).transpose())
        .sum::<Matrix3<f64>>()
        / n;
    let eigen = SymmetricEigen::new(covariance);
    let mut axes = eigen.eigenvectors;
    if axes.determinant() < 0.0 {
        axes.column_mut(2).neg_mut();
    }
    let principal =
        nalgebra::Rotation3::from_matrix_eps(&axes, 1e-12, 100, nalgebra::Rotation3::identity());
    let principal = box_along(points, UnitQuaternion::from_rotation_matrix(&principal));
    Some(match principal {
        Some(p) if p.volume() < aligned.volume() => p,
        _ => aligned,
    })
}

/// The smallest box with axes `rotation` around `points`.
fn box_along(points: &[Vector3<f64>], rotation: UnitQuaternion<f64>) -> Option<Obb> {
    let local: Vec<Vector3<f64>> = points
        .iter()
        .map(|p| rotation.inverse_transform_vector(p))
        .collect();
    let first = local.first()?;
    let (lo, hi) = local
        .iter()
        .fold((*first, *first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    let centre = rotation * ((lo + hi) / 2.0);
    let obb = Obb {
        frame: Isometry3::from_parts(Translation3::from(centre), rotation),
        half: (hi - lo) / 2.0,
    };
    obb.half.iter().all(|v| v.is_finite()).then_some(obb)
}

/// True when a separating axis of the two boxes (centre, axes as columns, half extents) shows them at
/// least `margin` apart (the separating-axis test of Gottschalk et al. with a gap).
#[inline(always)]
pub fn boxes_apart(
    a: &(Vector3<f64>, Matrix3<f64>),
    half_a: &Vector3<f64>,
    b: &(Vector3<f64>, Matrix3<f64>),
    half_b: &Vector3<f64>,
    margin: f64,
) -> bool {
    // Everything in A's frame; the epsilon keeps near-parallel edges conservative.
    let r = a.1.transpose() * b.1;
    let abs = r.abs().add_scalar(1e-12);
    let t = a.1.transpose() * (b.0 - a.0);
    for i in 0..3 {
        let reach = half_a[i] + half_b.dot(&abs.row(i).transpose());
        if t[i].abs() - reach >= margin {
            return true;
        }
    }
    for j in 0..3 {
        let reach = half_a.dot(&abs.column(j)) + half_b[j];
        if t.dot(&r.column(j)).abs() - reach >= margin {
            return true;
        }
    }
    for i in 0..3 {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        for j in 0..3 {
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            // |A_i × B_j| = sin of their angle; parallel edges are covered by the face axes.
            let length = (1.0 - r[(i, j)] * r[(i, j)]).max(0.0).sqrt();
            if length < 1e-6 {
                continue;
            }
            let reach = half_a[i1] * abs[(i2, j)]
                + half_a[i2] * abs[(i1, j)]
                + half_b[j1] * abs[(i, j2)]
                + half_b[j2] * abs[(i, j1)];
            let distance = (t[i2] * r[(i1, j)] - t[i1] * r[(i2, j)]).abs();
            if distance - reach >= margin * length {
                return true;
            }
        }
    }
    false
}

impl ConvexShape {
    /// Feed what the shape is (its core, radius and frame; the rest is derived from them).
    pub(crate) fn fingerprint(&self, print: &mut Fingerprint) {
        match &self.core {
            Core::Point => {
                print.value(0u8);
            }
            Core::Segment { half } => {
                print.value(1u8).float(*half);
            }
            Core::Cylinder { radius, half } => {
                print.value(2u8).float(*radius).float(*half);
            }
            Core::Hull(hull) => {
                print.value(3u8).value(hull.points.len());
                for p in &hull.points {
                    print.float(p.x).float(p.y).float(p.z);
                }
            }
        }
        print.float(self.radius).placement(&self.frame);
    }

    /// The collision shape of one [`Support`]; `None` when its numbers are unusable.
    pub fn from_support(support: &Support) -> Option<ConvexShape> {
        let (mut core, radius, frame) = match support {
            Support::Points(points) => {
                let points: Vec<Vector> =
                    points.iter().map(|p| Vector::new(p.x, p.y, p.z)).collect();
                (
                    Core::Hull(Hull::new(points, None)),
                    0.0,
                    Isometry3::identity(),
                )
            }
            Support::Hull { points, triangles } => {
                let points: Vec<Vector> =
                    points.iter().map(|p| Vector::new(p.x, p.y, p.z)).collect();
                let hull = Hull::new(points, Some(triangles));
                (Core::Hull(hull), 0.0, Isometry3::identity())
            }
            Support::Rounded {
                frame,
                radius,
                length,
            } => {
                let core = if *length > 0.0 {
                    Core::Segment { half: length / 2.0 }
                } else {
                    Core::Point
                };
                (core, *radius, *frame)
            }
            Support::Cylinder {
                frame,
                radius,
                length,
            } => (
                Core::Cylinder {
                    radius: *radius,
                    half: length / 2.0,
                },
                0.0,
                *frame,
            ),
        };
        let (centre, bound) = bounding_sphere(&core, radius, &frame)?;
        let obb = match &core {
            Core::Hull(hull) => {
                let placed: Vec<Vector3<f64>> = hull
                    .points
                    .iter()
                    .map(|p| frame.transform_point(&Point3::new(p.x, p.y, p.z)).coords)
                    .collect();
                fitted_box(&placed)?
            }
            Core::Point => Obb {
                frame,
                half: Vector3::repeat(radius),
            },
            Core::Segment { half } => Obb {
                frame,
                half: Vector3::new(radius, radius, half + radius),
            },
            Core::Cylinder { radius, half } => Obb {
                frame,
                half: Vector3::new(*radius, *radius, *half),
            },
        };
        let inner = frame.inverse_transform_point(&Point3::from(obb.frame.translation.vector));
        let inner = Vector::new(inner.x, inner.y, inner.z);
        let longest = obb.half.imax();
        let axis =
            frame.inverse_transform_vector(&(obb.frame.rotation * Vector3::ith(longest, 1.0)));
        let inside = Inside::of(
            &core,
            radius,
            inner,
            Vector::new(axis.x, axis.y, axis.z),
            obb.half[longest],
        );
        if let Core::Hull(hull) = &mut core {
            // The face planes served the inner spheres only: freed, so that the next hull built on this
            // thread reuses their memory instead of touching fresh pages (page faults are dear on a
            // virtual machine; g1 with hands' hulls have 3 MB of them).
            hull.faces = Vec::new();
        }
        Some(ConvexShape {
            core,
            radius,
            frame,
            centre,
            bound,
            obb,
            inner,
            inside,
        })
    }
}

/// A sphere around the grown core, in the link frame; `None` for empty or unbounded shapes.
fn bounding_sphere(
    core: &Core,
    radius: f64,
    frame: &Isometry3<f64>,
) -> Option<(Vector3<f64>, f64)> {
    let (centre, core_radius) = match core {
        Core::Point => (frame.translation.vector, 0.0),
        Core::Segment { half } => (frame.translation.vector, *half),
        Core::Cylinder { radius, half } => (frame.translation.vector, radius.hypot(*half)),
        Core::Hull(hull) => {
            let placed: Vec<Vector3<f64>> = hull
                .points
                .iter()
                .map(|p| frame.transform_point(&Point3::new(p.x, p.y, p.z)).coords)
                .collect();
            let first = placed.first()?;
            let (lo, hi) = placed
                .iter()
                .fold((*first, *first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
            let centre = (lo + hi) / 2.0;
            let reach = placed
                .iter()
                .map(|p| (p - centre).norm())
                .fold(0.0, f64::max);
            (centre, reach)
        }
    };
    let bound = core_radius + radius;
    let usable =
        centre.iter().all(|v| v.abs() <= MAX_EXTENT) && bound.is_finite() && bound <= MAX_EXTENT;
    usable.then_some((centre, bound))
}

/// The smallest-effort sphere around several spheres: centred on their bounding box.
pub fn enclosing_sphere(spheres: &[(Vector3<f64>, f64)]) -> Option<(Vector3<f64>, f64)> {
    let lo = spheres
        .iter()
        .map(|(c, r)| c.add_scalar(-r))
        .reduce(|a, b| a.inf(&b))?;
    let hi = spheres
        .iter()
        .map(|(c, r)| c.add_scalar(*r))
        .reduce(|a, b| a.sup(&b))?;
    let centre = (lo + hi) / 2.0;
    let radius = spheres
        .iter()
        .map(|(c, r)| (c - centre).norm() + r)
        .fold(0.0, f64::max);
    Some((centre, radius))
}

/// A placement in parry's types.
pub fn to_pose(iso: &Isometry3<f64>) -> Pose {
    let t = iso.translation.vector;
    let q = iso.rotation.quaternion().coords;
    Pose::from_parts(
        Vector::new(t.x, t.y, t.z),
        Rotation::from_xyzw(q.x, q.y, q.z, q.w),
    )
}

/// How close two placed shapes are, as far as a query with a margin can tell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Proximity {
    /// Overlapping or touching (closer than [`CONTACT_DISTANCE`]).
    Contact,
    /// Apart by this distance, which is below the margin asked for.
    Apart(f64),
    /// Farther apart than the margin.
    Beyond,
}

/// What the narrow phase keeps of a pair from one pose to the next.
#[derive(Clone, Copy, Debug, Default)]
pub struct PairMemory {
    /// The unit direction from the first shape to the second (in the first's frame) that the last
    /// search on this pair ended with; zero at first.
    axis: Vector,
    /// When the first shape stays in place between poses: that shape (as the caller numbers it) and its
    /// support point along `axis`, which does not change until `axis` does.
    held_support: Option<(usize, Vector)>,
    /// The last query on this pair found a contact.
    in_contact: bool,
}

impl PairMemory {
    fn set_axis(&mut self, axis: Vector) {
        self.axis = axis;
        self.held_support = None;
    }

    /// `shape`'s support point along `axis`, queried once per axis when `shape` is `held` in place.
    fn first_support(&mut self, shape: &Core, held: Option<usize>) -> Vector {
        match (held, self.held_support) {
            (Some(index), Some((cached, point))) if cached == index => point,
            (Some(index), _) => {
                let point = shape.local_support_point(self.axis);
                self.held_support = Some((index, point));
                point
            }
            (None, _) => shape.local_support_point(self.axis),
        }
    }
}

/// The proximity of `a` placed at `pose_a` and `b` at `pose_b` (world placements of the shape frames),
/// exact up to `margin` (distances at or above `margin` are [`Proximity::Beyond`]).
///
/// An overlap is looked for first without GJK, by the spheres inside both shapes (see [`Inside`]), on a
/// pair whose last query found a contact or that has never been separated (pairs that collide in one pose
/// often do in the next; on the others the test costs more than it saves). Then `memory`'s axis, the
/// direction from `a` to `b` (in `a`'s frame) the last search on this pair ended with, is tried as a
/// separating axis (two support points; `a`'s is kept in `memory` when `a_held` names `a` as a shape
/// that stays in place, so it is queried once per axis), then the line between the shapes' box centres.
/// Pairs tend to be separated along similar directions from pose to pose, so many are settled there.
/// Then a yes/no search ([`enclose`]) starting from those support points and, when it cannot tell,
/// parry's distance GJK, started afresh (seeded, it took near-touching shapes for intersecting); either
/// updates the axis.
#[allow(clippy::too_many_arguments)]
pub fn proximity(
    a: &ConvexShape,
    pose_a: &Pose,
    b: &ConvexShape,
    pose_b: &Pose,
    margin: f64,
    memory: &mut PairMemory,
    a_held: Option<usize>,
    simplex: &mut VoronoiSimplex,
) -> Proximity {
    let found = 'query: {
        let rounding = a.radius + b.radius;
        let core_distance = if let (Core::Point, Core::Point) = (&a.core, &b.core) {
            Some(pose_a.translation.distance(pose_b.translation))
        } else {
            let pos12 = pose_a.inv_mul(pose_b);
            let contact_likely = memory.in_contact || memory.axis == Vector::ZERO;
            if contact_likely && a.inside.meet(&b.inside, &pos12) {
                break 'query Proximity::Contact;
            }
            // The support points of the two tries below are points of the shapes' difference (`a`'s less
            // `b`'s): when neither separates the shapes, the yes/no search starts from them.
            let mut tried = [Vector::ZERO; 2];
            let mut count = 0;
            let axis = memory.axis;
            if axis != Vector::ZERO {
                // The last separating direction, tried first: two support points settle most pairs.
                let near_a = memory.first_support(&a.core, a_held);
                let near_b = b.core.support_point(&pos12, -axis);
                if axis.dot(near_b - near_a) - rounding >= margin {
                    break 'query Proximity::Beyond;
                }
                tried[count] = near_a - near_b;
                count += 1;
            }
            // Then the direction from one shape's box centre to the other's: pairs that are far apart for
            // this pose, whatever they were for the last one, are settled by two more support points.
            if let Some(toward) = (pos12.transform_point(b.inner) - a.inner).try_normalize() {
                let near_a = a.core.local_support_point(toward);
                let near_b = b.core.support_point(&pos12, -toward);
                if toward.dot(near_b - near_a) - rounding >= margin {
                    break 'query Proximity::Beyond;
                }
                tried[count] = near_a - near_b;
                count += 1;
            }
            let (warm_a, warm_b) = (
                Warm {
                    core: &a.core,
                    vertex: Cell::new(usize::MAX),
                },
                Warm {
                    core: &b.core,
                    vertex: Cell::new(usize::MAX),
                },
            );
            match enclose(&pos12, &warm_a, &warm_b, &tried[..count], margin + rounding) {
                Enclosure::Overlap => break 'query Proximity::Contact,
                Enclosure::Apart(unit) => {
                    memory.set_axis(unit);
                    break 'query Proximity::Beyond;
                }
                Enclosure::Unknown => {}
            }
            // GJK starts afresh, not from the points tried: seeded with them, parry's GJK took shapes a
            // few micrometres apart (a cylinder near a hull) for intersecting, depending on what the pair
            // tried first, so on the order in which the samples met it.
            let result = closest_points_support_map_support_map_with_params(
                &pos12,
                &warm_a,
                &warm_b,
                margin + rounding,
                simplex,
                None,
            );
            match result {
                GJKResult::ClosestPoints(p1, p2, dir) => {
                    memory.set_axis(dir);
                    Some(p1.distance(p2))
                }
                GJKResult::Intersection => None,
                GJKResult::NoIntersection(dir) | GJKResult::Proximity(dir) => {
                    memory.set_axis(dir);
                    break 'query Proximity::Beyond;
                }
            }
        };
        match core_distance.map(|d| d - rounding) {
            None => Proximity::Contact,
            Some(d) if d <= CONTACT_DISTANCE => Proximity::Contact,
            Some(d) if d < margin => Proximity::Apart(d),
            Some(_) => Proximity::Beyond,
        }
    };
    memory.in_contact = found == Proximity::Contact;
    found
}

/// How deep `a` placed at `pose_a` and `b` at `pose_b` (world placements of the shape frames) overlap,
/// metres: the shortest translation that separates them (GJK on the cores, EPA when the cores
/// intersect, less the radii), as a simulator's contact depth; 0 when they are apart or touch. Where EPA
/// cannot tell (cores sharing their centre: a key that stacks bodies at one point), the least overlap
/// along 13 axes, which is at least the depth.
pub fn overlap_depth(a: &ConvexShape, pose_a: &Pose, b: &ConvexShape, pose_b: &Pose) -> f64 {
    let rounding = a.radius + b.radius;
    let pos12 = pose_a.inv_mul(pose_b);
    let core_distance = if let (Core::Point, Core::Point) = (&a.core, &b.core) {
        pos12.translation.length()
    } else {
        let mut simplex = VoronoiSimplex::new();
        let dir = pos12.translation.try_normalize().unwrap_or(Vector::X);
        simplex.reset(CsoPoint::from_shapes(&pos12, &a.core, &b.core, dir));
        match gjk::closest_points(
            &pos12,
            &a.core,
            &b.core,
            rounding + CONTACT_DISTANCE,
            true,
            &mut simplex,
        ) {
            // GJK can stop on a degenerate simplex at distance 0 with the cores deep in each other
            // (two equal shapes at one place): that is an intersection too.
            GJKResult::ClosestPoints(p1, p2, _) if p1.distance(p2) > CONTACT_DISTANCE => {
                p1.distance(p2)
            }
            GJKResult::ClosestPoints(..) | GJKResult::Intersection => {
                // Negative: how far the cores reach into each other (EPA started from a degenerate
                // simplex can answer 0 for cores deep in each other).
                match EPA::new().closest_points(&pos12, &a.core, &b.core, &simplex) {
                    Some((p1, p2, normal)) if (p2 - p1).dot(normal) < -CONTACT_DISTANCE => {
                        (p2 - p1).dot(normal)
                    }
                    _ => -least_overlap_along_axes(&pos12, &a.core, &b.core),
                }
            }
            GJKResult::NoIntersection(_) | GJKResult::Proximity(_) => return 0.0,
        }
    };
    (rounding - core_distance).max(0.0)
}

/// The least overlap of `a` and `b` (at `pos12` in `a`'s frame) along the axes of `a`'s frame, its face
/// diagonals and its body diagonals (each with its opposite): an upper bound of their penetration depth.
fn least_overlap_along_axes(pos12: &Pose, a: &Core, b: &Core) -> f64 {
    let mut least = f64::INFINITY;
    for x in -1i8..=1 {
        for y in -1i8..=1 {
            for z in 0i8..=1 {
                if z == 0 && (y < 0 || (y == 0 && x <= 0)) {
                    continue; // one of each opposite pair, and not zero
                }
                let d = Vector::new(f64::from(x), f64::from(y), f64::from(z)).normalize();
                let overlap = a.local_support_point(d).dot(d) - b.support_point(pos12, -d).dot(d);
                let back = b.support_point(pos12, d).dot(d) - a.local_support_point(-d).dot(d);
                least = least.min(overlap).min(back);
            }
        }
    }
    least.max(0.0)
}

/// How far `shape` placed at `pose` (the world placement of its frame) reaches below the plane through
/// `point` with unit `normal` (solid on the side away from the normal), metres; 0 when it stays above.
pub fn depth_below_plane(
    shape: &ConvexShape,
    pose: &Isometry3<f64>,
    point: &Vector3<f64>,
    normal: &Vector3<f64>,
) -> f64 {
    let down = pose.rotation.inverse() * -normal;
    let local = shape
        .core
        .local_support_point(Vector::new(down.x, down.y, down.z));
    let lowest = pose.transform_point(&Point3::new(local.x, local.y, local.z));
    (normal.dot(&(point - lowest.coords)) + shape.radius).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use nalgebra::{Translation3, UnitQuaternion};

    /// Support queries on hulls of 1 to 200 points (scanned four at a time up to [`SCAN_UP_TO`] vertices
    /// where the CPU has AVX2, climbed or scanned one by one otherwise) reach the furthest value along
    /// every direction, random, along an axis (ties between vertices) or not a number; a scan answers the
    /// first vertex holding it.
    #[test]
    fn support_queries_reach_the_furthest_vertex() {
        let mut rng = SplitMix64::new(9);
        let mut scanned = 0;
        for n in 1..=200 {
            // Points in a box, some on its faces (axis directions then meet ties), or all on a sphere
            // (every point a vertex).
            let points: Vec<Vector> = (0..n)
                .map(|i| {
                    let mut c = [0.0; 3].map(|_| rng.uniform(-1.0, 1.0));
                    if n % 2 == 1 {
                        let norm = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
                        c = c.map(|v| v / norm);
                    } else if i % 3 == 0 {
                        c[i % 2] = if i % 4 == 0 { 1.0 } else { -1.0 };
                    }
                    Vector::new(c[0], c[1], c[2])
                })
                .collect();
            let hull = Hull::new(points.clone(), None);
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") {
                assert_eq!(hull.lanes.is_some(), hull.points.len() <= SCAN_UP_TO);
            }
            scanned += usize::from(hull.lanes.is_some());
            let mut directions: Vec<Vector> = (0..50)
                .map(|_| {
                    Vector::new(
                        rng.uniform(-1.0, 1.0),
                        rng.uniform(-1.0, 1.0),
                        rng.uniform(-1.0, 1.0),
                    )
                })
                .collect();
            directions.extend([Vector::X, -Vector::X, Vector::Y, -Vector::Z]);
            for dir in directions {
                let dots: Vec<f64> = points.iter().map(|p| p.dot(dir)).collect();
                let top = dots.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                let found = hull.points[hull.support_index(dir, usize::MAX)];
                assert_eq!(found.dot(dir), top, "{n} points along {dir:?}");
                if hull.lanes.is_some() {
                    // The hull's own vertices (a triangulated hull keeps only its corners).
                    let first = hull.points.iter().position(|p| p.dot(dir) == top);
                    assert_eq!(Some(hull.support_index(dir, usize::MAX)), first);
                }
            }
            // Not a number: some vertex, no panic.
            assert!(hull.support_index(Vector::splat(f64::NAN), 0) < hull.points.len());
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            assert!((100..200).contains(&scanned), "{scanned} hulls scanned");
        }
    }

    fn shape(support: Support) -> ConvexShape {
        ConvexShape::from_support(&support).expect("usable")
    }

    fn ball(radius: f64) -> ConvexShape {
        shape(Support::Rounded {
            frame: Isometry3::identity(),
            radius,
            length: 0.0,
        })
    }

    fn cube(half: f64) -> ConvexShape {
        let corners = (0..8)
            .map(|i| {
                let s = |bit: i32| if i & bit == 0 { -half } else { half };
                Vector3::new(s(1), s(2), s(4))
            })
            .collect();
        shape(Support::Points(corners))
    }

    fn at(x: f64, y: f64, z: f64) -> Pose {
        to_pose(&Isometry3::translation(x, y, z))
    }

    fn query(a: &ConvexShape, pa: &Pose, b: &ConvexShape, pb: &Pose) -> Proximity {
        proximity(
            a,
            pa,
            b,
            pb,
            f64::INFINITY,
            &mut PairMemory::default(),
            None,
            &mut VoronoiSimplex::new(),
        )
    }

    fn apart(p: Proximity) -> f64 {
        match p {
            Proximity::Apart(d) => d,
            other => panic!("expected a distance, got {other:?}"),
        }
    }

    /// Random hulls (point clouds of 4 to 60 points), capsules and cylinders, placed at random.
    fn random_shapes(rng: &mut SplitMix64) -> Vec<ConvexShape> {
        let mut shapes = Vec::new();
        for k in 0..60 {
            let frame = random_frame(rng);
            let support = match k % 4 {
                0 | 1 => {
                    let n = 4 + (rng.next_u64() % 57) as usize;
                    let stretch = Vector3::new(
                        rng.uniform(0.02, 0.4),
                        rng.uniform(0.02, 0.2),
                        rng.uniform(0.02, 0.1),
                    );
                    let points = (0..n)
                        .map(|_| {
                            let p = Vector3::new(
                                rng.uniform(-1.0, 1.0),
                                rng.uniform(-1.0, 1.0),
                                rng.uniform(-1.0, 1.0),
                            );
                            frame
                                .transform_point(&Point3::from(p.component_mul(&stretch)))
                                .coords
                        })
                        .collect();
                    Support::Points(points)
                }
                2 => Support::Rounded {
                    frame,
                    radius: rng.uniform(0.01, 0.1),
                    length: rng.uniform(0.0, 0.5),
                },
                _ => Support::Cylinder {
                    frame,
                    radius: rng.uniform(0.01, 0.2),
                    length: rng.uniform(0.01, 0.5),
                },
            };
            shapes.extend(ConvexShape::from_support(&support));
        }
        shapes
    }

    fn random_frame(rng: &mut SplitMix64) -> Isometry3<f64> {
        let axis = Vector3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        );
        let t = Vector3::new(
            rng.uniform(-0.3, 0.3),
            rng.uniform(-0.3, 0.3),
            rng.uniform(-0.3, 0.3),
        );
        Isometry3::from_parts(
            Translation3::from(t),
            UnitQuaternion::from_scaled_axis(axis * 2.0),
        )
    }

    /// Every point of every sphere inside a shape is in the shape, as parry's GJK measures the distance
    /// from the point to the core (an oracle independent of the face planes the spheres come from).
    /// Fails when the spheres are made 1 % larger.
    #[test]
    fn inner_spheres_lie_inside_their_shape() {
        let mut rng = SplitMix64::new(5);
        let shapes = random_shapes(&mut rng);
        let mut simplex = VoronoiSimplex::new();
        let mut spheres = 0;
        for shape in &shapes {
            for (centre, radius) in shape.inside.spheres() {
                spheres += 1;
                for k in 0..600 {
                    let direction = if k < 6 {
                        let mut axis = Vector::ZERO;
                        axis[k % 3] = if k < 3 { 1.0 } else { -1.0 };
                        axis
                    } else {
                        Vector::new(
                            rng.uniform(-1.0, 1.0),
                            rng.uniform(-1.0, 1.0),
                            rng.uniform(-1.0, 1.0),
                        )
                        .normalize()
                    };
                    let point = Pose::from_translation(centre + direction * radius);
                    let distance = match closest_points_support_map_support_map_with_params(
                        &point,
                        &shape.core,
                        &Core::Point,
                        f64::INFINITY,
                        &mut simplex,
                        None,
                    ) {
                        GJKResult::ClosestPoints(p1, p2, _) => p1.distance(p2),
                        _ => 0.0,
                    };
                    assert!(
                        distance <= shape.radius + 1e-12,
                        "a point of a sphere inside is {} outside: {shape:?}",
                        distance - shape.radius
                    );
                }
            }
        }
        assert!(
            spheres >= shapes.len(),
            "{spheres} spheres in {} shapes",
            shapes.len()
        );
    }

    /// The spheres inside shapes prove only contacts that GJK alone finds, and most of the contacts of
    /// random overlapping placements: shapes of [`random_shapes`] at random poses, judged by parry's GJK
    /// on the cores.
    #[test]
    fn inner_spheres_prove_only_contacts_gjk_finds() {
        let mut rng = SplitMix64::new(11);
        let shapes = random_shapes(&mut rng);
        let (mut proved, mut contacts) = (0, 0);
        let mut simplex = VoronoiSimplex::new();
        for a in &shapes {
            for b in &shapes {
                for _ in 0..4 {
                    let pose_a = to_pose(&random_frame(&mut rng));
                    let pose_b = to_pose(&random_frame(&mut rng));
                    let pos12 = pose_a.inv_mul(&pose_b);
                    let gjk = closest_points_support_map_support_map_with_params(
                        &pos12,
                        &a.core,
                        &b.core,
                        f64::INFINITY,
                        &mut simplex,
                        None,
                    );
                    let contact = match gjk {
                        GJKResult::ClosestPoints(p1, p2, _) => {
                            p1.distance(p2) - a.radius - b.radius <= CONTACT_DISTANCE
                        }
                        GJKResult::Intersection => true,
                        _ => false,
                    };
                    contacts += usize::from(contact);
                    if a.inside.meet(&b.inside, &pos12) {
                        proved += 1;
                        assert!(
                            contact,
                            "spheres met where GJK finds no contact: {a:?} {b:?} {pos12:?}"
                        );
                    }
                }
            }
        }
        // Not vacuous: most contacts of these overlapping placements are proved.
        assert!(
            proved * 4 > contacts,
            "{proved} of {contacts} contacts proved"
        );
    }

    #[test]
    fn balls_and_cubes_have_exact_distances() {
        let d = apart(query(
            &ball(0.1),
            &at(0.0, 0.0, 0.0),
            &ball(0.2),
            &at(1.0, 0.0, 0.0),
        ));
        assert!((d - 0.7).abs() < 1e-12, "{d}");
        let d = apart(query(
            &cube(0.5),
            &at(0.0, 0.0, 0.0),
            &ball(0.25),
            &at(0.0, 2.0, 0.0),
        ));
        assert!((d - 1.25).abs() < 1e-9, "{d}");
        // Cube corner towards a ball along the diagonal.
        let d = apart(query(
            &cube(0.5),
            &at(0.0, 0.0, 0.0),
            &ball(0.1),
            &at(1.0, 1.0, 1.0),
        ));
        assert!((d - (0.5 * 3f64.sqrt() - 0.1)).abs() < 1e-7, "{d}");
        assert_eq!(
            query(
                &cube(0.5),
                &at(0.0, 0.0, 0.0),
                &cube(0.5),
                &at(0.9, 0.0, 0.0)
            ),
            Proximity::Contact
        );
        assert_eq!(
            query(
                &cube(0.5),
                &at(0.0, 0.0, 0.0),
                &cube(0.5),
                &at(1.0, 0.0, 0.0)
            ),
            Proximity::Contact,
            "touching faces are in contact"
        );
    }

    /// Whether the inner-sphere test runs (a pair found in contact last time, or never separated) changes
    /// no answer: over random shapes, poses and margins (a twentieth of the queries at least in contact),
    /// a query that skips it and one that runs it agree.
    #[test]
    fn skipping_the_inner_spheres_changes_no_answer() {
        let mut rng = SplitMix64::new(23);
        let shapes = random_shapes(&mut rng);
        let mut simplex = VoronoiSimplex::new();
        let (mut contacts, mut queries) = (0, 0);
        for (k, b) in shapes.iter().enumerate().cycle().take(3000) {
            let a = &shapes[(k * 7 + 3) % shapes.len()];
            let (pose_a, pose_b) = (
                to_pose(&random_frame(&mut rng)),
                to_pose(&random_frame(&mut rng)),
            );
            let margin = [0.05, 1e-6, f64::INFINITY][k % 3];
            let axis = Vector::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.5).normalize();
            let answer = |in_contact: bool, simplex: &mut VoronoiSimplex| {
                let mut memory = PairMemory {
                    axis,
                    held_support: None,
                    in_contact,
                };
                proximity(a, &pose_a, b, &pose_b, margin, &mut memory, None, simplex)
            };
            let (tested, skipped) = (answer(true, &mut simplex), answer(false, &mut simplex));
            assert_eq!(
                tested,
                skipped,
                "shapes {k} and {}",
                (k * 7 + 3) % shapes.len()
            );
            queries += 1;
            contacts += usize::from(tested == Proximity::Contact);
        }
        assert!(
            contacts > queries / 20,
            "{contacts} contacts in {queries} queries"
        );
    }

    /// A first shape held in place keeps its support point along the pair's axis between poses: over a
    /// sequence of poses of the second shape, four at a time with each of two held first shapes sharing the
    /// pair's memory, every answer is the one of a query that keeps nothing. Fails when the kept point
    /// is not tied to its shape or not dropped when the axis changes.
    #[test]
    fn a_held_shapes_kept_support_point_changes_no_answer() {
        let mut rng = SplitMix64::new(17);
        let shapes = random_shapes(&mut rng);
        let mut simplex = VoronoiSimplex::new();
        let (mut memory, mut differing, mut queries) = (PairMemory::default(), 0, 0);
        let held = [
            to_pose(&random_frame(&mut rng)),
            to_pose(&random_frame(&mut rng)),
        ];
        for (k, b) in shapes.iter().enumerate().cycle().take(600) {
            let first = (k / 4) % 2;
            let a = &shapes[(first * 7) % shapes.len()];
            let pose_b = to_pose(&random_frame(&mut rng));
            let margin = [0.05, 1e-6, f64::INFINITY][k % 3];
            let mut fresh = PairMemory {
                axis: memory.axis,
                held_support: None,
                in_contact: memory.in_contact,
            };
            let expected = proximity(
                a,
                &held[first],
                b,
                &pose_b,
                margin,
                &mut fresh,
                None,
                &mut simplex,
            );
            let kept = proximity(
                a,
                &held[first],
                b,
                &pose_b,
                margin,
                &mut memory,
                Some(first),
                &mut simplex,
            );
            queries += 1;
            let same = match (expected, kept) {
                (Proximity::Apart(x), Proximity::Apart(y)) => (x - y).abs() < 1e-9,
                (x, y) => x == y,
            };
            differing += usize::from(!same);
        }
        assert_eq!(differing, 0, "{differing} of {queries} answers differ");
    }

    #[test]
    fn a_margin_cuts_the_query_short() {
        let mut simplex = VoronoiSimplex::new();
        let far = proximity(
            &cube(0.5),
            &at(0.0, 0.0, 0.0),
            &cube(0.5),
            &at(3.0, 0.0, 0.0),
            1.0,
            &mut PairMemory::default(),
            None,
            &mut simplex,
        );
        assert_eq!(far, Proximity::Beyond);
        let near = proximity(
            &cube(0.5),
            &at(0.0, 0.0, 0.0),
            &cube(0.5),
            &at(1.5, 0.0, 0.0),
            1.0,
            &mut PairMemory::default(),
            None,
            &mut simplex,
        );
        assert!((apart(near) - 0.5).abs() < 1e-9);
    }

    #[test]
    fn cylinders_are_along_z_and_capsules_are_rounded() {
        let cylinder = shape(Support::Cylinder {
            frame: Isometry3::identity(),
            radius: 0.1,
            length: 1.0,
        });
        // Beside the side wall, and above the cap.
        let d = apart(query(
            &cylinder,
            &at(0.0, 0.0, 0.0),
            &ball(0.05),
            &at(0.5, 0.0, 0.0),
        ));
        assert!((d - 0.35).abs() < 1e-7, "{d}");
        let d = apart(query(
            &cylinder,
            &at(0.0, 0.0, 0.0),
            &ball(0.05),
            &at(0.0, 0.0, 1.0),
        ));
        assert!((d - 0.45).abs() < 1e-7, "{d}");
        // A capsule lying along x (its z axis rotated by 90° about y) above a ball.
        let frame = Isometry3::from_parts(
            Translation3::identity(),
            UnitQuaternion::from_euler_angles(0.0, std::f64::consts::FRAC_PI_2, 0.0),
        );
        let capsule = shape(Support::Rounded {
            frame,
            radius: 0.05,
            length: 1.0,
        });
        let world = to_pose(&frame);
        let d = apart(query(&capsule, &world, &ball(0.1), &at(0.4, 0.0, 0.3)));
        assert!((d - 0.15).abs() < 1e-9, "{d}");
        let d = apart(query(&capsule, &world, &ball(0.1), &at(0.9, 0.0, 0.0)));
        assert!((d - 0.25).abs() < 1e-9, "{d}");
        assert!((capsule.bound - 0.55).abs() < 1e-12);
    }

    /// Two cylinders 46 µm apart, edge to side, as baxter's left forearm meets its elbow in a sampled
    /// pose: the pair's last axis and the line between the box centres give two support points of the
    /// shapes' difference 10⁻⁷ m apart. Seeded with both, parry's distance GJK took the near-degenerate
    /// segment for an intersection and the pose counted as colliding, depending on the order the samples
    /// met the pair; started afresh it finds the gap.
    #[test]
    fn nearly_equal_support_points_do_not_make_a_contact() {
        let cylinder = |half: f64| {
            shape(Support::Cylinder {
                frame: Isometry3::identity(),
                radius: 0.06,
                length: 2.0 * half,
            })
        };
        let (a, b) = (cylinder(0.1361), cylinder(0.0535));
        let pose_b = Pose::from_parts(
            Vector::new(
                0.11739399448639881,
                -2.4626828354357144e-13,
                0.13104511347308617,
            ),
            Rotation::from_xyzw(
                0.724822527272481,
                0.08759207293452714,
                0.6784089424617102,
                0.08198316598760003,
            ),
        );
        let margin = 2.5897373303356773e-5;
        let mut memory = PairMemory {
            axis: Vector::new(
                0.7019808249020961,
                -5.569407617083876e-7,
                0.7121958448835984,
            ),
            held_support: None,
            in_contact: true,
        };
        let found = proximity(
            &a,
            &Pose::IDENTITY,
            &b,
            &pose_b,
            margin,
            &mut memory,
            None,
            &mut VoronoiSimplex::new(),
        );
        assert_eq!(found, Proximity::Beyond);
        // The gap, 46 µm, from a query that keeps nothing.
        let gap = apart(proximity(
            &a,
            &Pose::IDENTITY,
            &b,
            &pose_b,
            1e-3,
            &mut PairMemory::default(),
            None,
            &mut VoronoiSimplex::new(),
        ));
        assert!((gap - 4.612e-5).abs() < 1e-8, "{gap}");
    }

    /// Random shapes moved to a gap of about 0.1 µm to 100 µm and queried with a pair memory whose axis
    /// is all but the line between their boxes (so the two support points tried first nearly coincide):
    /// every answer is the one of a query that keeps nothing. With parry's GJK seeded with those points,
    /// one of 2,675 was not: a contact where a cylinder and a hull were apart beyond the margin.
    #[test]
    fn what_a_pair_tried_first_changes_no_answer_on_near_touching_pairs() {
        let mut rng = SplitMix64::new(23);
        let shapes = random_shapes(&mut rng);
        let mut simplex = VoronoiSimplex::new();
        let (mut differing, mut queries) = (Vec::new(), 0);
        for k in 0..3000 {
            let (a, b) = (
                &shapes[k % shapes.len()],
                &shapes[(k * 7 + 3) % shapes.len()],
            );
            let (pose_a, pose_b) = (
                to_pose(&random_frame(&mut rng)),
                to_pose(&random_frame(&mut rng)),
            );
            let GJKResult::ClosestPoints(on_a, on_b, _) =
                closest_points_support_map_support_map_with_params(
                    &pose_a.inv_mul(&pose_b),
                    &a.core,
                    &b.core,
                    f64::INFINITY,
                    &mut simplex,
                    None,
                )
            else {
                continue;
            };
            // Moved along the line between the closest points to a gap of about `target`.
            let distance = on_a.distance(on_b) - a.radius - b.radius;
            if distance <= 1e-3 {
                continue;
            }
            let target = 10f64.powf(rng.uniform(-7.0, -4.0));
            let step = (on_b - on_a).normalize() * (distance - target);
            let moved =
                Pose::from_parts(pose_b.translation - pose_a.rotation * step, pose_b.rotation);
            let toward = (pose_a.inv_mul(&moved).transform_point(b.inner) - a.inner).normalize();
            let tilt = Vector::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
            );
            // As the sampler asks: never below the contact distance.
            let margin = (target * rng.uniform(0.5, 2.0)).max(CONTACT_DISTANCE);
            let mut memory = PairMemory {
                axis: (toward + tilt * 1e-7).normalize(),
                held_support: None,
                in_contact: k % 2 == 0,
            };
            let found = proximity(
                a,
                &pose_a,
                b,
                &moved,
                margin,
                &mut memory,
                None,
                &mut simplex,
            );
            let kept_nothing = proximity(
                a,
                &pose_a,
                b,
                &moved,
                margin,
                &mut PairMemory::default(),
                None,
                &mut simplex,
            );
            queries += 1;
            let same = match (found, kept_nothing) {
                // GJK's tolerance on a cylinder (where the report rounds to the micrometre).
                (Proximity::Apart(x), Proximity::Apart(y)) => (x - y).abs() < 1e-8,
                (x, y) => x == y,
            };
            if !same {
                differing.push((k, found, kept_nothing));
            }
        }
        assert!(queries > 2000, "{queries} queries");
        assert!(
            differing.is_empty(),
            "{} of {queries} answers differ: {:?}",
            differing.len(),
            &differing[..differing.len().min(5)]
        );
    }

    #[test]
    fn degenerate_hulls_do_not_panic() {
        let point = shape(Support::Points(vec![Vector3::new(0.0, 0.0, 0.0)]));
        let flat = shape(Support::Points(vec![
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
        ]));
        let d = apart(query(&point, &at(0.0, 0.0, 1.0), &flat, &at(0.0, 0.0, 0.0)));
        assert!((d - 1.0).abs() < 1e-9);
        assert_eq!(
            query(&point, &at(0.2, 0.2, 0.0), &flat, &at(0.0, 0.0, 0.0)),
            Proximity::Contact
        );
        assert!(ConvexShape::from_support(&Support::Points(Vec::new())).is_none());
        assert!(
            ConvexShape::from_support(&Support::Points(vec![Vector3::new(1e9, 0.0, 0.0)]))
                .is_none()
        );
    }

    /// Depths a simulator would find: spheres and boxes on paper, two equal cylinders at one place (GJK
    /// then stops on a degenerate simplex and EPA answers 0: the depth was 0 before), and shapes apart.
    #[test]
    fn overlap_depths_are_the_least_separating_translation() {
        let at = |x: f64, y: f64, z: f64| to_pose(&Isometry3::translation(x, y, z));
        let sphere = |radius| {
            ConvexShape::from_support(&Support::Rounded {
                frame: Isometry3::identity(),
                radius,
                length: 0.0,
            })
            .unwrap()
        };
        let cube = ConvexShape::from_support(&Support::Points(
            [-1.0, 1.0]
                .iter()
                .flat_map(|&x| {
                    [-1.0, 1.0].iter().flat_map(move |&y| {
                        [-1.0, 1.0]
                            .iter()
                            .map(move |&z| Vector3::new(x, y, z) * 0.1)
                    })
                })
                .collect(),
        ))
        .unwrap();
        let cylinder = ConvexShape::from_support(&Support::Cylinder {
            frame: Isometry3::identity(),
            radius: 0.02,
            length: 0.31,
        })
        .unwrap();
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
        let origin = at(0.0, 0.0, 0.0);
        assert!(close(
            overlap_depth(&sphere(0.1), &origin, &sphere(0.1), &at(0.15, 0.0, 0.0)),
            0.05
        ));
        assert_eq!(
            overlap_depth(&sphere(0.1), &origin, &sphere(0.1), &at(0.25, 0.0, 0.0)),
            0.0
        );
        assert!(close(
            overlap_depth(&cube, &origin, &sphere(0.05), &at(0.0, 0.0, 0.12)),
            0.03
        ));
        assert!(close(
            overlap_depth(&cube, &origin, &cube, &at(0.0, 0.15, 0.01)),
            0.05
        ));
        assert!(close(
            overlap_depth(&cylinder, &origin, &cylinder, &origin),
            0.04
        ));
        // Below a plane: a sphere of 0.1 m at 0.07 m above the floor reaches 30 mm into it.
        let floor = (Vector3::zeros(), Vector3::z());
        let depth = depth_below_plane(
            &sphere(0.1),
            &Isometry3::translation(0.0, 0.0, 0.07),
            &floor.0,
            &floor.1,
        );
        assert!(close(depth, 0.03), "{depth}");
    }
}
