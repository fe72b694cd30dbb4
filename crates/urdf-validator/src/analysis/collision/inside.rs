//! Spheres inside a collision shape, as a cheap proof of contact: when a sphere inside one shape meets a
//! sphere inside another, the shapes overlap. GJK proves an overlap only after enough support queries
//! to enclose the origin in the shapes' difference (its costliest answer); the spheres take a few
//! multiplications, and prove only overlaps GJK would also find, so no result changes. Where they do
//! not meet, GJK decides.

use parry3d_f64::math::{Pose, Vector};

use super::shape::Core;

/// The most spheres kept inside one shape: one at its deepest point along its longest axis and one
/// towards each end.
const INSIDE: usize = 3;

/// Where along the shape's longest axis sphere centres are tried: this many steps from the box centre to
/// each end.
const STEPS: i32 = 10;

/// Centres tried: the box centre and [`STEPS`] each way.
const TRIED: usize = 2 * STEPS as usize + 1;

/// How much each sphere is shrunk (metres), so that rounding in the face planes can never make a sphere
/// reach outside its shape; far below [`CONTACT_DISTANCE`](super::CONTACT_DISTANCE).
const SAFETY: f64 = 1e-9;

/// Spheres inside a shape (centres in the shape frame).
#[derive(Clone, Copy, Debug)]
pub struct Inside {
    centres: [Vector; INSIDE],
    radii: [f64; INSIDE],
    len: usize,
}

impl Inside {
    /// No sphere known to be inside (a flat or unknown shape): meets nothing.
    pub const NONE: Inside = Inside {
        centres: [Vector::ZERO; INSIDE],
        radii: [0.0; INSIDE],
        len: 0,
    };

