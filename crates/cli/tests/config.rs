//! Configuration files, `--select`/`--ignore`, inline suppressions, `--show-config` and
//! `--show-suppressed`, end to end through the binary.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

fn temp_dir() -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "urdf_validate_config_{}_{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::SeqCst)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .env("URDF_VALIDATOR_CACHE_DIR", dir.join(".cache"))
        .output()
        .expect("runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn describe(output: &Output) -> String {
    format!(
        "exit {:?}\n--- stdout ---\n{}\n--- stderr ---\n{}",
        output.status.code(),
        text(&output.stdout),
        text(&output.stderr)
    )
}

fn write(dir: &Path, name: &str, content: &str) -> PathBuf {
    let path = dir.join(name);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).expect("dir");
    }
    std::fs::write(&path, content).expect("write");
    path
}

/// One WARN finding (U201: the moving link `arm` declares no inertial), nothing else: exit 1.
const WARNING: &str = r#"<robot name="warn">
  <link name="base"/>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
  <link name="arm"/>
</robot>
"#;

/// The same robot with a suppression comment before the link.
const SUPPRESSED: &str = r#"<robot name="warn">
  <link name="base"/>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
  <!-- urdf-validate: ignore U201 -->
  <link name="arm"/>
</robot>
"#;

fn exit(output: &Output) -> Option<i32> {
    output.status.code()
}

#[test]
fn the_warning_robot_warns_without_configuration() {
    let dir = temp_dir();
    write(&dir, "robot.urdf", WARNING);
    let out = run_in(&dir, &["robot.urdf", "--no-write"]);
    assert_eq!(exit(&out), Some(1), "{}", describe(&out));
    assert!(text(&out.stdout).contains("U201"), "{}", describe(&out));
}

#[test]
fn a_config_file_next_to_the_robot_ignores_a_rule() {
    let dir = temp_dir();
    write(&dir, "robot.urdf", WARNING);
    write(&dir, "urdf-validate.toml", "ignore = [\"U201\"]\n");
    let out = run_in(&dir, &["robot.urdf", "--no-write"]);
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
    // --no-config reads nothing: the warning is back.
    let out = run_in(&dir, &["robot.urdf", "--no-write", "--no-config"]);
    assert_eq!(exit(&out), Some(1), "{}", describe(&out));
}

#[test]
fn the_nearest_config_in_a_parent_folder_wins_and_pyproject_counts() {
    let dir = temp_dir();
    write(&dir, "robots/deep/robot.urdf", WARNING);
    // Only pyproject.toml at the top: its [tool.urdf-validate] table applies.
    write(
        &dir,
        "pyproject.toml",
        "[project]\nname = \"x\"\n\n[tool.urdf-validate]\nignore = [\"missing-inertial\"]\n",
    );
    let out = run_in(&dir, &["robots/deep/robot.urdf", "--no-write"]);
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
    // A nearer urdf-validate.toml (which ignores nothing) wins over it.
    write(&dir, "robots/urdf-validate.toml", "ignore = []\n");
    let out = run_in(&dir, &["robots/deep/robot.urdf", "--no-write"]);
    assert_eq!(exit(&out), Some(1), "{}", describe(&out));
    // --config names one explicitly.
    let out = run_in(
        &dir,
        &[
            "robots/deep/robot.urdf",
            "--no-write",
            "--config",
            "pyproject.toml",
        ],
    );
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
}

#[test]
fn ignore_and_select_on_the_command_line() {
    let dir = temp_dir();
    write(&dir, "robot.urdf", WARNING);
    let out = run_in(&dir, &["robot.urdf", "--no-write", "--ignore", "U201"]);
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
    let out = run_in(&dir, &["robot.urdf", "--no-write", "--select", "U1,U3"]);
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
    // --select replaces the file's select; --ignore adds to the file's ignore.
    write(&dir, "urdf-validate.toml", "select = [\"U1\"]\n");
    let out = run_in(&dir, &["robot.urdf", "--no-write", "--select", "U2"]);
    assert_eq!(exit(&out), Some(1), "{}", describe(&out));
}

