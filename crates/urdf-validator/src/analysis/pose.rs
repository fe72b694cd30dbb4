//! Poses: the configuration statics (and later stability and workspace) are evaluated at.
//!
//! `zero` (clamped into the limits), `limits` (every limited joint at its upper limit), `custom`
//! (`--joint-angles`), `home` (a named SRDF `group_state`; for an MJCF model without SRDF, its keyframe of
//! that name), `key:NAME` (a keyframe of the robot file: MJCF's `<key>`), and `worst` (handled by the
//! statics sampler).

use std::path::{Path, PathBuf};

use crate::diagnostics::suggest::did_you_mean;
use crate::input::srdf::{group_states, GroupState, Srdf};
use crate::model::kinematics::Configuration;
use crate::model::{JointId, Model};
use crate::rng::SplitMix64;
use crate::urdf::robot::{Keyframe, Robot};

/// Which configuration to evaluate.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum PoseKind {
    /// Every joint at 0, clamped into its limits.
    #[default]
    Zero,
    /// Every limited joint at its upper limit; continuous joints at 0.
    Limits,
    /// The values of `--joint-angles`, others as in `Zero`.
    Custom,
    /// A named `group_state` of an SRDF; zero when none is found.
    Home,
    /// Per joint, the largest gravity torque over seeded samples within the limits.
    Worst,
    /// The keyframe of this name the robot file defines (MJCF `<key name>`).
    Key(String),
}

impl PoseKind {
    /// The flag value (`key:NAME` for a keyframe).
    pub fn label(&self) -> String {
        match self {
            PoseKind::Zero => "zero".to_string(),
            PoseKind::Limits => "limits".to_string(),
            PoseKind::Custom => "custom".to_string(),
            PoseKind::Home => "home".to_string(),
            PoseKind::Worst => "worst".to_string(),
            PoseKind::Key(name) => format!("key:{name}"),
        }
    }

    /// The pose a `--pose` value names: `zero`, `limits`, `custom`, `home`, `worst` or `key:NAME`.
    pub fn parse(text: &str) -> Result<PoseKind, String> {
        match text {
            "zero" => Ok(PoseKind::Zero),
            "limits" => Ok(PoseKind::Limits),
            "custom" => Ok(PoseKind::Custom),
            "home" => Ok(PoseKind::Home),
            "worst" => Ok(PoseKind::Worst),
            _ => match text.strip_prefix("key:") {
                Some(name) if !name.is_empty() => Ok(PoseKind::Key(name.to_string())),
                _ => Err(format!(
                    "'{text}' is not a pose: expected zero, limits, custom, home, worst or key:NAME (a keyframe of an MJCF model)"
                )),
            },
        }
    }
}

/// Everything that picks the configuration.
#[derive(Clone, Debug)]
pub struct PoseOptions {
    /// Which pose.
    pub kind: PoseKind,
    /// `--joint-angles "j1=0.5,j2=30deg"` for `Custom`.
    pub joint_angles: Option<String>,
    /// `--srdf FILE` for `Home` and self-collision; when absent, the one [`crate::input::srdf::find`] finds.
    pub srdf: Option<PathBuf>,
    /// The `group_state` name for `Home`.
    pub state: String,
    /// Samples for `Worst`.
    pub samples: usize,
    /// Seed for `Worst`.
    pub seed: u64,
}

impl Default for PoseOptions {
    fn default() -> Self {
        PoseOptions {
            kind: PoseKind::Zero,
            joint_angles: None,
            srdf: None,
            state: "home".to_string(),
            samples: crate::analysis::DEFAULT_SAMPLES,
            seed: crate::analysis::DEFAULT_SEED,
        }
    }
}

/// A resolved configuration and what the user should know about how it was made.
#[derive(Clone, Debug)]
pub struct ResolvedPose {
    /// One value per joint (mimic relations applied).
    pub q: Configuration,
    /// Clamping, fallbacks, values outside limits.
    pub notes: Vec<String>,
    /// Why the requested pose could not be made (then the zero pose is used): a requested check that
    /// could not run.
    pub unavailable: Option<String>,
}

/// The zero pose with each joint clamped into its limits.
fn clamped_zero(robot: &Robot, model: &Model, notes: &mut Vec<String>) -> Configuration {
    let mut q = model.zero_configuration();
    for (i, joint) in model.joint_data.iter().enumerate() {
        if let Some((lo, hi)) = joint.range() {
            if !(lo..=hi).contains(&0.0) {
                let value = if 0.0 < lo { lo } else { hi };
                q[i] = value;
                if model.mimic[i].is_none() {
                    notes.push(format!(
                        "joint '{}': 0 is outside its limits [{lo}, {hi}]; using {value}",
                        robot.joints[i].name.value
                    ));
                }
            }
        }
    }
    q
}

