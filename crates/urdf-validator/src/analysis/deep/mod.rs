//! `--deep`: the robot loaded into MuJoCo as the user would load it, its gravity forces and centre of mass
//! compared with ours, and a 2-second drop test. It runs by itself when the stability margin is negative.
//!
//! | module | job |
//! |---|---|
//! | [`job`] | the URDF handed to MuJoCo (meshes resolved, COLLADA as hulls), fallbacks, servos |
//! | [`bridge`] | the Python process running `bridge.py` with MuJoCo, bounded in time |
//! | [`verdict`] | the reply compared with our model: changes, cross-check, drop test, findings |
//! | `ground` | the drop test's end: support contacts, links fallen onto, agreement with stability |
//! | `section` | the `deep` section of the report |

pub mod bridge;
mod ground;
pub mod job;
mod section;
pub mod verdict;

pub use section::{DeepJoint, DeepSection, DropTest, SaggingJoint, SimulatorChange};

use std::time::Duration;

use crate::analysis::classify::RobotType;
use crate::analysis::statics::gravity;
use crate::analysis::Physics;
use crate::assets::Assets;
use crate::diagnostics::{rules, Confidence, Finding, Section, Status};
use crate::model::kinematics::Configuration;
use crate::model::Model;
use crate::timings::Progress;
use crate::urdf::robot::Robot;
use bridge::BridgeError;

/// Time the MuJoCo pass may take (model build, cross-check and drop test) before it is stopped.
pub const DEFAULT_TIME_LIMIT: Duration = Duration::from_secs(60);

/// `--deep`.
#[derive(Clone, Debug)]
pub struct DeepOptions {
    /// The user asked for the pass (`--deep`).
    pub requested: bool,
    /// Run it by itself when the stability margin is negative (the spec's auto-trigger).
    pub automatic: bool,
    /// Time limit of the MuJoCo process.
    pub time_limit: Duration,
    /// The Python to run MuJoCo with (the front ends set [`crate::input::interpreter::python`]); `None`:
    /// `python3` on `PATH`.
    pub python: Option<std::path::PathBuf>,
}

impl Default for DeepOptions {
    fn default() -> Self {
        DeepOptions {
            requested: false,
            automatic: true,
            time_limit: DEFAULT_TIME_LIMIT,
            python: None,
        }
    }
}

