//! The task-query API of the spec (`urdf_validator_main.api.task_runner`): "can this robot pick an
//! object of this mass at this place, in this orientation?", answered by the full pipeline as five named
//! sub-checks, for AI agents and scripts. The Python package and the MCP server are views of this module.
//!
//! A request names a URDF, a target position (x, y, z in metres, root frame), an optional orientation
//! (`"top_down"`, `"side"`, `[r, p, y]` in radians or `[qw, qx, qy, qz]`) and an object mass. It runs as
//! `urdf_validate URDF --task` with the tool at the target's height in the root frame, `--orientation`
//! and `--payload-mass`, and each sub-check reads one part of that report:
//!
//! | sub-check | passes when |
//! |---|---|
//! | `reach` | `reach_from_base` ≥ the target's distance from the root frame's origin |
//! | `reach_orientation` | ≥ 5 % of the sampled arm poses meet the orientation within the tolerance |
//! | `payload_strength` | every joint's effort margin ≥ 1.0 with the object held (statics PASS or WARN) |
//! | `stability_during_reach` | the whole-body COM stays over the support polygon at the pose reaching furthest at the target's height |
//! | `self_collision` | ≥ 95 % of the sampled arm poses are free of self-collision |
//!
//! The overall status is FAIL when a sub-check fails, else UNKNOWN when one could not be assessed, else
//! PASS (N/A sub-checks, asked nothing, do not count). Unlike the Python tool, an UNKNOWN sub-check is
//! never hidden behind a PASS.

use std::path::PathBuf;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::analysis::workspace::target::{Orientation, Task};
use crate::diagnostics::Status;
use crate::report::Report;
use crate::Options;

/// The orientation a pick must reach, as the spec writes it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum TargetOrientation {
    /// `"top_down"` or `"side"`.
    Named(String),
    /// `[r, p, y]` (radians) or `[qw, qx, qy, qz]`.
    Values(Vec<f64>),
}

impl TargetOrientation {
    /// The workspace analysis's orientation.
    fn parse(&self) -> Result<Orientation, String> {
        match self {
            TargetOrientation::Named(name) => Orientation::parse(name),
            TargetOrientation::Values(values) if matches!(values.len(), 3 | 4) => {
                let text: Vec<String> = values.iter().map(f64::to_string).collect();
                Orientation::parse(&text.join(","))
            }
            TargetOrientation::Values(values) => Err(format!(
                "target_orientation: expected [r, p, y] or [qw, qx, qy, qz], got {} numbers",
                values.len()
            )),
        }
    }
}

/// One task query (the spec's `TaskQueryRequest`, same field names; its JSON Schema describes the
/// arguments of the MCP server's task tools).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct TaskQueryRequest {
    /// The robot description (URDF or xacro).
    pub urdf_path: PathBuf,
    /// The task: only `"pick"` (the default, as in the Python tool's MCP server).
    #[serde(default = "pick")]
    pub task_type: String,
    /// Where the tool must be, `[x, y, z]` metres in the root frame.
    #[serde(default)]
    pub target_position: Option<[f64; 3]>,
    /// The orientation the tool must reach there.
    #[serde(default)]
    pub target_orientation: Option<TargetOrientation>,
    /// The mass of the object held at the arm's tip, kg.
    #[serde(default)]
    pub object_mass_kg: Option<f64>,
    /// Slope of the ground, degrees. Only 0 is analysed: another value adds an UNKNOWN
    /// `terrain_gravity` sub-check.
    #[serde(default)]
    pub terrain_angle_deg: f64,
}

/// `task_type`'s default.
fn pick() -> String {
    "pick".to_string()
}

/// One sub-check of a response (the spec's `SubCheckResult`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SubCheckResult {
    /// `reach`, `reach_orientation`, `payload_strength`, `stability_during_reach`, `self_collision`
    /// (or `urdf_load`, `request`, `terrain_gravity`).
    pub name: String,
    /// `PASS`, `FAIL`, `N/A` or `UNKNOWN`.
    pub status: String,
    /// Why, with the numbers.
    pub reason: String,
    /// The link or joint that limits the result, when one does.
    pub bottleneck: Option<String>,
    /// How far the result can be trusted: `exact`, `estimated` or `missing`.
    pub confidence: String,
}

