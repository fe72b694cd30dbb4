//! What every stage reports with: the one rule registry, [`Finding`]s with spans and severities, and the
//! verdict vocabulary ([`Status`], [`Confidence`]). Shared by all stages; it imports none of them.

pub mod finding;
pub mod rules;
pub mod suggest;
mod verdict;

pub use finding::{Finding, Section, Severity};
pub use verdict::{overall_status, Confidence, ConfidenceLevel, Status};
