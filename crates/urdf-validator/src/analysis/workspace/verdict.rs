//! The findings that explain the workspace's verdicts: the task out of reach or tipping the robot over,
//! a rare orientation, frequent self-collision, and a requested task that could not be checked.

use crate::analysis::arms::Arm;
use crate::analysis::workspace::{
    WorkspaceOptions, WorkspaceSection, COLLISION_FREE_PASS_FRACTION, ORIENTATION_PASS_FRACTION,
};
use crate::diagnostics::span::Span;
use crate::diagnostics::{rules, Finding, Section, Status};
use crate::model::Model;
use crate::urdf::robot::Robot;

/// The findings of `section`, computed for `arms`. `stability_applies` is false for robots without
/// ground contacts (fixed-base arms, aerial robots): no support polygon is then expected.
pub fn findings(
    robot: &Robot,
    model: &Model,
    arms: &[Arm],
    section: &WorkspaceSection,
    options: &WorkspaceOptions,
    stability_applies: bool,
) -> Vec<Finding> {
    // The first joint of the first arm: where an arm's verdict points.
    let arm_span: Span = arms
        .iter()
        .find_map(|arm| arm.first_joint(model))
        .map_or(robot.span, |j| robot.joints[j.0].span);
    let mut findings = Vec::new();
    if section.status == Status::NotApplicable {
        let asked: Vec<String> = options
            .task
            .map(|t| format!("--task {}", t.name()))
            .into_iter()
            .chain(
                options
                    .orientation
                    .map(|o| format!("--orientation {}", o.label())),
            )
            .collect();
        if !asked.is_empty() {
            findings.push(
                Finding::new(
                    &rules::REQUESTED_CHECK_NOT_RUN,
                    robot.span,
                    format!(
                        "{}: {}",
                        asked.join(" "),
                        section.reason.as_deref().unwrap_or("no arm to reach with")
                    ),
                )
                .in_section(Section::Workspace),
            );
        }
        return findings;
    }
    if let Some(task) = options.task {
        task_findings(
            arm_span,
            section,
            task.name(),
            stability_applies,
            &mut findings,
        );
    }
    if section.orientation_reachable == Some(false) {
        findings.push(Finding::new(
            &rules::ORIENTATION_RARELY_REACHED,
            arm_span,
            format!(
                "Orientation {} is met by {:.1}% of the sampled poses{} (< {:.0}%)",
                section.orientation.as_deref().unwrap_or_default(),
                section.orientation_fraction.unwrap_or_default() * 100.0,
                options
                    .task
                    .map_or(String::new(), |t| format!(" at the {} height", t.name())),
                ORIENTATION_PASS_FRACTION * 100.0
            ),
        ));
    }
    collision_finding(robot, section, &mut findings);
    findings
}

/// The task out of reach, tipping the robot over, or not checked.
fn task_findings(
    arm_span: Span,
    section: &WorkspaceSection,
    task: &str,
    stability_applies: bool,
    findings: &mut Vec<Finding>,
) {
    let height = section.task_target_height_m.unwrap_or_default();
    if section.task_height_reachable == Some(false) {
        let nearest = section
            .arms
            .iter()
            .map(|a| {
                format!(
                    "'{}' {:.2}–{:.2} m",
                    a.tip_link, a.lowest_tip_height, a.vertical_reach
                )
            })
            .collect::<Vec<_>>();
        findings.push(Finding::new(
            &rules::TASK_UNREACHABLE,
            arm_span,
            format!(
                "No arm reaches the {task} height ({height:.2} m above the ground){}",
                if nearest.is_empty() {
                    String::new()
                } else {
                    format!(": sampled tip heights {}", nearest.join(", "))
                }
            ),
        ));
    }
    match (
        section.task_com_stable_during_reach,
        section.task_com_worst_margin_mm,
    ) {
        (Some(false), _) => findings.push(Finding::new(
            &rules::TASK_TIPS_OVER,
            arm_span,
            format!(
                "Reaching for the {task} height tips the robot over: the centre of mass ends {:.1} mm outside the support polygon",
                -section.task_com_margin_mm.unwrap_or_default()
            ),
        )),
        (Some(true), Some(worst)) if worst < 0.0 => findings.push(Finding::new(
            &rules::TASK_TIPS_SOMETIMES,
            arm_span,
            format!(
                "Some sampled poses at the {task} height tip the robot over (worst: centre of mass {:.1} mm outside the support polygon)",
                -worst
            ),
        )),
        _ => {}
    }
    // The COM during the reach is part of the task check where the robot stands on the ground.
    if let (Some(why), true, Some(true)) = (
        &section.task_com_not_assessed,
        stability_applies,
        section.task_height_reachable,
    ) {
        findings.push(
            Finding::new(
                &rules::REQUESTED_CHECK_NOT_RUN,
                arm_span,
                format!(
                    "--task {task}: the centre of mass during the reach was not checked: {why}"
                ),
            )
            .in_section(Section::Workspace),
        );
    }
}

/// WARN when fewer than 95% of the sampled poses are free of self-collision, at the worst pair's
/// collision geometry.
fn collision_finding(robot: &Robot, section: &WorkspaceSection, findings: &mut Vec<Finding>) {
    let Some(free) = section
        .self_collision_free_fraction
        .filter(|f| *f < COLLISION_FREE_PASS_FRACTION)
    else {
        return;
    };
    let pair = section.self_collision_worst_pair.as_ref();
    let span = pair
        .and_then(|[_, b]| robot.links.iter().find(|l| &l.name.value == b))
        .map_or(robot.span, |link| {
            link.collisions.first().map_or(link.span, |c| c.span)
        });
    findings.push(Finding::new(
        &rules::SELF_COLLISION_FREQUENT,
        span,
        format!(
            "{:.1}% of the sampled arm poses are free of self-collision (< {:.0}%){}",
            free * 100.0,
            COLLISION_FREE_PASS_FRACTION * 100.0,
            pair.map_or(String::new(), |[a, b]| format!(
                "; most often '{a}' × '{b}'"
            ))
        ),
    ));
}
