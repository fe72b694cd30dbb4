//! SARIF 2.1.0, as GitHub code scanning ingests it: one run listing every rule of the registry, one result
//! per finding located at its file, line and column.
//!
//! Paths below [`FormatOptions::base_dir`] are written relative to it with `uriBaseId` `%SRCROOT%` (the
//! checkout, for code scanning); others as absolute `file://` URIs. A finding without a position is
//! located at the validated file. Inputs that gave no report are tool execution notifications, and make
//! `executionSuccessful` false.

use serde_json::{json, Map, Value};

use crate::diagnostics::finding::Severity;
use crate::diagnostics::fix::Applicability;
use crate::diagnostics::rules::{self, Rule};
use crate::render::location::{file_uri, uri_path, DisplayPath, Place};
use crate::render::{FormatOptions, Unreported};
use crate::report::FixReport;
use crate::Validation;

/// The schema named in `$schema`: SARIF 2.1.0 with errata 01, as published by OASIS.
pub const SARIF_SCHEMA: &str =
    "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json";

/// The SARIF `level` of a severity: error for CRITICAL and FAIL, warning for WARN, note for INFO.
pub fn level(severity: Severity) -> &'static str {
    match severity {
        Severity::Critical | Severity::Fail => "error",
        Severity::Warn => "warning",
        Severity::Info => "note",
    }
}

/// The SARIF log of one run over every validation, pretty-printed with a final newline.
pub fn render_sarif(
    validations: &[&Validation],
    unreported: &[Unreported],
    options: &FormatOptions,
) -> String {
    let log = sarif_log(validations, unreported, options);
    serde_json::to_string_pretty(&log).unwrap_or_default() + "\n"
}

fn sarif_log(
    validations: &[&Validation],
    unreported: &[Unreported],
    options: &FormatOptions,
) -> Value {
    let base = options.base_dir.as_deref();
    let mut driver = Map::new();
    driver.insert("name".into(), json!("urdf_validate"));
    driver.insert("version".into(), json!(crate::report::VERSION));
    driver.insert("semanticVersion".into(), json!(crate::report::VERSION));
    if let Some(url) = &options.rules_url {
        driver.insert("informationUri".into(), json!(url));
    }
    driver.insert(
        "rules".into(),
        Value::Array(
            rules::ALL
                .iter()
                .map(|rule| rule_descriptor(rule, options.rules_url.as_deref()))
                .collect(),
        ),
    );

    let results: Vec<Value> = validations
        .iter()
        .flat_map(|validation| {
            let report = &validation.report;
            report.findings.iter().map(move |finding| {
                let index = rules::ALL.iter().position(|r| r.code == finding.rule);
                let mut text = finding.message.clone();
                if let Some(help) = &finding.help {
                    text.push_str("\nhelp: ");
                    text.push_str(help);
                }
                for note in &finding.expanded_from {
                    text.push_str("\nnote: ");
                    text.push_str(note);
                }
                let place = Place::of(finding, &report.urdf_path);
                let mut result = Map::new();
                result.insert("ruleId".into(), json!(finding.rule));
                if let Some(index) = index {
                    result.insert("ruleIndex".into(), json!(index));
                }
                result.insert("level".into(), json!(level(finding.severity)));
                result.insert("message".into(), json!({ "text": text }));
                result.insert("locations".into(), json!([location(&place, base)]));
                if let Some(fix) = finding.fix.as_ref().filter(|f| !f.edits.is_empty()) {
                    result.insert("fixes".into(), json!([sarif_fix(fix, base)]));
                }
                if report.baseline.is_some() {
                    // Findings the baseline holds are not reported at all (they are not failures).
                    result.insert("baselineState".into(), json!("new"));
                }
                result.insert(
                    "properties".into(),
                    json!({
                        "severity": finding.severity.label(),
                        "section": finding.section.as_str(),
                        "robot": report.robot_name,
                        "validatedFile": DisplayPath::new(&report.urdf_path, base).as_str(),
                    }),
                );
                Value::Object(result)
            })
        })
        .collect();

    let notifications: Vec<Value> = unreported
        .iter()
        .map(|input| {
            let mut notification = json!({
                "level": "error",
                "message": { "text": input.error },
            });
            if !input.file.is_empty() {
                notification["locations"] = json!([location(
                    &Place {
                        file: &input.file,
                        region: None
                    },
                    base
                )]);
            }
            notification
        })
        .collect();

    let mut run = Map::new();
    run.insert("tool".into(), json!({ "driver": Value::Object(driver) }));
    if let Some(root) = base.filter(|b| b.is_absolute()) {
        let mut dir = file_uri(&root.to_string_lossy().replace('\\', "/"));
        if !dir.ends_with('/') {
            dir.push('/');
        }
        run.insert(
            "originalUriBaseIds".into(),
            json!({ "%SRCROOT%": { "uri": dir } }),
        );
    }
    run.insert(
        "invocations".into(),
        json!([{
            "executionSuccessful": unreported.is_empty(),
            "toolExecutionNotifications": notifications,
        }]),
    );
    run.insert("columnKind".into(), json!("unicodeCodePoints"));
    run.insert("results".into(), Value::Array(results));

    json!({
        "$schema": SARIF_SCHEMA,
        "version": "2.1.0",
        "runs": [Value::Object(run)],
    })
}

