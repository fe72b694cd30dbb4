//! What every stage reports with: the one rule registry, [`Finding`]s with spans and severities, and the
//! verdict vocabulary ([`Status`], [`Confidence`]). Shared by all stages; it imports none of them.

pub mod finding;
pub mod fix;
pub mod inline;
pub mod rules;
pub mod settings;
pub mod span;
pub mod suggest;
mod verdict;

pub use finding::{Finding, Section, Severity};
pub use settings::Settings;
pub use verdict::{overall_status, Confidence, ConfidenceLevel, Status};
