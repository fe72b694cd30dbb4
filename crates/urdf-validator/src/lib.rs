//! urdf-validator: physics-aware validation of URDF (and xacro, SDFormat and MJCF) robot descriptions.
//!
//! The library is laid out by pipeline stage, each folder handing the next exactly what it needs:
//!
//! | stage | module | produces |
//! |---|---|---|
//! | load | [`input`] | the URDF text (xacro expanded), positions back into the files the user edits |
//! | parse | [`urdf`], [`sdf`], [`mjcf`] | a typed [`urdf::Robot`] with spans (SDFormat and MJCF read into the same type), and parse findings |
//! | model | [`model`] | the kinematic tree, forward kinematics, mass properties |
//! | assets | [`assets`] | meshes and their hulls, link supports, the SRDF: loaded once |
//! | checks | `checks` (internal) | structural findings |
//! | analyses | [`analysis`] | statics, stability, workspace sections and their findings |
//! | report | [`report`] | the one [`report::Report`] |
//! | render | [`render`] | views of the report (text) |
//!
//! Findings, rules and verdicts ([`diagnostics`]) are shared by every stage.
//!
//! ```no_run
//! let options = urdf_validator::Options::default();
//! let validation = urdf_validator::validate(std::path::Path::new("robot.urdf"), &options)?;
//! println!("{}", validation.report.overall_status.label());
//! # Ok::<(), urdf_validator::Error>(())
//! ```

pub mod analysis;
pub mod assets;
pub(crate) mod checks;
pub mod diagnostics;
pub mod input;
pub mod mjcf;
pub mod model;
pub mod render;
pub mod report;
pub mod rng;
pub mod sdf;
pub mod task_query;
pub mod timings;
pub mod urdf;

use std::path::{Path, PathBuf};

use analysis::workspace::WorkspaceOptions;
use analysis::{statics::StaticsOptions, Overrides};
use assets::{AssetSource, Assets};
use input::mesh::MeshCache;
use input::resolve::PackageResolver;
use input::sandbox::Sandbox;
use input::source::SourceText;
use input::{LoadError, Loaded};
use model::Model;
use report::{Outcome, Report};
use timings::{Progress, Stopwatch};

pub use analysis::{DEFAULT_SAMPLES, DEFAULT_SEED};
pub use report::VERSION;

/// What a validation run needs besides the file; one value flows one way through the stages.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Where `package://` URIs are looked up.
    pub resolver: PackageResolver,
    /// What the robot's files may read (`--untrusted`): every file and variable the stages read is
    /// checked against it. Trusted by default.
    pub sandbox: Sandbox,
    /// Pose and payload for statics.
    pub statics: StaticsOptions,
    /// Samples, task and orientation for the workspace.
    pub workspace: WorkspaceOptions,
    /// What the user declares instead of heuristics.
    pub overrides: Overrides,
    /// Meshes loaded so far (shared by every file of a run).
    pub meshes: MeshCache,
    /// Arguments for `.xacro` inputs (`name:=value`).
    pub xacro_args: Vec<(String, String)>,
    /// Record the time of each phase in the report (`timings_ms`).
    pub timings: bool,
    /// Told each phase as it finishes, so a watchdog can say where a run stands.
    pub progress: Option<Progress>,
    /// Rule selection, severity overrides and suppressions, applied when the report is built
    /// (`urdf-validate.toml`, `--select`, `--ignore`, `--show-suppressed`).
    pub settings: diagnostics::Settings,
    /// `--deep`: the MuJoCo pass, and whether it runs by itself on a robot that tips over.
    pub deep: analysis::deep::DeepOptions,
    /// `--simulator`: the load profiles whose findings are added (what each importer does to the file).
    pub simulators: Vec<analysis::profiles::Simulator>,
    /// `--baseline`: findings it holds are not reported and do not count (shared by every file of a run).
    pub baseline: Option<std::sync::Arc<report::baseline::Baseline>>,
    /// `--model`: the model of an SDFormat world to analyse (default: its first non-static model with
    /// joints).
    pub sdf_model: Option<String>,
    /// `--override KEY=VALUE`: declared values to evaluate the robot with instead (the file untouched).
    pub value_overrides: Vec<model::overrides::ValueOverride>,
    /// Stop after the structural checks (parse, tree, meshes, schema rules): no statics, stability,
    /// workspace or deep section. The language server's first, fast pass after an edit.
    pub structure_only: bool,
    /// Build the 3-D view's scene into [`Validation::view`] (the HTML report draws it).
    pub view: bool,
}

