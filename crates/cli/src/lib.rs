//! `urdf_validate`: validate URDF files, write one JSON report each, exit 0 / 1 / 2.
//!
//! The command, its MCP server (`urdf_validate mcp`) and its language server (`urdf_validate server`):
//! each maps its input (flags, tool arguments) onto a request of the session crate
//! (`urdf_validate_session`), which the Python module shares. The binary (`src/main.rs`, also the wheel's
//! console command) calls [`main_from`]; the library exists for its tests.

/// Write to stdout, ignoring a closed pipe (`urdf_validate --list-rules | head -1`): the rest is dropped
/// quietly and the exit status stays what the run decides.
macro_rules! out {
    ($($arg:tt)*) => {{
        let _ = write!(std::io::stdout().lock(), $($arg)*);
    }};
}

/// [`out!`] with a newline.
macro_rules! outln {
    ($($arg:tt)*) => {{
        let _ = writeln!(std::io::stdout().lock(), $($arg)*);
    }};
}

/// `eprintln!` that does not panic when stderr is closed.
macro_rules! errln {
    ($($arg:tt)*) => {{
        let _ = writeln!(std::io::stderr().lock(), $($arg)*);
    }};
}

mod args;
mod book;
mod collection;
mod diff;
mod fixes;
mod formats;
mod mcp;
mod outputs;
mod progress;
mod request;
mod server;
mod view;

/// The language server's message loop on bytes in memory, for its fuzz target (crates/cli/fuzz).
#[doc(hidden)]
pub use server::fuzzing;

use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{CommandFactory, FromArgMatches};
use urdf_validate_session::options::{mesh_cache, sandbox_of};
use urdf_validate_session::{batch, config, config_file, discovery, Batch};
use urdf_validator::diagnostics::rules::{self, Rule};
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::input::sandbox::Sandbox;
use urdf_validator::render::FormatOptions;
use urdf_validator::report::baseline;

use args::{Args, ColorChoice, Format};
use formats::{GithubEnv, Plan};
use outputs::Outcome;

/// Run the command with `argv` (the program name first), as `urdf_validate` does; returns the exit status.
/// `--help`, `--version` and a usage error print and exit the process, as every command line does.
/// `urdf_validate mcp` serves the Model Context Protocol on stdin/stdout instead (see `docs/mcp.md`), and
/// `urdf_validate server` the Language Server Protocol (README, section Editors).
pub fn main_from<I, T>(argv: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let argv: Vec<OsString> = argv.into_iter().map(Into::into).collect();
    if argv.get(1).is_some_and(|word| word == "mcp") {
        return mcp::main(&argv[2..]);
    }
    if argv.get(1).is_some_and(|word| word == "server") {
        return server::main(&argv[2..]);
    }
    if argv.get(1).is_some_and(|word| word == "diff") {
        return diff::main(&argv[2..]);
    }
    if argv.get(1).is_some_and(|word| word == "view") {
        return view::main(&argv[2..]);
    }
    let matches = Args::command().get_matches_from(argv);
    let args = match Args::from_arg_matches(&matches) {
        Ok(args) => args,
        Err(error) => error.exit(),
    };
    match args.color {
        ColorChoice::Auto => {}
        ColorChoice::Always => anstream::ColorChoice::Always.write_global(),
        ColorChoice::Never => anstream::ColorChoice::Never.write_global(),
    }
    run(args, &matches)
}

