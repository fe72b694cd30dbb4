//! Write the HTML report of one robot (a development aid until the CLI's `--format html` lands, and what
//! `scripts/html-screenshot.sh` renders): `cargo run --example html_report -- robot.urdf report.html`.

use std::path::Path;
use std::process::ExitCode;

use urdf_validator::render::html::render_html;
use urdf_validator::Options;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [input, output] = args.as_slice() else {
        eprintln!("usage: html_report ROBOT.urdf OUT.html");
        return ExitCode::from(2);
    };
    let options = Options {
        resolver: urdf_validator::input::resolve::PackageResolver::from_env(Vec::new()),
        ..Options::default()
    };
    let validation = match urdf_validator::validate(Path::new(input), &options) {
        Ok(validation) => validation,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    if let Err(e) = std::fs::write(output, render_html(&validation)) {
        eprintln!("{output}: {e}");
        return ExitCode::from(2);
    }
    ExitCode::SUCCESS
}
