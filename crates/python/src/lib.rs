//! `urdf_validator._native`: the Rust side of the Python package. Every function takes the command's
//! flags (the Python layer turns keyword arguments into them), releases the GIL while Rust works, and
//! returns JSON text that the Python layer wraps (`Report`, `TaskQueryResponse`).

use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use urdf_validate_cli::api::Session;
use urdf_validator::input::LoadError;
use urdf_validator::render::render_json;
use urdf_validator::task_query::{self, TaskQueryRequest};
use urdf_validator::Validation;

/// The JSON report of `validation`, or for a file that could not be validated a document with its
/// path, `overall_status` UNKNOWN, `error` (the message the command prints) and `error_location`
/// (`file`, `line`, `column`, `message`; line and column when the error has a position).
fn report_json(path: &Path, validation: Result<Validation, LoadError>) -> String {
    match validation {
        Ok(validation) => render_json(&validation.report),
        Err(error) => {
            let (file, line, column, message) = location(path, &error);
            serde_json::json!({
                "urdf_path": path.display().to_string(),
                "overall_status": "UNKNOWN",
                "error": error.to_string(),
                "error_location": {"file": file, "line": line, "column": column, "message": message},
            })
            .to_string()
        }
    }
}

/// Where a load error points: the file, line and column when known, and the message without them.
fn location(path: &Path, error: &LoadError) -> (String, Option<u32>, Option<u32>, String) {
    let file = path.display().to_string();
    match error {
        LoadError::Xml {
            path,
            line,
            column,
            message,
        } => (
            path.display().to_string(),
            Some(*line),
            Some(*column),
            format!("not well-formed XML: {message}"),
        ),
        LoadError::Xacro {
            message,
            location: Some(at),
            ..
        } => {
            // The message without its `file:line:col: ` prefix.
            let prefix = format!("{}:{}:{}: ", at.path.display(), at.line, at.col);
            let detail = message
                .find(&prefix)
                .map_or(message.as_str(), |i| &message[i + prefix.len()..]);
            (
                at.path.display().to_string(),
                u32::try_from(at.line).ok(),
                u32::try_from(at.col).ok(),
                detail.to_string(),
            )
        }
        other => (file, None, None, other.to_string()),
    }
}

/// The options for files near `anchor`, or `ValueError` naming the bad flag.
fn session(flags: &[String], anchor: Option<&Path>) -> PyResult<Session> {
    Session::from_flags(flags, anchor).map_err(PyValueError::new_err)
}

/// Validate the file at `path` with the command's `flags`; the JSON report.
#[pyfunction]
fn validate(py: Python<'_>, path: PathBuf, flags: Vec<String>) -> PyResult<String> {
    py.detach(|| {
        let session = session(&flags, Some(&path))?;
        Ok(report_json(&path, session.validate(&path)))
    })
}

/// Validate every path in parallel; one JSON report per path, in order. Each file uses the
/// configuration file nearest to it, as the command does.
#[pyfunction]
fn validate_many(py: Python<'_>, paths: Vec<PathBuf>, flags: Vec<String>) -> PyResult<Vec<String>> {
    py.detach(|| {
        let mut sessions: HashMap<PathBuf, Session> = HashMap::new();
        for path in &paths {
            let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
            if let Entry::Vacant(entry) = sessions.entry(dir) {
                entry.insert(session(&flags, Some(path))?);
            }
        }
        Ok(urdf_validate_cli::batch::map_files(&paths, |path| {
            let dir = path.parent().unwrap_or(Path::new(""));
            match sessions.get(dir) {
                Some(session) => report_json(path, session.validate(path)),
                None => report_json(
                    path,
                    Err(LoadError::Usage {
                        path: path.clone(),
                        message: "no options for this file".to_string(),
                    }),
                ),
            }
        }))
    })
}

/// Validate URDF `xml` as if it were the file `path` (relative mesh paths and the report's name use it).
#[pyfunction]
fn validate_string(
    py: Python<'_>,
    xml: String,
    path: PathBuf,
    flags: Vec<String>,
) -> PyResult<String> {
    py.detach(|| {
        let session = session(&flags, Some(&path))?;
        Ok(report_json(&path, session.validate_text(xml, &path)))
    })
}

/// The task-query API: `requests_json` is a JSON list of requests (the spec's field names); returns the
/// JSON list of responses, in order, computed in parallel.
#[pyfunction]
fn run_pick_sweep(py: Python<'_>, requests_json: String, flags: Vec<String>) -> PyResult<String> {
    py.detach(|| {
        let requests: Vec<TaskQueryRequest> = serde_json::from_str(&requests_json)
            .map_err(|e| PyValueError::new_err(format!("task requests: {e}")))?;
        let session = session(&flags, None)?;
        let responses = task_query::run_pick_sweep(&requests, session.options());
        serde_json::to_string(&responses).map_err(|e| PyValueError::new_err(e.to_string()))
    })
}

/// Run the `urdf_validate` command with `argv` (program name first); returns its exit status.
#[pyfunction]
fn main(py: Python<'_>, argv: Vec<String>) -> u8 {
    py.detach(|| urdf_validate_cli::main_from(argv))
}

/// The native module.
#[pymodule]
fn _native(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("__version__", urdf_validator::VERSION)?;
    module.add_function(wrap_pyfunction!(validate, module)?)?;
    module.add_function(wrap_pyfunction!(validate_many, module)?)?;
    module.add_function(wrap_pyfunction!(validate_string, module)?)?;
    module.add_function(wrap_pyfunction!(run_pick_sweep, module)?)?;
    module.add_function(wrap_pyfunction!(main, module)?)?;
    Ok(())
}
