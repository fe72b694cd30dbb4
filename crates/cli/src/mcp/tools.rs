//! What each tool of `urdf_validate mcp` runs. The validation tools read their arguments into the
//! session's request ([`super::arguments::Flags::session`]: the same settings, configuration file and checks as
//! the command), so a report is the one the command computes for the same flags.

use std::path::{Path, PathBuf};

use rmcp::model::JsonObject;
use serde_json::{json, Value};
use urdf_validate_session::options::mesh_cache;
use urdf_validate_session::tasks;
use urdf_validator::diagnostics::rules;
use urdf_validator::task_query::{TaskQueryRequest, TaskQueryResponse};

use super::arguments::{
    check_names, parse, parse_with, schema, FileInput, FixInput, Flags, RuleName, RunFlags, Sweep,
    TextInput,
};
use super::policy::Policy;
use super::table::Output;

pub(super) fn validate_urdf(arguments: JsonObject) -> Result<Output, String> {
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

pub(super) fn fix_urdf(arguments: JsonObject) -> Result<Output, String> {
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

pub(super) fn validate_urdf_string(arguments: JsonObject) -> Result<Output, String> {
    let (input, flags): (TextInput, Flags) = parse_with(arguments)?;
    validate_text(input.urdf_xml, input.base_dir, &flags)
}

/// Validate URDF `xml` as the file robot.urdf in `base_dir`.
pub(super) fn validate_text(
    xml: String,
    base_dir: Option<String>,
    flags: &Flags,
) -> Result<Output, String> {
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

pub(super) fn run_pick_task(arguments: JsonObject) -> Result<Output, String> {
    let (request, flags): (TaskQueryRequest, RunFlags) = parse_with(arguments)?;
    let [response] = pick_responses(vec![request], flags.into())?
        .try_into()
        .map_err(|_| "no response to the request".to_string())?;
    Output::json(&response)
}

pub(super) fn run_pick_sweep(arguments: JsonObject) -> Result<Output, String> {
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

/// The responses to `requests`, in order: each robot's file must be inside the server's roots; each is
/// validated with its configuration file (the session crate's task sweep).
pub(super) fn pick_responses(
    requests: Vec<TaskQueryRequest>,
    flags: Flags,
) -> Result<Vec<TaskQueryResponse>, String> {
    for request in &requests {
        Policy::current().check_path("urdf_path", &request.urdf_path)?;
    }
    let request = flags.policed_request()?;
    tasks::pick_sweep(&request, &requests, &mesh_cache(request.no_cache))
}

pub(super) fn list_rules(_arguments: JsonObject) -> Result<Output, String> {
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

pub(super) fn explain_rule(arguments: JsonObject) -> Result<Output, String> {
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
pub(super) fn existing_file(path: &str) -> Result<PathBuf, String> {
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
