//! Which rules run and how loud they are: `select`, `ignore`, `per-file-ignores` and severity overrides
//! (ruff's model), applied to the findings when the report is built (see [`crate::report::build`]).
//!
//! A [`Settings`] value is plain data, filled by the command line from `urdf-validate.toml` /
//! `pyproject.toml` and flags, or by any other caller of the library. Every entry remembers where it came
//! from ([`Origin`]), so a misspelt code is reported at its place and `--show-config` can say why a setting
//! holds.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::diagnostics::finding::Severity;
use crate::diagnostics::rules::{self, Rule};

/// Where a setting came from.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Origin {
    /// The built-in default.
    #[default]
    Default,
    /// A command-line flag.
    CommandLine,
    /// A configuration file, at a 1-based line and column.
    File {
        /// The configuration file.
        path: PathBuf,
        /// 1-based line.
        line: u32,
        /// 1-based column.
        column: u32,
    },
    /// Set by the program using the library (no file, no flag).
    Api,
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::Default => write!(f, "default"),
            Origin::CommandLine => write!(f, "command line"),
            Origin::File { path, line, .. } => write!(f, "{}:{line}", path.display()),
            Origin::Api => write!(f, "API"),
        }
    }
}

/// A rule selector as written: a code (`U201`), a name (`missing-inertial`), a code prefix (`U2`, every
/// rule whose code starts with it) or `ALL`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Selector {
    /// The text as written.
    pub text: String,
    /// Where it was written.
    pub origin: Origin,
}

impl Selector {
    /// A selector `text` written at `origin`.
    pub fn new(text: impl Into<String>, origin: Origin) -> Self {
        Selector {
            text: text.into().trim().to_string(),
            origin,
        }
    }

    /// True when the selector names `rule` (by code, name, code prefix or `ALL`).
    pub fn matches(&self, rule: &Rule) -> bool {
        selector_matches(&self.text, rule)
    }

    /// True when the selector names at least one rule of the registry.
    pub fn is_known(&self) -> bool {
        rules::ALL.iter().any(|rule| self.matches(rule))
    }
}

/// True when `text` names `rule`: its code (any case), its name, a prefix of its code of at least two
/// characters (`U2`), or `ALL`.
pub fn selector_matches(text: &str, rule: &Rule) -> bool {
    let text = text.trim();
    if text.eq_ignore_ascii_case("ALL") || text == rule.name {
        return true;
    }
    text.len() >= 2
        && rule.code.len() >= text.len()
        && rule
            .code
            .get(..text.len())
            .is_some_and(|prefix| prefix.eq_ignore_ascii_case(text))
}

/// The "did you mean" help for a selector that names no rule.
pub fn suggest_rule(text: &str) -> String {
    let upper = text.trim().to_ascii_uppercase();
    let codes = crate::diagnostics::suggest::closest(&upper, rules::ALL.iter().map(|r| r.code));
    if let Some(code) = codes.first() {
        let name = rules::find(code).map_or("", |r| r.name);
        return format!(
            "did you mean '{code}' ({name})? `urdf_validate --list-rules` lists them all"
        );
    }
    let names = rules::ALL.iter().map(|r| r.name);
    format!(
        "{}; `urdf_validate --list-rules` lists them all",
        crate::diagnostics::suggest::did_you_mean(text.trim(), names)
    )
}

/// `per-file-ignores`: rules ignored in the files matching a glob.
#[derive(Clone, Debug)]
pub struct PerFileIgnore {
    /// The glob as written (`robots/legacy/*.urdf`, `**/*.xacro`).
    pub pattern: String,
    matcher: globset::GlobMatcher,
    /// The rules ignored in matching files.
    pub rules: Vec<Selector>,
    /// Where the pattern was written.
    pub origin: Origin,
}

impl PerFileIgnore {
    /// Ignore `rules` in the files matching `pattern` (a glob: `*`, `**`, `?`, `[ab]`, `{a,b}`), matched
    /// against the file's path relative to [`Settings::base_dir`] (or as given when it is not below it).
    pub fn new(
        pattern: impl Into<String>,
        rules: Vec<Selector>,
        origin: Origin,
    ) -> Result<Self, String> {
        let pattern = pattern.into();
        let glob = globset::Glob::new(&pattern)
            .map_err(|error| format!("invalid glob '{pattern}': {}", error.kind()))?;
        Ok(PerFileIgnore {
            matcher: glob.compile_matcher(),
            pattern,
            rules,
            origin,
        })
    }

