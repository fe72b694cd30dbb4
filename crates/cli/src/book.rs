//! The book's generated pages (`urdf_validate --write-book-pages docs`): one page per rule and its index
//! (from the rule registry) and the command-line reference (from the clap definition of [`Args`] and the
//! subcommands' help). A test fails when the committed pages under `docs/` differ from these.

use std::fmt::Write as _;
use std::path::Path;

use clap::CommandFactory;
use urdf_validator::diagnostics::rules;

use crate::args::Args;

const GENERATED: &str = "<!-- Generated from crates/cli/src/args.rs by `urdf_validate --write-book-pages docs`; a test fails when this file is stale. -->\n";

/// Every generated page: `(path below docs/, Markdown)`.
pub fn pages() -> Vec<(String, String)> {
    let mut pages = rules::book_pages();
    pages.push(("reference/cli.md".to_string(), cli_reference()));
    pages
}

/// Write [`pages`] below `dir` and remove rule pages under `dir/rules/` that no rule has any more.
pub fn write_pages(dir: &Path) -> std::io::Result<Vec<String>> {
    let pages = pages();
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
        let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs");
        let pages = pages();
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
