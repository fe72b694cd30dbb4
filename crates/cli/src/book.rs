//! The book's generated pages (`urdf_validate --write-book-pages docs`): one page per rule and its index
//! (from the rule registry, each with its failing and passing example from [`EXAMPLES`], validated here to
//! show what the tool reports) and the command-line reference (from the clap definition of [`Args`] and the
//! subcommands' help). A test fails when the committed pages under `docs/` differ from these.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use clap::CommandFactory;
use urdf_validator::diagnostics::fix::Applicability;
use urdf_validator::diagnostics::rules::{self, Rule};

use crate::args::Args;

const GENERATED: &str = "<!-- Generated from crates/cli/src/args.rs by `urdf_validate --write-book-pages docs`; a test fails when this file is stale. -->\n";

/// The rule examples, below the repository's root: a folder per rule page (`u304/`) holding `fail.*`, a
/// file that raises the rule, and `pass.*`, its corrected twin (a test below checks both), or `no-example.md`, why the rule cannot be shown by a small self-contained file.
pub const EXAMPLES: &str = "crates/urdf-validator/tests/data/rule-examples";

/// Every generated page: `(path below docs/, Markdown)`; `repo` is the repository's root (where
/// [`EXAMPLES`] is).
pub fn pages(repo: &Path) -> Vec<(String, String)> {
    let mut pages = rules::book_pages(|rule| example_section(repo, rule));
    pages.push(("reference/cli.md".to_string(), cli_reference()));
    pages.push((
        "reference/configuration.md".to_string(),
        configuration_reference(),
    ));
    pages
}

/// Write [`pages`] below `dir` (the book's `docs/`, in the repository's root) and remove rule pages
/// under `dir/rules/` that no rule has any more.
pub fn write_pages(dir: &Path) -> std::io::Result<Vec<String>> {
    let pages = pages(&dir.join(".."));
    let mut written = Vec::new();
    for (path, text) in &pages {
        let target = dir.join(path);
        if let Some(parent) = target.parent() {
            std::fs::create_dir_all(parent)?;
        }
        if std::fs::read_to_string(&target).ok().as_deref() != Some(text.as_str()) {
            std::fs::write(&target, text)?;
            written.push(path.clone());
        }
    }
    for entry in std::fs::read_dir(dir.join("rules"))? {
        let entry = entry?;
        let name = format!("rules/{}", entry.file_name().to_string_lossy());
        if name.ends_with(".md") && !pages.iter().any(|(path, _)| *path == name) {
            std::fs::remove_file(entry.path())?;
            written.push(format!("{name} (removed)"));
        }
    }
    Ok(written)
}

/// The file of `dir` whose name before its first `.` is `stem` (`fail.urdf`, `pass.sdf`), if there is one.
fn example_file(dir: &Path, stem: &str) -> Option<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .ok()?
        .flatten()
        .map(|entry| entry.path())
        .filter(|path| {
            path.file_name()
                .and_then(|name| name.to_str())
                .and_then(|name| name.split('.').next())
                == Some(stem)
        })
        .collect();
    files.sort();
    files.into_iter().next()
}

/// A rule's example files below `repo`'s [`EXAMPLES`]: `(fail, pass)`, when its folder has both.
pub fn example_files(repo: &Path, rule: &Rule) -> Option<(PathBuf, PathBuf)> {
    let dir = repo.join(EXAMPLES).join(rule.page());
    Some((example_file(&dir, "fail")?, example_file(&dir, "pass")?))
}

