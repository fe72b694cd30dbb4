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

mod disk_cache;
mod obj;
pub mod solid;
pub(crate) mod surface;

use std::collections::{HashMap, HashSet};
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

use nalgebra::{Matrix4, Rotation3, SymmetricEigen, Unit, Vector3};
use roxmltree::{Document, Node};

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
/// Above this many vertices, points provably inside the hull are dropped before quickhull.
const HULL_PREFILTER_MIN: usize = 64;
/// Largest points × hull faces product for which every point is checked to be inside the hull.
const HULL_CONTAINMENT_CHECK_LIMIT: usize = 2_000_000;
/// Grid resolution (cells per axis) of the first thinning step above [`HULL_EXACT_LIMIT`].
const HULL_GRID_CELLS: u32 = 128;
/// Fewest vertices a COLLADA file may instantiate whatever its size (see [`MAX_INSTANCED_PER_BYTE`]).
pub const MIN_INSTANCED_VERTICES: usize = 1_000_000;
/// Most vertices a COLLADA file may instantiate per byte of file (above [`MIN_INSTANCED_VERTICES`]).
/// A position takes at least 6 bytes of text ("0 0 0 "), so this allows every position to be
/// instantiated a dozen times, but keeps a few kilobytes of nested `<instance_node>`s from expanding
/// into [`MAX_VERTICES`] vertices (1.6 GB and 30 s for a 50 KB file).
pub const MAX_INSTANCED_PER_BYTE: usize = 2;
/// Largest number of XML nodes accepted in a COLLADA file.
const MAX_XML_NODES: u32 = 5_000_000;
/// A point cloud whose smallest principal variance is below this fraction of the largest is flat.
const FLAT_VARIANCE_RATIO: f64 = 1e-12;

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

    /// The rotation that takes this axis to +Z (right-handed, a proper rotation).
    fn to_z_up(self) -> Matrix4<f64> {
        #[rustfmt::skip]
        let m = match self {
            ColladaUpAxis::X => Matrix4::new(
                0.0, -1.0, 0.0, 0.0,
                0.0, 0.0, -1.0, 0.0,
                1.0, 0.0, 0.0, 0.0,
                0.0, 0.0, 0.0, 1.0,
            ),
            ColladaUpAxis::Y => Matrix4::new(
                1.0, 0.0, 0.0, 0.0,
                0.0, 0.0, -1.0, 0.0,
                0.0, 1.0, 0.0, 0.0,
                0.0, 0.0, 0.0, 1.0,
            ),
            ColladaUpAxis::Z => Matrix4::identity(),
        };
        m
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

/// Thread-safe cache keyed by path: each file read and parsed once per run, shared across
/// robots/poses. Clones share the same entries. With a [`DiskCache`], meshes loaded in earlier runs are
/// read from it, and meshes loaded now are kept in it.
#[derive(Default, Clone)]
pub struct MeshCache {
    entries: Arc<Mutex<CacheEntries>>,
    /// Summaries read from the disk cache (meshes not loaded), so each entry header is read once.
    summaries: Arc<Mutex<HashMap<PathBuf, MeshSummary>>>,
    options: MeshOptions,
    disk: Option<DiskCache>,
}

type CacheEntries = HashMap<PathBuf, Arc<Result<MeshData, MeshError>>>;

impl fmt::Debug for MeshCache {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let entries = self.lock().len();
        f.debug_struct("MeshCache")
            .field("entries", &entries)
            .field("options", &self.options)
            .field("disk", &self.disk)
            .finish()
    }
}

impl MeshCache {
    /// An empty cache loading with the default [`MeshOptions`].
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty cache loading with `options`.
    pub fn with_options(options: MeshOptions) -> Self {
        Self {
            entries: Arc::default(),
            summaries: Arc::default(),
            options,
            disk: None,
        }
    }

    /// This cache, also reading and keeping meshes in `disk` (across runs).
    pub fn with_disk_cache(self, disk: DiskCache) -> Self {
        Self {
            disk: Some(disk),
            ..self
        }
    }

    /// The mesh at `path` (or why it could not be loaded), read on first use. The lock is not held
    /// while a file is parsed; if two threads race on the same new path both parse it, and both get
    /// the entry stored first.
    pub fn get(&self, path: &Path) -> Arc<Result<MeshData, MeshError>> {
        if let Some(entry) = self.lock().get(path) {
            return Arc::clone(entry);
        }
        let loaded = Arc::new(self.load(path));
        Arc::clone(self.lock().entry(path.to_path_buf()).or_insert(loaded))
    }

