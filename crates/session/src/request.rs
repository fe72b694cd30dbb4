//! What a front end asks of a validation, typed: [`Request`]. The command line maps its flags onto it, the
//! MCP server its tools' arguments, the language server its start-up flags and the Python module its
//! keyword arguments ([`Request::from_json`]). A value left out (`None`, empty) is decided by the
//! configuration file, else by the default.

use std::path::PathBuf;

use serde_json::{Map, Value};
use urdf_validator::analysis::classify::RobotType;
use urdf_validator::analysis::pose::PoseKind;
use urdf_validator::analysis::profiles::Simulator;
use urdf_validator::diagnostics::suggest::did_you_mean;
use urdf_validator::model::UpAxis;

/// Seconds a file may take unless the request says otherwise (`--timeout`).
pub const DEFAULT_TIMEOUT_SECONDS: f64 = 60.0;
/// The approach-direction tolerance of `--orientation`, degrees, unless the request says otherwise.
pub const DEFAULT_ORIENTATION_TOLERANCE_DEG: f64 = 30.0;
/// The SRDF group state of `--pose home` unless the request names one.
pub const DEFAULT_STATE: &str = "home";

/// The settings of a validation as a front end gives them. Each field is named after the command's flag.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Request {
    /// `--xacro-arg` and positional `name:=value`: xacro arguments, in the order given.
    pub xacro_args: Vec<(String, String)>,
    /// `--model`: the model of an SDFormat world.
    pub model: Option<String>,
    /// `--package-path`: folders holding ROS packages (searched before the environment's).
    pub package_path: Vec<PathBuf>,
    /// `--untrusted`: read only below the roots, no environment variable unless allowed.
    pub untrusted: bool,
    /// Build the 3-D view's scene for the HTML report (`--format html`; not a flag of its own).
    pub view: bool,
    /// `--root`: more folders an untrusted run may read.
    pub root: Vec<PathBuf>,
    /// `--allow-env`: variables an untrusted run may read.
    pub allow_env: Vec<String>,
    /// `--pose` (default zero).
    pub pose: Option<PoseKind>,
    /// `--joint-angles`.
    pub joint_angles: Option<String>,
    /// `--srdf`.
    pub srdf: Option<PathBuf>,
    /// `--state` (default [`DEFAULT_STATE`]).
    pub state: Option<String>,
    /// `--samples` (default [`urdf_validator::DEFAULT_SAMPLES`]).
    pub samples: Option<usize>,
    /// `--seed` (default [`urdf_validator::DEFAULT_SEED`]).
    pub seed: Option<u64>,
    /// `--payload-mass`, kg.
    pub payload_mass: Option<f64>,
    /// `--payload-link`.
    pub payload_link: Option<String>,
    /// `--robot-type`.
    pub robot_type: Option<RobotType>,
    /// `--up-axis`.
    pub up_axis: Option<UpAxis>,
    /// `--contact-links`.
    pub contact_links: Option<Vec<String>>,
    /// `--arm-root`, the n-th paired with the n-th of `arm_tip`.
    pub arm_root: Vec<String>,
    /// `--arm-tip`.
    pub arm_tip: Vec<String>,
    /// `--task`.
    pub task: Option<String>,
    /// `--height`, metres (with `--task custom`).
    pub height: Option<f64>,
    /// `--orientation`.
    pub orientation: Option<String>,
    /// `--orientation-tolerance`, degrees (default [`DEFAULT_ORIENTATION_TOLERANCE_DEG`]).
    pub orientation_tolerance: Option<f64>,
    /// `--approach-axis`.
    pub approach_axis: Option<String>,
    /// `--timings`.
    pub timings: bool,
    /// `--no-cache`: neither read nor write the mesh cache on disk.
    pub no_cache: bool,
    /// `--deep`.
    pub deep: bool,
    /// `--simulator`.
    pub simulator: Vec<Simulator>,
    /// `--timeout`, seconds, 0 for none (default [`DEFAULT_TIMEOUT_SECONDS`]).
    pub timeout: Option<f64>,
    /// `--select` (replaces the configuration file's).
    pub select: Option<Vec<String>>,
    /// `--ignore` (added to the configuration file's).
    pub ignore: Vec<String>,
    /// `--show-suppressed`.
    pub show_suppressed: bool,
    /// `--config`: the configuration file for every input.
    pub config: Option<PathBuf>,
    /// `--no-config`.
    pub no_config: bool,
    /// `--override KEY=VALUE`s.
    pub overrides: Vec<String>,
    /// `--override-file`.
    pub override_file: Option<PathBuf>,
    /// `--baseline`.
    pub baseline: Option<PathBuf>,
}

