//! `--format` and `--output`: which views of the reports go where.
//!
//! - Report files, one per input (`<name>_validation.<ext>` beside it or in `--output-dir`): the JSON report
//!   always, and SARIF, JUnit and HTML when listed; none with `--no-write`.
//! - stdout: the text report when `text` is listed, or when neither `json` nor `github` is; the JSON
//!   report when `json` is listed without `text` (as `--format json` always did); GitHub annotations when
//!   `github` is listed.
//! - Under GitHub Actions (`GITHUB_ACTIONS=true`) annotations are added without being listed: on stdout,
//!   or on stderr when stdout carries a JSON, SARIF or JUnit document (the runner reads both).
//!   The step summary goes to `$GITHUB_STEP_SUMMARY` whenever annotations are made and it is set.
//! - `--output FILE|-` takes one format and writes every input into one document there (one SARIF run,
//!   one JUnit file with a suite per robot, the JSON object or array); the JSON report files are still
//!   written unless `--no-write` (or JSON is the format redirected).

use std::io::Write;
use std::path::PathBuf;

use urdf_validator::render::{
    render_github, render_html, render_junit, render_sarif, render_step_summary, render_text,
    FormatOptions, TextOptions, Unreported,
};
use urdf_validator::Validation;

use crate::args::{Args, Format};
use crate::outputs::{self, Outcome};

/// Where `--output` sends its format.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    /// `--output -`.
    Stdout,
    /// `--output FILE`.
    File(PathBuf),
}

/// A stream for annotations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stream {
    /// Standard output.
    Stdout,
    /// Standard error.
    Stderr,
}

/// What the environment says about GitHub Actions.
#[derive(Clone, Debug, Default)]
pub struct GithubEnv {
    /// `GITHUB_ACTIONS=true`.
    pub actions: bool,
    /// `GITHUB_STEP_SUMMARY`.
    pub step_summary: Option<PathBuf>,
}

impl GithubEnv {
    /// Read from the process environment.
    pub fn from_env() -> Self {
        GithubEnv {
            actions: std::env::var("GITHUB_ACTIONS").is_ok_and(|v| v == "true"),
            step_summary: std::env::var_os("GITHUB_STEP_SUMMARY")
                .filter(|v| !v.is_empty())
                .map(PathBuf::from),
        }
    }
}

/// Where each view goes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plan {
    /// The text report (and a batch's summary table) on stdout.
    pub text: bool,
    /// The JSON report(s) on stdout.
    pub json_stdout: bool,
    /// GitHub annotations, and on which stream.
    pub github: Option<Stream>,
    /// Append the Markdown summary to this file.
    pub step_summary: Option<PathBuf>,
    /// Report files written for each input.
    pub file_formats: Vec<Format>,
    /// Formats listed as files but not written because of `--no-write`.
    pub not_written: Vec<Format>,
    /// `--output`: one format, every input in one document.
    pub output: Option<(Format, Target)>,
}

impl Plan {
    /// The plan for these flags in this environment; an error for `--output` with several formats.
    pub fn new(args: &Args, github: &GithubEnv) -> Result<Plan, String> {
        let mut formats: Vec<Format> = Vec::new();
        for &format in &args.format {
            if !formats.contains(&format) {
                formats.push(format);
            }
        }
        let listed = |f: Format| formats.contains(&f);
        if let Some(path) = &args.output {
            let [format] = formats.as_slice() else {
                return Err(format!(
                    "--output takes one --format (got {}); write the others as files, or run once per format",
                    formats.iter().map(|f| f.name()).collect::<Vec<_>>().join(",")
                ));
            };
            let format = *format;
            let target = if path.as_os_str() == "-" {
                Target::Stdout
            } else {
                Target::File(path.clone())
            };
            let github_stream = match (&target, format) {
                _ if !github.actions || format == Format::Github => None,
                (Target::Stdout, Format::Text) | (Target::File(_), _) => Some(Stream::Stdout),
                (Target::Stdout, _) => Some(Stream::Stderr),
            };
            let annotating = github_stream.is_some() || format == Format::Github;
            return Ok(Plan {
                text: false,
                json_stdout: false,
                github: github_stream,
                step_summary: github.step_summary.clone().filter(|_| annotating),
                file_formats: if args.no_write || format == Format::Json {
                    Vec::new()
                } else {
                    vec![Format::Json]
                },
                not_written: Vec::new(),
                output: Some((format, target)),
            });
        }
        let text = listed(Format::Text) || !(listed(Format::Json) || listed(Format::Github));
        let json_stdout = listed(Format::Json) && !listed(Format::Text);
        let github_stream = if listed(Format::Github) {
            Some(Stream::Stdout)
        } else if github.actions {
            Some(if json_stdout {
                Stream::Stderr
            } else {
                Stream::Stdout
            })
        } else {
            None
        };
        let mut file_formats = vec![Format::Json];
        file_formats.extend(
            formats
                .iter()
                .copied()
                .filter(|f| f.extension().is_some() && *f != Format::Json),
        );
        let (file_formats, not_written) = if args.no_write {
            (Vec::new(), file_formats.split_off(1))
        } else {
            (file_formats, Vec::new())
        };
        Ok(Plan {
            text,
            json_stdout,
            github: github_stream,
            step_summary: github
                .step_summary
                .clone()
                .filter(|_| github_stream.is_some()),
            file_formats,
            not_written,
            output: None,
        })
    }
}

