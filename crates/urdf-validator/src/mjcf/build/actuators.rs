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

//!
//! The MJCF-only actuator rules are checked here too: a position servo whose `ctrlrange` cannot command
//! its joint's whole range (U034), an actuated joint without any bound (U035), a joint geared above 1
//! without `armature` or `damping` (U036).

use std::collections::HashMap;

use super::{Builder, MAIN};
use crate::diagnostics::rules;
use crate::diagnostics::span::{Span, Spanned};
use crate::mjcf::xml::El;

/// What the actuator rules need to know of a hinge or slide joint.
pub(super) struct JointFacts {
    /// Its `range` in MuJoCo's qpos units (radians, metres) when it is limited.
    pub range: Option<(f64, f64)>,
    /// Its `range` as written (or from its class), limited or not: what `inheritrange` copies.
    pub written_range: Option<(f64, f64)>,
    /// The joint element.
    pub span: Span,
    /// Both `armature` and `damping` are zero.
    pub still: bool,
}

/// An actuator read: the joint it drives, the effort it can apply there (`None`: unbounded) and its
/// element.
struct Drive {
    joint: String,
    effort: Option<Spanned<f64>>,
    span: Span,
    /// Its `ctrlrange` when limited.
    ctrl: Option<(f64, f64)>,
}

/// The actuator elements read; the others are U033.
const READ: [&str; 4] = ["motor", "position", "velocity", "general"];

