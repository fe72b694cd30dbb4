//! Findings: what a rule says about one place in the file.

use crate::diagnostics::fix::Fix;
use crate::diagnostics::rules::Rule;
use crate::diagnostics::span::Span;

/// How serious a finding is. Ordered: `Info < Warn < Fail < Critical`; the exit code follows the worst
/// (see [`crate::diagnostics::overall_status`] and [`crate::diagnostics::Status::exit_code`]).
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    PartialOrd,
    Ord,
    Hash,
    serde::Serialize,
    serde::Deserialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "UPPERCASE")]
pub enum Severity {
    /// Worth knowing; never changes the status.
    Info,
    /// Loads, but simulators or users will be surprised.
    Warn,
    /// A physics verdict failed: a joint too weak to hold its pose, a robot that tips over, a task out of
    /// reach, or a check the user asked for that could not run.
    Fail,
    /// Tools refuse the file or the model is meaningless.
    Critical,
}

impl Severity {
    /// The label used in terminal output and JSON.
    pub fn label(self) -> &'static str {
        match self {
            Severity::Info => "INFO",
            Severity::Warn => "WARN",
            Severity::Fail => "FAIL",
            Severity::Critical => "CRITICAL",
        }
    }
}

/// The part of the report a finding belongs to: the report section whose verdict it explains, one key of
/// the report with a `status` (self-collision and `--task` are verdicts of `workspace`, `--payload-mass`
/// of `statics`).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum Section {
    /// Structure, syntax, inertial data, meshes: `[SCHEMA]`.
    Schema,
    /// Mass, centre of mass and gravity torques: `[STATICS]`.
    Statics,
    /// Support polygon and tipping: `[STABILITY]`.
    Stability,
    /// Reach of the arms, their self-collision, the `--task` height, orientation and the COM during the
    /// reach: `[WORKSPACE]`.
    Workspace,
    /// Mirrored left/right chains that differ.
    Symmetry,
    /// The simulator cross-check (`--deep`).
    Deep,
}

impl Section {
    /// The JSON value (`statics`).
    pub fn as_str(self) -> &'static str {
        match self {
            Section::Schema => "schema",
            Section::Statics => "statics",
            Section::Stability => "stability",
            Section::Workspace => "workspace",
            Section::Symmetry => "symmetry",
            Section::Deep => "deep",
        }
    }
}

/// One diagnostic produced by a rule.
#[derive(Clone, Debug)]
pub struct Finding {
    /// The rule that fired.
    pub rule: &'static Rule,
    /// The report section it belongs to (the rule's, unless the finding says otherwise).
    pub section: Section,
    /// One sentence naming the element and the problem.
    pub message: String,
    /// Where in the source it is, when it has a place.
    pub span: Option<Span>,
    /// What to do about this occurrence, when more specific than the rule's doc.
    pub help: Option<String>,
    /// The severity when the settings override the rule's default (`[severity]` in the configuration).
    pub severity_override: Option<Severity>,
    /// The edit that resolves it, when it has one right answer (`--fix`).
    pub fix: Option<Fix>,
}

impl Finding {
    /// A finding at `span` with the rule's default severity.
    pub fn new(
        rule: &'static Rule,
        span: impl Into<Option<Span>>,
        message: impl Into<String>,
    ) -> Self {
        Finding {
            rule,
            section: rule.section,
            message: message.into(),
            span: span.into(),
            help: None,
            severity_override: None,
            fix: None,
        }
    }

    /// Attach the edit that resolves it.
    pub fn with_fix(mut self, fix: Fix) -> Self {
        self.fix = Some(fix);
        self
    }

    /// Attach the edit that resolves it, when there is one.
    pub fn with_fix_option(mut self, fix: Option<Fix>) -> Self {
        self.fix = fix;
        self
    }

    /// Attach a specific hint.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// File the finding under another section than its rule's (a requested check that could not run).
    pub fn in_section(mut self, section: Section) -> Self {
        self.section = section;
        self
    }

    /// The severity: the rule's default unless the settings override it.
    pub fn severity(&self) -> Severity {
        self.severity_override.unwrap_or(self.rule.severity)
    }
}
