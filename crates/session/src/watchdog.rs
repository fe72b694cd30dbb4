//! The per-file watchdog: a validation that does not finish in time is reported as such and cancelled.

use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

use urdf_validator::input::LoadError;
use urdf_validator::timings::Progress;
use urdf_validator::{Error, Options, Validation};

/// Validate `file` with `job` ([`urdf_validator::validate`], or [`urdf_validator::validate_text`] for text standing for
/// `file`), giving up after `timeout` (`None`: no limit). A run that does not finish in time is reported
/// as [`Error::DidNotFinish`], naming the stage it was in, and cancelled: it gives up before its next
/// stage, its sampling at the next chunk, and anything else it still does ends with it or with the process.
/// The caller waits here, so it must not be a worker of the pool the stages use ([`crate::batch`]).
pub fn validate_within<F>(
    file: &Path,
    options: &Options,
    timeout: Option<Duration>,
    job: F,
) -> Result<Validation, Error>
where
    F: FnOnce(&Path, &Options) -> Result<Validation, Error> + Send + 'static,
{
    let Some(timeout) = timeout else {
        return job(file, options);
    };
    let progress = Progress::with_time_limit(timeout.as_secs_f64());
    let options = Options {
        progress: Some(progress.clone()),
        ..options.clone()
    };
    let path = file.to_path_buf();
    let (done, result) = mpsc::channel();
    let worker = std::thread::Builder::new()
        .name(format!("validate {}", file.display()))
        .spawn(move || {
            let _ = done.send(job(&path, &options));
        });
    if let Err(error) = worker {
        return Err(Error::Load(LoadError::Io {
            path: file.to_path_buf(),
            error,
        }));
    }
    result.recv_timeout(timeout).unwrap_or_else(|_| {
        let stage = progress.running();
        // Stop the sampling so the threads it holds go to the next files.
        progress.cancel();
        Err(Error::DidNotFinish {
            path: file.to_path_buf(),
            seconds: timeout.as_secs_f64(),
            stage,
        })
    })
}
