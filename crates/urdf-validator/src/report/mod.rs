//! The report: one serde type tree, the single source of truth for the JSON file and every renderer.
//!
//! Field names follow the Python tool's JSON so existing CI scripts keep working. Sections that are not
//! implemented yet (statics, stability, workspace) are absent, never filled with placeholders.

pub mod baseline;
mod build;
pub mod diff;
pub mod filter;
pub mod schema_doc;
mod timestamp;

pub use crate::timings::Timings;
pub use build::{build, Outcome};
pub use filter::SuppressedFinding;

pub use crate::analysis::deep::{DeepJoint, DeepSection, DropTest, SaggingJoint, SimulatorChange};
pub use crate::analysis::mass::{LinkReport, PhysicsSummary};
pub use crate::analysis::stability::{ContactPoint, RaisedContact, StabilitySection};
pub use crate::analysis::statics::{JointStatics, StaticsSection};
pub use crate::analysis::workspace::{body_joints_held, ArmWorkspace, WorkspaceSection};
pub use crate::diagnostics::{Confidence, ConfidenceLevel, Status};

use schemars::JsonSchema;
use serde::Serialize;

use crate::diagnostics::fix::{Applicability, TextEdit};
use crate::diagnostics::{Section, Severity};

/// This library's version, written into every report.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The validation report of one robot: `<stem>_validation.json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct Report {
    /// The validated file, as given on the command line.
    pub urdf_path: String,
    /// `name` of `<robot>` (empty when absent).
    pub robot_name: String,
    /// When validation ran, ISO 8601 UTC.
    pub timestamp: String,
    /// Version of urdf_validate that wrote this report.
    pub validator_version: String,
    /// The verdict of the findings: FAIL with any CRITICAL or FAIL finding (UNKNOWN when those only say
    /// that a requested check could not run), WARN with any WARN finding, else PASS. The exit code follows it.
    pub overall_status: Status,
    /// The robot category used for the capability profile (declared with `--robot-type`, else detected).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robot_type: Option<crate::analysis::classify::RobotType>,
    /// `exact` when declared, `estimated` when detected.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robot_type_confidence: Option<Confidence>,
    /// What the structure shows (also when a type was declared, as a cross-check), and why.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robot_type_detected: Option<crate::analysis::classify::RobotType>,
    /// The evidence behind `robot_type_detected`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robot_type_evidence: Option<String>,
    /// Quality of the physics data.
    pub confidence_level: ConfidenceLevel,
    /// Messages of CRITICAL and FAIL findings, every section.
    pub critical_issues: Vec<String>,
    /// Messages of WARN findings, every section.
    pub warnings: Vec<String>,
    /// What could not be assessed.
    pub unknowns: Vec<String>,
    /// Structural checks.
    pub schema: SchemaSection,
    /// Counts behind the `[PHYSICS]` line.
    pub physics: PhysicsSummary,
    /// Per-link mass data, in document order.
    pub links: Vec<LinkReport>,
    /// Mass, centre of mass and gravity torques (absent when the file is not a robot).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub statics: Option<StaticsSection>,
    /// Support polygon and tipping (absent when the file is not a robot).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stability: Option<StabilitySection>,
    /// Reach, task, orientation and self-collision of every arm (absent when the file is not a robot).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub workspace: Option<WorkspaceSection>,
    /// Mirrored left/right pairs (sibling chains with mirrored origins) and what differs between them
    /// (absent when the file is not a robot).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub symmetry: Option<crate::analysis::symmetry::SymmetrySection>,
    /// The MuJoCo pass: what MuJoCo changed in the file, its gravity forces and centre of mass against
    /// statics, and the 2-second drop test (present with `--deep`, or when the stability margin is
    /// negative).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub deep: Option<crate::analysis::deep::DeepSection>,
    /// Every finding with its rule and source position (suppressed findings are not among them).
    pub findings: Vec<FindingReport>,
    /// Findings suppressed by the configuration (`select`, `ignore`, `per-file-ignores`) or an inline
    /// `<!-- urdf-validate: ignore ... -->` comment, each saying what suppressed it. They do not count
    /// towards any status or the exit code. Present only with `--show-suppressed`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub suppressed: Vec<SuppressedFinding>,
    /// What `--baseline` hid: the findings it matched (not counted), those it lacks (`new`, reported above)
    /// and its entries nothing matches any more (`stale`). Present only with `--baseline`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub baseline: Option<baseline::BaselineSummary>,
    /// `--override`s the robot was evaluated with (the file untouched), each with the value the file
    /// declares. Present only with `--override`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub overrides: Vec<AppliedOverride>,
    /// Milliseconds per pipeline phase (`--timings` only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub timings_ms: Option<Timings>,
}

