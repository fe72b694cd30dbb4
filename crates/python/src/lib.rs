//! `urdf_validator._native`: the Rust side of the Python package. Every function takes the keyword
//! arguments as a JSON object (the command's flags, `_` for `-`: the session crate's `Request`), releases
//! the GIL while Rust works, and returns JSON text that the Python layer wraps (`Report`,
//! `TaskQueryResponse`). The `urdf_validate` console command is the command's own binary, shipped in the
//! wheel beside this module.

use std::path::{Path, PathBuf};

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use urdf_validate_session::options::mesh_cache;
use urdf_validate_session::{tasks, Batch, Request, Session};
use urdf_validator::input::LoadError;
use urdf_validator::render::render_json;
use urdf_validator::task_query::TaskQueryRequest;
use urdf_validator::{Error, Validation};

/// The JSON report of `validation`, or for a file that could not be validated a document with its
/// path, `overall_status` UNKNOWN, `error` (the message the command prints) and `error_location`
/// (`file`, `line`, `column`, `message`; line and column when the error has a position).
fn report_json(path: &Path, validation: Result<Validation, Error>) -> String {
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
fn location(path: &Path, error: &Error) -> (String, Option<u32>, Option<u32>, String) {
    let file = path.display().to_string();
    match error {
        Error::Load(LoadError::Xml {
            path,
            line,
            column,
            message,
        }) => (
            path.display().to_string(),
            Some(*line),
            Some(*column),
            format!("not well-formed XML: {message}"),
        ),
        Error::Load(LoadError::Xacro {
            message,
            location: Some(at),
            ..
        }) => {
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

/// The request of the keyword arguments `options` (a JSON object), or `ValueError` naming the bad one.
fn request(options: &str) -> PyResult<Request> {
    match serde_json::from_str(options) {
        Ok(serde_json::Value::Object(object)) => {
            Request::from_json(&object).map_err(PyValueError::new_err)
        }
        _ => Err(PyValueError::new_err(format!(
            "options: expected a JSON object, got {options}"
        ))),
    }
}

/// The session for files near `anchor`, or `ValueError` naming the bad option.
fn session(options: &str, anchor: Option<&Path>) -> PyResult<Session> {
    Session::new(&request(options)?, anchor).map_err(PyValueError::new_err)
}

/// Validate the file at `path` with the keyword arguments `options` (JSON); the JSON report.
#[pyfunction]
fn validate(py: Python<'_>, path: PathBuf, options: String) -> PyResult<String> {
    py.detach(|| {
        let session = session(&options, Some(&path))?;
        Ok(report_json(&path, session.validate(&path)))
    })
}

/// Validate every path in parallel; one JSON report per path, in order. Each file uses the
/// configuration file nearest to it, as the command does.
#[pyfunction]
fn validate_many(py: Python<'_>, paths: Vec<PathBuf>, options: String) -> PyResult<Vec<String>> {
    py.detach(|| {
        let request = request(&options)?;
        let batch = Batch::new(&request, &paths, &mesh_cache(request.no_cache))
            .map_err(PyValueError::new_err)?;
        let validations = batch.validate();
        Ok(paths
            .iter()
            .zip(validations)
            .map(|(path, validation)| report_json(path, validation))
            .collect())
    })
}

/// Validate URDF `xml` as if it were the file `path` (relative mesh paths and the report's name use it).
#[pyfunction]
fn validate_string(
    py: Python<'_>,
    xml: String,
    path: PathBuf,
    options: String,
) -> PyResult<String> {
    py.detach(|| {
        let session = session(&options, Some(&path))?;
        Ok(report_json(&path, session.validate_text(xml, &path)))
    })
}

/// The task-query API: `requests_json` is a JSON list of requests (the spec's field names); returns the
/// JSON list of responses, in order, computed in parallel (each robot with its own configuration file).
#[pyfunction]
fn run_pick_sweep(py: Python<'_>, requests_json: String, options: String) -> PyResult<String> {
    py.detach(|| {
        let queries: Vec<TaskQueryRequest> = serde_json::from_str(&requests_json)
            .map_err(|e| PyValueError::new_err(format!("task requests: {e}")))?;
        let request = request(&options)?;
        let responses = tasks::pick_sweep(&request, &queries, &mesh_cache(request.no_cache))
            .map_err(PyValueError::new_err)?;
        serde_json::to_string(&responses).map_err(|e| PyValueError::new_err(e.to_string()))
    })
}

/// The native module.
#[pymodule]
fn _native(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("__version__", urdf_validator::VERSION)?;
    module.add_function(wrap_pyfunction!(validate, module)?)?;
    module.add_function(wrap_pyfunction!(validate_many, module)?)?;
    module.add_function(wrap_pyfunction!(validate_string, module)?)?;
    module.add_function(wrap_pyfunction!(run_pick_sweep, module)?)?;
    Ok(())
}
