//! Self-collision with real geometry: every link's collision shapes (primitives exactly, meshes as their
//! convex hulls), an allowed-collision matrix built as MoveIt's setup assistant builds it, and a per-pose
//! check with a bounding-sphere broad phase and a GJK narrow phase.
//!
//! Use from a sampling loop:
//!
//! ```no_run
//! # use urdf_validator::{analysis::collision::*, model::*, urdf::Robot};
//! # fn run(robot: &Robot, model: &Model, arm_joints: &[JointId], samples: &[Vec<f64>],
//! #        supports: &[urdf_validator::assets::LinkSupports]) {
//! let mut collision = CollisionModel::build(robot, model, supports);
//! // Reference pose: pairs already in contact are reported, then no longer checked.
//! let mut data = Data::new(model);
//! forward_kinematics(model, &model.zero_configuration(), &mut data);
//! let touching = collision.touching_pairs(&data.link_placement);
//! collision.allow(&touching, Allowed::Touching);
//! let pairs = collision.pairs_moved_by(&model.motion_of(arm_joints));
//! let mut scratch = CheckScratch::new(&collision);
//! let (mut free, mut clearance) = (0, f64::INFINITY);
//! for q in samples {
//!     forward_kinematics(model, q, &mut data);
//!     let check = collision.check(&pairs, &data.link_placement, clearance, &mut scratch);
//!     if check.is_free() {
//!         free += 1;
//!     }
//!     if let Some((distance, _pair)) = check.min_clearance {
//!         clearance = distance;
//!     }
//! }
//! # }
//! ```
//!
//! [`CollisionModel`] is immutable during checks and `Sync`; each thread keeps its own [`CheckScratch`]
//! (with rayon: `map_init`).

mod allowed;
mod broad;
mod check;
mod enclose;
mod held;
mod inside;
mod shape;

use std::ops::Range;

use nalgebra::{Isometry3, Vector3};
use rayon::prelude::*;

use crate::analysis::memo::Fingerprint;
use crate::assets::LinkSupports;
use crate::model::{JointId, LinkId, Model};
use crate::urdf::robot::Robot;

pub use allowed::Allowed;
pub use broad::PairSet;
pub(crate) use check::usable_parts;
pub use check::{CheckScratch, PoseCheck};
pub use shape::{CONTACT_DISTANCE, MAX_EXTENT};

/// Where every link is in the world for a check, by link: a slice of placements indexed by link (as
/// [`crate::model::kinematics::Data::link_placement`]) is one. A check reads the placements of the links
/// its tests reach, each at most a few times, so a sampler can hand a view that assembles them on demand.
pub trait LinkPlacements {
    /// The placement of `link`; `None` when there is none.
    fn placement(&self, link: LinkId) -> Option<Isometry3<f64>>;
}

impl LinkPlacements for [Isometry3<f64>] {
    #[inline]
    fn placement(&self, link: LinkId) -> Option<Isometry3<f64>> {
        self.get(link.0).copied()
    }
}

impl LinkPlacements for Vec<Isometry3<f64>> {
    #[inline]
    fn placement(&self, link: LinkId) -> Option<Isometry3<f64>> {
        self.as_slice().placement(link)
    }
}

/// The most links a self-collision model is built for: the allowed-collision matrix and the pair lists
/// grow with the square of it (real robots have at most a few hundred links; a generated 6,000-link
/// chain took minutes and gigabytes).
pub const MAX_COLLISION_LINKS: usize = 1024;

use shape::{enclosing_sphere, to_pose, ConvexShape};

/// The collision geometry of a robot and its allowed-collision matrix.
#[derive(Clone, Debug)]
pub struct CollisionModel {
    shapes: Vec<ConvexShape>,
    /// Per shape: the index of its link's collision it was built from.
    sources: Vec<usize>,
    /// Per link: its shapes in `shapes` and a sphere around them (centre in the link frame, radius).
    bodies: Vec<Body>,
    /// Links with at least one shape, in index order.
    geometric: Vec<LinkId>,
    /// Row-major `links × links`, symmetric.
    allowed: Vec<Option<Allowed>>,
    /// Per link: the joint to its parent and the parent.
    parent: Vec<Option<(JointId, LinkId)>>,
    /// Per link: joints between it and its root.
    depth: Vec<usize>,
}

#[derive(Clone, Debug)]
struct Body {
    shapes: Range<usize>,
    centre: Vector3<f64>,
    radius: f64,
}

