//! One pose of the robot for the 3-D view: the link placements (forward kinematics) and the overlays the
//! report's statics and stability code computes at that pose (centre of mass, support polygon, margin and
//! tip direction, each joint's gravity torque against its effort). No physics of its own: the same
//! functions the report's sections come from, at the configuration asked for.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::analysis::classify::{classify, Classification, RobotType};
use crate::analysis::pose::{PoseKind, PoseOptions};
use crate::analysis::stability::{self, PlacedRobot};
use crate::analysis::statics::{self, StaticsOptions};
use crate::assets::Assets;
use crate::model::kinematics::forward_kinematics;
use crate::model::{Data, LinkId};
use crate::{Inspection, Options};

/// The links and overlays at one pose.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PoseView {
    /// The value of every independent actuated joint (rad or m), clamped into its limits.
    pub configuration: BTreeMap<String, f64>,
    /// Each link's placement (indexed like the scene's links): x, y, z, quaternion x, y, z, w.
    pub links: Vec<[f64; 7]>,
    /// Full-body centre of mass, root frame, metres.
    pub com: Option<[f64; 3]>,
    /// Support polygon (counter-clockwise), ground plane, metres.
    pub support_polygon: Vec<[f64; 2]>,
    /// Height of the ground, metres.
    pub ground: Option<f64>,
    /// Stability status (PASS, FAIL, UNKNOWN, N/A).
    pub stability: String,
    /// Signed distance from the COM's projection to the polygon's boundary, mm (positive inside).
    pub margin_mm: Option<f64>,
    /// Where the robot would tip.
    pub tip_direction: Option<String>,
    /// Statics status.
    pub statics: String,
    /// Each actuated joint's gravity load.
    pub joints: Vec<JointLoad>,
}

/// One actuated joint's gravity torque against its effort limit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct JointLoad {
    /// The joint.
    pub name: String,
    /// Torque (N·m, N for prismatic) to hold the pose.
    pub torque: Option<f64>,
    /// `<limit effort>`.
    pub effort: Option<f64>,
    /// Effort over |torque|.
    pub margin: Option<f64>,
    /// PASS ≥ 1.5, WARN 1–1.5, FAIL < 1, else UNKNOWN or N/A.
    pub status: String,
}

/// What evaluates poses of one inspected robot: the inspection, its classification at the reference pose
/// and the run's options (payload, declared contacts).
#[derive(Debug)]
pub struct Poser {
    inspection: Inspection,
    classification: Option<Classification>,
    robot_type: Option<RobotType>,
    contacts: Option<Vec<LinkId>>,
    statics: StaticsOptions,
}

impl Poser {
    /// Prepare the poses of `inspection`, validated with `options`.
    pub fn new(inspection: Inspection, options: &Options) -> Poser {
        let (robot, model) = (&inspection.robot, &inspection.model);
        let classification = inspection.assets.as_ref().map(|assets: &Assets| {
            let mut data = Data::new(model);
            let q = reference_q(&inspection);
            forward_kinematics(model, &q, &mut data);
            classify(robot, model, &data, &assets.supports)
        });
        let contacts = options.overrides.contact_links.as_ref().map(|names| {
            names
                .iter()
                .filter_map(|n| model.link(n))
                .collect::<Vec<_>>()
        });
        Poser {
            robot_type: inspection.validation.report.robot_type,
            inspection,
            classification,
            contacts,
            statics: options.statics.clone(),
        }
    }

    /// The inspected robot.
    pub fn inspection(&self) -> &Inspection {
        &self.inspection
    }

    /// The inspected robot, handed back.
    pub fn into_inspection(self) -> Inspection {
        self.inspection
    }

    /// The report's pose: the statics section's configuration.
    pub fn reference(&self) -> BTreeMap<String, f64> {
        self.inspection
            .validation
            .report
            .statics
            .as_ref()
            .map(|s| s.configuration.clone())
            .unwrap_or_default()
    }

