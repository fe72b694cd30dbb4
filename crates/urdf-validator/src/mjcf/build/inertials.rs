//! Body masses: `<inertial>` read, the links' inertials set, and the moving bodies MuJoCo refuses.

use std::collections::HashSet;

use nalgebra::Vector3;

use super::{contacts, Builder};
use crate::diagnostics::rules;
use crate::diagnostics::span::{Span, Spanned};
use crate::mjcf::defaults::MAIN;
use crate::mjcf::mass::{self, MassProps};
use crate::mjcf::xml::El;
use crate::urdf::robot::{Inertia, Inertial, Pose};

impl<'a> Builder<'a, '_> {
    /// The mass properties of an `<inertial>`, in the body frame.
    pub(super) fn inertial(&mut self, el: El<'a>) -> MassProps {
        let mass = self.scalar(el, MAIN, "mass", 0.0);
        let placement = self.placement(el, MAIN);
        let diagonal = self.list(el, MAIN, "diaginertia");
        let full = self.list(el, MAIN, "fullinertia");
        let inertia = match (diagonal.as_deref(), full.as_deref()) {
            (Some([a, b, c]), None) => nalgebra::Matrix3::from_diagonal(&Vector3::new(*a, *b, *c)),
            (None, Some([xx, yy, zz, xy, xz, yz])) => {
                nalgebra::Matrix3::new(*xx, *xy, *xz, *xy, *yy, *yz, *xz, *yz, *zz)
            }
            // Neither: MuJoCo 4.0 takes a zero tensor (a moving body is then refused for mjMINVAL, which
            // refuse_massless_moving_bodies says; a welded one is accepted).
            (None, None) => nalgebra::Matrix3::zeros(),
            _ => {
                self.problem(
                    &rules::MJCF_STRUCTURE,
                    el,
                    "<inertial> takes diaginertia (3 numbers) or fullinertia (6), not both and no other count (MuJoCo refuses it)".to_string(),
                );
                nalgebra::Matrix3::zeros()
            }
        };
        MassProps {
            mass,
            com: Vector3::zeros(),
            inertia,
        }
        .placed(&placement)
    }

    /// `boundmass`, `boundinertia`, `balanceinertia` and `settotalmass` applied to every body's mass.
    /// A body whose inertia only a compiler setting makes acceptable is a U037.
    pub(super) fn finish_masses(&mut self) {
        let c = &self.compiler;
        let bounded: Vec<(usize, MassProps)> = self
            .masses
            .iter()
            .map(|(i, p)| {
                (
                    *i,
                    p.bounded(c.bound_mass, c.bound_inertia, c.balance_inertia),
                )
            })
            .collect();
        let rescued: Vec<(usize, &'static str)> = self
            .masses
            .iter()
            .filter_map(|(i, p)| Some((*i, p.rescued_by(c.bound_inertia, c.balance_inertia)?)))
            .collect();
        for (i, setting) in rescued {
            if let Some(link) = self.links.get(i) {
                let span = link.inertial.as_ref().map_or(link.span, |m| m.span);
                let message = format!(
                    "body '{}': MuJoCo accepts its inertia only thanks to <compiler {setting}>; the inertia simulated is the compiler's, not the one written",
                    link.name.value
                );
                self.reader
                    .report(&rules::MJCF_INERTIA_RESCUED, span, message);
            }
        }
        let total: f64 = bounded.iter().map(|(_, p)| p.mass).sum();
        let factor = match c.set_total_mass {
            Some(target) if total > 0.0 => target / total,
            _ => 1.0,
        };
        for (i, props) in bounded {
            let props = props.scaled(factor);
            if let Some(link) = self.links.get_mut(i) {
                let span = link.inertial.as_ref().map_or(link.span, |m| m.span);
                let mut inertial = inertial_of(&props, span);
                // A mesh not read leaves the tensor unknown (not zero): the mass and centre of mass stand.
                if self.unread_geoms.contains(&link.name.value) {
                    inertial.inertia = None;
                }
                link.inertial = Some(inertial);
            }
        }
    }

    /// U030 for each moving body MuJoCo refuses ("mass and inertia of moving bodies must be larger than
    /// mjMINVAL"): one none of whose weld group (itself and the bodies welded to it) has, on its own, a
    /// mass and all three principal moments of inertia of at least `mjMINVAL`. Not the group's combined
    /// mass or inertia: MuJoCo 4.0 refuses a body of 1 kg with moments (1, 10⁻²⁰, 1) welded to one with
    /// (1, 1, 10⁻²⁰), and three welded point masses (checked in tests/mjcf_mjminval.rs).
    pub(super) fn refuse_massless_moving_bodies(&mut self) {
        let enough = |link: &str| {
            self.links
                .iter()
                .find(|l| l.name.value == link)
                .and_then(|l| l.inertial.as_ref())
                .is_some_and(|inertial| {
                    let mass = inertial.mass.as_ref().map_or(0.0, |m| m.value);
                    let least = inertial
                        .inertia
                        .as_ref()
                        .and_then(|i| i.principal_moments())
                        .map_or(0.0, |[a, _, _]| a);
                    mass >= mass::MIN_VALUE && least >= mass::MIN_VALUE
                })
        };
        let by_link = contacts::by_link(&self.body_contacts);
        let mut accepted: HashSet<String> = HashSet::new();
        for body in &self.body_contacts {
            if enough(&body.link) || self.unread_geoms.contains(&body.link) {
                accepted.insert(contacts::weld_root(&by_link, &body.link));
            }
        }
        let refused: Vec<(Span, String)> = self
            .body_contacts
            .iter()
            .filter(|b| b.moving && !accepted.contains(&b.link))
            .filter_map(|b| {
                let link = self.links.iter().find(|l| l.name.value == b.link)?;
                Some((
                    link.span,
                    format!(
                        "body '{}' moves (it has a joint) but neither it nor a body welded to it has a mass and three principal moments of inertia of at least 1e-15 (mjMINVAL): MuJoCo refuses the model (\"mass and inertia of moving bodies must be larger than mjMINVAL\")",
                        b.link
                    ),
                ))
            })
            .collect();
        for (span, message) in refused {
            self.reader.report(&rules::MJCF_STRUCTURE, span, message);
        }
    }
}

/// Mass properties (in the link frame) as a URDF inertial at their centre, axes of the link.
pub(super) fn inertial_of(props: &MassProps, span: Span) -> Inertial {
    let m = props.inertia;
    Inertial {
        span,
        origin: Pose {
            xyz: props.com.into(),
            ..Pose::default()
        },
        mass: Some(Spanned {
            value: props.mass,
            span,
        }),
        inertia: Some(Inertia {
            span,
            ixx: m[(0, 0)],
            ixy: m[(0, 1)],
            ixz: m[(0, 2)],
            iyy: m[(1, 1)],
            iyz: m[(1, 2)],
            izz: m[(2, 2)],
            values: [span; 6],
        }),
    }
}
