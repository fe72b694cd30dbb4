//! The up axis of a model's root frame. REP 103 says z; a file modelled with another axis up (PyBullet's
//! laikago: y) is analysed with gravity along minus that axis when the user declares it (`--up-axis y`):
//! the root link is turned so that axis points up, which rotates gravity for every analysis at once.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// A signed axis of the root link frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
pub enum UpAxis {
    /// +x.
    #[serde(rename = "+x")]
    PosX,
    /// −x.
    #[serde(rename = "-x")]
    NegX,
    /// +y.
    #[serde(rename = "+y")]
    PosY,
    /// −y.
    #[serde(rename = "-y")]
    NegY,
    /// +z (REP 103).
    #[default]
    #[serde(rename = "+z")]
    PosZ,
    /// −z.
    #[serde(rename = "-z")]
    NegZ,
}

impl UpAxis {
    /// Every axis, +z first.
    pub const ALL: [UpAxis; 6] = [
        UpAxis::PosZ,
        UpAxis::PosY,
        UpAxis::NegY,
        UpAxis::PosX,
        UpAxis::NegX,
        UpAxis::NegZ,
    ];

    /// `x`, `+y`, `-z`, ... (a bare letter is the positive axis); `None` for anything else.
    pub fn parse(text: &str) -> Option<UpAxis> {
        let text = text.trim().to_ascii_lowercase();
        let (negative, letter) = match text.strip_prefix('-') {
            Some(rest) => (true, rest),
            None => (false, text.strip_prefix('+').unwrap_or(&text)),
        };
        let axis = match (letter, negative) {
            ("x", false) => UpAxis::PosX,
            ("x", true) => UpAxis::NegX,
            ("y", false) => UpAxis::PosY,
            ("y", true) => UpAxis::NegY,
            ("z", false) => UpAxis::PosZ,
            ("z", true) => UpAxis::NegZ,
            _ => return None,
        };
        Some(axis)
    }

    /// `+y`, as the CLI takes it.
    pub fn as_str(self) -> &'static str {
        match self {
            UpAxis::PosX => "+x",
            UpAxis::NegX => "-x",
            UpAxis::PosY => "+y",
            UpAxis::NegY => "-y",
            UpAxis::PosZ => "+z",
            UpAxis::NegZ => "-z",
        }
    }

    /// The axis as a unit vector of the root frame.
    pub fn vector(self) -> Vector3<f64> {
        match self {
            UpAxis::PosX => Vector3::x(),
            UpAxis::NegX => -Vector3::x(),
            UpAxis::PosY => Vector3::y(),
            UpAxis::NegY => -Vector3::y(),
            UpAxis::PosZ => Vector3::z(),
            UpAxis::NegZ => -Vector3::z(),
        }
    }

    /// The rotation taking this axis to +z: the root link's placement in the world (a quarter turn about x
    /// for ±y, about y for ±x, a half turn about x for −z).
    pub fn rotation(self) -> UnitQuaternion<f64> {
        let quarter = std::f64::consts::FRAC_PI_2;
        match self {
            UpAxis::PosZ => UnitQuaternion::identity(),
            UpAxis::NegZ => UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 2.0 * quarter),
            UpAxis::PosY => UnitQuaternion::from_axis_angle(&Vector3::x_axis(), quarter),
            UpAxis::NegY => UnitQuaternion::from_axis_angle(&Vector3::x_axis(), -quarter),
            UpAxis::PosX => UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -quarter),
            UpAxis::NegX => UnitQuaternion::from_axis_angle(&Vector3::y_axis(), quarter),
        }
    }

    /// The root link's placement in the world.
    pub fn root_placement(self) -> Isometry3<f64> {
        Isometry3::from_parts(Translation3::identity(), self.rotation())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_axis_turns_up_and_parses_back() {
        for axis in UpAxis::ALL {
            let up = axis.rotation() * axis.vector();
            assert!((up - Vector3::z()).norm() < 1e-12, "{axis:?}: {up}");
            assert_eq!(UpAxis::parse(axis.as_str()), Some(axis));
        }
        assert_eq!(UpAxis::parse("Y"), Some(UpAxis::PosY));
        assert_eq!(UpAxis::parse("w"), None);
        assert_eq!(UpAxis::parse("--y"), None);
    }
}
