//! Runs the physics analyses in order — statics at the chosen pose, classification at the reference pose,
//! stability at the chosen pose, then the workspace of every arm around the chosen pose — and applies the
//! user's declarations (`--robot-type`, `--contact-links`, `--arm-root`/`--arm-tip`), keeping the
//! heuristics as a cross-check.

pub mod arms;
pub mod classify;
pub mod collision;
pub mod deep;
pub mod geometry_inertia;
pub(crate) mod mass;
pub mod memo;
pub mod pose;
pub mod profiles;
pub mod stability;
pub mod start_contacts;
pub mod statics;
pub mod symmetry;
pub mod up_axis;
pub mod workspace;

use nalgebra::Vector3;

use crate::analysis::classify::{classify, RobotType};
use crate::analysis::collision::MAX_COLLISION_LINKS;
use crate::analysis::stability::StabilitySection;
use crate::analysis::statics::StaticsSection;
use crate::analysis::workspace::WorkspaceSection;
use crate::assets::Assets;
use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::diagnostics::suggest::did_you_mean;
use crate::diagnostics::{Confidence, Section, Status};
use crate::input::srdf::{srdf_collisions, Srdf, SrdfCollisions};
use crate::model::kinematics::{forward_kinematics, Data};
use crate::model::{LinkId, Model};
use crate::timings::Stopwatch;
use crate::urdf::robot::Robot;
use arms::Arm;
use pose::PoseOptions;
use stability::PlacedRobot;
use statics::StaticsOptions;
use workspace::{CollisionSetup, Scene, WorkspaceOptions};

/// Samples for every sampled analysis (`--samples`): the workspace of each arm and `--pose worst`.
pub const DEFAULT_SAMPLES: usize = 30_000;

/// Seed of every sampled analysis (`--seed`).
pub const DEFAULT_SEED: u64 = 7;

/// What the user declares instead of letting heuristics guess.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    /// `--robot-type`.
    pub robot_type: Option<RobotType>,
    /// `--contact-links`.
    pub contact_links: Option<Vec<String>>,
    /// `--arm-root` / `--arm-tip` pairs, in order: the arms to analyse instead of the detected ones.
    pub arms: Vec<(String, String)>,
    /// `--up-axis`: the root frame's axis that points up (the model is turned so it does, which turns
    /// gravity for every analysis); no U731 when declared.
    pub up_axis: Option<crate::model::UpAxis>,
}

/// The physics sections of a report.
#[derive(Clone, Debug)]
pub struct Physics {
    /// Statics at the chosen pose.
    pub statics: StaticsSection,
    /// Stability at the chosen pose.
    pub stability: StabilitySection,
    /// Reach, task, orientation and self-collision around the chosen pose.
    pub workspace: WorkspaceSection,
    /// Mirrored left/right pairs and how they compare.
    pub symmetry: symmetry::SymmetrySection,
    /// The type the capability profile uses.
    pub robot_type: RobotType,
    /// `exact` when declared.
    pub robot_type_confidence: Confidence,
    /// What the structure shows.
    pub detected: RobotType,
    /// Why.
    pub evidence: String,
    /// Findings of the analyses: every verdict that is not PASS, declarations that differ from the
    /// structure, link pairs in contact at the reference pose.
    pub findings: Vec<Finding>,
    /// The configuration statics and stability were evaluated at (mimic relations applied).
    pub q: crate::model::kinematics::Configuration,
    /// The MuJoCo pass (`--deep`, or by itself when the stability margin is negative).
    pub deep: Option<deep::DeepSection>,
}