#[test]
fn an_inline_comment_silences_the_finding_and_show_suppressed_lists_it() {
    let dir = temp_dir();
    write(&dir, "robot.urdf", SUPPRESSED);
    let out = run_in(&dir, &["robot.urdf", "--no-write"]);
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
    assert!(!text(&out.stdout).contains("U201"), "{}", describe(&out));

    let out = run_in(&dir, &["robot.urdf", "--no-write", "--show-suppressed"]);
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("[SUPPRESSED]"), "{stdout}");
    assert!(
        stdout.contains("U201 missing-inertial")
            && stdout.contains("urdf-validate: ignore comment (robot.urdf:4)"),
        "{stdout}"
    );

    let out = run_in(
        &dir,
        &[
            "robot.urdf",
            "--no-write",
            "--show-suppressed",
            "--format",
            "json",
        ],
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(report["overall_status"], "PASS");
    assert!(report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .all(|f| f["rule"] != "U201"));
    let suppressed = report["suppressed"].as_array().expect("suppressed[]");
    assert_eq!(suppressed.len(), 1, "{report:#}");
    assert_eq!(suppressed[0]["rule"], "U201");
    assert_eq!(suppressed[0]["line"], 5);
    assert_eq!(
        suppressed[0]["suppressed_by"],
        "urdf-validate: ignore comment (robot.urdf:4)"
    );
    // Without --show-suppressed the JSON has no suppressed[] at all.
    let out = run_in(&dir, &["robot.urdf", "--no-write", "--format", "json"]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert!(report.get("suppressed").is_none(), "{report:#}");
}

#[test]
fn the_fetch_robot_silenced_with_a_file_wide_comment() {
    let fetch = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/robots/fetch/fetch_description/robots/fetch.urdf");
    let Ok(original) = std::fs::read_to_string(&fetch) else {
        assert!(
            std::env::var_os("CI").is_none(),
            "{} is absent under CI",
            fetch.display()
        );
        eprintln!("skipping: {} is absent", fetch.display());
        return;
    };
    let dir = temp_dir();
    let copy = write(&dir, "fetch.urdf", &original);
    // Meshes resolve from the original package.
    let packages = fetch.join("../../..");
    let packages = packages.to_str().unwrap();
    let json = |out: &Output| -> serde_json::Value {
        serde_json::from_slice(&out.stdout).unwrap_or_else(|_| panic!("{}", describe(out)))
    };
    let base = [
        copy.to_str().unwrap(),
        "--no-write",
        "--format",
        "json",
        "--package-path",
        packages,
        "--samples",
        "2000",
    ];
    let out = run_in(&dir, &base);
    let report = json(&out);
    assert_eq!(exit(&out), Some(1), "{}", describe(&out));
    let mut codes: Vec<String> = report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["severity"] == "WARN")
        .map(|f| f["rule"].as_str().unwrap().to_string())
        .collect();
    codes.sort();
    codes.dedup();
    assert!(!codes.is_empty());
    let comment = format!("<!-- urdf-validate: ignore-file {} -->\n", codes.join(", "));
    let with_comment = original.replacen("<robot", &format!("{comment}<robot"), 1);
    std::fs::write(&copy, with_comment).unwrap();
    let out = run_in(&dir, &base);
    let report = json(&out);
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
    assert_eq!(report["overall_status"], "PASS");
    assert!(report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .all(|f| f["rule"] != "U801" && f["severity"] != "WARN"));
}

#[test]
fn an_unused_suppression_is_reported_as_u801() {
    let dir = temp_dir();
    let urdf = SUPPRESSED.replace("ignore U201", "ignore U201, U105");
    write(&dir, "robot.urdf", &urdf);
    let out = run_in(&dir, &["robot.urdf", "--no-write", "--format", "json"]);
    assert_eq!(exit(&out), Some(0), "INFO only: {}", describe(&out));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let unused: Vec<&serde_json::Value> = report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["rule"] == "U801")
        .collect();
    assert_eq!(unused.len(), 1, "{report:#}");
    assert_eq!(unused[0]["severity"], "INFO");
    assert_eq!(unused[0]["name"], "unused-suppression");
    assert_eq!(unused[0]["section"], "schema");
    assert_eq!(unused[0]["line"], 4);
    // The column of `U105` in `  <!-- urdf-validate: ignore U201, U105 -->`.
    assert_eq!(unused[0]["column"], 36);
    assert!(unused[0]["message"].as_str().unwrap().contains("'U105'"));
}

