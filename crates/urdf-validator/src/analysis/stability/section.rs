//! The `stability` section of the report.

use schemars::JsonSchema;
use serde::Serialize;

use crate::diagnostics::{Confidence, Status};

/// The `stability` section: the support polygon and where the centre of mass sits over it.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct StabilitySection {
    /// PASS when the COM projects inside the support polygon, FAIL outside, UNKNOWN when there is no
    /// polygon or no COM, N/A for fixed-base, aerial and object (nothing moves) descriptions.
    pub status: Status,
    /// True when the COM projects inside the polygon.
    pub stable: Option<bool>,
    /// Signed distance from the COM projection to the polygon boundary, mm (positive inside).
    pub margin_mm: Option<f64>,
    /// Where the robot would tip: front, front-left, left, back-left, back, back-right, right, front-right.
    pub tip_direction: Option<String>,
    /// COM height above the ground over the polygon's minimum width.
    pub com_height_ratio: Option<f64>,
    /// Confidence of the ratio.
    pub com_height_ratio_confidence: Confidence,
    /// very_stable < 0.5 ≤ stable < 1 ≤ manageable < 2 ≤ requires_active_balancing < 3 ≤ will_fall.
    pub com_height_ratio_class: Option<String>,
    /// Smallest tilt that brings the COM over an edge: min over edges of atan(d / h), degrees.
    pub tipping_angle_deg: Option<f64>,
    /// `exact` with `--contact-links`, else `estimated`.
    pub contact_confidence: Confidence,
    /// How contacts were found: declared, wheels, feet, lowest_geometry.
    pub contact_source: Option<String>,
    /// Links touching the ground (supporting).
    pub contact_links: Vec<String>,
    /// Where each supporting link touches the ground: the mean of its supporting points, in the order of
    /// `contact_links` (for plots; the polygon is built from every point, not from these).
    pub contact_points: Vec<ContactPoint>,
    /// Counter-clockwise support polygon in the root frame's ground plane, metres.
    pub support_polygon: Vec<[f64; 2]>,
    /// Height of the ground (the lowest contact) in the root frame, metres.
    pub ground_height: Option<f64>,
    /// COM height above the ground, metres.
    pub com_height: Option<f64>,
    /// Contact candidates more than 5 mm above the ground: they do not support (the robot rocks).
    pub raised_contacts: Vec<RaisedContact>,
    /// Why the status is UNKNOWN or N/A.
    pub reason: Option<String>,
}

/// Where one supporting link touches the ground.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct ContactPoint {
    /// The link.
    pub link: String,
    /// The mean of its supporting points in the root frame's ground plane, metres, rounded to the
    /// millimetre.
    pub position: [f64; 2],
}

/// A contact candidate that does not reach the ground.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct RaisedContact {
    /// The link.
    pub link: String,
    /// Its lowest point above the ground, mm.
    pub height_mm: f64,
}