/// What the run's options ask of a robot that it cannot give (an unknown link, a missing SRDF, a pose
/// that does not fit): the run stops with it, before any section is computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RequestError {
    /// A flag names a link the robot does not have.
    #[error("{flag}: unknown link '{name}' ({suggestion})")]
    UnknownLink {
        /// The flag (`--arm-root`, `--contact-links`, ...).
        flag: &'static str,
        /// The name given.
        name: String,
        /// `did you mean ...`.
        suggestion: String,
    },
    /// `--arm-root` and `--arm-tip` name one link.
    #[error(
        "--arm-root and --arm-tip both name '{0}' (expected the arm's base and its end effector)"
    )]
    SameArmLinks(String),
    /// The tip is not below the root.
    #[error("--arm-tip '{tip}' is not below --arm-root '{root}' in the kinematic tree")]
    TipNotBelowRoot {
        /// `--arm-root`.
        root: String,
        /// `--arm-tip`.
        tip: String,
    },
    /// No joint moves between root and tip.
    #[error("no actuated joint between --arm-root '{root}' and --arm-tip '{tip}' (expected an arm that moves)")]
    NoActuatedJoint {
        /// `--arm-root`.
        root: String,
        /// `--arm-tip`.
        tip: String,
    },
    /// The explicit `--srdf` does not exist.
    #[error("--srdf {}: no such file", .0.display())]
    MissingSrdf(std::path::PathBuf),
    /// The pose asked for (`--pose`, `--joint-angles`, `--state`) does not fit the robot.
    #[error("{0}")]
    Pose(String),
    /// `--payload-mass` is not a mass.
    #[error("--payload-mass {0}: expected a mass ≥ 0 in kg")]
    PayloadMass(f64),
}

fn link_id(model: &Model, flag: &'static str, name: &str) -> Result<LinkId, RequestError> {
    model.link(name).ok_or_else(|| RequestError::UnknownLink {
        flag,
        name: name.to_string(),
        suggestion: did_you_mean(name, model.link_names()),
    })
}

/// One arm declared with `--arm-root`/`--arm-tip`: existing links, the tip below the root, an actuated
/// joint between them.
fn declared_arm(robot: &Robot, model: &Model, root: &str, tip: &str) -> Result<Arm, RequestError> {
    let root_id = link_id(model, "--arm-root", root)?;
    let tip_id = link_id(model, "--arm-tip", tip)?;
    if root_id == tip_id {
        return Err(RequestError::SameArmLinks(root.to_string()));
    }
    let arm = arms::declared(robot, model, root_id, tip_id).ok_or_else(|| {
        RequestError::TipNotBelowRoot {
            root: root.to_string(),
            tip: tip.to_string(),
        }
    })?;
    if arm.first_joint(model).is_none() {
        return Err(RequestError::NoActuatedJoint {
            root: root.to_string(),
            tip: tip.to_string(),
        });
    }
    Ok(arm)
}

/// What the analyses need besides the robot and its model.
pub struct Inputs<'a> {
    /// Meshes, link supports and the SRDF, loaded once.
    pub assets: &'a Assets,
    /// Pose and payload.
    pub statics: &'a StaticsOptions,
    /// Samples, task and orientation.
    pub workspace: &'a WorkspaceOptions,
    /// Declarations.
    pub overrides: &'a Overrides,
}

