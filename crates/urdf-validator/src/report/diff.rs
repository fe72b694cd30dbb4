//! What changed between two reports (`urdf_validate diff OLD NEW`): verdicts, findings (by
//! [`Fingerprint`]), masses, centre of mass, torque margins, stability margin and reach.
//!
//! Both sides are report JSON values (a fresh [`crate::report::Report`] serialised, or a
//! `<robot>_validation.json` read back), so a report written by an earlier version compares too: a field it
//! lacks is `null` on its side.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::Serialize;
use serde_json::Value;

use crate::diagnostics::Severity;
use crate::report::baseline::{message_key, Fingerprint};

/// A value on each side (`null` where that side has none).
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct Change<T> {
    /// In OLD.
    pub old: Option<T>,
    /// In NEW.
    pub new: Option<T>,
}

impl<T: PartialEq> Change<T> {
    /// Whether the two sides differ.
    pub fn changed(&self) -> bool {
        self.old != self.new
    }
}

/// A verdict on each side.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct VerdictChange {
    /// `overall`, or the section: `schema`, `statics`, `stability`, `workspace`, `symmetry`.
    pub check: String,
    /// The statuses (PASS, WARN, FAIL, UNKNOWN, N/A).
    #[serde(flatten)]
    pub status: Change<String>,
    /// NEW's status is worse than OLD's (PASS/N/A < WARN < UNKNOWN < FAIL).
    pub worse: bool,
}

/// A finding only one side has.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct DiffFinding {
    /// Rule code.
    pub rule: String,
    /// Severity.
    pub severity: Severity,
    /// Element path (when the report carries it).
    pub element: Option<String>,
    /// The message.
    pub message: String,
}

/// The statics figures of one joint.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct JointFigures {
    /// Gravity torque (N·m, N for prismatic).
    pub torque: Option<f64>,
    /// Declared effort limit.
    pub effort: Option<f64>,
    /// Effort / torque (none when the torque is negligible).
    pub margin: Option<f64>,
    /// The smallest effort that would PASS (1.5 × |torque|).
    pub effort_needed: Option<f64>,
    /// PASS, WARN, FAIL, UNKNOWN.
    pub status: String,
}

/// A joint whose statics changed.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct JointChange {
    /// Joint name.
    pub joint: String,
    /// Its figures on each side.
    #[serde(flatten)]
    pub figures: Change<JointFigures>,
}

/// A named number that changed (a link's mass, an arm's reach).
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct NamedChange {
    /// Link name, or the arm's tip link.
    pub name: String,
    /// The values.
    #[serde(flatten)]
    pub value: Change<f64>,
}

/// What changed from OLD to NEW: `urdf_validate diff --format json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct ReportDiff {
    /// OLD's `urdf_path`.
    pub old: String,
    /// NEW's `urdf_path`.
    pub new: String,
    /// NEW is worse: a verdict got worse, or NEW has a WARN, FAIL or CRITICAL finding OLD lacks.
    pub worse: bool,
    /// Overall and section verdicts, every one (changed or not).
    pub verdicts: Vec<VerdictChange>,
    /// Findings of NEW that OLD lacks (by rule, severity, element and message without numbers).
    pub findings_added: Vec<DiffFinding>,
    /// Findings of OLD that NEW lacks.
    pub findings_removed: Vec<DiffFinding>,
    /// Total mass, kg.
    pub total_mass: Change<f64>,
    /// Full-body centre of mass, m.
    pub com: Change<Vec<f64>>,
    /// Links whose mass changed (or that one side lacks), kg.
    pub link_masses: Vec<NamedChange>,
    /// Statics joints whose torque, effort, margin or status changed.
    pub joints: Vec<JointChange>,
    /// Stability margin, mm.
    pub stability_margin_mm: Change<f64>,
    /// Arms (by tip link) whose maximum reach changed, m.
    pub reach: Vec<NamedChange>,
}

