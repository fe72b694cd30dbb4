//! `<compiler>`: the settings that change how the model's numbers are read (angle unit, Euler sequence,
//! where meshes are, joint limits, where mass comes from), with MuJoCo's defaults.

use super::xml::{numbers, El, Reader};
use crate::diagnostics::rules;

/// Where a body's mass and inertia come from (`inertiafromgeom`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InertiaFromGeom {
    /// From `<inertial>` only (a body without one is massless).
    False,
    /// From the geoms always, `<inertial>` ignored.
    True,
    /// From `<inertial>` when the body has one, else from its geoms (MuJoCo's default).
    Auto,
}

/// The compiler settings of a model.
#[derive(Clone, Debug)]
pub struct Compiler {
    /// Angles (`euler`, `axisangle`, hinge `range` and `ref`) are in degrees (MuJoCo's default).
    pub degrees: bool,
    /// `eulerseq`: three of `xyzXYZ`; lower case rotates about the moving axes, upper case the fixed.
    pub euler_seq: [u8; 3],
    /// `meshdir`, else `assetdir`: the folder mesh files are in, relative to the model file.
    pub mesh_dir: Option<String>,
    /// `autolimits`: a joint with a `range` is limited unless `limited="false"` (default true).
    pub auto_limits: bool,
    /// `inertiafromgeom`.
    pub inertia_from_geom: InertiaFromGeom,
    /// `boundmass`: the least mass of a body that is not the world.
    pub bound_mass: f64,
    /// `boundinertia`: the least principal moment of such a body.
    pub bound_inertia: f64,
    /// `balanceinertia`: principal moments that break the triangle inequality become their mean.
    pub balance_inertia: bool,
    /// `settotalmass`: when positive, every mass and inertia is scaled so the total is this.
    pub set_total_mass: Option<f64>,
    /// `inertiagrouprange`: the geom groups whose geoms count for mass and inertia.
    pub inertia_groups: (i64, i64),
    /// `fitaabb`: a primitive geom fitted to a mesh (`type="capsule" mesh=…`) encloses the mesh's
    /// bounding box in its principal frame, instead of matching its equivalent inertia box.
    pub fit_aabb: bool,
}

impl Default for Compiler {
    fn default() -> Self {
        Compiler {
            degrees: true,
            euler_seq: *b"xyz",
            mesh_dir: None,
            auto_limits: true,
            inertia_from_geom: InertiaFromGeom::Auto,
            bound_mass: 0.0,
            bound_inertia: 0.0,
            balance_inertia: false,
            set_total_mass: None,
            inertia_groups: (0, 5),
            fit_aabb: false,
        }
    }
}

impl Compiler {
    /// The settings of every `<compiler>` among `sections`, later ones overriding earlier ones.
    pub fn read(reader: &mut Reader<'_>, sections: &[El<'_>]) -> Self {
        let mut compiler = Compiler::default();
        let mut asset_dir = None;
        for el in sections.iter().filter(|el| el.tag() == "compiler") {
            for attribute in el.node.attributes() {
                let text = attribute.value().trim();
                let name = attribute.name();
                let ok = match name {
                    "angle" => keyword(text, &["degree", "radian"]).map(|i| {
                        compiler.degrees = i == 0;
                    }),
                    "eulerseq" => {
                        let bytes = text.as_bytes();
                        match <[u8; 3]>::try_from(bytes) {
                            Ok(seq) if seq.iter().all(|c| b"xyzXYZ".contains(c)) => {
                                compiler.euler_seq = seq;
                                Some(())
                            }
                            _ => None,
                        }
                    }
                    "meshdir" => {
                        compiler.mesh_dir = Some(text.to_string());
                        Some(())
                    }
                    "assetdir" => {
                        asset_dir = Some(text.to_string());
                        Some(())
                    }
                    "autolimits" => boolean(text).map(|b| compiler.auto_limits = b),
                    "inertiafromgeom" => keyword(text, &["false", "true", "auto"]).map(|i| {
                        compiler.inertia_from_geom = [
                            InertiaFromGeom::False,
                            InertiaFromGeom::True,
                            InertiaFromGeom::Auto,
                        ][i];
                    }),
                    "boundmass" => scalar(text).map(|v| compiler.bound_mass = v),
                    "boundinertia" => scalar(text).map(|v| compiler.bound_inertia = v),
                    "balanceinertia" => boolean(text).map(|b| compiler.balance_inertia = b),
                    "fitaabb" => boolean(text).map(|b| compiler.fit_aabb = b),
                    "settotalmass" => scalar(text).map(|v| {
                        compiler.set_total_mass = (v > 0.0).then_some(v);
                    }),
                    "inertiagrouprange" => match numbers(text).as_deref() {
                        Ok([lo, hi]) if lo.fract() == 0.0 && hi.fract() == 0.0 => {
                            compiler.inertia_groups = (*lo as i64, *hi as i64);
                            Some(())
                        }
                        _ => None,
                    },
                    _ => Some(()),
                };
                if ok.is_none() {
                    let span = reader.attr_span(*el, name);
                    reader.report(
                        &rules::MJCF_INVALID_VALUE,
                        span,
                        format!("<compiler {name}=\"{text}\">: not a value MuJoCo accepts"),
                    );
                }
            }
        }
        if compiler.mesh_dir.is_none() {
            compiler.mesh_dir = asset_dir;
        }
        compiler
    }

    /// `value` (in the compiler's angle unit) in radians.
    pub fn radians(&self, value: f64) -> f64 {
        if self.degrees {
            value.to_radians()
        } else {
            value
        }
    }
}

/// The index of `text` among `words`.
pub fn keyword(text: &str, words: &[&str]) -> Option<usize> {
    words.iter().position(|w| *w == text)
}

/// An MJCF boolean.
pub fn boolean(text: &str) -> Option<bool> {
    match text.trim() {
        "true" => Some(true),
        "false" => Some(false),
        _ => None,
    }
}

fn scalar(text: &str) -> Option<f64> {
    match numbers(text).as_deref() {
        Ok([v]) => Some(*v),
        _ => None,
    }
}