/// Why a file gave no report (exit code 2, one line naming the file).
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The file could not be loaded (read, expanded, parsed as XML).
    #[error(transparent)]
    Load(#[from] LoadError),
    /// The options ask of this robot what it cannot give (an unknown link, a missing SRDF, a bad pose).
    #[error("{}: {source}", path.display())]
    Request {
        /// The file.
        path: PathBuf,
        /// What does not fit.
        #[source]
        source: analysis::RequestError,
    },
    /// The options do not fit this file: an `--override` of a value it does not declare, an SDFormat
    /// world without the `--model` asked for, `--deep` with a turned up axis.
    #[error("{}: {message}", path.display())]
    Unusable {
        /// The file.
        path: PathBuf,
        /// What is wrong, with suggestions.
        message: String,
    },
    /// The validation did not finish in the time allowed (`--timeout`).
    #[error("{}: analysis did not finish within {seconds} s (stage running: {stage}); the rest of the run goes on (raise --timeout, or 0 for none)", path.display())]
    DidNotFinish {
        /// The file.
        path: PathBuf,
        /// The time allowed.
        seconds: f64,
        /// The phase that was running.
        stage: &'static str,
    },
}

/// The result of validating one file: the report plus what renderers need to show source snippets.
#[derive(Debug)]
pub struct Validation {
    /// The report.
    pub report: Report,
    /// The source texts findings point into.
    pub sources: Vec<SourceText>,
    /// The 3-D view's scene as JSON ([`render::view::Scene`]), when [`Options::view`] asked for it.
    pub view: Option<String>,
}

impl Validation {
    /// The text of `line` in `file`, if that file is one of the sources.
    pub fn source_line(&self, file: &str, line: u32) -> Option<&str> {
        self.sources
            .iter()
            .find(|s| s.path().display().to_string() == file)
            .map(|s| s.line_text(line))
    }
}

/// A validation with what it was computed from, for views that draw the robot ([`render::view`]).
#[derive(Debug)]
pub struct Inspection {
    /// The validation.
    pub validation: Validation,
    /// The parsed robot (after `--override`).
    pub robot: urdf::Robot,
    /// Its kinematic tree.
    pub model: Model,
    /// Its meshes, supports and SRDF; `None` when the file is not a robot (no assets were loaded).
    pub assets: Option<Assets>,
}

/// Validate the URDF (or xacro: expanded first, findings located in the xacro sources) at `path`.
pub fn validate(path: &Path, options: &Options) -> Result<Validation, Error> {
    inspect(path, options).map(|inspection| inspection.validation)
}

/// [`validate`], keeping the robot, its model and its assets.
pub fn inspect(path: &Path, options: &Options) -> Result<Inspection, Error> {
    let mut clock = Stopwatch::reporting_to(options.progress.clone());
    let sandbox = options.sandbox.for_input(path);
    sandbox
        .check_file(path)
        .map_err(|refusal| LoadError::Refused {
            path: path.to_path_buf(),
            message: format!("refused to read: {refusal}"),
        })?;
    let resolver = options.resolver.with_sandbox(sandbox);
    let loaded = Loaded::read(path, &options.xacro_args, &resolver)?;
    clock.lap("load");
    run(loaded, options, &resolver, clock)
}