/// Resolve `options` to a configuration (`Worst` resolves to the clamped zero pose, its reference).
pub fn resolve(
    robot: &Robot,
    model: &Model,
    srdf: Option<&Srdf>,
    options: &PoseOptions,
) -> Result<ResolvedPose, String> {
    let mut notes = Vec::new();
    let mut unavailable = None;
    let mut q = clamped_zero(robot, model, &mut notes);
    match &options.kind {
        PoseKind::Zero | PoseKind::Worst => {}
        PoseKind::Limits => {
            for (i, joint) in model.joint_data.iter().enumerate() {
                if let Some((_, hi)) = joint.range() {
                    q[i] = hi;
                }
            }
        }
        PoseKind::Custom => {
            let text = options
                .joint_angles
                .as_deref()
                .ok_or("--pose custom needs --joint-angles \"joint=value,...\"")?;
            for (name, value) in parse_joint_angles(text)? {
                set_joint(robot, model, &mut q, &name, value, &mut notes)?;
            }
        }
        PoseKind::Key(name) => {
            let key = keyframe(robot, name)?;
            set_keyframe(robot, model, &mut q, key, &mut notes)?;
        }
        PoseKind::Home => match srdf {
            Some(Srdf { path: srdf, text }) => {
                let text = text
                    .as_ref()
                    .map_err(|e| format!("{}: cannot read SRDF: {e}", srdf.display()))?;
                let states = group_states(text).map_err(|e| format!("{}: {e}", srdf.display()))?;
                let wanted: Vec<&GroupState> =
                    states.iter().filter(|s| s.name == options.state).collect();
                if wanted.is_empty() {
                    let mut names: Vec<&str> = states.iter().map(|s| s.name.as_str()).collect();
                    names.sort_unstable();
                    names.dedup();
                    let why = format!(
                        "SRDF {} has no group_state '{}' (it has: {}); using the zero pose",
                        srdf.display(),
                        options.state,
                        if names.is_empty() {
                            "none".to_string()
                        } else {
                            names.join(", ")
                        }
                    );
                    notes.push(why.clone());
                    unavailable = Some(why);
                }
                for state in wanted {
                    for (name, value) in &state.joints {
                        if model.joint(name).is_none() {
                            notes.push(format!(
                                "SRDF state '{}' names unknown joint '{name}'; ignored",
                                state.name
                            ));
                            continue;
                        }
                        set_joint(robot, model, &mut q, name, *value, &mut notes)?;
                    }
                }
            }
            None if options.srdf.is_some() => {
                return Err(format!(
                    "SRDF {} not found",
                    options.srdf.as_deref().unwrap_or(Path::new("")).display()
                ))
            }
            None => match robot.keyframes.iter().find(|k| k.name == options.state) {
                Some(key) => {
                    notes.push(format!(
                        "--pose home: no SRDF; the model's keyframe '{}' is the pose (as --pose key:{})",
                        key.name, key.name
                    ));
                    set_keyframe(robot, model, &mut q, key, &mut notes)?;
                }
                None => {
                    let why = "--pose home: no SRDF given (--srdf) or found beside the URDF (<file stem>.srdf or <robot name>.srdf); using the zero pose";
                    notes.push(why.to_string());
                    unavailable = Some(why.to_string());
                }
            },
        },
    }
    model.apply_mimic(&mut q);
    Ok(ResolvedPose {
        q,
        notes,
        unavailable,
    })
}

/// The robot file's keyframe `name`; a usage error listing the keyframes there are when it has none of
/// that name.
fn keyframe<'r>(robot: &'r Robot, name: &str) -> Result<&'r Keyframe, String> {
    if let Some(key) = robot.keyframes.iter().find(|k| k.name == name) {
        return Ok(key);
    }
    if robot.format != crate::input::Format::Mjcf {
        return Err(format!(
            "--pose key:{name}: keyframes are MJCF's (<keyframe><key>); this input is {}: use --pose home (an SRDF group_state) or --pose custom --joint-angles",
            if robot.format == crate::input::Format::Sdf { "SDFormat" } else { "URDF" }
        ));
    }
    let names: Vec<&str> = robot.keyframes.iter().map(|k| k.name.as_str()).collect();
    Err(format!(
        "--pose key:{name}: the model has no keyframe '{name}' ({})",
        if names.is_empty() {
            "it has no <keyframe><key>".to_string()
        } else {
            format!("its keys: {}", names.join(", "))
        }
    ))
}

