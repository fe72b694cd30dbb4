//! `urdf_validate diff OLD NEW`: what changed between two robot descriptions (or reports).
//!
//! Each side is a URDF/xacro file, validated with the same flags, or a report JSON this tool wrote
//! (`*.json`). Exit code: 0 when no verdict got worse, 1 when one did or NEW has a WARN/FAIL/CRITICAL
//! finding OLD lacks, 2 when an input cannot be read (or the command line is wrong).

use std::ffi::OsString;
use std::io::Write;
use std::path::Path;

use clap::{CommandFactory, FromArgMatches};
use serde_json::Value;
use urdf_validate_session::Session;
use urdf_validator::render::{render_diff_markdown, render_diff_text};
use urdf_validator::report::diff::compare;

use crate::args::Args;
use crate::request::{first_line, option_value, request_of};

pub(crate) const HELP: &str = "\
Compare two robot descriptions: verdicts, findings, masses, centre of mass, gravity torques and margins,
stability margin and reach.

Usage: urdf_validate diff OLD NEW [--format text|json|markdown] [FLAGS...]

OLD and NEW are URDF or xacro files (validated with the same FLAGS: --payload-mass, --robot-type, --pose,
--package-path, ... as for `urdf_validate`), or report JSON files written by urdf_validate.

Exit code: 0 when no verdict got worse, 1 when one did or NEW has a WARN, FAIL or CRITICAL finding that
OLD lacks, 2 when an input cannot be read.
";

/// The output formats of `diff`.
#[derive(Clone, Copy)]
enum DiffFormat {
    Text,
    Json,
    Markdown,
}

/// Run `urdf_validate diff` with the words after `diff`.
pub(crate) fn main(argv: &[OsString]) -> u8 {
    match run(argv) {
        Ok(code) => code,
        Err(message) => {
            errln!("error: {message}");
            2
        }
    }
}

fn run(argv: &[OsString]) -> Result<u8, String> {
    let mut format = DiffFormat::Text;
    let mut rest: Vec<OsString> = vec!["urdf_validate".into()];
    let mut words = argv.iter();
    while let Some(word) = words.next() {
        let text = word.to_string_lossy();
        if text == "-h" || text == "--help" {
            out!("{HELP}");
            return Ok(0);
        }
        let value = option_value(&text, "--format", &mut words);
        match value.as_deref() {
            None => rest.push(word.clone()),
            Some("text") => format = DiffFormat::Text,
            Some("json") => format = DiffFormat::Json,
            Some("markdown") => format = DiffFormat::Markdown,
            Some(other) => {
                return Err(format!(
                    "diff --format '{other}': expected text, json or markdown"
                ))
            }
        }
    }
    let matches = Args::command()
        .try_get_matches_from(rest)
        .map_err(|e| first_line(&e.to_string()))?;
    let args = Args::from_arg_matches(&matches).map_err(|e| first_line(&e.to_string()))?;
    let (paths, request) = request_of(&args, &matches)?;
    let [old, new] = paths.as_slice() else {
        return Err(format!(
            "diff takes two inputs, OLD and NEW (got {}); see urdf_validate diff --help",
            paths.len()
        ));
    };
    // Both sides whole: a baseline names NEW's path, so it would hide NEW's known findings and not OLD's, and
    // they would all look fixed.
    let session = Session::new(&request, Some(new))?.without_baseline();
    let side = |path: &Path| report_of(path, &session);
    let diff = compare(&side(old)?, &side(new)?);
    let text = match format {
        DiffFormat::Text => render_diff_text(&diff),
        DiffFormat::Markdown => render_diff_markdown(&diff),
        DiffFormat::Json => serde_json::to_string_pretty(&diff).unwrap_or_default() + "\n",
    };
    out!("{text}");
    Ok(u8::from(diff.worse))
}

/// The report of one side: read from a `.json` report, else validated.
fn report_of(path: &Path, session: &Session) -> Result<Value, String> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
    {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("{}: cannot read it: {e}", path.display()))?;
        let value: Value = serde_json::from_str(&text)
            .map_err(|e| format!("{}: not JSON ({e})", path.display()))?;
        if value.get("overall_status").is_none() || value.get("findings").is_none() {
            return Err(format!(
                "{}: not a report written by urdf_validate (no overall_status or findings)",
                path.display()
            ));
        }
        if value.get("baseline").is_some_and(|b| !b.is_null()) {
            return Err(format!(
                "{}: written with --baseline, so its findings leave out the baselined ones; diff needs a report written without --baseline",
                path.display()
            ));
        }
        return Ok(value);
    }
    let validation = session.validate(path).map_err(|e| e.to_string())?;
    serde_json::to_value(&validation.report).map_err(|e| format!("{}: {e}", path.display()))
}