/// Validate URDF or SDFormat `text` that was read from `path` (used for positions, relative meshes and
/// includes, and the report). SDFormat is told by its `<sdf>` root, as [`validate`] tells it. In untrusted
/// mode only the sandbox's own roots are readable (`path`'s folder is not added: the text is not from there).
pub fn validate_text(text: String, path: &Path, options: &Options) -> Result<Validation, Error> {
    let clock = Stopwatch::reporting_to(options.progress.clone());
    let resolver = options.resolver.with_sandbox(options.sandbox.clone());
    run(
        Loaded::from_document(text, path, &resolver)?,
        options,
        &resolver,
        clock,
    )
    .map(|inspection| inspection.validation)
}

/// Validate `text`, the unsaved content of the file at `path` (an editor's buffer): expanded first when
/// `path` is a xacro file (its includes read from disk), else URDF or SDFormat as [`validate`] tells them.
/// The file's sandbox applies, as for [`validate`]; positions are in `path` and the files it includes.
pub fn validate_unsaved(text: String, path: &Path, options: &Options) -> Result<Validation, Error> {
    let clock = Stopwatch::reporting_to(options.progress.clone());
    let resolver = options
        .resolver
        .with_sandbox(options.sandbox.for_input(path));
    let loaded = Loaded::from_unsaved(text, path, &options.xacro_args, &resolver)?;
    run(loaded, options, &resolver, clock).map(|inspection| inspection.validation)
}

/// The MJCF file's absolute path for `--deep` to hand MuJoCo (`Err`: why MuJoCo cannot be given it);
/// looked at only for MJCF input when the pass may run.
fn mjcf_on_disk(loaded: &Loaded, options: &Options) -> Result<PathBuf, String> {
    if loaded.mjcf().is_none() || !(options.deep.requested || options.deep.automatic) {
        return Err("not an MJCF file".to_string()); // (never shown: the pass does not run on it)
    }
    if options.sandbox.is_untrusted() {
        return Err("MuJoCo reads the files an MJCF file names (includes, meshes, textures) itself, outside the --untrusted sandbox".to_string());
    }
    // MuJoCo reads the saved file: an editor's unsaved buffer is another model.
    loaded.saved_path().ok_or_else(|| {
        "MuJoCo loads the file as saved, and the text validated differs from it (unsaved)"
            .to_string()
    })
}

/// What `--deep` hands MuJoCo: the URDF text, the MJCF file (or why not), nothing for SDFormat.
fn deep_source<'a>(
    loaded: &'a Loaded,
    mjcf: &'a Result<PathBuf, String>,
) -> analysis::deep::DeepSource<'a> {
    use analysis::deep::DeepSource;
    match (loaded.format(), loaded.mjcf(), mjcf) {
        (input::Format::Urdf, _, _) => DeepSource::Urdf(loaded.text()),
        (_, Some(_), Ok(path)) => DeepSource::Mjcf(path),
        (_, Some(_), Err(why)) => DeepSource::Withheld(why),
        _ => DeepSource::Sdf,
    }
}

