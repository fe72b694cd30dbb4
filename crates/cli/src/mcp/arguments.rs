//! The tools' arguments: their types (whose JSON Schemas `tools/list` shows), how a call's JSON object is
//! read into them, and the flags they share as the session's [`Request`].

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use clap::CommandFactory;
use rmcp::model::JsonObject;
use schemars::generate::SchemaSettings;
use schemars::JsonSchema;
use serde::de::DeserializeOwned;
use serde::Deserialize;
use serde_json::{json, Value};
use urdf_validate_session::request::{parse_robot_type, parse_simulator};
use urdf_validate_session::{Request, Session};
use urdf_validator::analysis::pose::PoseKind;
use urdf_validator::diagnostics::suggest::did_you_mean;
use urdf_validator::task_query::TaskQueryRequest;

use super::policy::Policy;
use crate::args::Args;

/// The flags of `urdf_validate` that the validation tools take, named as the flags with `_`.
#[derive(Debug, Default, Deserialize, JsonSchema)]
pub(super) struct Flags {
    /// Declared robot category (the structural heuristic still runs; a disagreement is an INFO finding,
    /// U730). Default: detected.
    pub(super) robot_type: Option<String>,
    /// Ground-contact links for the support polygon, e.g. ["foot_l", "foot_r"]. Default: wheels, feet
    /// or the lowest geometry.
    pub(super) contact_links: Option<Vec<String>>,
    /// Payload carried at payload_link, kg: torques and verdicts include it.
    pub(super) payload_mass: Option<f64>,
    /// Link carrying the payload. Default: the end of the longest actuated chain.
    pub(super) payload_link: Option<String>,
    /// Joint configuration for statics: zero (clamped into limits), limits (upper limits), custom
    /// (joint_angles), home (SRDF group_state; without an SRDF, an MJCF model's keyframe of that state name),
    /// worst (largest torque per joint over the samples), key:NAME (an MJCF model's keyframe).
    /// Default: zero.
    pub(super) pose: Option<String>,
    /// Joint values for pose "custom": "j1=0.5,j2=30deg" (radians or metres; deg for degrees).
    pub(super) joint_angles: Option<String>,
    /// SRDF file for pose "home" and self-collision's allowed pairs. Default: <stem>.srdf or <robot
    /// name>.srdf beside the URDF or in ../srdf/.
    pub(super) srdf: Option<String>,
    /// group_state name for pose "home". Default: home.
    pub(super) state: Option<String>,
    /// Samples per arm for the workspace (reach, task, orientation, self-collision) and for pose
    /// "worst". Default: 30000.
    pub(super) samples: Option<usize>,
    /// Seed of the sampling: same seed, same report. Default: 7.
    pub(super) seed: Option<u64>,
    /// Task reachability: pick_from_ground (0.05 m above the ground), pick_from_table (0.75 m),
    /// push_button (1.0 m), custom (height).
    pub(super) task: Option<String>,
    /// Target height above the ground for task "custom", metres.
    pub(super) height: Option<f64>,
    /// Tool orientation to reach: top_down, side, "r,p,y" (radians) or "qw,qx,qy,qz"; PASS when at
    /// least 5% of the sampled poses (at the task height, with a task) meet it.
    pub(super) orientation: Option<String>,
    /// Tolerance on the approach direction for orientation, degrees. Default: 30.
    pub(super) orientation_tolerance: Option<f64>,
    /// The tool's approach axis in the arm's tip frame: x, y, z, -x, -y, -z or "ax,ay,az". Default:
    /// from the hand towards its fingers, else z.
    pub(super) approach_axis: Option<String>,
    /// First link of each declared arm chain, paired in order with arm_tip. Default: detected arms.
    pub(super) arm_root: Option<Vec<String>>,
    /// End-effector link of each declared arm chain, paired in order with arm_root.
    pub(super) arm_tip: Option<Vec<String>>,
    /// Folders holding ROS packages, for package:// URIs and xacro's $(find pkg); searched before
    /// ROS_PACKAGE_PATH and AMENT_PREFIX_PATH.
    pub(super) package_path: Option<Vec<String>>,
    /// xacro arguments, {"name": "value"} (as name:=value on the xacro command line).
    pub(super) xacro_args: Option<BTreeMap<String, String>>,
    /// Only these rules report: codes, names, code prefixes such as U2, or ALL. Replaces the
    /// configuration file's select.
    pub(super) select: Option<Vec<String>>,
    /// These rules never report (codes, names or prefixes); added to the configuration file's ignore.
    pub(super) ignore: Option<Vec<String>>,
    /// Configuration file (urdf-validate.toml, or pyproject.toml with [tool.urdf-validate]) to use
    /// instead of the nearest one above the robot's file.
    pub(super) config: Option<String>,
    /// Read no configuration file.
    pub(super) no_config: Option<bool>,
    /// Baseline file (written by `urdf_validate --write-baseline`, or an earlier report JSON): the findings
    /// it holds are not reported and do not count (baseline{} in the report says how many it hid).
    pub(super) baseline: Option<String>,
    /// Also list the findings that the configuration or inline comments suppress (suppressed[]).
    pub(super) show_suppressed: Option<bool>,
    /// Time each phase: timings_ms in the report.
    pub(super) timings: Option<bool>,
    /// Do not read or write the mesh cache (hulls of meshes loaded before).
    pub(super) no_cache: Option<bool>,
    /// Simulator load profiles (mujoco, gazebo, pybullet, drake): what that simulator's URDF importer
    /// will do to the file, as findings U750–U759; no simulator needed.
    pub(super) simulator: Option<Vec<String>>,
    /// Seconds the validation may take; then the call fails, naming the stage it was in. 0: no limit.
    /// Default: 60.
    pub(super) timeout: Option<f64>,
}

