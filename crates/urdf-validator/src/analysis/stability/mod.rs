//! Builds the report's `stability` section: finds the ground contacts at the evaluated pose, builds the
//! support polygon, and measures the centre of mass against it. Which robots it applies to comes from the
//! capability profile of the robot type.

mod section;
pub(crate) mod support_polygon;

pub use section::{ContactPoint, RaisedContact, StabilitySection};

use nalgebra::Vector3;

use crate::analysis::classify::{Classification, RobotType};
use crate::analysis::stability::support_polygon::{
    convex_hull, degenerate_width, direction_name, is_polygon, margin, min_width, tipping_angle,
    Point2,
};
use crate::assets::supports::{lowest_points, LinkSupports};
use crate::diagnostics::{rules, Confidence, Finding, Status};
use crate::model::kinematics::Data;
use crate::model::{LinkId, Model};
use crate::urdf::robot::{Geometry, Robot};

/// Contacts more than this above the lowest one do not support the robot (the robot rocks), metres.
pub const SUPPORT_TOLERANCE: f64 = 0.005;
/// Points of one link within this of its lowest point all touch (a flat foot), metres.
const FLAT_TOLERANCE: f64 = 0.002;
/// Contact candidates must come this close to the lowest geometry of the robot, metres.
const CANDIDATE_TOLERANCE: f64 = 0.05;

/// How the contact links were chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Source {
    Declared,
    Wheels,
    Feet,
    LowestGeometry,
}

impl Source {
    fn as_str(self) -> &'static str {
        match self {
            Source::Declared => "declared",
            Source::Wheels => "wheels",
            Source::Feet => "feet",
            Source::LowestGeometry => "lowest_geometry",
        }
    }
}

/// The capability profile: why stability does not apply to a robot type, if it does not.
pub fn not_applicable_reason(robot_type: RobotType) -> Option<String> {
    match robot_type {
        RobotType::ArmOnly => Some(
            "robot type 'arm_only' is a fixed-base arm: no ground contact to tip over".to_string(),
        ),
        RobotType::Aerial => Some("robot type 'aerial' has no ground contact".to_string()),
        RobotType::Object => Some(
            "robot type 'object' has no movable joint: nothing to tip over actively".to_string(),
        ),
        _ => None,
    }
}

/// True when the link's name says it is a wheel or a caster.
pub(crate) fn is_named_caster_or_wheel(robot: &Robot, link: LinkId) -> bool {
    let name = robot.links[link.0].name.value.to_ascii_lowercase();
    name.contains("wheel") || name.contains("caster") || name.contains("castor")
}

fn is_caster_or_wheel(robot: &Robot, link: LinkId) -> bool {
    if is_named_caster_or_wheel(robot, link) {
        return true;
    }
    let link = &robot.links[link.0];
    // The spec's geometric pass: a cylinder with a wheel-like radius-to-length ratio.
    link.collisions.iter().filter_map(|s| s.geometry.as_ref()).any(|g| {
        matches!(g.value, Geometry::Cylinder { radius, length } if length > 0.0 && radius / length > 0.3)
    })
}

/// A robot placed at one configuration, with its link shapes.
pub struct PlacedRobot<'a> {
    /// The parsed robot.
    pub robot: &'a Robot,
    /// Its tree.
    pub model: &'a Model,
    /// Link placements at the configuration.
    pub data: &'a Data,
    /// Each link's shapes.
    pub supports: &'a [LinkSupports],
}