/// A servo commanding past its joint by less than this share of its control range (percent) is U043
/// (INFO), from it on U041 (WARN).
const SLIGHTLY_BEYOND_PERCENT: f64 = 1.0;
impl<'a> Builder<'a, '_> {
    /// Set each hinge and slide joint's effort from the `<actuator>` sections among `sections`.
    pub(super) fn set_efforts(&mut self, sections: &[El<'a>]) {
        // Per joint: the sum of its actuators' efforts, `None` once one of them is unbounded.
        let mut efforts: HashMap<String, Option<Spanned<f64>>> = HashMap::new();
        // Per joint, the first actuator without any bound (U035 points at it).
        let mut unbounded: HashMap<String, Span> = HashMap::new();
        for section in sections.iter().filter(|s| s.tag() == "actuator") {
            for el in self.reader.children(*section) {
                let name = el.attr("name").map_or_else(
                    || format!("actuator#{}", self.actuator_ctrl.len()),
                    str::to_string,
                );
                let drive = self.actuator(el);
                self.actuator_ctrl
                    .push((name, drive.as_ref().and_then(|d| d.ctrl)));
                let Some(Drive {
                    joint,
                    effort,
                    span,
                    ..
                }) = drive
                else {
                    continue;
                };
                if effort.is_none() {
                    unbounded.entry(joint.clone()).or_insert(span);
                }
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
        let mut findings = Vec::new();
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
            if let (None, Some(&span)) = (&limit.effort, unbounded.get(name)) {
                findings.push((span, format!("joint '{name}' is actuated without any bound: no forcerange, no ctrlrange and no actuatorfrcrange, so MuJoCo applies whatever force is asked and the statics check has no limit to judge it by")));
            }
        }
        for (span, message) in findings {
            self.reader
                .report(&rules::MJCF_ACTUATOR_UNBOUNDED, span, message);
        }
    }

    /// U034 when the position servo `name` (gear `gear`, control range `ctrl`) cannot command all of
    /// `joint`'s range, U041 (U043 below 1 % of the control range) when it commands past it, each beyond
    /// rounding: its targets in joint units are
    /// `ctrl / gear`.
    fn check_servo_reach(&mut self, name: &str, joint: &str, gear: f64, ctrl: ((f64, f64), Span)) {
        let Some((lo, hi)) = self.joint_facts.get(joint).and_then(|f| f.range) else {
            return;
        };
        if gear == 0.0 {
            return;
        }
        let ((c_lo, c_hi), span) = ctrl;
        let (a, b) = (c_lo / gear, c_hi / gear);
        let (reach_lo, reach_hi) = (a.min(b), a.max(b));
        // Numbers written to five or six digits (SO-ARM101's ctrlrange 1.91986 for a range of 1.919862)
        // fall short by rounding, not by design: a shortfall below 1e-4 of the range's scale is none.
        let scale = (hi - lo).abs().max(lo.abs()).max(hi.abs());
        let slack = 1e-4 * scale + 1e-12;
        if reach_lo > lo + slack || reach_hi < hi - slack {
            let message = format!(
                "position actuator '{name}' commands joint '{joint}' only within [{reach_lo:.6}, {reach_hi:.6}] (ctrlrange / gear {gear}), not its whole range [{lo:.6}, {hi:.6}] (radians or metres: a ctrlrange is not converted from degrees)"
            );
            self.reader
                .report(&rules::MJCF_CTRLRANGE_SHORT, span, message);
        }
        if reach_lo < lo - slack || reach_hi > hi + slack {
            let overlap = (reach_hi.min(hi) - reach_lo.max(lo)).max(0.0);
            let width = reach_hi - reach_lo;
            let outside = if width > 0.0 {
                100.0 * (1.0 - overlap / width)
            } else {
                0.0
            };
            let share = if outside < 10.0 {
                format!("{outside:.1}")
            } else {
                format!("{outside:.0}")
            };
            let message = format!(
                "position actuator '{name}' commands joint '{joint}' within [{reach_lo:.6}, {reach_hi:.6}] (ctrlrange / gear {gear}), beyond its range [{lo:.6}, {hi:.6}]: {share} % of the control range drives the servo into the joint's limit"
            );
            let rule = if outside >= SLIGHTLY_BEYOND_PERCENT {
                &rules::MJCF_CTRLRANGE_BEYOND_RANGE
            } else {
                &rules::MJCF_CTRLRANGE_SLIGHTLY_BEYOND
            };
            self.reader.report(rule, span, message);
        }
    }

    /// U036 when actuator `name`'s `gear` is above 1 in magnitude and `joint` has neither armature nor
    /// damping.
    fn check_geared_joint(&mut self, name: &str, joint: &str, gear: f64) {
        let Some(facts) = self.joint_facts.get(joint) else {
            return;
        };
        if gear.abs() > 1.0 && facts.still {
            let span = facts.span;
            let message = format!(
                "joint '{joint}' is driven through gear {gear} by actuator '{name}' but has neither armature nor damping: a geared motor's rotor inertia is reflected to the joint times the gear ratio squared (armature), and a gearbox dissipates"
            );
            self.reader
                .report(&rules::MJCF_GEARED_JOINT_WITHOUT_ARMATURE, span, message);
        }
    }

    /// The control range `inheritrange` gives a position servo (or `general`): its joint's range scaled
    /// about the range's middle, as MuJoCo compiles it (`Some(None)` when MuJoCo refuses it: U030);
    /// `None` without `inheritrange`.
    fn inherited_ctrl(
        &mut self,
        el: El<'a>,
        class: &str,
        joint: &str,
    ) -> Option<Option<((f64, f64), Span)>> {
        let written = self.value(el, class, "inheritrange")?;
        let scale = self.scalar(el, class, "inheritrange", 0.0);
        if scale <= 0.0 {
            return None;
        }
        let name = el.attr("name").unwrap_or("(unnamed)");
        if el.attr("ctrlrange").is_some() {
            self.reader.report(
                &rules::MJCF_STRUCTURE,
                written.span,
                format!("actuator '{name}' has both ctrlrange and inheritrange (MuJoCo refuses it: \"ctrlrange and inheritrange cannot both be defined\")"),
            );
            return Some(None);
        }
        let Some((lo, hi)) = self.joint_facts.get(joint).and_then(|f| f.written_range) else {
            self.reader.report(
                &rules::MJCF_STRUCTURE,
                written.span,
                format!("actuator '{name}' inherits the range of joint '{joint}', which has none (MuJoCo refuses it: \"inheritrange used but target has no range defined\")"),
            );
            return Some(None);
        };
        let (mean, radius) = (0.5 * (hi + lo), 0.5 * (hi - lo) * scale);
        Some(Some(((mean - radius, mean + radius), written.span)))
    }

    /// The joint an actuator drives and the effort it can apply there; `None` (with a U033) when it
    /// drives no joint or is of a kind not read. Checks U034 and U036 on the way.
    fn actuator(&mut self, el: El<'a>) -> Option<Drive> {
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
        let ctrl = match tag {
            "position" | "general" => self.inherited_ctrl(el, &class, joint),
            _ => None,
        }
        .unwrap_or_else(|| self.range(el, &class, "ctrl"));
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
        if let (true, Some(ctrl)) = (position_like, ctrl) {
            self.check_servo_reach(name, joint, gear, ctrl);
        }
        self.check_geared_joint(name, joint, gear);
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
        Some(Drive {
            joint: joint.to_string(),
            effort: bound.map(|(most, span)| Spanned {
                value: gear.abs() * most,
                span,
            }),
            span: self.reader.span(el),
            ctrl: ctrl.map(|(range, _)| range),
        })
    }
}
