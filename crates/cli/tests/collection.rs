//! The collection page: validating a folder with `--format html` also writes `index.html`, `index.json`
//! and `index.md` — every input with its verdict, counts by severity and rule, and a link to its report.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn run(cwd: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .current_dir(cwd)
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("urdf_validate runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("collection-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A PASS robot, the same robot with an elbow too weak to hold it (FAIL), and a file that is not XML,
/// two of them in a subfolder.
fn three_robots(dir: &Path) {
    let good = std::fs::read_to_string(
        common::repo_root().join("examples/robots/mobile_manipulator.urdf"),
    )
    .unwrap();
    std::fs::create_dir_all(dir.join("sub dir")).unwrap();
    std::fs::write(dir.join("good.urdf"), &good).unwrap();
    let weak = good.replacen("effort=\"60.0\"", "effort=\"0.6\"", 1);
    assert_ne!(weak, good, "the example's elbow effort changed");
    std::fs::write(dir.join("sub dir/weak.urdf"), weak).unwrap();
    std::fs::write(dir.join("sub dir/broken.urdf"), "<robot name='x'><link").unwrap();
}

#[test]
fn a_folder_with_format_html_gets_a_collection_page() {
    let dir = scratch("folder");
    three_robots(&dir.join("robots"));
    let out = run(&dir, &["robots", "--format", "html", "--quiet"]);
    assert_eq!(out.status.code(), Some(2), "a FAIL and an unreadable file");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("Collection page: robots/index.html"),
        "{stderr}"
    );

    let index = read_json(&dir.join("robots/index.json"));
    let robots = index["robots"].as_array().unwrap();
    assert_eq!(robots.len(), 3, "{index:#}");
    let row = |file: &str| {
        robots
            .iter()
            .find(|r| r["file"] == file)
            .unwrap_or_else(|| panic!("no row for {file}: {index:#}"))
    };
    let good = row("robots/good.urdf");
    assert_eq!(good["status"], "PASS");
    assert_eq!(good["dof"], 8);
    assert_eq!(good["report"], "good_validation.html");
    let weak = row("robots/sub dir/weak.urdf");
    assert_eq!(weak["status"], "FAIL");
    assert_eq!(weak["worst_joint"], "elbow_joint");
    assert!(weak["worst_joint_margin"].as_f64().unwrap() < 1.0);
    assert_eq!(weak["rules"]["U701"], 1, "{weak:#}");
    assert_eq!(weak["report"], "sub dir/weak_validation.html");
    let broken = row("robots/sub dir/broken.urdf");
    assert_eq!(broken["status"], "ERROR");
    assert!(broken["error"].as_str().unwrap().contains("broken.urdf"));
    assert_eq!(index["totals"]["by_status"]["PASS"], 1);
    assert_eq!(index["totals"]["by_status"]["FAIL"], 1);
    assert_eq!(index["totals"]["by_status"]["ERROR"], 1);
    let u701 = index["totals"]["by_rule"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["rule"] == "U701")
        .expect("U701 counted");
    assert_eq!(
        (u701["findings"].as_u64(), u701["robots"].as_u64()),
        (Some(1), Some(1))
    );

    // Every link of the page reaches its report; the Markdown links them too (space encoded).
    let html = std::fs::read_to_string(dir.join("robots/index.html")).unwrap();
    for link in ["good_validation.html", "sub%20dir/weak_validation.html"] {
        assert!(
            html.contains(&format!("href=\"{link}\"")),
            "{link} not linked"
        );
        let target = dir.join("robots").join(link.replace("%20", " "));
        assert!(target.is_file(), "{} missing", target.display());
        assert!(
            html.contains(&format!("href=\"{link}#view3d\"")),
            "{link}'s view not linked"
        );
        let report = std::fs::read_to_string(&target).unwrap();
        assert!(report.contains("id=\"view3d\""), "{link} has no 3-D view");
    }
    assert!(html.contains("id=\"chart-rules\""), "the rules bar chart");
    let markdown = std::fs::read_to_string(dir.join("robots/index.md")).unwrap();
    assert!(
        markdown.contains("(sub%20dir/weak_validation.html)"),
        "{markdown}"
    );
    assert!(markdown.contains("| FAIL |"), "{markdown}");
}

