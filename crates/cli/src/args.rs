//! Command-line flags.

use std::path::PathBuf;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Parser, ValueEnum};
use urdf_validator::analysis::classify::RobotType;
use urdf_validator::analysis::pose::PoseKind;
use urdf_validator::analysis::profiles::Simulator;

/// Physics-aware URDF validator: structure, inertia and references, with file:line:col for every finding.
///
/// Writes `<name>_validation.json` beside each input (or in --output-dir). Exit code: 0 PASS, 1 WARN,
/// 2 FAIL, UNKNOWN or unreadable input.
#[derive(Clone, Debug, Parser)]
#[command(
    name = "urdf_validate",
    version,
    about,
    long_about,
    after_help = "AI agents: `urdf_validate mcp` serves the validator over the Model Context Protocol (stdio; \
                  see https://urdf-validator.github.io/urdf-validator/integrations/mcp.html and `urdf_validate mcp --help`). A file named mcp is given as ./mcp. \
                  `urdf_validate diff OLD NEW` compares two descriptions or reports (`urdf_validate diff --help`). \
                  `urdf_validate view ROBOT` draws the robot in 3-D in a browser (`urdf_validate view --help`). \
                  Editors: `urdf_validate server` is the language server (LSP over stdio; `urdf_validate server --help`)."
)]
pub struct Args {
    /// URDF, xacro, SDFormat or MJCF files, or directories (every *.urdf, *.sdf and *.world below them,
    /// every *.xml with a <mujoco> root, and every *.xacro with a <robot> root that builds a robot), and
    /// xacro arguments as `name:=value`.
    #[arg(value_name = "URDF_OR_DIR")]
    pub inputs: Vec<PathBuf>,

    /// A xacro argument (repeatable): NAME=VALUE or NAME:=VALUE, as `name:=value` on the command line does.
    #[arg(long, value_name = "NAME=VALUE")]
    pub xacro_arg: Vec<String>,

    /// The model of an SDFormat world to analyse (default: its first non-static model with joints).
    #[arg(long, value_name = "NAME")]
    pub model: Option<String>,

    /// Leave out named .xacro files that build no robot (macro libraries), as directory inputs do: for
    /// hooks that pass every changed file (pre-commit). Exit 0 when nothing else is left.
    #[arg(long)]
    pub skip_xacro_libraries: bool,

    /// Print the expanded URDF of each xacro input and exit (a stand-in for the `xacro` command).
    #[arg(long)]
    pub expand_only: bool,

    /// Directory for the JSON reports (default: beside each input).
    #[arg(long, value_name = "DIR")]
    pub output_dir: Option<PathBuf>,

    /// Extra folder holding ROS packages, for package:// URIs and xacro's $(find pkg) (repeatable;
    /// searched before ROS_PACKAGE_PATH and AMENT_PREFIX_PATH).
    #[arg(long, value_name = "DIR")]
    pub package_path: Vec<PathBuf>,

    /// Untrusted input (pull requests, downloads): read files only below the roots (the input's folder
    /// tree, or its git work tree; --package-path and --root folders; symlinks resolved first), only
    /// regular files, and no environment variable unless --allow-env names it. What is refused is a
    /// finding (U013). See SECURITY.md.
    #[arg(long)]
    pub untrusted: bool,

    /// With --untrusted: another folder files may be read from (repeatable).
    #[arg(long, value_name = "DIR", requires = "untrusted")]
    pub root: Vec<PathBuf>,

    /// With --untrusted: an environment variable $(env), $(optenv) and the package path look-ups may
    /// read (repeatable; default none).
    #[arg(long, value_name = "NAME", requires = "untrusted")]
    pub allow_env: Vec<String>,

    /// Joint configuration for statics: zero (clamped into limits), limits (upper limits), custom
    /// (--joint-angles), home (SRDF group_state; without an SRDF, an MJCF model's keyframe of that --state name),
    /// worst (largest torque per joint over seeded samples), key:NAME (an MJCF model's <key name>).
    #[arg(long, value_name = "POSE", default_value = "zero", value_parser = PoseKind::parse)]
    pub pose: PoseKind,

    /// Joint values for --pose custom: "j1=0.5,j2=30deg" (radians or metres; `deg` for degrees).
    #[arg(long, value_name = "ANGLES")]
    pub joint_angles: Option<String>,

    /// SRDF for --pose home and self-collision (default: <stem>.srdf, else <robot name>.srdf, beside the
    /// URDF or in ../srdf/).
    #[arg(long, value_name = "FILE")]
    pub srdf: Option<PathBuf>,