/// Flags of the command that act on a whole run of it (they write files): refused in a request.
const RUN_FLAGS: &[(&str, &str)] = &[
    (
        "write_baseline",
        "--write-baseline writes a file for a whole run of the command: run `urdf_validate ... \
         --write-baseline FILE` (`--baseline FILE` is taken here)",
    ),
    (
        "fix",
        "--fix writes the files: run `urdf_validate --fix ...` (`--diff` shows the fixes)",
    ),
    (
        "diff",
        "--diff prints the fixes of a run of the command: run `urdf_validate --diff ...`",
    ),
    (
        "from_overrides",
        "--from-overrides writes the overrides as fixes: run `urdf_validate --fix --from-overrides ...`",
    ),
];

/// Flags of the command about its own output and threads, which a request accepts and that change
/// nothing in a report (the Python API has always taken every flag of the command).
const OUTPUT_FLAGS: &[&str] = &[
    "format",
    "output",
    "output_dir",
    "no_write",
    "verbose",
    "quiet",
    "color",
    "jobs",
    "detailed",
    "unsafe_fixes",
    "skip_xacro_libraries",
];

/// Every name [`Request::from_json`] takes, for suggestions.
const NAMES: &[&str] = &[
    "xacro_arg",
    "xacro_args",
    "model",
    "package_path",
    "untrusted",
    "root",
    "allow_env",
    "pose",
    "joint_angles",
    "srdf",
    "state",
    "samples",
    "seed",
    "payload_mass",
    "payload_link",
    "robot_type",
    "up_axis",
    "contact_links",
    "arm_root",
    "arm_tip",
    "task",
    "height",
    "orientation",
    "orientation_tolerance",
    "approach_axis",
    "timings",
    "no_cache",
    "deep",
    "simulator",
    "timeout",
    "select",
    "ignore",
    "show_suppressed",
    "config",
    "no_config",
    "override",
    "override_file",
    "baseline",
];

impl Request {
    /// A request from a JSON object whose keys are the command's long flags with `_` (or `-`) for `-`:
    /// `{"samples": 1000, "robot_type": "wheeled", "package_path": ["a"], "no_cache": true}`. A list
    /// flag takes a list or one value (`select` and `ignore` also a comma-separated text); `null` and
    /// `false` leave a flag out. An unknown or malformed value is an error naming its flag
    /// (`--samples: expected a whole number ≥ 0, got "many"`).
    pub fn from_json(object: &Map<String, Value>) -> Result<Request, String> {
        let mut request = Request::default();
        for (key, value) in object {
            let name = key.replace('-', "_");
            if value.is_null() || value == &Value::Bool(false) {
                continue;
            }
            if let Some((_, message)) = RUN_FLAGS.iter().find(|(flag, _)| *flag == name) {
                return Err((*message).to_string());
            }
            if OUTPUT_FLAGS.contains(&name.as_str()) {
                continue;
            }
            request.set(&name, value)?;
        }
        request.check()?;
        Ok(request)
    }

