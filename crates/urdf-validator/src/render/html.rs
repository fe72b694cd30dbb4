//! HTML view of a report.
//!
//! PLACEHOLDER: the real renderer is written on another branch (`helper-html`) and replaces this file at
//! merge. This one only exists so the CLI's `--format html` compiles: a minimal page with the verdict.

use crate::Validation;

/// The report of one validation as a self-contained HTML page.
pub fn render_html(validation: &Validation) -> String {
    let report = &validation.report;
    format!(
        "<!doctype html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\"><title>{name} — urdf_validate</title></head>\n\
         <body><h1>{name}</h1><p>{path}: {status}</p></body>\n</html>\n",
        name = escape(&report.robot_name),
        path = escape(&report.urdf_path),
        status = report.overall_status.label()
    )
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