/// A rule page's `## Example` section: the failing file, what `urdf_validate` reports on it (the rule's
/// findings, with their help and fix), and the passing file; or why there is none.
fn example_section(repo: &Path, rule: &Rule) -> String {
    let folder = format!("{EXAMPLES}/{}", rule.page());
    if let Ok(reason) = std::fs::read_to_string(repo.join(&folder).join("no-example.md")) {
        return format!("## Example\n\nNo example: {}\n\n", reason.trim_end());
    }
    let Some((fail, pass)) = example_files(repo, rule) else {
        return format!(
            "## Example\n\nNo example on this page yet; the tests that raise {} are listed in \
             `crates/urdf-validator/tests/rules.rs` (`COVERED`).\n\n",
            rule.code
        );
    };
    let name = |path: &Path| {
        path.file_name()
            .map(|name| name.to_string_lossy().to_string())
            .unwrap_or_default()
    };
    let text = |path: &Path| std::fs::read_to_string(path).unwrap_or_default();
    let mut out = format!(
        "## Example\n\n`{fail_name}` raises {code}:\n\n```xml\n{fail_text}```\n\n",
        fail_name = name(&fail),
        code = rule.code,
        fail_text = text(&fail),
    );
    let findings = urdf_validator::validate(&fail, &urdf_validator::Options::default())
        .map(|validation| validation.report.findings)
        .unwrap_or_default();
    // Paths in messages as seen from the example's folder, wherever the repository is.
    let dir = repo.join(&folder).display().to_string();
    let relative = |text: &str| text.replace(&format!("{dir}/"), "").replace(&dir, ".");
    let mut reported = String::new();
    for finding in findings.iter().filter(|finding| finding.rule == rule.code) {
        let place = match (finding.line, finding.column) {
            (Some(line), Some(column)) => format!("{}:{line}:{column}", name(&fail)),
            _ => name(&fail),
        };
        let _ = writeln!(
            reported,
            "{place}: {} {} {}: {}",
            finding.severity.label(),
            finding.rule,
            finding.name,
            relative(&finding.message)
        );
        if let Some(help) = &finding.help {
            let _ = writeln!(reported, "  help: {}", relative(help));
        }
        if let Some(fix) = &finding.fix {
            let flags = match fix.applicability {
                Applicability::Safe => "--fix",
                Applicability::Unsafe => "--fix --unsafe-fixes",
            };
            let _ = writeln!(reported, "  fix ({flags}): {}", fix.description);
        }
    }
    let mut beside: Vec<String> = std::fs::read_dir(repo.join(&folder))
        .into_iter()
        .flatten()
        .flatten()
        .map(|entry| entry.path())
        .filter(|path| *path != fail && *path != pass)
        .map(|path| format!("`{}`", name(&path)))
        .collect();
    beside.sort();
    let beside = if beside.is_empty() {
        String::new()
    } else {
        format!(" with {}, which they read", beside.join(", "))
    };
    let _ = write!(
        out,
        "`urdf_validate {}` reports:\n\n```text\n{reported}```\n\n\
         `{pass_name}`, corrected, does not:\n\n```xml\n{pass_text}```\n\n\
         Both files are in [`{folder}/`]({repository}/tree/main/{folder}){beside}; \
         `cargo test -p urdf-validate-cli --lib book` checks that the first raises {code} and the second \
         does not.\n\n",
        name(&fail),
        pass_name = name(&pass),
        pass_text = text(&pass),
        code = rule.code,
        repository = env!("CARGO_PKG_REPOSITORY").trim_end_matches('/'),
    );
    out
}