    /// Set the flag `name` (with `_`) from its JSON `value`.
    fn set(&mut self, name: &str, value: &Value) -> Result<(), String> {
        let flag = format!("--{}", name.replace('_', "-"));
        let field = Field { flag: &flag, value };
        match name {
            "xacro_arg" => {
                for text in field.texts(false)? {
                    self.xacro_args
                        .push(crate::discovery::parse_xacro_arg_flag(&text)?);
                }
            }
            "xacro_args" => {
                let Value::Object(arguments) = value else {
                    return Err(field.expected("an object of {\"name\": \"value\"}"));
                };
                for (name, value) in arguments {
                    let value = match value {
                        Value::String(text) => text.clone(),
                        Value::Number(_) | Value::Bool(_) => value.to_string(),
                        _ => return Err(field.expected("text values")),
                    };
                    self.xacro_args.push((name.clone(), value));
                }
            }
            "model" => self.model = Some(field.text()?),
            "package_path" => self.package_path.extend(field.paths()?),
            "untrusted" => self.untrusted = field.flag()?,
            "root" => self.root.extend(field.paths()?),
            "allow_env" => self.allow_env.extend(field.texts(false)?),
            "pose" => self.pose = Some(PoseKind::parse(&field.text()?).map_err(|e| field.says(e))?),
            "joint_angles" => self.joint_angles = Some(field.text()?),
            "srdf" => self.srdf = Some(field.text()?.into()),
            "state" => self.state = Some(field.text()?),
            "samples" => self.samples = Some(field.whole()?),
            "seed" => self.seed = Some(field.whole()?),
            "payload_mass" => self.payload_mass = Some(field.number()?),
            "payload_link" => self.payload_link = Some(field.text()?),
            "robot_type" => self.robot_type = Some(parse_robot_type(&field.text()?, &flag)?),
            "up_axis" => {
                self.up_axis = Some(parse_up_axis(&field.text()?).map_err(|e| field.says(e))?)
            }
            "contact_links" => self.contact_links = Some(field.texts(true)?),
            "arm_root" => self.arm_root.extend(field.texts(false)?),
            "arm_tip" => self.arm_tip.extend(field.texts(false)?),
            "task" => self.task = Some(field.text()?),
            "height" => self.height = Some(field.number()?),
            "orientation" => self.orientation = Some(field.text()?),
            "orientation_tolerance" => self.orientation_tolerance = Some(field.number()?),
            "approach_axis" => self.approach_axis = Some(field.text()?),
            "timings" => self.timings = field.flag()?,
            "no_cache" => self.no_cache = field.flag()?,
            "deep" => self.deep = field.flag()?,
            "simulator" => {
                for name in field.texts(true)? {
                    self.simulator.push(parse_simulator(&name, &flag)?);
                }
            }
            "timeout" => self.timeout = Some(field.number()?),
            "select" => self.select = Some(field.texts(true)?),
            "ignore" => self.ignore.extend(field.texts(true)?),
            "show_suppressed" => self.show_suppressed = field.flag()?,
            "config" => self.config = Some(field.text()?.into()),
            "no_config" => self.no_config = field.flag()?,
            "override" | "overrides" => self.overrides.extend(field.texts(false)?),
            "override_file" => self.override_file = Some(field.text()?.into()),
            "baseline" => self.baseline = Some(field.text()?.into()),
            _ => {
                let names = NAMES.iter().chain(OUTPUT_FLAGS);
                let suggestion = did_you_mean(name, names.copied());
                return Err(format!("unexpected argument '{flag}' ({suggestion})"));
            }
        }
        Ok(())
    }

    /// The checks that need no file: `--arm-root`/`--arm-tip` in pairs, and the workspace values.
    pub fn check(&self) -> Result<(), String> {
        if self.arm_root.len() != self.arm_tip.len() {
            return Err(format!(
                "{} --arm-root but {} --arm-tip: give them in pairs, one pair per arm",
                self.arm_root.len(),
                self.arm_tip.len()
            ));
        }
        crate::options::workspace_options(self).map(|_| ())
    }
}

/// One JSON value of flag `flag`, read as the flag's type.
struct Field<'a> {
    flag: &'a str,
    value: &'a Value,
}

impl Field<'_> {
    /// `--flag: expected WHAT, got VALUE`.
    fn expected(&self, what: &str) -> String {
        format!("{}: expected {what}, got {}", self.flag, self.value)
    }

    /// `--flag: MESSAGE`.
    fn says(&self, message: String) -> String {
        format!("{}: {message}", self.flag)
    }

    fn flag(&self) -> Result<bool, String> {
        self.value
            .as_bool()
            .ok_or_else(|| self.expected("true or false"))
    }

    fn text(&self) -> Result<String, String> {
        match self.value {
            Value::String(text) => Ok(text.clone()),
            Value::Number(number) => Ok(number.to_string()),
            _ => Err(self.expected("a text")),
        }
    }

    /// A list of texts, or one text (split at commas when `comma_separated`, as the flag is).
    fn texts(&self, comma_separated: bool) -> Result<Vec<String>, String> {
        let items: Vec<&Value> = match self.value {
            Value::Array(items) => items.iter().collect(),
            other => vec![other],
        };
        let mut texts = Vec::new();
        for item in items {
            let text = Field {
                flag: self.flag,
                value: item,
            }
            .text()
            .map_err(|_| self.expected("a text or a list of texts"))?;
            if comma_separated {
                texts.extend(text.split(',').map(str::to_string));
            } else {
                texts.push(text);
            }
        }
        Ok(texts)
    }

    fn paths(&self) -> Result<Vec<PathBuf>, String> {
        Ok(self.texts(false)?.into_iter().map(PathBuf::from).collect())
    }

    /// A whole number ≥ 0 (or its text).
    fn whole<T: std::str::FromStr>(&self) -> Result<T, String> {
        let text = match self.value {
            Value::Number(number) => number.to_string(),
            Value::String(text) => text.trim().to_string(),
            _ => String::new(),
        };
        text.parse()
            .map_err(|_| self.expected("a whole number ≥ 0"))
    }

    /// A number (or its text).
    fn number(&self) -> Result<f64, String> {
        match self.value {
            Value::Number(number) => number.as_f64(),
            Value::String(text) => text.trim().parse().ok(),
            _ => None,
        }
        .ok_or_else(|| self.expected("a number"))
    }
}