fn rule_descriptor(rule: &Rule, rules_url: Option<&str>) -> Value {
    let mut descriptor = Map::new();
    descriptor.insert("id".into(), json!(rule.code));
    descriptor.insert("name".into(), json!(rule.name));
    descriptor.insert("shortDescription".into(), json!({ "text": rule.what }));
    descriptor.insert(
        "fullDescription".into(),
        json!({ "text": format!("{} {}", rule.what, rule.why) }),
    );
    descriptor.insert(
        "help".into(),
        json!({
            "text": rule.fix,
            "markdown": format!(
                "**{} `{}`** ({})\n\n**What:** {}\n\n**Why it matters:** {}\n\n**How to fix:** {}",
                rule.code, rule.name, rule.severity.label(), rule.what, rule.why, rule.fix
            ),
        }),
    );
    if let Some(url) = rules_url {
        descriptor.insert(
            "helpUri".into(),
            json!(format!("{url}{}.html", rule.page())),
        );
    }
    descriptor.insert(
        "defaultConfiguration".into(),
        json!({ "level": level(rule.severity) }),
    );
    descriptor.insert(
        "properties".into(),
        json!({
            "tags": ["urdf", rule.section.as_str()],
            "severity": rule.severity.label(),
        }),
    );
    Value::Object(descriptor)
}

/// A SARIF `fix`: the edits grouped by file, each a byte region replaced by its text.
fn sarif_fix(fix: &FixReport, base: Option<&std::path::Path>) -> Value {
    let mut changes: Vec<(&str, Vec<Value>)> = Vec::new();
    for edit in &fix.edits {
        let replacement = json!({
            "deletedRegion": {
                "byteOffset": edit.edit.start,
                "byteLength": edit.edit.end - edit.edit.start,
            },
            "insertedContent": { "text": edit.edit.replacement },
        });
        match changes.iter_mut().find(|(file, _)| *file == edit.file) {
            Some((_, replacements)) => replacements.push(replacement),
            None => changes.push((&edit.file, vec![replacement])),
        }
    }
    let changes: Vec<Value> = changes
        .into_iter()
        .map(|(file, replacements)| {
            json!({ "artifactLocation": artifact_location(file, base), "replacements": replacements })
        })
        .collect();
    json!({
        "description": { "text": format!("{} ({})", fix.description, match fix.applicability {
            Applicability::Safe => "safe",
            Applicability::Unsafe => "unsafe",
        }) },
        "artifactChanges": changes,
    })
}

/// A file as SARIF names it: relative to `%SRCROOT%` when under the base folder, else a `file://` URI.
fn artifact_location(file: &str, base: Option<&std::path::Path>) -> Value {
    match DisplayPath::new(file, base) {
        DisplayPath::Relative(path) => json!({ "uri": uri_path(&path), "uriBaseId": "%SRCROOT%" }),
        DisplayPath::Absolute(path) => json!({ "uri": file_uri(&path) }),
    }
}

fn location(place: &Place<'_>, base: Option<&std::path::Path>) -> Value {
    let artifact = artifact_location(place.file, base);
    // GitHub code scanning wants a start line: a finding about the whole file points at its first line.
    let region = match place.region {
        Some((line, column, end_line, end_column)) => json!({
            "startLine": line,
            "startColumn": column,
            "endLine": end_line,
            "endColumn": end_column,
        }),
        None => json!({ "startLine": 1 }),
    };
    json!({ "physicalLocation": { "artifactLocation": artifact, "region": region } })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_follow_severities() {
        assert_eq!(level(Severity::Critical), "error");
        assert_eq!(level(Severity::Fail), "error");
        assert_eq!(level(Severity::Warn), "warning");
        assert_eq!(level(Severity::Info), "note");
    }

    /// The anchors GitHub and mdBook give the headings of the one-page reference (`--list-rules-markdown`) (`## U205 `inertia-not-positive-definite``):
    /// lowercase, backticks dropped, spaces as hyphens.
    #[test]
    fn anchors_match_the_rules_reference_headings() {
        let markdown = rules::reference_markdown();
        for rule in rules::ALL {
            let heading = format!("\n## {} `{}`\n", rule.code, rule.name);
            assert!(
                markdown.contains(&heading),
                "{heading} not in the rules reference"
            );
            let slug: String = heading
                .trim()
                .trim_start_matches("## ")
                .to_lowercase()
                .chars()
                .filter(|c| c.is_alphanumeric() || *c == '-' || *c == ' ')
                .map(|c| if c == ' ' { '-' } else { c })
                .collect();
            assert_eq!(rule.anchor(), slug);
        }
    }
}
