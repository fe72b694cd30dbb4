//! The assets stage: everything outside the URDF that the checks and analyses read, loaded once.
//!
//! Every mesh URI of every link (visual and collision) is resolved once. The meshes the links' contact and
//! collision shapes are made of are read and reduced to their convex hulls once, in parallel, through the
//! run's shared [`MeshCache`]; every link's ground-contact [`LinkSupports`] are built once from those
//! hulls, and the SRDF is found and read once. Any other mesh is read on first use (the checks only need
//! its bounds, which the disk cache gives without its points). The checks report what could not be
//! loaded (once per mesh element); the analyses only borrow.

pub(crate) mod supports;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

use rayon::prelude::*;

use crate::input::mesh::{
    load_view_surface, summary_of, MeshCache, MeshData, MeshError, MeshSummary, Surface,
};
use crate::input::resolve::{PackageResolver, Resolution};
use crate::input::sandbox::Refusal;
use crate::input::srdf::{self, Srdf};
use crate::urdf::robot::{Geometry, Robot, Shape};

pub use supports::{link_supports, LinkSupports, MeshPoints, Support};

/// The mesh file a shape names, as written.
fn mesh_uri(shape: &Shape) -> Option<&String> {
    match shape.geometry.as_ref().map(|g| &g.value) {
        Some(Geometry::Mesh { filename, .. }) => Some(&filename.value),
        _ => None,
    }
}

/// A loaded mesh, or why it could not be loaded.
pub type LoadedMesh = Arc<Result<MeshData, MeshError>>;

/// Where the assets of one robot come from.
#[derive(Clone, Copy, Debug)]
pub struct AssetSource<'a> {
    /// The robot description file (relative mesh paths, the package walk-up, SRDF discovery).
    pub urdf_path: &'a Path,
    /// Package search paths.
    pub resolver: &'a PackageResolver,
    /// Meshes loaded so far in this run (shared by every file of a batch).
    pub meshes: &'a MeshCache,
    /// `--srdf`, when given.
    pub srdf: Option<&'a Path>,
}

/// The assets of one robot, loaded once and shared by the checks and every analysis.
#[derive(Debug, Default)]
pub struct Assets {
    /// How each mesh URI resolved, by the URI as written.
    resolutions: HashMap<String, Resolution>,
    /// Each resolved mesh file, loaded on first use (those the supports are made of while loading).
    meshes: HashMap<PathBuf, OnceLock<LoadedMesh>>,
    /// Where meshes are loaded from.
    cache: MeshCache,
    /// Per link (indexed like `Robot::links`): its collision shapes (its visuals when it has none).
    pub supports: Vec<LinkSupports>,
    /// The SRDF (`--srdf`, else `<stem>.srdf` or `<robot name>.srdf` beside the URDF), read once.
    pub srdf: Option<Srdf>,
    /// The SRDF found beside the URDF that the sandbox did not let be read (untrusted mode), and why.
    pub srdf_refused: Option<(PathBuf, Refusal)>,
}

impl Assets {
    /// Resolve every mesh the robot names, load those the links' supports are made of (in parallel), build
    /// every link's supports and read the SRDF. Other meshes load on first use.
    pub fn load(robot: &Robot, source: &AssetSource) -> Assets {
        let urdf_dir = source
            .urdf_path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let mut resolutions = HashMap::new();
        // The meshes links' supports are made of (their collisions, or their visuals without any).
        let mut support_uris = Vec::new();
        for link in &robot.links {
            for uri in link
                .visuals
                .iter()
                .chain(&link.collisions)
                .filter_map(mesh_uri)
            {
                resolutions
                    .entry(uri.clone())
                    .or_insert_with(|| source.resolver.resolve(uri, urdf_dir));
            }
            let supported = if link.collisions.is_empty() {
                &link.visuals
            } else {
                &link.collisions
            };
            support_uris.extend(supported.iter().filter_map(mesh_uri));
        }
        let meshes: HashMap<PathBuf, OnceLock<LoadedMesh>> = resolutions
            .values()
            .filter_map(|r| r.found().map(|path| (path.clone(), OnceLock::new())))
            .collect();
        let mut needed: Vec<(&PathBuf, &OnceLock<LoadedMesh>)> = support_uris
            .into_iter()
            .filter_map(|uri| meshes.get_key_value(resolutions.get(uri)?.found()?))
            .collect();
        needed.sort_unstable_by_key(|(path, _)| *path);
        needed.dedup_by_key(|(path, _)| *path);
        let load = |(path, cell): (&PathBuf, &OnceLock<LoadedMesh>)| {
            cell.get_or_init(|| source.meshes.get(path));
        };
        // One mesh or none: no thread pool is started for it (a short run's start-up counts).
        if needed.len() > 1 {
            needed.into_par_iter().for_each(load);
        } else {
            needed.into_iter().for_each(load);
        }
        let mut assets = Assets {
            resolutions,
            meshes,
            cache: source.meshes.clone(),
            supports: Vec::new(),
            srdf: None,
            srdf_refused: None,
        };
        assets.supports = robot
            .links
            .iter()
            .map(|link| link_supports(link, &|uri| assets.mesh_points(uri)))
            .collect();
        let robot_name = robot.name.as_ref().map(|n| n.value.as_str());
        if let Some(path) = srdf::find(source.urdf_path, robot_name, source.srdf) {
            match source.resolver.sandbox().check_file(&path) {
                Ok(()) => assets.srdf = Some(Srdf::read(path)),
                Err(refusal) => assets.srdf_refused = Some((path, refusal)),
            }
        }
        assets
    }