/// The answer to one query (the spec's `TaskQueryResponse`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TaskQueryResponse {
    /// The request's task.
    pub task_type: String,
    /// `PASS`, `FAIL` or `UNKNOWN`.
    pub overall_status: String,
    /// The sub-checks, in the spec's order.
    pub sub_checks: Vec<SubCheckResult>,
    /// The request's terrain angle.
    pub terrain_angle_deg: f64,
    /// Set when the terrain angle is not 0 (not analysed).
    pub terrain_note: Option<String>,
}

impl TaskQueryResponse {
    /// A response whose request could not run at all: one UNKNOWN sub-check `name` saying why.
    fn unknown(request: &TaskQueryRequest, name: &str, reason: String) -> TaskQueryResponse {
        TaskQueryResponse {
            task_type: request.task_type.clone(),
            overall_status: "UNKNOWN".to_string(),
            sub_checks: vec![check(name, Status::Unknown, reason, None, "missing")],
            terrain_angle_deg: request.terrain_angle_deg,
            terrain_note: None,
        }
    }
}

fn check(
    name: &str,
    status: Status,
    reason: String,
    bottleneck: Option<String>,
    confidence: &str,
) -> SubCheckResult {
    SubCheckResult {
        name: name.to_string(),
        status: status.label().to_string(),
        reason,
        bottleneck,
        confidence: confidence.to_string(),
    }
}

/// Answer one query with `base` options (package paths, samples, seed, mesh cache...); the request sets
/// the task, orientation and payload. Never fails: what cannot run is an UNKNOWN sub-check.
pub fn run_pick_task(request: &TaskQueryRequest, base: &Options) -> TaskQueryResponse {
    if request.task_type != "pick" {
        return TaskQueryResponse::unknown(
            request,
            "request",
            format!(
                "task_type '{}' is not supported (expected \"pick\")",
                request.task_type
            ),
        );
    }
    let options = match request_options(request, base) {
        Ok(options) => options,
        Err(reason) => return TaskQueryResponse::unknown(request, "request", reason),
    };
    let validation = match crate::validate(&request.urdf_path, &options) {
        Ok(validation) => validation,
        Err(error) => return TaskQueryResponse::unknown(request, "urdf_load", error.to_string()),
    };
    respond(request, &validation.report)
}

/// The options of one request.
fn request_options(request: &TaskQueryRequest, base: &Options) -> Result<Options, String> {
    let mut options = base.clone();
    if let Some(position) = request.target_position {
        if !position.iter().all(|v| v.is_finite()) {
            return Err(format!(
                "target_position must be three finite numbers, got {position:?}"
            ));
        }
        options.workspace.task = Some(Task::PickAt(position[2]));
    }
    if let Some(orientation) = &request.target_orientation {
        options.workspace.orientation = Some(orientation.parse()?);
    }
    if let Some(mass) = request.object_mass_kg {
        if !(mass.is_finite() && mass >= 0.0) {
            return Err(format!("object_mass_kg must be ≥ 0, got {mass}"));
        }
        options.statics.payload_mass = Some(mass);
    }
    if !request.terrain_angle_deg.is_finite() {
        return Err("terrain_angle_deg must be a finite number".to_string());
    }
    Ok(options)
}

/// The response to `request` from its report.
fn respond(request: &TaskQueryRequest, report: &Report) -> TaskQueryResponse {
    let mut sub_checks = vec![
        reach(request, report),
        reach_orientation(request, report),
        payload_strength(request, report),
        stability_during_reach(request, report),
        self_collision(report),
    ];
    let terrain_note = (request.terrain_angle_deg != 0.0).then(|| {
        sub_checks.push(check(
            "terrain_gravity",
            Status::Unknown,
            format!(
                "terrain_angle_deg={} is not analysed: statics and stability are computed on flat ground",
                request.terrain_angle_deg
            ),
            None,
            "missing",
        ));
        format!(
            "terrain_angle_deg={} is not analysed; statics and stability are for flat ground",
            request.terrain_angle_deg
        )
    });
    TaskQueryResponse {
        task_type: request.task_type.clone(),
        overall_status: overall(&sub_checks).label().to_string(),
        sub_checks,
        terrain_angle_deg: request.terrain_angle_deg,
        terrain_note,
    }
}