/// Analyse stability of `placed`, a robot of `robot_type` whose centre of mass is `com`.
pub fn analyse(
    placed: &PlacedRobot,
    classification: &Classification,
    robot_type: RobotType,
    declared_contacts: Option<&[LinkId]>,
    com: Option<Vector3<f64>>,
) -> StabilitySection {
    let PlacedRobot {
        robot,
        data,
        supports,
        ..
    } = *placed;
    let mut section = StabilitySection {
        status: Status::Unknown,
        stable: None,
        margin_mm: None,
        tip_direction: None,
        com_height_ratio: None,
        com_height_ratio_confidence: Confidence::Missing,
        com_height_ratio_class: None,
        tipping_angle_deg: None,
        contact_confidence: if declared_contacts.is_some() {
            Confidence::Exact
        } else {
            Confidence::Estimated
        },
        contact_source: None,
        contact_links: Vec::new(),
        contact_points: Vec::new(),
        support_polygon: Vec::new(),
        ground_height: None,
        com_height: None,
        raised_contacts: Vec::new(),
        reason: None,
    };
    if declared_contacts.is_none() {
        if let Some(reason) = not_applicable_reason(robot_type) {
            section.status = Status::NotApplicable;
            section.reason = Some(reason);
            return section;
        }
    }
    if placed.model.gravity == Vector3::zeros() {
        section.status = Status::NotApplicable;
        section.reason = Some("the model has no gravity: nothing tips over".to_string());
        return section;
    }
    let (source, mut candidates) =
        contact_candidates(placed, classification, robot_type, declared_contacts);
    if source != Source::Declared {
        // Whatever else touches the ground supports too (a base mesh with built-in casters).
        let extra: Vec<LinkId> = touching(placed, &candidates)
            .into_iter()
            .filter(|l| !candidates.contains(l))
            .collect();
        candidates.extend(extra);
    }
    section.contact_source = Some(source.as_str().to_string());
    // Each candidate link's lowest points (all of a flat foot's corners).
    // A foot without shapes touches at its frame origin.
    let contacts: Vec<(LinkId, f64, Vec<Vector3<f64>>)> = candidates
        .iter()
        .map(|&l| {
            match lowest_points(
                &supports[l.0].shapes,
                &data.link_placement[l.0],
                FLAT_TOLERANCE,
            ) {
                Some((z, pts)) => (l, z, pts),
                None => {
                    let origin = data.link_placement[l.0].translation.vector;
                    (l, origin.z, vec![origin])
                }
            }
        })
        .collect();
    let Some(ground) = contacts.iter().map(|c| c.1).min_by(f64::total_cmp) else {
        section.reason = Some(
            "no contact geometry found (no collision or visual shapes on the candidate links)"
                .to_string(),
        );
        return section;
    };
    section.ground_height = Some(ground);
    let mut points: Vec<Point2> = Vec::new();
    for (link, z, pts) in &contacts {
        let name = robot.links[link.0].name.value.clone();
        if z - ground > SUPPORT_TOLERANCE {
            // A caster housing above its wheels is not a raised contact; a wheel in the air is.
            let carried = contacts.iter().any(|(other, oz, _)| {
                *oz - ground <= SUPPORT_TOLERANCE && is_below(placed.model, *other, *link)
            });
            if !carried {
                section.raised_contacts.push(RaisedContact {
                    link: name,
                    height_mm: 1000.0 * (z - ground),
                });
            }
            continue;
        }
        let supporting: Vec<Point2> = pts
            .iter()
            .filter(|p| p.z - ground <= SUPPORT_TOLERANCE)
            .map(|p| [p.x, p.y])
            .collect();
        if let Some(position) = mean_mm(&supporting) {
            section.contact_points.push(ContactPoint {
                link: name.clone(),
                position,
            });
        }
        points.extend(supporting);
        section.contact_links.push(name);
    }
    let hull = convex_hull(&points);
    section.support_polygon = hull.clone();
    let Some(com) = com else {
        section.reason = Some("no link declares a mass: the centre of mass is unknown".to_string());
        return section;
    };
    let height = com.z - ground;
    section.com_height = Some(height);
    if !is_polygon(&hull) {
        let on_a_line = if hull.len() >= 3 {
            format!(
                " (they lie on a line: the polygon is {:.3} mm wide)",
                1000.0 * degenerate_width(&hull)
            )
        } else {
            String::new()
        };
        let balancing = match robot_type {
            t if t.is_legged() => " (a walking robot balances actively)",
            RobotType::Wheeled | RobotType::GroundVehicle if section.contact_links.len() <= 2 => {
                " (a two-wheeled robot balances actively)"
            }
            _ => "",
        };
        section.reason = Some(format!(
            "{} supporting contact point(s) on {} link(s) do not span an area{on_a_line}: static stability needs at least 3 supports off one line{balancing}",
            points.len(),
            section.contact_links.len(),
        ));
        return section;
    }
    let centre = [com.x, com.y];
    if let Some(m) = margin(&hull, centre) {
        section.margin_mm = Some(1000.0 * m.distance);
        section.tip_direction = Some(direction_name(m.tip_normal).to_string());
        section.stable = Some(m.distance > 0.0);
        section.status = if m.distance > 0.0 {
            Status::Pass
        } else {
            Status::Fail
        };
    }
    section.tipping_angle_deg = tipping_angle(&hull, centre, height).map(f64::to_degrees);
    if let Some(width) = min_width(&hull).filter(|w| *w > 0.0) {
        let ratio = height / width;
        section.com_height_ratio = Some(ratio);
        section.com_height_ratio_confidence = Confidence::Estimated;
        section.com_height_ratio_class = Some(ratio_class(ratio).to_string());
    }
    section
}