/// Compare two report JSON values.
pub fn compare(old: &Value, new: &Value) -> ReportDiff {
    let verdicts: Vec<VerdictChange> = [
        ("overall", "/overall_status"),
        ("schema", "/schema/status"),
        ("statics", "/statics/status"),
        ("stability", "/stability/status"),
        ("workspace", "/workspace/status"),
        ("symmetry", "/symmetry/status"),
    ]
    .into_iter()
    .map(|(check, pointer)| {
        let status = Change {
            old: text(old.pointer(pointer)),
            new: text(new.pointer(pointer)),
        };
        VerdictChange {
            check: check.to_string(),
            worse: rank(status.new.as_deref()) > rank(status.old.as_deref()),
            status,
        }
    })
    .collect();
    let (findings_added, findings_removed) = finding_changes(old, new);
    let worse = verdicts.iter().any(|v| v.worse)
        || findings_added.iter().any(|f| f.severity > Severity::Info);
    ReportDiff {
        old: text(old.get("urdf_path")).unwrap_or_default(),
        new: text(new.get("urdf_path")).unwrap_or_default(),
        worse,
        verdicts,
        findings_added,
        findings_removed,
        total_mass: change(old, new, |r| number(r.pointer("/statics/total_mass"))),
        com: change(old, new, |r| {
            r.pointer("/statics/full_body_com")
                .and_then(Value::as_array)
                .map(|v| v.iter().filter_map(Value::as_f64).collect())
        }),
        link_masses: named_changes(old, new, "/links", "name", "mass"),
        joints: joint_changes(old, new),
        stability_margin_mm: change(old, new, |r| number(r.pointer("/stability/margin_mm"))),
        reach: named_changes(old, new, "/workspace/arms", "tip_link", "max_reach"),
    }
}

fn text(value: Option<&Value>) -> Option<String> {
    value.and_then(Value::as_str).map(str::to_string)
}

fn number(value: Option<&Value>) -> Option<f64> {
    value.and_then(Value::as_f64)
}

fn change<T>(old: &Value, new: &Value, get: impl Fn(&Value) -> Option<T>) -> Change<T> {
    Change {
        old: get(old),
        new: get(new),
    }
}

/// PASS and N/A < WARN < UNKNOWN < FAIL; an absent section ranks as PASS.
fn rank(status: Option<&str>) -> u8 {
    match status {
        Some("WARN") => 1,
        Some("UNKNOWN") => 2,
        Some("FAIL") => 3,
        _ => 0,
    }
}

/// The findings of each side that the other lacks, multiset-wise. Element paths take part only when
/// both reports carry them.
fn finding_changes(old: &Value, new: &Value) -> (Vec<DiffFinding>, Vec<DiffFinding>) {
    let findings = |r: &Value| -> Vec<DiffFinding> {
        r.get("findings")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
            .filter_map(|f| {
                Some(DiffFinding {
                    rule: text(f.get("rule"))?,
                    severity: serde_json::from_value(f.get("severity")?.clone()).ok()?,
                    element: text(f.get("element")),
                    message: text(f.get("message"))?,
                })
            })
            .collect()
    };
    let carries_elements = |r: &Value| {
        r.get("findings")
            .and_then(Value::as_array)
            .is_some_and(|all| all.iter().all(|f| f.get("element").is_some()))
    };
    let with_elements = carries_elements(old) && carries_elements(new);
    let print = |f: &DiffFinding| Fingerprint {
        rule: f.rule.clone(),
        severity: f.severity,
        element: f.element.clone().filter(|_| with_elements),
        key: message_key(&f.message),
    };
    let (old, new) = (findings(old), findings(new));
    let only_in = |these: &[DiffFinding], others: &[DiffFinding]| {
        let mut left: BTreeMap<Fingerprint, usize> = BTreeMap::new();
        for f in others {
            *left.entry(print(f)).or_insert(0) += 1;
        }
        these
            .iter()
            .filter(|f| match left.get_mut(&print(f)) {
                Some(n) if *n > 0 => {
                    *n -= 1;
                    false
                }
                _ => true,
            })
            .cloned()
            .collect::<Vec<_>>()
    };
    (only_in(&new, &old), only_in(&old, &new))
}

/// Entries of the array at `pointer`, by `key`, whose number `field` differs (or that one side lacks).
fn named_changes(
    old: &Value,
    new: &Value,
    pointer: &str,
    key: &str,
    field: &str,
) -> Vec<NamedChange> {
    let table = |r: &Value| -> Vec<(String, Option<f64>)> {
        r.pointer(pointer)
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
            .filter_map(|e| Some((text(e.get(key))?, number(e.get(field)))))
            .collect()
    };
    let (old, new) = (table(old), table(new));
    let mut names: Vec<&String> = old.iter().map(|(n, _)| n).collect();
    names.extend(
        new.iter()
            .map(|(n, _)| n)
            .filter(|n| !old.iter().any(|(o, _)| o == *n)),
    );
    names
        .into_iter()
        .map(|name| {
            let find = |side: &[(String, Option<f64>)]| {
                side.iter().find(|(n, _)| n == name).and_then(|(_, v)| *v)
            };
            NamedChange {
                name: name.clone(),
                value: Change {
                    old: find(&old),
                    new: find(&new),
                },
            }
        })
        .filter(|c| c.value.changed())
        .collect()
}

