//! A persistent cache of loaded meshes: what the analyses read of a mesh (its convex hull, bounds and
//! counts) kept on disk between runs, so validating the same robot again does not parse its COLLADA
//! files and build their hulls again (most of a run's time on mesh-heavy robots).
//!
//! An entry is keyed by the mesh file's identity (device and inode on Unix, else its canonical path), size
//! and modification time, the loader options and this library's version: editing or replacing a mesh, or
//! upgrading the tool, makes a new entry.
//! Entries are read defensively (a magic number, the full key, bounded sizes, finite numbers); anything
//! unexpected is a miss and the mesh is loaded from its file. Writes go to a temporary file renamed into
//! place, so concurrent runs never see half an entry. Failing to read or write the cache is never an error.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::UNIX_EPOCH;

use super::{
    ColladaUpAxis, MeshData, MeshOptions, MeshSolid, MeshSummary, ObjReading, SolidSource,
    UpAxisPolicy, VolumeIntegrals,
};

/// First bytes of every entry (04: the mesh's solid, [`MeshData::solid`], joined the header).
const MAGIC: &[u8; 8] = b"UVMESH05";

/// Bytes of an entry before its points, besides the key: magic, key length, bounds, triangle count, up
/// axis, binary-STL flag, solid (source and 10 numbers), hull flag.
const HEADER_BYTES: usize = 8 + 8 + 6 * 8 + 8 + 1 + 1 + 1 + SOLID_NUMBERS * 8 + 1;

/// A solid's numbers in an entry: volume, 3 first moments, 6 second moments (xx, xy, xz, yy, yz, zz).
const SOLID_NUMBERS: usize = 10;

/// Largest entry read (a hull has at most a few hundred thousand vertices).
const MAX_ENTRY_BYTES: u64 = 256 * 1024 * 1024;

/// A folder of cached meshes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DiskCache {
    dir: PathBuf,
}

impl DiskCache {
    /// A cache kept in `dir` (created on first write).
    pub fn at(dir: impl Into<PathBuf>) -> DiskCache {
        DiskCache { dir: dir.into() }
    }

    /// The user's cache: `$URDF_VALIDATOR_CACHE_DIR`, else `$XDG_CACHE_HOME/urdf-validator`, else
    /// `~/.cache/urdf-validator`; `None` when none of them is set.
    pub fn user_default() -> Option<DiskCache> {
        let var = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty());
        let dir = var("URDF_VALIDATOR_CACHE_DIR")
            .map(PathBuf::from)
            .or_else(|| var("XDG_CACHE_HOME").map(|d| PathBuf::from(d).join("urdf-validator")))
            .or_else(|| var("HOME").map(|h| PathBuf::from(h).join(".cache/urdf-validator")))?;
        Some(DiskCache::at(dir))
    }

    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The cached mesh for the file at `path` as it is now, if there is one.
    pub fn read(&self, path: &Path, options: &MeshOptions) -> Option<MeshData> {
        let key = key(path, options)?;
        let file = self.entry_path(&key);
        if std::fs::metadata(&file).ok()?.len() > MAX_ENTRY_BYTES {
            return None;
        }
        decode(&std::fs::read(file).ok()?, &key)
    }

    /// What the cached entry for the file at `path` says of the mesh without its points (only the
    /// entry's first bytes are read), if there is an entry.
    pub fn read_summary(&self, path: &Path, options: &MeshOptions) -> Option<MeshSummary> {
        use std::io::Read;
        let key = key(path, options)?;
        let file = std::fs::File::open(self.entry_path(&key)).ok()?;
        let mut head = Vec::with_capacity(HEADER_BYTES + key.len());
        file.take((HEADER_BYTES + key.len()) as u64)
            .read_to_end(&mut head)
            .ok()?;
        let (summary, _) = decode_header(&mut Reader { bytes: &head }, &key)?;
        Some(summary)
    }

    /// Keep `mesh`, loaded from the file at `path`, for later runs (best effort: errors are ignored).
    pub fn write(&self, path: &Path, options: &MeshOptions, mesh: &MeshData) {
        let Some(key) = key(path, options) else {
            return;
        };
        let file = self.entry_path(&key);
        let temporary = file.with_extension(format!("tmp{}", std::process::id()));
        let written = std::fs::create_dir_all(&self.dir)
            .and_then(|()| std::fs::File::create(&temporary))
            .and_then(|mut out| out.write_all(&encode(mesh, &key)))
            .and_then(|()| std::fs::rename(&temporary, &file));
        if written.is_err() {
            let _ = std::fs::remove_file(&temporary);
        }
    }

    fn entry_path(&self, key: &str) -> PathBuf {
        self.dir
            .join(format!("{:016x}.mesh", fnv1a(key.as_bytes())))
    }
}

