//! Command-line flags.

use std::path::PathBuf;

use clap::{Parser, ValueEnum};

/// Physics-aware URDF validator: structure, inertia and references, with file:line:col for every finding.
///
/// Writes `<name>_validation.json` beside each input (or in --output-dir). Exit code: 0 PASS, 1 WARN,
/// 2 FAIL, UNKNOWN or unreadable input.
#[derive(Debug, Parser)]
#[command(name = "urdf_validate", version, about, long_about)]
pub struct Args {
    /// URDF files, or directories (every *.urdf below them is validated).
    #[arg(value_name = "URDF_OR_DIR")]
    pub inputs: Vec<PathBuf>,

    /// Directory for the JSON reports (default: beside each input).
    #[arg(long, value_name = "DIR")]
    pub output_dir: Option<PathBuf>,

    /// Extra folder holding ROS packages, for package:// URIs (repeatable; searched before
    /// ROS_PACKAGE_PATH and AMENT_PREFIX_PATH).
    #[arg(long, value_name = "DIR")]
    pub package_path: Vec<PathBuf>,

    /// What to print on stdout: the text report, or the JSON report(s).
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,

    /// List every finding, each with its source snippet.
    #[arg(short, long)]
    pub verbose: bool,

    /// Print only the summary table.
    #[arg(short, long, conflicts_with = "verbose")]
    pub quiet: bool,

    /// Do not write JSON report files.
    #[arg(long)]
    pub no_write: bool,

    /// Colour: auto (a terminal without NO_COLOR set), always, never.
    #[arg(long, value_enum, default_value_t = ColorChoice::Auto)]
    pub color: ColorChoice,

    /// Files validated in parallel (default: one per core).
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,

    /// Explain a rule (code such as U205, or name) and exit.
    #[arg(long, value_name = "CODE")]
    pub explain: Option<String>,

    /// List all rules and exit.
    #[arg(long)]
    pub list_rules: bool,

    /// Print the rules reference (docs/rules.md) and exit.
    #[arg(long, hide = true)]
    pub list_rules_markdown: bool,

    /// Print the JSON Schema of the report and exit.
    #[arg(long)]
    pub json_schema: bool,

    /// Print the report reference (docs/json_schema.md) and exit.
    #[arg(long, hide = true)]
    pub json_schema_markdown: bool,
}

/// Output format on stdout.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Human-readable report.
    Text,
    /// The JSON report (an array when several files are given).
    Json,
}

/// When to colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ColorChoice {
    /// Colour on a terminal, unless NO_COLOR is set.
    Auto,
    /// Always colour.
    Always,
    /// Never colour.
    Never,
}
