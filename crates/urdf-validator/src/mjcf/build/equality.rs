//! `<equality>` constraints: what MuJoCo holds together besides the body tree.
//!
//! - `joint joint1 joint2 polycoef="a0 a1 a2 a3 a4"`: MuJoCo keeps q1 = a0 + a1·q2 + a2·q2² + ..., q being
//!   `qpos − qpos0` of each joint, which is this reader's q (`qpos − ref`): joint1 mimics joint2 with
//!   multiplier a1 and offset a0. Terms above the linear one are left out (U033).
//! - `joint joint1` without joint2: joint1 is held at q = a0: a fixed joint there.
//! - `connect`, `weld`: a kinematic loop between two bodies (or a body and the world), not analysed
//!   (U038).
//! - `tendon`, `flex`, `flexvert`, `flexstrain`: not read (U033).
//!
//! `active="false"` (written, or from the element's class: MuJoCo's `<default><equality active>`) is off.

use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

use super::{pose, Builder};
use crate::diagnostics::rules;
use crate::diagnostics::span::Spanned;
use crate::mjcf::compiler::boolean;
use crate::mjcf::defaults::MAIN;
use crate::mjcf::xml::El;
use crate::urdf::robot::pose_isometry;
use crate::urdf::robot::{JointKind, Mimic};

impl<'a> Builder<'a, '_> {
    /// Read the `<equality>` sections among `sections` into the joints built.
    pub(super) fn equalities(&mut self, sections: &[El<'a>]) {
        for section in sections.iter().filter(|s| s.tag() == "equality") {
            for el in self.reader.children(*section) {
                let class = self.class_of(el, MAIN);
                let active = el
                    .attr("active")
                    .or_else(|| Some(self.defaults.get(&class, "equality", "active")?.text));
                if active.and_then(boolean) == Some(false) {
                    continue;
                }
                match el.tag() {
                    "joint" => self.joint_equality(el),
                    "connect" | "weld" => self.loop_equality(el),
                    tag @ ("tendon" | "flex" | "flexvert" | "flexstrain") => self.note(
                        el,
                        format!("a <{tag}> equality is not read: the constraint is left out"),
                    ),
                    tag => self.problem(
                        &rules::MJCF_STRUCTURE,
                        el,
                        format!("<{tag}> is not an equality constraint (MuJoCo refuses the model)"),
                    ),
                }
            }
        }
    }

    /// The index of hinge or slide joint `attr` of `el` among the joints built; a U030 when it is not one.
    fn scalar_joint(&mut self, el: El<'a>, attr: &str) -> Option<usize> {
        let name = el.attr(attr)?;
        let found = self
            .joint_facts
            .contains_key(name)
            .then(|| self.joints.iter().position(|j| j.name.value == name));
        if let Some(Some(i)) = found {
            return Some(i);
        }
        let span = self.reader.attr_span(el, attr);
        self.reader.report(
            &rules::MJCF_STRUCTURE,
            span,
            format!("<equality><joint {attr}=\"{name}\">: no hinge or slide joint of that name (MuJoCo refuses the model)"),
        );
        None
    }

    fn joint_equality(&mut self, el: El<'a>) {
        if el.attr("joint1").is_none() {
            self.problem(
                &rules::MJCF_STRUCTURE,
                el,
                "<equality><joint> without joint1 (MuJoCo refuses the model)".to_string(),
            );
            return;
        }
        let Some(follower) = self.scalar_joint(el, "joint1") else {
            return;
        };
        let mut coefficients = self.list(el, MAIN, "polycoef").unwrap_or(vec![0.0, 1.0]);
        coefficients.resize(5, 0.0);
        let (offset, multiplier) = (coefficients[0], coefficients[1]);
        let name = self.joints[follower].name.value.clone();
        if el.attr("joint2").is_none() {
            self.hold(follower, offset);
            return;
        }
        let Some(leader) = self.scalar_joint(el, "joint2") else {
            return;
        };
        let leader_name = self.joints[leader].name.value.clone();
        if self.joints[follower].mimic.is_some() {
            self.note(
                el,
                format!("joint '{name}' is already coupled by an earlier <equality><joint>: this second coupling (to '{leader_name}') is not read"),
            );
            return;
        }
        if coefficients[2..].iter().any(|c| *c != 0.0) {
            let span = self.reader.attr_span(el, "polycoef");
            self.reader.report(
                &rules::MJCF_NOT_READ,
                span,
                format!("joint '{name}' follows '{leader_name}' through a polynomial: analysed with its linear part q = {offset} + {multiplier}·q('{leader_name}'); the terms in q² and above are left out"),
            );
        }
        self.joints[follower].mimic = Some(Mimic {
            span: self.reader.span(el),
            joint: Spanned {
                value: leader_name,
                span: self.reader.attr_span(el, "joint2"),
            },
            multiplier,
            offset,
        });
    }

    /// Joint `index` held at `q`: a fixed joint whose origin is the joint's at q.
    fn hold(&mut self, index: usize, q: f64) {
        let joint = &mut self.joints[index];
        let axis = joint.axis.as_ref().map_or([0.0, 0.0, 1.0], |a| a.value);
        let kind = match joint.kind.as_ref().map(|k| k.value) {
            Some(JointKind::Prismatic) => JointKind::Prismatic,
            _ => JointKind::Revolute,
        };
        // A zero axis (refused, U030) holds the joint where it is.
        let motion = match (kind, Unit::try_new(Vector3::from(axis), 1e-9)) {
            (_, None) => Isometry3::identity(),
            (JointKind::Prismatic, Some(axis)) => {
                Isometry3::from(Translation3::from(axis.into_inner() * q))
            }
            (_, Some(axis)) => Isometry3::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&axis, q),
            ),
        };
        joint.origin = pose(&(pose_isometry(&joint.origin) * motion));
        if let Some(kind) = joint.kind.as_mut() {
            kind.value = JointKind::Fixed;
        }
        joint.limit = None;
    }

    /// A `connect` or `weld`: the loop it closes, reported (U038).
    fn loop_equality(&mut self, el: El<'a>) {
        let end = |n: u8| {
            el.attr(&format!("body{n}"))
                .map(|b| format!("body '{b}'"))
                .or_else(|| el.attr(&format!("site{n}")).map(|s| format!("site '{s}'")))
        };
        let first = end(1).unwrap_or_else(|| "?".to_string());
        let second = end(2).unwrap_or_else(|| "the world".to_string());
        let message = format!(
            "<{}> between {first} and {second} closes a kinematic loop, which is not analysed: statics puts the gravity load on the open tree's joints (the loop's constraint would carry part of it), and the workspace moves the loop's joints independently",
            el.tag()
        );
        self.problem(&rules::MJCF_CLOSED_LOOP, el, message);
    }
}
