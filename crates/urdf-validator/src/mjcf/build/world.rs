//! The world: gravity from `<option>`, its plane geoms as ground planes, whether contacts are off.

use nalgebra::{Isometry3, Vector3};

use super::Builder;
use crate::diagnostics::rules;
use crate::diagnostics::span::Spanned;
use crate::mjcf::xml::{numbers, El};
use crate::urdf::robot::{WorldPlane, STANDARD_GRAVITY};

/// A world plane tilted by more than this (degrees) is a slope the stability analysis does not model.
const PLANE_TILT_DEG: f64 = 0.01;

impl<'a> Builder<'a, '_> {
    /// The model's gravity: the last `<option gravity>`, zero when an `<option><flag gravity="disable">`
    /// says so (MuJoCo then applies none); `None` when the file declares nothing. A U040 when it is not
    /// the standard one.
    pub(super) fn gravity(&mut self, sections: &[El<'a>]) -> Option<Spanned<[f64; 3]>> {
        let mut gravity = None;
        let mut disabled = None;
        for option in sections.iter().filter(|s| s.tag() == "option") {
            if let Some(text) = option.attr("gravity") {
                let span = self.reader.attr_span(*option, "gravity");
                match numbers(text).map(<[f64; 3]>::try_from) {
                    Ok(Ok(value)) if value.iter().all(|v| v.is_finite()) => {
                        gravity = Some(Spanned { value, span });
                    }
                    _ => self.reader.report(
                        &rules::MJCF_INVALID_VALUE,
                        span,
                        "<option gravity>: 3 finite numbers expected".to_string(),
                    ),
                }
            }
            for flag in option.node.children().filter(|n| n.has_tag_name("flag")) {
                let flag = El {
                    file: option.file,
                    node: flag,
                };
                if flag.attr("gravity").map(str::trim) == Some("disable") {
                    disabled = Some(Spanned {
                        value: [0.0; 3],
                        span: self.reader.attr_span(flag, "gravity"),
                    });
                }
            }
        }
        let off = disabled.is_some();
        let gravity = disabled.or(gravity)?;
        let standard = Vector3::from(STANDARD_GRAVITY);
        let [x, y, z] = gravity.value;
        if (Vector3::new(x, y, z) - standard).norm() > 1e-9 {
            let how = if off {
                "disabled (<flag gravity=\"disable\">)".to_string()
            } else {
                format!("({x}, {y}, {z}) m/s² (<option gravity>)")
            };
            self.reader.report(
                &rules::MODEL_GRAVITY,
                gravity.span,
                format!("the model's gravity is {how}, not the standard (0, 0, -9.81): gravity torques, payload and stability follow it, as MuJoCo simulates it"),
            );
        }
        Some(gravity)
    }

    /// The planes of the world among its `geoms`, with a U033 for each that is not horizontal: the
    /// stability analysis stands a floating robot on horizontal ground under its lowest point, which a
    /// horizontal plane's height does not change (the robot settles onto it), but a slope would.
    pub(super) fn world_planes(
        &mut self,
        geoms: &[(El<'a>, String, Isometry3<f64>)],
    ) -> Vec<WorldPlane> {
        let mut planes = Vec::new();
        for (el, class, frame) in geoms {
            if self.value(*el, class, "type").map(|v| v.text.trim()) != Some("plane") {
                continue;
            }
            let at = frame * self.placement(*el, class);
            let normal = at * Vector3::z();
            let tilt = normal.z.clamp(-1.0, 1.0).acos().to_degrees();
            if tilt > PLANE_TILT_DEG {
                let name = el.attr("name").map_or(String::new(), |n| format!(" '{n}'"));
                self.note(
                    *el,
                    format!("world plane{name} is tilted by {tilt:.1}°: the stability analysis assumes horizontal ground and does not use the tilt (--deep's drop test does)"),
                );
            }
            let (contype, conaffinity) = self.contact_masks(*el, class);
            planes.push(WorldPlane {
                name: el.attr("name").map(str::to_string),
                span: self.reader.span(*el),
                point: at.translation.vector.into(),
                normal: normal.into(),
                bits: (contype, conaffinity),
            });
        }
        planes
    }
}

/// Whether an `<option><flag>` among `sections` turns MuJoCo's contacts off (`contact` or `constraint`
/// disabled).
pub(super) fn contacts_disabled(sections: &[El<'_>]) -> bool {
    sections
        .iter()
        .filter(|s| s.tag() == "option")
        .flat_map(|option| option.node.children().filter(|n| n.has_tag_name("flag")))
        .any(|flag| {
            ["contact", "constraint"]
                .iter()
                .any(|name| flag.attribute(*name).map(str::trim) == Some("disable"))
        })
}
