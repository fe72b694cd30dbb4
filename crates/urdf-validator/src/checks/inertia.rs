//! Mass and inertia plausibility: missing inertials on moving links, signs, positive definiteness, the
//! triangle inequality on the principal moments, and the declared tensor against the link's geometry.
//! Findings the geometry can resolve carry the fix that writes its inertia ([`super::inertia_fix`]).

use crate::analysis::geometry_inertia::{self, GeometryInertia, Role};
use crate::assets::Assets;
use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::diagnostics::span::Spanned;
use crate::input::Format;
use crate::model::kinematics::pose_isometry;
use crate::model::{LinkId, Model};
use crate::urdf::robot::{principal_moments, Inertia, Inertial, JointKind, Link, Robot};

use super::inertia_fix;

/// Relative slack on `A + B ≥ C`: values printed with ~6 significant digits round by ~1e-6, and thin plates
/// sit exactly on the boundary.
const TRIANGLE_TOLERANCE: f64 = 1e-4;

/// Principal moments further apart than this factor from the geometry's are U208.
const FAR_FACTOR: f64 = 3.0;

pub(super) fn check(robot: &Robot, model: &Model, assets: &Assets) -> Vec<Finding> {
    let mut findings = Vec::new();
    // Each link's geometry solid once: the lumped shares, the checks and the fixes all read it.
    let geometries: Vec<Result<GeometryInertia, _>> = robot
        .links
        .iter()
        .map(|link| geometry_inertia::of_link(link, assets))
        .collect();
    let lumps = Lumps::new(robot, model, &geometries);
    for (i, link) in robot.links.iter().enumerate() {
        let owner = format!("Link '{}'", link.name.value);
        let moving = model.is_moving(robot, LinkId(i));
        let geometry = || geometries[i].as_ref();
        let Some(inertial) = &link.inertial else {
            // An MJCF link without mass or shapes chains a body's joints (MuJoCo has no such body).
            let joint_chain = robot.format == Format::Mjcf && link.is_bare();
            if moving && !joint_chain {
                findings.push(
                    Finding::new(
                        &rules::MISSING_INERTIAL,
                        link.span,
                        format!("{owner} has no inertial block (mass unknown) — will cause physics engine instability"),
                    )
                    .with_fix_option(
                        geometry()
                            .ok()
                            .map(|g| inertia_fix::insert_inertial(link, g)),
                    ),
                );
            } else if !link.visuals.is_empty() || !link.collisions.is_empty() {
                findings.push(Finding::new(
                    &rules::MASSLESS_GEOMETRY,
                    link.span,
                    format!(
                        "{owner} has geometry but no inertial block: its weight is not counted"
                    ),
                ));
            }
            continue;
        };
        let mass = inertial.mass.as_ref().filter(|m| m.value.is_finite());
        if let Some(mass) = mass {
            if mass.value < 0.0 {
                findings.push(Finding::new(
                    &rules::NEGATIVE_MASS,
                    mass.span,
                    format!("{owner} has negative mass {} kg", mass.value),
                ));
            } else if mass.value == 0.0 && moving {
                findings.push(Finding::new(
                    &rules::ZERO_MASS,
                    mass.span,
                    format!("{owner} is moved by a joint but has mass 0"),
                ));
            }
        }
        // MJCF masses come from the geoms' declared density (ant's 5 kg/m³, a pusher goal's 1e-5 are
        // the author's choice, and MuJoCo simulates them so); only URDF and SDFormat masses are judged.
        if let Some(mass) = mass.filter(|m| m.value > 0.0 && robot.format != Format::Mjcf) {
            findings.extend(implausible_density(link, assets, mass, moving, &owner));
        }
        let Some(inertia) = inertial.inertia.as_ref() else {
            continue;
        };
        let massive = mass.is_none_or(|m| m.value > 0.0);
        let positive_mass = mass.map(|m| m.value).filter(|&m| m > 0.0);
        if let Some(finding) = check_tensor(inertia, &owner, moving && massive) {
            let fix = positive_mass
                .and_then(|m| inertia_fix::replace_tensor(inertial, inertia, geometry().ok()?, m));
            findings.push(finding.with_fix_option(fix));
        } else if let (true, Some(m), Ok(g)) = (lumps.judged(LinkId(i)), positive_mass, geometry())
        {
            let owner = match lumps.into[i] {
                Some(parent) => format!(
                    "{owner} (welded to '{}': simulators lump its mass and inertia into that link's)",
                    robot.links[parent.0].name.value
                ),
                None => owner,
            };
            findings.extend(
                against_geometry(link, assets, inertial, inertia, g, m, &owner).map(|f| {
                    f.with_fix_option(inertia_fix::replace_tensor(inertial, inertia, g, m))
                }),
            );
        }
    }
    findings
}