    /// How a mesh URI resolved (`None` for a URI the robot does not name).
    pub fn resolution(&self, uri: &str) -> Option<&Resolution> {
        self.resolutions.get(uri)
    }

    /// The mesh a URI names, loaded (or why not) on first use; `None` when the URI does not resolve to a
    /// file.
    pub fn mesh(&self, uri: &str) -> Option<&LoadedMesh> {
        let (path, cell) = self.mesh_cell(uri)?;
        Some(cell.get_or_init(|| self.cache.get(path)))
    }

    /// What the checks read of the mesh a URI names, without loading its points when the disk cache
    /// knows the mesh; `None` when the URI does not resolve to a file.
    pub fn mesh_summary(&self, uri: &str) -> Option<Result<MeshSummary, MeshError>> {
        let (path, cell) = self.mesh_cell(uri)?;
        Some(match cell.get() {
            Some(mesh) => summary_of(mesh),
            None => self.cache.summary(path),
        })
    }

    fn mesh_cell(&self, uri: &str) -> Option<(&PathBuf, &OnceLock<LoadedMesh>)> {
        self.meshes
            .get_key_value(self.resolutions.get(uri)?.found()?)
    }

    /// The triangles of the mesh a URI names as its file writes them (STL and OBJ; COLLADA's as its visual
    /// scene instantiates them, see [`load_view_surface`]), read now and not kept: for views that draw the
    /// mesh, never for what the validator computes. `None` when the URI does not resolve to a file the
    /// sandbox lets be read.
    pub fn surface(&self, uri: &str) -> Option<Result<Surface, MeshError>> {
        let (path, _) = self.mesh_cell(uri)?;
        Some(load_view_surface(path, &self.cache.options()))
    }

    /// Points of a mesh for contact geometry, in the mesh frame before scale: its convex hull (with the
    /// hull's triangles), or every vertex when the hull is degenerate; `None` when the mesh is unusable.
    pub fn mesh_points(&self, uri: &str) -> Option<MeshPoints<'_>> {
        let mesh = self.mesh(uri)?.as_ref().as_ref().ok()?;
        Some(if mesh.hull.is_empty() {
            MeshPoints {
                points: &mesh.vertices,
                hull_triangles: None,
            }
        } else {
            MeshPoints {
                points: &mesh.hull,
                hull_triangles: Some(&mesh.hull_triangles),
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tetrahedron, as ASCII STL.
    const TETRAHEDRON: &str = "solid t
facet normal 0 0 -1
outer loop
vertex 0 0 0
vertex 0 1 0
vertex 1 0 0
endloop
endfacet
facet normal 0 -1 0
outer loop
vertex 0 0 0
vertex 1 0 0
vertex 0 0 1
endloop
endfacet
facet normal -1 0 0
outer loop
vertex 0 0 0
vertex 0 0 1
vertex 0 1 0
endloop
endfacet
facet normal 1 1 1
outer loop
vertex 1 0 0
vertex 0 1 0
vertex 0 0 1
endloop
endfacet
endsolid t
";

    /// Only the meshes the supports are made of load with the assets; a visual mesh of a link with
    /// collisions loads when it is asked for.
    #[test]
    fn meshes_no_support_needs_load_on_first_use() {
        let dir = std::env::temp_dir().join(format!("uv-assets-lazy-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("shown.stl"), TETRAHEDRON).unwrap();
        std::fs::write(dir.join("hits.stl"), TETRAHEDRON.replace("1 ", "2 ")).unwrap();
        let urdf = r#"<robot name="r">
  <link name="a">
    <visual><geometry><mesh filename="shown.stl"/></geometry></visual>
    <collision><geometry><box size="1 1 1"/></geometry></collision>
  </link>
  <link name="b">
    <visual><geometry><mesh filename="hits.stl"/></geometry></visual>
  </link>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>"#;
        let path = dir.join("r.urdf");
        let (robot, _) = crate::urdf::parse_urdf(urdf, &path).unwrap();
        let meshes = MeshCache::new();
        let assets = Assets::load(
            &robot,
            &AssetSource {
                urdf_path: &path,
                resolver: &PackageResolver::default(),
                meshes: &meshes,
                srdf: None,
            },
        );
        assert_eq!(
            meshes.len(),
            1,
            "only b's visual mesh (its support) is loaded"
        );
        assert_eq!(assets.supports[1].shapes.len(), 1);
        let summary = assets.mesh_summary("shown.stl").unwrap().unwrap();
        assert_eq!(summary.aabb, ([0.0; 3], [1.0; 3]));
        let shown = assets.mesh("shown.stl").unwrap().as_ref().as_ref().unwrap();
        assert_eq!(shown.summary(), summary);
        assert_eq!(meshes.len(), 2);
        assert!(assets.mesh("absent.stl").is_none());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
