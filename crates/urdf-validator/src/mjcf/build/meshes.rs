//! Mesh assets: `<asset><mesh>` read, their files found, and their solids for the geoms' masses.

use std::cell::OnceCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::Builder;
use crate::diagnostics::rules;
use crate::diagnostics::span::Span;
use crate::input::mesh::load_surface;
use crate::input::resolve::{mjcf_mesh_path, readable_file};
use crate::mjcf::defaults::MAIN;
use crate::mjcf::mass::{self, MeshVolume, Solid};
use crate::mjcf::orientation;
use crate::mjcf::xml::El;

/// A `<mesh>` asset.
#[derive(Clone, Debug)]
pub(super) struct MeshAsset {
    /// The file, relative to the model file's folder (through `meshdir`).
    pub(super) file: String,
    /// The `file` attribute.
    pub(super) span: Span,
    /// `scale`.
    pub(super) scale: [f64; 3],
    /// `inertia`: how its volume (or, for `shell`, its area) is summed.
    volume: MeshVolume,
    /// `inertia="convex"`: over the convex hull's triangles.
    convex: bool,
    /// `refpos` and `refquat`: the frame the file's vertices are written in (MuJoCo moves them by its
    /// inverse).
    reference: Isometry3<f64>,
    /// Its solid once read (shared by the clones: the file is read once however many geoms use it).
    solid: Rc<OnceCell<Option<Solid>>>,
}

impl MeshAsset {
    /// The file's `triangles` as MuJoCo winds them: reversed when the scale mirrors the mesh (an odd
    /// number of negative factors), so that they still face outwards (an `exact` volume stays positive).
    fn triangles(&self, triangles: &[[u32; 3]]) -> Vec<[u32; 3]> {
        let mirrored = self.scale.iter().product::<f64>() < 0.0;
        triangles
            .iter()
            .map(|&[a, b, c]| if mirrored { [a, c, b] } else { [a, b, c] })
            .collect()
    }

    /// The file's `points` as MuJoCo holds them, in the frame of the geoms that use the mesh: single-
    /// precision floats (an OBJ's decimals are read into floats; STL is floats already), moved by the
    /// inverse of `refpos`/`refquat`, then scaled. The same rounding gives MuJoCo's mass to 1e-9.
    pub(super) fn vertices(&self, points: &[[f64; 3]]) -> Vec<[f64; 3]> {
        points
            .iter()
            .map(|p| {
                let read = self
                    .reference
                    .inverse_transform_point(&[0, 1, 2].map(|k| f64::from(p[k] as f32)).into());
                [0, 1, 2].map(|k| read[k] * self.scale[k])
            })
            .collect()
    }
}

impl<'a> Builder<'a, '_> {
    pub(super) fn assets(&mut self, section: El<'a>) {
        for el in self.reader.children(section) {
            if el.tag() != "mesh" {
                continue;
            }
            let class = self.class_of(el, MAIN);
            let Some(file) = self.value(el, &class, "file") else {
                self.note(
                    el,
                    "a <mesh> without a file (inline vertices) is not read: geoms using it have no shape or mass".to_string(),
                );
                continue;
            };
            let name = el.attr("name").map(str::to_string).unwrap_or_else(|| {
                Path::new(file.text)
                    .file_stem()
                    .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
            });
            let scale = self.vector(el, &class, "scale", [1.0; 3]);
            let inertia = self.word(
                el,
                &class,
                "inertia",
                &["legacy", "exact", "convex", "shell"],
            );
            let relative = self.mesh_path(el, file.text);
            let refpos = self.vector(el, &class, "refpos", [0.0; 3]);
            let refquat = self.vector(el, &class, "refquat", [1.0, 0.0, 0.0, 0.0]);
            let rotation = match orientation::rotation("quat", &refquat, &self.compiler) {
                Ok(r) => r,
                Err(why) => {
                    let span = self.reader.attr_span(el, "refquat");
                    self.reader.report(
                        &rules::MJCF_INVALID_VALUE,
                        span,
                        format!("<mesh refquat>: {why}"),
                    );
                    UnitQuaternion::identity()
                }
            };
            self.meshes.insert(
                name,
                MeshAsset {
                    file: relative,
                    span: file.span,
                    scale,
                    volume: match inertia {
                        "legacy" => MeshVolume::Legacy,
                        "shell" => MeshVolume::Shell,
                        _ => MeshVolume::Exact,
                    },
                    convex: inertia == "convex",
                    reference: Isometry3::from_parts(
                        Translation3::from(Vector3::from(refpos)),
                        rotation,
                    ),
                    solid: Rc::default(),
                },
            );
        }
    }

    /// Where MuJoCo finds a mesh file (relative to the model's folder): [`mjcf_mesh_path`].
    fn mesh_path(&self, el: El<'a>, file: &str) -> String {
        let included_from = (el.file != 0).then(|| self.reader.files().path(el.file));
        mjcf_mesh_path(
            &self.dir,
            self.compiler.mesh_dir.as_deref(),
            included_from,
            file,
        )
        .to_string_lossy()
        .into_owned()
    }

    /// The `<mesh>` asset a geom's `mesh` attribute names (a finding when it names none).
    pub(super) fn mesh_asset(&mut self, el: El<'a>, class: &str) -> Option<MeshAsset> {
        let Some(name) = self.value(el, class, "mesh") else {
            self.problem(
                &rules::MJCF_STRUCTURE,
                el,
                "a mesh geom without a mesh attribute (MuJoCo refuses it)".to_string(),
            );
            return None;
        };
        let asset = self.meshes.get(name.text).cloned();
        if asset.is_none() {
            self.reader.report(
                &rules::MJCF_STRUCTURE,
                name.span,
                format!(
                    "mesh '{}' is not an <asset> mesh of this model (MuJoCo refuses it)",
                    name.text
                ),
            );
        }
        asset
    }

    /// The path of a mesh asset's file when the sandbox lets it be read and it is there (the asset
    /// checks report a missing or refused mesh file).
    pub(super) fn readable(&self, asset: &MeshAsset) -> Option<PathBuf> {
        readable_file(self.resolver.sandbox(), self.dir.join(&asset.file))
    }

    /// The solid of a mesh asset, in the frame of the geoms that use it (`None` without a readable file, or
    /// when MuJoCo would refuse the mesh), read on its first use.
    pub(super) fn mesh_solid(&self, asset: &MeshAsset) -> Option<Solid> {
        *asset.solid.get_or_init(|| self.read_mesh_solid(asset))
    }

    fn read_mesh_solid(&self, asset: &MeshAsset) -> Option<Solid> {
        let path = self.readable(asset)?;
        if asset.convex {
            let data = self.mesh_cache.get(&path);
            let data = data.as_ref().as_ref().ok()?;
            mass::mesh(
                &asset.vertices(&data.hull),
                &asset.triangles(&data.hull_triangles),
                asset.volume,
            )
        } else {
            let surface = load_surface(&path).ok()?;
            mass::mesh(
                &asset.vertices(&surface.vertices),
                &asset.triangles(&surface.triangles),
                asset.volume,
            )
        }
    }
}
