//! The inertia fixes: a link's `<inertial>` rewritten, or written, from its geometry
//! ([`crate::analysis::geometry_inertia`]), as Drake's `fix_inertia` writes it: the tensor about the
//! geometry's centroid in the link's axes, the `<origin>` at that centroid with no rotation.

use crate::analysis::geometry_inertia::GeometryInertia;
use crate::diagnostics::fix::{significant, Edit, Fix};
use crate::urdf::robot::{Inertia, Inertial, Link};

/// Significant digits written (Drake's `fix_inertia` writes 5): enough that rounding never breaks
/// A + B ≥ C beyond the checks' tolerance, and the tensor reads back within 1e-6 of the computed one.
const DIGITS: usize = 6;

/// Density of the guessed `<inertial>` of a link without one, kg/m³: water, Gazebo's auto-inertia default.
pub const GUESS_DENSITY: f64 = 1000.0;

/// The six components written for `geometry` at `mass` (ixx, ixy, ixz, iyy, iyz, izz); products below
/// 1e-12 of the largest moment (rounding noise of a symmetric shape) are written as 0.
fn components(geometry: &GeometryInertia, mass: f64) -> [String; 6] {
    let i = geometry.inertia(mass);
    let largest = i[0][0].abs().max(i[1][1].abs()).max(i[2][2].abs());
    let tidy = |v: f64| {
        if v.abs() <= 1e-12 * largest {
            "0".to_string()
        } else {
            significant(v, DIGITS)
        }
    };
    [i[0][0], i[0][1], i[0][2], i[1][1], i[1][2], i[2][2]].map(tidy)
}

fn xyz(geometry: &GeometryInertia) -> String {
    let com = geometry.com();
    let scale = com.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    com.map(|c| {
        if c.abs() <= 1e-12 * scale {
            "0".to_string()
        } else {
            significant(c, DIGITS)
        }
    })
    .join(" ")
}

/// What the geometry is, for a fix's description (`the collision geometry`, with its hull notes).
fn source(geometry: &GeometryInertia) -> String {
    let mut text = format!("the {} geometry", geometry.role.label());
    if !geometry.hulls.is_empty() {
        text.push_str(&format!(
            " ({})",
            geometry.hulls.join("; ").replace(": its", " as its")
        ));
    }
    text
}

/// Replace `inertial`'s tensor (and its `<origin>`) by `geometry`'s at the declared `mass`; `None` when the
/// `<origin>` cannot be rewritten in place (written without `xyz`/`rpy` to anchor an edit on).
pub(super) fn replace_tensor(
    inertial: &Inertial,
    inertia: &Inertia,
    geometry: &GeometryInertia,
    mass: f64,
) -> Option<Fix> {
    let mut edits: Vec<Edit> = inertia
        .values
        .iter()
        .zip(components(geometry, mass))
        .map(|(&value, with)| Edit::ReplaceValue { value, with })
        .collect();
    let xyz = xyz(geometry);
    let origin = &inertial.origin;
    match (origin.span, origin.values.xyz, origin.values.rpy) {
        (None, _, _) => edits.push(Edit::InsertChild {
            element: inertial.span,
            lines: vec![format!("<origin xyz=\"{xyz}\" rpy=\"0 0 0\"/>")],
        }),
        (Some(_), Some(value), _) => edits.push(Edit::ReplaceValue { value, with: xyz }),
        (Some(_), None, Some(rpy)) => edits.push(Edit::InsertAttributeAfter {
            value: rpy,
            name: "xyz".into(),
            text: xyz,
        }),
        (Some(_), None, None) => return None,
    }
    if let Some(value) = origin.values.rpy {
        edits.push(Edit::ReplaceValue {
            value,
            with: "0 0 0".into(),
        });
    }
    if let Some(value) = origin.values.quat_xyzw {
        edits.push(Edit::ReplaceValue {
            value,
            with: "0 0 0 1".into(),
        });
    }
    Some(Fix::unsafe_(
        format!(
            "replace the inertia by that of {} filled uniformly at the declared mass {} kg, about its centroid (xyz=\"{}\", rpy 0, as Drake's fix_inertia writes it)",
            source(geometry),
            significant(mass, DIGITS),
            self::xyz(geometry)
        ),
        edits,
    ))
}

/// Insert an `<inertial>` into `link` guessed from `geometry` at [`GUESS_DENSITY`].
pub(super) fn insert_inertial(link: &Link, geometry: &GeometryInertia) -> Fix {
    let mass = GUESS_DENSITY * geometry.volume();
    let [ixx, ixy, ixz, iyy, iyz, izz] = components(geometry, mass);
    let mass_text = significant(mass, DIGITS);
    Fix::unsafe_(
        format!(
            "insert an <inertial> guessed from {} at {GUESS_DENSITY} kg/m³ (water, Gazebo's auto-inertia default): mass {mass_text} kg — guessed, replace it by the real mass",
            source(geometry)
        ),
        vec![Edit::InsertChild {
            element: link.span,
            lines: vec![
                "<inertial>".into(),
                format!("  <origin xyz=\"{}\" rpy=\"0 0 0\"/>", xyz(geometry)),
                format!("  <mass value=\"{mass_text}\"/>"),
                format!(
                    "  <inertia ixx=\"{ixx}\" ixy=\"{ixy}\" ixz=\"{ixz}\" iyy=\"{iyy}\" iyz=\"{iyz}\" izz=\"{izz}\"/>"
                ),
                "</inertial>".into(),
            ],
        }],
    )
}