/// The file behind `path` and its metadata: on Unix its device and inode (one `stat`, where resolving the
/// canonical path costs a system call per path component), elsewhere its canonical path.
#[cfg(unix)]
fn identity(path: &Path) -> Option<(String, std::fs::Metadata)> {
    use std::os::unix::fs::MetadataExt;
    let meta = std::fs::metadata(path).ok()?;
    Some((format!("inode {}:{}", meta.dev(), meta.ino()), meta))
}

#[cfg(not(unix))]
fn identity(path: &Path) -> Option<(String, std::fs::Metadata)> {
    let canonical = std::fs::canonicalize(path).ok()?;
    let meta = std::fs::metadata(&canonical).ok()?;
    Some((canonical.display().to_string(), meta))
}

/// What identifies a mesh file's content and how it is loaded; `None` when the file cannot be examined.
fn key(path: &Path, options: &MeshOptions) -> Option<String> {
    let (file, meta) = identity(path)?;
    let modified = meta.modified().ok()?.duration_since(UNIX_EPOCH).ok()?;
    let up_axis = match options.up_axis {
        UpAxisPolicy::Honour => "honour",
        UpAxisPolicy::Ignore => "ignore",
    };
    // Drake's OBJ reading (the default) adds nothing, so the entries written before readings existed
    // stay valid.
    let obj_reading = match options.obj_reading {
        ObjReading::Drake => "",
        ObjReading::MuJoCo => " obj:mujoco",
    };
    // The entry format is part of the key: builds with different formats keep separate entries.
    Some(format!(
        "{file}\n{}\n{}.{:09}\n{up_axis}{obj_reading}\n{}\n{}",
        meta.len(),
        modified.as_secs(),
        modified.subsec_nanos(),
        // This crate's version (the reports' `validator_version`): another build's entries are not read.
        env!("CARGO_PKG_VERSION"),
        String::from_utf8_lossy(MAGIC)
    ))
}