    /// True when `path` (relative to the base directory, or absolute) matches the pattern; a pattern
    /// without `/` also matches the file name alone.
    pub fn matches_path(&self, path: &Path) -> bool {
        self.matcher.is_match(path)
            || (!self.pattern.contains('/')
                && path.file_name().is_some_and(|n| self.matcher.is_match(n)))
    }
}

/// A severity override: findings of the rules named by `rule` get `severity`.
#[derive(Clone, Debug)]
pub struct SeverityOverride {
    /// The rule (code, name or prefix).
    pub rule: Selector,
    /// The new severity.
    pub severity: Severity,
}

/// Rule selection, per-file ignores and severity overrides; applied when the report is built.
#[derive(Clone, Debug, Default)]
pub struct Settings {
    /// Only these rules report (`None`: every rule).
    pub select: Option<Vec<Selector>>,
    /// These rules never report (wins over `select`).
    pub ignore: Vec<Selector>,
    /// Rules ignored in some files.
    pub per_file_ignores: Vec<PerFileIgnore>,
    /// Severities changed from the rules' defaults (later entries win).
    pub severity: Vec<SeverityOverride>,
    /// The folder `per_file_ignores` patterns are relative to (the configuration file's).
    pub base_dir: Option<PathBuf>,
    /// Honour `<!-- urdf-validate: ignore ... -->` comments (on unless turned off).
    pub no_inline: bool,
    /// Keep the suppressed findings in the report (`suppressed`), for `--show-suppressed`.
    pub show_suppressed: bool,
}

/// Why a finding does not count.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Suppression {
    /// Its rule is not in `select`.
    NotSelected(Origin),
    /// Its rule is in `ignore`.
    Ignored(Origin),
    /// A `per-file-ignores` pattern matches the file.
    PerFile {
        /// The pattern.
        pattern: String,
        /// Where it was written.
        origin: Origin,
    },
    /// An inline comment in the file.
    Comment {
        /// The file holding the comment.
        file: String,
        /// 1-based line of the comment.
        line: u32,
        /// `true` for `ignore-file`.
        whole_file: bool,
    },
}

impl fmt::Display for Suppression {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Suppression::NotSelected(origin) => write!(f, "not in select ({origin})"),
            Suppression::Ignored(origin) => write!(f, "ignore ({origin})"),
            Suppression::PerFile { pattern, origin } => {
                write!(f, "per-file-ignores \"{pattern}\" ({origin})")
            }
            Suppression::Comment {
                file,
                line,
                whole_file,
            } => {
                let kind = if *whole_file { "ignore-file" } else { "ignore" };
                write!(f, "urdf-validate: {kind} comment ({file}:{line})")
            }
        }
    }
}

impl Settings {
    /// Why findings of `rule` in `file` are dropped by the configuration, or `None` when they count.
    pub fn suppression_for(&self, rule: &Rule, file: &Path) -> Option<Suppression> {
        if let Some(select) = &self.select {
            if !select.iter().any(|s| s.matches(rule)) {
                let origin = select.first().map_or(Origin::Default, |s| s.origin.clone());
                return Some(Suppression::NotSelected(origin));
            }
        }
        if let Some(hit) = self.ignore.iter().find(|s| s.matches(rule)) {
            return Some(Suppression::Ignored(hit.origin.clone()));
        }
        let relative = self.relative(file);
        self.per_file_ignores
            .iter()
            .find(|p| p.rules.iter().any(|s| s.matches(rule)) && p.matches_path(&relative))
            .map(|p| Suppression::PerFile {
                pattern: p.pattern.clone(),
                origin: p.origin.clone(),
            })
    }

    /// The severity of `rule`'s findings: the last override naming it, else the rule's default.
    pub fn severity_of(&self, rule: &Rule) -> Severity {
        self.severity
            .iter()
            .rev()
            .find(|o| o.rule.matches(rule))
            .map_or(rule.severity, |o| o.severity)
    }

