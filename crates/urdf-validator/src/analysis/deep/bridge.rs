//! Running MuJoCo: a Python process (`bridge.py`, embedded) reads the job as JSON on stdin and writes the
//! reply as JSON on stdout.
//!
//! Why a process and not the shared library: the binary builds and runs without MuJoCo or a C toolchain,
//! users get MuJoCo exactly as they install it (`pip install "urdf-validator[mujoco]"`), and a crash
//! inside MuJoCo cannot take the validator down. The interpreter is [`super::DeepOptions::python`] (the
//! front ends set it from [`crate::input::interpreter::python`]), else `python3` on `PATH`. A bare `libmujoco`
//! (`MUJOCO_PATH`) is not used.

use std::io::{Read, Write};
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use serde_json::Value;

use crate::timings::Progress;

/// The bridge script.
pub const SCRIPT: &str = include_str!("bridge.py");

/// The install line shown when MuJoCo is not found.
pub const INSTALL_HINT: &str = "pip install \"urdf-validator[mujoco]\"";

/// Largest reply read from the bridge (bytes).
const MAX_REPLY: u64 = 64 << 20;
/// Largest part of the bridge's stderr kept (bytes).
const MAX_STDERR: u64 = 64 << 10;

/// Why the bridge gave no reply.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BridgeError {
    /// No Python interpreter could be started.
    NoPython(String),
    /// Python runs but `import mujoco` fails there.
    NoMujoco {
        /// The interpreter.
        python: String,
        /// Python's own message.
        message: String,
    },
    /// The bridge ran past its time limit and was killed.
    Timeout(Duration),
    /// The run was cancelled (`--timeout` of the whole file).
    Cancelled,
    /// The bridge ended without a readable reply.
    Crashed(String),
    /// The input is SDFormat: the pass hands MuJoCo URDF text, which there is none of.
    NotUrdf,
    /// An MJCF file MuJoCo is not given (why).
    Withheld(String),
}

impl BridgeError {
    /// One sentence for a finding.
    pub fn describe(&self) -> String {
        match self {
            BridgeError::NoPython(why) => format!(
                "MuJoCo was not found: no Python interpreter could be started ({why}); install MuJoCo with `{INSTALL_HINT}` (or point URDF_VALIDATOR_PYTHON at a Python that has the `mujoco` package; a bare libmujoco in MUJOCO_PATH is not supported)"
            ),
            BridgeError::NoMujoco { python, message } => format!(
                "MuJoCo was not found: `import mujoco` fails in {python} ({message}); install it with `{INSTALL_HINT}` (or point URDF_VALIDATOR_PYTHON at a Python that has the `mujoco` package; a bare libmujoco in MUJOCO_PATH is not supported)"
            ),
            BridgeError::Timeout(limit) => format!(
                "the MuJoCo pass did not finish within {} s and was stopped",
                limit.as_secs_f64()
            ),
            BridgeError::Cancelled => "the MuJoCo pass was cancelled".to_string(),
            BridgeError::Crashed(why) => format!("the MuJoCo pass failed: {why}"),
            BridgeError::Withheld(why) => format!("the MuJoCo pass does not load this MJCF file: {why}"),
            BridgeError::NotUrdf => "the MuJoCo pass does not run on SDFormat input yet (it hands MuJoCo the URDF text); validate the URDF the SDF was made from, or load the SDF in Gazebo".to_string(),
        }
    }
}

/// Run the bridge on `job`; the reply (`ok` true, or a MuJoCo compile error) or why there is none.
pub fn run(
    python: &std::path::Path,
    job: &Value,
    limit: Duration,
    progress: Option<&Progress>,
) -> Result<Value, BridgeError> {
    let scratch = Scratch::new().map_err(|e| BridgeError::Crashed(e.to_string()))?;
    let mut child = Command::new(python)
        .arg("-c")
        .arg(SCRIPT)
        // MuJoCo writes MUJOCO_LOG.TXT into the working directory on errors: a scratch folder.
        .current_dir(&scratch.0)
        .env("PYTHONDONTWRITEBYTECODE", "1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| BridgeError::NoPython(format!("{}: {e}", python.display())))?;
    let input = serde_json::to_vec(job).map_err(|e| BridgeError::Crashed(e.to_string()))?;
    let stdin = child.stdin.take();
    let writer = std::thread::spawn(move || {
        if let Some(mut stdin) = stdin {
            // A bridge that exits early closes the pipe: its reply says why.
            let _ = stdin.write_all(&input);
        }
    });
    let stdout = child.stdout.take();
    let reader = std::thread::spawn(move || {
        let mut text = Vec::new();
        if let Some(stdout) = stdout {
            let _ = stdout.take(MAX_REPLY).read_to_end(&mut text);
        }
        text
    });
    let stderr = child.stderr.take();
    let errors = std::thread::spawn(move || {
        let mut text = Vec::new();
        if let Some(stderr) = stderr {
            let mut limited = stderr.take(MAX_STDERR);
            let _ = limited.read_to_end(&mut text);
            // Drain the rest so the bridge never blocks on a full pipe.
            let _ = std::io::copy(&mut limited.into_inner(), &mut std::io::sink());
        }
        text
    });
    let started = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Ok(status),
            Ok(None) => {}
            Err(e) => break Err(BridgeError::Crashed(e.to_string())),
        }
        if progress.is_some_and(Progress::is_cancelled) {
            let _ = child.kill();
            let _ = child.wait();
            break Err(BridgeError::Cancelled);
        }
        if started.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            break Err(BridgeError::Timeout(limit));
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let _ = writer.join();
    let stdout = reader.join().unwrap_or_default();
    let stderr = errors.join().unwrap_or_default();
    let status = status?;
    let reply: Value = serde_json::from_slice(&stdout).map_err(|_| {
        let stderr = String::from_utf8_lossy(&stderr);
        let last = stderr.lines().rev().find(|l| !l.trim().is_empty());
        BridgeError::Crashed(match last {
            Some(line) => format!(
                "{} exited ({status}) without a reply: {line}",
                python.display()
            ),
            None => format!("{} exited ({status}) without a reply", python.display()),
        })
    })?;
    match reply["kind"].as_str() {
        Some("no_mujoco") => Err(BridgeError::NoMujoco {
            python: reply["python"]
                .as_str()
                .map_or_else(|| python.display().to_string(), str::to_string),
            message: reply["message"].as_str().unwrap_or("").to_string(),
        }),
        Some("internal") => Err(BridgeError::Crashed(
            reply["message"]
                .as_str()
                .unwrap_or("no message")
                .to_string(),
        )),
        _ => Ok(reply),
    }
}

/// A scratch folder, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new() -> std::io::Result<Scratch> {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let dir = std::env::temp_dir().join(format!(
            "urdf-validator-deep-{}-{}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&dir)?;
        Ok(Scratch(dir))
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
