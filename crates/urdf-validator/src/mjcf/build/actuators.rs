//! `<actuator>`s as joint effort limits: what a joint's actuators can apply to hold it still.
//!
//! Per actuator on a joint (`joint` or `jointinparent`), the force it can produce at rest: a `motor`, or a
//! `general` without a position bias, |gain| · max |ctrl| over `ctrlrange`; a `position` servo (or a
//! `general` whose affine bias has a position term) |kp| · (ctrl range width), the most it pushes anywhere
//! in that range; a `velocity` servo at rest |kv| · max |ctrl|. `forcerange` clamps it when force-limited;
//! times |`gear`|. A joint's effort is the sum over its actuators, clamped by its `actuatorfrcrange`. An
//! actuator with neither range is unbounded, and so is its joint's effort unless `actuatorfrcrange`
//! bounds it; a joint without actuator is passive, its effort undeclared too (statics: UNKNOWN). The effort's span is the attribute that bounds it (`forcerange`,
//! `ctrlrange` or `actuatorfrcrange`): where U701/U702 point.

use std::collections::HashMap;

use super::{Builder, MAIN};
use crate::input::source::{Span, Spanned};
use crate::mjcf::xml::El;

/// The actuator elements read; the others are U033.
const READ: [&str; 4] = ["motor", "position", "velocity", "general"];

impl<'a> Builder<'a, '_> {
    /// Set each hinge and slide joint's effort from the `<actuator>` sections among `sections`.
    pub(super) fn set_efforts(&mut self, sections: &[El<'a>]) {
        // Per joint: the sum of its actuators' efforts, `None` once one of them is unbounded.
        let mut efforts: HashMap<String, Option<Spanned<f64>>> = HashMap::new();
        for section in sections.iter().filter(|s| s.tag() == "actuator") {
            for el in self.reader.children(*section) {
                let Some((joint, effort)) = self.actuator(el) else {
                    continue;
                };
                let sum = match efforts.remove(&joint) {
                    None => effort,
                    Some(Some(s)) => effort.map(|e| Spanned {
                        value: s.value + e.value,
                        span: s.span,
                    }),
                    Some(None) => None,
                };
                efforts.insert(joint, sum);
            }
        }
        for joint in &mut self.joints {
            let Some(limit) = joint.limit.as_mut() else {
                continue;
            };
            let name = joint.name.value.as_str();
            let clamp = self
                .actuator_force
                .get(name)
                .map(|((lo, hi), span)| (lo.abs().max(hi.abs()), *span));
            limit.effort = match (efforts.remove(name), clamp) {
                // Passive: no actuator, no effort.
                (None, _) => None,
                (Some(Some(sum)), Some((most, _))) if sum.value <= most => Some(sum),
                (Some(_), Some((most, span))) => Some(Spanned { value: most, span }),
                (Some(sum), None) => sum,
            };
        }
    }

    /// The joint an actuator drives and the effort it can apply there (`None`: unbounded); `None` (with a
    /// U033) when it drives no joint or is of a kind not read.
    fn actuator(&mut self, el: El<'a>) -> Option<(String, Option<Spanned<f64>>)> {
        let tag = el.tag();
        let name = el.attr("name").unwrap_or("(unnamed)");
        if !READ.contains(&tag) {
            self.note(
                el,
                format!("<{tag}> actuator '{name}' is not read: its joint gets no effort from it"),
            );
            return None;
        }
        let class = self.class_of(el, MAIN);
        let Some(joint) = el.attr("joint").or_else(|| el.attr("jointinparent")) else {
            self.note(
                el,
                format!("actuator '{name}' drives a tendon, site or body: not read (no joint effort from it)"),
            );
            return None;
        };
        let gear = self
            .list(el, &class, "gear")
            .and_then(|g| g.first().copied())
            .unwrap_or(1.0);
        let ctrl = self.range(el, &class, "ctrl");
        let force = self.range(el, &class, "force");
        let (gain, position_like) = match tag {
            "motor" => (1.0, false),
            "position" => (self.scalar(el, &class, "kp", 1.0), true),
            "velocity" => (self.scalar(el, &class, "kv", 1.0), false),
            _ => {
                let gain = self
                    .list(el, &class, "gainprm")
                    .and_then(|g| g.first().copied())
                    .unwrap_or(1.0);
                let affine = self
                    .value(el, &class, "biastype")
                    .is_some_and(|v| v.text.trim() == "affine");
                let position_term = self
                    .list(el, &class, "biasprm")
                    .and_then(|b| b.get(1).copied())
                    .is_some_and(|b| b != 0.0);
                (gain, affine && position_term)
            }
        };
        let from_ctrl = ctrl.map(|((lo, hi), span)| {
            let reach = if position_like {
                hi - lo
            } else {
                lo.abs().max(hi.abs())
            };
            (gain.abs() * reach, span)
        });
        let from_force = force.map(|((lo, hi), span)| (lo.abs().max(hi.abs()), span));
        let bound: Option<(f64, Span)> = match (from_ctrl, from_force) {
            (Some(c), Some(f)) if c.0 < f.0 => Some(c),
            (_, Some(f)) => Some(f),
            (c, None) => c,
        };
        Some((
            joint.to_string(),
            bound.map(|(most, span)| Spanned {
                value: gear.abs() * most,
                span,
            }),
        ))
    }
}
