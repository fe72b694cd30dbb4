//! `--override KEY=VALUE`: evaluate the robot with some of its declared values changed, the file untouched
//! (`joint.NAME.effort=80`, `joint.NAME.lower`/`upper`/`velocity`, `link.NAME.mass=12`,
//! `link.NAME.com=x,y,z`, `payload.mass=2`). The report lists each override with the value it replaced,
//! and the edit that would write it into the file (`--fix --from-overrides`).

use crate::diagnostics::fix::{number, Edit, Fix};
use crate::diagnostics::span::{Span, Spanned};
use crate::diagnostics::suggest::did_you_mean;
use crate::urdf::robot::{Inertial, Limit, Pose, Robot};

/// What an override changes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Field {
    Effort,
    Lower,
    Upper,
    Velocity,
    Mass,
    Com,
    Payload,
}

/// One `KEY=VALUE`, parsed.
#[derive(Clone, Debug, PartialEq)]
pub struct ValueOverride {
    /// The key as written (`joint.shoulder.effort`).
    pub key: String,
    /// The joint or link it names (empty for `payload.mass`).
    name: String,
    field: Field,
    /// One number, or three for `com`.
    values: Vec<f64>,
}

impl ValueOverride {
    /// Parse `KEY=VALUE`; an error says what was expected.
    pub fn parse(text: &str) -> Result<ValueOverride, String> {
        let (key, value) = text.split_once('=').ok_or_else(|| {
            format!("override '{text}': expected KEY=VALUE, e.g. joint.shoulder.effort=80")
        })?;
        let key = key.trim();
        let (kind, rest) = key.split_once('.').unwrap_or((key, ""));
        let (name, attribute) = match kind {
            "payload" => ("", rest),
            _ => rest.rsplit_once('.').unwrap_or((rest, "")),
        };
        let field = match (kind, attribute) {
            ("joint", "effort") => Field::Effort,
            ("joint", "lower") => Field::Lower,
            ("joint", "upper") => Field::Upper,
            ("joint", "velocity") => Field::Velocity,
            ("link", "mass") => Field::Mass,
            ("link", "com") => Field::Com,
            ("payload", "mass") => Field::Payload,
            _ => {
                return Err(format!(
                    "override '{key}': expected joint.NAME.effort|lower|upper|velocity, link.NAME.mass|com or payload.mass"
                ))
            }
        };
        if kind != "payload" && name.is_empty() {
            return Err(format!("override '{key}': the {kind} name is missing"));
        }
        let values: Vec<f64> = value
            .split(',')
            .map(|v| v.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("override '{key}': '{value}' is not a number"))?;
        let wanted = if field == Field::Com { 3 } else { 1 };
        if values.len() != wanted || !values.iter().all(|v| v.is_finite()) {
            return Err(format!(
                "override '{key}': expected {} finite number{}, got '{value}'",
                wanted,
                if wanted == 1 { "" } else { "s (x,y,z)" }
            ));
        }
        let negative = matches!(
            field,
            Field::Effort | Field::Velocity | Field::Mass | Field::Payload
        );
        if negative && values[0] < 0.0 {
            return Err(format!("override '{key}': must be ≥ 0, got {}", values[0]));
        }
        Ok(ValueOverride {
            key: key.to_string(),
            name: name.to_string(),
            field,
            values,
        })
    }

    /// The payload mass it sets, for `payload.mass`.
    pub fn payload_mass(&self) -> Option<f64> {
        (self.field == Field::Payload).then(|| self.values[0])
    }
}

/// An override as applied, with the fix that would write it into the text the parser read.
pub struct Applied {
    /// The key (`joint.shoulder.effort`).
    pub key: String,
    /// The value used, as written.
    pub value: String,
    /// The value the file declares (`None` when it declares none).
    pub was: Option<String>,
    /// Writing the value into the file, when there is an attribute to hold it.
    pub fix: Option<Fix>,
}

fn written(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| v.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

/// The index of the joint or link (`kind`) `o` names among `names`, or an error naming the closest.
fn index_of<'a>(
    o: &ValueOverride,
    kind: &str,
    names: impl Iterator<Item = &'a str> + Clone,
) -> Result<usize, String> {
    names.clone().position(|n| n == o.name).ok_or_else(|| {
        format!(
            "override '{}': the robot has no {kind} '{}' ({})",
            o.key,
            o.name,
            did_you_mean(&o.name, names)
        )
    })
}