/// Run the analyses.
pub fn analyse(
    robot: &Robot,
    model: &Model,
    inputs: &Inputs,
    clock: &mut Stopwatch,
) -> Result<Physics, RequestError> {
    let Inputs {
        assets,
        statics: statics_options,
        overrides,
        ..
    } = *inputs;
    let supports = &assets.supports;
    // An explicit --srdf must exist, whichever analyses end up reading it (the assets stage found it, or
    // refused to read it, when it does).
    if let Some(path) = statics_options
        .pose
        .srdf
        .as_deref()
        .filter(|_| assets.srdf.is_none() && assets.srdf_refused.is_none())
    {
        return Err(RequestError::MissingSrdf(path.to_path_buf()));
    }
    let declared = overrides
        .arms
        .iter()
        .map(|(root, tip)| declared_arm(robot, model, root, tip))
        .collect::<Result<Vec<Arm>, RequestError>>()?;
    let declared_contacts = match &overrides.contact_links {
        Some(names) => Some(
            names
                .iter()
                .map(|n| link_id(model, "--contact-links", n))
                .collect::<Result<Vec<_>, _>>()?,
        ),
        None => None,
    };
    let statics::StaticsOutcome {
        section: mut statics,
        findings: statics_findings,
        q,
    } = statics::analyse(robot, model, assets.srdf.as_ref(), statics_options)?;
    clock.lap("statics");
    let (symmetry, symmetry_findings) = symmetry::analyse(robot, model);

    let reference =
        pose::resolve(robot, model, None, &PoseOptions::default()).map_err(RequestError::Pose)?;
    let mut data = Data::new(model);
    forward_kinematics(model, &reference.q, &mut data);
    let mut classification = classify(robot, model, &data, supports);
    let mut findings = statics_findings;
    findings.extend(symmetry_findings);
    // Another up axis: classified in its frame, the physics keeps the model's (the ground stays its).
    if let Some(other) = overrides
        .up_axis
        .is_none()
        .then(|| up_axis::detect(robot, model, &data, supports, &classification))
        .flatten()
    {
        findings.push(up_axis::finding(robot, model, &other));
        classification = classify::Classification {
            ground_z: classification.ground_z,
            ..other.classification
        };
    }
    clock.lap("classify");
    let detected = classification.robot_type;
    let root_span = model
        .root
        .map_or(robot.span, |root| robot.links[root.0].span);
    let (robot_type, confidence) = match overrides.robot_type {
        Some(declared) => {
            if declared != detected {
                findings.push(Finding::new(
                    &rules::DECLARATION_DIFFERS,
                    root_span,
                    format!(
                        "User declared --robot-type={}, but the structure suggests {} ({})",
                        declared.as_str(),
                        detected.as_str(),
                        classification.evidence
                    ),
                ));
            }
            (declared, Confidence::Exact)
        }
        None => (detected, Confidence::Estimated),
    };

    // Pairs in contact here are left out of self-collision sampling, as MoveIt's setup assistant leaves
    // out those in contact at the default pose: at the --pose configuration a contact is a collision.
    let reference_data = data.clone();
    forward_kinematics(model, &q, &mut data);
    let com = statics.full_body_com.map(Vector3::from);
    let placed = PlacedRobot {
        robot,
        model,
        data: &data,
        supports,
    };
    let stability = stability::analyse(
        &placed,
        &classification,
        robot_type,
        declared_contacts.as_deref(),
        com,
    );
    findings.extend(stability::findings(robot, model, &stability));
    clock.lap("stability");
    if let (Some(ground), Some(com)) = (stability.ground_height, com) {
        statics.com_height_above_ground = Some(com.z - ground);
    }
    let arms = if declared.is_empty() {
        if robot_type == RobotType::GroundVehicle {
            Vec::new()
        } else {
            classification.arms
        }
    } else {
        for arm in &declared {
            // A declared arm should be one the structure shows: its tip on a detected arm's path.
            let link_name = |l: LinkId| robot.links[l.0].name.value.as_str();
            let matches = |found: &Arm| {
                found.tip == arm.tip
                    || found
                        .path
                        .iter()
                        .any(|j| model.joint_links[j.0].is_some_and(|(_, c)| c == arm.tip))
            };
            if !classification.arms.is_empty() && !classification.arms.iter().any(matches) {
                let detected: Vec<String> = classification
                    .arms
                    .iter()
                    .map(|a| format!("{} → {}", link_name(a.base), link_name(a.tip)))
                    .collect();
                findings.push(
                    Finding::new(
                        &rules::DECLARATION_DIFFERS,
                        robot.links[arm.tip.0].span,
                        format!(
                            "User declared the arm {} → {}, but the structure suggests {}",
                            link_name(arm.base),
                            link_name(arm.tip),
                            detected.join(", ")
                        ),
                    )
                    .in_section(Section::Workspace),
                );
            }
        }
        declared
    };
    let ground = stability
        .ground_height
        .or(classification.ground_z)
        .unwrap_or(0.0);
    let scene = Scene {
        robot,
        model,
        q: &q,
        data: &data,
        ground,
        support_polygon: if stability.stable.is_some() {
            &stability.support_polygon
        } else {
            &[]
        },
        robot_type,
        payload: statics_options.payload_mass.map(|mass| {
            let link = statics_options.payload_link.as_deref();
            (mass, link.and_then(|name| model.link(name)))
        }),
    };
    // Built for every robot with collision geometry: the contacts at the reference pose (U601) concern
    // a quadruped's base and legs (solo12's overlap by 3.5 mm) as much as an arm; only arms are sampled.
    let has_collisions = robot.links.iter().any(|link| !link.collisions.is_empty());
    let collision = if !has_collisions || robot.links.len() > MAX_COLLISION_LINKS {
        None
    } else {
        let (setup, setup_findings) = collision_setup(robot, model, &reference_data, inputs);
        findings.extend(setup_findings);
        Some(setup)
    };
    clock.lap("collision_setup");
    let workspace = workspace::analyse(&scene, &arms, collision.as_ref(), inputs.workspace);
    findings.extend(workspace::findings(
        robot,
        model,
        &arms,
        &workspace,
        inputs.workspace,
        stability.status != Status::NotApplicable,
    ));
    clock.lap("workspace");
    if let Some(c) = &collision {
        let start = start_contacts::check(robot, model, &c.model, &data, stability.ground_height);
        findings.extend(start.findings);
        let touching: Vec<(LinkId, LinkId)> = c
            .touching
            .iter()
            .copied()
            .filter(|&(a, b)| !start.reported_pairs.contains(&(a.min(b), a.max(b))))
            .collect();
        findings.extend(contact_findings(robot, &touching, !arms.is_empty()));
    }
    clock.lap("start_contacts");
    Ok(Physics {
        statics,
        stability,
        workspace,
        symmetry,
        robot_type,
        robot_type_confidence: confidence,
        detected,
        evidence: classification.evidence,
        findings,
        q,
        deep: None,
    })
}

