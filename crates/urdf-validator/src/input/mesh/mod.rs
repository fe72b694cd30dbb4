//! Mesh files → [`MeshData`]: the vertices (metres, Z up, in the mesh file's own frame), their convex
//! hull and their axis-aligned bounds, for the stability and self-collision analyses.
//!
//! Formats, chosen by extension (case-insensitive):
//! * **STL** (`.stl`), binary and ASCII. A binary file whose 80-byte header starts with `solid` is
//!   common, so the size decides first: `84 + 50·n` bytes (with `n` the header's triangle count) means
//!   binary. Otherwise a file that starts with `solid` and has no NUL byte near the start is ASCII.
//! * **Wavefront OBJ** (`.obj`): `v x y z [w]` lines (extra numbers such as vertex colours are
//!   ignored); `f` lines only count triangles (a polygon of k vertices is k − 2 triangles). Material
//!   libraries are never opened.
//! * **COLLADA** (`.dae`): geometry positions instantiated through the visual scene, with node
//!   transforms composed down the hierarchy, `<unit meter>` applied once to everything (node
//!   translations included) and `<up_axis>` turned into Z up at the root (see [`UpAxisPolicy`]).
//!
//! Files are untrusted: nothing here panics on file content, memory and time are bounded
//! ([`MAX_FILE_BYTES`], [`MAX_VERTICES`], an XML node limit, a node-instancing depth and count limit,
//! instantiated COLLADA vertices proportional to the file size: [`MAX_INSTANCED_PER_BYTE`]),
//! and every error names the file and, where possible, the line (text formats) or byte offset (binary
//! STL).
//!
//! Vertices are deduplicated exactly (same bits, `-0.0` folded into `0.0`), keeping the order of
//! first occurrence: an STL's triangle soup shrinks about sixfold. The convex hull is computed with
//! parry3d-f64's quickhull after an affine normalisation (see [`MeshData::hull`]).

mod cache;
mod collada;
mod disk_cache;
pub(crate) mod hull;
mod obj;
pub mod solid;
mod stl;
pub(crate) mod surface;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

pub use cache::MeshCache;
pub use disk_cache::DiskCache;
pub use obj::ObjReading;
pub use solid::{MeshSolid, SolidSource, VolumeIntegrals};

/// Largest mesh file read, in bytes (256 MiB).
pub const MAX_FILE_BYTES: u64 = 256 * 1024 * 1024;
/// Largest number of vertices read from one file (before deduplication; COLLADA: after instancing).
pub const MAX_VERTICES: usize = 20_000_000;
/// Deepest COLLADA node hierarchy followed (nested `<node>`s plus `<instance_node>` hops).
pub const MAX_NODE_DEPTH: usize = 32;
/// Most COLLADA nodes instantiated in one file (bounds `<instance_node>` fan-out).
pub const MAX_NODE_INSTANCES: usize = 100_000;
/// Most hull candidates handed to quickhull as they are; above it the candidates are thinned on a
/// grid first and the hull is approximate (see [`MeshData::hull`]). parry's quickhull costs about
/// candidates × hull vertices (≈ 1 s, release build, for 60,000 points that are all on the hull).
pub const HULL_EXACT_LIMIT: usize = 60_000;
/// Fewest vertices a COLLADA file may instantiate whatever its size (see [`MAX_INSTANCED_PER_BYTE`]).
pub const MIN_INSTANCED_VERTICES: usize = 1_000_000;
/// Most vertices a COLLADA file may instantiate per byte of file (above [`MIN_INSTANCED_VERTICES`]).
/// A position takes at least 6 bytes of text ("0 0 0 "), so this allows every position to be
/// instantiated a dozen times, but keeps a few kilobytes of nested `<instance_node>`s from expanding
/// into [`MAX_VERTICES`] vertices (1.6 GB and 30 s for a 50 KB file).
pub const MAX_INSTANCED_PER_BYTE: usize = 2;

