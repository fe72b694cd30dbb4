//! The assets stage: everything outside the URDF that the checks and analyses read, loaded once.
//!
//! Every mesh URI of every link (visual and collision) is resolved once, every distinct file is read and
//! reduced to its convex hull once (in parallel, through the run's shared [`MeshCache`]), every link's
//! ground-contact [`LinkSupports`] are built once from those hulls, and the SRDF is found and read once.
//! The checks report what could not be loaded (once per mesh element); the analyses only borrow.

pub(crate) mod supports;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use rayon::prelude::*;

use crate::input::mesh::{MeshCache, MeshData, MeshError};
use crate::input::resolve::{PackageResolver, Resolution};
use crate::input::srdf::{self, Srdf};
use crate::urdf::robot::{Geometry, Robot};

pub use supports::{link_supports, LinkSupports, MeshPoints, Support};

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
    /// Each resolved mesh file, loaded.
    meshes: HashMap<PathBuf, LoadedMesh>,
    /// Per link (indexed like `Robot::links`): its collision shapes (its visuals when it has none).
    pub supports: Vec<LinkSupports>,
    /// The SRDF (`--srdf`, else `<stem>.srdf` or `<robot name>.srdf` beside the URDF), read once.
    pub srdf: Option<Srdf>,
}

impl Assets {
    /// Resolve and load every mesh the robot names, build every link's supports and read the SRDF.
    pub fn load(robot: &Robot, source: &AssetSource) -> Assets {
        let urdf_dir = source
            .urdf_path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let mut resolutions = HashMap::new();
        for link in &robot.links {
            for shape in link.visuals.iter().chain(&link.collisions) {
                if let Some(Geometry::Mesh { filename, .. }) =
                    shape.geometry.as_ref().map(|g| &g.value)
                {
                    resolutions
                        .entry(filename.value.clone())
                        .or_insert_with(|| source.resolver.resolve(&filename.value, urdf_dir));
                }
            }
        }
        let mut files: Vec<&PathBuf> = resolutions
            .values()
            .filter_map(|r| match r {
                Resolution::Found(path) => Some(path),
                _ => None,
            })
            .collect();
        files.sort_unstable();
        files.dedup();
        let meshes: HashMap<PathBuf, LoadedMesh> = files
            .into_par_iter()
            .map(|path| (path.clone(), source.meshes.get(path)))
            .collect();
        let mut assets = Assets {
            resolutions,
            meshes,
            supports: Vec::new(),
            srdf: None,
        };
        assets.supports = robot
            .links
            .iter()
            .map(|link| link_supports(link, &|uri| assets.mesh_points(uri)))
            .collect();
        let robot_name = robot.name.as_ref().map(|n| n.value.as_str());
        assets.srdf = srdf::find(source.urdf_path, robot_name, source.srdf).map(Srdf::read);
        assets
    }

    /// How a mesh URI resolved (`None` for a URI the robot does not name).
    pub fn resolution(&self, uri: &str) -> Option<&Resolution> {
        self.resolutions.get(uri)
    }

    /// The mesh a URI names, loaded (or why not); `None` when the URI does not resolve to a file.
    pub fn mesh(&self, uri: &str) -> Option<&LoadedMesh> {
        match self.resolutions.get(uri)? {
            Resolution::Found(path) => self.meshes.get(path),
            _ => None,
        }
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