/// The configuration reference: every key of `urdf-validate.toml` with its type, default and description,
/// from the JSON Schema of the configuration table ([`urdf_validate_session::config::json_schema`]).
pub fn configuration_reference() -> String {
    let schema = urdf_validate_session::config::json_schema();
    let mut out = format!(
        "# Configuration reference\n\n{}\n\
         Every key of `urdf-validate.toml` (in `pyproject.toml`, the same keys under `[tool.urdf-validate]`); \
         [Configuration and suppressions](../configuration.md) says where the file is found and how its values \
         meet the flags'. A key left out takes its default; a flag given on the command line wins.\n\n",
        GENERATED.replace("crates/cli/src/args.rs", "crates/session/src/config.rs")
    );
    let empty = serde_json::Map::new();
    let properties = schema
        .get("properties")
        .and_then(serde_json::Value::as_object)
        .unwrap_or(&empty);
    for (key, property) in properties {
        let _ = writeln!(out, "## `{key}`\n");
        let _ = writeln!(out, "Type: {}.\n", schema_type(property, &schema));
        match property.get("default") {
            Some(default) => {
                let _ = writeln!(out, "Default: `{}`.\n", toml_value(default));
            }
            None => {
                let _ = writeln!(out, "Default: none.\n");
            }
        }
        if let Some(description) = property.get("description").and_then(|d| d.as_str()) {
            let _ = writeln!(out, "{}\n", escape_html(&description.replace('\n', " ")));
        }
    }
    out
}

/// A JSON Schema type as the configuration file spells it: `string`, `array of strings`, `table (keys to
/// ...)`, the values of an enumeration.
fn schema_type(property: &serde_json::Value, schema: &serde_json::Value) -> String {
    if let Some(reference) = property.get("$ref").and_then(|r| r.as_str()) {
        let name = reference.rsplit('/').next().unwrap_or_default();
        return schema
            .get("$defs")
            .and_then(|defs| defs.get(name))
            .map_or_else(|| name.to_string(), |def| schema_type(def, schema));
    }
    if let Some(values) = property.get("enum").and_then(|e| e.as_array()) {
        let values: Vec<String> = values
            .iter()
            .map(|v| format!("`{}`", toml_value(v)))
            .collect();
        return format!("one of {}", values.join(", "));
    }
    let kinds: Vec<&str> = match property.get("type") {
        Some(serde_json::Value::String(kind)) => vec![kind.as_str()],
        Some(serde_json::Value::Array(kinds)) => kinds.iter().filter_map(|k| k.as_str()).collect(),
        _ => Vec::new(),
    };
    match kinds.iter().find(|kind| **kind != "null") {
        Some(&"array") => {
            let item = property
                .get("items")
                .map(|items| schema_type(items, schema));
            format!("array of {}", plural(item.as_deref().unwrap_or("values")))
        }
        Some(&"object") => {
            let value = property
                .get("additionalProperties")
                .map(|values| schema_type(values, schema));
            format!("table (keys to {})", value.as_deref().unwrap_or("values"))
        }
        Some(&"integer") if property.get("minimum").is_some() => "integer ≥ 0".to_string(),
        Some(kind) => kind.to_string(),
        None => "any".to_string(),
    }
}

/// `string` → `strings`; a compound type (`one of ...`, `array of ...`) unchanged.
fn plural(kind: &str) -> String {
    if kind.contains(' ') {
        kind.to_string()
    } else {
        format!("{kind}s")
    }
}

/// A JSON value written as TOML: `"ALL"`, `["ALL"]`, `{}`, `10000`.
fn toml_value(value: &serde_json::Value) -> String {
    match value {
        serde_json::Value::Array(items) => {
            let items: Vec<String> = items.iter().map(toml_value).collect();
            format!("[{}]", items.join(", "))
        }
        serde_json::Value::Object(entries) if entries.is_empty() => "{}".to_string(),
        other => other.to_string(),
    }
}

