//! Code actions: each finding's fix as a quick fix (unsafe ones say so and are never preferred), "fix all
//! safe" (`source.fixAll`, the fixes `urdf_validate --fix` applies), and "suppress this finding" (the
//! inline comment). Fixes are byte edits of the files the validation read; they are offered only while
//! those files still hold the text that was validated, so that no edit lands on moved text.

use std::collections::HashMap;
use std::path::Path;

use lsp_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, Diagnostic, NumberOrString, Range, TextEdit,
    Url, WorkspaceEdit,
};
use urdf_validator::diagnostics::fix::Applicability;
use urdf_validator::report::{FileEdit, FindingReport};
use urdf_validator::Validation;

use super::diagnostics::{finding_range, Texts};
use super::documents::Documents;
use super::positions::{changed_part, LineIndex};
use super::xml::Scan;
use crate::fixes;

/// The code actions for `range` of `uri`, from the validation of the document (or xacro tree) holding it.
pub fn actions(
    uri: &Url,
    range: Range,
    only: Option<&[CodeActionKind]>,
    validation: &Validation,
    documents: &Documents,
) -> Vec<CodeActionOrCommand> {
    let wants = |kind: &CodeActionKind| {
        only.is_none_or(|only| only.iter().any(|o| kind.as_str().starts_with(o.as_str())))
    };
    let texts = Texts::of(validation);
    let mut actions: Vec<CodeAction> = Vec::new();
    // Every finding on the lines the cursor or selection touches (as rust-analyzer offers them), those
    // under the cursor first, then the most severe.
    let mut here: Vec<(&FindingReport, Range)> = validation
        .report
        .findings
        .iter()
        .filter(|f| in_file(f, uri))
        .map(|f| (f, finding_range(f, &texts)))
        .filter(|(_, at)| at.start.line <= range.end.line && range.start.line <= at.end.line)
        .collect();
    here.sort_by_key(|(f, at)| {
        let under = at.start <= range.end && range.start <= at.end;
        (std::cmp::Reverse(under), std::cmp::Reverse(f.severity))
    });
    // The edits of the fixes offered so far: a fix whose edits they already hold is that fix again (a
    // xacro macro's literal, once per call), one whose edits overlap them is another fix of the same
    // text (never offered beside the first).
    let mut offered: Vec<&FileEdit> = Vec::new();
    for (finding, _) in here {
        let diagnostic = diagnostic_of(finding, &texts);
        if !wants(&CodeActionKind::QUICKFIX) {
            continue;
        }
        if let Some(fix) = finding.fix.as_ref().filter(|fix| {
            !fix.edits.is_empty()
                && !fix.edits.iter().any(|edit| {
                    offered
                        .iter()
                        .any(|o| o.file == edit.file && o.edit.conflicts_with(&edit.edit))
                })
                && !fix.edits.iter().all(|edit| offered.contains(&edit))
        }) {
            if let Some(action) = fix_action(finding, diagnostic.clone(), &texts, documents) {
                offered.extend(&fix.edits);
                actions.push(action);
            }
        }
        if let Some(action) = suppress_action(uri, finding, diagnostic, documents) {
            if !actions
                .iter()
                .any(|a| a.title == action.title && a.edit == action.edit)
            {
                actions.push(action);
            }
        }
    }
    if wants(&CodeActionKind::SOURCE_FIX_ALL) {
        actions.extend(fix_all(validation, documents));
    }
    actions
        .into_iter()
        .map(CodeActionOrCommand::CodeAction)
        .collect()
}

/// Whether `finding` is in the file at `uri`.
fn in_file(finding: &FindingReport, uri: &Url) -> bool {
    finding
        .file
        .as_deref()
        .and_then(|f| Url::from_file_path(f).ok())
        .is_some_and(|f| f == *uri)
}

/// The diagnostic a finding was published as (what the action resolves), as far as clients match it:
/// code and range.
fn diagnostic_of(finding: &FindingReport, texts: &Texts) -> Diagnostic {
    Diagnostic {
        range: finding_range(finding, texts),
        code: Some(NumberOrString::String(finding.rule.clone())),
        source: Some(super::diagnostics::SOURCE.to_string()),
        message: finding.message.clone(),
        ..Diagnostic::default()
    }
}

