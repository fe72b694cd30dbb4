//! Configuration files: `urdf-validate.toml`, or `[tool.urdf-validate]` in `pyproject.toml`, found next to
//! each input or in a parent folder (the nearest wins), or named with `--config`. The library applies the
//! resulting [`Settings`]; this module only finds, parses and merges them with the [`Request`].
//!
//! ```toml
//! select = ["ALL"]
//! ignore = ["U105", "massless-geometry"]
//! robot-type = "wheeled"
//! up-axis = "y"                       # the model's up axis, when it is not z
//! samples = 10000
//! package-path = ["../deps"]          # relative to this file
//! baseline = "urdf-validate-baseline.json"  # relative to this file
//!
//! [per-file-ignores]
//! "legacy/**/*.urdf" = ["U201"]
//!
//! [severity]
//! U201 = "info"
//! ```

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;
use urdf_validator::analysis::classify::RobotType;
use urdf_validator::diagnostics::settings::{
    Origin, PerFileIgnore, Selector, Settings, SeverityOverride,
};
use urdf_validator::diagnostics::suggest::did_you_mean;
use urdf_validator::diagnostics::Severity;
use urdf_validator::model::UpAxis;
use urdf_validator::{DEFAULT_SAMPLES, DEFAULT_SEED};

use crate::request::Request;

/// The dedicated configuration file name.
pub const CONFIG_FILE: &str = "urdf-validate.toml";
/// Python projects' configuration file (`[tool.urdf-validate]`).
pub const PYPROJECT: &str = "pyproject.toml";

/// The configuration table as written: the keys of `urdf-validate.toml` (or of `[tool.urdf-validate]` in
/// `pyproject.toml`). Its doc comments and defaults are the book's configuration reference
/// (`docs/reference/configuration.md`, from [`json_schema`]).
#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
#[schemars(title = "urdf-validate.toml")]
struct Raw {
    /// The rules to run: codes (`U201`), names (`missing-inertial`), code prefixes (`U2`) or `ALL`.
    /// `--select` replaces it.
    #[schemars(with = "Option<Vec<String>>", extend("default" = ["ALL"]))]
    select: Option<Vec<Spanned<String>>>,
    /// Rules not to run, as in `select`. `--ignore` adds to it.
    #[schemars(with = "Option<Vec<String>>", extend("default" = []))]
    ignore: Option<Vec<Spanned<String>>>,
    /// Rules ignored in some files: a glob, relative to this file's folder (a pattern without `/` also
    /// matches the file name alone), to the rules it ignores there.
    #[schemars(
        with = "Option<BTreeMap<String, Vec<String>>>",
        extend("default" = {})
    )]
    per_file_ignores: Option<BTreeMap<Spanned<String>, Vec<Spanned<String>>>>,
    /// A rule's severity instead of its default: rule code or name to `info`, `warn`, `fail` or
    /// `critical`. The last entry naming a rule wins.
    #[schemars(
        with = "Option<BTreeMap<String, SeverityName>>",
        extend("default" = {})
    )]
    severity: Option<BTreeMap<Spanned<String>, Spanned<SeverityName>>>,
    /// The robot's category (`--robot-type`, whose help lists the values); without it, the category is
    /// guessed from the links and joints. The guess still runs: a disagreement is an INFO, U730.
    #[schemars(with = "Option<String>")]
    robot_type: Option<Spanned<String>>,
    /// The root frame's axis that points up (`--up-axis`: `x`, `y`, `z`, with an optional sign, `-y`), when
    /// the model is not z-up; without it, z, and U731 reports a model that looks otherwise.
    #[schemars(with = "Option<String>")]
    up_axis: Option<Spanned<String>>,
    /// A payload carried at `payload-link`, in kg (`--payload-mass`): torques and verdicts include it.
    #[schemars(with = "Option<f64>")]
    payload_mass: Option<Spanned<f64>>,
    /// The link carrying the payload (`--payload-link`); without it, the end of the longest actuated
    /// chain.
    #[schemars(with = "Option<String>")]
    payload_link: Option<Spanned<String>>,
    /// Samples per arm for the workspace (reach, task, orientation, self-collision), and for
    /// `--pose worst` (`--samples`).
    #[schemars(with = "Option<usize>", extend("default" = DEFAULT_SAMPLES))]
    samples: Option<Spanned<usize>>,
    /// The seed of that sampling (`--seed`): the same seed gives the same report.
    #[schemars(with = "Option<u64>", extend("default" = DEFAULT_SEED))]
    seed: Option<Spanned<u64>>,
    /// Folders searched for `package://` and `$(find)` packages, relative to this file; searched after
    /// `--package-path`, which adds to it.
    #[schemars(with = "Option<Vec<String>>", extend("default" = []))]
    package_path: Option<Vec<Spanned<String>>>,
    /// The ground-contact links of the support polygon (`--contact-links`); without it, the wheels and
    /// casters of a wheeled robot, the feet of a legged one, else the lowest geometry.
    #[schemars(with = "Option<Vec<String>>")]
    contact_links: Option<Spanned<Vec<String>>>,
    /// A baseline file, relative to this file (`--baseline`): the findings it holds are not reported. See
    /// "Adopting on an existing robot".
    #[schemars(with = "Option<String>")]
    baseline: Option<Spanned<String>>,
}