/// The command-line reference: every flag of `urdf_validate` (hidden ones left out), by heading, then the
/// subcommands.
pub fn cli_reference() -> String {
    let mut command = Args::command();
    command.build();
    let mut out = format!("# Command-line reference\n\n{GENERATED}\n");
    let about = command
        .get_long_about()
        .or(command.get_about())
        .map(|text| text.to_string())
        .unwrap_or_default();
    let _ = writeln!(out, "{}\n", escape_html(&about));
    let _ = writeln!(
        out,
        "```text\nurdf_validate [FLAGS] URDF_OR_DIR...\nurdf_validate diff OLD NEW [FLAGS]\nurdf_validate view ROBOT [--port N] [--open] [FLAGS]\nurdf_validate server\nurdf_validate mcp [POLICY FLAGS]\n```\n"
    );
    let _ = writeln!(
        out,
        "Exit codes are on [Exit codes](../getting-started/exit-codes.md).\n"
    );
    let mut headings: Vec<Option<String>> = Vec::new();
    for arg in command.get_arguments() {
        let heading = arg.get_help_heading().map(str::to_string);
        if !arg.is_hide_set() && !headings.contains(&heading) {
            headings.push(heading);
        }
    }
    for heading in headings {
        let title = match &heading {
            Some(title) => title.clone(),
            None => "Options".to_string(),
        };
        let _ = writeln!(out, "## {title}\n");
        for arg in command.get_arguments() {
            if arg.is_hide_set() || arg.get_help_heading().map(str::to_string) != heading {
                continue;
            }
            out.push_str(&argument(arg));
        }
    }
    for (name, help) in [
        ("urdf_validate diff", crate::diff::HELP),
        ("urdf_validate view", crate::view::HELP),
        ("urdf_validate server", crate::server::HELP),
        ("urdf_validate mcp", crate::mcp::HELP),
    ] {
        let _ = writeln!(
            out,
            "## `{name}`\n\n`{name} --help` prints:\n\n```text\n{}\n```\n",
            help.trim_end()
        );
    }
    out
}

/// One argument: its spelling as a heading, then its help, values, default and environment variable.
fn argument(arg: &clap::Arg) -> String {
    let value_names: Vec<String> = arg
        .get_value_names()
        .map(|names| names.iter().map(|name| format!("<{name}>")).collect())
        .unwrap_or_default();
    let takes_value = arg.get_num_args().is_some_and(|n| n.takes_values());
    let mut spelling = Vec::new();
    if let Some(short) = arg.get_short() {
        spelling.push(format!("-{short}"));
    }
    if let Some(long) = arg.get_long() {
        spelling.push(format!("--{long}"));
    }
    let mut title = if spelling.is_empty() {
        value_names.join(" ")
    } else {
        spelling.join(", ")
    };
    if !spelling.is_empty() && takes_value && !value_names.is_empty() {
        title = format!("{title} {}", value_names.join(" "));
    }
    let mut out = format!("### `{title}`\n\n");
    let help = arg
        .get_long_help()
        .or(arg.get_help())
        .map(|help| help.to_string())
        .unwrap_or_default();
    if !help.is_empty() {
        let _ = writeln!(out, "{}\n", escape_html(help.trim_end()));
    }
    let values: Vec<String> = arg
        .get_possible_values()
        .iter()
        .filter(|value| !value.is_hide_set())
        .map(|value| match value.get_help() {
            Some(help) => format!(
                "- `{}`: {}",
                value.get_name(),
                escape_html(&help.to_string())
            ),
            None => format!("- `{}`", value.get_name()),
        })
        .collect();
    if takes_value && !values.is_empty() {
        let _ = writeln!(out, "Values:\n\n{}\n", values.join("\n"));
    }
    let defaults: Vec<String> = arg
        .get_default_values()
        .iter()
        .map(|value| format!("`{}`", value.to_string_lossy()))
        .collect();
    let switch = matches!(
        arg.get_action(),
        clap::ArgAction::SetTrue | clap::ArgAction::SetFalse | clap::ArgAction::Count
    );
    if !defaults.is_empty() && !switch {
        let _ = writeln!(out, "Default: {}.\n", defaults.join(", "));
    }
    if let Some(env) = arg.get_env() {
        let _ = writeln!(out, "Environment variable: `{}`.\n", env.to_string_lossy());
    }
    out
}