    /// The mesh at `path` without its points (or why it could not be loaded): from this cache when it
    /// holds the mesh, else from the disk cache's entry header alone (read once), else loaded whole (and
    /// kept).
    pub fn summary(&self, path: &Path) -> Result<MeshSummary, MeshError> {
        if let Some(entry) = self.lock().get(path) {
            return summary_of(entry);
        }
        let summaries = || {
            self.summaries
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
        };
        if let Some(summary) = summaries().get(path) {
            return Ok(*summary);
        }
        if let Some(summary) = self
            .disk
            .as_ref()
            .and_then(|disk| disk.read_summary(path, &self.options))
        {
            summaries().insert(path.to_path_buf(), summary);
            return Ok(summary);
        }
        summary_of(&self.get(path))
    }

    /// The mesh at `path` from the disk cache, else from its file (then kept in the disk cache).
    fn load(&self, path: &Path) -> Result<MeshData, MeshError> {
        let Some(disk) = &self.disk else {
            return load_mesh_with(path, &self.options);
        };
        if let Some(mesh) = disk.read(path, &self.options) {
            return Ok(mesh);
        }
        let loaded = load_mesh_with(path, &self.options);
        if let Ok(mesh) = &loaded {
            disk.write(path, &self.options, mesh);
        }
        loaded
    }