#[test]
fn output_dir_holds_the_page_and_links_reach_the_reports() {
    let dir = scratch("output-dir");
    three_robots(&dir.join("robots"));
    let out = run(
        &dir,
        &[
            "robots/good.urdf",
            "robots/sub dir/weak.urdf",
            "--format",
            "html,json",
            "--output-dir",
            "out/reports",
            "--quiet",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    let index = read_json(&dir.join("out/reports/index.json"));
    let links: Vec<&str> = index["robots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["report"].as_str().unwrap())
        .collect();
    assert_eq!(links, ["good_validation.html", "weak_validation.html"]);
}

#[test]
fn one_file_or_no_html_writes_no_collection_page() {
    let dir = scratch("single");
    three_robots(&dir.join("robots"));
    run(&dir, &["robots/good.urdf", "--format", "html", "--quiet"]);
    assert!(dir.join("robots/good_validation.html").is_file());
    assert!(!dir.join("robots/index.html").exists());
    run(&dir, &["robots", "--format", "sarif", "--quiet"]);
    assert!(!dir.join("robots/index.html").exists());
    assert!(!dir.join("robots/index.json").exists());
}

/// On the reference robots: each row says what the robot's own JSON report says.
#[test]
fn rows_agree_with_each_report() {
    let Some(shared) = common::shared_robots() else {
        return;
    };
    let dir = scratch("shared");
    let out = run(
        &dir,
        &[
            shared.to_str().unwrap(),
            "--format",
            "html,json",
            "--output-dir",
            "out",
            "--quiet",
        ],
    );
    assert!(out.status.code().is_some());
    let index = read_json(&dir.join("out/index.json"));
    assert_eq!(index["root"], shared.display().to_string());
    let robots = index["robots"].as_array().unwrap();
    assert!(robots.len() >= 10, "{} rows", robots.len());
    let mut findings = 0;
    for row in robots {
        let link = row["report"].as_str().expect("a report link");
        let report = read_json(&dir.join("out").join(link.replace(".html", ".json")));
        let status = match report["overall_status"].as_str().unwrap() {
            "N/A" => "PASS",
            other => other,
        };
        assert_eq!(row["status"], status, "{link}");
        assert_eq!(row["robot_name"], report["robot_name"], "{link}");
        let count = report["findings"].as_array().unwrap().len() as u64;
        let counted: u64 = ["critical", "fail", "warn", "info"]
            .iter()
            .map(|s| row["findings"][s].as_u64().unwrap())
            .sum();
        assert_eq!(counted, count, "{link}");
        findings += count;
        assert_eq!(
            row["total_mass_kg"], report["statics"]["total_mass"],
            "{link}"
        );
        assert_eq!(
            row["stability_margin_mm"], report["stability"]["margin_mm"],
            "{link}"
        );
    }
    let totals: u64 = index["totals"]["by_rule"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["findings"].as_u64().unwrap())
        .sum();
    assert_eq!(totals, findings);
}

/// In headless Chromium, clicking a header sorts the robots table by it (numbers numerically with missing
/// values last, text by name), and a second click reverses it (`view_browser/sort_table.mjs`).
#[test]
fn clicking_a_header_sorts_the_table() {
    let Some((chromium, node)) = common::browser_tools() else {
        return;
    };
    let dir = scratch("sort");
    three_robots(&dir.join("robots"));
    let light = std::fs::read_to_string(dir.join("robots/good.urdf"))
        .unwrap()
        .replacen("<mass value=\"45.0\"/>", "<mass value=\"4.5\"/>", 1);
    std::fs::write(dir.join("robots/light.urdf"), light).unwrap();
    run(&dir, &["robots", "--format", "html", "--quiet"]);
    let page = dir.join("robots/index.html");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/view_browser/sort_table.mjs");
    let out = Command::new(node)
        .arg(script)
        .arg(chromium)
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    let result: Value = serde_json::from_str(text.trim()).unwrap_or_else(|e| {
        panic!(
            "driver output {text:?} ({e}); stderr {}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    assert!(result.get("error").is_none(), "{result:#}");
    assert_eq!(result["console"], serde_json::json!([]), "{result:#}");
    let column = |title: &str| {
        result["columns"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["title"] == title)
            .unwrap_or_else(|| panic!("no column {title}: {result:#}"))
            .clone()
    };
    let keys = |click: &Value| -> Vec<String> {
        click["keys"]
            .as_array()
            .unwrap()
            .iter()
            .map(|k| k.as_str().unwrap().to_string())
            .collect()
    };
    // Mass: light (≈21 kg), good (61.7 kg), weak (61.7 kg), then the unreadable file's missing value.
    let mass = column("Mass (kg)");
    assert_eq!(mass["first"]["sort"], "ascending");
    let ascending = keys(&mass["first"]);
    let numbers: Vec<f64> = ascending
        .iter()
        .filter(|k| !k.is_empty())
        .map(|k| k.parse().unwrap())
        .collect();
    assert_eq!(numbers.len(), 3, "{ascending:?}");
    assert!(numbers.windows(2).all(|w| w[0] <= w[1]), "{ascending:?}");
    assert_eq!(
        ascending.last().map(String::as_str),
        Some(""),
        "missing values last: {ascending:?}"
    );
    assert_eq!(mass["second"]["sort"], "descending");
    let descending = keys(&mass["second"]);
    assert_eq!(descending[0], ascending[2], "{descending:?}");
    assert_eq!(
        descending.last().map(String::as_str),
        Some(""),
        "{descending:?}"
    );
    // Text: file names in order, then reversed.
    let file = column("File");
    let mut sorted = keys(&file["first"]);
    sorted.sort();
    assert_eq!(keys(&file["first"]), sorted);
    sorted.reverse();
    assert_eq!(keys(&file["second"]), sorted);
}