/// FAIL when a sub-check fails, else UNKNOWN when one is unknown, else PASS when one passed.
fn overall(sub_checks: &[SubCheckResult]) -> Status {
    let has = |status: Status| sub_checks.iter().any(|c| c.status == status.label());
    if has(Status::Fail) {
        Status::Fail
    } else if has(Status::Unknown) || !has(Status::Pass) {
        Status::Unknown
    } else {
        Status::Pass
    }
}

fn reach(request: &TaskQueryRequest, report: &Report) -> SubCheckResult {
    let Some(target) = request.target_position else {
        return check(
            "reach",
            Status::NotApplicable,
            "no target_position specified".into(),
            None,
            "missing",
        );
    };
    let workspace = report.workspace.as_ref();
    let Some(reach) = workspace.and_then(|w| w.reach_from_base) else {
        let why = workspace
            .and_then(|w| w.reason.clone())
            .unwrap_or_else(|| "workspace not computed".into());
        return check("reach", Status::Unknown, why, None, "missing");
    };
    let distance = target.iter().map(|v| v * v).sum::<f64>().sqrt();
    if reach >= distance {
        check(
            "reach",
            Status::Pass,
            format!("reach_from_base={reach:.3}m >= target_dist={distance:.3}m"),
            None,
            "estimated",
        )
    } else {
        check(
            "reach",
            Status::Fail,
            format!(
                "reach_from_base={reach:.3}m < target_dist={distance:.3}m (deficit={:.3}m)",
                distance - reach
            ),
            None,
            "estimated",
        )
    }
}

fn reach_orientation(request: &TaskQueryRequest, report: &Report) -> SubCheckResult {
    let name = "reach_orientation";
    if request.target_orientation.is_none() {
        return check(
            name,
            Status::NotApplicable,
            "no target_orientation specified".into(),
            None,
            "missing",
        );
    }
    let Some(workspace) = report.workspace.as_ref() else {
        return check(
            name,
            Status::Unknown,
            "workspace not computed".into(),
            None,
            "missing",
        );
    };
    let tolerance = workspace.orientation_tolerance_deg;
    match (
        workspace.orientation_reachable,
        workspace.orientation_fraction,
    ) {
        (Some(reachable), fraction) => {
            let percent = fraction.map_or(String::new(), |f| format!("{:.1}% of ", f * 100.0));
            check(
                name,
                if reachable {
                    Status::Pass
                } else {
                    Status::Fail
                },
                format!(
                    "{percent}sampled poses{} meet the orientation within {tolerance:.0} deg (needs >= 5%)",
                    if request.target_position.is_some() {
                        " at the target height"
                    } else {
                        ""
                    }
                ),
                None,
                "estimated",
            )
        }
        (None, _) => check(
            name,
            Status::Unknown,
            workspace
                .reason
                .clone()
                .unwrap_or_else(|| "no sampled pose to assess the orientation".into()),
            None,
            "missing",
        ),
    }
}