    /// group_state name for --pose home.
    #[arg(long, value_name = "NAME", default_value = "home")]
    pub state: String,

    /// Samples per arm for the workspace (reach, task, orientation, self-collision), and for --pose worst.
    #[arg(long, value_name = "N", default_value_t = urdf_validator::DEFAULT_SAMPLES)]
    pub samples: usize,

    /// Seed of the sampling (same seed, same report).
    #[arg(long, value_name = "S", default_value_t = urdf_validator::DEFAULT_SEED)]
    pub seed: u64,

    /// Payload carried at --payload-link, kg: torques and verdicts include it.
    #[arg(long, value_name = "KG")]
    pub payload_mass: Option<f64>,

    /// Link carrying the payload (default: the end of the longest actuated chain).
    #[arg(long, value_name = "LINK")]
    pub payload_link: Option<String>,

    /// Declare the robot category (the structural heuristic still runs; a disagreement is an INFO, U730).
    #[arg(long, value_name = "TYPE", value_parser = robot_types())]
    pub robot_type: Option<RobotType>,

    /// The root frame's axis that points up, when the model is not z-up (REP 103): x, y, z, with an
    /// optional sign (-y). The model is turned so that axis points up, which turns gravity for every
    /// analysis; the structure's own guess (U731) is then not reported.
    #[arg(long, value_name = "AXIS", value_parser = urdf_validate_session::request::parse_up_axis, allow_hyphen_values = true)]
    pub up_axis: Option<urdf_validator::model::UpAxis>,

    /// Ground-contact links for the support polygon, comma-separated: "foot_l,foot_r".
    #[arg(long, value_name = "LINKS", value_delimiter = ',')]
    pub contact_links: Option<Vec<String>>,

    /// First link of an arm chain (with --arm-tip; repeat the pair for each arm); validated against
    /// the tree.
    #[arg(long, value_name = "LINK", requires = "arm_tip")]
    pub arm_root: Vec<String>,

    /// End-effector link of an arm chain (with --arm-root; the n-th tip goes with the n-th root).
    #[arg(long, value_name = "LINK", requires = "arm_root")]
    pub arm_tip: Vec<String>,

    /// Task reachability: pick_from_ground (0.05 m above the ground), pick_from_table (0.75 m),
    /// push_button (1.0 m), custom (--height).
    #[arg(long, value_name = "TASK", value_parser = ["pick_from_ground", "pick_from_table", "push_button", "custom"])]
    pub task: Option<String>,

    /// Target height above the ground for --task custom, metres.
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub height: Option<f64>,

    /// Tool orientation to reach: top_down, side, "r,p,y" (radians) or "qw,qx,qy,qz"; PASS when at least
    /// 5% of samples (at the task height, with --task) meet it.
    #[arg(long, value_name = "ORIENTATION", allow_hyphen_values = true)]
    pub orientation: Option<String>,

    /// Tolerance on the approach direction for --orientation, degrees.
    #[arg(long, value_name = "DEG", default_value_t = 30.0)]
    pub orientation_tolerance: f64,

    /// The tool's approach axis in the arm's tip frame: x, y, z, -x, -y, -z or "ax,ay,az" (default: from
    /// the hand towards its fingers, else z).
    #[arg(long, value_name = "AXIS", allow_hyphen_values = true)]
    pub approach_axis: Option<String>,

    /// Print the per-arm workspace table.
    #[arg(long)]
    pub detailed: bool,