/// Densest material, kg/m³, with rounding slack (osmium is 22,590).
const MAX_DENSITY: f64 = 25_000.0;

/// Lightest plausible solid part, kg/m³ (foams are 20–100).
const MIN_DENSITY: f64 = 10.0;

/// Geometry below this volume (a 12.6 mm cube) is a marker or a placeholder (PR2's 1 mm sensor boxes
/// carry 100 g): no density is judged from it, m³.
const MIN_JUDGED_VOLUME: f64 = 2e-6;

/// U210 when `mass` in the volume of `link`'s geometry is beyond every material: above [`MAX_DENSITY`] in
/// the larger of its collision and visual volumes (a part is at least as big as either shows it), or, on a
/// moving link, below [`MIN_DENSITY`] in the smaller (fixed links so often carry placeholder grams for
/// sensors and frames that only a moving one is judged light). No finding without geometry, or with less
/// than [`MIN_JUDGED_VOLUME`] of it.
fn implausible_density(
    link: &Link,
    assets: &Assets,
    mass: &Spanned<f64>,
    moving: bool,
    owner: &str,
) -> Option<Finding> {
    let volumes: Vec<(Role, f64)> = [Role::Collision, Role::Visual]
        .into_iter()
        .filter_map(|role| {
            let volume = geometry_inertia::of_role(link, role, assets).ok()?.volume();
            (volume.is_finite() && volume > 0.0).then_some((role, volume))
        })
        .collect();
    let largest = volumes.iter().copied().max_by(|a, b| a.1.total_cmp(&b.1))?;
    if largest.1 < MIN_JUDGED_VOLUME {
        return None;
    }
    let smallest = volumes.iter().copied().min_by(|a, b| a.1.total_cmp(&b.1))?;
    let (role, volume, bound) = if mass.value / largest.1 > MAX_DENSITY {
        (
            largest.0,
            largest.1,
            "beyond any material (osmium, the densest, is 22,590 kg/m³): the mass is wrong, or the geometry shows only part of the link",
        )
    } else if moving && mass.value / smallest.1 < MIN_DENSITY {
        (
            smallest.0,
            smallest.1,
            "lighter than any solid part (foams are 20–100 kg/m³): the mass is wrong, or the geometry is larger than the link",
        )
    } else {
        return None;
    };
    let density = mass.value / volume;
    Some(
        Finding::new(
            &rules::IMPLAUSIBLE_DENSITY,
            mass.span,
            format!(
                "{owner}: mass {} kg in the {} m³ of its {} geometry is a density of {} kg/m³, {bound}; as plastic (1,000 kg/m³) it would weigh {} kg, as steel (7,850 kg/m³) {} kg",
                short_number(mass.value),
                short_number(volume),
                role.label(),
                short_number(density),
                short_number(1000.0 * volume),
                short_number(7850.0 * volume),
            ),
        )
        .with_help("check the mass's units (g or kg) and that it belongs to this link"),
    )
}

/// Share of the lumped body's inertia below which a fixed link's tensor is not judged: a 0.1 g sensor
/// frame's placeholder tensor changes nothing in the link it is welded to.
const LUMP_SHARE: f64 = 0.01;