/// The file the deep pass hands MuJoCo.
#[derive(Clone, Copy, Debug)]
pub enum DeepSource<'a> {
    /// The URDF text the robot was parsed from.
    Urdf(&'a str),
    /// The MJCF file, which MuJoCo loads itself.
    Mjcf(&'a std::path::Path),
    /// SDFormat input, which the pass does not read yet.
    Sdf,
    /// An MJCF file MuJoCo cannot be given (under `--untrusted`, or unsaved): why.
    Withheld(&'a str),
}

/// What the deep pass reads.
pub struct DeepInput<'a> {
    /// The file MuJoCo loads.
    pub source: DeepSource<'a>,
    /// The robot.
    pub robot: &'a Robot,
    /// Its tree.
    pub model: &'a Model,
    /// Its meshes.
    pub assets: &'a Assets,
    /// The analyses (statics, stability, type).
    pub physics: &'a Physics,
    /// `--payload-mass` and its link, as statics used them.
    pub payload: Option<(crate::model::LinkId, f64)>,
    /// `--contact-links`, when declared.
    pub contact_links: Option<&'a [String]>,
    /// The options.
    pub options: &'a DeepOptions,
    /// Cancels the MuJoCo process when the file's time runs out.
    pub progress: Option<&'a Progress>,
}

/// The deep section and its findings; `None` when the pass neither was asked for nor triggered.
pub fn run(input: &DeepInput) -> Option<(DeepSection, Vec<Finding>)> {
    let physics = input.physics;
    let automatic = !input.options.requested
        && input.options.automatic
        && physics.stability.margin_mm.is_some_and(|m| m < 0.0);
    if !input.options.requested && !automatic {
        return None;
    }
    let trigger = if automatic { "automatic" } else { "requested" };
    // For SDFormat there is no text MuJoCo reads (yet), an MJCF file may be withheld: say so when asked.
    let not_read = |why: BridgeError| {
        input
            .options
            .requested
            .then(|| not_run(input, trigger, std::path::Path::new(""), &why))
    };
    let source = match input.source {
        DeepSource::Urdf(text) => job::JobSource::Urdf(text),
        DeepSource::Mjcf(path) => job::JobSource::Mjcf(path),
        DeepSource::Sdf => return not_read(BridgeError::NotUrdf),
        DeepSource::Withheld(why) => return not_read(BridgeError::Withheld(why.to_string())),
    };
    let model = input.model;
    let q = &physics.q;
    let mut configurations = vec![(physics.statics.pose.clone(), q.clone())];
    for joint in &physics.statics.joints {
        if let Some(worst) = &joint.worst_configuration {
            configurations.push((
                format!("worst:{}", joint.name),
                configuration(model, q, worst),
            ));
        }
    }
    // A link named 'world' is MuJoCo's world body: what hangs from it cannot fall.
    let fixed_base = physics.robot_type == RobotType::ArmOnly
        || model
            .root
            .is_some_and(|r| input.robot.links[r.0].name.value == "world");
    let job = job::build(&job::JobInput {
        source,
        robot: input.robot,
        model,
        assets: input.assets,
        configurations,
        drop_q: q,
        fixed_base,
        payload: input.payload,
    })?;
    let python = input
        .options
        .python
        .clone()
        .unwrap_or_else(|| std::path::PathBuf::from("python3"));
    let reply = bridge::run(&python, &job.json, input.options.time_limit, input.progress);
    Some(match reply {
        Ok(reply) => {
            let mut outcome = verdict::judge(&verdict::Context {
                robot: input.robot,
                model,
                physics,
                job: &job,
                reply: &reply,
                payload: input.payload,
                contact_links: input.contact_links,
                fixed_base,
                trigger,
            });
            if automatic {
                outcome.1.insert(
                    0,
                    Finding::new(
                        &rules::DEEP_PASS_AUTOMATIC,
                        root_span(input.robot, model),
                        format!(
                            "The stability margin is negative ({:.1} mm): the MuJoCo pass ran by itself (as --deep would)",
                            physics.stability.margin_mm.unwrap_or(0.0)
                        ),
                    ),
                );
            }
            outcome
        }
        Err(error) => not_run(input, trigger, &python, &error),
    })
}

/// The section and finding when MuJoCo could not run: a FAIL when `--deep` was asked for (U790), an
/// INFO when the pass triggered itself.
fn not_run(
    input: &DeepInput,
    trigger: &str,
    interpreter: &std::path::Path,
    error: &BridgeError,
) -> (DeepSection, Vec<Finding>) {
    let why = error.describe();
    let finding = if input.options.requested {
        Finding::new(
            &rules::REQUESTED_CHECK_NOT_RUN,
            input.robot.span,
            format!("--deep: {why}"),
        )
        .in_section(Section::Deep)
    } else {
        Finding::new(
            &rules::DEEP_PASS_AUTOMATIC,
            root_span(input.robot, input.model),
            format!(
                "The stability margin is negative: a MuJoCo drop test would have run by itself (as --deep does), but {why}",
            ),
        )
    };
    let (python, version) = match error {
        BridgeError::NoMujoco { python, .. } => (Some(python.clone()), None),
        BridgeError::NotUrdf | BridgeError::Withheld(_) => (None, None),
        _ => (Some(interpreter.display().to_string()), None),
    };
    let section = DeepSection {
        status: Status::Unknown,
        trigger: trigger.to_string(),
        simulator: "mujoco".to_string(),
        simulator_version: version,
        python,
        reason: Some(why),
        simulator_changes: Vec::new(),
        joints: Vec::new(),
        mujoco_com: None,
        our_com: None,
        com_abs_diff: None,
        agreement: None,
        tolerance: verdict::RELATIVE_TOLERANCE,
        drop_test: None,
    };
    (section, vec![finding])
}

fn root_span(robot: &Robot, model: &Model) -> crate::diagnostics::span::Span {
    model
        .root
        .map_or(robot.span, |root| robot.links[root.0].span)
}

/// A configuration from named independent joint values (the rest as in `base`), mimic applied.
fn configuration(
    model: &Model,
    base: &Configuration,
    named: &std::collections::BTreeMap<String, f64>,
) -> Configuration {
    let mut q = base.clone();
    for (name, value) in named {
        if let Some(joint) = model.joint(name) {
            if let Some(slot) = q.get_mut(joint.0) {
                *slot = *value;
            }
        }
    }
    model.apply_mimic(&mut q);
    q
}

/// Mark what MuJoCo confirmed: statics' centre of mass and each agreeing joint's torque become
/// `simulated`.
pub fn mark_simulated(physics: &mut Physics, section: &DeepSection) {
    if section.com_abs_diff.is_some()
        && section.mujoco_com.is_some()
        && section.agreement.is_some()
        && com_agrees(section)
    {
        physics.statics.com_confidence = Confidence::Simulated;
    }
    for joint in &mut physics.statics.joints {
        let agrees = section
            .joints
            .iter()
            .any(|d| d.name == joint.name && d.agrees);
        if agrees && joint.torque_confidence == Confidence::Estimated {
            joint.torque_confidence = Confidence::Simulated;
        }
    }
}

fn com_agrees(section: &DeepSection) -> bool {
    match (section.our_com, section.com_abs_diff) {
        (Some(ours), Some(diff)) => {
            let norm = ours.iter().map(|v| v * v).sum::<f64>().sqrt();
            diff <= verdict::RELATIVE_TOLERANCE * norm.max(verdict::COM_SCALE_M)
        }
        _ => false,
    }
}

/// Our gravity torque per joint at `q`, mimic folded, with the payload's share.
pub(crate) fn our_torques(
    model: &Model,
    q: &[f64],
    payload: Option<(crate::model::LinkId, f64)>,
) -> Vec<f64> {
    let mut data = gravity::StaticsData::new(model);
    gravity::evaluate(model, q, &mut data);
    let mut torque = data.torque.clone();
    if let Some((link, mass)) = payload {
        let per_kg = gravity::payload_torque_per_kg(model, &data.kinematics, link);
        for (t, p) in torque.iter_mut().zip(per_kg) {
            *t += p * mass;
        }
    }
    torque
}