    /// Number of paths loaded (or failed) so far.
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    /// Whether nothing has been loaded yet.
    pub fn is_empty(&self) -> bool {
        self.lock().is_empty()
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, CacheEntries> {
        // A panic elsewhere while holding the lock cannot leave the map half-updated.
        self.entries.lock().unwrap_or_else(PoisonError::into_inner)
    }
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

fn load(path: &Path, options: &MeshOptions) -> Result<MeshData, String> {
    read_raw(path, options).map(finish)
}

fn read_raw(path: &Path, options: &MeshOptions) -> Result<RawMesh, String> {
    let format = format_of(path)?;
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
    match format {
        Format::Stl => parse_stl(&bytes),
        Format::Obj => obj::parse(&bytes, options.obj_reading),
        Format::Dae => parse_dae(&bytes, options),
    }
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
    let hull = convex_hull(&raw.vertices, aabb);
    let hull_triangles = triangulate(&hull);
    let solid = solid_of(&raw, &hull, &hull_triangles);
    MeshData {
        vertices: raw.vertices,
        hull,
        hull_triangles,
        aabb,
        triangles: raw.triangles,
        declared_up_axis: raw.declared_up_axis,
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

// ---------------------------------------------------------------------------------------------
// STL

fn parse_stl(bytes: &[u8]) -> Result<RawMesh, String> {
    if bytes.is_empty() {
        return Err("empty file (expected binary or ASCII STL)".to_string());
    }
    let declared = (bytes.len() >= 84)
        .then(|| u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64);
    let binary_size = declared.map(|n| 84 + 50 * n);
    if binary_size == Some(bytes.len() as u64) {
        return parse_binary_stl(bytes);
    }
    let starts_with_solid = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .is_some_and(|start| bytes[start..].starts_with(b"solid"));
    let textual = !bytes[..bytes.len().min(1024)].contains(&0);
    if starts_with_solid && textual {
        return parse_ascii_stl(bytes, declared);
    }
    if bytes.len() < 84 {
        return Err(format!(
            "file is {} bytes: too short for a binary STL (80-byte header and 4-byte triangle count) \
             and does not start with 'solid' (ASCII STL)",
            bytes.len()
        ));
    }
    // Binary with a size that does not match: truncated is an error, trailing bytes are ignored.
    parse_binary_stl(bytes)
}

fn parse_binary_stl(bytes: &[u8]) -> Result<RawMesh, String> {
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let expected = 84 + 50 * count as u64;
    let complete = (bytes.len() - 84) / 50;
    if complete < count {
        let offset = 84 + 50 * complete;
        return Err(format!(
            "byte offset {offset}: binary STL truncated: triangle {complete} of {count} is incomplete \
             (the header declares {count} triangles, {expected} bytes; the file has {} bytes)",
            bytes.len()
        ));
    }
    if count == 0 {
        return Err("binary STL declares 0 triangles (byte offset 80)".to_string());
    }
    let mut sink = VertexSink::default();
    let mut faces = Vec::with_capacity(count);
    for t in 0..count {
        let base = 84 + 50 * t;
        let mut face = [0u32; 3];
        for (corner, index) in face.iter_mut().enumerate() {
            let at = base + 12 + 12 * corner;
            let mut v = [0.0; 3];
            for (k, value) in v.iter_mut().enumerate() {
                let o = at + 4 * k;
                let raw = [bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]];
                *value = f64::from(f32::from_le_bytes(raw));
            }
            *index = sink
                .push(v)
                .map_err(|e| format!("byte offset {at}: triangle {t}, vertex {corner}: {e}"))?;
        }
        faces.push(face);
    }
    Ok(RawMesh {
        vertices: sink.finish("binary STL triangles")?,
        triangles: count,
        declared_up_axis: None,
        faces: Some(faces),
    })
}

fn parse_ascii_stl(bytes: &[u8], declared: Option<u64>) -> Result<RawMesh, String> {
    let mut sink = VertexSink::default();
    let mut facets = 0usize;
    // The vertices of the facet being read; a facet of other than three vertices leaves the surface
    // unknown.
    let mut corners: Vec<u32> = Vec::with_capacity(3);
    let mut faces = Some(Vec::new());
    for (line, tokens) in lines(bytes) {
        let Some(first) = tokens.first() else {
            continue;
        };
        if first.eq_ignore_ascii_case(b"vertex") {
            let v = xyz(&tokens, line, "vertex")?;
            corners.push(sink.push(v).map_err(|e| format!("line {line}: {e}"))?);
        } else if first.eq_ignore_ascii_case(b"facet") {
            facets += 1;
        } else if first.eq_ignore_ascii_case(b"endfacet") {
            match (corners.as_slice(), faces.as_mut()) {
                (&[a, b, c], Some(faces)) => faces.push([a, b, c]),
                _ => faces = None,
            }
            corners.clear();
        }
    }
    if !corners.is_empty() {
        faces = None;
    }
    if sink.vertices.is_empty() {
        let hint = match declared {
            Some(n) => format!(
                "; if it is binary, its size {} does not match 84 + 50 × {n} triangles from its header",
                bytes.len()
            ),
            None => String::new(),
        };
        return Err(format!(
            "ASCII STL (starts with 'solid') has no 'vertex x y z' lines{hint}"
        ));
    }
    Ok(RawMesh {
        vertices: sink.vertices,
        triangles: facets,
        declared_up_axis: None,
        faces,
    })
}

// ---------------------------------------------------------------------------------------------
// COLLADA

/// A geometry's positions in file units, and its triangle count.
struct Geometry {
    positions: Vec<[f64; 3]>,
    triangles: usize,
}

struct Collada<'a, 'input> {
    doc: &'a Document<'input>,
    ids: HashMap<&'a str, Node<'a, 'input>>,
    geometries: HashMap<&'a str, Arc<Geometry>>,
    sink: VertexSink,
    triangles: usize,
    instances: usize,
}

fn parse_dae(bytes: &[u8], options: &MeshOptions) -> Result<RawMesh, String> {
    if bytes.is_empty() {
        return Err("empty file (expected COLLADA XML)".to_string());
    }
    let text = std::str::from_utf8(bytes).map_err(|e| {
        format!(
            "byte offset {}: not UTF-8 (expected COLLADA XML in UTF-8)",
            e.valid_up_to()
        )
    })?;
    let parsing = roxmltree::ParsingOptions {
        allow_dtd: true,
        nodes_limit: MAX_XML_NODES,
        ..Default::default()
    };
    let doc = Document::parse_with_options(text, parsing).map_err(|e| {
        let pos = e.pos();
        format!("line {}, column {}: invalid XML: {e}", pos.row, pos.col)
    })?;
    let root = doc.root_element();
    if root.tag_name().name() != "COLLADA" {
        return Err(format!(
            "line {}: expected a <COLLADA> root element, found <{}>",
            line_of(&doc, root),
            root.tag_name().name()
        ));
    }
    let mut c = Collada {
        doc: &doc,
        ids: HashMap::new(),
        geometries: HashMap::new(),
        sink: VertexSink {
            limit: bytes
                .len()
                .saturating_mul(MAX_INSTANCED_PER_BYTE)
                .clamp(MIN_INSTANCED_VERTICES, MAX_VERTICES),
            ..VertexSink::default()
        },
        triangles: 0,
        instances: 0,
    };
    for node in root.descendants().filter(|n| n.is_element()) {
        if let Some(id) = node.attribute("id") {
            c.ids.entry(id).or_insert(node);
        }
    }

    let (unit, declared_up_axis) = c.asset(root)?;
    let mut top = Matrix4::new_scaling(unit);
    if let (Some(axis), UpAxisPolicy::Honour) = (declared_up_axis, options.up_axis) {
        top = axis.to_z_up() * top;
    }

    match c.scene(root)? {
        Some(scene) => {
            for node in elements(scene).filter(|n| tag(*n) == "node") {
                c.node(node, &top, 1)?;
            }
        }
        None => {
            // No visual scene: every geometry, untransformed (unit and up axis still apply).
            let geometries: Vec<Node> = root
                .descendants()
                .filter(|n| n.is_element() && tag(*n) == "geometry")
                .collect();
            for geometry in geometries {
                c.instantiate(geometry, &top)?;
            }
        }
    }
    let triangles = c.triangles;
    Ok(RawMesh {
        vertices: c
            .sink
            .finish("COLLADA <mesh> positions instantiated by the visual scene")?,
        triangles,
        declared_up_axis,
        faces: None,
    })
}

fn tag<'a>(node: Node<'a, '_>) -> &'a str {
    node.tag_name().name()
}

fn elements<'a, 'i>(node: Node<'a, 'i>) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(|n| n.is_element())
}

fn child<'a, 'i>(node: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    elements(node).find(|n| tag(*n) == name)
}

fn line_of(doc: &Document, node: Node) -> u32 {
    doc.text_pos_at(node.range().start).row
}

/// The element's text as numbers (at most `limit` of them: the rest is not read), each finite; errors
/// give the line of the offending token.
fn floats(doc: &Document, node: Node, limit: usize) -> Result<Vec<f64>, String> {
    let Some(text_node) = node.first_child().filter(|n| n.is_text()) else {
        return Ok(Vec::new());
    };
    let text = text_node.text().unwrap_or("");
    let base = text_node.range().start;
    let mut out = Vec::new();
    for token in text.split_ascii_whitespace().take(limit) {
        match number(token.as_bytes()) {
            Some(v) => out.push(v),
            None => {
                // Offsets in the text are offsets in the file only when the text is the file's bytes
                // as they are: entity and character references change its length (and an entity's
                // text lies in the DTD), so then the element's position is given instead.
                let offset = token.as_ptr() as usize - text.as_ptr() as usize;
                let verbatim = doc.input_text().get(text_node.range()) == Some(text);
                let pos = doc.text_pos_at(if verbatim {
                    base + offset
                } else {
                    node.range().start
                });
                return Err(format!(
                    "line {}, column {}: expected a finite number in <{}>, found '{}'",
                    pos.row,
                    pos.col,
                    tag(node),
                    shown(token.as_bytes())
                ));
            }
        }
    }
    Ok(out)
}

/// Exactly `n` numbers from an element (transforms, bind_shape_matrix).
fn fixed_floats(doc: &Document, node: Node, n: usize) -> Result<Vec<f64>, String> {
    let values = floats(doc, node, n + 1)?;
    if values.len() != n {
        return Err(format!(
            "line {}: expected {n} numbers in <{}>, found {}",
            line_of(doc, node),
            tag(node),
            values.len()
        ));
    }
    Ok(values)
}

/// A non-negative integer attribute (absent → `default`).
fn usize_attr(doc: &Document, node: Node, name: &str, default: usize) -> Result<usize, String> {
    match node.attribute(name) {
        None => Ok(default),
        Some(text) => text.trim().parse::<usize>().map_err(|_| {
            format!(
                "line {}: expected a non-negative integer for <{} {name}>, found '{}'",
                line_of(doc, node),
                tag(node),
                shown(text.as_bytes())
            )
        }),
    }
}

/// Whitespace-separated tokens in an element's text.
fn token_count(node: Node) -> usize {
    node.text()
        .map(|t| t.split_ascii_whitespace().count())
        .unwrap_or(0)
}

impl<'a, 'input> Collada<'a, 'input> {
    /// `<asset><unit meter>` (default 1) and `<asset><up_axis>` (absent → `None`, no rotation).
    fn asset(&self, root: Node<'a, 'input>) -> Result<(f64, Option<ColladaUpAxis>), String> {
        let Some(asset) = child(root, "asset") else {
            return Ok((1.0, None));
        };
        let mut unit = 1.0;
        if let Some(node) = child(asset, "unit") {
            if let Some(text) = node.attribute("meter") {
                unit = text
                    .trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite() && *v > 0.0)
                    .ok_or_else(|| {
                        format!(
                            "line {}: expected a positive number for <unit meter>, found '{}'",
                            line_of(self.doc, node),
                            shown(text.as_bytes())
                        )
                    })?;
            }
        }
        let up = match child(asset, "up_axis") {
            None => None,
            Some(node) => match node.text().unwrap_or("").trim() {
                "X_UP" => Some(ColladaUpAxis::X),
                "Y_UP" => Some(ColladaUpAxis::Y),
                "Z_UP" => Some(ColladaUpAxis::Z),
                other => {
                    return Err(format!(
                        "line {}: expected X_UP, Y_UP or Z_UP in <up_axis>, found '{}'",
                        line_of(self.doc, node),
                        shown(other.as_bytes())
                    ))
                }
            },
        };
        Ok((unit, up))
    }

    /// The visual scene to instantiate: the one `<scene><instance_visual_scene url>` names, else the
    /// first `<visual_scene>`, else none.
    fn scene(&self, root: Node<'a, 'input>) -> Result<Option<Node<'a, 'input>>, String> {
        if let Some(instance) = child(root, "scene").and_then(|s| child(s, "instance_visual_scene"))
        {
            return self.target(instance, "url", "visual_scene").map(Some);
        }
        Ok(root
            .descendants()
            .find(|n| n.is_element() && tag(*n) == "visual_scene"))
    }

    /// The element a `#id` reference in attribute `attr` of `from` points to, which must be a `<kind>`.
    fn target(&self, from: Node, attr: &str, kind: &str) -> Result<Node<'a, 'input>, String> {
        let line = || line_of(self.doc, from);
        let name = tag(from);
        let Some(url) = from.attribute(attr) else {
            return Err(format!(
                "line {}: <{name}> has no '{attr}' attribute",
                line()
            ));
        };
        let Some(id) = url.strip_prefix('#') else {
            return Err(format!(
                "line {}: <{name} {attr}=\"{}\">: only references inside the file ('#id') are supported",
                line(),
                shown(url.as_bytes())
            ));
        };
        let Some(&node) = self.ids.get(id) else {
            return Err(format!(
                "line {}: <{name} {attr}=\"{}\">: no element with id '{}'",
                line(),
                shown(url.as_bytes()),
                shown(id.as_bytes())
            ));
        };
        if tag(node) != kind {
            return Err(format!(
                "line {}: <{name} {attr}=\"{}\"> points to a <{}> (line {}), expected a <{kind}>",
                line(),
                shown(url.as_bytes()),
                tag(node),
                line_of(self.doc, node)
            ));
        }
        Ok(node)
    }

    /// Instantiate `node` under `parent` (the transform to metres, Z up, of its parent frame).
    fn node(
        &mut self,
        node: Node<'a, 'input>,
        parent: &Matrix4<f64>,
        depth: usize,
    ) -> Result<(), String> {
        if depth > MAX_NODE_DEPTH {
            return Err(format!(
                "line {}: node hierarchy deeper than {MAX_NODE_DEPTH} levels (an <instance_node> cycle?)",
                line_of(self.doc, node)
            ));
        }
        self.instances += 1;
        if self.instances > MAX_NODE_INSTANCES {
            return Err(format!(
                "line {}: more than {MAX_NODE_INSTANCES} node instances (limit)",
                line_of(self.doc, node)
            ));
        }
        let mut m = *parent;
        for t in elements(node) {
            m *= match tag(t) {
                "matrix" => {
                    let v = fixed_floats(self.doc, t, 16)?;
                    Matrix4::from_row_slice(&v)
                }
                "translate" => {
                    let v = fixed_floats(self.doc, t, 3)?;
                    Matrix4::new_translation(&Vector3::new(v[0], v[1], v[2]))
                }
                "rotate" => {
                    let v = fixed_floats(self.doc, t, 4)?;
                    match Unit::try_new(Vector3::new(v[0], v[1], v[2]), f64::MIN_POSITIVE) {
                        Some(axis) => {
                            Rotation3::from_axis_angle(&axis, v[3].to_radians()).to_homogeneous()
                        }
                        None => Matrix4::identity(),
                    }
                }
                "scale" => {
                    let v = fixed_floats(self.doc, t, 3)?;
                    Matrix4::new_nonuniform_scaling(&Vector3::new(v[0], v[1], v[2]))
                }
                "lookat" => {
                    let v = fixed_floats(self.doc, t, 9)?;
                    look_at(&v)
                }
                // <skew> is not supported (practically unused); other children are not transforms.
                _ => continue,
            };
        }
        for item in elements(node) {
            match tag(item) {
                "node" => self.node(item, &m, depth + 1)?,
                "instance_node" => {
                    let target = self.target(item, "url", "node")?;
                    self.node(target, &m, depth + 1)?;
                }
                "instance_geometry" => {
                    let geometry = self.target(item, "url", "geometry")?;
                    self.instantiate(geometry, &m)?;
                }
                "instance_controller" => self.controller(item, &m)?,
                _ => {}
            }
        }
        Ok(())
    }

    /// `<instance_controller>` → `<controller><skin source="#geometry">` (with its
    /// `<bind_shape_matrix>`) or `<morph source="#geometry">`.
    fn controller(&mut self, item: Node<'a, 'input>, m: &Matrix4<f64>) -> Result<(), String> {
        let controller = self.target(item, "url", "controller")?;
        if let Some(skin) = child(controller, "skin") {
            let geometry = self.target(skin, "source", "geometry")?;
            let bind = match child(skin, "bind_shape_matrix") {
                Some(b) => Matrix4::from_row_slice(&fixed_floats(self.doc, b, 16)?),
                None => Matrix4::identity(),
            };
            self.instantiate(geometry, &(m * bind))
        } else if let Some(morph) = child(controller, "morph") {
            let geometry = self.target(morph, "source", "geometry")?;
            self.instantiate(geometry, m)
        } else {
            Ok(())
        }
    }

    /// Add the positions of `geometry`, transformed by `m`, and its triangles.
    fn instantiate(&mut self, geometry: Node<'a, 'input>, m: &Matrix4<f64>) -> Result<(), String> {
        let Some(data) = self.geometry(geometry)? else {
            return Ok(());
        };
        // The affine part (COLLADA transforms are affine), in plain arithmetic for unoptimised builds.
        let row = |r: usize| [m[(r, 0)], m[(r, 1)], m[(r, 2)], m[(r, 3)]];
        let rows = [row(0), row(1), row(2)];
        for p in &data.positions {
            let q = rows.map(|r| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3]);
            self.sink.push(q).map_err(|e| {
                format!(
                    "line {}: geometry instantiated by the visual scene: {e}",
                    line_of(self.doc, geometry)
                )
            })?;
        }
        self.triangles = self.triangles.saturating_add(data.triangles);
        Ok(())
    }