/// Which links' tensors are judged against their geometry, and the link each fixed one is lumped into.
struct Lumps {
    /// Per link: the link a fixed link is lumped into (up its fixed joints to the first link that moves, or
    /// the root); `None` for a moving link, the root, or a link outside the tree.
    into: Vec<Option<LinkId>>,
    /// Per link: part of the tree (the root, or a link with a parent joint).
    in_tree: Vec<bool>,
    /// Per link: its largest declared principal moment, kg·m² (0 without a tensor).
    declared: Vec<f64>,
    /// Per link: the largest principal moment of its geometry filled at its declared mass, summed over
    /// the link and every link lumped into it, kg·m². From masses and shapes only, so a fix that rewrites
    /// tensors leaves it as it was (the fixes stay idempotent).
    lumped: Vec<f64>,
    /// The root when it is the world itself (a link named `world`, as Gazebo, the SDFormat reader and
    /// MJCF's worldbody have it): what is welded to it never moves, and its inertia enters no dynamics.
    world: Option<LinkId>,
}

impl Lumps {
    fn new(
        robot: &Robot,
        model: &Model,
        geometries: &[Result<GeometryInertia, geometry_inertia::NoGeometry>],
    ) -> Lumps {
        let links = robot.links.len();
        let mut into: Vec<Option<LinkId>> = vec![None; links];
        for &link in &model.topological_order {
            let Some(joint) = model.parent_joint[link.0] else {
                continue;
            };
            let Some((parent, _)) = model.joint_links[joint.0] else {
                continue;
            };
            if model.joint_data[joint.0].kind == JointKind::Fixed {
                into[link.0] = Some(into[parent.0].unwrap_or(parent));
            }
        }
        let declared: Vec<f64> = robot
            .links
            .iter()
            .map(|link| {
                link.inertial
                    .as_ref()
                    .and_then(|i| i.inertia.as_ref())
                    .and_then(Inertia::principal_moments)
                    .map_or(0.0, |[_, _, c]| c.max(0.0))
            })
            .collect();
        let mut lumped: Vec<f64> = robot
            .links
            .iter()
            .zip(geometries)
            .map(|(link, geometry)| {
                let mass = link
                    .inertial
                    .as_ref()
                    .and_then(|i| i.mass.as_ref())
                    .map_or(0.0, |m| m.value);
                if !(mass.is_finite() && mass > 0.0) {
                    return 0.0;
                }
                geometry
                    .as_ref()
                    .ok()
                    .and_then(|g| principal_moments(&g.inertia(mass)))
                    .map_or(0.0, |[_, _, c]| c.max(0.0))
            })
            .collect();
        for (link, target) in into.iter().enumerate() {
            if let Some(target) = target {
                lumped[target.0] += lumped[link];
            }
        }
        let in_tree = (0..links)
            .map(|l| model.parent_joint[l].is_some() || model.root == Some(LinkId(l)))
            .collect();
        let world = model
            .root
            .filter(|root| robot.links[root.0].name.value == "world");
        Lumps {
            into,
            in_tree,
            declared,
            lumped,
            world,
        }
    }

    /// Whether `link`'s tensor is judged against its geometry: a moving link or the root (the floating
    /// base of a simulator), or a fixed link whose declared tensor is at least [`LUMP_SHARE`] of the body it
    /// is lumped into (turtlebot3's 5 g caster with I = 0.001 kg·m² is a third of its base's); nothing
    /// welded to the world.
    fn judged(&self, link: LinkId) -> bool {
        self.in_tree[link.0]
            && self.world != Some(link)
            && self.into[link.0].is_none_or(|target| {
                self.world != Some(target)
                    && self.declared[link.0] >= LUMP_SHARE * self.lumped[target.0]
            })
    }
}