#[test]
fn unknown_codes_are_u802_with_the_closest_code() {
    let dir = temp_dir();
    // In a comment: the misspelt code suppresses nothing, so U201 still warns too.
    let urdf = SUPPRESSED.replace("ignore U201", "ignore U2O1");
    write(&dir, "robot.urdf", &urdf);
    let out = run_in(&dir, &["robot.urdf", "--no-write", "--format", "json"]);
    assert_eq!(exit(&out), Some(1), "{}", describe(&out));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let findings = report["findings"].as_array().unwrap();
    let unknown: Vec<&serde_json::Value> =
        findings.iter().filter(|f| f["rule"] == "U802").collect();
    assert_eq!(unknown.len(), 1, "{report:#}");
    assert_eq!(unknown[0]["severity"], "WARN");
    assert_eq!(unknown[0]["line"], 4);
    assert!(
        unknown[0]["help"].as_str().unwrap().contains("'U201'"),
        "{report:#}"
    );
    assert!(findings.iter().any(|f| f["rule"] == "U201"));

    // In the configuration file: located at the code in the file.
    write(&dir, "robot.urdf", WARNING);
    write(
        &dir,
        "urdf-validate.toml",
        "# settings\nignore = [\"U201\", \"massless-geometri\"]\n",
    );
    let out = run_in(&dir, &["robot.urdf", "--no-write", "--format", "json"]);
    assert_eq!(exit(&out), Some(1), "U802 is a WARN: {}", describe(&out));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let unknown = report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["rule"] == "U802")
        .unwrap_or_else(|| panic!("{report:#}"));
    assert!(unknown["file"]
        .as_str()
        .unwrap()
        .ends_with("urdf-validate.toml"));
    assert_eq!(unknown["line"], 2);
    assert_eq!(unknown["column"], 20);
    assert!(
        unknown["help"]
            .as_str()
            .unwrap()
            .contains("'massless-geometry'"),
        "{unknown:#}"
    );

    // On the command line, in text.
    std::fs::remove_file(dir.join("urdf-validate.toml")).unwrap();
    let out = run_in(&dir, &["robot.urdf", "--no-write", "--ignore", "U201,U10S"]);
    assert_eq!(exit(&out), Some(1), "{}", describe(&out));
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains("'U10S' (on the command line) names no rule"),
        "{stdout}"
    );
}

#[test]
fn severity_overrides_change_the_exit_code() {
    let dir = temp_dir();
    write(&dir, "robot.urdf", WARNING);
    write(&dir, "urdf-validate.toml", "[severity]\nU201 = \"info\"\n");
    let out = run_in(&dir, &["robot.urdf", "--no-write"]);
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
    write(
        &dir,
        "urdf-validate.toml",
        "[severity]\nmissing-inertial = \"critical\"\n",
    );
    let out = run_in(&dir, &["robot.urdf", "--no-write", "--format", "json"]);
    assert_eq!(exit(&out), Some(2), "{}", describe(&out));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let u201 = report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["rule"] == "U201")
        .unwrap();
    assert_eq!(u201["severity"], "CRITICAL");
    assert_eq!(report["overall_status"], "FAIL");
}

#[test]
fn per_file_ignores_match_globs_relative_to_the_config() {
    let dir = temp_dir();
    write(&dir, "legacy/old.urdf", WARNING);
    write(&dir, "new/robot.urdf", WARNING);
    write(
        &dir,
        "urdf-validate.toml",
        "[per-file-ignores]\n\"legacy/*.urdf\" = [\"U201\"]\n",
    );
    let out = run_in(&dir, &["legacy/old.urdf", "--no-write"]);
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
    let out = run_in(&dir, &["new/robot.urdf", "--no-write"]);
    assert_eq!(exit(&out), Some(1), "{}", describe(&out));
}

