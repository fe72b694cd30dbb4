//! A link's inertia from its geometry, with the semantics of Drake's `fix_inertia`
//! (`pydrake.multibody.fix_inertia`): the link's collision shapes, or its visuals when it has no collision
//! shape, filled with a uniform density; the centre of mass is the shapes' joint centroid and the tensor is
//! about it, in the link frame's axes (Drake writes the inertial `<origin>` as `xyz` = that centroid,
//! `rpy="0 0 0"`). The declared mass is kept: only the distribution comes from the geometry.
//!
//! Per shape, as Drake's `CalcSpatialInertia`: a box, cylinder, sphere and capsule exactly; a mesh as the
//! solid its surface bounds, by the divergence theorem ([`crate::input::mesh::solid`]), scaled by the
//! URDF `scale` (a mirroring scale flips the surface's orientation; the solid is the same, mirrored), and
//! as its convex hull when the surface is not closed (Drake, which reads only OBJ meshes for this, would
//! integrate the open surface as it is). Overlapping shapes count twice, as in Drake.

use std::f64::consts::PI;

use crate::assets::Assets;
use crate::input::mesh::{SolidSource, VolumeIntegrals};
use crate::model::kinematics::pose_isometry;
use crate::urdf::robot::{Geometry, Link, Shape};

/// Which of a link's shapes the inertia comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Its `<collision>` shapes.
    Collision,
    /// Its `<visual>` shapes (it has no collision shape).
    Visual,
}

impl Role {
    /// `collision` or `visual`.
    pub fn label(self) -> &'static str {
        match self {
            Role::Collision => "collision",
            Role::Visual => "visual",
        }
    }
}

/// The solid a link's geometry fills.
#[derive(Debug, Clone, PartialEq)]
pub struct GeometryInertia {
    /// The shapes used.
    pub role: Role,
    /// Their volume integrals in the link frame (metres; density 1).
    pub integrals: VolumeIntegrals,
    /// Meshes integrated as their convex hull, with why (`"…/part.stl: its convex hull (…)"`).
    pub hulls: Vec<String>,
    /// A box in the link frame (min, max) holding every shape (each shape's own bounding box, placed).
    pub bounds: ([f64; 3], [f64; 3]),
}

impl GeometryInertia {
    /// Total volume, m³.
    pub fn volume(&self) -> f64 {
        self.integrals.volume
    }

    /// Centre of mass in the link frame, m.
    pub fn com(&self) -> [f64; 3] {
        self.integrals.first.map(|f| f / self.integrals.volume)
    }

    /// The inertia tensor about the centre of mass, in the link frame's axes, of a body of `mass` filling
    /// the solid uniformly, kg·m².
    pub fn inertia(&self, mass: f64) -> [[f64; 3]; 3] {
        let i = &self.integrals;
        let c = self.com();
        // Second moments about the centroid: ∫ y yᵀ = ∫ x xᵀ − V c cᵀ.
        let central = |a: usize, b: usize| i.second[a][b] - i.volume * c[a] * c[b];
        let trace = central(0, 0) + central(1, 1) + central(2, 2);
        let density = mass / i.volume;
        let mut out = [[0.0; 3]; 3];
        for (a, row) in out.iter_mut().enumerate() {
            for (b, value) in row.iter_mut().enumerate() {
                let delta = if a == b { trace } else { 0.0 };
                *value = density * (delta - central(a, b));
            }
        }
        out
    }
}

/// Why a link's geometry gives no inertia.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum NoGeometry {
    /// The link has no shape with a valid geometry.
    NoShapes,
    /// One of the shapes has no volume known here: the message says which and why.
    Unknown(String),
}

impl std::fmt::Display for NoGeometry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NoGeometry::NoShapes => f.write_str("the link has no collision or visual geometry"),
            NoGeometry::Unknown(why) => f.write_str(why),
        }
    }
}

/// The solid `link`'s geometry fills: its collision shapes, else its visuals (Drake's role order), each
/// placed by its `<origin>`; meshes read through `assets`.
pub fn of_link(link: &Link, assets: &Assets) -> Result<GeometryInertia, NoGeometry> {
    if has_geometry(link, Role::Collision) {
        of_role(link, Role::Collision, assets)
    } else {
        of_role(link, Role::Visual, assets)
    }
}

