//! Joint elements as URDF joints: type, axis, anchor, `ref`, range and dynamics, one per axis.

use nalgebra::Vector3;

use super::{actuators, Builder};
use crate::diagnostics::rules;
use crate::diagnostics::span::{Span, Spanned};
use crate::mjcf::xml::El;
use crate::urdf::robot::{Dynamics, Joint, JointKind, Limit, Pose};

/// The limits of a slide joint without a range: SDFormat's "unlimited" (the samplers and checks read a
/// range this wide as no limit, see `model::kinematics::MAX_PRISMATIC_TRAVEL`).
const UNLIMITED_SLIDE: f64 = 1e16;

impl<'a> Builder<'a, '_> {
    pub(super) fn joint_type(&self, el: El<'a>, class: &str) -> &'a str {
        if el.tag() == "freejoint" {
            return "free";
        }
        self.value(el, class, "type")
            .map_or("hinge", |v| v.text.trim())
    }

    /// The name of joint `el`: its `name`, else `joint#N` (N its MuJoCo joint id).
    pub(super) fn joint_name(&self, el: El<'a>) -> String {
        el.attr("name")
            .map_or_else(|| format!("joint#{}", self.joint_ids), str::to_string)
    }

    /// A joint's numbers (three hinges for a ball joint).
    pub(super) fn joint(
        &mut self,
        el: El<'a>,
        class: &str,
        body: &str,
        kind: &str,
        top_level: bool,
    ) -> JointSpec {
        let name = self.joint_name(el);
        self.joint_ids += 1;
        let span = self.reader.span(el);
        let name_span = self.reader.attr_span(el, "name");
        let type_span = self.reader.attr_span(el, "type");
        let anchor = Vector3::from(self.vector(el, class, "pos", [0.0; 3]));
        let axis_span = self.value(el, class, "axis").map_or(span, |v| v.span);
        let written_axis = Vector3::from(self.vector(el, class, "axis", [0.0, 0.0, 1.0]));
        let axis = match written_axis.try_normalize(1e-14) {
            Some(a) => a,
            None => {
                self.reader.report(
                    &rules::MJCF_STRUCTURE,
                    axis_span,
                    format!("joint '{name}': the axis is zero (MuJoCo refuses it)"),
                );
                Vector3::z()
            }
        };
        let mut spec = JointSpec {
            names: vec![name.clone()],
            span,
            name_span,
            type_span,
            axis_span,
            anchor,
            axes: vec![axis],
            kind: JointKind::Revolute,
            reference: 0.0,
            limit: None,
            dynamics: None,
        };
        match kind {
            "free" => {
                if !top_level {
                    self.problem(
                        &rules::MJCF_STRUCTURE,
                        el,
                        format!("joint '{name}' in body '{body}' is free, but only a body of the <worldbody> may have a free joint (MuJoCo refuses it)"),
                    );
                }
                spec.kind = JointKind::Floating;
                return spec;
            }
            "ball" => {
                self.note(
                    el,
                    format!("ball joint '{name}' is analysed as three hinges '{name}_x', '{name}_y', '{name}_z' about the body's axes (MuJoCo's three ball dofs at the pose analysed)"),
                );
                spec.names = ["x", "y", "z"]
                    .iter()
                    .map(|a| format!("{name}_{a}"))
                    .collect();
                spec.axes = vec![Vector3::x(), Vector3::y(), Vector3::z()];
                spec.kind = JointKind::Continuous;
                return spec;
            }
            "hinge" | "slide" => {}
            other => {
                self.problem(
                    &rules::MJCF_INVALID_VALUE,
                    el,
                    format!("joint '{name}': type '{other}' is not free, ball, slide or hinge; read as a hinge"),
                );
            }
        }
        let hinge = kind != "slide";
        let degrees = hinge && self.compiler.degrees;
        let to_q = |v: f64| if degrees { v.to_radians() } else { v };
        let reference = to_q(self.scalar(el, class, "ref", 0.0));
        spec.reference = reference;
        let range = self.value(el, class, "range");
        let limited = match self.word(el, class, "limited", &["auto", "true", "false"]) {
            "true" => true,
            "false" => false,
            _ => {
                if range.is_some() && !self.compiler.auto_limits {
                    self.problem(
                        &rules::MJCF_STRUCTURE,
                        el,
                        format!("joint '{name}' has a range but neither limited=\"true\" nor <compiler autolimits=\"true\"> (MuJoCo refuses it)"),
                    );
                }
                range.is_some() && self.compiler.auto_limits
            }
        };
        let bounds = self.vector(el, class, "range", [0.0, 0.0]);
        spec.kind = match (hinge, limited) {
            (true, true) => JointKind::Revolute,
            (true, false) => JointKind::Continuous,
            (false, _) => JointKind::Prismatic,
        };
        let limit_span = range.map_or(span, |r| r.span);
        // An unlimited slide moves freely: as SDFormat writes it, ±1e16 (no travel, not "both limits 0").
        let (lower, upper) = if limited {
            (to_q(bounds[0]) - reference, to_q(bounds[1]) - reference)
        } else {
            (-UNLIMITED_SLIDE, UNLIMITED_SLIDE)
        };
        let bound = |value: f64| {
            (limited || !hinge).then_some(Spanned {
                value,
                span: limit_span,
            })
        };
        spec.limit = Some(Limit {
            span: limit_span,
            lower: bound(lower),
            upper: bound(upper),
            effort: None,
            velocity: None,
        });
        if let Some(range) = self.range(el, class, "actuatorfrc") {
            self.actuator_force.insert(name.clone(), range);
        }
        let damping = self.scalar(el, class, "damping", 0.0);
        let armature = self.scalar(el, class, "armature", 0.0);
        self.joint_facts.insert(
            name.clone(),
            actuators::JointFacts {
                range: limited.then(|| (to_q(bounds[0]), to_q(bounds[1]))),
                written_range: range.is_some().then(|| (to_q(bounds[0]), to_q(bounds[1]))),
                span,
                still: damping == 0.0 && armature == 0.0,
            },
        );
        let friction = self.scalar(el, class, "frictionloss", 0.0);
        spec.dynamics = Some(Dynamics {
            damping: Some(damping),
            friction: Some(friction),
        });
        spec
    }
}

/// What a joint element turns into: one URDF joint per axis (three for a ball).
pub(super) struct JointSpec {
    pub(super) names: Vec<String>,
    pub(super) span: Span,
    pub(super) name_span: Span,
    pub(super) type_span: Span,
    pub(super) axis_span: Span,
    pub(super) anchor: Vector3<f64>,
    pub(super) axes: Vec<Vector3<f64>>,
    pub(super) kind: JointKind,
    /// `ref` (radians or metres): MuJoCo's `qpos0` of a hinge or slide joint, 0 for the others.
    pub(super) reference: f64,
    pub(super) limit: Option<Limit>,
    pub(super) dynamics: Option<Dynamics>,
}

pub(super) fn blank_joint() -> Joint {
    Joint {
        name: Spanned {
            value: String::new(),
            span: Span::default(),
        },
        span: Span::default(),
        kind: None,
        origin: Pose::default(),
        parent: None,
        child: None,
        axis: None,
        limit: None,
        dynamics: None,
        mimic: None,
        safety_controller: None,
        calibration: None,
    }
}