    /// Spheres inside `core` grown by `radius`, centred on the segment of `axis` (a unit vector of the
    /// shape frame: the longest axis of the shape's box) that runs `reach` either way from `middle` (the
    /// box centre): the deepest such centre, and on each side of it the one whose sphere reaches furthest
    /// along the axis while at least half as deep, when it reaches further than the deepest one.
    pub fn of(core: &Core, radius: f64, middle: Vector, axis: Vector, reach: f64) -> Inside {
        let step = reach / f64::from(STEPS);
        let along: [f64; TRIED] = std::array::from_fn(|k| f64::from(k as i32 - STEPS) * step);
        let depths = core.depths(&along.map(|along| middle + axis * along));
        let tried: Vec<(f64, f64)> = along
            .into_iter()
            .zip(depths.map(|depth| depth + radius))
            .filter(|(_, depth)| depth.is_finite() && *depth > SAFETY)
            .collect();
        let Some(&(deepest_at, deepest)) = tried
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.abs().total_cmp(&a.0.abs())))
        else {
            return Inside::NONE;
        };
        let mut inside = Inside::NONE;
        let mut keep = |along: f64, depth: f64| {
            inside.centres[inside.len] = middle + axis * along;
            inside.radii[inside.len] = depth - SAFETY;
            inside.len += 1;
        };
        keep(deepest_at, deepest);
        for side in [-1.0, 1.0] {
            let furthest = tried
                .iter()
                .filter(|(along, depth)| {
                    (along - deepest_at) * side > 0.0 && *depth >= deepest / 2.0
                })
                .map(|&(along, depth)| ((along - deepest_at).abs() + depth, along, depth))
                .max_by(|a, b| a.0.total_cmp(&b.0));
            if let Some((extent, along, depth)) = furthest {
                if extent > deepest {
                    keep(along, depth);
                }
            }
        }
        inside
    }

    /// The spheres, as (centre in the shape frame, radius).
    #[cfg(test)]
    pub fn spheres(&self) -> impl Iterator<Item = (Vector, f64)> + '_ {
        (0..self.len).map(|i| (self.centres[i], self.radii[i]))
    }

    /// True when a sphere inside this shape meets one inside `other`, placed at `pos12` in this shape's
    /// frame: the shapes overlap.
    pub fn meet(&self, other: &Inside, pos12: &Pose) -> bool {
        if self.len == 0 || other.len == 0 {
            return false;
        }
        let theirs: [Vector; INSIDE] =
            std::array::from_fn(|j| pos12.transform_point(other.centres[j]));
        (0..self.len).any(|i| {
            (0..other.len).any(|j| {
                let reach = self.radii[i] + other.radii[j];
                self.centres[i].distance_squared(theirs[j]) < reach * reach
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::collision::shape::Hull;

    fn cube(half: f64) -> Core {
        Core::cuboid(Vector::splat(half))
    }

    #[test]
    fn spheres_stay_inside_their_shape() {
        // A 2 × 0.5 × 0.5 box along x (a cube core stretched), a capsule and a cylinder along z.
        let long_box = Core::cuboid(Vector::new(1.0, 0.25, 0.25));
        let inside = Inside::of(&long_box, 0.0, Vector::ZERO, Vector::X, 1.0);
        assert_eq!(inside.len, 3, "{inside:?}");
        for i in 0..inside.len {
            let c = inside.centres[i];
            let r = inside.radii[i];
            assert!(c.x.abs() + r <= 1.0 && c.y.abs() + r <= 0.25 && c.z.abs() + r <= 0.25);
            // At least half as deep as the deepest (0.25).
            assert!(r >= 0.125 - 1e-6, "{inside:?}");
        }
        // The end spheres reach to within a quarter of the box's ends.
        let ends = (0..inside.len).map(|i| inside.centres[i].x.abs() + inside.radii[i]);
        assert!(ends.fold(0.0, f64::max) >= 0.95);

        let capsule = Inside::of(
            &Core::Segment { half: 1.0 },
            0.1,
            Vector::ZERO,
            Vector::Z,
            1.1,
        );
        let cylinder = Inside::of(
            &Core::Cylinder {
                radius: 0.2,
                half: 0.5,
            },
            0.0,
            Vector::ZERO,
            Vector::Z,
            0.5,
        );
        for (inside, radius, half) in [(capsule, 0.1, 1.1), (cylinder, 0.2, 0.5)] {
            assert_eq!(inside.len, 3, "{inside:?}");
            for i in 0..inside.len {
                let c = inside.centres[i];
                assert!(inside.radii[i] <= radius);
                assert!(c.z.abs() + inside.radii[i] <= half + 1e-12, "{inside:?}");
            }
        }
    }

    #[test]
    fn spheres_meet_only_where_the_shapes_overlap() {
        let a = Inside::of(&cube(0.5), 0.0, Vector::ZERO, Vector::X, 0.5);
        assert_eq!(a.len, 1, "a cube holds one sphere: {a:?}");
        let at = |x: f64| Pose::from_translation(Vector::new(x, 0.0, 0.0));
        // Centres 0.99 apart: the inscribed spheres (radius 0.5) meet, the cubes overlap.
        assert!(a.meet(&a, &at(0.99)));
        // Touching faces: the spheres touch without meeting (GJK decides).
        assert!(!a.meet(&a, &at(1.0)));
        // Cubes overlapping by a corner only: their spheres do not meet.
        let diagonal = Pose::from_translation(Vector::new(0.9, 0.9, 0.9));
        assert!(!a.meet(&a, &diagonal));
        // A point, a flat square and an unknown hull hold no sphere and meet nothing.
        let flat = Core::Hull(Hull::new(
            vec![
                Vector::new(0.0, 0.0, 0.0),
                Vector::new(1.0, 0.0, 0.0),
                Vector::new(0.0, 1.0, 0.0),
                Vector::new(1.0, 1.0, 0.0),
            ],
            None,
        ));
        for core in [Core::Point, flat] {
            let none = Inside::of(&core, 0.0, Vector::ZERO, Vector::X, 1.0);
            assert_eq!(none.len, 0);
            assert!(!none.meet(&a, &at(0.0)) && !a.meet(&none, &at(0.0)));
        }
        let nan = Inside::of(&cube(0.5), 0.0, Vector::splat(f64::NAN), Vector::X, 0.5);
        assert_eq!(nan.len, 0);
    }
}