/// The JSON Schema of the configuration table (`urdf-validate.toml`, `[tool.urdf-validate]`): every key,
/// with its type, default and description.
pub fn json_schema() -> serde_json::Value {
    serde_json::to_value(schemars::schema_for!(Raw)).unwrap_or_default()
}

/// The keys of a configuration table, from [`json_schema`], for suggestions.
fn keys() -> Vec<String> {
    json_schema()
        .get("properties")
        .and_then(serde_json::Value::as_object)
        .map(|properties| properties.keys().cloned().collect())
        .unwrap_or_default()
}

/// `[severity]` values.
#[derive(Clone, Copy, Debug, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
enum SeverityName {
    #[serde(alias = "INFO")]
    Info,
    #[serde(alias = "WARN", alias = "warning")]
    Warn,
    #[serde(alias = "FAIL")]
    Fail,
    #[serde(alias = "CRITICAL")]
    Critical,
}

impl From<SeverityName> for Severity {
    fn from(name: SeverityName) -> Self {
        match name {
            SeverityName::Info => Severity::Info,
            SeverityName::Warn => Severity::Warn,
            SeverityName::Fail => Severity::Fail,
            SeverityName::Critical => Severity::Critical,
        }
    }
}

#[derive(Debug, Deserialize)]
struct Pyproject {
    tool: Option<Tool>,
}

#[derive(Debug, Deserialize)]
struct Tool {
    #[serde(rename = "urdf-validate")]
    urdf_validate: Option<Raw>,
}

/// A value and where it came from.
#[derive(Clone, Debug)]
pub struct Setting<T> {
    /// The value.
    pub value: T,
    /// Where it came from.
    pub origin: Origin,
}

impl<T> Setting<T> {
    fn default(value: T) -> Self {
        Setting {
            value,
            origin: Origin::Default,
        }
    }
}

/// What a run uses for the files sharing one configuration: the file's settings merged with the flags
/// (flags win; `--ignore` and `--package-path` add to the file's).
#[derive(Clone, Debug)]
pub struct Effective {
    /// The configuration file read, if any.
    pub file: Option<PathBuf>,
    /// Rule selection and severities, for the library.
    pub settings: Settings,
    /// `robot-type`.
    pub robot_type: Setting<Option<RobotType>>,
    /// `up-axis`.
    pub up_axis: Setting<Option<UpAxis>>,
    /// `payload-mass`.
    pub payload_mass: Setting<Option<f64>>,
    /// `payload-link`.
    pub payload_link: Setting<Option<String>>,
    /// `samples`.
    pub samples: Setting<usize>,
    /// `seed`.
    pub seed: Setting<u64>,
    /// `package-path`, each folder with its origin (the flags' first).
    pub package_path: Vec<Setting<PathBuf>>,
    /// `contact-links`.
    pub contact_links: Setting<Option<Vec<String>>>,
    /// `baseline` (a path in the file is relative to the file).
    pub baseline: Setting<Option<PathBuf>>,
}

impl Effective {
    /// The request with the merged values in place of its own.
    pub fn applied_to(&self, request: &Request) -> Request {
        Request {
            robot_type: self.robot_type.value,
            up_axis: self.up_axis.value,
            payload_mass: self.payload_mass.value,
            payload_link: self.payload_link.value.clone(),
            samples: Some(self.samples.value),
            seed: Some(self.seed.value),
            package_path: self.package_path.iter().map(|p| p.value.clone()).collect(),
            contact_links: self.contact_links.value.clone(),
            baseline: self.baseline.value.clone(),
            ..request.clone()
        }
    }

