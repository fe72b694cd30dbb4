//! Link geometry as support points: what touches the ground when a link is placed in the world.
//!
//! Each collision shape (the visual when a link has no collision) becomes a [`Support`] in its link's
//! frame; [`Support::world_points`] gives, at a placement, a set of world points that contains the exact
//! lowest point of the shape (boxes: corners; spheres and capsules: their bottom; cylinders: the lowest point
//! of each rim, plus the rims when the axis is vertical; meshes: convex-hull vertices).

use nalgebra::{Isometry3, Point3, Vector3};

use crate::model::kinematics::pose_isometry;
use crate::urdf::robot::{Geometry, Link, Shape};

/// Primitives no larger than this in every dimension are markers (a visible dot for a frame), not bodies.
const MARKER_SIZE: f64 = 0.001;

/// Points around a rim used when a cylinder stands on its cap.
const RIM_POINTS: usize = 16;

/// One shape, ready to be placed.
#[derive(Clone, Debug)]
pub enum Support {
    /// A point cloud in the link frame (box corners, the vertices of a mesh whose hull is degenerate).
    Points(Vec<Vector3<f64>>),
    /// A mesh's convex hull in the link frame: its vertices, and the triangles of its surface (indices
    /// into `points`; empty when unknown).
    Hull {
        /// The hull's vertices.
        points: Vec<Vector3<f64>>,
        /// Its surface triangles.
        triangles: Vec<[u32; 3]>,
    },
    /// A sphere (`length` 0) or capsule (cylinder part of `length` along the local z axis).
    Rounded {
        /// Shape frame in the link frame.
        frame: Isometry3<f64>,
        /// Radius.
        radius: f64,
        /// Length of the straight part.
        length: f64,
    },
    /// A cylinder along its local z axis.
    Cylinder {
        /// Shape frame in the link frame.
        frame: Isometry3<f64>,
        /// Radius.
        radius: f64,
        /// Length.
        length: f64,
    },
}

impl Support {
    /// World points containing the shape's lowest point, for a link placed at `link`.
    pub fn world_points(&self, link: &Isometry3<f64>) -> Vec<Vector3<f64>> {
        match self {
            Support::Points(points) | Support::Hull { points, .. } => points
                .iter()
                .map(|p| link.transform_point(&Point3::from(*p)).coords)
                .collect(),
            Support::Rounded {
                frame,
                radius,
                length,
            } => {
                let frame = link * frame;
                let axis = frame.rotation * Vector3::z();
                let centre = frame.translation.vector;
                [-0.5, 0.5]
                    .iter()
                    .map(|s| centre + axis * (s * length) - Vector3::z() * *radius)
                    .collect()
            }
            Support::Cylinder {
                frame,
                radius,
                length,
            } => {
                let frame = link * frame;
                let axis = frame.rotation * Vector3::z();
                let centre = frame.translation.vector;
                let down = -Vector3::z() + axis * axis.z; // −z with its component along the axis removed
                let mut points = Vec::new();
                for cap in [
                    centre + axis * (0.5 * length),
                    centre - axis * (0.5 * length),
                ] {
                    match down.try_normalize(1e-9) {
                        Some(d) => points.push(cap + d * *radius),
                        None => {
                            // Axis vertical: the whole rim is equally low.
                            let u = frame.rotation * Vector3::x();
                            let v = frame.rotation * Vector3::y();
                            for k in 0..RIM_POINTS {
                                let t = std::f64::consts::TAU * k as f64 / RIM_POINTS as f64;
                                points.push(cap + (u * t.cos() + v * t.sin()) * *radius);
                            }
                        }
                    }
                }
                points
            }
        }
    }
}

/// What a mesh contributes to contact geometry, in the mesh frame before scale.
#[derive(Clone, Copy, Debug)]
pub struct MeshPoints<'m> {
    /// The hull's vertices, or every vertex when the hull is degenerate.
    pub points: &'m [[f64; 3]],
    /// When `points` is the hull: its surface triangles (possibly empty).
    pub hull_triangles: Option<&'m [[u32; 3]]>,
}

/// The shapes of one link (meshes that cannot be loaded are left out; the checks report them).
#[derive(Clone, Debug, Default)]
pub struct LinkSupports {
    /// Usable shapes.
    pub shapes: Vec<Support>,
    /// Per shape: the index of the link's collision (or visual, when it has no collisions) it is.
    pub sources: Vec<usize>,
}