impl Flags {
    /// The command's options for the files near `anchor` (their configuration file applies), under the
    /// server's policy ([`Flags::policed_request`]).
    pub(super) fn session(&self, anchor: &Path) -> Result<Session, String> {
        Session::new(&self.policed_request()?, Some(anchor))
    }

    /// The arguments as a request under the server's policy: the path arguments must be inside its roots,
    /// and its sandbox is added.
    pub(super) fn policed_request(&self) -> Result<Request, String> {
        let policy = Policy::current();
        let paths = [
            ("srdf", self.srdf.as_slice()),
            ("config", self.config.as_slice()),
            ("baseline", self.baseline.as_slice()),
            (
                "package_path",
                self.package_path.as_deref().unwrap_or_default(),
            ),
        ];
        for (name, values) in paths {
            for value in values {
                policy.check_path(name, Path::new(value))?;
            }
        }
        policy.check_timeout(self.timeout)?;
        let mut request = self.request()?;
        policy.apply(&mut request);
        Ok(request)
    }

    /// The arguments as the session's request (named as the flags, with `_`).
    fn request(&self) -> Result<Request, String> {
        let texts = |values: &Option<Vec<String>>| values.clone().unwrap_or_default();
        let paths = |values: &Option<Vec<String>>| {
            values
                .iter()
                .flatten()
                .map(PathBuf::from)
                .collect::<Vec<_>>()
        };
        let request = Request {
            robot_type: self
                .robot_type
                .as_deref()
                .map(|name| parse_robot_type(name, "robot_type"))
                .transpose()?,
            contact_links: self.contact_links.clone(),
            payload_mass: self.payload_mass,
            payload_link: self.payload_link.clone(),
            pose: self
                .pose
                .as_deref()
                .map(|pose| PoseKind::parse(pose).map_err(|e| format!("pose: {e}")))
                .transpose()?,
            joint_angles: self.joint_angles.clone(),
            srdf: self.srdf.as_ref().map(PathBuf::from),
            state: self.state.clone(),
            samples: self.samples,
            seed: self.seed,
            task: self.task.clone(),
            height: self.height,
            orientation: self.orientation.clone(),
            orientation_tolerance: self.orientation_tolerance,
            approach_axis: self.approach_axis.clone(),
            arm_root: texts(&self.arm_root),
            arm_tip: texts(&self.arm_tip),
            package_path: paths(&self.package_path),
            xacro_args: self
                .xacro_args
                .clone()
                .unwrap_or_default()
                .into_iter()
                .collect(),
            select: self.select.clone(),
            ignore: texts(&self.ignore),
            config: self.config.as_ref().map(PathBuf::from),
            no_config: self.no_config == Some(true),
            baseline: self.baseline.as_ref().map(PathBuf::from),
            show_suppressed: self.show_suppressed == Some(true),
            timings: self.timings == Some(true),
            no_cache: self.no_cache == Some(true),
            simulator: texts(&self.simulator)
                .iter()
                .map(|name| parse_simulator(name, "simulator"))
                .collect::<Result<_, _>>()?,
            timeout: self.timeout,
            ..Request::default()
        };
        request.check()?;
        Ok(request)
    }
}