/// One loaded mesh, in metres, Z up, before the URDF `scale`.
#[derive(Debug, Clone)]
pub struct MeshData {
    /// Every vertex, deduplicated exactly (first occurrence order). STL/OBJ: as in the file (no units:
    /// metres assumed). COLLADA: every position of every instantiated geometry, transformed into the
    /// file's root frame, in metres, Z up (unless [`UpAxisPolicy::Ignore`]).
    pub vertices: Vec<[f64; 3]>,
    /// Vertices of the convex hull (a subset of `vertices`, bit for bit); empty if the hull is
    /// degenerate (flat / < 4 points), then callers fall back to `vertices`.
    ///
    /// How it is computed:
    /// 1. **Whitening**: the vertices are centred and scaled along their principal axes to unit
    ///    variance. This affine map leaves the set of hull vertices unchanged but keeps thin plates
    ///    from being mistaken for flat ones. A cloud whose smallest principal variance is below 1e-12
    ///    of the largest is flat: no hull.
    /// 2. **Prefilter** (above 10,000 vertices, exact): the extreme points along 98 fixed directions
    ///    span an inner polytope; every vertex strictly inside it is dropped.
    /// 3. **Thinning** (only if more than [`HULL_EXACT_LIMIT`] candidates remain, i.e. a finely
    ///    tessellated, mostly convex surface; **approximate**): the candidates are bucketed on a 128³
    ///    grid (coarser, halving, until at most the limit remain) and each cell keeps only its point
    ///    farthest from the centroid. The hull then lies inside the true one, within about a cell
    ///    diagonal (≲ 1.5 % of the mesh size; 6e-5 on a 1-million-vertex sphere).
    /// 4. **Quickhull**: `parry3d_f64::transformation::try_convex_hull` on the candidates joggled by
    ///    ±5e-10 (whitened units), because parry can return a broken surface on exactly coplanar
    ///    points and then leave true hull vertices out. The result is checked (closed, consistently
    ///    oriented, locally convex, Euler characteristic 2, and every candidate inside when
    ///    candidates × faces ≤ 2·10⁶; tests check every corpus hull against the vertices' extremes); if the check fails it is retried with a 100× larger joggle,
    ///    then left empty. Corners whose incident facets do not span three directions (sine > 1e-6)
    ///    lie on a facet or an edge and are dropped, so a cube with points on its faces has 8.
    ///
    /// On the 883 meshes of the reference robots and the example-robot-data corpus, no vertex lies
    /// outside the hull by more than 1.3e-7 of the mesh's bounding-box diagonal.
    pub hull: Vec<[f64; 3]>,
    /// A triangulation of the hull's surface (indices into `hull`, by parry's quickhull on the hull
    /// vertices), checked once here to be closed and convex and to hold every hull vertex, so collision
    /// shapes climb along its edges without triangulating or checking each placed copy again; empty when
    /// it could not be built or failed the check (consumers then build their own, or scan).
    pub hull_triangles: Vec<[u32; 3]>,
    /// Axis-aligned bounds (min, max) of `vertices`.
    pub aabb: ([f64; 3], [f64; 3]),
    /// Triangle count as read (STL facets; OBJ `f` polygons as k − 2 triangles; COLLADA primitives of
    /// every instantiated geometry, once per instance).
    pub triangles: usize,
    /// The COLLADA `<asset><up_axis>` the file declares (`None` for STL/OBJ, or a COLLADA file
    /// without one), whether or not it was applied (see [`UpAxisPolicy`]).
    pub declared_up_axis: Option<ColladaUpAxis>,
    /// A binary STL whose size is exactly 84 + 50 bytes per declared triangle: the one mesh encoding
    /// MuJoCo reads as it is (the `--deep` pass hands it the file; anything else gets our hull).
    pub binary_stl: bool,
    /// The solid the mesh bounds, for mass properties: its own surface when that is closed (STL, OBJ),
    /// else its convex hull; `None` when neither encloses a volume (a flat mesh).
    pub solid: Option<MeshSolid>,
}

/// What the checks read of a mesh, without its points: cheap to get from the disk cache.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshSummary {
    /// Axis-aligned bounds (min, max) of the vertices ([`MeshData::aabb`]).
    pub aabb: ([f64; 3], [f64; 3]),
    /// Triangle count as read ([`MeshData::triangles`]).
    pub triangles: usize,
    /// The declared COLLADA up axis ([`MeshData::declared_up_axis`]).
    pub declared_up_axis: Option<ColladaUpAxis>,
    /// A binary STL MuJoCo reads ([`MeshData::binary_stl`]).
    pub binary_stl: bool,
    /// The solid it bounds ([`MeshData::solid`]).
    pub solid: Option<MeshSolid>,
}

impl MeshData {
    /// The mesh without its points.
    pub fn summary(&self) -> MeshSummary {
        MeshSummary {
            aabb: self.aabb,
            triangles: self.triangles,
            declared_up_axis: self.declared_up_axis,
            binary_stl: self.binary_stl,
            solid: self.solid,
        }
    }
}