    /// Every selector that names no rule (in `select`, `ignore`, `per-file-ignores` and `severity`).
    pub fn unknown_selectors(&self) -> Vec<&Selector> {
        let all = self
            .select
            .iter()
            .flatten()
            .chain(&self.ignore)
            .chain(self.per_file_ignores.iter().flat_map(|p| &p.rules))
            .chain(self.severity.iter().map(|o| &o.rule));
        all.filter(|s| !s.is_known()).collect()
    }

    /// `file` relative to the base directory (both made absolute first), else `file` as given.
    fn relative(&self, file: &Path) -> PathBuf {
        let Some(base) = &self.base_dir else {
            return file.to_path_buf();
        };
        let absolute = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
        let (file_abs, base_abs) = (absolute(file), absolute(base));
        file_abs
            .strip_prefix(&base_abs)
            .map(Path::to_path_buf)
            .unwrap_or(file_abs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sel(text: &str) -> Selector {
        Selector::new(text, Origin::Api)
    }

    #[test]
    fn selectors_match_codes_names_prefixes_and_all() {
        assert!(sel("U201").matches(&rules::MISSING_INERTIAL));
        assert!(sel("u201").matches(&rules::MISSING_INERTIAL));
        assert!(sel("missing-inertial").matches(&rules::MISSING_INERTIAL));
        assert!(sel("U2").matches(&rules::MISSING_INERTIAL));
        assert!(sel("ALL").matches(&rules::MISSING_INERTIAL));
        assert!(!sel("U3").matches(&rules::MISSING_INERTIAL));
        assert!(!sel("U").matches(&rules::MISSING_INERTIAL));
        assert!(!sel("U2011").matches(&rules::MISSING_INERTIAL));
        assert!(!sel("U2O1").is_known());
        assert!(suggest_rule("U2O1").contains("'U201'"));
        assert!(suggest_rule("mising-inertial").contains("'missing-inertial'"));
    }

    #[test]
    fn ignore_wins_over_select_and_per_file_globs_match_relative_paths() {
        let settings = Settings {
            select: Some(vec![sel("U2")]),
            ignore: vec![sel("U203")],
            per_file_ignores: vec![PerFileIgnore::new(
                "legacy/**/*.urdf",
                vec![sel("U204")],
                Origin::Api,
            )
            .unwrap_or_else(|e| panic!("{e}"))],
            base_dir: Some(PathBuf::from("/repo")),
            ..Settings::default()
        };
        let file = Path::new("/repo/legacy/a/robot.urdf");
        assert_eq!(
            settings.suppression_for(&rules::MISSING_INERTIAL, file),
            None
        );
        assert!(matches!(
            settings.suppression_for(&rules::ZERO_MASS, file),
            Some(Suppression::Ignored(_))
        ));
        assert!(matches!(
            settings.suppression_for(&rules::ZERO_INERTIA, file),
            Some(Suppression::PerFile { .. })
        ));
        assert_eq!(
            settings.suppression_for(&rules::ZERO_INERTIA, Path::new("/repo/new/robot.urdf")),
            None
        );
        assert!(matches!(
            settings.suppression_for(&rules::MISSING_LIMIT, file),
            Some(Suppression::NotSelected(_))
        ));
        assert!(PerFileIgnore::new("a[", vec![], Origin::Api).is_err());
    }

    #[test]
    fn the_last_severity_override_wins() {
        let settings = Settings {
            severity: vec![
                SeverityOverride {
                    rule: sel("U2"),
                    severity: Severity::Critical,
                },
                SeverityOverride {
                    rule: sel("U201"),
                    severity: Severity::Info,
                },
            ],
            ..Settings::default()
        };
        assert_eq!(
            settings.severity_of(&rules::MISSING_INERTIAL),
            Severity::Info
        );
        assert_eq!(settings.severity_of(&rules::ZERO_MASS), Severity::Critical);
        assert_eq!(
            settings.severity_of(&rules::MISSING_LIMIT),
            Severity::Critical
        );
    }
}