    /// A `<geometry>`'s `<mesh>` (parsed once); `None` for other geometry kinds (splines…).
    fn geometry(&mut self, geometry: Node<'a, 'input>) -> Result<Option<Arc<Geometry>>, String> {
        let key = geometry.attribute("id").unwrap_or("");
        if !key.is_empty() {
            if let Some(data) = self.geometries.get(key) {
                return Ok(Some(Arc::clone(data)));
            }
        }
        let Some(mesh) = child(geometry, "mesh") else {
            return Ok(None);
        };
        let data = Arc::new(Geometry {
            positions: self.positions(mesh)?,
            triangles: self.mesh_triangles(mesh)?,
        });
        if !key.is_empty() {
            self.geometries.insert(key, Arc::clone(&data));
        }
        Ok(Some(data))
    }

    /// `<vertices><input semantic="POSITION" source="#…">` → `<source>` → accessor → float_array.
    fn positions(&self, mesh: Node<'a, 'input>) -> Result<Vec<[f64; 3]>, String> {
        let input = child(mesh, "vertices")
            .and_then(|v| {
                elements(v).find(|i| tag(*i) == "input" && i.attribute("semantic") == Some("POSITION"))
            })
            .ok_or_else(|| {
                format!(
                    "line {}: <mesh> has no <vertices><input semantic=\"POSITION\"> (expected vertex positions)",
                    line_of(self.doc, mesh)
                )
            })?;
        let source = self.target(input, "source", "source")?;
        let accessor = child(source, "technique_common").and_then(|t| child(t, "accessor"));
        let array = match accessor {
            Some(a) if a.attribute("source").is_some() => {
                self.target(a, "source", "float_array")?
            }
            _ => child(source, "float_array").ok_or_else(|| {
                format!(
                    "line {}: POSITION <source> has no <float_array>",
                    line_of(self.doc, source)
                )
            })?,
        };
        let (count, stride, offset, slots, values) = match accessor {
            Some(a) => {
                let stride = usize_attr(self.doc, a, "stride", 1)?;
                let offset = usize_attr(self.doc, a, "offset", 0)?;
                let count = usize_attr(self.doc, a, "count", 0)?;
                let params: Vec<Node> = elements(a).filter(|p| tag(*p) == "param").collect();
                let slots: Vec<usize> = if params.is_empty() {
                    vec![0, 1, 2]
                } else {
                    params
                        .iter()
                        .enumerate()
                        .filter(|(_, p)| p.attribute("name").is_some_and(|n| !n.is_empty()))
                        .map(|(i, _)| i)
                        .take(3)
                        .collect()
                };
                if slots.len() < 3 || slots.iter().any(|&s| s >= stride) {
                    return Err(format!(
                        "line {}: POSITION <accessor> must bind 3 named params within its stride {stride}",
                        line_of(self.doc, a)
                    ));
                }
                if count > MAX_VERTICES {
                    return Err(format!(
                        "line {}: POSITION <accessor> count {count} is more than {MAX_VERTICES} vertices (limit)",
                        line_of(self.doc, a)
                    ));
                }
                // Only the numbers the accessor reads are parsed.
                let needed = count
                    .saturating_sub(1)
                    .saturating_mul(stride)
                    .saturating_add(offset)
                    .saturating_add(stride);
                let values = floats(self.doc, array, needed)?;
                (count, stride, offset, slots, values)
            }
            None => {
                let values = floats(self.doc, array, 3 * MAX_VERTICES + 1)?;
                if values.len() > 3 * MAX_VERTICES {
                    return Err(format!(
                        "line {}: POSITION <float_array> holds more than {MAX_VERTICES} vertices (limit)",
                        line_of(self.doc, array)
                    ));
                }
                (values.len() / 3, 3, 0, vec![0, 1, 2], values)
            }
        };
        if count == 0 {
            return Ok(Vec::new());
        }
        let last = (count - 1)
            .checked_mul(stride)
            .and_then(|n| n.checked_add(offset))
            .and_then(|n| n.checked_add(slots[2].max(slots[1]).max(slots[0])));
        if last.is_none_or(|n| n >= values.len()) {
            return Err(format!(
                "line {}: accessor reads {count} points with stride {stride} from offset {offset}, \
                 but the <float_array> (line {}) has {} numbers",
                line_of(self.doc, accessor.unwrap_or(source)),
                line_of(self.doc, array),
                token_count(array)
            ));
        }
        Ok((0..count)
            .map(|i| {
                let at = offset + i * stride;
                [
                    values[at + slots[0]],
                    values[at + slots[1]],
                    values[at + slots[2]],
                ]
            })
            .collect())
    }