/// Apply the joint and link overrides to `robot`; what each changed and how to write it into the file
/// (`document` is the URDF the robot was read from: it locates the `xyz` of an inertial `<origin>`; `None`
/// for SDFormat, whose files fixes do not edit). An override naming a joint or link the robot does not have
/// is an error naming the closest names. (`payload.mass` is the caller's, as the payload option.)
pub fn apply(
    robot: &mut Robot,
    overrides: &[ValueOverride],
    document: Option<&roxmltree::Document>,
) -> Result<Vec<Applied>, String> {
    let mut applied = Vec::new();
    for o in overrides {
        let value = o.values[0];
        let (was, edit) = match o.field {
            Field::Payload => (None, None),
            Field::Effort | Field::Lower | Field::Upper | Field::Velocity => {
                let index = index_of(
                    o,
                    "joint",
                    robot.joints.iter().map(|j| j.name.value.as_str()),
                )?;
                let joint = &mut robot.joints[index];
                let declared_limit = joint.limit.is_some();
                let span = joint.span;
                let limit = joint.limit.get_or_insert(Limit {
                    span,
                    lower: None,
                    upper: None,
                    effort: None,
                    velocity: None,
                });
                // An attribute of the <limit> to insert a missing one after.
                let sibling = [&limit.lower, &limit.upper, &limit.effort, &limit.velocity]
                    .into_iter()
                    .find_map(|v| v.as_ref().map(|v| v.span))
                    .filter(|_| declared_limit);
                let (slot, attribute) = match o.field {
                    Field::Effort => (&mut limit.effort, "effort"),
                    Field::Lower => (&mut limit.lower, "lower"),
                    Field::Upper => (&mut limit.upper, "upper"),
                    _ => (&mut limit.velocity, "velocity"),
                };
                let was = slot.as_ref().map(|v| v.value.to_string());
                let edit = value_edit(slot.as_ref().map(|v| v.span), sibling, attribute, value);
                let span = slot.as_ref().map_or(limit.span, |v| v.span);
                *slot = Some(Spanned { value, span });
                (was, edit)
            }
            Field::Mass | Field::Com => {
                let index = index_of(o, "link", robot.links.iter().map(|l| l.name.value.as_str()))?;
                let link = &mut robot.links[index];
                let span = link.span;
                let inertial = link.inertial.get_or_insert(Inertial {
                    span,
                    origin: Pose::default(),
                    mass: None,
                    inertia: None,
                });
                if o.field == Field::Mass {
                    let was = inertial.mass.as_ref().map(|m| m.value.to_string());
                    let edit =
                        value_edit(inertial.mass.as_ref().map(|m| m.span), None, "value", value);
                    let span = inertial.mass.as_ref().map_or(inertial.span, |m| m.span);
                    inertial.mass = Some(Spanned { value, span });
                    (was, edit)
                } else {
                    let was = written(&inertial.origin.xyz);
                    let (xyz, rpy) = match (inertial.origin.span, document) {
                        (Some(origin), Some(document)) => (
                            attribute_value(document, origin, "xyz"),
                            attribute_value(document, origin, "rpy"),
                        ),
                        _ => (None, None),
                    };
                    let edit = match xyz {
                        Some(xyz) => Some(Edit::ReplaceValue {
                            value: xyz,
                            with: triple(&o.values),
                        }),
                        None => rpy.map(|rpy| Edit::InsertAttributeAfter {
                            value: rpy,
                            name: "xyz".into(),
                            text: triple(&o.values),
                        }),
                    };
                    inertial.origin.xyz = [o.values[0], o.values[1], o.values[2]];
                    (Some(was), edit)
                }
            }
        };
        let value = written(&o.values);
        let fix = edit.map(|edit| {
            let was = was
                .as_ref()
                .map_or_else(|| "not declared".to_string(), |w| format!("was {w}"));
            Fix::unsafe_(
                format!("write the override {}={value} into the file ({was})", o.key),
                vec![edit],
            )
        });
        applied.push(Applied {
            key: o.key.clone(),
            value,
            was,
            fix,
        });
    }
    Ok(applied)
}

/// Replace the attribute value at `declared`, or insert `attribute` after the one at `sibling`.
fn value_edit(
    declared: Option<Span>,
    sibling: Option<Span>,
    attribute: &str,
    value: f64,
) -> Option<Edit> {
    match (declared, sibling) {
        (Some(at), _) => Some(Edit::ReplaceValue {
            value: at,
            with: number(value),
        }),
        (None, Some(after)) => Some(Edit::InsertAttributeAfter {
            value: after,
            name: attribute.to_string(),
            text: number(value),
        }),
        (None, None) => None,
    }
}

/// `x y z` as an `xyz` attribute writes it.
fn triple(values: &[f64]) -> String {
    values
        .iter()
        .map(|&v| number(v))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The span of the value of attribute `name` of the element at `element` in `document`.
fn attribute_value(document: &roxmltree::Document, element: Span, name: &str) -> Option<Span> {
    let range = element.start as usize..element.end as usize;
    document
        .descendants()
        .find(|n| n.is_element() && n.range() == range)?
        .attributes()
        .find(|a| a.name() == name)
        .map(|a| Span::from_range(a.range_value()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_and_values_are_checked() {
        let effort = ValueOverride::parse("joint.r_shoulder.effort=80").unwrap();
        assert_eq!(
            (effort.name.as_str(), effort.field),
            ("r_shoulder", Field::Effort)
        );
        let com = ValueOverride::parse("link.base.link.com=0.1, 0, -0.2").unwrap();
        assert_eq!(com.name, "base.link");
        assert_eq!(com.values, vec![0.1, 0.0, -0.2]);
        assert_eq!(
            ValueOverride::parse("payload.mass=2")
                .unwrap()
                .payload_mass(),
            Some(2.0)
        );
        for bad in [
            "joint.a.effort",
            "joint.a.torque=1",
            "joint.effort=1",
            "link.a.com=1,2",
            "link.a.mass=-1",
            "joint.a.effort=NaN",
            "joint.a.effort=x",
        ] {
            assert!(ValueOverride::parse(bad).is_err(), "{bad}");
        }
    }
}
