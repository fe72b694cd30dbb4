//! urdf-validator: physics-aware validation of URDF robot descriptions.
//!
//! Pipeline: [`parse`] the XML into a typed [`robot::Robot`] that keeps source spans, build the kinematic
//! [`model::Model`], run the [`checks`], and assemble one [`report::Report`]. Renderers (text, JSON) are
//! views of the report.
//!
//! ```no_run
//! let options = urdf_validator::Options::default();
//! let validation = urdf_validator::validate(std::path::Path::new("robot.urdf"), &options)?;
//! println!("{}", validation.report.overall_status.label());
//! # Ok::<(), urdf_validator::input::LoadError>(())
//! ```

pub mod analysis;
pub mod assets;
pub mod checks;
pub mod diagnostics;
pub mod input;
pub mod model;
pub mod render;
pub mod report;
pub mod rng;
pub mod urdf;

use std::path::Path;

use analysis::{mass, Physics};
use diagnostics::{rules, Finding, Severity};
use input::LoadError;
use input::{resolve::PackageResolver, source::SourceText, xacro as xacro_input};
use model::Model;
use report::{FindingReport, Report, SchemaSection, Status};
use urdf::Robot;

/// This library's version, written into every report.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// What a validation run needs besides the file.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Where `package://` URIs are looked up.
    pub resolver: PackageResolver,
    /// Pose and payload for statics.
    pub statics: analysis::statics::StaticsOptions,
    /// Samples, task and orientation for the workspace.
    pub workspace: analysis::workspace::WorkspaceOptions,
    /// What the user declares instead of heuristics.
    pub overrides: analysis::Overrides,
    /// Meshes loaded so far (shared by every file of a run).
    pub meshes: input::mesh::MeshCache,
    /// Arguments for `.xacro` inputs (`name:=value`).
    pub xacro_args: Vec<(String, String)>,
}

