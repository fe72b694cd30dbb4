//! The JSON report: the [`Report`] serialised, pretty-printed (`<stem>_validation.json`).

use crate::report::Report;

/// One report as a JSON object, with a final newline.
pub fn render_json(report: &Report) -> String {
    // Serialising the report cannot fail: string keys only, and non-finite numbers become null.
    serde_json::to_string_pretty(report).unwrap_or_default() + "\n"
}

/// Several reports as a JSON array, with a final newline.
pub fn render_json_list(reports: &[&Report]) -> String {
    serde_json::to_string_pretty(reports).unwrap_or_default() + "\n"
}