/// The summary of a loaded mesh, or why it could not be loaded.
pub fn summary_of(loaded: &Result<MeshData, MeshError>) -> Result<MeshSummary, MeshError> {
    loaded.as_ref().map(MeshData::summary).map_err(Clone::clone)
}

/// A COLLADA up axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColladaUpAxis {
    /// `X_UP`: mapped to Z up by (x, y, z) → (−y, −z, x).
    X,
    /// `Y_UP`: mapped to Z up by (x, y, z) → (x, −z, y).
    Y,
    /// `Z_UP`: identity.
    Z,
}

impl ColladaUpAxis {
    /// The COLLADA spelling (`X_UP`, `Y_UP`, `Z_UP`).
    pub fn label(self) -> &'static str {
        match self {
            ColladaUpAxis::X => "X_UP",
            ColladaUpAxis::Y => "Y_UP",
            ColladaUpAxis::Z => "Z_UP",
        }
    }
}

/// What to do with a COLLADA file's `<asset><up_axis>`.
///
/// The COLLADA specification says to honour it. ROS tools do not: RViz drops the rotation part of
/// the root transform (keeping the unit scale), MoveIt's `geometric_shapes` and Gazebo classic ignore
/// the tag, so many ROS meshes (PR2's, for one) say `Y_UP` while their geometry is already Z up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum UpAxisPolicy {
    /// Rotate `X_UP`/`Y_UP` files so that their up axis becomes +Z (the COLLADA specification).
    #[default]
    Honour,
    /// Leave the axes as they are in the file (what RViz, MoveIt and Gazebo do).
    Ignore,
}

/// How meshes are loaded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MeshOptions {
    /// Treatment of COLLADA `<up_axis>`.
    pub up_axis: UpAxisPolicy,
    /// Whose reading of an OBJ file's faces.
    pub obj_reading: ObjReading,
}

/// Why a mesh could not be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: {message}", path.display())]
pub struct MeshError {
    /// The mesh file.
    pub path: PathBuf,
    /// What went wrong: what was expected, with the line (text formats) or byte offset (binary STL)
    /// where possible.
    pub message: String,
}

/// Load a mesh file, choosing the format by extension (case-insensitive): `.stl`, `.obj` or `.dae`,
/// with the default [`MeshOptions`].
pub fn load_mesh(path: &Path) -> Result<MeshData, MeshError> {
    load_mesh_with(path, &MeshOptions::default())
}

/// Load a mesh file like [`load_mesh`], with explicit options.
pub fn load_mesh_with(path: &Path, options: &MeshOptions) -> Result<MeshData, MeshError> {
    load(path, options).map_err(|message| MeshError {
        path: path.to_path_buf(),
        message,
    })
}

// ---------------------------------------------------------------------------------------------
// Reading

#[derive(Clone, Copy, PartialEq, Eq)]
enum Format {
    Stl,
    Obj,
    Dae,
}

/// What a format parser hands back.
struct RawMesh {
    vertices: Vec<[f64; 3]>,
    triangles: usize,
    declared_up_axis: Option<ColladaUpAxis>,
    /// [`MeshData::binary_stl`].
    binary_stl: bool,
    /// The surface's triangles (indices into `vertices`), or `None` when the format's are not read
    /// (COLLADA) or an OBJ face names no vertex read.
    faces: Option<Vec<[u32; 3]>>,
}

/// A mesh file's surface as written: its vertices (deduplicated exactly) and triangles (indices into
/// them), for computations that follow another tool's reading of the triangles (MuJoCo's mesh inertia).
#[derive(Debug, Clone)]
pub struct Surface {
    /// The vertices, metres.
    pub vertices: Vec<[f64; 3]>,
    /// The triangles.
    pub triangles: Vec<[u32; 3]>,
}

/// The surface of an STL or OBJ file as MuJoCo reads it (an OBJ's first object, see
/// [`ObjReading::MuJoCo`]; COLLADA triangles are not read: an error says so), with the loader's limits.
pub fn load_surface(path: &Path) -> Result<Surface, MeshError> {
    let error = |message: String| MeshError {
        path: path.to_path_buf(),
        message,
    };
    let options = MeshOptions {
        obj_reading: ObjReading::MuJoCo,
        ..MeshOptions::default()
    };
    let raw = read_raw(path, &options).map_err(error)?;
    match raw.faces {
        Some(triangles) => Ok(Surface {
            vertices: raw.vertices,
            triangles,
        }),
        None => Err(error(
            "the mesh's triangles are not read (COLLADA, or an OBJ face naming no vertex)"
                .to_string(),
        )),
    }
}

