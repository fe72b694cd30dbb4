//! Fixes on real files: every fix of every URDF of the example-robot-data corpus and the reference robots,
//! applied to the text in memory (safe and unsafe), gives a file that loads, differs only by the edits, and
//! in which no finding of the kinds fixed has a fix left to apply (idempotent; effort fixes computed in the
//! same pass as an inertia fix that moved a centre of mass take a second pass, which must settle).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::collections::BTreeSet;
use std::path::Path;

use common::{corpus, shared_robots, urdfs_below};
use urdf_validator::diagnostics::fix::{apply, TextEdit};
use urdf_validator::report::Report;
use urdf_validator::{validate, validate_text, Options};

fn options() -> Options {
    let mut options = Options::default();
    options.workspace.samples = 200;
    options
}

/// The rules whose findings in `report` have edits of `file`, and those edits (each once).
fn fixes_of(report: &Report, file: &Path) -> (BTreeSet<String>, Vec<TextEdit>) {
    let mut rules = BTreeSet::new();
    let mut edits: Vec<TextEdit> = Vec::new();
    for finding in &report.findings {
        let Some(fix) = &finding.fix else { continue };
        if fix.edits.is_empty() {
            continue;
        }
        assert!(
            fix.edits.iter().all(|e| Path::new(&e.file) == file),
            "{}: a URDF's fix edits only the URDF: {:?}",
            file.display(),
            fix.edits
        );
        rules.insert(finding.rule.clone());
        for edit in &fix.edits {
            if !edits.contains(&edit.edit) {
                edits.push(edit.edit.clone());
            }
        }
    }
    (rules, edits)
}

/// Fix `path` in memory; the number of edits applied.
fn fix_round_trip(path: &Path) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    let Ok(validation) = validate(path, &options()) else {
        return 0; // Unreadable files have no findings to fix.
    };
    let (rules, edits) = fixes_of(&validation.report, path);
    if edits.is_empty() {
        return 0;
    }
    let (fixed, dropped) = apply(&text, &edits);
    assert!(
        dropped.is_empty(),
        "{}: edits overlap: {dropped:?}",
        path.display()
    );
    // Only the edited spans changed: the text outside them is the same.
    let mut sorted = edits.clone();
    sorted.sort_by_key(|e| e.start);
    let mut at = 0;
    let mut rebuilt = String::new();
    for edit in &sorted {
        rebuilt.push_str(&text[at..edit.start]);
        rebuilt.push_str(&edit.replacement);
        at = edit.end;
    }
    rebuilt.push_str(&text[at..]);
    assert_eq!(rebuilt, fixed);
    let again = validate_text(fixed.clone(), path, &options())
        .unwrap_or_else(|e| panic!("{}: the fixed text does not load: {e}", path.display()));
    let (left, left_edits) = fixes_of(&again.report, path);
    let still: Vec<&String> = left.intersection(&rules).collect();
    // An inertia fix moves a link's centre of mass to its geometry's, so the gravity torques the effort
    // fixes of the same pass were computed from change: those take a second pass, which must settle.
    let inertia_fixed = rules.iter().any(|r| INERTIA_FIXES.contains(&r.as_str()));
    let only_efforts = still.iter().all(|r| EFFORT_FIXES.contains(&r.as_str()));
    if inertia_fixed && only_efforts && !still.is_empty() {
        let (second, dropped) = apply(&fixed, &left_edits);
        assert!(dropped.is_empty(), "{}: {dropped:?}", path.display());
        let third = validate_text(second, path, &options()).unwrap();
        let (left, _) = fixes_of(&third.report, path);
        let still: Vec<&String> = left.intersection(&rules).collect();
        assert!(
            still.is_empty(),
            "{}: after two passes, {still:?} still have fixes to apply",
            path.display()
        );
        return edits.len();
    }
    assert!(
        still.is_empty(),
        "{}: after the fixes, {still:?} still have fixes to apply",
        path.display()
    );
    edits.len()
}

/// Fixes that rewrite a link's inertia and centre of mass from its geometry.
const INERTIA_FIXES: &[&str] = &["U201", "U204", "U205", "U206", "U208", "U209"];
/// Fixes computed from the gravity torques.
const EFFORT_FIXES: &[&str] = &["U701", "U702"];

#[test]
fn every_corpus_and_reference_urdf_fixes_cleanly_and_idempotently() {
    let mut files = Vec::new();
    if let Some(dir) = corpus() {
        files.extend(urdfs_below(&dir));
    }
    if let Some(dir) = shared_robots() {
        files.extend(urdfs_below(&dir));
    }
    if files.is_empty() {
        return; // Said by corpus() and shared_robots() (a failure under CI).
    }
    let fixed_files = files.iter().filter(|f| fix_round_trip(f) > 0).count();
    // Baxter, Kinova, PR2, TIAGo and others carry fixable findings (efforts, axes, continuous limits).
    assert!(fixed_files >= 5, "only {fixed_files} files had fixes");
}