/// The flags of the task tools: the task query sets the task, orientation and payload itself.
#[derive(Debug, Deserialize, JsonSchema)]
pub(super) struct RunFlags {
    /// Samples per arm for the workspace. Default: 30000; a few hundred is quicker and coarser.
    pub(super) samples: Option<usize>,
    /// Seed of the sampling: same seed, same answer. Default: 7.
    pub(super) seed: Option<u64>,
    /// Folders holding ROS packages, for package:// URIs and xacro's $(find pkg).
    pub(super) package_path: Option<Vec<String>>,
}

impl From<RunFlags> for Flags {
    fn from(run: RunFlags) -> Flags {
        Flags {
            samples: run.samples,
            seed: run.seed,
            package_path: run.package_path,
            ..Flags::default()
        }
    }
}

/// `validate_urdf`'s own arguments: a file or a text.
#[derive(Debug, Deserialize, JsonSchema)]
pub(super) struct FileInput {
    /// The URDF or xacro file (.urdf, .xacro, .urdf.xacro). Relative paths start from the server's
    /// working directory. Give this or `xml`.
    pub(super) path: Option<String>,
    /// The same as `path` (the name the Python tool's server used).
    pub(super) urdf_path: Option<String>,
    /// URDF XML text (not xacro), validated as the file robot.urdf in `base_dir`. Give this or `path`.
    pub(super) xml: Option<String>,
    /// With `xml`: the folder relative mesh paths, package:// look-ups and the configuration file start
    /// from. Default: the server's working directory.
    pub(super) base_dir: Option<String>,
}

/// `fix_urdf`'s own arguments.
#[derive(Debug, Deserialize, JsonSchema)]
pub(super) struct FixInput {
    /// The URDF or xacro file. Relative paths start from the server's working directory.
    pub(super) path: String,
    /// Also the unsafe fixes (effort, limits, mesh scale), and edits of files outside the input's package.
    #[serde(default)]
    pub(super) unsafe_fixes: bool,
}

/// `validate_urdf_string`'s own arguments.
#[derive(Debug, Deserialize, JsonSchema)]
pub(super) struct TextInput {
    /// The URDF document, XML text (not xacro).
    pub(super) urdf_xml: String,
    /// The folder the text stands in, as the file robot.urdf: relative mesh paths, package:// look-ups
    /// and the configuration file start there. Default: the server's working directory.
    pub(super) base_dir: Option<String>,
}

/// `run_pick_sweep`'s own argument.
#[derive(Debug, Deserialize, JsonSchema)]
pub(super) struct Sweep {
    /// The task queries, each as run_pick_task's arguments (without samples, seed and package_path,
    /// which apply to all).
    pub(super) requests: Vec<TaskQueryRequest>,
}

/// `explain_rule`'s argument.
#[derive(Debug, Deserialize, JsonSchema)]
pub(super) struct RuleName {
    /// A rule code (U205) or name (inertia-not-positive-definite).
    pub(super) code: String,
}

/// A tool without arguments.
#[derive(Debug, Deserialize, JsonSchema)]
pub(super) struct NoArguments {}

/// `arguments` as a `T`, a failure naming the argument (`samples: invalid type: ...`).
pub(super) fn parse<T: DeserializeOwned>(arguments: JsonObject) -> Result<T, String> {
    serde_path_to_error::deserialize(Value::Object(arguments)).map_err(|error| {
        let path = error.path().to_string();
        let error = error.into_inner();
        if path == "." {
            format!("invalid arguments: {error}")
        } else {
            format!("argument {path}: {error}")
        }
    })
}

/// `arguments` as a `T` and an `F`: the arguments `F`'s schema names go to `F`.
pub(super) fn parse_with<T: DeserializeOwned, F: DeserializeOwned + JsonSchema>(
    mut arguments: JsonObject,
) -> Result<(T, F), String> {
    let flags: JsonObject = property_names(&schema::<F>())
        .iter()
        .filter_map(|name| arguments.remove_entry(name.as_str()))
        .collect();
    Ok((parse(arguments)?, parse(flags)?))
}

