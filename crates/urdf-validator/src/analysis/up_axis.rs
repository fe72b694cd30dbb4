//! The up axis the structure shows. A model whose legs stand on the ground only when an axis of the root
//! frame other than z points up (PyBullet's laikago: its legs hang along −y) is modelled with that axis up:
//! classified in that frame, with a WARN, while the physics keeps z up as a simulator loads the file.

use nalgebra::{Isometry3, Translation3, Vector3};

use super::classify::{classify, Classification, Leg};
use crate::assets::supports::{lowest_points, LinkSupports};
use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::model::kinematics::Data;
use crate::model::{Model, UpAxis};
use crate::urdf::robot::Robot;

/// What the structure shows when z is not up: the axis and the classification in its frame.
pub struct OtherUp {
    /// The root frame's axis that points up.
    pub axis: UpAxis,
    /// The classification with that axis up.
    pub classification: Classification,
}

/// The up axis the structure shows, when it is not the model's: only a model whose legs were found by
/// name alone (none stands on the ground with the model's up axis up) is tried with each other axis up,
/// and one where at least as many legs stand is taken (the first of the most legs). `data` holds the
/// reference pose with the model's up axis.
pub fn detect(
    robot: &Robot,
    model: &Model,
    data: &Data,
    supports: &[LinkSupports],
    found: &Classification,
) -> Option<OtherUp> {
    if !found.legs_by_name {
        return None;
    }
    let mut best: Option<OtherUp> = None;
    // −z is left out: legs pointing up at the zero pose are folded, not a model upside down.
    for axis in UpAxis::ALL
        .into_iter()
        .filter(|a| *a != model.up && *a != UpAxis::NegZ)
    {
        // Turn the whole robot so `axis` points up (relative to the model's own up axis).
        let turn = Isometry3::from_parts(
            Translation3::identity(),
            axis.rotation() * model.up.rotation().inverse(),
        );
        let turned = Data {
            link_placement: data.link_placement.iter().map(|p| turn * p).collect(),
        };
        let classification = classify(robot, model, &turned, supports);
        let stands = !classification.legs_by_name
            && classification.legs.len() >= found.legs.len()
            && classification
                .legs
                .iter()
                .all(|leg| hangs_down(model, &turned, supports, leg));
        let more = best
            .as_ref()
            .is_none_or(|b| classification.legs.len() > b.classification.legs.len());
        if stands && more {
            best = Some(OtherUp {
                axis,
                classification,
            });
        }
    }
    best
}

/// The U731 finding: what the structure shows and what it does to the verdicts.
pub fn finding(robot: &Robot, model: &Model, other: &OtherUp) -> Finding {
    let span = model
        .root
        .map_or(robot.span, |root| robot.links[root.0].span);
    let axis = other.axis.as_str();
    let letter = axis.trim_start_matches('+');
    Finding::new(
        &rules::NOT_Z_UP,
        span,
        format!(
            "the structure shows {axis} up, not z (REP 103): with {axis} up it is a {} ({}); statics, stability and workspace are computed with z up, as a simulator loads the file, so they judge the robot lying on its side",
            other.classification.robot_type.as_str(),
            other.classification.evidence
        ),
    )
    .with_help(format!(
        "re-export the model z-up, or validate it as loaded with the base rotation (`--up-axis {letter}` turns gravity for every analysis)"
    ))
}

/// Most a standing leg leans, from the joint where it leaves the body to its foot: laikago's bent legs
/// lean 40° with y up; Cassie's legs at the zero pose lean 65° with x up and do not show an up axis.
const MAX_LEAN_DEG: f64 = 45.0;

/// Whether `leg` hangs down at the placements `data`: the lowest point of its foot (its frame origin
/// without geometry) below the joint where it leaves the body, within [`MAX_LEAN_DEG`] of the vertical (the
/// legs of a model with that axis up hang straight; a leg stretched sideways at the zero pose shows no up
/// axis).
fn hangs_down(model: &Model, data: &Data, supports: &[LinkSupports], leg: &Leg) -> bool {
    let Some((_, top)) = model.joint_links[leg.top_joint.0] else {
        return false;
    };
    let hip = (data.link_placement[top.0] * model.joint_data[leg.top_joint.0].placement)
        .translation
        .vector;
    let placement = &data.link_placement[leg.foot.0];
    let foot = supports
        .get(leg.foot.0)
        .and_then(|s| lowest_points(&s.shapes, placement, 0.0))
        .and_then(|(_, points)| {
            let n = points.len() as f64;
            (n > 0.0).then(|| points.iter().sum::<Vector3<f64>>() / n)
        })
        .unwrap_or(placement.translation.vector);
    let down = hip - foot;
    down.norm() > 0.0 && down.z >= down.norm() * MAX_LEAN_DEG.to_radians().cos()
}
