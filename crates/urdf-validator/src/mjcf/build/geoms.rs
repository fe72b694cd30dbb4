//! Geoms as collision or visual shapes with their mass: primitives, meshes and fitted primitives.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::{pose, Builder};
use crate::diagnostics::rules;
use crate::diagnostics::span::Spanned;
use crate::input::mesh::load_surface;
use crate::mjcf::compiler::boolean;
use crate::mjcf::mass::{self, MassProps, Solid};
use crate::mjcf::orientation;
use crate::mjcf::xml::{numbers, El};
use crate::urdf::robot::{Geometry, Shape};

/// The shape of a primitive geom of MuJoCo type `kind` and `size` (`None` for types without one).
fn primitive_geometry(kind: &str, [a, b, c]: [f64; 3]) -> Option<Geometry> {
    match kind {
        "sphere" => Some(Geometry::Sphere { radius: a }),
        "capsule" => Some(Geometry::Capsule {
            radius: a,
            length: 2.0 * b,
        }),
        "cylinder" => Some(Geometry::Cylinder {
            radius: a,
            length: 2.0 * b,
        }),
        "box" => Some(Geometry::Box {
            size: [2.0 * a, 2.0 * b, 2.0 * c],
        }),
        _ => None,
    }
}

impl<'a> Builder<'a, '_> {
    /// A geom's `(contype, conaffinity)` bit masks (1 and 1 unless written), as the integers MuJoCo reads.
    pub(super) fn contact_masks(&mut self, el: El<'a>, class: &str) -> (u32, u32) {
        let contype = self.scalar(el, class, "contype", 1.0).max(0.0) as u32;
        let conaffinity = self.scalar(el, class, "conaffinity", 1.0).max(0.0) as u32;
        (contype, conaffinity)
    }

    /// A geom's shape (in the link frame: `frame` places the geom's written frame there), collision
    /// filter, mass properties and whether its mesh was read.
    pub(super) fn geom(&mut self, el: El<'a>, class: &str, frame: &Isometry3<f64>) -> GeomParts {
        let kind = self.word(
            el,
            class,
            "type",
            &[
                "sphere",
                "capsule",
                "ellipsoid",
                "cylinder",
                "box",
                "mesh",
                "plane",
                "hfield",
                "sdf",
            ],
        );
        let mut size = self.list(el, class, "size").unwrap_or_default();
        size.resize(3, 0.0);
        let mut size = [size[0], size[1], size[2]];
        let mut placement = self.placement(el, class);
        if let Some(fromto) = self.value(el, class, "fromto") {
            match numbers(fromto.text).map(<[f64; 6]>::try_from) {
                Ok(Ok([x0, y0, z0, x1, y1, z1])) => {
                    let (a, b) = (Vector3::new(x0, y0, z0), Vector3::new(x1, y1, z1));
                    let d = b - a;
                    let half = d.norm() / 2.0;
                    match kind {
                        "capsule" | "cylinder" => size[1] = half,
                        "box" | "ellipsoid" => size[2] = half,
                        _ => {}
                    }
                    let rotation = d
                        .try_normalize(1e-14)
                        .map_or_else(UnitQuaternion::identity, orientation::z_to);
                    placement = Isometry3::from_parts(Translation3::from((a + b) / 2.0), rotation);
                }
                _ => self.reader.report(
                    &rules::MJCF_INVALID_VALUE,
                    fromto.span,
                    "<geom fromto>: 6 finite numbers expected".to_string(),
                ),
            }
        }
        let mut at = frame * placement;
        let (contype, conaffinity) = self.contact_masks(el, class);
        let collides = (contype != 0 || conaffinity != 0).then_some((contype, conaffinity));
        let group = self.scalar(el, class, "group", 0.0);
        let (lo, hi) = self.compiler.inertia_groups;
        let counts = group >= lo as f64 && group <= hi as f64;
        let span = self.reader.span(el);
        let (geometry, solid) = match kind {
            "mesh" => self.mesh_geom(el, class),
            "plane" => (None, None),
            "hfield" | "sdf" => {
                self.note(el, format!("a {kind} geom is not read: no shape, no mass"));
                (None, None)
            }
            _ if self.value(el, class, "mesh").is_some() => {
                match self.fitted_geom(el, class, kind) {
                    Some((geometry, fitted, solid)) => {
                        at *= fitted;
                        (geometry, Some(solid))
                    }
                    None => (None, None),
                }
            }
            _ => (
                primitive_geometry(kind, size),
                mass::primitive(kind, size, self.shell_inertia(el, class)),
            ),
        };
        // A mesh that cannot be read (the asset checks say why) gives no solid: its explicit `mass` still
        // counts, as a point at the geom's frame (MuJoCo puts it at the mesh's centroid, unknown here).
        let explicit = self
            .value(el, class, "mass")
            .map(|_| self.scalar(el, class, "mass", 0.0));
        let unread = solid.is_none() && (kind == "mesh" || self.value(el, class, "mesh").is_some());
        let mass = match (solid, explicit) {
            (Some(solid), _) if counts => {
                let mass = explicit
                    .unwrap_or_else(|| self.scalar(el, class, "density", 1000.0) * solid.volume);
                Some(solid.with_mass(mass).placed(&at))
            }
            (None, Some(mass)) if counts && unread => Some(MassProps {
                mass,
                com: at.translation.vector,
                inertia: nalgebra::Matrix3::zeros(),
            }),
            _ => None,
        };
        let shape = geometry.map(|geometry| Shape {
            span,
            name: el.attr("name").map(str::to_string),
            origin: pose(&at),
            geometry: Some(Spanned {
                value: geometry,
                span,
            }),
            material: None,
        });
        GeomParts {
            shape,
            collides,
            mass,
            read: !unread,
        }
    }

    /// A mesh geom's shape and solid (the mesh file read through the sandbox and the mesh cache).
    fn mesh_geom(&mut self, el: El<'a>, class: &str) -> (Option<Geometry>, Option<Solid>) {
        let Some(asset) = self.mesh_asset(el, class) else {
            return (None, None);
        };
        if self.shell_inertia(el, class) {
            self.problem(
                &rules::MJCF_STRUCTURE,
                el,
                "shellinertia on a mesh geom (MuJoCo refuses it: \"for mesh geoms, inertia should be specified in the mesh asset\", <mesh inertia=\"shell\">)".to_string(),
            );
        }
        let geometry = Geometry::Mesh {
            filename: Spanned {
                value: asset.file.clone(),
                span: asset.span,
            },
            scale: asset.scale,
        };
        (Some(geometry), self.mesh_solid(&asset))
    }

    /// A primitive geom that names a mesh (`type="capsule" mesh=…`): the primitive MuJoCo fits to the
    /// mesh, its shape and its solid, both in the geom frame. `None` when the mesh cannot be read (the
    /// asset checks say why) or MuJoCo cannot fit it.
    fn fitted_geom(
        &mut self,
        el: El<'a>,
        class: &str,
        kind: &str,
    ) -> Option<(Option<Geometry>, Isometry3<f64>, Solid)> {
        let asset = self.mesh_asset(el, class)?;
        let solid = self.mesh_solid(&asset)?;
        let vertices = if self.compiler.fit_aabb {
            Some(asset.vertices(&load_surface(&self.readable(&asset)?).ok()?.vertices))
        } else {
            None
        };
        let fitscale = self.scalar(el, class, "fitscale", 1.0);
        let Some(fitted) = mass::fit_primitive(kind, &solid, vertices.as_deref(), fitscale) else {
            self.problem(
                &rules::MJCF_STRUCTURE,
                el,
                format!(
                    "a {kind} fitted to mesh '{}' has no positive size (MuJoCo refuses it)",
                    asset.file
                ),
            );
            return None;
        };
        let solid = mass::primitive(kind, fitted.size, self.shell_inertia(el, class))?;
        Some((primitive_geometry(kind, fitted.size), fitted.frame, solid))
    }

    /// Whether a geom's mass is spread over its surface (`shellinertia="true"`, written or from its class).
    fn shell_inertia(&self, el: El<'a>, class: &str) -> bool {
        self.value(el, class, "shellinertia")
            .is_some_and(|v| boolean(v.text) == Some(true))
    }
}

/// What a geom element turns into.
pub(super) struct GeomParts {
    /// Its shape in the link frame.
    pub(super) shape: Option<Shape>,
    /// Its `contype` and `conaffinity` when it collides (not both 0).
    pub(super) collides: Option<(u32, u32)>,
    /// Its mass properties when it counts for the body's mass.
    pub(super) mass: Option<MassProps>,
    /// Whether its mesh (if it names one) was read.
    pub(super) read: bool,
}
