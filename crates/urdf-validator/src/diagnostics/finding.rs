//! Findings: what a rule says about one place in the file.

use crate::diagnostics::rules::Rule;
use crate::input::source::Span;

/// How serious a finding is. Ordered: `Info < Warn < Critical`.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, schemars::JsonSchema,
)]
#[serde(rename_all = "UPPERCASE")]
pub enum Severity {
    /// Worth knowing; never changes the status.
    Info,
    /// Loads, but simulators or users will be surprised.
    Warn,
    /// Tools refuse the file or the model is meaningless.
    Critical,
}

impl Severity {
    /// The label used in terminal output and JSON.
    pub fn label(self) -> &'static str {
        match self {
            Severity::Info => "INFO",
            Severity::Warn => "WARN",
            Severity::Critical => "CRITICAL",
        }
    }
}

/// One diagnostic produced by a rule.
#[derive(Clone, Debug)]
pub struct Finding {
    /// The rule that fired.
    pub rule: &'static Rule,
    /// One sentence naming the element and the problem.
    pub message: String,
    /// Where in the source it is, when it has a place.
    pub span: Option<Span>,
    /// What to do about this occurrence, when more specific than the rule's doc.
    pub help: Option<String>,
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
            message: message.into(),
            span: span.into(),
            help: None,
        }
    }

    /// Attach a specific hint.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// The severity (the rule's default).
    pub fn severity(&self) -> Severity {
        self.rule.severity
    }
}
