//! Views of a [`crate::report::Report`]: each renderer reads the report (and, for snippets, the sources of
//! its [`crate::Validation`]) and computes nothing of its own.
//!
//! | format | module | for |
//! |---|---|---|
//! | text | [`text`] | people at a terminal |
//! | json | [`json`] | the report file, scripts |
//! | sarif | [`sarif`] | code scanning (GitHub, GitLab, IDEs): SARIF 2.1.0 |
//! | junit | [`junit`] | CI test reports: JUnit XML, one test case per check |
//! | github | [`github`] | GitHub Actions: workflow-command annotations and the step summary |
//! | html | [`html`] | a page to open in a browser |
//! | collection | [`collection`], [`html::render_collection_html`] | a batch's summary: `index.json`, `index.md`, `index.html` |
//! | 3-D view | [`view`] | the robot drawn, its pose's statics and stability (`urdf_validate view`, the HTML report) |
//!
//! [`diff`] renders what changed between two reports (`urdf_validate diff`) as text or Markdown.

pub mod collection;
pub mod diff;
pub mod github;
pub mod html;
pub mod json;
pub mod junit;
mod location;
pub mod sarif;
pub mod text;
pub mod view;

pub use collection::{render_collection_json, render_collection_markdown, Collection};
pub use diff::{render_diff_markdown, render_diff_text};
pub use github::{render_github, render_step_summary};
pub use html::{render_collection_html, render_html};
pub use json::{render_json, render_json_list};
pub use junit::render_junit;
pub use sarif::render_sarif;
pub use text::{render_text, TextOptions};

use std::path::PathBuf;

/// What the machine formats (SARIF, JUnit, GitHub) need besides the reports.
#[derive(Clone, Debug, Default)]
pub struct FormatOptions {
    /// The directory paths are made relative to (the working directory): SARIF's `%SRCROOT%`, the
    /// `file=` of GitHub annotations. Paths outside it stay absolute.
    pub base_dir: Option<PathBuf>,
    /// Address of the book's rules index, ending in `/` (`rules::index_url()`): SARIF `informationUri`
    /// points at it and each rule's `helpUri` at its page there (`{rules_url}u205.html`). `None`: left out.
    pub rules_url: Option<String>,
}

/// An input that gave no report (unreadable, not XML, did not finish in time): the formats that account
/// for every input (SARIF, JUnit, GitHub) list it as an error.
#[derive(Clone, Debug)]
pub struct Unreported {
    /// The input, as given (empty when the error names no file, such as a folder that cannot be read).
    pub file: String,
    /// Why there is no report (one line).
    pub error: String,
}