/// The findings that explain a stability verdict: FAIL when the robot tips over, WARN when stability
/// applies but could not be computed. They point at the root link (contacts are named in the message).
pub fn findings(robot: &Robot, model: &Model, section: &StabilitySection) -> Vec<Finding> {
    let span = model
        .root
        .map_or(robot.span, |root| robot.links[root.0].span);
    let contacts = if section.contact_links.is_empty() {
        String::new()
    } else {
        format!(" on {}", section.contact_links.join(", "))
    };
    match section.status {
        Status::Fail => vec![Finding::new(
            &rules::ROBOT_TIPS_OVER,
            span,
            format!(
                "The robot tips over{}: its centre of mass projects {:.1} mm outside the support polygon{contacts}",
                section
                    .tip_direction
                    .as_deref()
                    .map_or(String::new(), |d| format!(" to the {d}")),
                -section.margin_mm.unwrap_or(0.0)
            ),
        )],
        Status::Unknown => vec![Finding::new(
            &rules::STABILITY_NOT_ASSESSED,
            span,
            format!(
                "Stability could not be computed: {}",
                section.reason.as_deref().unwrap_or("no result")
            ),
        )],
        _ => Vec::new(),
    }
}

/// The mean of `points`, rounded to the millimetre (`None` for no points).
fn mean_mm(points: &[Point2]) -> Option<Point2> {
    if points.is_empty() {
        return None;
    }
    let n = points.len() as f64;
    let mm = |v: f64| (v * 1000.0).round() / 1000.0;
    let sum = points
        .iter()
        .fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
    Some([mm(sum[0] / n), mm(sum[1] / n)])
}

/// The spec's classes of COM height over support width.
pub fn ratio_class(ratio: f64) -> &'static str {
    match ratio {
        r if r < 0.5 => "very_stable",
        r if r < 1.0 => "stable",
        r if r < 2.0 => "manageable",
        r if r < 3.0 => "requires_active_balancing",
        _ => "will_fall",
    }
}

/// Candidate contact links: declared; else wheels and casters (wheeled robots); else feet (legged robots);
/// else whatever geometry is lowest. Only links near the ground are candidates.
fn contact_candidates(
    placed: &PlacedRobot,
    classification: &Classification,
    robot_type: RobotType,
    declared: Option<&[LinkId]>,
) -> (Source, Vec<LinkId>) {
    let PlacedRobot {
        robot,
        model,
        data,
        supports,
    } = *placed;
    if let Some(links) = declared {
        return (Source::Declared, links.to_vec());
    }
    if robot_type.is_legged() && !classification.legs.is_empty() {
        return (
            Source::Feet,
            classification.legs.iter().map(|leg| leg.foot).collect(),
        );
    }
    let lowest: Vec<(LinkId, f64)> = model
        .topological_order
        .iter()
        .filter_map(|&l| {
            lowest_points(&supports[l.0].shapes, &data.link_placement[l.0], 0.0)
                .map(|(z, _)| (l, z))
        })
        .collect();
    let Some(floor) = lowest.iter().map(|x| x.1).min_by(f64::total_cmp) else {
        return (Source::LowestGeometry, Vec::new());
    };
    let near: Vec<LinkId> = lowest
        .iter()
        .filter(|x| x.1 <= floor + CANDIDATE_TOLERANCE)
        .map(|x| x.0)
        .collect();
    match robot_type {
        RobotType::Wheeled | RobotType::GroundVehicle => {
            let wheels: Vec<LinkId> = near
                .iter()
                .copied()
                .filter(|&l| classification.wheels.contains(&l) || is_caster_or_wheel(robot, l))
                .collect();
            if wheels.len() >= 2 {
                return (Source::Wheels, wheels);
            }
        }
        _ => {}
    }
    let lowest_links: Vec<LinkId> = lowest
        .iter()
        .filter(|x| x.1 <= floor + SUPPORT_TOLERANCE)
        .map(|x| x.0)
        .collect();
    (Source::LowestGeometry, lowest_links)
}

/// Links whose lowest point is within the support tolerance of the lowest point of `candidates`.
fn touching(placed: &PlacedRobot, candidates: &[LinkId]) -> Vec<LinkId> {
    let lowest = |l: LinkId| {
        lowest_points(
            &placed.supports[l.0].shapes,
            &placed.data.link_placement[l.0],
            0.0,
        )
        .map(|(z, _)| z)
    };
    let Some(ground) = candidates
        .iter()
        .filter_map(|&l| lowest(l))
        .min_by(f64::total_cmp)
    else {
        return Vec::new();
    };
    placed
        .model
        .topological_order
        .iter()
        .copied()
        .filter(|&l| lowest(l).is_some_and(|z| z <= ground + SUPPORT_TOLERANCE))
        .collect()
}

/// True when `link` hangs somewhere below `ancestor`.
fn is_below(model: &Model, link: LinkId, ancestor: LinkId) -> bool {
    let mut current = link;
    for _ in 0..model.parent_joint.len() {
        match model.parent_joint[current.0].and_then(|j| model.joint_links[j.0]) {
            Some((parent, _)) if parent == ancestor => return true,
            Some((parent, _)) => current = parent,
            None => return false,
        }
    }
    false
}
