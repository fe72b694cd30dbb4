//! Per-link mass data and the counts behind `[PHYSICS]` and the report's confidence level.

use crate::model::{LinkId, Model};
use schemars::JsonSchema;
use serde::Serialize;

use crate::diagnostics::{Confidence, ConfidenceLevel};
use crate::input::Format;
use crate::urdf::robot::{Link, Robot};

/// A pure frame: nothing physical on it, and attached rigidly (by a fixed joint, or as the root); in MJCF
/// any link without mass or shapes, since the reader makes them to chain one body's joints (MuJoCo's body
/// has no such part, so nothing is missing from it).
pub fn is_frame(robot: &Robot, model: &Model, link: LinkId) -> bool {
    robot.links[link.0].is_bare() && (robot.format == Format::Mjcf || !model.is_moving(robot, link))
}

fn finite_mass(link: &Link) -> Option<f64> {
    link.inertial
        .as_ref()?
        .mass
        .as_ref()
        .map(|m| m.value)
        .filter(|m| m.is_finite())
}

fn finite_inertia(link: &Link) -> Option<[f64; 9]> {
    let tensor = link.inertial.as_ref()?.inertia.as_ref()?.matrix();
    let flat = [
        tensor[0][0],
        tensor[0][1],
        tensor[0][2],
        tensor[1][0],
        tensor[1][1],
        tensor[1][2],
        tensor[2][0],
        tensor[2][1],
        tensor[2][2],
    ];
    flat.iter().all(|v| v.is_finite()).then_some(flat)
}

fn label<T>(value: &Option<T>) -> Confidence {
    if value.is_some() {
        Confidence::Exact
    } else {
        Confidence::Missing
    }
}

/// The `links` entries, in document order.
pub fn link_reports(robot: &Robot, model: &Model) -> Vec<LinkReport> {
    robot
        .links
        .iter()
        .enumerate()
        .map(|(i, link)| {
            let mass = finite_mass(link);
            let inertia_tensor = finite_inertia(link);
            let com_offset = link
                .inertial
                .as_ref()
                .map(|inertial| inertial.origin.xyz)
                .filter(|xyz| xyz.iter().all(|v| v.is_finite()));
            LinkReport {
                name: link.name.value.clone(),
                frame: is_frame(robot, model, LinkId(i)),
                mass_confidence: label(&mass),
                mass,
                inertia_confidence: label(&inertia_tensor),
                inertia_tensor,
                com_confidence: label(&com_offset),
                com_offset,
            }
        })
        .collect()
}

/// Counts over the link reports.
pub fn summarize(links: &[LinkReport]) -> PhysicsSummary {
    let bodies = links.iter().filter(|l| !l.frame);
    let mut summary = PhysicsSummary {
        links: links.len(),
        frames: links.len() - bodies.clone().count(),
        ..Default::default()
    };
    for link in bodies {
        if link.mass.is_some() {
            summary.mass_exact += 1;
        } else {
            summary.mass_missing += 1;
        }
        if link.inertia_tensor.is_some() {
            summary.inertia_exact += 1;
        } else {
            summary.inertia_missing += 1;
        }
    }
    summary
}

/// HIGH: every body link declares mass and inertia; MEDIUM: at least half declare a mass; LOW otherwise.
pub fn confidence_level(summary: &PhysicsSummary) -> ConfidenceLevel {
    let bodies = summary.mass_exact + summary.mass_missing;
    if bodies > 0 && summary.mass_missing == 0 && summary.inertia_missing == 0 {
        ConfidenceLevel::High
    } else if bodies > 0 && 2 * summary.mass_exact >= bodies {
        ConfidenceLevel::Medium
    } else {
        ConfidenceLevel::Low
    }
}

/// Mass-data counts over the links (frames are counted apart, not as missing mass).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, JsonSchema)]
pub struct PhysicsSummary {
    /// All links.
    pub links: usize,
    /// Pure frames: no inertial, no geometry, fixed to their parent (or the root); in MJCF, every link
    /// without mass or geometry (the links chaining one body's joints).
    pub frames: usize,
    /// Non-frame links declaring a finite mass.
    pub mass_exact: usize,
    /// Non-frame links without a usable mass.
    pub mass_missing: usize,
    /// Non-frame links declaring a finite inertia tensor.
    pub inertia_exact: usize,
    /// Non-frame links without a usable inertia tensor.
    pub inertia_missing: usize,
}

/// One entry of `links`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct LinkReport {
    /// Link name.
    pub name: String,
    /// True for a pure frame link.
    pub frame: bool,
    /// Declared mass in kg.
    pub mass: Option<f64>,
    /// `exact` when declared, else `missing`.
    pub mass_confidence: Confidence,
    /// Row-major 3×3 inertia tensor in kg·m², about the inertial frame.
    pub inertia_tensor: Option<[f64; 9]>,
    /// `exact` when declared, else `missing`.
    pub inertia_confidence: Confidence,
    /// Centre of mass in the link frame (the `<inertial><origin xyz>`, zero when omitted), metres.
    pub com_offset: Option<[f64; 3]>,
    /// `exact` when the link has an inertial, else `missing`.
    pub com_confidence: Confidence,
}
