//! MJCF's five ways of writing an orientation, turned into a rotation as MuJoCo's compiler does
//! (`mjs_resolveOrientation`): `quat` (w x y z, normalised), `axisangle` (angle in the compiler's unit),
//! `euler` (three angles about the axes of `eulerseq`), `xyaxes` (the frame's x and y axes, y made
//! orthogonal to x) and `zaxis` (the smallest rotation taking z to it).

use nalgebra::{Matrix3, Quaternion, Rotation3, Unit, UnitQuaternion, Vector3};

use super::compiler::Compiler;

/// The orientation attributes, in the order MuJoCo documents them.
pub const FORMS: [&str; 5] = ["quat", "axisangle", "euler", "xyaxes", "zaxis"];

/// Below this norm a vector has no direction.
const TINY: f64 = 1e-14;

/// The rotation written as `values` of attribute `form` (one of [`FORMS`]); an error says why the
/// numbers are not one.
pub fn rotation(
    form: &str,
    values: &[f64],
    compiler: &Compiler,
) -> Result<UnitQuaternion<f64>, String> {
    let count = |n: usize| {
        if values.len() == n {
            Ok(())
        } else {
            Err(format!("{form} takes {n} numbers, not {}", values.len()))
        }
    };
    match form {
        "quat" => {
            count(4)?;
            let q = Quaternion::new(values[0], values[1], values[2], values[3]);
            if q.norm() < TINY {
                return Err("quat is zero".to_string());
            }
            Ok(UnitQuaternion::from_quaternion(q))
        }
        "axisangle" => {
            count(4)?;
            let axis = direction(Vector3::new(values[0], values[1], values[2]), form)?;
            Ok(UnitQuaternion::from_axis_angle(
                &axis,
                compiler.radians(values[3]),
            ))
        }
        "euler" => {
            count(3)?;
            let mut q = UnitQuaternion::identity();
            for (axis, angle) in compiler.euler_seq.iter().zip(values) {
                let unit = match axis.to_ascii_lowercase() {
                    b'x' => Vector3::x_axis(),
                    b'y' => Vector3::y_axis(),
                    _ => Vector3::z_axis(),
                };
                let r = UnitQuaternion::from_axis_angle(&unit, compiler.radians(*angle));
                q = if axis.is_ascii_lowercase() {
                    q * r
                } else {
                    r * q
                };
            }
            Ok(q)
        }
        "xyaxes" => {
            count(6)?;
            let x = direction(Vector3::new(values[0], values[1], values[2]), form)?;
            let y = Vector3::new(values[3], values[4], values[5]);
            let y = direction(y - x.into_inner() * x.dot(&y), "xyaxes' y axis")?;
            let z = x.cross(&y);
            let m = Matrix3::from_columns(&[x.into_inner(), y.into_inner(), z]);
            Ok(UnitQuaternion::from_rotation_matrix(
                &Rotation3::from_matrix_unchecked(m),
            ))
        }
        "zaxis" => {
            count(3)?;
            let z = direction(Vector3::new(values[0], values[1], values[2]), form)?;
            Ok(z_to(z.into_inner()))
        }
        _ => Err(format!("{form} is not an orientation")),
    }
}

/// The smallest rotation taking +z to unit vector `v` (MuJoCo's `mjuu_z2quat`: a half turn about x when
/// `v` is −z).
pub fn z_to(v: Vector3<f64>) -> UnitQuaternion<f64> {
    let z = Vector3::z();
    let axis = z.cross(&v);
    let sine = axis.norm();
    if sine < TINY {
        return if v.z < 0.0 {
            UnitQuaternion::from_quaternion(Quaternion::new(0.0, 1.0, 0.0, 0.0))
        } else {
            UnitQuaternion::identity()
        };
    }
    let angle = sine.atan2(z.dot(&v));
    UnitQuaternion::from_axis_angle(&Unit::new_unchecked(axis / sine), angle)
}

fn direction(v: Vector3<f64>, what: &str) -> Result<Unit<Vector3<f64>>, String> {
    Unit::try_new(v, TINY).ok_or_else(|| format!("{what} has no direction (zero vector)"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn radians() -> Compiler {
        Compiler {
            degrees: false,
            ..Compiler::default()
        }
    }

    fn close(a: UnitQuaternion<f64>, b: UnitQuaternion<f64>) -> bool {
        a.angle_to(&b) < 1e-12
    }

    #[test]
    fn every_form_writes_the_same_quarter_turn_about_z() {
        let want = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let c = radians();
        assert!(close(
            rotation("quat", &[h, 0.0, 0.0, h], &c).unwrap(),
            want
        ));
        assert!(close(
            rotation("axisangle", &[0.0, 0.0, 2.0, 90.0], &Compiler::default()).unwrap(),
            want
        ));
        assert!(close(
            rotation("euler", &[0.0, 0.0, 90.0], &Compiler::default()).unwrap(),
            want
        ));
        assert!(close(
            rotation("xyaxes", &[0.0, 1.0, 0.0, -1.0, 0.5, 0.0], &c).unwrap(),
            want
        ));
    }

    #[test]
    fn intrinsic_and_extrinsic_euler_sequences_differ_as_mujoco_composes_them() {
        let intrinsic = rotation("euler", &[0.3, 0.5, 0.0], &radians()).unwrap();
        let x = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.3);
        let y = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 0.5);
        assert!(close(intrinsic, x * y));
        let extrinsic = Compiler {
            euler_seq: *b"XYZ",
            ..radians()
        };
        assert!(close(
            rotation("euler", &[0.3, 0.5, 0.0], &extrinsic).unwrap(),
            y * x
        ));
    }

    #[test]
    fn zaxis_is_the_smallest_rotation_and_minus_z_is_a_half_turn_about_x() {
        let q = rotation("zaxis", &[1.0, 0.0, 0.0], &radians()).unwrap();
        assert!((q * Vector3::z() - Vector3::x()).norm() < 1e-12);
        assert!((q * Vector3::y() - Vector3::y()).norm() < 1e-12);
        let flip = z_to(-Vector3::z());
        assert!((flip * Vector3::x() - Vector3::x()).norm() < 1e-12);
    }

    #[test]
    fn wrong_counts_and_zero_vectors_are_errors() {
        assert!(rotation("quat", &[1.0, 0.0, 0.0], &radians()).is_err());
        assert!(rotation("quat", &[0.0; 4], &radians()).is_err());
        assert!(rotation("zaxis", &[0.0; 3], &radians()).is_err());
        assert!(rotation("xyaxes", &[1.0, 0.0, 0.0, 2.0, 0.0, 0.0], &radians()).is_err());
    }
}