/// 64-bit FNV-1a: a stable file name for a key (the full key is stored in the entry and compared).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &b| {
        (hash ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The entry: magic, key, bounds, triangle count, declared up axis, the solid (its source, 0 for none, and
/// its numbers, zeros for none), whether the points are the hull,
/// the points (the hull's vertices, or every vertex when the hull is degenerate), then the hull's
/// triangulation.
fn encode(mesh: &MeshData, key: &str) -> Vec<u8> {
    let hull_known = !mesh.hull.is_empty();
    let points = if hull_known {
        &mesh.hull
    } else {
        &mesh.vertices
    };
    let mut out = Vec::with_capacity(64 + key.len() + points.len() * 24);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&(key.len() as u64).to_le_bytes());
    out.extend_from_slice(key.as_bytes());
    for v in mesh.aabb.0.iter().chain(&mesh.aabb.1) {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&(mesh.triangles as u64).to_le_bytes());
    out.push(match mesh.declared_up_axis {
        None => 0,
        Some(ColladaUpAxis::X) => 1,
        Some(ColladaUpAxis::Y) => 2,
        Some(ColladaUpAxis::Z) => 3,
    });
    out.push(u8::from(mesh.binary_stl));
    out.push(match mesh.solid.map(|s| s.source) {
        None => 0,
        Some(SolidSource::ClosedSurface) => 1,
        Some(SolidSource::HullOfOpenSurface) => 2,
        Some(SolidSource::HullSurfaceNotRead) => 3,
    });
    let i = mesh
        .solid
        .map_or_else(VolumeIntegrals::default, |s| s.integrals);
    let (f, m) = (i.first, i.second);
    let numbers: [f64; SOLID_NUMBERS] = [
        i.volume, f[0], f[1], f[2], m[0][0], m[0][1], m[0][2], m[1][1], m[1][2], m[2][2],
    ];
    for v in numbers {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.push(u8::from(hull_known));
    out.extend_from_slice(&(points.len() as u64).to_le_bytes());
    for p in points {
        for v in p {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out.extend_from_slice(&(mesh.hull_triangles.len() as u64).to_le_bytes());
    for t in &mesh.hull_triangles {
        for v in t {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out
}

/// Reads an entry's header (up to its points): the summary and whether the points are the hull; `None`
/// unless it is well-formed and for `key`.
fn decode_header(reader: &mut Reader, key: &str) -> Option<(MeshSummary, bool)> {
    if reader.take(MAGIC.len())? != MAGIC {
        return None;
    }
    let key_len = usize::try_from(reader.u64()?).ok()?;
    if reader.take(key_len)? != key.as_bytes() {
        return None;
    }
    let mut bounds = [0.0; 6];
    for v in &mut bounds {
        *v = reader.f64()?;
    }
    if !bounds.iter().all(|v| v.is_finite()) {
        return None;
    }
    let triangles = usize::try_from(reader.u64()?).ok()?;
    let declared_up_axis = match reader.take(1)?[0] {
        0 => None,
        1 => Some(ColladaUpAxis::X),
        2 => Some(ColladaUpAxis::Y),
        3 => Some(ColladaUpAxis::Z),
        _ => return None,
    };
    let binary_stl = match reader.take(1)?[0] {
        0 => false,
        1 => true,
        _ => return None,
    };
    let source = match reader.take(1)?[0] {
        0 => None,
        1 => Some(SolidSource::ClosedSurface),
        2 => Some(SolidSource::HullOfOpenSurface),
        3 => Some(SolidSource::HullSurfaceNotRead),
        _ => return None,
    };
    let mut n = [0.0; SOLID_NUMBERS];
    for v in &mut n {
        *v = reader.f64()?;
    }
    if !n.iter().all(|v| v.is_finite()) {
        return None;
    }
    let solid = source.map(|source| MeshSolid {
        integrals: VolumeIntegrals {
            volume: n[0],
            first: [n[1], n[2], n[3]],
            second: [[n[4], n[5], n[6]], [n[5], n[7], n[8]], [n[6], n[8], n[9]]],
        },
        source,
    });
    let hull_known = match reader.take(1)?[0] {
        0 => false,
        1 => true,
        _ => return None,
    };
    let aabb = (
        [bounds[0], bounds[1], bounds[2]],
        [bounds[3], bounds[4], bounds[5]],
    );
    let summary = MeshSummary {
        aabb,
        triangles,
        declared_up_axis,
        binary_stl,
        solid,
    };
    Some((summary, hull_known))
}

/// Reads an entry back; `None` unless it is complete, well-formed and for `key`.
fn decode(bytes: &[u8], key: &str) -> Option<MeshData> {
    let mut reader = Reader { bytes };
    let (summary, hull_known) = decode_header(&mut reader, key)?;
    let count = usize::try_from(reader.u64()?).ok()?;
    if count.checked_mul(24)? > reader.bytes.len() {
        return None;
    }
    let mut points = Vec::with_capacity(count);
    for _ in 0..count {
        points.push([reader.f64()?, reader.f64()?, reader.f64()?]);
    }
    let triangle_count = usize::try_from(reader.u64()?).ok()?;
    if triangle_count.checked_mul(12)? != reader.bytes.len() || (triangle_count > 0 && !hull_known)
    {
        return None;
    }
    let mut hull_triangles = Vec::with_capacity(triangle_count);
    for _ in 0..triangle_count {
        let t = [reader.u32()?, reader.u32()?, reader.u32()?];
        if t.iter().any(|&v| v as usize >= count) {
            return None;
        }
        hull_triangles.push(t);
    }
    if !points.iter().flatten().all(|v| v.is_finite()) {
        return None;
    }
    // Only what the analyses read of a mesh is kept: with a hull, its vertices stand for the vertices.
    let (vertices, hull) = if hull_known {
        (points.clone(), points)
    } else {
        (points, Vec::new())
    };
    Some(MeshData {
        vertices,
        hull,
        hull_triangles,
        aabb: summary.aabb,
        triangles: summary.triangles,
        declared_up_axis: summary.declared_up_axis,
        binary_stl: summary.binary_stl,
        solid: summary.solid,
    })
}

/// A cursor over an entry's bytes.
struct Reader<'a> {
    bytes: &'a [u8],
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        if n > self.bytes.len() {
            return None;
        }
        let (head, rest) = self.bytes.split_at(n);
        self.bytes = rest;
        Some(head)
    }

    fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }

    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }

    fn f64(&mut self) -> Option<f64> {
        Some(f64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> MeshData {
        let corners: Vec<[f64; 3]> = (0..8)
            .map(|i| {
                [
                    f64::from(i & 1),
                    f64::from((i >> 1) & 1),
                    f64::from((i >> 2) & 1),
                ]
            })
            .collect();
        MeshData {
            vertices: corners.clone(),
            hull: corners,
            hull_triangles: vec![[0, 1, 2], [1, 3, 2]],
            aabb: ([0.0; 3], [1.0; 3]),
            triangles: 12,
            declared_up_axis: Some(ColladaUpAxis::Y),
            binary_stl: true,
            solid: Some(MeshSolid {
                integrals: VolumeIntegrals {
                    volume: 1.0,
                    first: [0.5; 3],
                    second: [
                        [1.0 / 3.0, 0.25, 0.25],
                        [0.25, 1.0 / 3.0, 0.25],
                        [0.25, 0.25, 1.0 / 3.0],
                    ],
                },
                source: SolidSource::HullOfOpenSurface,
            }),
        }
    }

    #[test]
    fn an_entry_reads_back_for_its_key_only() {
        let mesh = cube();
        let bytes = encode(&mesh, "k");
        let back = decode(&bytes, "k").expect("reads back");
        assert_eq!(back.hull, mesh.hull);
        assert_eq!(back.hull_triangles, mesh.hull_triangles);
        assert_eq!(back.aabb, mesh.aabb);
        assert!(back.binary_stl, "the STL encoding survives the cache");
        assert_eq!(back.triangles, 12);
        assert_eq!(back.declared_up_axis, Some(ColladaUpAxis::Y));
        assert_eq!(back.solid, mesh.solid);
        assert!(decode(&bytes, "other").is_none());
    }

    #[test]
    fn a_damaged_entry_is_a_miss() {
        let bytes = encode(&cube(), "k");
        for cut in [0, 7, 20, bytes.len() - 1] {
            assert!(decode(&bytes[..cut], "k").is_none(), "cut at {cut}");
        }
        let mut longer = bytes.clone();
        longer.push(0);
        assert!(decode(&longer, "k").is_none());
        let mut nan = bytes.clone();
        let at = nan.len() - 8 - 8 - 2 * 12;
        nan[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
        assert!(decode(&nan, "k").is_none());
        let mut out_of_range = bytes;
        let at = out_of_range.len() - 4;
        out_of_range[at..].copy_from_slice(&8u32.to_le_bytes());
        assert!(
            decode(&out_of_range, "k").is_none(),
            "a triangle naming no point"
        );
    }

    /// A fresh folder `uv-disk-<name>-<pid>` holding a mesh file `m.stl`, and a cache in it.
    fn scratch(name: &str) -> (PathBuf, PathBuf, DiskCache) {
        let dir = std::env::temp_dir().join(format!("uv-disk-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let mesh_file = dir.join("m.stl");
        std::fs::write(&mesh_file, b"one").unwrap();
        let cache = DiskCache::at(dir.join("cache"));
        (dir, mesh_file, cache)
    }

    /// The summary comes from the entry's header alone, and is what the whole entry says.
    #[test]
    fn a_summary_reads_only_the_header() {
        let (dir, mesh_file, cache) = scratch("summary");
        let options = MeshOptions::default();
        assert_eq!(
            cache.read_summary(&mesh_file, &options),
            None,
            "no entry yet"
        );
        cache.write(&mesh_file, &options, &cube());
        assert_eq!(
            cache.read_summary(&mesh_file, &options),
            Some(cube().summary())
        );
        // Points cut off: the whole entry is a miss, its header still summarises the mesh.
        let entry = std::fs::read_dir(dir.join("cache"))
            .unwrap()
            .next()
            .unwrap()
            .unwrap()
            .path();
        let bytes = std::fs::read(&entry).unwrap();
        std::fs::write(&entry, &bytes[..bytes.len() - 30]).unwrap();
        assert!(cache.read(&mesh_file, &options).is_none());
        assert_eq!(
            cache.read_summary(&mesh_file, &options),
            Some(cube().summary())
        );
        // A damaged header is a miss.
        std::fs::write(&entry, b"UVMESH04").unwrap();
        assert_eq!(cache.read_summary(&mesh_file, &options), None);
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A run reads each entry's header once: the summary is kept (here, the entry is gone the second time).
    #[test]
    fn a_mesh_cache_reads_a_summary_once() {
        let (dir, mesh_file, cache) = scratch("summary-once");
        let options = MeshOptions::default();
        cache.write(&mesh_file, &options, &cube());
        let meshes = crate::input::mesh::MeshCache::with_options(options).with_disk_cache(cache);
        assert_eq!(meshes.summary(&mesh_file), Ok(cube().summary()));
        std::fs::remove_dir_all(dir.join("cache")).unwrap();
        assert_eq!(
            meshes.summary(&mesh_file),
            Ok(cube().summary()),
            "kept, not read again (the file itself is no mesh)"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn each_obj_reading_has_its_own_entry() {
        let (dir, mesh_file, cache) = scratch("reading");
        let drake = MeshOptions::default();
        let mujoco = MeshOptions {
            obj_reading: ObjReading::MuJoCo,
            ..drake
        };
        cache.write(&mesh_file, &drake, &cube());
        assert!(cache.read(&mesh_file, &drake).is_some());
        assert!(cache.read(&mesh_file, &mujoco).is_none());
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn a_changed_file_gets_a_new_entry() {
        let (dir, mesh_file, cache) = scratch("cache");
        let options = MeshOptions::default();
        assert!(cache.read(&mesh_file, &options).is_none());
        cache.write(&mesh_file, &options, &cube());
        assert_eq!(
            cache.read(&mesh_file, &options).map(|m| m.triangles),
            Some(12)
        );
        std::fs::write(&mesh_file, b"changed").unwrap();
        assert!(
            cache.read(&mesh_file, &options).is_none(),
            "size and time changed"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