    /// The `--show-config` text.
    pub fn show(&self) -> String {
        let mut out = String::new();
        let _ = writeln!(
            out,
            "# configuration file: {}",
            self.file
                .as_ref()
                .map_or_else(|| "none".to_string(), |p| p.display().to_string())
        );
        let selectors = |list: &[Selector]| -> String {
            let items: Vec<String> = list.iter().map(|s| format!("{:?}", s.text)).collect();
            format!("[{}]", items.join(", "))
        };
        let origins = |list: &[Selector]| -> String {
            let mut seen: Vec<String> = Vec::new();
            for s in list {
                let o = s.origin.to_string();
                if !seen.contains(&o) {
                    seen.push(o);
                }
            }
            if seen.is_empty() {
                "default".to_string()
            } else {
                seen.join(", ")
            }
        };
        let mut line = |key: &str, value: String, origin: String| {
            let _ = writeln!(out, "{key:<17} = {value:<40} # {origin}");
        };
        match &self.settings.select {
            Some(select) => line("select", selectors(select), origins(select)),
            None => line("select", "[\"ALL\"]".into(), "default".into()),
        }
        line(
            "ignore",
            selectors(&self.settings.ignore),
            origins(&self.settings.ignore),
        );
        if self.settings.per_file_ignores.is_empty() {
            line("per-file-ignores", "{}".into(), "default".into());
        }
        for p in &self.settings.per_file_ignores {
            line(
                &format!("per-file-ignores.{:?}", p.pattern),
                selectors(&p.rules),
                p.origin.to_string(),
            );
        }
        if self.settings.severity.is_empty() {
            line("severity", "{}".into(), "default".into());
        }
        for o in &self.settings.severity {
            line(
                &format!("severity.{}", o.rule.text),
                format!("{:?}", o.severity.label().to_ascii_lowercase()),
                o.rule.origin.to_string(),
            );
        }
        let opt = |v: Option<String>| v.unwrap_or_else(|| "(none)".to_string());
        line(
            "robot-type",
            opt(self.robot_type.value.map(|t| format!("{:?}", t.as_str()))),
            self.robot_type.origin.to_string(),
        );
        line(
            "up-axis",
            opt(self.up_axis.value.map(|a| format!("{:?}", a.as_str()))),
            self.up_axis.origin.to_string(),
        );
        line(
            "payload-mass",
            opt(self.payload_mass.value.map(|m| m.to_string())),
            self.payload_mass.origin.to_string(),
        );
        line(
            "payload-link",
            opt(self.payload_link.value.as_ref().map(|l| format!("{l:?}"))),
            self.payload_link.origin.to_string(),
        );
        line(
            "samples",
            self.samples.value.to_string(),
            self.samples.origin.to_string(),
        );
        line(
            "seed",
            self.seed.value.to_string(),
            self.seed.origin.to_string(),
        );
        let paths: Vec<String> = self
            .package_path
            .iter()
            .map(|p| format!("{:?}", p.value.display().to_string()))
            .collect();
        let mut path_origins: Vec<String> = Vec::new();
        for p in &self.package_path {
            let o = p.origin.to_string();
            if !path_origins.contains(&o) {
                path_origins.push(o);
            }
        }
        line(
            "package-path",
            format!("[{}]", paths.join(", ")),
            if path_origins.is_empty() {
                "default".to_string()
            } else {
                path_origins.join(", ")
            },
        );
        line(
            "contact-links",
            opt(self.contact_links.value.as_ref().map(|l| format!("{l:?}"))),
            self.contact_links.origin.to_string(),
        );
        line(
            "baseline",
            opt(self
                .baseline
                .value
                .as_ref()
                .map(|p| format!("{:?}", p.display().to_string()))),
            self.baseline.origin.to_string(),
        );
        line(
            "show-suppressed",
            self.settings.show_suppressed.to_string(),
            if self.settings.show_suppressed {
                "command line".to_string()
            } else {
                "default".to_string()
            },
        );
        out
    }
}