    /// Triangles of a `<mesh>`'s primitives: `<triangles count>`, `<polylist>` `<vcount>`,
    /// `<polygons>`/`<trifans>`/`<tristrips>` `<p>` lengths; lines count none.
    fn mesh_triangles(&self, mesh: Node<'a, 'input>) -> Result<usize, String> {
        let mut total = 0usize;
        for prim in elements(mesh) {
            let n = match tag(prim) {
                "triangles" => usize_attr(self.doc, prim, "count", 0)?,
                "polylist" => match child(prim, "vcount") {
                    Some(vcount) => {
                        let mut sum = 0usize;
                        for token in vcount.text().unwrap_or("").split_ascii_whitespace() {
                            let k = token.parse::<usize>().map_err(|_| {
                                format!(
                                    "line {}: expected a vertex count in <vcount>, found '{}'",
                                    line_of(self.doc, vcount),
                                    shown(token.as_bytes())
                                )
                            })?;
                            sum = sum.saturating_add(k.saturating_sub(2));
                        }
                        sum
                    }
                    None => 0,
                },
                "polygons" | "trifans" | "tristrips" => {
                    let stride = self.input_stride(prim)?;
                    let mut sum = 0usize;
                    let ps = elements(prim).flat_map(|c| match tag(c) {
                        "p" => vec![c],
                        // polygons with holes: the outer boundary.
                        "ph" => child(c, "p").into_iter().collect(),
                        _ => Vec::new(),
                    });
                    for p in ps {
                        sum = sum.saturating_add((token_count(p) / stride).saturating_sub(2));
                    }
                    sum
                }
                _ => 0,
            };
            total = total.saturating_add(n);
        }
        Ok(total)
    }