#[test]
fn a_malformed_config_is_an_error_naming_file_line_and_key() {
    let dir = temp_dir();
    write(&dir, "robot.urdf", WARNING);
    write(
        &dir,
        "urdf-validate.toml",
        "ignore = [\"U105\"]\nselct = [\"U2\"]\n",
    );
    let out = run_in(&dir, &["robot.urdf", "--no-write"]);
    assert_eq!(exit(&out), Some(2), "{}", describe(&out));
    let stderr = text(&out.stderr);
    assert!(
        stderr.contains("urdf-validate.toml:2:1: invalid configuration: unknown field `selct`"),
        "{stderr}"
    );
    assert!(stderr.contains("did you mean 'select'?"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");

    // TOML syntax errors, wrong types and bad values are located too.
    for (config, line, what) in [
        ("ignore = [\"U105\"\n\n", 1, ""),
        ("samples = \"many\"\n", 1, "key `samples`"),
        ("[severity]\nU201 = \"loud\"\n", 2, "key `severity.U201`"),
        (
            "seed = 1\nrobot-type = \"wheeld\"\n",
            2,
            "did you mean 'wheeled'?",
        ),
        (
            "[per-file-ignores]\n\"a[\" = [\"U201\"]\n",
            2,
            "invalid glob",
        ),
        (
            "seed = 1\nup-axis = \"w\"\n",
            2,
            "up-axis 'w' is not an axis",
        ),
    ] {
        write(&dir, "urdf-validate.toml", config);
        let out = run_in(&dir, &["robot.urdf", "--no-write"]);
        assert_eq!(exit(&out), Some(2), "{config}: {}", describe(&out));
        let stderr = text(&out.stderr);
        assert!(
            stderr.contains(&format!("urdf-validate.toml:{line}:")) && stderr.contains(what),
            "{config}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn show_config_prints_each_setting_and_its_origin() {
    let dir = temp_dir();
    write(&dir, "robot.urdf", WARNING);
    write(
        &dir,
        "urdf-validate.toml",
        "ignore = [\"U105\"]\nsamples = 500\npackage-path = [\"deps\"]\nup-axis = \"-y\"\n\n[severity]\nU201 = \"info\"\n",
    );
    let out = run_in(
        &dir,
        &[
            "robot.urdf",
            "--show-config",
            "--seed",
            "3",
            "--ignore",
            "U207",
        ],
    );
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
    let stdout = text(&out.stdout);
    let line_of = |key: &str| -> String {
        stdout
            .lines()
            .find(|l| l.starts_with(&format!("{key} ")))
            .unwrap_or_else(|| panic!("no {key} line in\n{stdout}"))
            .to_string()
    };
    let config = dir.join("urdf-validate.toml");
    let config = config.display();
    assert!(
        stdout.starts_with(&format!("# configuration file: {config}")),
        "{stdout}"
    );
    assert!(line_of("select").contains("# default"), "{stdout}");
    let ignore = line_of("ignore");
    assert!(
        ignore.contains("[\"U105\", \"U207\"]")
            && ignore.contains(&format!("{config}:1"))
            && ignore.contains("command line"),
        "{ignore}"
    );
    assert!(
        line_of("samples").contains("500") && line_of("samples").contains(&format!("{config}:2"))
    );
    assert!(line_of("seed").contains("3") && line_of("seed").contains("# command line"));
    assert!(line_of("payload-mass").contains("# default"));
    let up_axis = line_of("up-axis");
    assert!(
        up_axis.contains("\"-y\"") && up_axis.contains(&format!("{config}:4")),
        "{up_axis}"
    );
    assert!(line_of("severity.U201").contains("\"info\""));
    let package_path = line_of("package-path");
    assert!(
        package_path.contains(&dir.join("deps").display().to_string())
            && package_path.contains(&format!("{config}:3")),
        "{package_path}"
    );
    // Nothing was validated.
    assert!(!stdout.contains("[OVERALL]"), "{stdout}");
    // --no-config: everything is a default.
    let out = run_in(&dir, &["robot.urdf", "--show-config", "--no-config"]);
    let stdout = text(&out.stdout);
    assert!(stdout.starts_with("# configuration file: none"), "{stdout}");
    assert!(!stdout.contains("urdf-validate.toml"), "{stdout}");
}

#[test]
fn config_defaults_reach_the_analyses_and_flags_win() {
    let dir = temp_dir();
    write(&dir, "robot.urdf", WARNING);
    write(&dir, "urdf-validate.toml", "robot-type = \"arm_only\"\n");
    let json = |args: &[&str]| -> serde_json::Value {
        let out = run_in(&dir, args);
        serde_json::from_slice(&out.stdout).unwrap_or_else(|_| panic!("{}", describe(&out)))
    };
    let report = json(&["robot.urdf", "--no-write", "--format", "json"]);
    assert_eq!(report["robot_type"], "arm_only", "{report:#}");
    assert_eq!(report["robot_type_confidence"], "exact");
    let report = json(&[
        "robot.urdf",
        "--no-write",
        "--format",
        "json",
        "--robot-type",
        "wheeled",
    ]);
    assert_eq!(report["robot_type"], "wheeled", "{report:#}");
}

#[test]
fn skip_xacro_libraries_leaves_out_macro_files() {
    let dir = temp_dir();
    write(
        &dir,
        "macros.xacro",
        "<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n  <xacro:macro name=\"m\" params=\"\"><link name=\"a\"/></xacro:macro>\n</robot>\n",
    );
    let out = run_in(&dir, &["macros.xacro", "--no-write"]);
    assert_eq!(
        exit(&out),
        Some(2),
        "a macro library alone is no robot: {}",
        describe(&out)
    );
    let out = run_in(
        &dir,
        &["macros.xacro", "--no-write", "--skip-xacro-libraries"],
    );
    assert_eq!(exit(&out), Some(0), "{}", describe(&out));
}