/// The result of validating one file: the report plus what renderers need to show source snippets.
#[derive(Debug)]
pub struct Validation {
    /// The report.
    pub report: Report,
    /// The source texts findings point into.
    pub sources: Vec<SourceText>,
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

/// Validate the URDF (or xacro: expanded first, findings located in the xacro sources) at `path`.
pub fn validate(path: &Path, options: &Options) -> Result<Validation, LoadError> {
    if xacro_input::is_xacro(path) {
        let expanded = xacro_input::expand(path, &options.xacro_args, &options.resolver, false)?;
        let text = expanded.xml().to_string();
        return validate_source(text, path, options, Locator::Xacro(expanded));
    }
    let text = input::read_text(path)?;
    validate_text(text, path, options)
}

/// Validate URDF `text` that was read from `path` (used for positions, relative meshes and the report).
pub fn validate_text(
    text: String,
    path: &Path,
    options: &Options,
) -> Result<Validation, LoadError> {
    validate_source(text, path, options, Locator::Urdf)
}

/// How positions in the parsed text become positions in the files the user edits.
enum Locator {
    /// The text is the file.
    Urdf,
    /// The text was expanded from xacro sources.
    Xacro(xacro_input::Expanded),
}

fn validate_source(
    text: String,
    path: &Path,
    options: &Options,
    locator: Locator,
) -> Result<Validation, LoadError> {
    let (robot, mut findings) = urdf::parse_urdf(&text, path)?;
    // Expander warnings are located in the sources already (not in the expanded text).
    let xacro_warnings = match &locator {
        Locator::Urdf => Vec::new(),
        Locator::Xacro(expanded) => expanded.warnings(),
    };
    let (model, tree_findings) = Model::build(&robot);
    findings.extend(tree_findings);
    let is_robot = !findings.iter().any(|f| f.rule == &rules::NOT_A_ROBOT);
    let physics = if is_robot {
        let urdf_dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let ctx = checks::CheckContext {
            urdf_dir,
            resolver: &options.resolver,
            meshes: &options.meshes,
        };
        findings.extend(checks::run(&robot, &model, &ctx));
        let supports: Vec<assets::supports::LinkSupports> = robot
            .links
            .iter()
            .map(|link| assets::supports::link_supports(link, &|uri| ctx.mesh_points(uri)))
            .collect();
        let mesh_points = |uri: &str| ctx.mesh_points(uri);
        let inputs = analysis::Inputs {
            urdf_path: path,
            supports: &supports,
            mesh_points: &mesh_points,
            statics: &options.statics,
            workspace: &options.workspace,
            overrides: &options.overrides,
        };
        let physics =
            analysis::analyse(&robot, &model, &inputs).map_err(|message| LoadError::Usage {
                path: path.to_path_buf(),
                message,
            })?;
        findings.extend(physics.findings.iter().cloned());
        Some(physics)
    } else {
        None
    };
    let source = SourceText::new(path, text);
    let mut report_findings: Vec<FindingReport> = findings
        .iter()
        .map(|f| finding_report(f, &source, &locator))
        .collect();
    for (message, location) in xacro_warnings {
        let finding = Finding::new(&rules::XACRO_WARNING, None, message);
        let mut report = finding_report(&finding, &source, &locator);
        if let Some(at) = location {
            report.file = Some(at.file);
            report.line = Some(at.line);
            report.column = Some(at.column);
            report.end_line = Some(at.end_line);
            report.end_column = Some(at.end_column);
            report.expanded_from = at.stack;
        }
        report_findings.push(report);
        findings.push(finding);
    }
    let report = build_report(path, &robot, &model, &findings, report_findings, physics);
    let sources = match &locator {
        Locator::Urdf => vec![source],
        Locator::Xacro(expanded) => expanded.sources(),
    };
    Ok(Validation { report, sources })
}

/// What could not be assessed, one line per section.
fn unknowns(analyses: &Physics) -> Vec<String> {
    let mut lines = Vec::new();
    if analyses.statics.status == Status::Unknown {
        lines.push(format!(
            "Statics: {}",
            analyses
                .statics
                .reason
                .as_deref()
                .unwrap_or("a joint cannot be assessed")
        ));
    }
    if analyses.stability.status == Status::Unknown {
        lines.push(format!(
            "Stability: {}",
            analyses.stability.reason.as_deref().unwrap_or("no result")
        ));
    }
    if analyses.workspace.status == Status::Unknown {
        lines.push(format!(
            "Workspace: {}",
            analyses.workspace.reason.as_deref().unwrap_or("no result")
        ));
    }
    lines
}

fn messages(findings: &[Finding], severity: Severity) -> Vec<String> {
    findings
        .iter()
        .filter(|f| f.severity() == severity)
        .map(|f| f.message.clone())
        .collect()
}

fn build_report(
    path: &Path,
    robot: &Robot,
    model: &Model,
    findings: &[Finding],
    finding_reports: Vec<FindingReport>,
    analyses: Option<Physics>,
) -> Report {
    let critical_issues = messages(findings, Severity::Critical);
    let warnings = messages(findings, Severity::Warn);
    let schema_status = if !critical_issues.is_empty() {
        Status::Fail
    } else if !warnings.is_empty() {
        Status::Warn
    } else {
        Status::Pass
    };
    let links = mass::link_reports(robot, model);
    let summary = mass::summarize(&links);
    let overall_status = analyses.as_ref().map_or(schema_status, |a| {
        schema_status
            .worst(a.statics.status)
            .worst(a.stability.status)
            .worst(a.workspace.status)
    });
    Report {
        urdf_path: path.display().to_string(),
        robot_name: robot
            .name
            .as_ref()
            .map(|n| n.value.clone())
            .unwrap_or_default(),
        timestamp: report::timestamp::now(),
        validator_version: VERSION.to_string(),
        overall_status,
        robot_type: analyses.as_ref().map(|a| a.robot_type),
        robot_type_confidence: analyses.as_ref().map(|a| a.robot_type_confidence),
        robot_type_detected: analyses.as_ref().map(|a| a.detected),
        robot_type_evidence: analyses.as_ref().map(|a| a.evidence.clone()),
        confidence_level: mass::confidence_level(&summary),
        critical_issues: critical_issues.clone(),
        warnings: warnings
            .iter()
            .chain(analyses.iter().flat_map(|a| &a.warnings))
            .cloned()
            .collect(),
        unknowns: analyses.iter().flat_map(unknowns).collect(),
        schema: SchemaSection {
            status: schema_status,
            critical_issues,
            warnings,
            infos: messages(findings, Severity::Info),
        },
        physics: summary,
        links,
        statics: analyses.as_ref().map(|a| a.statics.clone()),
        workspace: analyses.as_ref().map(|a| a.workspace.clone()),
        stability: analyses.map(|a| a.stability),
        findings: finding_reports,
    }
}

fn finding_report(finding: &Finding, source: &SourceText, locator: &Locator) -> FindingReport {
    let mut report = FindingReport {
        rule: finding.rule.code.to_string(),
        name: finding.rule.name.to_string(),
        severity: finding.severity(),
        message: finding.message.clone(),
        file: None,
        line: None,
        column: None,
        end_line: None,
        end_column: None,
        help: finding.help.clone(),
        expanded_from: Vec::new(),
    };
    let Some(span) = finding.span else {
        return report;
    };
    match locator {
        Locator::Urdf => {
            let start = source.location(span);
            let end = source.line_col(span.end as usize);
            report.file = Some(start.file);
            report.line = Some(start.line);
            report.column = Some(start.column);
            report.end_line = Some(end.0);
            report.end_column = Some(end.1);
        }
        Locator::Xacro(expanded) => {
            if let Some(at) = expanded.locate(span) {
                report.file = Some(at.file);
                report.line = Some(at.line);
                report.column = Some(at.column);
                report.end_line = Some(at.end_line);
                report.end_column = Some(at.end_column);
                report.expanded_from = at.stack;
            }
        }
    }
    report
}
