//! The verdict vocabulary every stage shares: a check's [`Status`] and how far a number can be trusted
//! ([`Confidence`], [`ConfidenceLevel`]).

use schemars::JsonSchema;
use serde::Serialize;

use crate::diagnostics::finding::{Finding, Severity};
use crate::diagnostics::rules;

/// The overall verdict of a report, from its findings alone: FAIL with any CRITICAL or FAIL finding, except
/// that when the only such findings say a requested check could not run (U790) it is UNKNOWN; WARN with
/// any WARN finding; else PASS. The exit code is [`Status::exit_code`] of this.
pub fn overall_status<'a>(findings: impl IntoIterator<Item = &'a Finding>) -> Status {
    let mut status = Status::Pass;
    for finding in findings {
        let this = match finding.severity() {
            Severity::Info => Status::Pass,
            Severity::Warn => Status::Warn,
            Severity::Fail if finding.rule == &rules::REQUESTED_CHECK_NOT_RUN => Status::Unknown,
            Severity::Fail | Severity::Critical => Status::Fail,
        };
        status = status.worst(this);
    }
    status
}

/// A check's verdict. The overall one follows the findings ([`overall_status`]).
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

impl Confidence {
    /// The label used in text and HTML output (as in JSON: `exact`, `estimated`, ...).
    pub fn label(self) -> &'static str {
        match self {
            Confidence::Exact => "exact",
            Confidence::Estimated => "estimated",
            Confidence::Guessed => "guessed",
            Confidence::Missing => "missing",
            Confidence::Simulated => "simulated",
        }
    }
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