/// The surface of a mesh file for drawing it: an STL or OBJ file's as [`load_surface`] reads it, a
/// COLLADA file's instantiated triangles (node transforms, unit and up axis applied as for its vertices,
/// polygons fanned), with the loader's limits. Only the view reads it: what the validator computes from
/// meshes never does. `options` apply to COLLADA only (OBJ faces are read as [`load_surface`] reads them).
pub fn load_view_surface(path: &Path, options: &MeshOptions) -> Result<Surface, MeshError> {
    if !matches!(format_of(path), Ok(Format::Dae)) {
        return load_surface(path);
    }
    let error = |message: String| MeshError {
        path: path.to_path_buf(),
        message,
    };
    let bytes = read_bytes(path).map_err(error)?;
    collada::triangles(&bytes, options).map_err(error)
}

fn load(path: &Path, options: &MeshOptions) -> Result<MeshData, String> {
    read_raw(path, options).map(finish)
}

fn read_raw(path: &Path, options: &MeshOptions) -> Result<RawMesh, String> {
    let format = format_of(path)?;
    let bytes = read_bytes(path)?;
    match format {
        Format::Stl => stl::parse_stl(&bytes),
        Format::Obj => obj::parse(&bytes, options.obj_reading),
        Format::Dae => collada::parse_dae(&bytes, options),
    }
}

/// A mesh file's bytes, within [`MAX_FILE_BYTES`].
fn read_bytes(path: &Path) -> Result<Vec<u8>, String> {
    let size = std::fs::metadata(path)
        .map_err(|e| format!("cannot read file: {e}"))?
        .len();
    if size > MAX_FILE_BYTES {
        return Err(format!(
            "file is {size} bytes, larger than the {MAX_FILE_BYTES}-byte limit for meshes"
        ));
    }
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read file: {e}"))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(format!(
            "file is {} bytes, larger than the {MAX_FILE_BYTES}-byte limit for meshes",
            bytes.len()
        ));
    }
    Ok(bytes)
}

fn format_of(path: &Path) -> Result<Format, String> {
    let Some(ext) = path.extension() else {
        return Err("mesh file has no extension (expected .stl, .obj or .dae)".to_string());
    };
    let ext = ext.to_string_lossy();
    match ext.to_ascii_lowercase().as_str() {
        "stl" => Ok(Format::Stl),
        "obj" => Ok(Format::Obj),
        "dae" => Ok(Format::Dae),
        _ => Err(format!(
            "unsupported mesh format '.{ext}' (expected .stl, .obj or .dae)"
        )),
    }
}

fn finish(raw: RawMesh) -> MeshData {
    let aabb = bounds(&raw.vertices);
    let hull = hull::convex_hull(&raw.vertices, aabb);
    let hull_triangles = hull::triangulate(&hull);
    let solid = solid_of(&raw, &hull, &hull_triangles);
    MeshData {
        vertices: raw.vertices,
        hull,
        hull_triangles,
        aabb,
        triangles: raw.triangles,
        declared_up_axis: raw.declared_up_axis,
        binary_stl: raw.binary_stl,
        solid,
    }
}

/// The solid of a mesh: its surface's when that is closed and encloses a positive volume, else its
/// convex hull's (wound outwards by construction), else none.
fn solid_of(raw: &RawMesh, hull: &[[f64; 3]], hull_triangles: &[[u32; 3]]) -> Option<MeshSolid> {
    let enclosed = |integrals: VolumeIntegrals| {
        (integrals.is_finite() && integrals.volume > 0.0).then_some(integrals)
    };
    let fallback = match &raw.faces {
        Some(faces) => {
            let closed = solid::is_closed(faces)
                .then(|| VolumeIntegrals::of_surface(&raw.vertices, faces))
                .flatten()
                .and_then(enclosed);
            if let Some(integrals) = closed {
                return Some(MeshSolid {
                    integrals,
                    source: SolidSource::ClosedSurface,
                });
            }
            SolidSource::HullOfOpenSurface
        }
        None => SolidSource::HullSurfaceNotRead,
    };
    let integrals = VolumeIntegrals::of_surface(hull, hull_triangles).and_then(enclosed)?;
    Some(MeshSolid {
        integrals,
        source: fallback,
    })
}