/// Statics joints whose figures differ (torques compared to 1e-6).
fn joint_changes(old: &Value, new: &Value) -> Vec<JointChange> {
    let joints = |r: &Value| -> Vec<(String, JointFigures)> {
        r.pointer("/statics/joints")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
            .filter_map(|j| {
                Some((
                    text(j.get("name"))?,
                    JointFigures {
                        torque: number(j.get("required_torque_gravity")),
                        effort: number(j.get("declared_effort")),
                        margin: number(j.get("margin")),
                        effort_needed: number(j.get("effort_needed")),
                        status: text(j.get("status")).unwrap_or_default(),
                    },
                ))
            })
            .collect()
    };
    let (old, new) = (joints(old), joints(new));
    let mut names: Vec<&String> = old.iter().map(|(n, _)| n).collect();
    names.extend(
        new.iter()
            .map(|(n, _)| n)
            .filter(|n| !old.iter().any(|(o, _)| o == *n)),
    );
    let close = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() <= 1e-6,
        (a, b) => a.is_none() && b.is_none(),
    };
    names
        .into_iter()
        .map(|name| {
            let find = |side: &[(String, JointFigures)]| {
                side.iter().find(|(n, _)| n == name).map(|(_, f)| f.clone())
            };
            JointChange {
                joint: name.clone(),
                figures: Change {
                    old: find(&old),
                    new: find(&new),
                },
            }
        })
        .filter(|c| match (&c.figures.old, &c.figures.new) {
            (Some(a), Some(b)) => {
                !(close(a.torque, b.torque)
                    && close(a.effort, b.effort)
                    && close(a.margin, b.margin)
                    && a.status == b.status)
            }
            _ => true,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn changes_are_found_and_a_worse_verdict_is_worse() {
        let old = json!({
            "urdf_path": "a.urdf", "overall_status": "WARN", "schema": {"status": "WARN"},
            "statics": {"status": "PASS", "total_mass": 8.0, "full_body_com": [0.1, 0.0, 0.2],
                "joints": [{"name": "elbow", "required_torque_gravity": 2.0, "declared_effort": 10.0, "margin": 5.0, "status": "PASS"},
                           {"name": "wrist", "required_torque_gravity": 0.5, "declared_effort": 10.0, "margin": 20.0, "status": "PASS"}]},
            "links": [{"name": "fore", "mass": 1.0}, {"name": "hand", "mass": 0.5}],
            "findings": [{"rule": "U206", "severity": "WARN", "message": "Link 'base': 1.0 < 2.0", "element": "robot/link[@name='base']"}]
        });
        let new = json!({
            "urdf_path": "b.urdf", "overall_status": "FAIL", "schema": {"status": "WARN"},
            "statics": {"status": "FAIL", "total_mass": 9.0, "full_body_com": [0.2, 0.0, 0.2],
                "joints": [{"name": "elbow", "required_torque_gravity": 12.0, "declared_effort": 10.0, "margin": 0.83, "status": "FAIL"},
                           {"name": "wrist", "required_torque_gravity": 0.5, "declared_effort": 10.0, "margin": 20.0, "status": "PASS"}]},
            "links": [{"name": "fore", "mass": 2.0}, {"name": "hand", "mass": 0.5}],
            "findings": [{"rule": "U206", "severity": "WARN", "message": "Link 'base': 1.5 < 2.0", "element": "robot/link[@name='base']"},
                         {"rule": "U701", "severity": "FAIL", "message": "Joint 'elbow' needs 12 N·m", "element": "robot/joint[@name='elbow']/limit"}]
        });
        let diff = compare(&old, &new);
        assert!(diff.worse);
        assert_eq!(diff.findings_added.len(), 1);
        assert_eq!(diff.findings_added[0].rule, "U701");
        assert!(diff.findings_removed.is_empty());
        assert_eq!(diff.joints.len(), 1);
        assert_eq!(diff.joints[0].joint, "elbow");
        assert_eq!(diff.link_masses.len(), 1);
        assert_eq!(diff.total_mass.new, Some(9.0));
        assert!(diff
            .verdicts
            .iter()
            .any(|v| v.check == "statics" && v.worse));
        let back = compare(&new, &old);
        assert!(!back.worse);
        assert_eq!(back.findings_removed.len(), 1);
    }
}
