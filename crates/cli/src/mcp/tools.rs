//! The tools of `urdf_validate mcp`: their arguments (JSON Schemas from the argument types) and what
//! each runs. The validation tools turn their arguments into `urdf_validate` flags and set them up with
//! the CLI's own code ([`Session`]: flags, configuration file, checks), so a report is the one the CLI
//! computes for the same flags.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, LazyLock};

use clap::CommandFactory;
use rmcp::model::{CallToolResult, ContentBlock, JsonObject, Tool, ToolAnnotations};
use schemars::generate::SchemaSettings;
use schemars::JsonSchema;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use urdf_validate_session::request::{parse_robot_type, parse_simulator};
use urdf_validate_session::{Request, Session};
use urdf_validator::analysis::pose::PoseKind;
use urdf_validator::diagnostics::rules;
use urdf_validator::diagnostics::suggest::did_you_mean;
use urdf_validator::report::Report;
use urdf_validator::task_query::{self, TaskQueryRequest, TaskQueryResponse};

use super::policy::Policy;
use crate::args::Args;

/// One tool: what `tools/list` shows of it, and what a call runs.
pub struct ToolDef {
    /// Its name.
    name: &'static str,
    /// What it does, for the agent choosing a tool.
    description: &'static str,
    /// The JSON Schema of its arguments.
    schema: fn() -> JsonObject,
    /// The call, on checked argument names.
    run: fn(JsonObject) -> Result<Output, String>,
}

/// Every tool.
static TOOLS: &[ToolDef] = &[
    ToolDef {
        name: "validate_urdf",
        description: "Validate a robot description with the full physics-aware pipeline (structure, \
            mass and inertia, statics at a pose, stability, workspace reach, self-collision, and the \
            task, orientation and payload checks asked for). Give `path` (a URDF or xacro file) or `xml` \
            (URDF text, with `base_dir` for its relative mesh paths). The text result is the verdict and \
            every finding (severity, rule code, file:line:col, message); the structured result is the \
            complete JSON report `urdf_validate` writes as <name>_validation.json (overall_status PASS, \
            WARN, FAIL or UNKNOWN, confidence_level, the sections, findings[]; rule codes: see \
            explain_rule). The optional arguments are the CLI's flags; a urdf-validate.toml (or \
            pyproject.toml [tool.urdf-validate]) near the file applies, as on the command line. Writes \
            no report file. samples defaults to 30000 per arm (seconds on big robots); a few hundred \
            gives a quick, coarser workspace.",
        schema: || merged(schema::<FileInput>(), schema::<Flags>()),
        run: validate_urdf,
    },
    ToolDef {
        name: "validate_urdf_string",
        description: "validate_urdf with `xml` (the Python tool's server had this tool): URDF XML given \
            as text (not xacro) as `urdf_xml`. The text stands for the file robot.urdf in base_dir (default: the \
            server's working directory): relative mesh paths, package:// look-ups and the \
            configuration file start there. Takes validate_urdf's optional arguments.",
        schema: || merged(schema::<TextInput>(), schema::<Flags>()),
        run: validate_urdf_string,
    },
    ToolDef {
        name: "check_pick_task",
        description: "Can this robot pick an object of this mass at this place, in this orientation? \
            Runs the full pipeline with the target's height as the task, the orientation and the mass \
            as payload, and answers with five sub-checks: reach, reach_orientation, payload_strength, \
            stability_during_reach, self_collision, each PASS, FAIL, N/A (not asked) or UNKNOWN with a \
            reason (numbers), the bottleneck link or joint and a confidence. overall_status is FAIL when \
            a sub-check fails, else UNKNOWN when one could not be assessed, else PASS. A robot that \
            cannot be loaded gives an UNKNOWN urdf_load sub-check, not an error.",
        schema: || merged(schema::<TaskQueryRequest>(), schema::<RunFlags>()),
        run: run_pick_task,
    },
    ToolDef {
        name: "run_pick_task",
        description: "check_pick_task under the name the Python tool's MCP server used.",
        schema: || merged(schema::<TaskQueryRequest>(), schema::<RunFlags>()),
        run: run_pick_task,
    },
    ToolDef {
        name: "run_pick_sweep",
        description: "check_pick_task for every request of `requests`, in parallel: the responses in \
            request order, as {\"responses\": [...]}. A request that cannot run gets its own UNKNOWN \
            response and the others still run.",
        schema: || merged(schema::<Sweep>(), schema::<RunFlags>()),
        run: run_pick_sweep,
    },
    ToolDef {
        name: "fix_urdf",
        description: "The fixes of validate_urdf's findings for a file (`path`), as a unified diff of the \
            files the user edits (the xacro source for xacro input): what `urdf_validate --diff` prints. \
            Safe fixes only (an axis normalised, limits a continuous joint ignores removed, whitespace \
            before <?xml) unless `unsafe_fixes` (effort, limits, mesh scale: the robot changes). Writes \
            nothing; apply the diff, or run `urdf_validate --fix`. The structured result: diff, files, \
            fixes, unsafe_left (fixes left out for want of unsafe_fixes) and skipped (each with why).",
        schema: || merged(schema::<FixInput>(), schema::<Flags>()),
        run: fix_urdf,
    },
    ToolDef {
        name: "list_rules",
        description: "Every rule the validator reports: its code (U205), name, default severity, report \
            section and what it checks, as {\"rules\": [...]}.",
        schema: schema::<NoArguments>,
        run: list_rules,
    },
    ToolDef {
        name: "explain_rule",
        description: "A rule's documentation: what it checks, why it matters (which tool refuses or \
            misbehaves) and how to fix it. `code` is a code such as U205 or a name such as \
            inertia-not-positive-definite.",
        schema: schema::<RuleName>,
        run: explain_rule,
    },
];