/// Whether `link` has a shape of `role` with a geometry.
fn has_geometry(link: &Link, role: Role) -> bool {
    shapes_of(link, role).iter().any(|s| s.geometry.is_some())
}

/// `link`'s shapes of `role`.
fn shapes_of(link: &Link, role: Role) -> &[Shape] {
    match role {
        Role::Collision => &link.collisions,
        Role::Visual => &link.visuals,
    }
}

/// The solid `link`'s shapes of `role` fill (its collision shapes, or its visuals).
pub fn of_role(link: &Link, role: Role, assets: &Assets) -> Result<GeometryInertia, NoGeometry> {
    if !has_geometry(link, role) {
        return Err(NoGeometry::NoShapes);
    }
    let shapes = shapes_of(link, role);
    let mut total = VolumeIntegrals::default();
    let mut hulls = Vec::new();
    let mut bounds = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for shape in shapes {
        let Some(geometry) = &shape.geometry else {
            continue;
        };
        let local = shape_solid(&geometry.value, assets)?;
        hulls.extend(local.hull);
        let (rows, t) = placement(shape);
        total = total.plus(&local.integrals.transformed(rows).translated(t));
        widen(&mut bounds, shape, local.bounds);
    }
    if !(total.is_finite() && total.volume > 0.0) {
        return Err(NoGeometry::Unknown(format!(
            "the {} geometry encloses no volume",
            role.label()
        )));
    }
    Ok(GeometryInertia {
        role,
        integrals: total,
        hulls,
        bounds,
    })
}

/// A box in the link frame (min, max) holding every collision and visual shape of `link` whose size is
/// known (a mesh that cannot be read is left out); `None` when there is none.
pub fn bounds_of_all_shapes(link: &Link, assets: &Assets) -> Option<([f64; 3], [f64; 3])> {
    let mut bounds = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for shape in link.collisions.iter().chain(&link.visuals) {
        let Some(geometry) = &shape.geometry else {
            continue;
        };
        if let Ok(local) = shape_solid(&geometry.value, assets) {
            widen(&mut bounds, shape, local.bounds);
        }
    }
    bounds.0.iter().all(|v| v.is_finite()).then_some(bounds)
}

/// A shape's placement in the link frame: rotation rows and translation.
fn placement(shape: &Shape) -> ([[f64; 3]; 3], [f64; 3]) {
    let placement = pose_isometry(&shape.origin);
    let m = *placement.rotation.to_rotation_matrix().matrix();
    let t = placement.translation.vector;
    (
        [0, 1, 2].map(|a| [m[(a, 0)], m[(a, 1)], m[(a, 2)]]),
        [t.x, t.y, t.z],
    )
}

/// Grow `bounds` to hold the box `local` of `shape`, placed in the link frame.
fn widen(bounds: &mut ([f64; 3], [f64; 3]), shape: &Shape, local: ([f64; 3], [f64; 3])) {
    let (rows, t) = placement(shape);
    let (low, high) = local;
    for corner in 0..8 {
        let p = [0, 1, 2].map(|k| {
            if corner >> k & 1 == 0 {
                low[k]
            } else {
                high[k]
            }
        });
        for a in 0..3 {
            let q = rows[a][0] * p[0] + rows[a][1] * p[1] + rows[a][2] * p[2] + t[a];
            bounds.0[a] = bounds.0[a].min(q);
            bounds.1[a] = bounds.1[a].max(q);
        }
    }
}

/// One shape in its own frame.
struct LocalSolid {
    integrals: VolumeIntegrals,
    /// Its bounding box (min, max).
    bounds: ([f64; 3], [f64; 3]),
    /// The hull note of a mesh integrated as its hull.
    hull: Option<String>,
}