/// `<` and `>` outside code spans as entities: help text names elements (`<robot>`) that Markdown would
/// take for HTML tags.
fn escape_html(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut in_code = false;
    for c in text.chars() {
        match c {
            '`' => {
                in_code = !in_code;
                out.push(c);
            }
            '<' if !in_code => out.push_str("&lt;"),
            '>' if !in_code => out.push_str("&gt;"),
            _ => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed book pages are what the binary generates (regenerate with
    /// `cargo run -p urdf-validate-cli -- --write-book-pages docs`), and no rule page is left over.
    #[test]
    fn the_generated_book_pages_are_up_to_date() {
        let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let docs = repo.join("docs");
        let pages = pages(&repo);
        let mut stale = Vec::new();
        for (path, text) in &pages {
            if std::fs::read_to_string(docs.join(path)).ok().as_deref() != Some(text.as_str()) {
                stale.push(path.clone());
            }
        }
        for entry in std::fs::read_dir(docs.join("rules"))
            .into_iter()
            .flatten()
            .flatten()
        {
            let name = format!("rules/{}", entry.file_name().to_string_lossy());
            if !pages.iter().any(|(path, _)| *path == name) {
                stale.push(format!("{name} (no rule has it)"));
            }
        }
        let summary = std::fs::read_to_string(docs.join("SUMMARY.md")).unwrap_or_default();
        for rule in rules::ALL {
            let entry = format!("](rules/{}.md)", rule.page());
            if !summary.contains(&entry) {
                stale.push(format!("SUMMARY.md lacks {entry}"));
            }
        }
        assert!(
            stale.is_empty(),
            "stale book pages {stale:?}: regenerate them with `cargo run -p urdf-validate-cli -- --write-book-pages docs`"
        );
    }

    /// The rule codes `path` raises.
    fn codes(path: &Path) -> Vec<String> {
        let validation = urdf_validator::validate(path, &urdf_validator::Options::default())
            .unwrap_or_else(|error| panic!("{}: {error}", path.display()));
        validation
            .report
            .findings
            .into_iter()
            .map(|finding| finding.rule)
            .collect()
    }

    /// Every folder of [`EXAMPLES`] is a rule's page name and holds either `no-example.md` or a `fail.*`
    /// that raises the rule and a `pass.*` that does not, validated from disk as the command would.
    #[test]
    fn every_failing_example_raises_its_rule_and_its_passing_twin_does_not() {
        let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let mut failures = Vec::new();
        let mut checked = 0;
        for entry in std::fs::read_dir(repo.join(EXAMPLES))
            .expect("examples")
            .flatten()
        {
            let page = entry.file_name().to_string_lossy().to_string();
            let Some(rule) = rules::ALL.iter().find(|rule| rule.page() == page) else {
                failures.push(format!("{page}: no rule has this page"));
                continue;
            };
            if entry.path().join("no-example.md").exists() {
                continue;
            }
            let Some((fail, pass)) = example_files(&repo, rule) else {
                failures.push(format!("{page}: wants fail.* and pass.*, or no-example.md"));
                continue;
            };
            let raised = codes(&fail);
            if !raised.iter().any(|code| code == rule.code) {
                failures.push(format!(
                    "{}: does not raise {} ({raised:?})",
                    fail.display(),
                    rule.code
                ));
            }
            if codes(&pass).iter().any(|code| code == rule.code) {
                failures.push(format!("{}: raises {}", pass.display(), rule.code));
            }
            checked += 1;
        }
        eprintln!("{checked} rule examples checked");
        assert!(checked > 0, "no rule example");
        assert!(failures.is_empty(), "{}", failures.join("\n"));
    }

    #[test]
    fn the_cli_reference_has_every_visible_flag() {
        let reference = cli_reference();
        for arg in Args::command().get_arguments() {
            if let (Some(long), false) = (arg.get_long(), arg.is_hide_set()) {
                assert!(reference.contains(&format!("--{long}")), "--{long}");
            }
        }
        assert!(!reference.contains("### `--write-book-pages"));
    }
}