/// Fail on an argument that `schema` does not name (a misspelt `sample` would otherwise be ignored).
pub(super) fn check_names(
    arguments: &JsonObject,
    schema: &JsonObject,
    what: &str,
) -> Result<(), String> {
    let names = property_names(schema);
    let Some(unknown) = arguments.keys().find(|key| !names.contains(key)) else {
        return Ok(());
    };
    if unknown == "overrides" {
        return Err(format!(
            "{what}: argument 'overrides' is not supported (this server has no overrides: edit the \
             URDF and call again)"
        ));
    }
    if names.is_empty() {
        return Err(format!(
            "{what}: unknown argument '{unknown}' (it takes none)"
        ));
    }
    Err(format!(
        "{what}: unknown argument '{unknown}': {} (arguments: {})",
        did_you_mean(unknown, names.iter().map(String::as_str)),
        names.join(", ")
    ))
}

/// The property names of an object schema.
pub(super) fn property_names(schema: &JsonObject) -> Vec<String> {
    schema
        .get("properties")
        .and_then(Value::as_object)
        .map(|properties| properties.keys().cloned().collect())
        .unwrap_or_default()
}

/// The JSON Schema of `T` as a tool's arguments: optional fields are simply not required (no `null`
/// type), no `$ref`s, objects closed to other properties, and the values clap accepts listed as `enum`
/// for the string arguments named as a flag with a fixed list (`robot_type`, `task`; `pose` also takes
/// `key:NAME`, so it has none).
pub(super) fn schema<T: JsonSchema>() -> JsonObject {
    let settings =
        SchemaSettings::draft2020_12().with(|settings| settings.inline_subschemas = true);
    let mut schema = match settings
        .into_generator()
        .into_root_schema_for::<T>()
        .to_value()
    {
        Value::Object(schema) => schema,
        _ => JsonObject::new(),
    };
    for key in ["$schema", "title", "description"] {
        schema.remove(key);
    }
    schema.insert("type".into(), "object".into());
    tidy(&mut schema);
    let command = Args::command();
    if let Some(Value::Object(properties)) = schema.get_mut("properties") {
        for (name, property) in properties.iter_mut() {
            let Some(arg) = command.get_arguments().find(|arg| arg.get_id() == name) else {
                continue;
            };
            let choices: Vec<Value> = arg
                .get_possible_values()
                .iter()
                .filter(|value| !value.is_hide_set())
                .map(|value| value.get_name().into())
                .collect();
            if !choices.is_empty() && property.get("type") == Some(&json!("string")) {
                property["enum"] = Value::Array(choices);
            }
        }
    }
    schema
}

/// Down the tree: an optional argument is one that may be left out, so `null` is not offered (it is still
/// read as absent); object schemas with properties take no others.
pub(super) fn tidy(schema: &mut JsonObject) {
    if let Some(Value::Array(types)) = schema.get_mut("type") {
        types.retain(|t| t != "null");
        if let [single] = types.as_slice() {
            let single = single.clone();
            schema.insert("type".into(), single);
        }
    }
    if let Some(Value::Array(branches)) = schema.get_mut("anyOf") {
        branches.retain(|branch| branch.get("type") != Some(&json!("null")));
        if let [Value::Object(single)] = branches.as_slice() {
            let single = single.clone();
            schema.remove("anyOf");
            for (key, value) in single {
                schema.entry(key).or_insert(value);
            }
        }
    }
    if schema.get("default") == Some(&Value::Null) {
        schema.remove("default");
    }
    if schema.contains_key("properties") {
        schema.insert("additionalProperties".into(), false.into());
    }
    for value in schema.values_mut() {
        match value {
            Value::Object(object) => tidy(object),
            Value::Array(items) => items
                .iter_mut()
                .filter_map(Value::as_object_mut)
                .for_each(tidy),
            _ => {}
        }
    }
}

/// One object schema with the properties (and required ones) of both.
pub(super) fn merged(mut schema: JsonObject, other: JsonObject) -> JsonObject {
    for key in ["properties", "required"] {
        let Some(theirs) = other.get(key) else {
            continue;
        };
        match (schema.get_mut(key), theirs) {
            (Some(Value::Object(ours)), Value::Object(theirs)) => {
                ours.extend(theirs.iter().map(|(k, v)| (k.clone(), v.clone())));
            }
            (Some(Value::Array(ours)), Value::Array(theirs)) => ours.extend(theirs.iter().cloned()),
            _ => {
                schema.insert(key.into(), theirs.clone());
            }
        }
    }
    schema
}
