//! Cross-references outside the tree: transmissions, `<gazebo reference>`, `<ros2_control>` joints, materials.

use std::collections::HashSet;

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::diagnostics::suggest::did_you_mean;
use crate::model::Model;
use crate::urdf::robot::Robot;

pub(super) fn check(robot: &Robot, model: &Model) -> Vec<Finding> {
    let mut findings = Vec::new();
    let joint_help = |name: &str| did_you_mean(name, model.joint_names());
    for transmission in &robot.transmissions {
        let label = transmission.name.as_deref().unwrap_or("<unnamed>");
        for joint in transmission
            .joints
            .iter()
            .filter(|j| model.joint(&j.value).is_none())
        {
            findings.push(
                Finding::new(
                    &rules::TRANSMISSION_UNDEFINED_JOINT,
                    joint.span,
                    format!(
                        "Transmission '{label}' names joint '{}', which does not exist",
                        joint.value
                    ),
                )
                .with_help(joint_help(&joint.value)),
            );
        }
    }
    for block in &robot.ros2_control {
        let label = block.name.as_deref().unwrap_or("<unnamed>");
        for joint in block
            .joints
            .iter()
            .filter(|j| model.joint(&j.value).is_none())
        {
            findings.push(
                Finding::new(
                    &rules::ROS2_CONTROL_UNDEFINED_JOINT,
                    joint.span,
                    format!(
                        "ros2_control '{label}' names joint '{}', which does not exist",
                        joint.value
                    ),
                )
                .with_help(joint_help(&joint.value)),
            );
        }
    }
    for block in &robot.gazebo {
        let Some(reference) = &block.reference else {
            continue;
        };
        if model.link(&reference.value).is_none() && model.joint(&reference.value).is_none() {
            findings.push(
                Finding::new(
                    &rules::GAZEBO_UNDEFINED_REFERENCE,
                    reference.span,
                    format!(
                        "<gazebo reference='{}'> names no link or joint",
                        reference.value
                    ),
                )
                .with_help(did_you_mean(
                    &reference.value,
                    model.link_names().chain(model.joint_names()),
                )),
            );
        }
    }
    // urdfdom adds a material defined inline in any visual to the robot's materials.
    let inline = robot
        .links
        .iter()
        .flat_map(|l| &l.visuals)
        .filter_map(|v| v.material.as_ref())
        .filter(|m| m.defines_appearance)
        .filter_map(|m| m.name.as_deref());
    let defined: HashSet<&str> = robot
        .materials
        .iter()
        .map(|m| m.name.value.as_str())
        .chain(inline)
        .collect();
    for link in &robot.links {
        for material in link.visuals.iter().filter_map(|v| v.material.as_ref()) {
            let Some(name) = &material.name else { continue };
            if !material.defines_appearance && !defined.contains(name.as_str()) {
                findings.push(Finding::new(
                    &rules::UNDEFINED_MATERIAL,
                    material.span,
                    format!(
                        "Link '{}': material '{name}' is not defined and gives no colour",
                        link.name.value
                    ),
                ));
            }
        }
    }
    findings
}
