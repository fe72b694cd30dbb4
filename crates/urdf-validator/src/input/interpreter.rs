//! The Python interpreter the `--deep` pass runs MuJoCo in: read from the environment here, in the load
//! stage, so the analysis itself touches no environment.

use std::path::PathBuf;

/// The variable naming the interpreter.
pub const PYTHON_VARIABLE: &str = "URDF_VALIDATOR_PYTHON";

/// `URDF_VALIDATOR_PYTHON` when set; else the `python3` beside the running program when there is one (the
/// binary installed into a virtual environment by the wheel, or a Python process of that environment:
/// the Python MuJoCo was installed into); else `python3` on `PATH`.
pub fn python() -> PathBuf {
    if let Some(python) = std::env::var_os(PYTHON_VARIABLE).filter(|v| !v.is_empty()) {
        return PathBuf::from(python);
    }
    std::env::current_exe()
        .ok()
        .and_then(|exe| Some(exe.parent()?.join(PYTHON_NAME)))
        .filter(|beside| beside.is_file())
        .unwrap_or_else(|| PathBuf::from(PYTHON_NAME))
}

/// The interpreter's file name.
#[cfg(windows)]
const PYTHON_NAME: &str = "python.exe";
/// The interpreter's file name.
#[cfg(not(windows))]
const PYTHON_NAME: &str = "python3";