    /// Output formats, comma-separated: text (terminal), json (the report, on stdout when listed without
    /// text), sarif, junit, html (files `<name>_validation.sarif|.xml|.html` beside each input or in
    /// --output-dir; a folder or several inputs with html also get the collection page index.html, with
    /// index.json and index.md), github (annotations; automatic when GITHUB_ACTIONS=true).
    #[arg(
        long,
        value_enum,
        value_name = "LIST",
        value_delimiter = ',',
        default_value = "text"
    )]
    pub format: Vec<Format>,

    /// Write the one --format to FILE instead, every input in one document (one SARIF run, one JUnit file
    /// with a suite per robot, a JSON array); `-` for stdout.
    #[arg(long, value_name = "FILE")]
    pub output: Option<PathBuf>,

    /// List every finding, each with its source snippet.
    #[arg(short, long)]
    pub verbose: bool,

    /// Print only the summary table.
    #[arg(short, long, conflicts_with = "verbose")]
    pub quiet: bool,

    /// Do not write report files (JSON, and the SARIF, JUnit and HTML files of --format).
    #[arg(long)]
    pub no_write: bool,

    /// Time each phase (load, parse, model, assets, checks, statics, classify, stability, workspace, …):
    /// `timings_ms` in the JSON report and a one-line breakdown after the text report.
    #[arg(long)]
    pub timings: bool,

    /// Do not read or write the mesh cache (hulls of meshes loaded in earlier runs, kept in
    /// $URDF_VALIDATOR_CACHE_DIR, else $XDG_CACHE_HOME/urdf-validator, else ~/.cache/urdf-validator).
    #[arg(long)]
    pub no_cache: bool,

    /// Also load the robot into MuJoCo (from PyPI: pip install "urdf-validator[mujoco]"; the Python of
    /// URDF_VALIDATOR_PYTHON, else the python3 beside this binary, else python3 on PATH): what MuJoCo
    /// refuses or changes, its gravity torques and centre of mass against statics, and a 2-second drop
    /// test. Runs by itself when the stability margin is negative.
    #[arg(long)]
    pub deep: bool,

    /// Simulator load profiles, repeatable or comma-separated: what that simulator's URDF importer does
    /// to this file (links it merges or drops, masses it refuses or invents, elements it ignores), as
    /// findings U750–U761; no simulator needs to be installed.
    #[arg(long, value_name = "NAME", value_delimiter = ',', value_parser = simulators())]
    pub simulator: Vec<Simulator>,

    /// Seconds each file may take; a file still running then is reported as not finished (naming the
    /// stage it was in, exit 2) and a batch goes on with the next file. 0: no limit.
    #[arg(long, value_name = "SECONDS", default_value_t = 60.0)]
    pub timeout: f64,

    /// Colour: auto (a terminal without NO_COLOR set), always, never.
    #[arg(long, value_enum, default_value_t = ColorChoice::Auto)]
    pub color: ColorChoice,

    /// Threads (default: one per core): files validated in parallel, and the workspace sampling of each.
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,

    /// Only these rules report (codes, names, code prefixes such as U2, or ALL; comma-separated):
    /// replaces `select` of the configuration file.
    #[arg(long, value_name = "CODES", value_delimiter = ',')]
    pub select: Option<Vec<String>>,

    /// These rules never report (codes, names or prefixes; comma-separated): added to `ignore` of the
    /// configuration file. Ignored findings leave the status and the exit code.
    #[arg(long, value_name = "CODES", value_delimiter = ',')]
    pub ignore: Vec<String>,

    /// Use this configuration file (urdf-validate.toml, or a pyproject.toml with [tool.urdf-validate])
    /// for every input, instead of the nearest one found from each input's folder upwards.
    #[arg(long, value_name = "FILE", conflicts_with = "no_config")]
    pub config: Option<PathBuf>,

    /// Read no configuration file.
    #[arg(long)]
    pub no_config: bool,

    /// Print the settings in effect (for the first input, else the current folder) and where each came
    /// from (file:line, command line or default), then exit.
    #[arg(long)]
    pub show_config: bool,

    /// Evaluate the robot with a declared value changed, the file untouched (repeatable):
    /// `joint.NAME.effort|lower|upper|velocity=V`, `link.NAME.mass=V`, `link.NAME.com=x,y,z`,
    /// `payload.mass=V`. The report lists each override with the value the file declares.
    #[arg(long = "override", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,

    /// Overrides from a TOML file: `[joint.NAME] effort = 80`, `[link.NAME] mass = 12` / `com = [x, y, z]`,
    /// `[payload] mass = 2` (--override on the command line wins).
    #[arg(long, value_name = "FILE.toml")]
    pub override_file: Option<PathBuf>,

    /// Apply the safe fixes of the findings (those that change nothing a simulator computes) to the files
    /// the user edits (a xacro source for xacro input), then validate again and report what is left.
    /// Files are written atomically; a file that changed since it was read is not overwritten.
    #[arg(long)]
    pub fix: bool,

    /// With --fix or --diff, also the unsafe fixes (mass, inertia, limits, scale, effort change), and
    /// edits of files outside the input's package and --package-path folders.
    #[arg(long)]
    pub unsafe_fixes: bool,

    /// Print the fixes as a unified diff and write nothing (exit 1 when there is something to fix, else 0).
    #[arg(long, conflicts_with = "fix")]
    pub diff: bool,

    /// With --fix or --diff: write the --override/--override-file values into the files (as unsafe edits
    /// the user asked for: applied without --unsafe-fixes). Without it, --override cannot be combined with
    /// --fix or --diff (the fixes would be computed for values the file does not hold).
    #[arg(long)]
    pub from_overrides: bool,

    /// Report only the findings that baseline FILE (written by --write-baseline, or an earlier
    /// `<name>_validation.json`) does not hold: the status and the exit code follow the new ones alone;
    /// baseline entries nothing matches any more are listed as stale.
    #[arg(long, value_name = "FILE")]
    pub baseline: Option<PathBuf>,

    /// Write every finding that counts (of every input; baselined ones too) to baseline FILE, keyed by
    /// rule, element and message without its numbers (not by line); the exit code is then 0 unless an
    /// input could not be read or FILE written.
    #[arg(long, value_name = "FILE")]
    pub write_baseline: Option<PathBuf>,

    /// Also list the findings that the configuration or inline `urdf-validate: ignore` comments
    /// suppress (marked as suppressed; `suppressed` in the JSON). They still do not count.
    #[arg(long)]
    pub show_suppressed: bool,

    /// Explain a rule (code such as U205, or name) and exit.
    #[arg(long, value_name = "CODE")]
    pub explain: Option<String>,

    /// List all rules and exit.
    #[arg(long)]
    pub list_rules: bool,

    /// Print the rules reference as one Markdown page and exit.
    #[arg(long, hide = true)]
    pub list_rules_markdown: bool,

    /// Write the book's generated pages (the rule pages and the command-line reference) below DIR
    /// (`docs`) and exit.
    #[arg(long, hide = true, value_name = "DIR")]
    pub write_book_pages: Option<PathBuf>,

    /// Print the JSON Schema of the report and exit.
    #[arg(long)]
    pub json_schema: bool,

    /// Print the report reference (docs/json_schema.md) and exit.
    #[arg(long, hide = true)]
    pub json_schema_markdown: bool,
}