fn run(args: Args, matches: &clap::ArgMatches) -> u8 {
    if let Some(code) = &args.explain {
        return explain(code);
    }
    if args.list_rules {
        for rule in rules::ALL {
            outln!(
                "{}  {:<32} {:<8} {}",
                rule.code,
                rule.name,
                rule.severity.label(),
                rule.what
            );
        }
        return 0;
    }
    if args.list_rules_markdown {
        out!("{}", rules::reference_markdown());
        return 0;
    }
    if let Some(dir) = &args.write_book_pages {
        return match book::write_pages(dir) {
            Ok(written) => {
                for path in written {
                    outln!("wrote {}", dir.join(path).display());
                }
                0
            }
            Err(error) => {
                errln!("error: --write-book-pages {}: {error}", dir.display());
                2
            }
        };
    }
    if args.json_schema_markdown {
        out!(
            "{}",
            urdf_validator::report::schema_doc::json_schema_markdown()
        );
        return 0;
    }
    if args.json_schema {
        out!("{}", urdf_validator::report::json_schema());
        return 0;
    }
    if args.show_config {
        return show_config(&args, matches);
    }
    if args.inputs.is_empty() {
        errln!(
            "error: no input given (expected one or more URDF or xacro files or directories; see --help)"
        );
        return 2;
    }
    if let Some(jobs) = args.jobs {
        // Only fails when a global pool already exists, which cannot happen this early.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(jobs)
            .build_global();
    }
    let (paths, request) = match request::request_of(&args, matches) {
        Ok(checked) => checked,
        Err(message) => {
            errln!("error: {message}");
            return 2;
        }
    };
    let (files, input_errors) = discovery::expand(&paths, args.skip_xacro_libraries);
    if files.is_empty() && input_errors.is_empty() && args.skip_xacro_libraries {
        // Only macro libraries were named (a pre-commit run on changed library files): nothing to do.
        return 0;
    }
    if files.is_empty() && input_errors.is_empty() {
        errln!("error: no input given (expected one or more URDF or xacro files or directories; see --help)");
        return 2;
    }
    let sandbox = sandbox_of(&request);
    let resolver = PackageResolver::from_env_in(request.package_path.clone(), &sandbox);
    if args.expand_only {
        if paths.len() != 1 || paths[0].is_dir() {
            errln!(
                "error: --expand-only expands one xacro file (got {} input(s){})",
                paths.len(),
                if paths.iter().any(|p| p.is_dir()) {
                    ", a directory among them"
                } else {
                    ""
                }
            );
            return 2;
        }
        return expand_only(
            &files,
            &input_errors,
            &request.xacro_args,
            &resolver,
            &sandbox,
        );
    }
    let plan = match Plan::new(&args, &GithubEnv::from_env()) {
        Ok(plan) => plan,
        Err(message) => {
            errln!("error: {message}");
            return 2;
        }
    };
    // An HTML report draws the robot in 3-D: the validation builds its scene.
    let request = urdf_validate_session::Request {
        view: plan
            .output
            .as_ref()
            .is_some_and(|(f, _)| *f == Format::Html)
            || plan.file_formats.contains(&Format::Html),
        ..request
    };
    // One session per configuration file (the nearest to each input, unless named or turned off).
    let sessions = match Batch::new(&request, &files, &mesh_cache(request.no_cache)) {
        Ok(sessions) => sessions,
        Err(message) => {
            errln!("error: {message}");
            return 2;
        }
    };
    if matches!(plan.output, Some((Format::Html, _))) && files.len() + input_errors.len() != 1 {
        errln!(
            "error: --format html --output takes one input (got {}); without --output each input gets its own page",
            files.len() + input_errors.len()
        );
        return 2;
    }
    let format_options = FormatOptions {
        base_dir: std::env::current_dir().ok(),
        rules_url: Some(rules::index_url()),
    };
    let files_to_write = outputs::Files {
        // --diff writes nothing.
        formats: if args.diff {
            Vec::new()
        } else {
            plan.file_formats.clone()
        },
        options: format_options.clone(),
    };
    let bases = outputs::report_bases(&files, args.output_dir.as_deref());
    let progress = progress::Bar::for_batch(files.len());
    let jobs: Vec<_> = files.iter().zip(&bases).enumerate().collect();
    // Files on threads of their own, not on the pool their stages use (see `batch`); a single file on
    // this thread.
    let run = || -> Vec<Outcome> {
        batch::map_files(&jobs, |(index, (file, base))| {
            let outcome =
                outputs::validate_one(file, base, sessions.session(*index), &files_to_write);
            progress.tick(file);
            outcome
        })
    };
    let mut outcomes = run();
    progress.finish();
    if args.fix || args.diff {
        match fix_or_diff(&args, outcomes, &run) {
            Ok(left) => outcomes = left,
            Err(code) => return code,
        }
    }
    let single_file = paths.len() == 1 && !paths[0].is_dir();
    let written = formats::emit(
        &plan,
        &args,
        single_file,
        &outcomes,
        &input_errors,
        &format_options,
    );
    let indexed = !single_file && plan.file_formats.contains(&Format::Html);
    let written =
        written && (!indexed || write_collection(&args, &paths, &outcomes, &input_errors));
    let worst = match &args.write_baseline {
        Some(path) => write_baseline(path, &outcomes),
        None => outcomes.iter().map(Outcome::exit_code).max().unwrap_or(0),
    };
    if input_errors.is_empty() && written {
        worst
    } else {
        2
    }
}