/// One shape's solid in its own frame.
fn shape_solid(geometry: &Geometry, assets: &Assets) -> Result<LocalSolid, NoGeometry> {
    let positive = |v: f64| v.is_finite() && v > 0.0;
    let diagonal = |volume: f64, d: [f64; 3]| VolumeIntegrals {
        volume,
        first: [0.0; 3],
        second: [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]],
    };
    let degenerate = || NoGeometry::Unknown(format!("{} has no volume", describe(geometry)));
    let centred = |h: [f64; 3]| (h.map(|v| -v), h);
    let (integrals, bounds) = match *geometry {
        Geometry::Box { size } => {
            if !size.iter().all(|&s| positive(s)) {
                return Err(degenerate());
            }
            let v = size[0] * size[1] * size[2];
            (
                diagonal(v, size.map(|s| v * s * s / 12.0)),
                centred(size.map(|s| s / 2.0)),
            )
        }
        Geometry::Cylinder { radius, length } => {
            if !(positive(radius) && positive(length)) {
                return Err(degenerate());
            }
            let v = PI * radius * radius * length;
            let across = v * radius * radius / 4.0;
            (
                diagonal(v, [across, across, v * length * length / 12.0]),
                centred([radius, radius, length / 2.0]),
            )
        }
        Geometry::Sphere { radius } => {
            if !positive(radius) {
                return Err(degenerate());
            }
            let v = 4.0 / 3.0 * PI * radius.powi(3);
            (
                diagonal(v, [v * radius * radius / 5.0; 3]),
                centred([radius; 3]),
            )
        }
        Geometry::Capsule { radius, length } => {
            if !(positive(radius) && positive(length)) {
                return Err(degenerate());
            }
            let (r, l) = (radius, length);
            let cylinder = PI * r * r * l;
            // Two hemispheres, flat faces at z = ±l/2; one hemisphere: ∫x² = ∫z'² = V r²/5, ∫z' = 3rV/8.
            let half = 2.0 / 3.0 * PI * r.powi(3);
            let across = cylinder * r * r / 4.0 + 2.0 * half * r * r / 5.0;
            let along = cylinder * l * l / 12.0
                + 2.0 * (half * l * l / 4.0 + l * half * 3.0 * r / 8.0 + half * r * r / 5.0);
            (
                diagonal(cylinder + 2.0 * half, [across, across, along]),
                centred([r, r, l / 2.0 + r]),
            )
        }
        Geometry::Mesh {
            ref filename,
            scale,
        } => {
            let uri = &filename.value;
            let summary = match assets.mesh_summary(uri) {
                None => return Err(NoGeometry::Unknown(format!("mesh '{uri}' was not found"))),
                Some(Err(error)) => {
                    return Err(NoGeometry::Unknown(format!(
                        "mesh '{uri}' cannot be read: {}",
                        error.message
                    )))
                }
                Some(Ok(summary)) => summary,
            };
            let Some(solid) = summary.solid else {
                return Err(NoGeometry::Unknown(format!(
                    "mesh '{uri}' encloses no volume (it is flat)"
                )));
            };
            if !scale.iter().all(|s| s.is_finite() && *s != 0.0) {
                return Err(degenerate());
            }
            let scaled = solid.integrals.transformed([
                [scale[0], 0.0, 0.0],
                [0.0, scale[1], 0.0],
                [0.0, 0.0, scale[2]],
            ]);
            let hull = (solid.source != SolidSource::ClosedSurface)
                .then(|| format!("mesh '{uri}': {}", solid.source.describe()));
            let (low, high) = summary.aabb;
            let ends = [0, 1, 2].map(|k| (low[k] * scale[k], high[k] * scale[k]));
            return Ok(LocalSolid {
                integrals: scaled,
                bounds: (ends.map(|(a, b)| a.min(b)), ends.map(|(a, b)| a.max(b))),
                hull,
            });
        }
    };
    Ok(LocalSolid {
        integrals,
        bounds,
        hull: None,
    })
}