/// The tools as `tools/list` gives them (schemas built once).
pub fn listed() -> &'static [Tool] {
    static LISTED: LazyLock<Vec<Tool>> = LazyLock::new(|| {
        TOOLS
            .iter()
            .map(|tool| {
                Tool::new(tool.name, tool.description, Arc::new((tool.schema)()))
                    .with_annotations(ToolAnnotations::new().read_only(true).open_world(false))
            })
            .collect()
    });
    &LISTED
}

/// The tool called `name`.
pub fn find(name: &str) -> Option<&'static ToolDef> {
    TOOLS.iter().find(|tool| tool.name == name)
}

/// The names of the tools.
pub fn names() -> Vec<&'static str> {
    TOOLS.iter().map(|tool| tool.name).collect()
}

/// Run `tool` on `arguments` (blocking): its output, or the one-line message of an error result.
pub fn call(tool: &ToolDef, arguments: JsonObject) -> Result<Output, String> {
    let schema = listed()
        .iter()
        .find(|listed| listed.name == tool.name)
        .map(|listed| listed.input_schema.clone())
        .unwrap_or_default();
    check_names(&arguments, &schema, tool.name)?;
    (tool.run)(arguments)
}

/// A tool's answer: JSON for programs (`structuredContent`) and text for the model.
pub struct Output {
    /// The JSON result.
    structured: Value,
    /// The text shown for it.
    text: String,
}

impl Output {
    /// `value`, shown as indented JSON.
    fn json(value: &impl Serialize) -> Result<Output, String> {
        let structured = serde_json::to_value(value)
            .map_err(|error| format!("cannot serialise the result: {error}"))?;
        let text = serde_json::to_string_pretty(&structured).unwrap_or_default();
        Ok(Output { structured, text })
    }

    /// A validation report: the whole report as JSON, the verdict and the findings as text.
    fn report(report: &Report) -> Result<Output, String> {
        let mut text = format!(
            "{}: {} (confidence {}), {} finding(s)\n",
            report.robot_name,
            report.overall_status.label(),
            report.confidence_level.label(),
            report.findings.len()
        );
        for finding in &report.findings {
            let at = match (&finding.file, finding.line, finding.column) {
                (Some(file), Some(line), Some(column)) => format!("{file}:{line}:{column}: "),
                (Some(file), _, _) => format!("{file}: "),
                _ => String::new(),
            };
            text.push_str(&format!(
                "{} {} {}: {at}{}\n",
                finding.severity.label(),
                finding.rule,
                finding.name,
                finding.message
            ));
        }
        Ok(Output {
            text,
            ..Output::json(report)?
        })
    }

