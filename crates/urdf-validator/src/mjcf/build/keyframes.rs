//! `<keyframe><key qpos>` as poses of the robot (`--pose key:NAME`), and the keys `<size nkey>` adds at
//! `qpos0` (named by index): MuJoCo's `qpos` (in its order: a
//! free joint's 7 numbers, position and quaternion w x y z, a ball's 4, a hinge's or slide's 1, joints in
//! body and document order) turned into the values of this robot's joints. A key shorter than the model's
//! `nq` leaves the rest at `qpos0` (MuJoCo's rule); a longer one MuJoCo refuses (U030). Only `qpos`
//! matters for statics: `time`, `qvel`, `act`, `mpos` and `mquat` are not read; `ctrl` is only checked
//! against the actuators' `ctrlrange` (U039, as a `qpos` outside a joint's range).
//!
//! - hinge and slide: q = qpos − `ref` (every one is set, to 0 when the key leaves it at `qpos0`);
//! - ball: the quaternion as the three chained hinges `NAME_x`, `NAME_y`, `NAME_z` (R = Rx·Ry·Rz, exact
//!   for every rotation); their torques are about those chained axes, not MuJoCo's three ball dofs
//!   (which are the torque's components in the body frame), unless the ball is at its identity;
//! - free: the robot's base stays where `qpos0` puts it (the analyses have no base pose to take); a key
//!   that moves it gets a note saying the analyses keep it there, upright.

use std::collections::HashMap;

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};

use super::Builder;
use crate::diagnostics::rules;
use crate::diagnostics::span::Span;
use crate::mjcf::defaults::MAIN;
use crate::mjcf::xml::El;
use crate::urdf::robot::Keyframe;

/// Most keys `<size nkey>` makes poses of (the ones past the written ones are all qpos0).
const MAX_SIZED_KEYS: usize = 1_000;

/// A joint as MuJoCo lays it out in `qpos`.
pub(super) enum QposJoint {
    /// A free joint (7 numbers) and its `qpos0`: position, quaternion w x y z.
    Free {
        /// The MJCF joint's name.
        name: String,
        /// Its `qpos0`.
        qpos0: [f64; 7],
        /// Its body's link, unless it is the floating root's (whose link frame is the world's).
        body: Option<String>,
    },
    /// A ball joint (4 numbers), read as three hinges (x, y, z, chained in that order).
    Ball {
        /// The three hinges' names.
        hinges: Vec<String>,
    },
    /// A hinge or slide joint (1 number).
    Scalar {
        /// Its name.
        joint: String,
        /// Its `ref`: its `qpos0`.
        reference: f64,
    },
}

impl QposJoint {
    /// A free joint whose body (`body`'s link; `None` for the floating root) sits at `at` in the world
    /// at `qpos0`.
    pub(super) fn free(name: String, at: &Isometry3<f64>, body: Option<String>) -> Self {
        let p = at.translation.vector;
        let q = at.rotation.quaternion();
        QposJoint::Free {
            name,
            qpos0: [p.x, p.y, p.z, q.w, q.i, q.j, q.k],
            body,
        }
    }

    /// How many `qpos` numbers it takes.
    fn size(&self) -> usize {
        match self {
            QposJoint::Free { .. } => 7,
            QposJoint::Ball { .. } => 4,
            QposJoint::Scalar { .. } => 1,
        }
    }

    /// Its `qpos0`.
    fn qpos0(&self) -> Vec<f64> {
        match self {
            QposJoint::Free { qpos0, .. } => qpos0.to_vec(),
            QposJoint::Ball { .. } => vec![1.0, 0.0, 0.0, 0.0],
            QposJoint::Scalar { reference, .. } => vec![*reference],
        }
    }
}

/// How far past a range (relative, at least 1e-6 of a radian or metre) a key's value must be for a U039:
/// less is the rounding of a range or a key written to a few digits (MS-Human-700's knees sit 1e-8 past
/// theirs), which no simulation notices.
const OUT_OF_RANGE: f64 = 1e-6;

/// "`what` at VALUE (its `range_name` is LOWER to UPPER)" when `value` is past `range` (a limited one) by
/// more than [`OUT_OF_RANGE`].
fn past_range(
    what: &str,
    range_name: &str,
    value: f64,
    range: Option<(f64, f64)>,
) -> Option<String> {
    let (lower, upper) = range?;
    let slack = OUT_OF_RANGE * lower.abs().max(upper.abs()).max(1.0);
    (value < lower - slack || value > upper + slack).then(|| {
        format!(
            "{what} at {} (its {range_name} is {} to {})",
            shown(value),
            shown(lower),
            shown(upper)
        )
    })
}

/// A `qpos` value, to 6 decimals.
fn shown(value: f64) -> String {
    format!("{}", (value * 1e6).round() / 1e6)
}