/// The pipeline: parse → overrides → model → (assets → checks → physics → deep) → report, each stage
/// handed what it needs. `resolver` is the run's, checking against this file's sandbox.
fn run(
    loaded: Loaded,
    options: &Options,
    resolver: &PackageResolver,
    mut clock: Stopwatch,
) -> Result<Inspection, Error> {
    // A URDF's XML document is read once: the parse reads the robot from it, the report element paths.
    let urdf_text =
        (loaded.format() == input::Format::Urdf).then(|| urdf::parse::UrdfText::new(loaded.text()));
    let document = urdf_text
        .as_ref()
        .map(|text| text.document(&loaded.path))
        .transpose()?;
    let (mut robot, mut findings) = match (&urdf_text, &document, loaded.mjcf()) {
        (Some(text), Some(document), _) => text.parse(document),
        (_, _, Some(files)) => mjcf::parse_mjcf(files, &options.meshes, resolver),
        _ => parse_sdf(&loaded, options)?,
    };
    let overrides =
        model::overrides::apply(&mut robot, &options.value_overrides, document.as_ref())
            .map_err(|message| usage(&loaded, message))?;
    let options = &with_overridden_payload(options);
    clock.lap("parse");
    let (mut model, tree_findings) = Model::build(&robot);
    model.up = options.overrides.up_axis.unwrap_or_default();
    findings.extend(tree_findings);
    clock.lap("model");
    let is_robot = !findings
        .iter()
        .any(|f| f.rule == &diagnostics::rules::NOT_A_ROBOT);
    let (analyses, assets) = if is_robot {
        let robot_run = RobotRun {
            loaded: &loaded,
            robot: &robot,
            model: &model,
            options,
        };
        let (analyses, assets) = robot_run.analyse(resolver, &mut findings, &mut clock)?;
        (analyses, Some(assets))
    } else {
        (None, None)
    };
    let report = report::build(Outcome {
        loaded: &loaded,
        document: document.as_ref(),
        robot: &robot,
        model: &model,
        findings,
        analyses,
        settings: &options.settings,
        baseline: options.baseline.as_deref(),
        overrides,
    });
    clock.lap("report");
    let report = Report {
        timings_ms: options.timings.then_some(clock.timings),
        ..report
    };
    let sources = loaded.into_sources();
    let inspection = Inspection {
        validation: Validation {
            report,
            sources,
            view: None,
        },
        robot,
        model,
        assets,
    };
    Ok(if options.view {
        with_view(inspection, options)
    } else {
        inspection
    })
}

/// The inspection with its 3-D scene in the validation, for the HTML report.
fn with_view(inspection: Inspection, options: &Options) -> Inspection {
    let poser = render::view::Poser::new(inspection, options);
    let scene = serde_json::to_string(&render::view::scene::build(&poser)).ok();
    let mut inspection = poser.into_inspection();
    inspection.validation.view = scene;
    inspection
}

/// The options with `--override payload.mass=V` as the payload, when given.
fn with_overridden_payload(options: &Options) -> std::borrow::Cow<'_, Options> {
    match options
        .value_overrides
        .iter()
        .find_map(|o| o.payload_mass())
    {
        Some(mass) => std::borrow::Cow::Owned(Options {
            statics: StaticsOptions {
                payload_mass: Some(mass),
                ..options.statics.clone()
            },
            ..options.clone()
        }),
        None => std::borrow::Cow::Borrowed(options),
    }
}

/// A robot past the model stage, on its way through the stages that analyse it.
struct RobotRun<'a> {
    loaded: &'a Loaded,
    robot: &'a urdf::Robot,
    model: &'a Model,
    options: &'a Options,
}