    /// Indices per vertex in a primitive's `<p>`: largest input offset + 1.
    fn input_stride(&self, prim: Node<'a, 'input>) -> Result<usize, String> {
        let mut stride = 1;
        for input in elements(prim).filter(|i| tag(*i) == "input") {
            let offset = usize_attr(self.doc, input, "offset", 0)?;
            stride = stride.max(offset.saturating_add(1));
        }
        Ok(stride)
    }
}

/// COLLADA `<lookat>`: eye, interest, up → the frame at `eye` looking along −Z at `interest`.
fn look_at(v: &[f64]) -> Matrix4<f64> {
    let eye = Vector3::new(v[0], v[1], v[2]);
    let dir = Vector3::new(v[3], v[4], v[5]) - eye;
    let up = Vector3::new(v[6], v[7], v[8]);
    let (Some(dir), Some(up)) = (dir.try_normalize(0.0), up.try_normalize(0.0)) else {
        return Matrix4::new_translation(&eye);
    };
    let Some(right) = dir.cross(&up).try_normalize(0.0) else {
        return Matrix4::new_translation(&eye);
    };
    let up = right.cross(&dir);
    #[rustfmt::skip]
    let m = Matrix4::new(
        right.x, up.x, -dir.x, eye.x,
        right.y, up.y, -dir.y, eye.y,
        right.z, up.z, -dir.z, eye.z,
        0.0, 0.0, 0.0, 1.0,
    );
    m
}