fn describe(geometry: &Geometry) -> &'static str {
    match geometry {
        Geometry::Box { .. } => "a box",
        Geometry::Cylinder { .. } => "a cylinder",
        Geometry::Sphere { .. } => "a sphere",
        Geometry::Capsule { .. } => "a capsule",
        Geometry::Mesh { .. } => "a mesh with a zero or non-finite scale",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::span::{Span, Spanned};
    use crate::urdf::robot::Pose;

    fn shape(geometry: Geometry, xyz: [f64; 3], rpy: [f64; 3]) -> Shape {
        Shape {
            span: Span::default(),
            name: None,
            origin: Pose {
                xyz,
                rpy,
                ..Pose::default()
            },
            geometry: Some(Spanned {
                value: geometry,
                span: Span::default(),
            }),
            material: None,
        }
    }

    fn link(collisions: Vec<Shape>, visuals: Vec<Shape>) -> Link {
        Link {
            name: Spanned {
                value: "l".into(),
                span: Span::default(),
            },
            span: Span::default(),
            inertial: None,
            visuals,
            collisions,
        }
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300)
    }

    #[test]
    fn a_box_is_exact_and_collision_comes_before_visual() {
        let b = shape(
            Geometry::Box {
                size: [1.0, 2.0, 3.0],
            },
            [0.5, 0.0, 0.0],
            [0.0; 3],
        );
        let s = shape(Geometry::Sphere { radius: 9.0 }, [0.0; 3], [0.0; 3]);
        let g = of_link(&link(vec![b], vec![s]), &Assets::default()).unwrap();
        assert_eq!(g.role, Role::Collision);
        assert!(close(g.volume(), 6.0));
        assert_eq!(g.com(), [0.5, 0.0, 0.0]);
        let i = g.inertia(12.0);
        assert!(close(i[0][0], 12.0 * (4.0 + 9.0) / 12.0));
        assert!(close(i[1][1], 12.0 * (1.0 + 9.0) / 12.0));
        assert!(close(i[2][2], 12.0 * (1.0 + 4.0) / 12.0));
        assert_eq!(i[0][1], 0.0);
    }

    #[test]
    fn a_cylinder_and_a_sphere_are_exact() {
        let c = shape(
            Geometry::Cylinder {
                radius: 0.5,
                length: 2.0,
            },
            [0.0; 3],
            [0.0; 3],
        );
        let g = of_link(&link(vec![], vec![c]), &Assets::default()).unwrap();
        assert_eq!(g.role, Role::Visual);
        assert!(close(g.volume(), PI * 0.25 * 2.0));
        let i = g.inertia(3.0);
        assert!(close(i[0][0], 3.0 * (3.0 * 0.25 + 4.0) / 12.0));
        assert!(close(i[2][2], 3.0 * 0.25 / 2.0));
        let s = shape(Geometry::Sphere { radius: 2.0 }, [0.0; 3], [0.0; 3]);
        let i = of_link(&link(vec![s], vec![]), &Assets::default())
            .unwrap()
            .inertia(5.0);
        assert!(close(i[1][1], 0.4 * 5.0 * 4.0));
    }

    #[test]
    fn a_rotated_offset_pair_gives_the_parallel_axis_terms() {
        // Two unit cubes at x = ±1, the second turned about z: about the centroid (0, 0, 0),
        // Iyy = Izz = m (1/6 + 1), Ixx = m/6.
        let cube = || Geometry::Box { size: [1.0; 3] };
        let g = of_link(
            &link(
                vec![
                    shape(cube(), [1.0, 0.0, 0.0], [0.0; 3]),
                    shape(cube(), [-1.0, 0.0, 0.0], [0.0, 0.0, 0.3]),
                ],
                vec![],
            ),
            &Assets::default(),
        )
        .unwrap();
        let i = g.inertia(2.0);
        assert!(close(i[0][0], 2.0 / 6.0));
        assert!(close(i[1][1], 2.0 * (1.0 / 6.0 + 1.0)));
        assert!(i[0][1].abs() < 1e-15);
    }

    #[test]
    fn a_capsule_matches_its_parts() {
        // A capsule of length 0 is a sphere.
        let r = 0.7;
        let cap = shape(
            Geometry::Capsule {
                radius: r,
                length: 1e-300,
            },
            [0.0; 3],
            [0.0; 3],
        );
        let i = of_link(&link(vec![cap], vec![]), &Assets::default())
            .unwrap()
            .inertia(1.0);
        assert!(close(i[0][0], 0.4 * r * r) && close(i[2][2], 0.4 * r * r));
    }

    #[test]
    fn missing_geometry_is_said() {
        assert_eq!(
            of_link(&link(vec![], vec![]), &Assets::default()),
            Err(NoGeometry::NoShapes)
        );
        let flat = shape(
            Geometry::Box {
                size: [1.0, 0.0, 1.0],
            },
            [0.0; 3],
            [0.0; 3],
        );
        assert!(matches!(
            of_link(&link(vec![flat], vec![]), &Assets::default()),
            Err(NoGeometry::Unknown(_))
        ));
    }
}