/// A `--robot-type` value, else an error listing them (`invalid value 'boat' for '--robot-type'
/// [possible values: wheeled, ...]`).
pub fn parse_robot_type(text: &str, flag: &str) -> Result<RobotType, String> {
    RobotType::parse(text).ok_or_else(|| {
        let names: Vec<&str> = RobotType::ALL.iter().map(|t| t.as_str()).collect();
        format!(
            "invalid value '{text}' for '{flag}' [possible values: {}]",
            names.join(", ")
        )
    })
}

/// A `--simulator` value, else an error listing them.
pub fn parse_simulator(text: &str, flag: &str) -> Result<Simulator, String> {
    let text = text.trim();
    Simulator::ALL
        .into_iter()
        .find(|s| s.name() == text)
        .ok_or_else(|| {
            let names: Vec<&str> = Simulator::ALL.iter().map(|s| s.name()).collect();
            format!(
                "invalid value '{text}' for '{flag}' [possible values: {}]",
                names.join(", ")
            )
        })
}

/// An `--up-axis` value: `x`, `+y`, `-z`, ...
pub fn parse_up_axis(text: &str) -> Result<UpAxis, String> {
    UpAxis::parse(text)
        .ok_or_else(|| format!("'{text}' is not an axis: x, y or z, with an optional sign (-y)"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(json: &str) -> Result<Request, String> {
        let Ok(Value::Object(object)) = serde_json::from_str(json) else {
            return Err(format!("not an object: {json}"));
        };
        Request::from_json(&object)
    }

    #[test]
    fn keys_are_the_flags() {
        let request = request(
            r#"{"samples": 1234, "payload-mass": 2, "robot_type": "wheeled", "package_path": "a",
                "select": "U2,U7", "no_cache": true, "deep": false, "seed": null,
                "xacro_arg": ["arm:=ur5"], "simulator": ["mujoco", "drake"], "format": "json"}"#,
        )
        .expect("request");
        assert_eq!(request.samples, Some(1234));
        assert_eq!(request.payload_mass, Some(2.0));
        assert_eq!(request.robot_type, Some(RobotType::Wheeled));
        assert_eq!(request.package_path, [PathBuf::from("a")]);
        assert_eq!(request.select, Some(vec!["U2".into(), "U7".into()]));
        assert!(request.no_cache && !request.deep && request.seed.is_none());
        assert_eq!(request.xacro_args, [("arm".into(), "ur5".into())]);
        assert_eq!(request.simulator, [Simulator::Mujoco, Simulator::Drake]);
    }

    #[test]
    fn errors_name_the_flag() {
        let error = |json: &str| request(json).expect_err(json);
        assert!(error(r#"{"sampels": 3}"#).contains("'--sampels' (did you mean 'samples'?)"));
        assert!(error(r#"{"samples": "many"}"#).starts_with("--samples: expected a whole number"));
        assert!(error(r#"{"samples": 0}"#).contains("--samples"));
        assert!(error(r#"{"robot_type": "boat"}"#).contains("possible values: wheeled"));
        assert!(error(r#"{"arm_root": ["a"]}"#).contains("1 --arm-root but 0 --arm-tip"));
        assert!(error(r#"{"write_baseline": "b.json"}"#).starts_with("--write-baseline"));
        assert!(error(r#"{"fix": true}"#).starts_with("--fix"));
    }
}