/// The configuration file governing `input`: `urdf-validate.toml`, else a `pyproject.toml` with a
/// `[tool.urdf-validate]` table, in the input's folder or the nearest parent holding one.
pub fn discover(input: &Path) -> Option<PathBuf> {
    let absolute = std::path::absolute(input).unwrap_or_else(|_| input.to_path_buf());
    let start = if absolute.is_dir() {
        absolute.as_path()
    } else {
        absolute.parent()?
    };
    for dir in start.ancestors() {
        let dedicated = dir.join(CONFIG_FILE);
        if dedicated.is_file() {
            return Some(dedicated);
        }
        let pyproject = dir.join(PYPROJECT);
        if pyproject.is_file()
            && std::fs::read_to_string(&pyproject).is_ok_and(|t| has_tool_table(&t))
        {
            return Some(pyproject);
        }
    }
    None
}

/// True when a `pyproject.toml` text has a `[tool.urdf-validate]` table (or sub-table).
fn has_tool_table(text: &str) -> bool {
    text.lines().any(|line| {
        let line = line.trim();
        line.starts_with("[tool.urdf-validate]")
            || line.starts_with("[tool.urdf-validate.")
            || line.starts_with("[tool.\"urdf-validate\"")
    }) || toml::from_str::<Pyproject>(text)
        .ok()
        .and_then(|p| p.tool)
        .and_then(|t| t.urdf_validate)
        .is_some()
}

/// Read and check the configuration file at `path`, merged with the request (its values win).
pub fn load(path: Option<&Path>, request: &Request) -> Result<Effective, String> {
    let raw = match path {
        Some(path) => read(path)?,
        None => Raw::default(),
    };
    merge(path, raw, request)
}

/// The configuration table of the file at `path`.
fn read(path: &Path) -> Result<Raw, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|error| format!("{}: cannot read configuration: {error}", path.display()))?;
    let is_pyproject = path.file_name().is_some_and(|n| n == PYPROJECT);
    let parsed = if is_pyproject {
        toml::from_str::<Pyproject>(&text)
            .map(|p| p.tool.and_then(|t| t.urdf_validate).unwrap_or_default())
    } else {
        toml::from_str::<Raw>(&text)
    };
    parsed.map_err(|error| describe_error(path, &text, &error))
}

/// `path:line:column: message (did you mean ...)` for a TOML or schema error.
fn describe_error(path: &Path, text: &str, error: &toml::de::Error) -> String {
    let message = error.message().trim_end().to_string();
    let at = error
        .span()
        .map(|span| {
            let (line, column) = line_col(text, span.start);
            format!("{line}:{column}: ")
        })
        .unwrap_or_default();
    let key = error
        .span()
        .and_then(|span| key_at(text, span.start))
        .filter(|key| !message.contains(&format!("`{key}`")))
        .map(|key| format!("key `{key}`: "))
        .unwrap_or_default();
    let mut out = format!(
        "{}:{at}invalid configuration: {key}{message}",
        path.display()
    );
    if let Some(unknown) = message
        .strip_prefix("unknown field `")
        .and_then(|rest| rest.split('`').next())
    {
        out.push_str(&format!(
            " ({})",
            did_you_mean(unknown, keys().iter().map(String::as_str))
        ));
    }
    out
}

/// The dotted key whose value holds byte `at` (`samples`, `severity.U201`), from the `key =` on its line
/// and the table header above it (`[tool.urdf-validate]` left out).
fn key_at(text: &str, at: usize) -> Option<String> {
    let before = text.get(..at)?;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line = text.get(line_start..)?.lines().next()?;
    let (key, _) = line.split_once('=')?;
    let key = key.trim().trim_matches('"');
    if key.is_empty() || key.starts_with('[') {
        return None;
    }
    let header = before
        .get(..line_start)?
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| l.starts_with('['))
        .map(|l| l.trim_matches(|c| c == '[' || c == ']').trim().to_string())
        .map(|h| {
            h.strip_prefix("tool.urdf-validate")
                .map(|rest| rest.trim_start_matches('.').to_string())
                .unwrap_or(h)
        })
        .unwrap_or_default();
    Some(if header.is_empty() {
        key.to_string()
    } else {
        format!("{header}.{key}")
    })
}

/// 1-based (line, column) of byte `at` of `text`.
fn line_col(text: &str, at: usize) -> (u32, u32) {
    let before = text.get(..at).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before.get(start..).map_or(0, |s| s.chars().count()) + 1;
    (
        u32::try_from(line).unwrap_or(u32::MAX),
        u32::try_from(column).unwrap_or(u32::MAX),
    )
}

