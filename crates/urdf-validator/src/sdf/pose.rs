//! `<pose>` text and the values SDFormat writes as text (vectors, numbers, booleans), and rigid
//! transforms turned back into URDF [`Pose`]s.

use nalgebra::{Isometry3, Translation3, UnitQuaternion};

use crate::diagnostics::span::Span;
use crate::urdf::robot::Pose;

/// A rigid transform.
pub type Transform = Isometry3<f64>;

/// Why a value could not be read (the caller adds the rule and the span).
pub type ValueError = String;

/// `n` whitespace-separated finite numbers.
pub fn numbers(text: &str, n: usize, what: &str) -> Result<Vec<f64>, ValueError> {
    let values: Vec<f64> = text
        .split_ascii_whitespace()
        .map(|t| {
            t.parse::<f64>()
                .map_err(|_| format!("{what}: '{t}' is not a number"))
        })
        .collect::<Result<_, _>>()?;
    if values.len() != n {
        return Err(format!(
            "{what}: expected {n} numbers, found {} in '{}'",
            values.len(),
            text.trim()
        ));
    }
    if values.iter().any(|v| !v.is_finite()) {
        return Err(format!(
            "{what}: '{}' holds NaN or an infinite value",
            text.trim()
        ));
    }
    Ok(values)
}

/// One finite number.
pub fn number(text: &str, what: &str) -> Result<f64, ValueError> {
    Ok(numbers(text, 1, what)?.first().copied().unwrap_or(0.0))
}

/// Three finite numbers.
pub fn vector3(text: &str, what: &str) -> Result<[f64; 3], ValueError> {
    let v = numbers(text, 3, what)?;
    Ok([v[0], v[1], v[2]])
}

/// An SDFormat boolean: `true`/`false`/`1`/`0`.
pub fn boolean(text: &str, what: &str) -> Result<bool, ValueError> {
    match text.trim() {
        "true" | "1" => Ok(true),
        "false" | "0" => Ok(false),
        other => Err(format!(
            "{what}: '{other}' is not a boolean (true, false, 1 or 0)"
        )),
    }
}

/// The transform a `<pose>` element's text writes: `x y z roll pitch yaw` (radians, or degrees with
/// `degrees="true"`), or `x y z qx qy qz qw` with `rotation_format="quat_xyzw"` (SDFormat 1.9). Empty text
/// is the identity, as sdformat reads it.
pub fn pose_text(
    text: &str,
    rotation_format: Option<&str>,
    degrees: Option<&str>,
) -> Result<Transform, ValueError> {
    if text.trim().is_empty() {
        return Ok(Transform::identity());
    }
    let degrees = degrees
        .map(|d| boolean(d, "<pose degrees>"))
        .transpose()?
        .unwrap_or(false);
    match rotation_format.map(str::trim).unwrap_or("euler_rpy") {
        "euler_rpy" => {
            let v = numbers(text, 6, "<pose>")?;
            let scale = if degrees {
                std::f64::consts::PI / 180.0
            } else {
                1.0
            };
            Ok(Transform::from_parts(
                Translation3::new(v[0], v[1], v[2]),
                UnitQuaternion::from_euler_angles(v[3] * scale, v[4] * scale, v[5] * scale),
            ))
        }
        "quat_xyzw" => {
            let v = numbers(text, 7, "<pose rotation_format=\"quat_xyzw\">")?;
            let q = nalgebra::Quaternion::new(v[6], v[3], v[4], v[5]);
            if q.norm() < 1e-12 {
                return Err("<pose>: the quaternion is zero".to_string());
            }
            Ok(Transform::from_parts(
                Translation3::new(v[0], v[1], v[2]),
                UnitQuaternion::new_normalize(q),
            ))
        }
        other => Err(format!(
            "<pose rotation_format=\"{other}\">: expected euler_rpy or quat_xyzw"
        )),
    }
}

/// A URDF [`Pose`] holding `transform` exactly (as `xyz` + `quat_xyzw`), pointing at `span`.
pub fn to_pose(transform: &Transform, span: Option<Span>) -> Pose {
    let t = transform.translation.vector;
    let q = transform.rotation.into_inner();
    Pose {
        xyz: [t.x, t.y, t.z],
        rpy: [0.0; 3],
        quat_xyzw: Some([q.i, q.j, q.k, q.w]),
        span,
        values: Default::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn euler_pose_is_fixed_axis_rpy_and_degrees_scale_it() {
        let a = pose_text("1 2 3 0 0 1.5707963267948966", None, None).unwrap();
        let b = pose_text("1 2 3 0 0 90", None, Some("true")).unwrap();
        assert!((a.rotation.angle() - b.rotation.angle()).abs() < 1e-12);
        let x = a.rotation * nalgebra::Vector3::x();
        assert!((x - nalgebra::Vector3::y()).norm() < 1e-12);
        assert_eq!(a.translation.vector, nalgebra::Vector3::new(1.0, 2.0, 3.0));
    }

    #[test]
    fn quaternion_pose_and_errors() {
        let q = pose_text(
            "0 0 0 0 0 0.7071067811865476 0.7071067811865476",
            Some("quat_xyzw"),
            None,
        )
        .unwrap();
        assert!((q.rotation.angle() - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!(pose_text("1 2 3", None, None).is_err());
        assert!(pose_text("1 2 3 0 0 nan", None, None).is_err());
        assert!(pose_text("0 0 0 0 0 0 0", Some("quat_xyzw"), None).is_err());
        assert!(pose_text(" ", None, None).unwrap() == Transform::identity());
    }
}