fn payload_strength(request: &TaskQueryRequest, report: &Report) -> SubCheckResult {
    let name = "payload_strength";
    let Some(mass) = request.object_mass_kg else {
        return check(
            name,
            Status::NotApplicable,
            "no object_mass_kg specified".into(),
            None,
            "missing",
        );
    };
    let Some(statics) = report.statics.as_ref() else {
        return check(
            name,
            Status::Unknown,
            "statics not computed".into(),
            None,
            "missing",
        );
    };
    let bottleneck = statics.weakest_joint_name.clone();
    let weakest = bottleneck.as_ref().and_then(|name| {
        statics
            .joints
            .iter()
            .find(|j| &j.name == name)
            .and_then(|j| j.margin)
    });
    let margin = weakest.map_or(String::new(), |m| format!(" (weakest margin {m:.2}x)"));
    match statics.status {
        Status::Pass | Status::Warn => check(
            name,
            Status::Pass,
            format!(
                "every joint holds the robot with {mass:.2} kg at the tip{margin}{}",
                if statics.status == Status::Warn {
                    ", near its effort limit"
                } else {
                    ""
                }
            ),
            bottleneck,
            "estimated",
        ),
        Status::Fail => check(
            name,
            Status::Fail,
            format!("a joint is undersized with {mass:.2} kg at the tip{margin}"),
            bottleneck,
            "estimated",
        ),
        _ => check(
            name,
            Status::Unknown,
            statics.reason.clone().unwrap_or_else(|| {
                "torques unavailable: check the joints' effort limits and the links' masses".into()
            }),
            bottleneck,
            "missing",
        ),
    }
}

fn stability_during_reach(request: &TaskQueryRequest, report: &Report) -> SubCheckResult {
    let name = "stability_during_reach";
    if let Some(stability) = report
        .stability
        .as_ref()
        .filter(|s| s.status == Status::NotApplicable)
    {
        return check(
            name,
            Status::NotApplicable,
            stability
                .reason
                .clone()
                .unwrap_or_else(|| "the robot cannot tip over".into()),
            None,
            "exact",
        );
    }
    if request.target_position.is_none() {
        return check(
            name,
            Status::NotApplicable,
            "no target_position specified".into(),
            None,
            "missing",
        );
    }
    let workspace = report.workspace.as_ref();
    let stable = workspace.and_then(|w| w.task_com_stable_during_reach);
    let shift = workspace
        .and_then(|w| w.task_com_shift_estimate_m)
        .unwrap_or(0.0);
    let margin = workspace.and_then(|w| w.task_com_margin_mm).unwrap_or(0.0);
    match stable {
        Some(true) => check(
            name,
            Status::Pass,
            format!(
                "COM shift at the furthest reach = {:.1}mm, {margin:.1}mm inside the support polygon",
                shift * 1000.0
            ),
            None,
            "estimated",
        ),
        Some(false) => check(
            name,
            Status::Fail,
            format!(
                "COM shift at the furthest reach = {:.1}mm puts the COM {:.1}mm outside the support polygon",
                shift * 1000.0,
                -margin
            ),
            None,
            "estimated",
        ),
        None => check(
            name,
            Status::Unknown,
            workspace
                .and_then(|w| w.task_com_not_assessed.clone().or(w.reason.clone()))
                .or_else(|| report.stability.as_ref().and_then(|s| s.reason.clone()))
                .unwrap_or_else(|| "COM during the reach not assessed".into()),
            None,
            "missing",
        ),
    }
}

fn self_collision(report: &Report) -> SubCheckResult {
    let name = "self_collision";
    let workspace = report.workspace.as_ref();
    let Some(free) = workspace.and_then(|w| w.self_collision_free_fraction) else {
        let why = workspace
            .and_then(|w| w.self_collision_not_assessed.clone().or(w.reason.clone()))
            .unwrap_or_else(|| "self-collision not assessed".into());
        return check(name, Status::Unknown, why, None, "missing");
    };
    let bottleneck = workspace
        .and_then(|w| w.self_collision_worst_pair.clone())
        .map(|[a, b]| format!("{a} vs {b}"));
    let status = if free >= crate::analysis::workspace::COLLISION_FREE_PASS_FRACTION {
        Status::Pass
    } else {
        Status::Fail
    };
    let worst = match (&bottleneck, status) {
        (Some(pair), Status::Fail) => format!(" (most often: {pair})"),
        _ => String::new(),
    };
    check(
        name,
        status,
        format!(
            "{:.1}% of sampled poses are collision-free (needs >= 95%){worst}",
            free * 100.0
        ),
        bottleneck,
        "estimated",
    )
}