/// The `schema` section.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct SchemaSection {
    /// FAIL with any CRITICAL schema finding, WARN with any WARN schema finding, else PASS.
    pub status: Status,
    /// Messages of CRITICAL schema findings.
    pub critical_issues: Vec<String>,
    /// Messages of WARN schema findings.
    pub warnings: Vec<String>,
    /// Messages of INFO schema findings.
    pub infos: Vec<String>,
}

/// One finding, positioned.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct FindingReport {
    /// Rule code, e.g. `U205`.
    pub rule: String,
    /// Rule name, e.g. `inertia-not-positive-definite`.
    pub name: String,
    /// CRITICAL, FAIL, WARN or INFO.
    pub severity: Severity,
    /// The report section whose verdict it explains, a key of the report with a `status`: schema, statics,
    /// stability, workspace, symmetry or deep.
    pub section: Section,
    /// What is wrong, naming the element.
    pub message: String,
    /// File holding the problem (null when it has no place).
    pub file: Option<String>,
    /// 1-based line.
    pub line: Option<u32>,
    /// 1-based column.
    pub column: Option<u32>,
    /// 1-based line where the flagged text ends.
    pub end_line: Option<u32>,
    /// 1-based column just past the flagged text.
    pub end_column: Option<u32>,
    /// What to do about it.
    pub help: Option<String>,
    /// Path of the element the finding points at in the (expanded) URDF, such as
    /// `robot[@name='pr2']/joint[@name='r_elbow_flex_joint']/limit` (null when it points at none): with the
    /// rule, severity and message, what identifies the finding in a baseline whatever its line.
    pub element: Option<String>,
    /// For xacro input: the macro calls and includes that produced the flagged text, innermost first
    /// (`in macro 'wheel' called at robot.urdf.xacro:40:3`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub expanded_from: Vec<String>,
    /// The edit that resolves it (`urdf_validate --fix`), when it has one right answer.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fix: Option<FixReport>,
}

/// A finding's fix, as edits of the files the user edits.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct FixReport {
    /// `safe` (applied by `--fix`: nothing a simulator computes changes) or `unsafe` (also needs
    /// `--unsafe-fixes`: mass, inertia, limits, scale or effort change).
    pub applicability: Applicability,
    /// What applying it does.
    pub description: String,
    /// The edits, all applied or none (empty when the fix cannot be made in a file: see `not_applicable`).
    pub edits: Vec<FileEdit>,
    /// Why the fix cannot be applied here (a xacro value computed from a property, expression or macro
    /// argument: where that is), when it cannot.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub not_applicable: Option<String>,
}

/// One edit of one file: replace bytes `start..end` with `replacement`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, JsonSchema)]
pub struct FileEdit {
    /// The file, as the user named it (a xacro source for xacro input).
    pub file: String,
    /// 1-based line of `start`.
    pub line: u32,
    /// 1-based column of `start`, in characters.
    pub column: u32,
    /// 1-based line of `end`.
    pub end_line: u32,
    /// 1-based column of `end`, in characters.
    pub end_column: u32,
    /// The byte edit.
    #[serde(flatten)]
    pub edit: TextEdit,
}

impl FindingReport {
    /// Point the finding at `at`.
    fn place(&mut self, at: crate::input::xacro::SourceLocation) {
        self.file = Some(at.file);
        self.line = Some(at.line);
        self.column = Some(at.column);
        self.end_line = Some(at.end_line);
        self.end_column = Some(at.end_column);
        self.expanded_from = at.stack;
    }
}

/// The JSON Schema of [`Report`], pretty-printed.
pub fn json_schema() -> String {
    let schema = schemars::schema_for!(Report);
    serde_json::to_string_pretty(&schema).unwrap_or_default() + "\n"
}

/// An `--override` as applied, in `overrides`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct AppliedOverride {
    /// The key (`joint.shoulder.effort`).
    pub key: String,
    /// The value used.
    pub value: String,
    /// The value the file declares (null when it declares none).
    pub was: Option<String>,
    /// The edit that writes the value into the file (`--fix --from-overrides`); absent when the file has no
    /// attribute to hold it (no `<limit>`, `<mass>` or `<origin>` element: add it by hand) and for
    /// `payload.mass`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fix: Option<FixReport>,
}
