//! Structural and physical-plausibility checks over a parsed robot and its tree.
//!
//! Each submodule owns one family of rules and is a plain function of (robot, model, assets) → findings.

mod geometry;
mod inertia;
mod inertia_fix;
mod joints;
mod references;

use crate::assets::Assets;
use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::model::Model;
use crate::urdf::robot::Robot;

/// Links above this count get an INFO.
pub const MANY_LINKS: usize = 50;

/// Run every check; findings come back grouped by family, each family in document order.
pub fn run(robot: &Robot, model: &Model, assets: &Assets) -> Vec<Finding> {
    let mut findings = Vec::new();
    if robot.links.is_empty() {
        findings.push(Finding::new(
            &rules::NO_LINKS,
            robot.span,
            format!(
                "Robot '{}' has no links",
                robot
                    .name
                    .as_ref()
                    .map_or("<unnamed>", |n| n.value.as_str())
            ),
        ));
    }
    findings.extend(inertia::check(robot, model, assets));
    findings.extend(joints::check(robot, model));
    findings.extend(references::check(robot, model));
    findings.extend(geometry::check(robot, model, assets));
    if let Some((path, refusal)) = &assets.srdf_refused {
        findings.push(Finding::new(
            &rules::ACCESS_REFUSED,
            None,
            format!("refused to read the SRDF {}: {refusal}", path.display()),
        ));
    }
    if robot.links.len() > MANY_LINKS {
        findings.push(Finding::new(
            &rules::TOO_MANY_LINKS,
            robot.span,
            format!(
                "Robot has {} links (>{MANY_LINKS}) — may be slow to simulate or validate",
                robot.links.len()
            ),
        ));
    }
    findings
}