/// `--robot-type` values: the library's categories, each with its help line.
fn robot_types() -> impl TypedValueParser<Value = RobotType> {
    let help = |robot_type: RobotType| match robot_type {
        RobotType::Wheeled => "Drives on wheels (may carry arms)",
        RobotType::GroundVehicle => "Drives on wheels, no manipulator",
        RobotType::Legged => "Walks on legs",
        RobotType::Quadruped => "Four legs",
        RobotType::Humanoid => "Two legs and arms",
        RobotType::ArmOnly => "Fixed-base arm",
        RobotType::Aerial => "Flies",
        RobotType::Object => {
            "Nothing moves (a table, a tray, a mug): no stability or workspace to check"
        }
        RobotType::Unknown => "Anything else",
    };
    let values = RobotType::ALL.map(|t| PossibleValue::new(t.as_str()).help(help(t)));
    PossibleValuesParser::new(values)
        .try_map(|name| urdf_validate_session::request::parse_robot_type(&name, "--robot-type"))
}

/// `--simulator` values: the library's load profiles, each with its help line.
fn simulators() -> impl TypedValueParser<Value = Simulator> {
    let help = |simulator: Simulator| match simulator {
        Simulator::Mujoco => "MuJoCo's URDF reader and compiler",
        Simulator::Gazebo => "Gazebo (sdformat's URDF to SDF converter)",
        Simulator::Pybullet => "PyBullet's loadURDF",
        Simulator::Drake => "Drake's URDF parser",
        Simulator::Isaac => "Isaac Sim's URDF importer",
    };
    let values = Simulator::ALL.map(|s| PossibleValue::new(s.name()).help(help(s)));
    PossibleValuesParser::new(values)
        .try_map(|name| urdf_validate_session::request::parse_simulator(&name, "--simulator"))
}

/// `--format` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Human-readable report on stdout.
    Text,
    /// The JSON report: always written as a file (unless --no-write); on stdout when listed without
    /// text: an object for one named file, an array for directories and several inputs.
    Json,
    /// SARIF 2.1.0 for code scanning: `<name>_validation.sarif`.
    Sarif,
    /// JUnit XML, one test case per check: `<name>_validation.xml`.
    Junit,
    /// GitHub Actions annotations on stdout, and the step summary when GITHUB_STEP_SUMMARY is set.
    Github,
    /// An HTML page: `<name>_validation.html`.
    Html,
}

impl Format {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Format::Text => "text",
            Format::Json => "json",
            Format::Sarif => "sarif",
            Format::Junit => "junit",
            Format::Github => "github",
            Format::Html => "html",
        }
    }

    /// The extension of its report file (`None`: a terminal format).
    pub fn extension(self) -> Option<&'static str> {
        match self {
            Format::Json => Some("json"),
            Format::Sarif => Some("sarif"),
            Format::Junit => Some("xml"),
            Format::Html => Some("html"),
            Format::Text | Format::Github => None,
        }
    }
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