/// The rotation of the quaternion (w, x, y, z) as MuJoCo normalises it: one shorter than mjMINVAL
/// (`0 0 0 0`, which a key padded with zeros holds) is the identity.
fn unit(w: f64, x: f64, y: f64, z: f64) -> UnitQuaternion<f64> {
    let q = Quaternion::new(w, x, y, z);
    if q.norm() < 1e-15 || !q.norm().is_finite() {
        UnitQuaternion::identity()
    } else {
        UnitQuaternion::from_quaternion(q)
    }
}

/// Angles (a, b, c) of three hinges about x, then the turned y, then the twice-turned z whose rotation is
/// `rotation` (R = Rx(a)·Ry(b)·Rz(c)).
fn xyz_angles(rotation: &UnitQuaternion<f64>) -> [f64; 3] {
    // Rᵀ = Rz(−c)·Ry(−b)·Rx(−a): nalgebra's roll, pitch, yaw of Rᵀ are −a, −b, −c.
    let (roll, pitch, yaw) = rotation.inverse().euler_angles();
    [-roll, -pitch, -yaw]
}

impl<'a> Builder<'a, '_> {
    /// The `<key>`s of the `<keyframe>` sections among `sections`, as poses of the robot built.
    pub(super) fn keyframes(&mut self, sections: &[El<'a>]) -> Vec<Keyframe> {
        let mut keys = Vec::new();
        for section in sections.iter().filter(|s| s.tag() == "keyframe") {
            for el in self.reader.children(*section) {
                if el.tag() != "key" {
                    self.problem(
                        &rules::MJCF_STRUCTURE,
                        el,
                        format!(
                            "<{}> cannot be in <keyframe>, only <key> (MuJoCo refuses the model)",
                            el.tag()
                        ),
                    );
                    continue;
                }
                let index = keys.len();
                if let Some(key) = self.key(el, index) {
                    keys.push(key);
                }
            }
        }
        // `<size nkey="N">` makes N keys at least: those not written are at qpos0, named by index.
        let sized = sections
            .iter()
            .rev()
            .find(|s| s.tag() == "size" && s.attr("nkey").is_some())
            .map(|size| {
                (
                    self.scalar(*size, MAIN, "nkey", 0.0),
                    self.reader.attr_span(*size, "nkey"),
                )
            });
        if let Some((count, span)) = sized {
            // MuJoCo reads an int: 1e308 or 2^31 is refused, not a billion keys to build (a fuzzed
            // nkey="1e308" grew the process without end).
            if !(count.fract() == 0.0 && (0.0..=f64::from(i32::MAX)).contains(&count)) {
                self.reader.report(
                    &rules::MJCF_INVALID_VALUE,
                    span,
                    format!("<size nkey=\"{count}\">: a non-negative int expected (MuJoCo refuses the model)"),
                );
                return keys;
            }
            // Keys past the written ones are all qpos0: the first MAX_SIZED_KEYS stand for the rest.
            if count > MAX_SIZED_KEYS as f64 && keys.len() < MAX_SIZED_KEYS {
                self.reader.report(
                    &rules::MJCF_NOT_READ,
                    span,
                    format!("<size nkey=\"{count}\">: the keys past the written ones are all at qpos0; only the first {MAX_SIZED_KEYS} are made poses (key:0 ... key:{})", MAX_SIZED_KEYS - 1),
                );
            }
            while keys.len() < MAX_SIZED_KEYS && (keys.len() as f64) < count {
                let name = keys.len().to_string();
                keys.push(self.pose_of(name, span, &[]));
            }
        }
        keys
    }

    /// One `<key>` (the `index`-th) as a pose; `None` (with a U030) when MuJoCo refuses it.
    fn key(&mut self, el: El<'a>, index: usize) -> Option<Keyframe> {
        let name = el
            .attr("name")
            .map_or_else(|| index.to_string(), str::to_string);
        let nq: usize = self.qpos.iter().map(QposJoint::size).sum();
        let written = self.list(el, MAIN, "qpos").unwrap_or_default();
        if written.len() > nq {
            let span = self.reader.attr_span(el, "qpos");
            self.reader.report(
                &rules::MJCF_STRUCTURE,
                span,
                format!(
                    "keyframe '{name}': qpos has {} numbers, the model's qpos {nq} (MuJoCo refuses it: \"invalid qpos size\")",
                    written.len()
                ),
            );
            return None;
        }
        let key = self.pose_of(name, self.reader.span(el), &written);
        self.check_key_ranges(el, &key);
        Some(key)
    }

    /// U039 for the limited hinge and slide joints the key puts past their ranges (by more than
    /// [`OUT_OF_RANGE`]), in `qpos` terms (radians or metres, `ref` included) as the key is written, and
    /// for the limited actuators (of the kinds read) its `ctrl` sets past their `ctrlrange`.
    fn check_key_ranges(&mut self, el: El<'a>, key: &Keyframe) {
        // By name, once per key: a model has hundreds of joints, and some models dozens of keys.
        // The first of a repeated name, as a search from the start finds.
        let mut values: HashMap<&str, f64> = HashMap::new();
        for (name, q) in &key.joints {
            values.entry(name.as_str()).or_insert(*q);
        }
        let mut ranges: HashMap<&str, Option<(f64, f64)>> = HashMap::new();
        for j in &self.joints {
            let range = j
                .limit
                .as_ref()
                .and_then(|l| Some((l.lower.as_ref()?.value, l.upper.as_ref()?.value)));
            ranges.entry(j.name.value.as_str()).or_insert(range);
        }
        let mut joints = Vec::new();
        for joint in &self.qpos {
            let QposJoint::Scalar { joint, reference } = joint else {
                continue;
            };
            let Some(q) = values.get(joint.as_str()) else {
                continue;
            };
            let range = ranges.get(joint.as_str()).copied().flatten();
            if let Some(past) = past_range(
                &format!("joint '{joint}'"),
                "range",
                q + reference,
                range.map(|(lo, hi)| (lo + reference, hi + reference)),
            ) {
                joints.push(past);
            }
        }
        let ctrl = self.list(el, MAIN, "ctrl").unwrap_or_default();
        let actuators: Vec<String> = ctrl
            .iter()
            .zip(&self.actuator_ctrl)
            .filter_map(|(value, (name, range))| {
                past_range(&format!("actuator '{name}'"), "ctrlrange", *value, *range)
            })
            .collect();
        let reports = [
            ("qpos", joints, "puts", "in qpos terms (radians or metres): MuJoCo starts there and the limit pushes the joint back"),
            ("ctrl", actuators, "sets", "MuJoCo clamps the control, so the key does not command what it says"),
        ];
        for (attribute, past, verb, consequence) in reports {
            if past.is_empty() {
                continue;
            }
            let message = format!(
                "keyframe '{}' {verb} {}, {consequence}",
                key.name,
                past.join(", ")
            );
            let span = self.reader.attr_span(el, attribute);
            self.reader
                .report(&rules::MJCF_KEYFRAME_OUT_OF_RANGE, span, message);
        }
    }

    /// The key `name` (at `span`) whose `qpos` starts with `written` (the rest at `qpos0`) as a pose.
    fn pose_of(&self, name: String, span: Span, written: &[f64]) -> Keyframe {
        let mut key = Keyframe {
            name: name.clone(),
            span,
            ..Keyframe::default()
        };
        let mut at = 0;
        for joint in &self.qpos {
            let size = joint.size();
            let mut values = joint.qpos0();
            for (k, value) in values.iter_mut().enumerate() {
                if let Some(v) = written.get(at + k) {
                    *value = *v;
                }
            }
            at += size;
            match joint {
                QposJoint::Scalar { joint, reference } => {
                    key.joints.push((joint.clone(), values[0] - reference));
                }
                QposJoint::Ball { hinges } => {
                    let rotation = unit(values[0], values[1], values[2], values[3]);
                    let angles = xyz_angles(&rotation);
                    if rotation.angle() > 0.0 {
                        let ball = hinges[0].strip_suffix("_x").unwrap_or(&hinges[0]);
                        key.notes.push(format!(
                            "keyframe '{name}': ball joint '{ball}' is set as the angles of '{}', '{}', '{}' (its orientation exactly); their gravity torques are about those chained axes, not MuJoCo's three ball dofs",
                            hinges[0], hinges[1], hinges[2]
                        ));
                    }
                    for (hinge, angle) in hinges.iter().zip(angles) {
                        key.joints.push((hinge.clone(), angle));
                    }
                }
                QposJoint::Free {
                    name: joint,
                    qpos0,
                    body,
                } => {
                    let moved = Vector3::new(values[0], values[1], values[2])
                        != Vector3::new(qpos0[0], qpos0[1], qpos0[2]);
                    let turn = |v: &[f64]| unit(v[3], v[4], v[5], v[6]);
                    let tilted = turn(&values).angle_to(&turn(qpos0)) > 1e-12;
                    if moved || tilted {
                        let place = |v: &[f64]| {
                            Isometry3::from_parts(Translation3::new(v[0], v[1], v[2]), turn(v))
                        };
                        match body {
                            None => {
                                key.base =
                                    Some(super::pose(&(place(&values) * place(qpos0).inverse())));
                            }
                            Some(body) => key
                                .free_bodies
                                .push((body.clone(), super::pose(&place(&values)))),
                        }
                        key.notes.push(format!(
                            "keyframe '{name}': free joint '{joint}' is not moved{}: the analyses keep its body where qpos0 puts it{}",
                            if tilted { " nor turned" } else { "" },
                            if tilted {
                                ", so gravity acts as on the robot at qpos0's orientation, not the key's"
                            } else {
                                ""
                            }
                        ));
                    }
                }
            }
        }
        key
    }
}
