//! `urdf_validate`: validate URDF files, write one JSON report each, exit 0 / 1 / 2.
//!
//! The command lives in this library so that every front end runs the same code: the binary
//! (`src/main.rs`) and the console command of the Python wheel both call [`main_from`].

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

pub mod api;
mod args;
pub mod batch;
mod config;
mod diff;
mod fixes;
mod formats;
mod inputs;
mod mcp;
mod outputs;
mod progress;
mod server;

use std::collections::HashMap;
use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{CommandFactory, FromArgMatches};
use urdf_validator::analysis::pose::PoseOptions;
use urdf_validator::analysis::statics::StaticsOptions;
use urdf_validator::analysis::workspace::target::{parse_axis, Orientation, Task};
use urdf_validator::analysis::workspace::WorkspaceOptions;
use urdf_validator::analysis::Overrides;
use urdf_validator::diagnostics::rules::{self, Rule};
use urdf_validator::input::mesh::{DiskCache, MeshCache};
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::input::sandbox::Sandbox;
use urdf_validator::model::overrides::ValueOverride;
use urdf_validator::render::FormatOptions;
use urdf_validator::report::baseline::{self, Baseline};
use urdf_validator::Options;

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
    let (paths, xacro_args) = match checked_inputs(&args) {
        Ok(checked) => checked,
        Err(message) => {
            errln!("error: {message}");
            return 2;
        }
    };
    let (files, input_errors) = inputs::expand(&paths, args.skip_xacro_libraries);
    if files.is_empty() && input_errors.is_empty() && args.skip_xacro_libraries {
        // Only macro libraries were named (a pre-commit run on changed library files): nothing to do.
        return 0;
    }
    if files.is_empty() && input_errors.is_empty() {
        errln!("error: no input given (expected one or more URDF or xacro files or directories; see --help)");
        return 2;
    }
    let sandbox = sandbox_of(&args);
    let resolver = PackageResolver::from_env_in(args.package_path.clone(), &sandbox);
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
        return expand_only(&files, &input_errors, &xacro_args, &resolver, &sandbox);
    }
    // One set of options per configuration file (the nearest to each input, unless named or turned off).
    let meshes = mesh_cache(args.no_cache);
    let config_of: Vec<Option<PathBuf>> = configs_of(&args, &files);
    let mut groups: Vec<(Option<PathBuf>, Options)> = Vec::new();
    for path in &config_of {
        if groups.iter().any(|(p, _)| p == path) {
            continue;
        }
        match configured_options(&args, matches, path.as_deref(), &xacro_args, &meshes) {
            Ok(options) => groups.push((path.clone(), options)),
            Err(message) => {
                errln!("error: {message}");
                return 2;
            }
        }
    }
    let timeout = match timeout_of(&args) {
        Ok(timeout) => timeout,
        Err(message) => {
            errln!("error: {message}");
            return 2;
        }
    };
    let plan = match Plan::new(&args, &GithubEnv::from_env()) {
        Ok(plan) => plan,
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
        rules_url: rules_url(),
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
    let jobs: Vec<_> = files.iter().zip(&bases).zip(&config_of).collect();
    // Files on threads of their own, not on the pool their stages use (see `batch`); a single file on
    // this thread.
    let run = || -> Vec<Outcome> {
        batch::map_files(&jobs, |((file, base), config)| {
            let options = groups
                .iter()
                .find(|(p, _)| p == *config)
                .map(|(_, options)| options);
            let outcome = match options {
                Some(options) => {
                    outputs::validate_one(file, base, options, &files_to_write, timeout)
                }
                None => outputs::Outcome::not_configured(file),
            };
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

/// `--timeout`: `None` for no limit (0, or more seconds than a `Duration` holds).
fn timeout_of(args: &Args) -> Result<Option<std::time::Duration>, String> {
    match args.timeout {
        t if t >= 0.0 => Ok(std::time::Duration::try_from_secs_f64(t)
            .ok()
            .filter(|d| !d.is_zero())),
        t => Err(format!("--timeout {t}: expected seconds ≥ 0 (0: no limit)")),
    }
}

/// The rules reference on the web, for SARIF `helpUri`s: `docs/rules.md` of the repository named in
/// Cargo.toml (`repository`); none when it names none.
fn rules_url() -> Option<String> {
    option_env!("CARGO_PKG_REPOSITORY")
        .map(|url| url.trim_end_matches('/'))
        .filter(|url| !url.is_empty())
        .map(|url| format!("{url}/blob/main/docs/rules.md"))
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

/// The configuration file of each input: `--config` for all, none with `--no-config`, else the nearest
/// found from the input's folder upwards.
fn configs_of(args: &Args, files: &[PathBuf]) -> Vec<Option<PathBuf>> {
    if args.no_config {
        return vec![None; files.len()];
    }
    if let Some(path) = &args.config {
        return vec![Some(path.clone()); files.len()];
    }
    let mut by_dir: HashMap<PathBuf, Option<PathBuf>> = HashMap::new();
    files
        .iter()
        .map(|file| {
            let dir = file.parent().unwrap_or(Path::new("")).to_path_buf();
            by_dir
                .entry(dir)
                .or_insert_with(|| config::discover(file))
                .clone()
        })
        .collect()
}

/// `--show-config`: the settings for the first input (else the current folder), with their origins.
fn show_config(args: &Args, matches: &clap::ArgMatches) -> u8 {
    let (paths, _) = inputs::split_xacro_args(&args.inputs);
    let anchor = paths.first().cloned().unwrap_or_else(|| PathBuf::from("."));
    let path = if args.no_config {
        None
    } else if let Some(path) = &args.config {
        Some(path.clone())
    } else {
        config::discover(&anchor)
    };
    match config::load(path.as_deref(), args, matches) {
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

/// xacro arguments, `(name, value)` in the order given.
type XacroArgs = Vec<(String, String)>;

/// The flags' checks that come before any file is read, and the paths to validate with the xacro
/// arguments (positional `name:=value` words and `--xacro-arg`).
fn checked_inputs(args: &Args) -> Result<(Vec<PathBuf>, XacroArgs), String> {
    workspace_options(args)?;
    let overriding = !args.overrides.is_empty() || args.override_file.is_some();
    if args.from_overrides && !(args.fix || args.diff) {
        return Err(
            "--from-overrides writes the overrides as fixes: give it with --fix or --diff".into(),
        );
    }
    if args.from_overrides && !overriding {
        return Err("--from-overrides: no --override or --override-file to write".into());
    }
    if overriding && (args.fix || args.diff) && !args.from_overrides {
        return Err(
            "--override with --fix or --diff: the fixes would be computed for values the file does not hold; \
             add --from-overrides to write the overrides into the file"
                .into(),
        );
    }
    if args.arm_root.len() != args.arm_tip.len() {
        return Err(format!(
            "{} --arm-root but {} --arm-tip: give them in pairs, one pair per arm",
            args.arm_root.len(),
            args.arm_tip.len()
        ));
    }
    let (paths, mut xacro_args) = inputs::split_xacro_args(&args.inputs);
    for arg in &args.xacro_arg {
        xacro_args.push(inputs::parse_xacro_arg_flag(arg)?);
    }
    Ok((paths, xacro_args))
}

/// The options of the inputs that configuration file `config` governs (none: the flags and defaults
/// alone): the file read and merged with the flags.
fn configured_options(
    args: &Args,
    matches: &clap::ArgMatches,
    config: Option<&Path>,
    xacro_args: &[(String, String)],
    meshes: &MeshCache,
) -> Result<Options, String> {
    let effective = config::load(config, args, matches)?;
    let mut group_args = args.clone();
    effective.apply_to(&mut group_args);
    // The roots come from the command line only: a configuration file beside an untrusted input is as
    // untrusted as the input.
    let sandbox = sandbox_of(args);
    options_for(&group_args, effective.settings, xacro_args, meshes, sandbox).map_err(|message| {
        match config {
            Some(path) => format!("{message} (with the settings of {})", path.display()),
            None => message,
        }
    })
}

/// The sandbox the flags ask for: trusted, or `--untrusted` with the `--package-path` and `--root`
/// folders as roots and the `--allow-env` variables.
fn sandbox_of(args: &Args) -> Sandbox {
    if !args.untrusted {
        return Sandbox::default();
    }
    Sandbox::untrusted(
        args.package_path.iter().chain(&args.root).cloned(),
        args.allow_env.iter().cloned(),
    )
}

/// The library options from the flags (already merged with a configuration file), `settings` and the
/// `sandbox`.
fn options_for(
    args: &Args,
    settings: urdf_validator::diagnostics::Settings,
    xacro_args: &[(String, String)],
    meshes: &MeshCache,
    sandbox: Sandbox,
) -> Result<Options, String> {
    if let Some(mass) = args.payload_mass.filter(|m| !(m.is_finite() && *m >= 0.0)) {
        return Err(format!("--payload-mass {mass}: expected a mass ≥ 0 in kg"));
    }
    Ok(Options {
        workspace: workspace_options(args)?,
        xacro_args: xacro_args.to_vec(),
        resolver: PackageResolver::from_env_in(args.package_path.clone(), &sandbox),
        sandbox,
        statics: StaticsOptions {
            pose: PoseOptions {
                kind: args.pose.clone(),
                joint_angles: args.joint_angles.clone(),
                srdf: args.srdf.clone(),
                state: args.state.clone(),
                samples: args.samples,
                seed: args.seed,
            },
            payload_mass: args.payload_mass,
            payload_link: args.payload_link.clone(),
        },
        overrides: Overrides {
            robot_type: args.robot_type.map(Into::into),
            up_axis: args.up_axis,
            contact_links: args.contact_links.clone(),
            arms: args
                .arm_root
                .iter()
                .cloned()
                .zip(args.arm_tip.iter().cloned())
                .collect(),
        },
        timings: args.timings,
        meshes: meshes.clone(),
        progress: None,
        settings,
        deep: urdf_validator::analysis::deep::DeepOptions {
            requested: args.deep,
            ..Default::default()
        },
        simulators: args.simulator.iter().map(|&s| s.into()).collect(),
        baseline: args
            .baseline
            .as_deref()
            .map(|path| Baseline::load(path).map(std::sync::Arc::new))
            .transpose()?,
        sdf_model: args.model.clone(),
        value_overrides: value_overrides(args)?,
        structure_only: false,
    })
}

/// `--override KEY=VALUE`s, after those of `--override-file` (so the command line wins).
fn value_overrides(args: &Args) -> Result<Vec<ValueOverride>, String> {
    let mut texts = Vec::new();
    if let Some(path) = &args.override_file {
        texts.extend(override_file(path)?);
    }
    texts.extend(args.overrides.iter().cloned());
    texts
        .iter()
        .map(|text| ValueOverride::parse(text))
        .collect()
}

/// The `KEY=VALUE`s of an override file: `[joint.NAME]` tables with `effort`/`lower`/`upper`/`velocity`,
/// `[link.NAME]` with `mass` and `com = [x, y, z]`, `[payload]` with `mass`.
fn override_file(path: &Path) -> Result<Vec<String>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("--override-file {}: cannot read it ({e})", path.display()))?;
    let table: toml::Table = text
        .parse()
        .map_err(|e| format!("--override-file {}: not TOML ({e})", path.display()))?;
    let number = |value: &toml::Value| match value {
        toml::Value::Float(v) => Some(v.to_string()),
        toml::Value::Integer(v) => Some(v.to_string()),
        _ => None,
    };
    let mut texts = Vec::new();
    for (kind, entries) in &table {
        let entries = entries.as_table().ok_or_else(|| {
            format!(
                "--override-file {}: '{kind}' must be a table",
                path.display()
            )
        })?;
        let mut add = |key: String, value: &toml::Value| -> Result<(), String> {
            let value = match value {
                toml::Value::Array(items) => items
                    .iter()
                    .map(number)
                    .collect::<Option<Vec<_>>>()
                    .map(|v| v.join(",")),
                other => number(other),
            }
            .ok_or_else(|| {
                format!(
                    "--override-file {}: '{key}' must be a number (or [x, y, z])",
                    path.display()
                )
            })?;
            texts.push(format!("{key}={value}"));
            Ok(())
        };
        if kind == "payload" {
            for (attribute, value) in entries {
                add(format!("payload.{attribute}"), value)?;
            }
            continue;
        }
        for (name, attributes) in entries {
            let attributes = attributes.as_table().ok_or_else(|| {
                format!(
                    "--override-file {}: '{kind}.{name}' must be a table",
                    path.display()
                )
            })?;
            for (attribute, value) in attributes {
                add(format!("{kind}.{name}.{attribute}"), value)?;
            }
        }
    }
    Ok(texts)
}

/// The run's mesh cache: in memory, and on disk unless `--no-cache` (or no cache folder is known).
fn mesh_cache(no_cache: bool) -> MeshCache {
    match DiskCache::user_default().filter(|_| !no_cache) {
        Some(disk) => MeshCache::new().with_disk_cache(disk),
        None => MeshCache::new(),
    }
}

/// The workspace flags, checked.
fn workspace_options(args: &Args) -> Result<WorkspaceOptions, String> {
    let task = match (&args.task, args.height) {
        (Some(name), height) => Some(Task::parse(name, height)?),
        (None, Some(_)) => return Err("--height needs --task custom".to_string()),
        (None, None) => None,
    };
    if args.samples == 0 {
        return Err("--samples must be at least 1".to_string());
    }
    let tolerance = args.orientation_tolerance;
    if !(tolerance.is_finite() && (0.0..=180.0).contains(&tolerance)) {
        return Err(format!(
            "--orientation-tolerance must be between 0 and 180 degrees, not {tolerance}"
        ));
    }
    Ok(WorkspaceOptions {
        samples: args.samples,
        seed: args.seed,
        task,
        orientation: args
            .orientation
            .as_deref()
            .map(Orientation::parse)
            .transpose()?,
        orientation_tolerance_deg: tolerance,
        approach_axis: args.approach_axis.as_deref().map(parse_axis).transpose()?,
        progress: None,
    })
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
