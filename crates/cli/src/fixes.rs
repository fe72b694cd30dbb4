//! `--fix`, `--unsafe-fixes` and `--diff`: the findings' fixes gathered per file, applied to the text read,
//! checked and written (atomically), or shown as a unified diff.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use urdf_validator::diagnostics::fix::{apply, Applicability, TextEdit};
use urdf_validator::report::FixReport;
use urdf_validator::Validation;

/// Which fixes apply.
#[derive(Clone, Debug)]
pub struct Policy {
    /// Unsafe fixes too, and edits outside the trusted folders.
    pub unsafe_fixes: bool,
    /// The overrides' fixes too (`--from-overrides`), first and whether or not `unsafe_fixes`.
    pub from_overrides: bool,
    /// `--package-path` folders: files under them may be edited by safe fixes.
    pub package_paths: Vec<PathBuf>,
}

/// The new text of one file.
#[derive(Debug)]
pub struct FileFix {
    /// The file.
    pub path: PathBuf,
    /// Its text as the validation read it.
    pub before: String,
    /// Its text with the fixes applied.
    pub after: String,
    /// How many findings' fixes it holds.
    pub fixes: usize,
}

/// What a run would change, and what it leaves out (one line each: a fix skipped and why).
#[derive(Debug, Default)]
pub struct Plan {
    /// Files whose text changes.
    pub files: Vec<FileFix>,
    /// Fixes left out: not applicable, unsafe, outside the trusted folders, overlapping another, or
    /// producing XML that does not parse.
    pub skipped: Vec<String>,
    /// Unsafe fixes not applied for want of `--unsafe-fixes`.
    pub unsafe_left: usize,
}

/// Gather the fixes of `validations` under `policy`, file by file.
pub fn plan(validations: &[&Validation], policy: &Policy) -> Plan {
    let mut plan = Plan::default();
    // Per file: its text as read, the edits accepted so far and how many fixes they come from.
    let mut per_file: BTreeMap<PathBuf, (String, Vec<TextEdit>, usize)> = BTreeMap::new();
    for validation in validations {
        let input = Path::new(&validation.report.urdf_path);
        let trusted = trusted_folders(input, &policy.package_paths);
        let overrides = validation
            .report
            .overrides
            .iter()
            .filter(|_| policy.from_overrides);
        for applied in overrides {
            let outcome = match &applied.fix {
                Some(fix) if !fix.edits.is_empty() => {
                    accept(fix, validation, &trusted, policy, &mut per_file)
                }
                Some(fix) => Err(fix.not_applicable.clone().unwrap_or_default()),
                None => Err("the file declares no attribute to hold it: add it by hand".into()),
            };
            if let Err(why) = outcome {
                plan.skipped
                    .push(format!("override {}: {why}", applied.key));
            }
        }
        for finding in &validation.report.findings {
            let Some(fix) = &finding.fix else { continue };
            if fix.edits.is_empty() {
                continue;
            }
            if fix.applicability == Applicability::Unsafe && !policy.unsafe_fixes {
                plan.unsafe_left += 1;
                continue;
            }
            match accept(fix, validation, &trusted, policy, &mut per_file) {
                Ok(()) => {}
                Err(why) => plan.skipped.push(format!(
                    "{} {} ({}): {why}",
                    finding.rule, finding.name, fix.description
                )),
            }
        }
    }
    for (path, (before, edits, fixes)) in per_file {
        let (after, _) = apply(&before, &edits);
        if after == before {
            // Edits that write what is there already (an override's value once written).
            continue;
        }
        if let Err(error) = roxmltree::Document::parse(&after) {
            plan.skipped.push(format!(
                "{}: the fixed text would not be well-formed XML ({error}); nothing applied to it",
                path.display()
            ));
            continue;
        }
        plan.files.push(FileFix {
            path,
            before,
            after,
            fixes,
        });
    }
    plan
}

