//! `urdf_validate`: validate URDF files, write one JSON report each, exit 0 / 1 / 2.

use std::process::ExitCode;

fn main() -> ExitCode {
    ExitCode::from(urdf_validate_cli::main_from(std::env::args_os()))
}