impl CollisionModel {
    /// Feed everything a check reads of the model: every link's shapes and the allowed-collision matrix.
    pub(crate) fn fingerprint(&self, print: &mut Fingerprint) {
        print.value(self.shapes.len());
        for (shape, source) in self.shapes.iter().zip(&self.sources) {
            shape.fingerprint(print);
            print.value(source);
        }
        for body in &self.bodies {
            print
                .value(&body.shapes)
                .vector(&body.centre)
                .float(body.radius);
        }
        print
            .value(&self.geometric)
            .value(&self.allowed)
            .value(&self.parent)
            .value(&self.depth);
    }

    /// The collision shapes of every link (`<collision>` elements only: primitives, and meshes as their
    /// convex hull), from the links' supports the assets stage built (`supports[link]`). Markers (≤ 1 mm)
    /// and unusable shapes are left out there. The allowed-collision matrix starts with the adjacent and
    /// rigidly attached pairs.
    pub fn build(robot: &Robot, model: &Model, supports: &[LinkSupports]) -> CollisionModel {
        let links = robot.links.len();
        // Each link's shapes (a mesh hull's edges and support map are built here), links in parallel.
        let per_link: Vec<Vec<(ConvexShape, usize)>> = robot
            .links
            .par_iter()
            .zip(supports)
            .map(|(link, link_supports)| {
                // Supports are the collisions, or the visuals when a link has none: only collisions
                // collide.
                if link.collisions.is_empty() {
                    return Vec::new();
                }
                link_supports
                    .shapes
                    .iter()
                    .zip(&link_supports.sources)
                    .filter_map(|(support, &source)| {
                        Some((ConvexShape::from_support(support)?, source))
                    })
                    .collect()
            })
            .collect();
        let mut shapes = Vec::new();
        let mut sources = Vec::new();
        let mut bodies = Vec::with_capacity(links);
        for link_shapes in per_link {
            let start = shapes.len();
            for (shape, source) in link_shapes {
                shapes.push(shape);
                sources.push(source);
            }
            let spheres: Vec<(Vector3<f64>, f64)> = shapes[start..]
                .iter()
                .map(|s| (s.centre, s.bound))
                .collect();
            let (centre, radius) = enclosing_sphere(&spheres).unwrap_or((Vector3::zeros(), 0.0));
            bodies.push(Body {
                shapes: start..shapes.len(),
                centre,
                radius,
            });
        }
        let parent: Vec<Option<(JointId, LinkId)>> = (0..links)
            .map(|l| {
                let joint = model.parent_joint.get(l).copied().flatten()?;
                let (p, _) = model.joint_links.get(joint.0).copied().flatten()?;
                Some((joint, p))
            })
            .collect();
        let depth = (0..links)
            .map(|l| {
                let mut link = l;
                let mut depth = 0;
                while let Some((_, p)) = parent[link] {
                    link = p.0;
                    depth += 1;
                    if depth > links {
                        break; // not a tree; Model::build prevents this
                    }
                }
                depth
            })
            .collect();
        let mut collision = CollisionModel {
            geometric: (0..links)
                .filter(|&l| !bodies[l].shapes.is_empty())
                .map(LinkId)
                .collect(),
            shapes,
            sources,
            bodies,
            allowed: vec![None; links * links],
            parent,
            depth,
        };
        collision.allow_structural(model);
        collision
    }

