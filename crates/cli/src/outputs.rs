//! Running one file, writing its report files, and the summary table of a batch.

use std::collections::HashMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

use urdf_validate_session::Session;

use urdf_validator::render::{render_html, render_json, render_junit, render_sarif, FormatOptions};
use urdf_validator::report::Status;
use urdf_validator::{Error, Validation};

use crate::args::Format;

/// What happened to one input.
pub struct Outcome {
    /// The input.
    pub file: PathBuf,
    /// The validation, or why the file could not be loaded.
    pub validation: Result<Validation, Error>,
    /// Where the JSON report was written.
    pub written: Option<String>,
    /// The other report files written (SARIF, JUnit, HTML).
    pub also_written: Vec<String>,
    /// Why the JSON report could not be written.
    pub write_error: Option<String>,
    /// How long the validation took (writing the report files not included).
    pub elapsed: std::time::Duration,
}

impl Outcome {
    /// 0 PASS, 1 WARN, 2 FAIL / UNKNOWN / unreadable / report not written.
    pub fn exit_code(&self) -> u8 {
        match (&self.validation, &self.write_error) {
            (Ok(v), None) => v.report.overall_status.exit_code() as u8,
            _ => 2,
        }
    }
}

/// `robot.urdf` → `robot`, `robot.urdf.xacro` → `robot`.
fn stem(file: &Path) -> String {
    let name = file
        .file_name()
        .map_or_else(|| "robot".to_string(), |n| n.to_string_lossy().into_owned());
    let name = name.strip_suffix(".xacro").unwrap_or(&name);
    let name = name.strip_suffix(".urdf").unwrap_or(name);
    name.to_string()
}

/// The report files of each input, without extension: `<stem>_validation` beside it or in `output_dir`
/// (`.json`, `.sarif`, ... are appended). Two inputs that would share a report file in `output_dir` get
/// `_2`, `_3`, ... in input order.
pub fn report_bases(files: &[PathBuf], output_dir: Option<&Path>) -> Vec<PathBuf> {
    let mut used: HashMap<PathBuf, usize> = HashMap::new();
    files
        .iter()
        .map(|file| {
            let dir = output_dir
                .map(Path::to_path_buf)
                .unwrap_or_else(|| file.parent().unwrap_or(Path::new("")).to_path_buf());
            let base = stem(file);
            let count = used.entry(dir.join(&base)).or_insert(0);
            *count += 1;
            let name = if *count == 1 {
                format!("{base}_validation")
            } else {
                format!("{base}_{count}_validation")
            };
            dir.join(name)
        })
        .collect()
}

/// `base` with `.ext` appended (`robot_validation` → `robot_validation.sarif`).
pub fn with_extension(base: &Path, ext: &str) -> PathBuf {
    let mut path = base.as_os_str().to_owned();
    path.push(".");
    path.push(ext);
    PathBuf::from(path)
}

/// The report files to write for each input.
pub struct Files {
    /// The formats written as files (`json`, `sarif`, `junit`, `html`); empty with `--no-write`.
    pub formats: Vec<Format>,
    /// Paths and rule links for SARIF and JUnit.
    pub options: FormatOptions,
}

/// Validate one file (within `timeout`) and write its report files (`<base>.json`, `.sarif`, ...).
pub fn validate_one(file: &Path, base: &Path, session: &Session, files: &Files) -> Outcome {
    let started = std::time::Instant::now();
    let validation = session.validate(file);
    let mut outcome = Outcome {
        file: file.to_path_buf(),
        validation,
        written: None,
        also_written: Vec::new(),
        write_error: None,
        elapsed: started.elapsed(),
    };
    let Ok(validation) = &outcome.validation else {
        return outcome;
    };
    let mut errors = Vec::new();
    for &format in &files.formats {
        let Some(ext) = format.extension() else {
            continue;
        };
        let path = with_extension(base, ext);
        let text = match format {
            Format::Json => render_json(&validation.report),
            Format::Sarif => render_sarif(&[validation], &[], &files.options),
            Format::Junit => render_junit(&[validation], &[], &files.options),
            Format::Html => render_html(validation),
            Format::Text | Format::Github => continue,
        };
        match write_file(&path, &text) {
            Ok(()) if format == Format::Json => outcome.written = Some(path.display().to_string()),
            Ok(()) => outcome.also_written.push(path.display().to_string()),
            Err(error) => errors.push(format!("{}: cannot write report: {error}", path.display())),
        }
    }
    if !errors.is_empty() {
        outcome.write_error = Some(errors.join("\nerror: "));
    }
    outcome
}

/// Write `text` to `path`, creating its folder.
pub fn write_file(path: &Path, text: &str) -> std::io::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(path, text)
}

/// The table printed after a batch.
pub fn summary_table(outcomes: &[Outcome]) -> String {
    let mut out = String::new();
    let worst = outcomes.iter().map(Outcome::exit_code).max().unwrap_or(0);
    let _ = writeln!(
        out,
        "\nSummary: {} file(s), exit code {worst}",
        outcomes.len()
    );
    let _ = writeln!(
        out,
        "  {:<8} {:<7} {:>5} {:>5} {:>5}  FILE",
        "STATUS", "CONF", "CRIT", "WARN", "INFO"
    );
    for outcome in outcomes {
        let file = outcome.file.display();
        match &outcome.validation {
            Ok(v) => {
                let r = &v.report;
                let status = if outcome.write_error.is_some() {
                    "ERROR"
                } else {
                    r.overall_status.label()
                };
                let _ = writeln!(
                    out,
                    "  {:<8} {:<7} {:>5} {:>5} {:>5}  {file}",
                    status,
                    r.confidence_level.label(),
                    r.schema.critical_issues.len(),
                    r.schema.warnings.len(),
                    r.schema.infos.len()
                );
            }
            Err(_) => {
                let _ = writeln!(
                    out,
                    "  {:<8} {:<7} {:>5} {:>5} {:>5}  {file}",
                    "ERROR", "-", "-", "-", "-"
                );
            }
        }
    }
    let count = |s: Status| {
        outcomes
            .iter()
            .filter(|o| {
                o.validation
                    .as_ref()
                    .is_ok_and(|v| v.report.overall_status == s)
            })
            .count()
    };
    let errors = outcomes
        .iter()
        .filter(|o| o.validation.is_err() || o.write_error.is_some())
        .count();
    let _ = writeln!(
        out,
        "  {} PASS · {} WARN · {} FAIL · {} UNKNOWN · {errors} ERROR",
        count(Status::Pass),
        count(Status::Warn),
        count(Status::Fail),
        count(Status::Unknown)
    );
    out
}