/// The inputs that gave no report, for the formats that list every input.
fn unreported(outcomes: &[Outcome], input_errors: &[String]) -> Vec<Unreported> {
    let mut list: Vec<Unreported> = input_errors
        .iter()
        .map(|error| Unreported {
            file: String::new(),
            error: error.clone(),
        })
        .collect();
    list.extend(outcomes.iter().filter_map(|o| match &o.validation {
        Err(error) => Some(Unreported {
            file: o.file.display().to_string(),
            error: error.to_string(),
        }),
        Ok(_) => None,
    }));
    list
}

/// Print and write every view of the outcomes as `plan` says. `single_file`: one file was named, so the
/// JSON is that report as an object (or nothing when it cannot be loaded); otherwise an array. Returns
/// false when a document could not be written.
pub fn emit(
    plan: &Plan,
    args: &Args,
    single_file: bool,
    outcomes: &[Outcome],
    input_errors: &[String],
    options: &FormatOptions,
) -> bool {
    let validations: Vec<&Validation> = outcomes
        .iter()
        .filter_map(|o| o.validation.as_ref().ok())
        .collect();
    let unreported = unreported(outcomes, input_errors);
    let mut stderr = anstream::stderr().lock();
    for error in input_errors {
        let _ = writeln!(stderr, "error: {error}");
    }
    let mut ok = true;
    if plan.text {
        print_styled(&text_document(args, outcomes, true));
    } else {
        for outcome in outcomes {
            if let Err(error) = &outcome.validation {
                let _ = writeln!(stderr, "error: {error}");
            }
            if let Some(error) = &outcome.write_error {
                let _ = writeln!(stderr, "error: {error}");
            }
        }
    }
    for format in &plan.not_written {
        let _ = writeln!(
            stderr,
            "note: --no-write: no {} file written (`--format {} --output -` prints it)",
            format.name(),
            format.name()
        );
    }
    if plan.json_stdout {
        if let Some(json) = json_document(single_file, &validations) {
            let _ = std::io::stdout().lock().write_all(json.as_bytes());
        }
    }
    if let Some((format, target)) = &plan.output {
        let document = match format {
            Format::Text => Some(text_document(args, outcomes, false)),
            Format::Json => json_document(single_file, &validations),
            Format::Sarif => Some(render_sarif(&validations, &unreported, options)),
            Format::Junit => Some(render_junit(&validations, &unreported, options)),
            Format::Github => Some(render_github(&validations, &unreported, options)),
            Format::Html => validations.first().map(|v| render_html(v)),
        };
        if let Some(document) = document {
            match target {
                Target::Stdout => {
                    print_styled(&document);
                }
                Target::File(path) => {
                    let document = anstream::adapter::strip_str(&document).to_string();
                    if let Err(error) = outputs::write_file(path, &document) {
                        let _ =
                            writeln!(stderr, "error: {}: cannot write: {error}", path.display());
                        ok = false;
                    }
                }
            }
        }
    }
    if let Some(stream) = plan.github {
        let annotations = render_github(&validations, &unreported, options);
        let _ = match stream {
            Stream::Stdout => std::io::stdout().lock().write_all(annotations.as_bytes()),
            Stream::Stderr => std::io::stderr().lock().write_all(annotations.as_bytes()),
        };
    }
    if let Some(path) = &plan.step_summary {
        let summary = render_step_summary(&validations, &unreported, options);
        let appended = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .and_then(|mut file| file.write_all(summary.as_bytes()));
        if let Err(error) = appended {
            let _ = writeln!(
                stderr,
                "warning: GITHUB_STEP_SUMMARY {}: cannot append the summary: {error}",
                path.display()
            );
        }
    }
    ok
}

/// Print `text` to stdout in one write, its ANSI styles kept or stripped as `anstream` decides for stdout
/// (a line-buffered stdout would make a system call per line); a closed pipe is ignored.
fn print_styled(text: &str) {
    let choice = anstream::AutoStream::choice(&std::io::stdout());
    let mut styled = anstream::AutoStream::new(Vec::with_capacity(text.len()), choice);
    let _ = styled.write_all(text.as_bytes());
    let _ = std::io::stdout().lock().write_all(&styled.into_inner());
}