/// The shapes a link contributes: its collisions, or its visuals when it has none.
/// `mesh_points` gives a mesh URI's hull points in the mesh frame (before scale), `None` when unusable.
pub fn link_supports<'m>(
    link: &Link,
    mesh_points: &dyn Fn(&str) -> Option<MeshPoints<'m>>,
) -> LinkSupports {
    let shapes: &[Shape] = if link.collisions.is_empty() {
        &link.visuals
    } else {
        &link.collisions
    };
    let mut out = LinkSupports::default();
    for (index, shape) in shapes.iter().enumerate() {
        let Some(geometry) = &shape.geometry else {
            continue;
        };
        let frame = pose_isometry(&shape.origin);
        let usable = |v: f64| v.is_finite() && v >= 0.0;
        let marker = match &geometry.value {
            Geometry::Box { size } => size.iter().all(|v| *v <= MARKER_SIZE),
            Geometry::Sphere { radius } => 2.0 * radius <= MARKER_SIZE,
            Geometry::Cylinder { radius, length } => {
                2.0 * radius <= MARKER_SIZE && *length <= MARKER_SIZE
            }
            // A capsule's `length` is its cylindrical part: the caps add a radius at each end.
            Geometry::Capsule { radius, length } => {
                2.0 * radius <= MARKER_SIZE && length + 2.0 * radius <= MARKER_SIZE
            }
            Geometry::Mesh { .. } => false,
        };
        if marker {
            continue;
        }
        match &geometry.value {
            Geometry::Box { size } if size.iter().all(|&v| usable(v)) => {
                let [x, y, z] = size.map(|v| v / 2.0);
                let corners = [-1.0, 1.0]
                    .iter()
                    .flat_map(|&sx| {
                        [-1.0, 1.0]
                            .iter()
                            .flat_map(move |&sy| [-1.0, 1.0].iter().map(move |&sz| (sx, sy, sz)))
                    })
                    .map(|(sx, sy, sz)| {
                        frame
                            .transform_point(&Point3::new(sx * x, sy * y, sz * z))
                            .coords
                    })
                    .collect();
                out.shapes.push(Support::Points(corners));
            }
            Geometry::Sphere { radius } if usable(*radius) => out.shapes.push(Support::Rounded {
                frame,
                radius: *radius,
                length: 0.0,
            }),
            Geometry::Capsule { radius, length } if usable(*radius) && usable(*length) => {
                out.shapes.push(Support::Rounded {
                    frame,
                    radius: *radius,
                    length: *length,
                })
            }
            Geometry::Cylinder { radius, length } if usable(*radius) && usable(*length) => {
                out.shapes.push(Support::Cylinder {
                    frame,
                    radius: *radius,
                    length: *length,
                })
            }
            Geometry::Mesh { filename, scale } if scale.iter().all(|v| v.is_finite()) => {
                if let Some(mesh) = mesh_points(&filename.value).filter(|m| !m.points.is_empty()) {
                    let scaled = mesh
                        .points
                        .iter()
                        .map(|p| {
                            frame
                                .transform_point(&Point3::new(
                                    p[0] * scale[0],
                                    p[1] * scale[1],
                                    p[2] * scale[2],
                                ))
                                .coords
                        })
                        .collect();
                    out.shapes.push(match mesh.hull_triangles {
                        Some(triangles) => Support::Hull {
                            points: scaled,
                            triangles: triangles.to_vec(),
                        },
                        None => Support::Points(scaled),
                    });
                }
            }
            _ => {}
        }
        out.sources.resize(out.shapes.len(), index);
    }
    out
}

/// Lowest world z of a link's shapes and the points within `tolerance` of it.
pub fn lowest_points(
    supports: &[Support],
    link: &Isometry3<f64>,
    tolerance: f64,
) -> Option<(f64, Vec<Vector3<f64>>)> {
    let points: Vec<Vector3<f64>> = supports.iter().flat_map(|s| s.world_points(link)).collect();
    let lowest = points.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
    lowest.is_finite().then(|| {
        (
            lowest,
            points
                .into_iter()
                .filter(|p| p.z <= lowest + tolerance)
                .collect(),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Translation3, UnitQuaternion};

    #[test]
    fn a_wheel_touches_at_the_bottom_of_its_rim() {
        // A wheel of radius 0.1 with its axis along y (cylinder z rotated onto y), centre at height 0.1.
        let frame = Isometry3::from_parts(
            Translation3::identity(),
            UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, 0.0),
        );
        let wheel = Support::Cylinder {
            frame,
            radius: 0.1,
            length: 0.04,
        };
        let placed = Isometry3::translation(0.0, 0.2, 0.1);
        let (lowest, points) = lowest_points(&[wheel], &placed, 1e-9).unwrap();
        assert!(lowest.abs() < 1e-12);
        assert_eq!(points.len(), 2, "one point per rim edge");
        assert!(points.iter().all(|p| (p.x).abs() < 1e-12));
    }

    #[test]
    fn a_capsule_is_a_marker_only_when_its_whole_length_is() {
        let supports = |shape: &str| {
            let urdf = format!(
                "<robot name=\"r\" version=\"1.1\"><link name=\"l\"><collision><geometry>{shape}</geometry></collision></link></robot>"
            );
            let (robot, _) =
                crate::urdf::parse_urdf(&urdf, std::path::Path::new("t.urdf")).unwrap();
            link_supports(&robot.links[0], &|_| None).shapes.len()
        };
        // 1 mm of cylinder plus two 0.5 mm caps: 2 mm long, a body.
        assert_eq!(supports(r#"<capsule radius="0.0005" length="0.001"/>"#), 1);
        assert_eq!(supports(r#"<capsule radius="0.0002" length="0.0005"/>"#), 0);
        assert_eq!(supports(r#"<cylinder radius="0.0005" length="0.001"/>"#), 0);
    }

    #[test]
    fn a_box_foot_gives_its_four_bottom_corners() {
        let foot = Support::Points(vec![]);
        assert!(lowest_points(&[foot], &Isometry3::identity(), 1e-3).is_none());
        let corners: Vec<Vector3<f64>> = [-1.0, 1.0]
            .iter()
            .flat_map(|&x| {
                [-1.0, 1.0].iter().flat_map(move |&y| {
                    [-1.0, 1.0]
                        .iter()
                        .map(move |&z| Vector3::new(0.1 * x, 0.05 * y, 0.02 * z))
                })
            })
            .collect();
        let (lowest, points) = lowest_points(
            &[Support::Points(corners)],
            &Isometry3::translation(0.0, 0.0, 0.02),
            1e-6,
        )
        .unwrap();
        assert!(lowest.abs() < 1e-12);
        assert_eq!(points.len(), 4);
    }
}