    /// The successful tool result.
    pub fn into_result(self) -> CallToolResult {
        let mut result = CallToolResult::success(vec![ContentBlock::text(self.text)]);
        result.structured_content = Some(self.structured);
        result
    }
}

/// The flags of `urdf_validate` that the validation tools take, named as the flags with `_`.
#[derive(Debug, Default, Deserialize, JsonSchema)]
struct Flags {
    /// Declared robot category (the structural heuristic still runs; a disagreement is an INFO finding,
    /// U730). Default: detected.
    robot_type: Option<String>,
    /// Ground-contact links for the support polygon, e.g. ["foot_l", "foot_r"]. Default: wheels, feet
    /// or the lowest geometry.
    contact_links: Option<Vec<String>>,
    /// Payload carried at payload_link, kg: torques and verdicts include it.
    payload_mass: Option<f64>,
    /// Link carrying the payload. Default: the end of the longest actuated chain.
    payload_link: Option<String>,
    /// Joint configuration for statics: zero (clamped into limits), limits (upper limits), custom
    /// (joint_angles), home (SRDF group_state; without an SRDF, an MJCF model's keyframe of that state name),
    /// worst (largest torque per joint over the samples), key:NAME (an MJCF model's keyframe).
    /// Default: zero.
    pose: Option<String>,
    /// Joint values for pose "custom": "j1=0.5,j2=30deg" (radians or metres; deg for degrees).
    joint_angles: Option<String>,
    /// SRDF file for pose "home" and self-collision's allowed pairs. Default: <stem>.srdf or <robot
    /// name>.srdf beside the URDF or in ../srdf/.
    srdf: Option<String>,
    /// group_state name for pose "home". Default: home.
    state: Option<String>,
    /// Samples per arm for the workspace (reach, task, orientation, self-collision) and for pose
    /// "worst". Default: 30000.
    samples: Option<usize>,
    /// Seed of the sampling: same seed, same report. Default: 7.
    seed: Option<u64>,
    /// Task reachability: pick_from_ground (0.05 m above the ground), pick_from_table (0.75 m),
    /// push_button (1.0 m), custom (height).
    task: Option<String>,
    /// Target height above the ground for task "custom", metres.
    height: Option<f64>,
    /// Tool orientation to reach: top_down, side, "r,p,y" (radians) or "qw,qx,qy,qz"; PASS when at
    /// least 5% of the sampled poses (at the task height, with a task) meet it.
    orientation: Option<String>,
    /// Tolerance on the approach direction for orientation, degrees. Default: 30.
    orientation_tolerance: Option<f64>,
    /// The tool's approach axis in the arm's tip frame: x, y, z, -x, -y, -z or "ax,ay,az". Default:
    /// from the hand towards its fingers, else z.
    approach_axis: Option<String>,
    /// First link of each declared arm chain, paired in order with arm_tip. Default: detected arms.
    arm_root: Option<Vec<String>>,
    /// End-effector link of each declared arm chain, paired in order with arm_root.
    arm_tip: Option<Vec<String>>,
    /// Folders holding ROS packages, for package:// URIs and xacro's $(find pkg); searched before
    /// ROS_PACKAGE_PATH and AMENT_PREFIX_PATH.
    package_path: Option<Vec<String>>,
    /// xacro arguments, {"name": "value"} (as name:=value on the xacro command line).
    xacro_args: Option<BTreeMap<String, String>>,
    /// Only these rules report: codes, names, code prefixes such as U2, or ALL. Replaces the
    /// configuration file's select.
    select: Option<Vec<String>>,
    /// These rules never report (codes, names or prefixes); added to the configuration file's ignore.
    ignore: Option<Vec<String>>,
    /// Configuration file (urdf-validate.toml, or pyproject.toml with [tool.urdf-validate]) to use
    /// instead of the nearest one above the robot's file.
    config: Option<String>,
    /// Read no configuration file.
    no_config: Option<bool>,
    /// Baseline file (written by `urdf_validate --write-baseline`, or an earlier report JSON): the findings
    /// it holds are not reported and do not count (baseline{} in the report says how many it hid).
    baseline: Option<String>,
    /// Also list the findings that the configuration or inline comments suppress (suppressed[]).
    show_suppressed: Option<bool>,
    /// Time each phase: timings_ms in the report.
    timings: Option<bool>,
    /// Do not read or write the mesh cache (hulls of meshes loaded before).
    no_cache: Option<bool>,
    /// Simulator load profiles (mujoco, gazebo, pybullet, drake): what that simulator's URDF importer
    /// will do to the file, as findings U750–U759; no simulator needed.
    simulator: Option<Vec<String>>,
    /// Seconds the validation may take; then the call fails, naming the stage it was in. 0: no limit.
    /// Default: 60.
    timeout: Option<f64>,
}

