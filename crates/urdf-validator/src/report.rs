//! The report: one serde type tree, the single source of truth for the JSON file and every renderer.
//!
//! Field names follow the Python tool's JSON so existing CI scripts keep working. Sections that are not
//! implemented yet (statics, stability, workspace) are absent, never filled with placeholders.

use schemars::JsonSchema;
use serde::Serialize;

use crate::finding::Severity;

/// A check's verdict. Overall = worst of the applicable ones (N/A is excluded).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, JsonSchema)]
pub enum Status {
    /// The check does not apply to this robot category.
    #[serde(rename = "N/A")]
    NotApplicable,
    /// Everything checked is fine.
    #[serde(rename = "PASS")]
    Pass,
    /// Usable, but something deserves attention.
    #[serde(rename = "WARN")]
    Warn,
    /// The check applies but could not run.
    #[serde(rename = "UNKNOWN")]
    Unknown,
    /// Something is wrong.
    #[serde(rename = "FAIL")]
    Fail,
}

impl Status {
    /// The label used in text output.
    pub fn label(self) -> &'static str {
        match self {
            Status::NotApplicable => "N/A",
            Status::Pass => "PASS",
            Status::Warn => "WARN",
            Status::Unknown => "UNKNOWN",
            Status::Fail => "FAIL",
        }
    }

    /// The process exit code for this overall status: 0 PASS (and N/A), 1 WARN, 2 FAIL or UNKNOWN.
    pub fn exit_code(self) -> i32 {
        match self {
            Status::NotApplicable | Status::Pass => 0,
            Status::Warn => 1,
            Status::Unknown | Status::Fail => 2,
        }
    }

    /// The worse of two statuses for the overall verdict (UNKNOWN ranks with FAIL for exit codes, below it here).
    pub fn worst(self, other: Status) -> Status {
        self.max(other)
    }
}

/// How far a number can be trusted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Confidence {
    /// Read from the file or declared by the user.
    Exact,
    /// Derived analytically from declared data, or a heuristic without a declaration to check it.
    Estimated,
    /// From geometry when data is missing.
    Guessed,
    /// No data.
    Missing,
    /// Cross-checked in a simulator.
    Simulated,
}

/// Overall quality of the physics data.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, JsonSchema)]
pub enum ConfidenceLevel {
    /// Every link that should have mass declares mass and inertia.
    #[serde(rename = "HIGH")]
    High,
    /// At least half of those links declare a mass.
    #[serde(rename = "MEDIUM")]
    Medium,
    /// Sparse physics data.
    #[serde(rename = "LOW")]
    Low,
}

impl ConfidenceLevel {
    /// The label used in text output.
    pub fn label(self) -> &'static str {
        match self {
            ConfidenceLevel::High => "HIGH",
            ConfidenceLevel::Medium => "MEDIUM",
            ConfidenceLevel::Low => "LOW",
        }
    }
}

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
    /// Worst applicable section status.
    pub overall_status: Status,
    /// Quality of the physics data.
    pub confidence_level: ConfidenceLevel,
    /// Messages of CRITICAL findings.
    pub critical_issues: Vec<String>,
    /// Messages of WARN findings.
    pub warnings: Vec<String>,
    /// What could not be assessed.
    pub unknowns: Vec<String>,
    /// Structural checks.
    pub schema: SchemaSection,
    /// Counts behind the `[PHYSICS]` line.
    pub physics: PhysicsSummary,
    /// Per-link mass data, in document order.
    pub links: Vec<LinkReport>,
    /// Every finding with its rule and source position.
    pub findings: Vec<FindingReport>,
}

/// The `schema` section.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct SchemaSection {
    /// FAIL with any CRITICAL finding, WARN with any WARN finding, else PASS.
    pub status: Status,
    /// Messages of CRITICAL findings.
    pub critical_issues: Vec<String>,
    /// Messages of WARN findings.
    pub warnings: Vec<String>,
    /// Messages of INFO findings.
    pub infos: Vec<String>,
}

/// Mass-data counts over the links (frames are counted apart, not as missing mass).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, JsonSchema)]
pub struct PhysicsSummary {
    /// All links.
    pub links: usize,
    /// Pure frames: no inertial, no geometry, fixed to their parent (or the root).
    pub frames: usize,
    /// Non-frame links declaring a finite mass.
    pub mass_exact: usize,
    /// Non-frame links without a usable mass.
    pub mass_missing: usize,
    /// Non-frame links declaring a finite inertia tensor.
    pub inertia_exact: usize,
    /// Non-frame links without a usable inertia tensor.
    pub inertia_missing: usize,
}

/// One entry of `links`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct LinkReport {
    /// Link name.
    pub name: String,
    /// True for a pure frame link.
    pub frame: bool,
    /// Declared mass in kg.
    pub mass: Option<f64>,
    /// `exact` when declared, else `missing`.
    pub mass_confidence: Confidence,
    /// Row-major 3×3 inertia tensor in kg·m², about the inertial frame.
    pub inertia_tensor: Option<[f64; 9]>,
    /// `exact` when declared, else `missing`.
    pub inertia_confidence: Confidence,
    /// Centre of mass in the link frame (the `<inertial><origin xyz>`, zero when omitted), metres.
    pub com_offset: Option<[f64; 3]>,
    /// `exact` when the link has an inertial, else `missing`.
    pub com_confidence: Confidence,
}

/// One finding, positioned.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct FindingReport {
    /// Rule code, e.g. `U205`.
    pub rule: String,
    /// Rule name, e.g. `inertia-not-positive-definite`.
    pub name: String,
    /// CRITICAL, WARN or INFO.
    pub severity: Severity,
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
}

/// The JSON Schema of [`Report`], pretty-printed.
pub fn json_schema() -> String {
    let schema = schemars::schema_for!(Report);
    serde_json::to_string_pretty(&schema).unwrap_or_default() + "\n"
}
