//! Convex collision shapes and the narrow phase.
//!
//! Every shape is a convex *core* (a point, a segment, a cylinder or a point cloud standing for its convex
//! hull) grown by a radius: a sphere is a point grown by its radius, a capsule a segment. GJK runs on the
//! cores (parry's implementation, statically dispatched over [`Core`]) and the radii are subtracted
//! afterwards, which is exact for rounded shapes and converges faster than GJK on curved support maps.

use nalgebra::{Isometry3, Point3, Vector3};
use parry3d_f64::math::{Pose, Rotation, Vector};
use parry3d_f64::query::details::closest_points_support_map_support_map_with_params;
use parry3d_f64::query::gjk::{GJKResult, VoronoiSimplex};
use parry3d_f64::shape::SupportMap;

use crate::geometry::Support;

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
    /// The convex hull of these points.
    Hull(Vec<Vector>),
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
            Core::Hull(points) => {
                let mut best = Vector::ZERO;
                let mut best_dot = f64::NEG_INFINITY;
                for p in points {
                    let d = p.dot(dir);
                    if d > best_dot {
                        best_dot = d;
                        best = *p;
                    }
                }
                best
            }
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
}

impl ConvexShape {
    /// The collision shape of one [`Support`]; `None` when its numbers are unusable.
    pub fn from_support(support: &Support) -> Option<ConvexShape> {
        let (core, radius, frame) = match support {
            Support::Points(points) => {
                let points: Vec<Vector> =
                    points.iter().map(|p| Vector::new(p.x, p.y, p.z)).collect();
                (Core::Hull(points), 0.0, Isometry3::identity())
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
        Some(ConvexShape {
            core,
            radius,
            frame,
            centre,
            bound,
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
        Core::Hull(points) => {
            let placed: Vec<Vector3<f64>> = points
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

/// The proximity of `a` placed at `pose_a` and `b` at `pose_b` (world placements of the shape frames),
/// exact up to `margin` (distances at or above `margin` are [`Proximity::Beyond`]).
pub fn proximity(
    a: &ConvexShape,
    pose_a: &Pose,
    b: &ConvexShape,
    pose_b: &Pose,
    margin: f64,
    simplex: &mut VoronoiSimplex,
) -> Proximity {
    let rounding = a.radius + b.radius;
    let core_distance = if let (Core::Point, Core::Point) = (&a.core, &b.core) {
        Some(pose_a.translation.distance(pose_b.translation))
    } else {
        let pos12 = pose_a.inv_mul(pose_b);
        match closest_points_support_map_support_map_with_params(
            &pos12,
            &a.core,
            &b.core,
            margin + rounding,
            simplex,
            None,
        ) {
            GJKResult::ClosestPoints(p1, p2, _) => Some(p1.distance(p2)),
            GJKResult::Intersection => None,
            GJKResult::NoIntersection(_) | GJKResult::Proximity(_) => return Proximity::Beyond,
        }
    };
    match core_distance.map(|d| d - rounding) {
        None => Proximity::Contact,
        Some(d) if d <= CONTACT_DISTANCE => Proximity::Contact,
        Some(d) if d < margin => Proximity::Apart(d),
        Some(_) => Proximity::Beyond,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Translation3, UnitQuaternion};

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
        proximity(a, pa, b, pb, f64::INFINITY, &mut VoronoiSimplex::new())
    }

    fn apart(p: Proximity) -> f64 {
        match p {
            Proximity::Apart(d) => d,
            other => panic!("expected a distance, got {other:?}"),
        }
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

    #[test]
    fn a_margin_cuts_the_query_short() {
        let mut simplex = VoronoiSimplex::new();
        let far = proximity(
            &cube(0.5),
            &at(0.0, 0.0, 0.0),
            &cube(0.5),
            &at(3.0, 0.0, 0.0),
            1.0,
            &mut simplex,
        );
        assert_eq!(far, Proximity::Beyond);
        let near = proximity(
            &cube(0.5),
            &at(0.0, 0.0, 0.0),
            &cube(0.5),
            &at(1.5, 0.0, 0.0),
            1.0,
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
}