/// Add `fix`'s edits to their files' edit lists, all or none.
fn accept(
    fix: &FixReport,
    validation: &Validation,
    trusted: &[PathBuf],
    policy: &Policy,
    per_file: &mut BTreeMap<PathBuf, (String, Vec<TextEdit>, usize)>,
) -> Result<(), String> {
    for edit in &fix.edits {
        let path = PathBuf::from(&edit.file);
        if !policy.unsafe_fixes && !is_under(&path, trusted) {
            return Err(format!(
                "{} is outside the input's package and --package-path folders (--unsafe-fixes edits it)",
                edit.file
            ));
        }
        if !per_file.contains_key(&path) {
            let text = validation
                .sources
                .iter()
                .find(|s| s.path() == path)
                .map(|s| s.text().to_string())
                .ok_or_else(|| format!("{} was not read by the validation", edit.file))?;
            per_file.insert(path.clone(), (text, Vec::new(), 0));
        }
        let (_, edits, _) = &per_file[&path];
        // The same edit from another finding is that fix again (a literal in a macro body many links use).
        if edits.iter().any(|e| edit.edit.conflicts_with(e)) {
            return Err(format!("{}: overlaps the edit of another fix", edit.file));
        }
    }
    let mut added = false;
    for edit in &fix.edits {
        let (_, edits, _) = per_file
            .get_mut(Path::new(&edit.file))
            .ok_or("internal: file not gathered")?;
        if !edits.contains(&edit.edit) {
            edits.push(edit.edit.clone());
            added = true;
        }
    }
    if added {
        if let Some(first) = fix.edits.first() {
            if let Some((_, _, fixes)) = per_file.get_mut(Path::new(&first.file)) {
                *fixes += 1;
            }
        }
    }
    Ok(())
}

/// The folders safe fixes may edit for `input`: its package (the nearest folder above it holding a
/// `package.xml`), else its own folder; and the `--package-path` folders.
fn trusted_folders(input: &Path, package_paths: &[PathBuf]) -> Vec<PathBuf> {
    let dir = input
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let dir = dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf());
    let package = dir
        .ancestors()
        .find(|d| d.join("package.xml").is_file())
        .map_or_else(|| dir.clone(), Path::to_path_buf);
    std::iter::once(package)
        .chain(
            package_paths
                .iter()
                .map(|p| p.canonicalize().unwrap_or_else(|_| p.clone())),
        )
        .collect()
}

fn is_under(path: &Path, folders: &[PathBuf]) -> bool {
    let path = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
    folders.iter().any(|folder| path.starts_with(folder))
}

/// The unified diff of every file of `plan`.
pub fn diff(plan: &Plan) -> String {
    let mut out = String::new();
    for file in &plan.files {
        let name = file.path.display().to_string();
        out.push_str(
            &similar::TextDiff::from_lines(&file.before, &file.after)
                .unified_diff()
                .context_radius(3)
                .header(&name, &name)
                .to_string(),
        );
    }
    out
}

/// Write every file of `plan`: each through a temporary file in its folder renamed over it, and only
/// when it still holds the text the validation read. One line per file not written.
pub fn write(plan: &Plan) -> Vec<String> {
    let mut errors = Vec::new();
    for file in &plan.files {
        if let Err(why) = write_one(file) {
            errors.push(format!("{}: not fixed: {why}", file.path.display()));
        }
    }
    errors
}

fn write_one(file: &FileFix) -> Result<(), String> {
    let now = std::fs::read_to_string(&file.path).map_err(|e| format!("cannot read it ({e})"))?;
    if now != file.before {
        return Err("it changed since it was read; validate it again".into());
    }
    let dir = file
        .path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = file
        .path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temporary = dir.join(format!(".{name}.urdf-validate-fix.{}", std::process::id()));
    let written = std::fs::write(&temporary, &file.after).and_then(|()| {
        if let Ok(metadata) = std::fs::metadata(&file.path) {
            std::fs::set_permissions(&temporary, metadata.permissions())?;
        }
        std::fs::rename(&temporary, &file.path)
    });
    written.map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        format!("cannot write it ({e})")
    })
}