    /// The placements and overlays with the joints at `values` (by name; unknown names and values that are
    /// not finite are left out, the other joints keep the report's pose), each clamped into its limits.
    pub fn evaluate(&self, values: &BTreeMap<String, f64>) -> PoseView {
        let Inspection { robot, model, .. } = &self.inspection;
        let mut asked = self.reference();
        for (name, value) in values.iter().filter(|(_, v)| v.is_finite()) {
            let Some(joint) = model.joint(name) else {
                continue;
            };
            let data = &model.joint_data[joint.0];
            if !data.is_actuated() || model.mimic[joint.0].is_some() {
                continue;
            }
            // (max then min: inverted limits, a finding of their own, must not panic here)
            let value = match data.range() {
                Some((lo, hi)) => value.max(lo).min(hi),
                None => *value,
            };
            asked.insert(name.clone(), value);
        }
        let text = asked
            .iter()
            .map(|(name, value)| format!("{name}={value}"))
            .collect::<Vec<_>>()
            .join(",");
        let options = StaticsOptions {
            pose: PoseOptions {
                kind: PoseKind::Custom,
                joint_angles: Some(text),
                ..self.statics.pose.clone()
            },
            ..self.statics.clone()
        };
        let srdf = self
            .inspection
            .assets
            .as_ref()
            .and_then(|a| a.srdf.as_ref());
        let outcome = statics::analyse(robot, model, srdf, &options).ok();
        let mut q = outcome
            .as_ref()
            .map_or_else(|| model.zero_configuration(), |o| o.q.clone());
        model.apply_mimic(&mut q);
        let mut data = Data::new(model);
        forward_kinematics(model, &q, &mut data);
        let links = data
            .link_placement
            .iter()
            .map(|p| {
                let (t, r) = (p.translation.vector, p.rotation.coords);
                [t.x, t.y, t.z, r.x, r.y, r.z, r.w]
            })
            .collect();
        let section = outcome.as_ref().map(|o| &o.section);
        let com = section.and_then(|s| s.full_body_com);
        let stability = match (
            &self.classification,
            self.robot_type,
            &self.inspection.assets,
        ) {
            (Some(classification), Some(robot_type), Some(assets)) => Some(stability::analyse(
                &PlacedRobot {
                    robot,
                    model,
                    data: &data,
                    supports: &assets.supports,
                },
                classification,
                robot_type,
                self.contacts.as_deref(),
                com.map(nalgebra::Vector3::from),
            )),
            _ => None,
        };
        PoseView {
            configuration: section.map(|s| s.configuration.clone()).unwrap_or(asked),
            links,
            com,
            support_polygon: stability
                .as_ref()
                .map(|s| s.support_polygon.clone())
                .unwrap_or_default(),
            ground: stability.as_ref().and_then(|s| s.ground_height),
            stability: stability
                .as_ref()
                .map_or("UNKNOWN", |s| s.status.label())
                .to_string(),
            margin_mm: stability.as_ref().and_then(|s| s.margin_mm),
            tip_direction: stability.as_ref().and_then(|s| s.tip_direction.clone()),
            statics: section.map_or("UNKNOWN", |s| s.status.label()).to_string(),
            joints: section
                .map(|s| {
                    s.joints
                        .iter()
                        .map(|j| JointLoad {
                            name: j.name.clone(),
                            torque: j.required_torque_gravity,
                            effort: j.declared_effort,
                            margin: j.margin,
                            status: j.status.label().to_string(),
                        })
                        .collect()
                })
                .unwrap_or_default(),
        }
    }
}

/// The report's configuration as a full joint vector (zero for joints it does not list, mimic applied).
fn reference_q(inspection: &Inspection) -> Vec<f64> {
    let model = &inspection.model;
    let mut q = model.zero_configuration();
    if let Some(statics) = &inspection.validation.report.statics {
        for (name, value) in &statics.configuration {
            if let Some(joint) = model.joint(name) {
                q[joint.0] = *value;
            }
        }
    }
    model.apply_mimic(&mut q);
    q
}