/// The quick fix of `finding`'s fix, when it has edits and the files still hold the text validated.
fn fix_action(
    finding: &FindingReport,
    diagnostic: Diagnostic,
    texts: &Texts,
    documents: &Documents,
) -> Option<CodeAction> {
    let fix = finding.fix.as_ref()?;
    if fix.edits.is_empty() {
        return None;
    }
    let mut changes: HashMap<Url, Vec<TextEdit>> = HashMap::new();
    for edit in &fix.edits {
        let (text, index) = texts.get(&edit.file)?;
        if !unchanged(&edit.file, text, documents) {
            return None;
        }
        let range = index.range(text, edit.edit.start, edit.edit.end);
        changes
            .entry(Url::from_file_path(&edit.file).ok()?)
            .or_default()
            .push(TextEdit::new(range, edit.edit.replacement.clone()));
    }
    let safe = fix.applicability == Applicability::Safe;
    let title = if safe {
        format!("Fix {}: {}", finding.rule, fix.description)
    } else {
        format!(
            "Fix {} (unsafe: changes the robot): {}",
            finding.rule, fix.description
        )
    };
    Some(CodeAction {
        title,
        kind: Some(CodeActionKind::QUICKFIX),
        diagnostics: Some(vec![diagnostic]),
        edit: Some(WorkspaceEdit::new(changes)),
        is_preferred: Some(safe),
        ..CodeAction::default()
    })
}

/// "Fix all safe": the safe fixes `--fix` would apply, one edit per file (from the first to the last
/// byte that changes).
fn fix_all(validation: &Validation, documents: &Documents) -> Option<CodeAction> {
    let policy = fixes::Policy {
        unsafe_fixes: false,
        from_overrides: false,
        package_paths: Vec::new(),
    };
    let plan = fixes::plan(&[validation], &policy);
    let mut changes: HashMap<Url, Vec<TextEdit>> = HashMap::new();
    let mut count = 0;
    for file in &plan.files {
        let name = file.path.display().to_string();
        if !unchanged(&name, &file.before, documents) {
            return None;
        }
        let index = LineIndex::new(&file.before);
        let (start, end, replacement) = changed_part(&file.before, &file.after);
        changes
            .entry(Url::from_file_path(&file.path).ok()?)
            .or_default()
            .push(TextEdit::new(
                index.range(&file.before, start, end),
                replacement.to_string(),
            ));
        count += file.fixes;
    }
    (count > 0).then(|| CodeAction {
        title: format!("Fix all safe ({count} fix(es); unsafe ones are left out)"),
        kind: Some(CodeActionKind::SOURCE_FIX_ALL),
        edit: Some(WorkspaceEdit::new(changes)),
        ..CodeAction::default()
    })
}

/// "Suppress this finding": `<!-- urdf-validate: ignore CODE -->` on its own line before the start tag
/// that holds the finding (the comment covers the next start tag), else at the end of the finding's line
/// (a trailing comment covers its line).
fn suppress_action(
    uri: &Url,
    finding: &FindingReport,
    diagnostic: Diagnostic,
    documents: &Documents,
) -> Option<CodeAction> {
    let document = documents.get(uri)?;
    let text = &document.text;
    let index = &document.index;
    let start = index.offset(text, diagnostic.range.start);
    let comment = format!("<!-- urdf-validate: ignore {} -->", finding.rule);
    let scan = Scan::new(text);
    let (at, insert) = match scan.at(start) {
        Some((element, _)) => {
            let tag = scan.elements[element].tag.start;
            let line_start = text[..tag].rfind('\n').map_or(0, |i| i + 1);
            let indent: String = text[line_start..tag]
                .chars()
                .take_while(|c| c.is_whitespace())
                .collect();
            (line_start, format!("{indent}{comment}\n"))
        }
        None => {
            let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
            let line_end = if text[..line_end].ends_with('\r') {
                line_end - 1
            } else {
                line_end
            };
            (line_end, format!(" {comment}"))
        }
    };
    let position = index.position(text, at);
    let changes = HashMap::from([(
        uri.clone(),
        vec![TextEdit::new(Range::new(position, position), insert)],
    )]);
    Some(CodeAction {
        title: format!("Suppress {} here (inline comment)", finding.rule),
        kind: Some(CodeActionKind::QUICKFIX),
        diagnostics: Some(vec![diagnostic]),
        edit: Some(WorkspaceEdit::new(changes)),
        ..CodeAction::default()
    })
}

/// Whether `file` still holds `text`: its open document's text, else the file on disk.
fn unchanged(file: &str, text: &str, documents: &Documents) -> bool {
    match documents.by_path(Path::new(file)) {
        Some(document) => document.text == text,
        None => std::fs::read_to_string(file).is_ok_and(|disk| disk == text),
    }
}