/// U209 when the declared tensor cannot be that of a body of mass `mass` inside the geometry's bounding
/// box, else U208 when its principal moments are more than [`FAR_FACTOR`] from the geometry's. For the
/// links [`Lumps::judged`] picks: a fixed link's tensor is lumped into its parent's by every simulator, and
/// a root without a joint to the world is the floating base.
#[allow(clippy::too_many_arguments)]
fn against_geometry(
    link: &Link,
    assets: &Assets,
    inertial: &Inertial,
    inertia: &Inertia,
    geometry: &GeometryInertia,
    mass: f64,
    owner: &str,
) -> Option<Finding> {
    let declared = principal_moments(&inertia.matrix())?;
    let from_geometry = principal_moments(&geometry.inertia(mass))?;
    let what = geometry_words(geometry);
    // The box of the shapes the inertia comes from first; when the tensor does not fit it, the box of
    // every shape (collision shapes are often smaller than the part, its visuals closer to it).
    let outside = outside_bounds(inertial, inertia, geometry.bounds, mass).and_then(|problem| {
        match geometry_inertia::bounds_of_all_shapes(link, assets) {
            Some(all) if all != geometry.bounds => outside_bounds(inertial, inertia, all, mass)
                .map(|p| (p, "all its collision and visual shapes".to_string())),
            _ => Some((problem, what.clone())),
        }
    });
    if let Some((problem, what)) = outside {
        return Some(Finding::new(
            &rules::INERTIA_OUTSIDE_GEOMETRY,
            inertia.span,
            format!("{owner}: the declared inertia cannot be that of a {} kg body inside the bounding box of {what}: {problem}", short_number(mass)),
        ));
    }
    let factor = declared
        .iter()
        .zip(&from_geometry)
        .filter(|(d, g)| **d > 0.0 && **g > 0.0)
        .map(|(d, g)| (d / g).max(g / d))
        .fold(1.0, f64::max);
    (factor > FAR_FACTOR).then(|| {
        let list = |m: [f64; 3]| m.map(short_number).join(", ");
        Finding::new(
            &rules::INERTIA_FAR_FROM_GEOMETRY,
            inertia.span,
            format!(
                "{owner}: declared principal moments ({}) kg·m² are up to {factor:.1}× from those of {what} filled uniformly at the declared {} kg ({})",
                list(declared),
                short_number(mass),
                list(from_geometry)
            ),
        )
    })
}

/// `the collision geometry`, with the meshes integrated as their hull.
fn geometry_words(geometry: &GeometryInertia) -> String {
    let mut words = format!("its {} geometry", geometry.role.label());
    if !geometry.hulls.is_empty() {
        words.push_str(&format!(" ({})", geometry.hulls.join("; ")));
    }
    words
}

/// Why no body of `mass` inside `bounds` (widened by 1 % of its size on each side, for
/// rounded numbers) has the declared tensor and centre of mass, if none can: by the Bhatia–Davis inequality a
/// mass distribution on [lo, hi] with mean c has ∫(x − c)² dm ≤ m (c − lo)(hi − c).
fn outside_bounds(
    inertial: &Inertial,
    inertia: &Inertia,
    bounds: ([f64; 3], [f64; 3]),
    mass: f64,
) -> Option<String> {
    let placement = pose_isometry(&inertial.origin);
    let r = placement.rotation.to_rotation_matrix().into_inner();
    let tensor = nalgebra::Matrix3::from_fn(|a, b| inertia.matrix()[a][b]);
    let in_link = r * tensor * r.transpose();
    // Second moments S = ½ tr(I) 1 − I, about the centre of mass, along the link axes.
    let half_trace = 0.5 * in_link.trace();
    let com = placement.translation.vector;
    let (low, high) = bounds;
    let axes = ["x", "y", "z"];
    for k in 0..3 {
        let margin = 0.01 * (high[k] - low[k]);
        let (lo, hi) = (low[k] - margin, high[k] + margin);
        if !(lo..=hi).contains(&com[k]) {
            return Some(format!(
                "its centre of mass is at {} = {} m, outside the box's [{}, {}] m",
                axes[k],
                short_number(com[k]),
                short_number(low[k]),
                short_number(high[k])
            ));
        }
        let second = half_trace - in_link[(k, k)];
        let bound = mass * (com[k] - lo) * (hi - com[k]);
        if second > 1.01 * bound {
            return Some(format!(
                "its second moment along the link's {} axis is {} kg·m², more than the {} kg·m² any such body with its centre of mass at {} = {} m can have in the box's [{}, {}] m",
                axes[k],
                short_number(second),
                short_number(bound),
                axes[k],
                short_number(com[k]),
                short_number(low[k]),
                short_number(high[k])
            ));
        }
    }
    None
}