/// Set the joints `key` sets: a mimic follower follows its leader instead (as in MuJoCo, whose equality
/// constraint pulls it there), and a joint held fixed (an MJCF joint equality without joint2) stays.
fn set_keyframe(
    robot: &Robot,
    model: &Model,
    q: &mut Configuration,
    key: &Keyframe,
    notes: &mut Vec<String>,
) -> Result<(), String> {
    notes.extend(key.notes.iter().cloned());
    for (name, value) in &key.joints {
        let Some(JointId(j)) = model.joint(name) else {
            continue;
        };
        if model.mimic[j].is_some() || !model.joint_data[j].is_actuated() {
            continue;
        }
        set_joint(robot, model, q, name, *value, notes)?;
    }
    Ok(())
}

fn set_joint(
    robot: &Robot,
    model: &Model,
    q: &mut Configuration,
    name: &str,
    value: f64,
    notes: &mut Vec<String>,
) -> Result<(), String> {
    let Some(JointId(i)) = model.joint(name) else {
        return Err(format!(
            "unknown joint '{name}' ({})",
            did_you_mean(name, model.joint_names())
        ));
    };
    let joint = &model.joint_data[i];
    if !joint.is_actuated() {
        return Err(format!(
            "joint '{name}' is {} and has no position to set",
            joint.kind.as_str()
        ));
    }
    if let Some(leader) = model.mimic[i] {
        notes.push(format!(
            "joint '{name}' mimics '{}': its value follows the leader, the given value is ignored",
            robot.joints[leader.leader.0].name.value
        ));
        return Ok(());
    }
    if let Some((lo, hi)) = joint.range() {
        if !(lo..=hi).contains(&value) {
            notes.push(format!(
                "joint '{name}': {value} is outside its limits [{lo}, {hi}]"
            ));
        }
    }
    q[i] = value;
    Ok(())
}

/// Parse `"j1=0.5, j2=30deg, j3=-1.2rad"`: radians or metres, or degrees with a `deg` / `°` suffix.
pub fn parse_joint_angles(text: &str) -> Result<Vec<(String, f64)>, String> {
    text.split(',')
        .map(str::trim)
        .filter(|item| !item.is_empty())
        .map(|item| {
            let (name, value) = item
                .split_once('=')
                .ok_or_else(|| format!("'{item}' in --joint-angles is not joint=value"))?;
            let (name, value) = (name.trim(), value.trim());
            let (number, scale) = if let Some(v) = value
                .strip_suffix("deg")
                .or_else(|| value.strip_suffix('°'))
            {
                (v.trim(), std::f64::consts::PI / 180.0)
            } else {
                (value.strip_suffix("rad").unwrap_or(value).trim(), 1.0)
            };
            let parsed: f64 = number.parse().map_err(|_| {
                format!("'{value}' for joint '{name}' is not a number (e.g. 0.5, 30deg)")
            })?;
            if !parsed.is_finite() || name.is_empty() {
                return Err(format!(
                    "'{item}' in --joint-angles is not joint=finite-number"
                ));
            }
            Ok((name.to_string(), parsed * scale))
        })
        .collect()
}

/// A seeded uniform sampler over the configuration space (continuous joints over a full turn; joints
/// without a usable range stay at the reference value).
pub struct ConfigurationSampler<'a> {
    model: &'a Model,
    rng: SplitMix64,
}

impl<'a> ConfigurationSampler<'a> {
    /// A sampler seeded with `seed`.
    pub fn new(model: &'a Model, seed: u64) -> Self {
        ConfigurationSampler {
            model,
            rng: SplitMix64::new(seed),
        }
    }

    /// Overwrite `q` with the next sample (mimic relations applied).
    pub fn sample_into(&mut self, q: &mut Configuration) {
        for (i, joint) in self.model.joint_data.iter().enumerate() {
            if self.model.mimic[i].is_some() {
                continue;
            }
            if let Some((lo, hi)) = joint.sampling_interval() {
                q[i] = self.rng.uniform(lo, hi);
            }
        }
        self.model.apply_mimic(q);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joint_angles_accept_radians_degrees_and_spaces() {
        let parsed = parse_joint_angles(" a=0.5, b = 30deg ,c=-1rad,d=90°").unwrap();
        assert_eq!(parsed[0], ("a".to_string(), 0.5));
        assert!((parsed[1].1 - std::f64::consts::PI / 6.0).abs() < 1e-15);
        assert_eq!(parsed[2].1, -1.0);
        assert!((parsed[3].1 - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert!(parse_joint_angles("a=x")
            .unwrap_err()
            .contains("not a number"));
        assert!(parse_joint_angles("a").is_err());
        assert!(parse_joint_angles("a=nan").is_err());
    }
}