impl RobotRun<'_> {
    /// Assets, checks, then (unless `structure_only`) the physics and the MuJoCo pass; their findings
    /// added to `findings`. The assets are handed back with the physics.
    fn analyse(
        &self,
        resolver: &PackageResolver,
        findings: &mut Vec<diagnostics::Finding>,
        clock: &mut Stopwatch,
    ) -> Result<(Option<analysis::Physics>, Assets), Error> {
        let (loaded, robot, model, options) = (self.loaded, self.robot, self.model, self.options);
        give_up_if_cancelled(options, &loaded.path)?;
        let assets = Assets::load(robot, &asset_source(&loaded.path, options, resolver));
        clock.lap("assets");
        give_up_if_cancelled(options, &loaded.path)?;
        findings.extend(checks::run(robot, model, &assets));
        findings.extend(analysis::profiles::check(robot, model, &options.simulators));
        clock.lap("checks");
        if options.structure_only {
            return Ok((None, assets));
        }
        give_up_if_cancelled(options, &loaded.path)?;
        // The workspace sampler stops early when a watchdog cancels the run.
        let workspace = WorkspaceOptions {
            progress: options.progress.clone(),
            ..options.workspace.clone()
        };
        let inputs = analysis_inputs(&assets, options, &workspace);
        let mut physics =
            analysis::analyse(robot, model, &inputs, clock).map_err(|source| Error::Request {
                path: loaded.path.clone(),
                source,
            })?;
        findings.extend(physics.findings.iter().cloned());
        give_up_if_cancelled(options, &loaded.path)?;
        if let Some((section, deep_findings)) = self.deep(&assets, &physics)? {
            analysis::deep::mark_simulated(&mut physics, &section);
            physics.deep = Some(section);
            findings.extend(deep_findings);
            clock.lap("deep");
        }
        Ok((Some(physics), assets))
    }

    /// The MuJoCo pass, when it runs (`--deep`, or by itself on a robot that tips over).
    fn deep(
        &self,
        assets: &Assets,
        physics: &analysis::Physics,
    ) -> Result<Option<(analysis::deep::DeepSection, Vec<diagnostics::Finding>)>, Error> {
        let (loaded, model, options) = (self.loaded, self.model, self.options);
        // MuJoCo loads the file z-up: with another declared up axis its pass would judge another robot.
        if model.up != model::UpAxis::default() {
            if options.deep.requested {
                return Err(usage(
                    loaded,
                    format!(
                        "--deep with --up-axis {}: the MuJoCo pass loads the file z-up and cannot turn it yet",
                        model.up.as_str()
                    ),
                ));
            }
            return Ok(None);
        }
        let mjcf_on_disk = mjcf_on_disk(loaded, options);
        Ok(analysis::deep::run(&analysis::deep::DeepInput {
            source: deep_source(loaded, &mjcf_on_disk),
            robot: self.robot,
            model,
            assets,
            physics,
            payload: payload(model, options),
            contact_links: options.overrides.contact_links.as_deref(),
            options: &options.deep,
            progress: options.progress.as_ref(),
        }))
    }
}

/// The options do not fit this file.
fn usage(loaded: &Loaded, message: String) -> Error {
    Error::Unusable {
        path: loaded.path.clone(),
        message,
    }
}

/// [`Error::DidNotFinish`] once a watchdog has cancelled the run (`--timeout`): nobody waits for its
/// answer any more, so the stages left would only hold threads other files need.
fn give_up_if_cancelled(options: &Options, path: &Path) -> Result<(), Error> {
    match &options.progress {
        Some(progress) if progress.is_cancelled() => Err(Error::DidNotFinish {
            path: path.to_path_buf(),
            seconds: progress.time_limit_seconds(),
            stage: progress.running(),
        }),
        _ => Ok(()),
    }
}

/// The parse stage of SDFormat files.
fn parse_sdf(
    loaded: &Loaded,
    options: &Options,
) -> Result<(urdf::Robot, Vec<diagnostics::Finding>), Error> {
    let files = loaded
        .sdf()
        .ok_or_else(|| usage(loaded, "not an SDFormat file".to_string()))?;
    sdf::parse_sdf(files, options.sdf_model.as_deref()).map_err(|message| usage(loaded, message))
}

/// `--payload-mass` at the link statics carries it at.
fn payload(model: &Model, options: &Options) -> Option<(model::LinkId, f64)> {
    let mass = options.statics.payload_mass?;
    let link = match &options.statics.payload_link {
        Some(name) => model.link(name)?,
        None => analysis::statics::gravity::default_payload_link(model)?,
    };
    Some((link, mass))
}

fn asset_source<'a>(
    path: &'a Path,
    options: &'a Options,
    resolver: &'a PackageResolver,
) -> AssetSource<'a> {
    AssetSource {
        urdf_path: path,
        resolver,
        meshes: &options.meshes,
        srdf: options.statics.pose.srdf.as_deref(),
    }
}

fn analysis_inputs<'a>(
    assets: &'a Assets,
    options: &'a Options,
    workspace: &'a WorkspaceOptions,
) -> analysis::Inputs<'a> {
    analysis::Inputs {
        assets,
        statics: &options.statics,
        workspace,
        overrides: &options.overrides,
    }
}