/// The collection page of a batch written with `--format html` (`index.html`, `.json`, `.md`); false when
/// it could not be written.
fn write_collection(
    args: &Args,
    paths: &[PathBuf],
    outcomes: &[Outcome],
    input_errors: &[String],
) -> bool {
    let Some(dir) = collection::index_dir(args.output_dir.as_deref(), paths, outcomes) else {
        return true;
    };
    match collection::write(&dir, outcomes, input_errors) {
        Ok(written) => {
            if let Some(page) = written.first() {
                errln!(
                    "Collection page: {} (with {} and {} beside it)",
                    page.display(),
                    collection::FILES[1],
                    collection::FILES[2]
                );
            }
            true
        }
        Err(error) => {
            errln!("error: {error}");
            false
        }
    }
}

/// Most passes of `--fix`: applying a fix can call for another (an inertia from geometry moves the centre of
/// mass, so a joint needs another effort), so the files are validated again and fixed again, as ruff does,
/// until nothing is left to fix or this many passes ran.
const MAX_FIX_PASSES: usize = 4;

/// `--diff`: print the fixes, `Err` with the exit code. `--fix`: apply them (pass after pass, see
/// [`MAX_FIX_PASSES`]) and return the outcomes of the files as written; `Err(2)` when a file could not be
/// written.
fn fix_or_diff(
    args: &Args,
    mut outcomes: Vec<Outcome>,
    run: &dyn Fn() -> Vec<Outcome>,
) -> Result<Vec<Outcome>, u8> {
    let policy = fixes::Policy {
        unsafe_fixes: args.unsafe_fixes,
        from_overrides: args.from_overrides,
        package_paths: args.package_path.clone(),
    };
    let (mut fixed, mut written, mut passes) = (0, std::collections::BTreeSet::new(), 0);
    for pass in 1..=MAX_FIX_PASSES {
        let validations: Vec<&urdf_validator::Validation> = outcomes
            .iter()
            .filter_map(|o| o.validation.as_ref().ok())
            .collect();
        let fix_plan = fixes::plan(&validations, &policy);
        let last = fix_plan.files.is_empty() || pass == MAX_FIX_PASSES || args.diff;
        if last {
            for line in &fix_plan.skipped {
                errln!("note: fix not applied: {line}");
            }
        }
        let unsafe_left = match fix_plan.unsafe_left {
            0 => String::new(),
            n => format!(" ({n} more with --unsafe-fixes)"),
        };
        if args.diff {
            out!("{}", fixes::diff(&fix_plan));
            let fixes: usize = fix_plan.files.iter().map(|f| f.fixes).sum();
            errln!(
                "{fixes} fix(es) in {} file(s){unsafe_left}",
                fix_plan.files.len()
            );
            return Err(u8::from(!fix_plan.files.is_empty()));
        }
        let errors = fixes::write(&fix_plan);
        for error in &errors {
            errln!("error: {error}");
        }
        fixed += fix_plan.files.iter().map(|f| f.fixes).sum::<usize>();
        passes += usize::from(!fix_plan.files.is_empty());
        written.extend(fix_plan.files.iter().map(|f| f.path.clone()));
        if !fix_plan.files.is_empty() {
            // What is left, from the files as written.
            outcomes = run();
        }
        if !errors.is_empty() {
            return Err(2);
        }
        if fix_plan.files.is_empty() || pass == MAX_FIX_PASSES {
            let passes = match passes {
                0 | 1 => String::new(),
                n => format!(" in {n} passes"),
            };
            errln!(
                "fixed {fixed} finding(s) in {} file(s){passes}{unsafe_left}",
                written.len()
            );
            break;
        }
    }
    Ok(outcomes)
}