    /// Every pair of links with geometry, lower index first.
    fn geometric_pairs(&self) -> impl Iterator<Item = (LinkId, LinkId)> + '_ {
        self.geometric
            .iter()
            .enumerate()
            .flat_map(move |(i, &a)| self.geometric[i + 1..].iter().map(move |&b| (a, b)))
    }

    /// True when `link` has at least one usable collision shape.
    pub fn has_geometry(&self, link: LinkId) -> bool {
        self.bodies
            .get(link.0)
            .is_some_and(|b| !b.shapes.is_empty())
    }

    /// The deepest overlap between a shape of `a` placed at `pose_a` and one of `b` at `pose_b` that
    /// `may_touch` lets collide (given the indices of the links' collisions they are): its depth
    /// (metres, > 0) and those two indices; `None` when no such pair overlaps.
    pub fn overlap_depth(
        &self,
        (a, pose_a): (LinkId, &Isometry3<f64>),
        (b, pose_b): (LinkId, &Isometry3<f64>),
        may_touch: &dyn Fn(usize, usize) -> bool,
    ) -> Option<(f64, usize, usize)> {
        let (body_a, body_b) = (self.bodies.get(a.0)?, self.bodies.get(b.0)?);
        let (centre_a, centre_b) = (
            pose_a.transform_point(&body_a.centre.into()),
            pose_b.transform_point(&body_b.centre.into()),
        );
        if (centre_a - centre_b).norm() >= body_a.radius + body_b.radius {
            return None;
        }
        let mut deepest: Option<(f64, usize, usize)> = None;
        for i in body_a.shapes.clone() {
            let at_a = to_pose(&(pose_a * self.shapes[i].frame));
            for j in body_b.shapes.clone() {
                let sources = (self.sources[i], self.sources[j]);
                if !may_touch(sources.0, sources.1) {
                    continue;
                }
                let at_b = to_pose(&(pose_b * self.shapes[j].frame));
                let depth = shape::overlap_depth(&self.shapes[i], &at_a, &self.shapes[j], &at_b);
                if depth > 0.0 && deepest.is_none_or(|d| depth > d.0) {
                    deepest = Some((depth, sources.0, sources.1));
                }
            }
        }
        deepest
    }

    /// The shape of `link` placed at `placement` that `may_touch` lets touch the plane through `point`
    /// with unit `normal` (solid on the side away from the normal) and reaches deepest below it: how far
    /// (metres, > 0) and the index of the link's collision it is; `None` when none reaches below.
    pub fn depth_below_plane(
        &self,
        link: LinkId,
        placement: &Isometry3<f64>,
        (point, normal): (&Vector3<f64>, &Vector3<f64>),
        may_touch: &dyn Fn(usize) -> bool,
    ) -> Option<(f64, usize)> {
        self.bodies
            .get(link.0)?
            .shapes
            .clone()
            .filter(|&i| may_touch(self.sources[i]))
            .map(|i| {
                let shape = &self.shapes[i];
                let depth =
                    shape::depth_below_plane(shape, &(placement * shape.frame), point, normal);
                (depth, self.sources[i])
            })
            .filter(|&(depth, _)| depth > 0.0)
            .max_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// The links with collision shapes, in index order.
    pub fn geometric_links(&self) -> &[LinkId] {
        &self.geometric
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Point3;

    use super::*;
    use crate::analysis::pose::ConfigurationSampler;
    use crate::assets::link_supports;
    use crate::model::{forward_kinematics, Data};

    /// A chain of `n` box links 2 cm apart, each joint bending by up to `range` radians.
    fn chain(n: usize, range: f64) -> String {
        let body = "<collision><geometry><box size=\"0.01 0.01 0.01\"/></geometry></collision>";
        let links: String = (0..=n)
            .map(|i| format!("<link name=\"l{i}\">{body}</link>"))
            .collect();
        let joints: String = (0..n)
            .map(|i| {
                format!(
                    "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{i}\"/><child link=\"l{}\"/>\
                     <origin xyz=\"0 0 0.02\"/><axis xyz=\"{} 1 0\"/>\
                     <limit lower=\"-{range}\" upper=\"{range}\" effort=\"1\" velocity=\"1\"/></joint>",
                    i + 1,
                    i % 2
                )
            })
            .collect();
        format!("<robot name=\"chain\">{links}{joints}</robot>")
    }

    /// The tree and collision model of [`chain`]`(n, range)`.
    fn chain_collision(n: usize, range: f64) -> (Model, CollisionModel) {
        let text = chain(n, range);
        let (robot, _) = crate::urdf::parse_urdf(&text, std::path::Path::new("c.urdf")).unwrap();
        let (model, _) = Model::build(&robot);
        let supports: Vec<_> = robot
            .links
            .iter()
            .map(|l| link_supports(l, &|_| None))
            .collect();
        let collision = CollisionModel::build(&robot, &model, &supports);
        (model, collision)
    }

    /// A scratch holding the links the pair set's joints do not move gives every pose the same result as
    /// one recomputing every link, when only those joints vary (the other links stay where they are):
    /// with one link per moving group (the last six joints vary, the first six hold their reference
    /// bends), and with groups of three links (every third joint varies).
    #[test]
    fn holding_the_fixed_links_changes_no_result() {
        let six: Vec<JointId> = (6..12).map(JointId).collect();
        let every_third: Vec<JointId> = [2, 5, 8, 11].map(JointId).to_vec();
        holding_changes_no_result(&six);
        holding_changes_no_result(&every_third);
    }

    fn holding_changes_no_result(varied: &[JointId]) {
        let (model, collision) = chain_collision(12, 3.0);
        let pairs = collision.pairs_moved_by(&model.motion_of(varied));
        assert!(pairs.held.is_some(), "the rigid-group broad phase is used");
        assert!(
            pairs.moving.len() < pairs.links.len(),
            "some links are held"
        );
        let mut sampler = ConfigurationSampler::new(&model, 3);
        let mut reference = model.zero_configuration();
        sampler.sample_into(&mut reference);
        let mut q = reference.clone();
        let mut data = Data::new(&model);
        // Both scratches keep their GJK warm starts from pose to pose, as the sampler's do.
        let mut plain = CheckScratch::new(&collision);
        let mut held = CheckScratch::holding_fixed(&collision);
        // And one told the moving links' sphere centres (as the workspace sampler's batches tell it).
        let mut vouched = CheckScratch::holding_fixed(&collision);
        let (mut cutoff, mut contacts) = (f64::INFINITY, 0);
        for _ in 0..400 {
            let mut sample = model.zero_configuration();
            sampler.sample_into(&mut sample);
            for joint in varied {
                q[joint.0] = sample[joint.0];
            }
            forward_kinematics(&model, &q, &mut data);
            let reused = collision.check(&pairs, &data.link_placement, cutoff, &mut plain);
            let kept = collision.check(&pairs, &data.link_placement, cutoff, &mut held);
            assert_eq!(reused, kept);
            let centres: Vec<Vector3<f64>> = pairs
                .moving_links()
                .map(|link| {
                    (data.link_placement[link.0] * Point3::from(collision.sphere_centre(link)))
                        .coords
                })
                .collect();
            vouched.vouch_moving(&pairs, centres.into_iter());
            let told = collision.check(&pairs, &data.link_placement, cutoff, &mut vouched);
            assert_eq!(told, kept);
            // And as a scratch that knows nothing of earlier poses finds (up to GJK's warm start).
            let fresh = collision.check(
                &pairs,
                &data.link_placement,
                cutoff,
                &mut CheckScratch::new(&collision),
            );
            assert_eq!((fresh.contact, fresh.skipped), (kept.contact, kept.skipped));
            match (fresh.min_clearance, kept.min_clearance) {
                (Some((a, pa)), Some((b, pb))) => assert!(pa == pb && (a - b).abs() < 1e-12),
                (a, b) => assert_eq!(a, b),
            }
            contacts += usize::from(!fresh.is_free());
            if let Some((distance, _)) = kept.min_clearance {
                cutoff = distance;
            }
        }
        assert!(
            contacts > 0 && contacts < 400,
            "{contacts} poses in contact"
        );
    }

    /// The sweep-and-prune broad phase only skips pairs the full scan would reject: on long chains,
    /// folded (contacts) and nearly straight (clearances), every pose gives the same result both ways.
    #[test]
    fn the_sweep_gives_the_same_result_as_scanning_every_pair() {
        for range in [1.5, 0.2, 0.01] {
            let (model, collision) = chain_collision(300, range);
            let swept = collision.all_pairs();
            assert!(swept.sweep.is_some(), "a 300-link chain uses the sweep");
            let scanned = PairSet {
                sweep: None,
                ..swept.clone()
            };
            let mut sampler = ConfigurationSampler::new(&model, 11);
            let mut q = model.zero_configuration();
            let mut data = Data::new(&model);
            let (mut one, mut other) =
                (CheckScratch::new(&collision), CheckScratch::new(&collision));
            let mut cutoff = f64::INFINITY;
            let mut free = 0;
            for _ in 0..300 {
                sampler.sample_into(&mut q);
                forward_kinematics(&model, &q, &mut data);
                let a = collision.check(&swept, &data.link_placement, cutoff, &mut one);
                let b = collision.check(&scanned, &data.link_placement, cutoff, &mut other);
                assert_eq!(a, b, "range {range}");
                if let Some((distance, _)) = a.min_clearance {
                    cutoff = distance;
                }
                free += usize::from(a.is_free());
            }
            if range < 0.05 {
                assert_eq!(free, 300, "a nearly straight chain is free");
            }
        }
    }
}
