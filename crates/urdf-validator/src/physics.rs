//! Runs the physics analyses in order — statics at the chosen pose, classification at the reference pose,
//! stability at the chosen pose — and applies the user's declarations (`--robot-type`, `--contact-links`,
//! `--arm-root`/`--arm-tip`), keeping the heuristics as a cross-check.

use std::path::Path;

use nalgebra::Vector3;

use crate::classify::{classify, RobotType};
use crate::geometry::LinkSupports;
use crate::kinematics::{forward_kinematics, Data};
use crate::model::{LinkId, Model};
use crate::pose::{self, PoseOptions};
use crate::report::{Confidence, StabilitySection, StaticsSection};
use crate::robot::Robot;
use crate::stability_section::{self, PlacedRobot};
use crate::statics_section::{self, StaticsOptions};
use crate::suggest::did_you_mean;

/// What the user declares instead of letting heuristics guess.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    /// `--robot-type`.
    pub robot_type: Option<RobotType>,
    /// `--contact-links`.
    pub contact_links: Option<Vec<String>>,
    /// `--arm-root` (with `arm_tip`).
    pub arm_root: Option<String>,
    /// `--arm-tip` (with `arm_root`).
    pub arm_tip: Option<String>,
}

/// The physics sections of a report.
#[derive(Clone, Debug)]
pub struct Physics {
    /// Statics at the chosen pose.
    pub statics: StaticsSection,
    /// Stability at the chosen pose.
    pub stability: StabilitySection,
    /// The type the capability profile uses.
    pub robot_type: RobotType,
    /// `exact` when declared.
    pub robot_type_confidence: Confidence,
    /// What the structure shows.
    pub detected: RobotType,
    /// Why.
    pub evidence: String,
    /// Disagreements between declarations and heuristics.
    pub warnings: Vec<String>,
}

fn link_id(model: &Model, flag: &str, name: &str) -> Result<LinkId, String> {
    model.link(name).ok_or_else(|| {
        format!(
            "{flag}: unknown link '{name}' ({})",
            did_you_mean(name, model.link_names())
        )
    })
}

/// Check `--arm-root`/`--arm-tip`: both or neither, existing links, the tip below the root.
fn check_arm(model: &Model, overrides: &Overrides) -> Result<(), String> {
    match (&overrides.arm_root, &overrides.arm_tip) {
        (None, None) => Ok(()),
        (Some(_), None) | (None, Some(_)) => {
            Err("--arm-root and --arm-tip must be given together".to_string())
        }
        (Some(root), Some(tip)) => {
            let root_id = link_id(model, "--arm-root", root)?;
            let mut current = link_id(model, "--arm-tip", tip)?;
            while current != root_id {
                match model.parent_joint[current.0].and_then(|j| model.joint_links[j.0]) {
                    Some((parent, _)) => current = parent,
                    None => {
                        return Err(format!(
                        "--arm-tip '{tip}' is not below --arm-root '{root}' in the kinematic tree"
                    ))
                    }
                }
            }
            Ok(())
        }
    }
}

/// Run the analyses.
pub fn analyse(
    robot: &Robot,
    model: &Model,
    urdf_path: &Path,
    supports: &[LinkSupports],
    statics_options: &StaticsOptions,
    overrides: &Overrides,
) -> Result<Physics, String> {
    check_arm(model, overrides)?;
    let declared_contacts = match &overrides.contact_links {
        Some(names) => Some(
            names
                .iter()
                .map(|n| link_id(model, "--contact-links", n))
                .collect::<Result<Vec<_>, _>>()?,
        ),
        None => None,
    };
    let (mut statics, q) = statics_section::analyse(robot, model, urdf_path, statics_options)?;

    let reference = pose::resolve(robot, model, urdf_path, &PoseOptions::default())?;
    let mut data = Data::new(model);
    forward_kinematics(model, &reference.q, &mut data);
    let classification = classify(robot, model, &data, supports);
    let detected = classification.robot_type;
    let mut warnings = Vec::new();
    let (robot_type, confidence) = match overrides.robot_type {
        Some(declared) => {
            if declared != detected {
                warnings.push(format!(
                    "User declared --robot-type={}, but the structure suggests {} ({})",
                    declared.as_str(),
                    detected.as_str(),
                    classification.evidence
                ));
            }
            (declared, Confidence::Exact)
        }
        None => (detected, Confidence::Estimated),
    };

    forward_kinematics(model, &q, &mut data);
    let com = statics.full_body_com.map(Vector3::from);
    let placed = PlacedRobot {
        robot,
        model,
        data: &data,
        supports,
    };
    let stability = stability_section::analyse(
        &placed,
        &classification,
        robot_type,
        declared_contacts.as_deref(),
        com,
    );
    if let (Some(ground), Some(com)) = (stability.ground_height, com) {
        statics.com_height_above_ground = Some(com.z - ground);
    }
    Ok(Physics {
        statics,
        stability,
        robot_type,
        robot_type_confidence: confidence,
        detected,
        evidence: classification.evidence,
        warnings,
    })
}
