//! Mass and inertia plausibility: missing inertials on moving links, signs, positive definiteness and the
//! triangle inequality on the principal moments.

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::model::{LinkId, Model};
use crate::urdf::robot::{Inertia, Robot};

/// Relative slack on `A + B ≥ C`: values printed with ~6 significant digits round by ~1e-6, and thin plates
/// sit exactly on the boundary.
const TRIANGLE_TOLERANCE: f64 = 1e-4;

pub(super) fn check(robot: &Robot, model: &Model) -> Vec<Finding> {
    let mut findings = Vec::new();
    for (i, link) in robot.links.iter().enumerate() {
        let owner = format!("Link '{}'", link.name.value);
        let moving = model.is_moving(robot, LinkId(i));
        let Some(inertial) = &link.inertial else {
            if moving {
                findings.push(Finding::new(
                    &rules::MISSING_INERTIAL,
                    link.span,
                    format!("{owner} has no inertial block (mass unknown) — will cause physics engine instability"),
                ));
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
        let Some(inertia) = inertial.inertia.as_ref() else {
            continue;
        };
        let massive = mass.is_none_or(|m| m.value > 0.0);
        if let Some(finding) = check_tensor(inertia, &owner, moving && massive) {
            findings.push(finding);
        }
    }
    findings
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
    use crate::input::source::Span;

    fn tensor(ixx: f64, iyy: f64, izz: f64, ixy: f64) -> Inertia {
        Inertia {
            span: Span::default(),
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