/// Merge the file's table with the request (the values it gives win).
fn merge(path: Option<&Path>, raw: Raw, request: &Request) -> Result<Effective, String> {
    let text = match path {
        Some(p) => std::fs::read_to_string(p).unwrap_or_default(),
        None => String::new(),
    };
    let origin_at = |span: std::ops::Range<usize>| -> Origin {
        match path {
            Some(p) => {
                let (line, column) = line_col(&text, span.start);
                Origin::File {
                    path: p.to_path_buf(),
                    line,
                    column,
                }
            }
            None => Origin::Default,
        }
    };
    // String spans include the quotes: point at the text inside them.
    let inner = |s: &Spanned<String>| -> Origin {
        let span = s.span();
        origin_at(span.start.saturating_add(1)..span.end)
    };
    let error_at = |span: std::ops::Range<usize>, message: String| -> String {
        match path {
            Some(p) => {
                let (line, column) = line_col(&text, span.start);
                format!(
                    "{}:{line}:{column}: invalid configuration: {message}",
                    p.display()
                )
            }
            None => message,
        }
    };
    let selectors = |list: &[Spanned<String>]| -> Vec<Selector> {
        list.iter()
            .map(|s| Selector::new(s.get_ref().clone(), inner(s)))
            .collect()
    };
    let cli_selectors = |list: &[String]| -> Vec<Selector> {
        list.iter()
            .filter(|s| !s.trim().is_empty())
            .map(|s| Selector::new(s.clone(), Origin::CommandLine))
            .collect()
    };

    let mut settings = Settings {
        base_dir: path.and_then(Path::parent).map(Path::to_path_buf),
        show_suppressed: request.show_suppressed,
        ..Settings::default()
    };
    settings.select = match (&request.select, &raw.select) {
        (Some(cli), _) => Some(cli_selectors(cli)),
        (None, Some(file)) => Some(selectors(file)),
        (None, None) => None,
    };
    settings.ignore = raw.ignore.as_deref().map(selectors).unwrap_or_default();
    settings.ignore.extend(cli_selectors(&request.ignore));
    for (pattern, codes) in raw.per_file_ignores.unwrap_or_default() {
        let entry = PerFileIgnore::new(
            pattern.get_ref().clone(),
            selectors(&codes),
            inner(&pattern),
        )
        .map_err(|message| error_at(pattern.span(), format!("per-file-ignores: {message}")))?;
        settings.per_file_ignores.push(entry);
    }
    for (rule, severity) in raw.severity.unwrap_or_default() {
        settings.severity.push(SeverityOverride {
            rule: Selector::new(rule.get_ref().clone(), inner(&rule)),
            severity: (*severity.get_ref()).into(),
        });
    }

    let robot_type = if request.robot_type.is_some() {
        Setting {
            value: request.robot_type,
            origin: Origin::CommandLine,
        }
    } else if let Some(name) = &raw.robot_type {
        let value = RobotType::parse(&name.get_ref().to_ascii_lowercase()).ok_or_else(|| {
            let names: Vec<&str> = RobotType::ALL.iter().map(|t| t.as_str()).collect();
            error_at(
                name.span(),
                format!(
                    "robot-type '{}' is not one of {} ({})",
                    name.get_ref(),
                    names.join(", "),
                    did_you_mean(name.get_ref(), names.iter().copied())
                ),
            )
        })?;
        Setting {
            value: Some(value),
            origin: inner(name),
        }
    } else {
        Setting::default(None)
    };
    let up_axis = match (&raw.up_axis, request.up_axis.is_some()) {
        (_, true) => Setting {
            value: request.up_axis,
            origin: Origin::CommandLine,
        },
        (Some(axis), false) => Setting {
            value: Some(UpAxis::parse(axis.get_ref()).ok_or_else(|| {
                error_at(
                    axis.span(),
                    format!(
                        "up-axis '{}' is not an axis: x, y or z, with an optional sign (\"-y\")",
                        axis.get_ref()
                    ),
                )
            })?),
            origin: inner(axis),
        },
        (None, false) => Setting::default(None),
    };
    let payload_mass = match (&raw.payload_mass, request.payload_mass.is_some()) {
        (_, true) => Setting {
            value: request.payload_mass,
            origin: Origin::CommandLine,
        },
        (Some(mass), false) => {
            let value = *mass.get_ref();
            if !(value.is_finite() && value >= 0.0) {
                return Err(error_at(
                    mass.span(),
                    format!("payload-mass must be a finite number of kg ≥ 0, not {value}"),
                ));
            }
            Setting {
                value: Some(value),
                origin: origin_at(mass.span()),
            }
        }
        (None, false) => Setting::default(None),
    };
    let payload_link = match (&raw.payload_link, request.payload_link.is_some()) {
        (_, true) => Setting {
            value: request.payload_link.clone(),
            origin: Origin::CommandLine,
        },
        (Some(link), false) => Setting {
            value: Some(link.get_ref().clone()),
            origin: inner(link),
        },
        (None, false) => Setting::default(None),
    };
    let samples = match (&raw.samples, request.samples.is_some()) {
        (_, true) => Setting {
            value: request.samples.unwrap_or(DEFAULT_SAMPLES),
            origin: Origin::CommandLine,
        },
        (Some(samples), false) => {
            if *samples.get_ref() == 0 {
                return Err(error_at(
                    samples.span(),
                    "samples must be at least 1".into(),
                ));
            }
            Setting {
                value: *samples.get_ref(),
                origin: origin_at(samples.span()),
            }
        }
        (None, false) => Setting::default(DEFAULT_SAMPLES),
    };
    let seed = match (&raw.seed, request.seed.is_some()) {
        (_, true) => Setting {
            value: request.seed.unwrap_or(DEFAULT_SEED),
            origin: Origin::CommandLine,
        },
        (Some(seed), false) => Setting {
            value: *seed.get_ref(),
            origin: origin_at(seed.span()),
        },
        (None, false) => Setting::default(DEFAULT_SEED),
    };
    let mut package_path: Vec<Setting<PathBuf>> = request
        .package_path
        .iter()
        .map(|p| Setting {
            value: p.clone(),
            origin: Origin::CommandLine,
        })
        .collect();
    let base = path.and_then(Path::parent).unwrap_or(Path::new(""));
    for folder in raw.package_path.iter().flatten() {
        package_path.push(Setting {
            value: base.join(folder.get_ref()),
            origin: inner(folder),
        });
    }
    let contact_links = match (&raw.contact_links, request.contact_links.is_some()) {
        (_, true) => Setting {
            value: request.contact_links.clone(),
            origin: Origin::CommandLine,
        },
        (Some(links), false) => Setting {
            value: Some(links.get_ref().clone()),
            origin: origin_at(links.span()),
        },
        (None, false) => Setting::default(None),
    };
    let baseline = match (&raw.baseline, request.baseline.is_some()) {
        (_, true) => Setting {
            value: request.baseline.clone(),
            origin: Origin::CommandLine,
        },
        (Some(file), false) => Setting {
            value: Some(base.join(file.get_ref())),
            origin: inner(file),
        },
        (None, false) => Setting::default(None),
    };
    Ok(Effective {
        file: path.map(Path::to_path_buf),
        settings,
        robot_type,
        up_axis,
        payload_mass,
        payload_link,
        samples,
        seed,
        package_path,
        contact_links,
        baseline,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_keys_name_the_line_and_the_closest_key() {
        let text = "ignore = [\"U105\"]\nselct = [\"U2\"]\n";
        let error = toml::from_str::<Raw>(text).map(|_| ()).unwrap_err();
        let message = describe_error(Path::new("urdf-validate.toml"), text, &error);
        assert!(
            message.starts_with(
                "urdf-validate.toml:2:1: invalid configuration: unknown field `selct`"
            ),
            "{message}"
        );
        assert!(message.contains("did you mean 'select'?"), "{message}");
    }

    #[test]
    fn type_errors_name_the_key() {
        let text = "[tool.urdf-validate]\nsamples = \"many\"\n\n[tool.urdf-validate.severity]\nU201 = \"loud\"\n";
        let error = toml::from_str::<Pyproject>(text).map(|_| ()).unwrap_err();
        let message = describe_error(Path::new("pyproject.toml"), text, &error);
        assert!(
            message.starts_with("pyproject.toml:2:11: invalid configuration: key `samples`: "),
            "{message}"
        );
        assert_eq!(
            key_at(text, text.find("\"loud").unwrap_or(0)).as_deref(),
            Some("severity.U201")
        );
    }

    #[test]
    fn pyproject_tables_are_recognised() {
        assert!(has_tool_table("[tool.urdf-validate]\nignore = []\n"));
        assert!(has_tool_table(
            "[tool.urdf-validate.severity]\nU201 = \"info\"\n"
        ));
        assert!(!has_tool_table("[tool.ruff]\nselect = []\n"));
    }
}