impl Flags {
    /// The command's options for the files near `anchor` (their configuration file applies), under the
    /// server's policy: the path arguments must be inside its roots, and its sandbox flags are added.
    fn session(&self, anchor: &Path) -> Result<Session, String> {
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
        Session::new(&request, Some(anchor))
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
struct RunFlags {
    /// Samples per arm for the workspace. Default: 30000; a few hundred is quicker and coarser.
    samples: Option<usize>,
    /// Seed of the sampling: same seed, same answer. Default: 7.
    seed: Option<u64>,
    /// Folders holding ROS packages, for package:// URIs and xacro's $(find pkg).
    package_path: Option<Vec<String>>,
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
struct FileInput {
    /// The URDF or xacro file (.urdf, .xacro, .urdf.xacro). Relative paths start from the server's
    /// working directory. Give this or `xml`.
    path: Option<String>,
    /// The same as `path` (the name the Python tool's server used).
    urdf_path: Option<String>,
    /// URDF XML text (not xacro), validated as the file robot.urdf in `base_dir`. Give this or `path`.
    xml: Option<String>,
    /// With `xml`: the folder relative mesh paths, package:// look-ups and the configuration file start
    /// from. Default: the server's working directory.
    base_dir: Option<String>,
}

/// `fix_urdf`'s own arguments.
#[derive(Debug, Deserialize, JsonSchema)]
struct FixInput {
    /// The URDF or xacro file. Relative paths start from the server's working directory.
    path: String,
    /// Also the unsafe fixes (effort, limits, mesh scale), and edits of files outside the input's package.
    #[serde(default)]
    unsafe_fixes: bool,
}

/// `validate_urdf_string`'s own arguments.
#[derive(Debug, Deserialize, JsonSchema)]
struct TextInput {
    /// The URDF document, XML text (not xacro).
    urdf_xml: String,
    /// The folder the text stands in, as the file robot.urdf: relative mesh paths, package:// look-ups
    /// and the configuration file start there. Default: the server's working directory.
    base_dir: Option<String>,
}

/// `run_pick_sweep`'s own argument.
#[derive(Debug, Deserialize, JsonSchema)]
struct Sweep {
    /// The task queries, each as run_pick_task's arguments (without samples, seed and package_path,
    /// which apply to all).
    requests: Vec<TaskQueryRequest>,
}

/// `explain_rule`'s argument.
#[derive(Debug, Deserialize, JsonSchema)]
struct RuleName {
    /// A rule code (U205) or name (inertia-not-positive-definite).
    code: String,
}

/// A tool without arguments.
#[derive(Debug, Deserialize, JsonSchema)]
struct NoArguments {}

fn validate_urdf(arguments: JsonObject) -> Result<Output, String> {
    let (input, flags): (FileInput, Flags) = parse_with(arguments)?;
    match (input.path.or(input.urdf_path), input.xml) {
        (Some(path), None) => {
            if input.base_dir.is_some() {
                return Err("base_dir goes with xml, not with path".to_string());
            }
            let file = existing_file(&path)?;
            Policy::current().check_path("path", &file)?;
            let validation = flags
                .session(&file)?
                .validate(&file)
                .map_err(|error| error.to_string())?;
            Output::report(&validation.report)
        }
        (None, Some(xml)) => validate_text(xml, input.base_dir, &flags),
        (Some(_), Some(_)) => Err("give path or xml, not both".to_string()),
        (None, None) => Err("missing path (a URDF or xacro file) or xml (URDF text)".to_string()),
    }
}

fn fix_urdf(arguments: JsonObject) -> Result<Output, String> {
    let (input, flags): (FixInput, Flags) = parse_with(arguments)?;
    let file = existing_file(&input.path)?;
    Policy::current().check_path("path", &file)?;
    let validation = flags
        .session(&file)?
        .validate(&file)
        .map_err(|error| error.to_string())?;
    let policy = crate::fixes::Policy {
        unsafe_fixes: input.unsafe_fixes,
        from_overrides: false,
        package_paths: flags
            .package_path
            .as_deref()
            .unwrap_or_default()
            .iter()
            .map(PathBuf::from)
            .collect(),
    };
    let plan = crate::fixes::plan(&[&validation], &policy);
    let diff = crate::fixes::diff(&plan);
    let fixes: usize = plan.files.iter().map(|f| f.fixes).sum();
    let files: Vec<String> = plan
        .files
        .iter()
        .map(|f| f.path.display().to_string())
        .collect();
    let mut output = Output::json(&json!({
        "diff": diff,
        "files": files,
        "fixes": fixes,
        "unsafe_left": plan.unsafe_left,
        "skipped": plan.skipped,
    }))?;
    output.text = if diff.is_empty() {
        format!(
            "nothing to fix{}",
            match plan.unsafe_left {
                0 => String::new(),
                n => format!(" ({n} unsafe fix(es) with unsafe_fixes)"),
            }
        )
    } else {
        diff
    };
    Ok(output)
}

fn validate_urdf_string(arguments: JsonObject) -> Result<Output, String> {
    let (input, flags): (TextInput, Flags) = parse_with(arguments)?;
    validate_text(input.urdf_xml, input.base_dir, &flags)
}

/// Validate URDF `xml` as the file robot.urdf in `base_dir`.
fn validate_text(xml: String, base_dir: Option<String>, flags: &Flags) -> Result<Output, String> {
    let policy = Policy::current();
    policy.check_xml(&xml)?;
    if let Some(dir) = &base_dir {
        policy.check_path("base_dir", Path::new(dir))?;
    }
    let dir = match base_dir {
        Some(dir) if Path::new(&dir).is_dir() => PathBuf::from(dir),
        Some(dir) => {
            return Err(format!(
                "{dir}: no such directory (expected base_dir, the folder that relative mesh paths \
                 start from)"
            ))
        }
        None => std::env::current_dir().unwrap_or_default(),
    };
    let validation = flags
        .session(&dir)?
        .validate_text(xml, &dir.join("robot.urdf"))
        .map_err(|error| error.to_string())?;
    Output::report(&validation.report)
}

fn run_pick_task(arguments: JsonObject) -> Result<Output, String> {
    let (request, flags): (TaskQueryRequest, RunFlags) = parse_with(arguments)?;
    let [response] = pick_responses(vec![request], flags.into())?
        .try_into()
        .map_err(|_| "no response to the request".to_string())?;
    Output::json(&response)
}

fn run_pick_sweep(arguments: JsonObject) -> Result<Output, String> {
    let request_schema = schema::<TaskQueryRequest>();
    if let Some(Value::Array(requests)) = arguments.get("requests") {
        for (i, request) in requests.iter().enumerate() {
            if let Value::Object(request) = request {
                check_names(request, &request_schema, &format!("requests[{i}]"))?;
            }
        }
    }
    let (sweep, flags): (Sweep, RunFlags) = parse_with(arguments)?;
    if sweep.requests.is_empty() {
        return Err("requests is empty (expected at least one task query)".to_string());
    }
    let responses = pick_responses(sweep.requests, flags.into())?;
    Output::json(&json!({ "responses": responses }))
}

/// The answers to `requests`, in order. The requests on one robot share their options (its
/// configuration file and the flags) and run in parallel.
fn pick_responses(
    requests: Vec<TaskQueryRequest>,
    flags: Flags,
) -> Result<Vec<TaskQueryResponse>, String> {
    let mut robots: Vec<(PathBuf, Vec<usize>)> = Vec::new();
    for (i, request) in requests.iter().enumerate() {
        match robots
            .iter_mut()
            .find(|(path, _)| *path == request.urdf_path)
        {
            Some((_, indices)) => indices.push(i),
            None => robots.push((request.urdf_path.clone(), vec![i])),
        }
    }
    let mut responses: Vec<Option<TaskQueryResponse>> = vec![None; requests.len()];
    for (path, indices) in robots {
        Policy::current().check_path("urdf_path", &path)?;
        let session = flags.session(&path)?;
        let batch: Vec<TaskQueryRequest> = indices.iter().map(|&i| requests[i].clone()).collect();
        for (i, response) in indices
            .into_iter()
            .zip(task_query::run_pick_sweep(&batch, session.options()))
        {
            responses[i] = Some(response);
        }
    }
    Ok(responses.into_iter().flatten().collect())
}

fn list_rules(_arguments: JsonObject) -> Result<Output, String> {
    let rules: Vec<Value> = rules::ALL
        .iter()
        .map(|rule| {
            json!({
                "code": rule.code,
                "name": rule.name,
                "severity": rule.severity.label(),
                "section": rule.section.as_str(),
                "what": rule.what,
            })
        })
        .collect();
    Output::json(&json!({ "rules": rules }))
}

fn explain_rule(arguments: JsonObject) -> Result<Output, String> {
    let name: RuleName = parse(arguments)?;
    let rule = crate::find_rule(&name.code)
        .map_err(|message| format!("{message}; list_rules lists them all"))?;
    Ok(Output {
        text: rules::explain(rule),
        ..Output::json(&json!({
            "code": rule.code,
            "name": rule.name,
            "severity": rule.severity.label(),
            "section": rule.section.as_str(),
            "what": rule.what,
            "why": rule.why,
            "fix": rule.fix,
        }))?
    })
}

/// `path` when it is a file, else what it is and what was expected.
fn existing_file(path: &str) -> Result<PathBuf, String> {
    let file = PathBuf::from(path);
    if file.is_file() {
        return Ok(file);
    }
    let what = if file.is_dir() {
        "is a directory"
    } else {
        "no such file"
    };
    let from = match std::env::current_dir() {
        Ok(dir) if file.is_relative() => format!(
            "; a relative path starts from the server's working directory, {}",
            dir.display()
        ),
        _ => String::new(),
    };
    Err(format!(
        "{path}: {what} (expected a URDF or xacro file{from})"
    ))
}

/// `arguments` as a `T`, a failure naming the argument (`samples: invalid type: ...`).
fn parse<T: DeserializeOwned>(arguments: JsonObject) -> Result<T, String> {
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
fn parse_with<T: DeserializeOwned, F: DeserializeOwned + JsonSchema>(
    mut arguments: JsonObject,
) -> Result<(T, F), String> {
    let flags: JsonObject = property_names(&schema::<F>())
        .iter()
        .filter_map(|name| arguments.remove_entry(name.as_str()))
        .collect();
    Ok((parse(arguments)?, parse(flags)?))
}

/// Fail on an argument that `schema` does not name (a misspelt `sample` would otherwise be ignored).
fn check_names(arguments: &JsonObject, schema: &JsonObject, what: &str) -> Result<(), String> {
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
fn property_names(schema: &JsonObject) -> Vec<String> {
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
fn schema<T: JsonSchema>() -> JsonObject {
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
fn tidy(schema: &mut JsonObject) {
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
fn merged(mut schema: JsonObject, other: JsonObject) -> JsonObject {
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