/// `--write-baseline`: every finding that counts, of every robot read, to `path`; 0 when written and
/// every input gave a report, else 2.
fn write_baseline(path: &Path, outcomes: &[Outcome]) -> u8 {
    let reports: Vec<&urdf_validator::report::Report> = outcomes
        .iter()
        .filter_map(|o| o.validation.as_ref().ok())
        .map(|v| &v.report)
        .collect();
    let findings: usize = reports
        .iter()
        .map(|r| r.findings.len() + r.baseline.as_ref().map_or(0, |b| b.baselined.len()))
        .sum();
    if let Err(error) = outputs::write_file(path, &baseline::render(&reports, path)) {
        errln!("error: {}: cannot write baseline: {error}", path.display());
        return 2;
    }
    errln!(
        "Baseline written: {} ({findings} finding(s) of {} robot(s))",
        path.display(),
        reports.len()
    );
    if reports.len() == outcomes.len() {
        0
    } else {
        2
    }
}

fn explain(code: &str) -> u8 {
    match find_rule(code) {
        Ok(rule) => {
            out!("{}", rules::explain(rule));
            0
        }
        Err(message) => {
            errln!("error: {message}; `urdf_validate --list-rules` lists them all");
            2
        }
    }
}

/// The rule with this code or name, else `no rule 'X' (did you mean ...)`.
fn find_rule(code: &str) -> Result<&'static Rule, String> {
    rules::find(code).ok_or_else(|| {
        let names = rules::ALL.iter().flat_map(|r| [r.code, r.name]);
        format!(
            "no rule '{code}' ({})",
            urdf_validator::diagnostics::suggest::did_you_mean(code, names)
        )
    })
}

/// `--show-config`: the settings for the first input (else the current folder), with their origins.
fn show_config(args: &Args, matches: &clap::ArgMatches) -> u8 {
    let shown = request::request_of(args, matches).and_then(|(paths, request)| {
        let anchor = paths.first().cloned().unwrap_or_else(|| PathBuf::from("."));
        config::load(config_file(&request, &anchor).as_deref(), &request)
    });
    match shown {
        Ok(effective) => {
            out!("{}", effective.show());
            0
        }
        Err(message) => {
            errln!("error: {message}");
            2
        }
    }
}

/// `--expand-only`: the expanded URDF of each xacro input on stdout.
fn expand_only(
    files: &[std::path::PathBuf],
    input_errors: &[String],
    xacro_args: &[(String, String)],
    resolver: &PackageResolver,
    sandbox: &Sandbox,
) -> u8 {
    for error in input_errors {
        errln!("error: {error}");
    }
    let mut status = u8::from(!input_errors.is_empty()) * 2;
    let mut stdout = std::io::stdout().lock();
    for file in files {
        if !urdf_validator::input::xacro::is_xacro(file) {
            errln!(
                "error: {}: --expand-only expects a .xacro file",
                file.display()
            );
            status = 2;
            continue;
        }
        let resolver = resolver.with_sandbox(sandbox.for_input(file));
        match urdf_validator::input::xacro::expand(file, xacro_args, &resolver, true) {
            Ok(expanded) => {
                for warning in expanded.warnings() {
                    let message = warning.message;
                    match warning.location {
                        Some(at) => {
                            errln!("warning: {}:{}:{}: {message}", at.file, at.line, at.column)
                        }
                        None => errln!("warning: {message}"),
                    }
                }
                let _ = stdout.write_all(expanded.xml().as_bytes());
            }
            Err(error) => {
                errln!("error: {error}");
                status = 2;
            }
        }
    }
    status
}