// ---------------------------------------------------------------------------------------------
// Convex hull

/// See [`MeshData::hull`].
fn convex_hull(vertices: &[[f64; 3]], aabb: ([f64; 3], [f64; 3])) -> Vec<[f64; 3]> {
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

type HullResult = (Vec<parry3d_f64::math::Vector>, Vec<[u32; 3]>);

/// The triangles of the hull of `hull` (its vertices), by index into `hull`; empty when quickhull fails,
/// returns a point it was not given, or gives a surface that is not closed and convex around every
/// point of `hull` ([`surface::is_closed_convex`]).
fn triangulate(hull: &[[f64; 3]]) -> Vec<[u32; 3]> {
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
/// as a last resort (the inputs here are whitened and non-flat, so this is not expected to trigger).
fn run_hull(points: &[parry3d_f64::math::Vector]) -> Option<HullResult> {
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
/// farthest from the origin (the whitened centroid). Approximate (see [`MeshData::hull`]).
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
    use nalgebra::Point3;

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
    fn up_axes_are_proper_rotations_taking_up_to_z() {
        for (axis, up) in [
            (ColladaUpAxis::X, [1.0, 0.0, 0.0]),
            (ColladaUpAxis::Y, [0.0, 1.0, 0.0]),
            (ColladaUpAxis::Z, [0.0, 0.0, 1.0]),
        ] {
            let m = axis.to_z_up();
            let r = m.fixed_view::<3, 3>(0, 0).into_owned();
            assert!((r.determinant() - 1.0).abs() < 1e-15, "{axis:?}");
            let z = m.transform_point(&Point3::new(up[0], up[1], up[2]));
            assert_eq!([z.x, z.y, z.z], [0.0, 0.0, 1.0], "{axis:?}");
        }
        let y = ColladaUpAxis::Y
            .to_z_up()
            .transform_point(&Point3::new(1.0, 2.0, 3.0));
        assert_eq!([y.x, y.y, y.z], [1.0, -3.0, 2.0]);
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