/// One finding at most per tensor: the most basic problem wins (zero, then not positive definite, then the
/// triangle inequality), since each implies noise in the next.
fn check_tensor(inertia: &Inertia, owner: &str, moving_with_mass: bool) -> Option<Finding> {
    let [a, b, c] = inertia.principal_moments()?;
    let components = [
        inertia.ixx,
        inertia.ixy,
        inertia.ixz,
        inertia.iyy,
        inertia.iyz,
        inertia.izz,
    ];
    if components.iter().all(|&v| v == 0.0) {
        return moving_with_mass.then(|| {
            Finding::new(
                &rules::ZERO_INERTIA,
                inertia.span,
                format!("{owner} has mass but an all-zero inertia tensor"),
            )
        });
    }
    let scale = c.abs().max(f64::MIN_POSITIVE);
    if a <= scale * 1e-12 {
        return Some(Finding::new(
            &rules::INERTIA_NOT_POSITIVE_DEFINITE,
            inertia.span,
            format!(
                "{owner} has non-positive-definite inertia tensor (min eigenvalue: {}) — physically impossible",
                short_number(a)
            ),
        ));
    }
    let shortfall = c - (a + b);
    (shortfall > TRIANGLE_TOLERANCE * c).then(|| {
        Finding::new(
            &rules::INERTIA_TRIANGLE_INEQUALITY,
            inertia.span,
            format!(
                "{owner}: principal moments violate A + B ≥ C: {a:.6e} + {b:.6e} < {c:.6e} (short by {shortfall:.3e} kg·m², {:.1}% of C)",
                100.0 * shortfall / c
            ),
        )
    })
}

/// Six decimals for ordinary values and exact zero; scientific notation for tiny or huge ones.
fn short_number(value: f64) -> String {
    if value == 0.0 || (1e-4..1e6).contains(&value.abs()) {
        format!("{value:.6}")
    } else {
        format!("{value:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::span::Span;

    fn tensor(ixx: f64, iyy: f64, izz: f64, ixy: f64) -> Inertia {
        Inertia {
            span: Span::default(),
            values: [Span::default(); 6],
            ixx,
            ixy,
            ixz: 0.0,
            iyy,
            iyz: 0.0,
            izz,
        }
    }

    #[test]
    fn principal_moments_of_a_rotated_tensor() {
        let m = tensor(2.0, 2.0, 1.0, 1.0).principal_moments().unwrap();
        assert!(
            (m[0] - 1.0).abs() < 1e-12 && (m[1] - 1.0).abs() < 1e-12 && (m[2] - 3.0).abs() < 1e-12
        );
    }

    #[test]
    fn thin_plate_on_the_boundary_passes() {
        assert!(check_tensor(&tensor(1.0, 2.0, 3.0, 0.0), "L", true).is_none());
    }

    #[test]
    fn triangle_violation_names_the_shortfall() {
        let f = check_tensor(&tensor(1.0, 1.0, 3.0, 0.0), "L", true).unwrap();
        assert_eq!(f.rule.code, "U206");
        assert!(f.message.contains("short by 1.000e0"), "{}", f.message);
    }

    #[test]
    fn singular_tensor_is_not_positive_definite() {
        let f = check_tensor(&tensor(0.002, 0.0, 0.0, 0.0), "L", true).unwrap();
        assert_eq!(f.rule.code, "U205");
    }
}