/// The collision model at the chosen pose, with the allowed collisions of the SRDF (`--srdf`, else the one
/// [`crate::input::srdf::find`] finds) applied.
///
/// (An explicit `--srdf` that does not exist was refused by [`analyse`].) An SRDF that cannot be read, or that names
/// links the robot does not have, gives U602 findings and the rest runs.
fn collision_setup(
    robot: &Robot,
    model: &Model,
    data: &Data,
    inputs: &Inputs,
) -> (CollisionSetup, Vec<Finding>) {
    let mut findings = Vec::new();
    let srdf_problem = |message: String| Finding::new(&rules::SRDF_PROBLEM, None, message);
    let file = inputs.assets.srdf.as_ref();
    let path = file.map(|srdf| &srdf.path);
    let srdf = match file {
        Some(Srdf { path, text }) => {
            let parsed = text
                .as_ref()
                .map_err(|e| format!("cannot read it: {e}"))
                .and_then(|text| srdf_collisions(text));
            match parsed {
                Ok(collisions) => collisions,
                Err(e) => {
                    findings.push(srdf_problem(format!(
                        "SRDF {}: {e} — its allowed collisions are not used",
                        path.display()
                    )));
                    SrdfCollisions::default()
                }
            }
        }
        None => SrdfCollisions::default(),
    };
    let setup = CollisionSetup::new(robot, model, data, &inputs.assets.supports, &srdf);
    // One finding per SRDF: an SRDF written for a larger model can name hundreds of absent links.
    if let (Some(path), false) = (&path, setup.unknown_srdf_links.is_empty()) {
        let mentions = setup.unknown_srdf_links.len();
        let shown: Vec<&str> = setup
            .unknown_srdf_links
            .iter()
            .take(3)
            .map(String::as_str)
            .collect();
        findings.push(srdf_problem(format!(
            "SRDF {}: {mentions} mention{} of links the robot does not have ({}{}) — {} ignored",
            path.display(),
            if mentions == 1 { "" } else { "s" },
            shown.join("; "),
            if mentions > shown.len() { "; …" } else { "" },
            if mentions == 1 {
                "that entry is"
            } else {
                "those entries are"
            },
        )));
    }
    (setup, findings)
}

/// One U601 finding per link pair in contact at the reference (clamped zero) pose, at the second link's
/// collision; `sampled` when arms are sampled for self-collision (the pair is left out of it).
fn contact_findings(robot: &Robot, touching: &[(LinkId, LinkId)], sampled: bool) -> Vec<Finding> {
    touching
        .iter()
        .map(|&(a, b)| {
            let (a, b) = (&robot.links[a.0], &robot.links[b.0]);
            let span = b.collisions.first().map_or(b.span, |c| c.span);
            Finding::new(
                &rules::CONTACT_AT_REFERENCE,
                span,
                format!(
                    "Links '{}' and '{}' have collision geometry in contact at the zero pose{}",
                    a.name.value,
                    b.name.value,
                    if sampled {
                        " — left out of self-collision sampling"
                    } else {
                        ""
                    }
                ),
            )
        })
        .collect()
}