/// The text report of every outcome and, for a batch or `--quiet`, the summary table. `errors`: also
/// print load and write errors on stderr, in order.
fn text_document(args: &Args, outcomes: &[Outcome], errors: bool) -> String {
    let mut out = String::new();
    let mut stderr = anstream::stderr().lock();
    for outcome in outcomes {
        match &outcome.validation {
            Ok(validation) if !args.quiet => {
                let options = TextOptions {
                    verbose: args.verbose,
                    detailed: args.detailed,
                    report_path: outcome.written.clone(),
                };
                out.push_str(&render_text(validation, &options));
                if !outcome.also_written.is_empty() {
                    out.push_str(&format!(
                        "Also written: {}\n",
                        outcome.also_written.join(", ")
                    ));
                }
            }
            Ok(_) => {}
            Err(error) if errors => {
                // Keep stdout and stderr in order on a terminal.
                print_styled(&out);
                out.clear();
                let _ = writeln!(stderr, "error: {error}");
            }
            Err(_) => {}
        }
        if let (Some(error), true) = (&outcome.write_error, errors) {
            print_styled(&out);
            out.clear();
            let _ = writeln!(stderr, "error: {error}");
        }
    }
    if outcomes.len() > 1 || args.quiet {
        out.push_str(&outputs::summary_table(outcomes));
    }
    out
}

/// The JSON of the reports: the object of one named file, else an array; nothing when the one named file
/// gave no report.
fn json_document(single_file: bool, validations: &[&Validation]) -> Option<String> {
    let reports: Vec<&urdf_validator::report::Report> =
        validations.iter().map(|v| &v.report).collect();
    match reports.as_slice() {
        [one] if single_file => Some(urdf_validator::render::render_json(one)),
        [] if single_file => None,
        many => Some(urdf_validator::render::render_json_list(many)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    fn plan(argv: &[&str], actions: bool) -> Result<Plan, String> {
        let args = Args::parse_from(std::iter::once("urdf_validate").chain(argv.iter().copied()));
        let github = GithubEnv {
            actions,
            step_summary: Some(PathBuf::from("/tmp/summary.md")),
        };
        Plan::new(&args, &github)
    }

    #[test]
    fn default_is_text_and_the_json_file() {
        let p = plan(&["r.urdf"], false).unwrap();
        assert!(p.text && !p.json_stdout && p.github.is_none() && p.step_summary.is_none());
        assert_eq!(p.file_formats, vec![Format::Json]);
    }

    #[test]
    fn json_alone_prints_json_as_before() {
        let p = plan(&["r.urdf", "--format", "json"], false).unwrap();
        assert!(!p.text && p.json_stdout);
        assert_eq!(p.file_formats, vec![Format::Json]);
        let p = plan(&["r.urdf", "--format", "json,text"], false).unwrap();
        assert!(p.text && !p.json_stdout);
    }

    #[test]
    fn file_formats_are_written_unless_no_write() {
        let p = plan(&["r.urdf", "--format", "sarif,junit,html,json"], false).unwrap();
        assert_eq!(
            p.file_formats,
            vec![Format::Json, Format::Sarif, Format::Junit, Format::Html]
        );
        assert!(!p.text && p.json_stdout);
        let p = plan(&["r.urdf", "--format", "sarif", "--no-write"], false).unwrap();
        assert!(p.file_formats.is_empty() && p.text);
        assert_eq!(p.not_written, vec![Format::Sarif]);
    }

    #[test]
    fn github_annotations_under_actions_avoid_a_json_stdout() {
        let p = plan(&["r.urdf"], true).unwrap();
        assert_eq!(p.github, Some(Stream::Stdout));
        assert!(p.text && p.step_summary.is_some());
        let p = plan(&["r.urdf", "--format", "json"], true).unwrap();
        assert_eq!(p.github, Some(Stream::Stderr));
        let p = plan(&["r.urdf", "--format", "sarif", "--output", "-"], true).unwrap();
        assert_eq!(p.github, Some(Stream::Stderr));
        let p = plan(&["r.urdf", "--format", "github"], false).unwrap();
        assert_eq!(p.github, Some(Stream::Stdout));
        assert!(!p.text && p.step_summary.is_some());
    }

    #[test]
    fn output_takes_one_format() {
        let p = plan(&["r.urdf", "--format", "sarif", "--output", "-"], false).unwrap();
        assert_eq!(p.output, Some((Format::Sarif, Target::Stdout)));
        assert!(!p.text && !p.json_stdout && p.github.is_none());
        assert_eq!(p.file_formats, vec![Format::Json]);
        let p = plan(&["r.urdf", "--format", "json", "--output", "x.json"], false).unwrap();
        assert_eq!(
            p.output,
            Some((Format::Json, Target::File("x.json".into())))
        );
        assert!(p.file_formats.is_empty());
        let error = plan(
            &["r.urdf", "--format", "sarif,junit", "--output", "-"],
            false,
        )
        .unwrap_err();
        assert!(error.contains("sarif,junit"), "{error}");
    }
}
