//! A session: the library options for the files one configuration file governs, and the time each
//! file may take. Every front end validates through one, so a report is the one the command computes
//! for the same settings.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Duration;

use urdf_validator::input::mesh::MeshCache;
use urdf_validator::Error;
use urdf_validator::{Options, Validation};

use crate::options::{mesh_cache, options_for, timeout_of};
use crate::request::Request;

/// Validation options built from a [`Request`] and its configuration file.
#[derive(Clone, Debug)]
pub struct Session {
    options: Options,
    timeout: Option<Duration>,
}

impl Session {
    /// The options of `request` for files near `anchor` (their configuration file is the nearest
    /// `urdf-validate.toml` or `pyproject.toml` from there, unless the request names one or says
    /// `no_config`), with a mesh cache of their own.
    pub fn new(request: &Request, anchor: Option<&Path>) -> Result<Session, String> {
        let config = config_file(request, anchor.unwrap_or(Path::new(".")));
        Session::with_config(request, config.as_deref(), &mesh_cache(request.no_cache))
    }

    /// The options of `request` merged with configuration file `config` (none: the request and the
    /// defaults alone), sharing `meshes` with the rest of the run.
    pub fn with_config(
        request: &Request,
        config: Option<&Path>,
        meshes: &MeshCache,
    ) -> Result<Session, String> {
        request.check()?;
        let timeout = timeout_of(request)?;
        let effective = crate::config::load(config, request)?;
        let merged = effective.applied_to(request);
        let options =
            options_for(&merged, effective.settings, meshes).map_err(|message| match config {
                Some(path) => format!("{message} (with the settings of {})", path.display()),
                None => message,
            })?;
        Ok(Session { options, timeout })
    }

    /// The session without the baseline of its request or configuration file: every finding reported.
    pub fn without_baseline(mut self) -> Session {
        self.options.baseline = None;
        self
    }

    /// How long one validation may take (`--timeout`; `None`: no limit).
    pub fn timeout(&self) -> Option<Duration> {
        self.timeout
    }

    /// The library options.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// Validate one file (within `--timeout`).
    pub fn validate(&self, path: &Path) -> Result<Validation, Error> {
        crate::watchdog::validate_within(
            path,
            &self.options,
            self.timeout,
            urdf_validator::validate,
        )
    }

    /// Validate URDF `text`, as if read from `path` (relative meshes and the report's name use it), within
    /// `--timeout`.
    pub fn validate_text(&self, text: String, path: &Path) -> Result<Validation, Error> {
        crate::watchdog::validate_within(path, &self.options, self.timeout, move |path, options| {
            urdf_validator::validate_text(text, path, options)
        })
    }
}

/// The configuration file of inputs near `anchor`: the request's (`config`), none (`no_config`), else
/// the nearest found from `anchor` upwards.
pub fn config_file(request: &Request, anchor: &Path) -> Option<PathBuf> {
    if request.no_config {
        return None;
    }
    request
        .config
        .clone()
        .or_else(|| crate::config::discover(anchor))
}

/// The sessions of a batch of files: one per configuration file, sharing one mesh cache.
pub struct Batch {
    files: Vec<PathBuf>,
    sessions: Vec<Session>,
    /// The index in `sessions` of each file's.
    session_of: Vec<usize>,
}

impl Batch {
    /// The sessions of `files` (each file's configuration file found from its folder, once per folder);
    /// the first configuration that cannot be used is the error.
    pub fn new(request: &Request, files: &[PathBuf], meshes: &MeshCache) -> Result<Batch, String> {
        let mut config_of_dir: HashMap<PathBuf, Option<PathBuf>> = HashMap::new();
        let mut configs: Vec<Option<PathBuf>> = Vec::new();
        let mut sessions = Vec::new();
        let mut session_of = Vec::with_capacity(files.len());
        for file in files {
            let dir = file.parent().unwrap_or(Path::new("")).to_path_buf();
            let config = config_of_dir
                .entry(dir)
                .or_insert_with(|| config_file(request, file))
                .clone();
            let index = match configs.iter().position(|c| *c == config) {
                Some(index) => index,
                None => {
                    sessions.push(Session::with_config(request, config.as_deref(), meshes)?);
                    configs.push(config);
                    sessions.len() - 1
                }
            };
            session_of.push(index);
        }
        Ok(Batch {
            files: files.to_vec(),
            sessions,
            session_of,
        })
    }

    /// The session of the `index`-th file.
    pub fn session(&self, index: usize) -> &Session {
        &self.sessions[self.session_of[index]]
    }

    /// Validate every file in parallel (on threads of their own: [`crate::batch::map_files`]), each with
    /// its session; one result per file, in order.
    pub fn validate(&self) -> Vec<Result<Validation, Error>> {
        let indexed: Vec<(usize, &PathBuf)> = self.files.iter().enumerate().collect();
        crate::batch::map_files(&indexed, |(index, file)| {
            self.session(*index).validate(file)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn session_of(json: &str) -> Result<Session, String> {
        let Ok(serde_json::Value::Object(object)) = serde_json::from_str(json) else {
            return Err(format!("not an object: {json}"));
        };
        Session::new(&Request::from_json(&object)?, None)
    }

    #[test]
    fn a_request_becomes_the_options_the_command_uses() {
        let session = session_of(r#"{"samples": 1234, "payload_mass": 2, "no_config": true}"#)
            .expect("session");
        assert_eq!(session.options().workspace.samples, 1234);
        assert_eq!(session.options().statics.payload_mass, Some(2.0));
        assert_eq!(session.timeout(), Some(Duration::from_secs(60)));
        let session = session_of(r#"{"xacro_arg": "arm:=ur5", "timeout": 0}"#).expect("session");
        assert_eq!(
            session.options().xacro_args,
            [("arm".to_string(), "ur5".to_string())]
        );
        assert_eq!(session.timeout(), None);
    }

    #[test]
    fn bad_values_are_named() {
        let error = |json: &str| session_of(json).expect_err(json);
        assert!(error(r#"{"payload_mass": -3}"#).contains("--payload-mass -3"));
        assert!(error(r#"{"timeout": -1}"#).contains("--timeout -1"));
        assert!(error(r#"{"baseline": "missing.json"}"#).contains("baseline missing.json"));
    }
}