fn bounds(vertices: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    for v in vertices {
        for k in 0..3 {
            min[k] = min[k].min(v[k]);
            max[k] = max[k].max(v[k]);
        }
    }
    (min, max)
}

/// Collects vertices, dropping exact duplicates and enforcing a vertex limit ([`MAX_VERTICES`] unless
/// set lower).
struct VertexSink {
    vertices: Vec<[f64; 3]>,
    seen: HashMap<[u64; 3], u32>,
    read: usize,
    limit: usize,
}

impl Default for VertexSink {
    fn default() -> Self {
        VertexSink {
            vertices: Vec::new(),
            seen: HashMap::new(),
            read: 0,
            limit: MAX_VERTICES,
        }
    }
}

impl VertexSink {
    /// Add one vertex and return its index among the deduplicated vertices; `Err` with a message
    /// (without location) past the limit or on a non-finite value.
    fn push(&mut self, v: [f64; 3]) -> Result<u32, String> {
        self.read += 1;
        if self.read > self.limit {
            return Err(if self.limit == MAX_VERTICES {
                format!("more than {MAX_VERTICES} vertices (limit)")
            } else {
                format!(
                    "more than {} vertices instantiated (limit: {MAX_INSTANCED_PER_BYTE} per byte of \
                     the file, at least {MIN_INSTANCED_VERTICES})",
                    self.limit
                )
            });
        }
        if !v.iter().all(|c| c.is_finite()) {
            return Err(format!("non-finite vertex {v:?}"));
        }
        // `+ 0.0` folds -0.0 into 0.0 so that both hash alike.
        let v = [v[0] + 0.0, v[1] + 0.0, v[2] + 0.0];
        // Below MAX_VERTICES (checked above), so the index fits.
        let next = self.vertices.len() as u32;
        let index = *self.seen.entry(bits(v)).or_insert(next);
        if index == next {
            self.vertices.push(v);
        }
        Ok(index)
    }

    /// The vertices read, or an error if there are none.
    fn finish(self, what: &str) -> Result<Vec<[f64; 3]>, String> {
        if self.vertices.is_empty() {
            Err(format!("no vertices found (expected {what})"))
        } else {
            Ok(self.vertices)
        }
    }
}

fn bits(v: [f64; 3]) -> [u64; 3] {
    [v[0].to_bits(), v[1].to_bits(), v[2].to_bits()]
}

/// A finite number, or `None`.
fn number(token: &[u8]) -> Option<f64> {
    std::str::from_utf8(token)
        .ok()?
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
}

/// A token for an error message: lossy UTF-8, at most 40 characters.
fn shown(token: &[u8]) -> String {
    let text = String::from_utf8_lossy(token);
    if text.chars().count() > 40 {
        format!("{}…", text.chars().take(40).collect::<String>())
    } else {
        text.into_owned()
    }
}

/// Lines (1-based numbers, `\r` stripped) and their whitespace-separated tokens.
fn lines(bytes: &[u8]) -> impl Iterator<Item = (usize, Vec<&[u8]>)> {
    bytes.split(|&b| b == b'\n').enumerate().map(|(i, line)| {
        let tokens = line
            .split(|b| b.is_ascii_whitespace())
            .filter(|t| !t.is_empty())
            .collect();
        (i + 1, tokens)
    })
}

/// Parse the three numbers after a keyword (`tokens[1..4]`); `what` names the keyword in errors.
fn xyz(tokens: &[&[u8]], line: usize, what: &str) -> Result<[f64; 3], String> {
    let mut v = [0.0; 3];
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        let Some(token) = tokens.get(k + 1) else {
            return Err(format!(
                "line {line}: expected 3 numbers after '{what}', found {}",
                tokens.len().saturating_sub(1)
            ));
        };
        v[k] = number(token).ok_or_else(|| {
            format!(
                "line {line}: expected a finite number for the {axis} coordinate of '{what}', found '{}'",
                shown(token)
            )
        })?;
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sink_dedupes_and_folds_negative_zero() {
        let mut sink = VertexSink::default();
        sink.push([0.0, 1.0, 2.0]).unwrap();
        sink.push([-0.0, 1.0, 2.0]).unwrap();
        sink.push([0.0, 1.0, 2.0]).unwrap();
        assert_eq!(sink.vertices.len(), 1);
        assert!(sink.push([f64::NAN, 0.0, 0.0]).is_err());
    }
}
