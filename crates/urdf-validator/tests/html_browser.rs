//! The HTML report in a real browser: headless Chromium renders the PR2's report to a PNG, logs no console
//! message, and its DOM holds the plots and one row per finding; the same for the deep section (MuJoCo) of
//! a cart that falls onto its boom, with its tilt plot (needs MuJoCo, see `common::mujoco_python`).
//!
//! Chromium is found as `URDF_VALIDATOR_CHROMIUM`, else `chromium`, `chromium-browser`, `google-chrome` or
//! `google-chrome-stable` on PATH (Debian: `apt-get install chromium`; `.ci/run` installs it). Without it
//! (or without ../shared/robots) the test skips with a message, except under `CI` where it fails.
//! `URDF_VALIDATOR_HTML_SCREENSHOT=docs/report-pr2.png` also copies the screenshot there
//! (`URDF_VALIDATOR_HTML_DEEP_SCREENSHOT` the cart's).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::render::html::render_html;
use urdf_validator::{validate, Options};

const WIDTH: u32 = 1280;
const HEIGHT: u32 = 2400;

fn chromium() -> Option<PathBuf> {
    const VAR: &str = "URDF_VALIDATOR_CHROMIUM";
    let found = std::env::var_os(VAR).map(PathBuf::from).or_else(|| {
        let path = std::env::var_os("PATH")?;
        std::env::split_paths(&path)
            .flat_map(|dir| {
                [
                    "chromium",
                    "chromium-browser",
                    "google-chrome",
                    "google-chrome-stable",
                ]
                .map(|name| dir.join(name))
            })
            .find(|p| p.is_file())
    });
    match found {
        Some(p) => Some(p),
        None if std::env::var_os("CI").is_some() => panic!(
            "Chromium is absent under CI (apt-get install chromium, or set {VAR}); .ci/run installs it"
        ),
        None => {
            eprintln!("skipping: no chromium on PATH (apt-get install chromium, or set {VAR})");
            None
        }
    }
}

/// A scratch directory for one run (removed on drop).
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("urdf-html-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Runs headless Chromium on `page` with its own profile, logging to stderr; `extra` picks the output.
fn headless(browser: &Path, scratch: &Path, page: &Path, extra: &[&str]) -> Output {
    let url = format!("file://{}", page.display());
    Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--hide-scrollbars",
            "--force-device-scale-factor=1",
            "--enable-logging=stderr",
            "--v=0",
        ])
        .arg(format!(
            "--user-data-dir={}",
            scratch.join("profile").display()
        ))
        .arg(format!("--window-size={WIDTH},{HEIGHT}"))
        .args(extra)
        .arg(url)
        .output()
        .expect("chromium runs")
}

/// Console messages Chromium logged (`CONSOLE(line)] "message"` or `Uncaught ...`).
fn console_lines(stderr: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(stderr)
        .lines()
        .filter(|l| l.contains("CONSOLE") || l.contains("Uncaught"))
        .map(str::to_string)
        .collect()
}

/// Width and height from a PNG's IHDR chunk.
fn png_size(png: &[u8]) -> Option<(u32, u32)> {
    if png.len() < 24 || &png[..8] != b"\x89PNG\r\n\x1a\n" || &png[12..16] != b"IHDR" {
        return None;
    }
    let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
    Some((be(&png[16..20]), be(&png[20..24])))
}

#[test]
fn the_console_check_sees_a_console_error() {
    // The check below is only worth something if a page that logs is caught.
    let Some(browser) = chromium() else {
        return;
    };
    let scratch = Scratch::new("console");
    let page = scratch.0.join("noisy.html");
    std::fs::write(
        &page,
        "<!DOCTYPE html><title>t</title><script>console.error('html-report-check')</script>",
    )
    .unwrap();
    let out = headless(&browser, &scratch.0, &page, &["--dump-dom"]);
    let lines = console_lines(&out.stderr);
    assert!(
        lines.iter().any(|l| l.contains("html-report-check")),
        "console.error not seen in Chromium's log:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `page` as headless Chromium parses it (the DOM) and draws it (a PNG of the window's size, with content:
/// a blank page compresses to a few kB), with no console message in either run.
fn dom_and_screenshot(browser: &Path, scratch: &Scratch, page: &Path) -> (String, Vec<u8>) {
    let out = headless(browser, &scratch.0, page, &["--dump-dom"]);
    assert!(out.status.success(), "chromium --dump-dom failed: {out:?}");
    let dom = String::from_utf8_lossy(&out.stdout).into_owned();
    let console = console_lines(&out.stderr);
    assert!(
        console.is_empty(),
        "console messages:\n{}",
        console.join("\n")
    );
    let shot = page.with_extension("png");
    let out = headless(
        browser,
        &scratch.0,
        page,
        &[&format!("--screenshot={}", shot.display())],
    );
    assert!(
        out.status.success(),
        "chromium --screenshot failed: {out:?}"
    );
    let console = console_lines(&out.stderr);
    assert!(
        console.is_empty(),
        "console messages:\n{}",
        console.join("\n")
    );
    let png = std::fs::read(&shot).expect("a screenshot was written");
    assert_eq!(png_size(&png), Some((WIDTH, HEIGHT)));
    assert!(
        png.len() > 100_000,
        "the screenshot is nearly blank ({} bytes)",
        png.len()
    );
    (dom, png)
}

#[test]
fn the_pr2_report_renders_in_headless_chromium() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let Some(browser) = chromium() else {
        return;
    };
    let urdf = robots.join("pr2/pr2_description/robots/pr2.urdf");
    let options = Options {
        resolver: PackageResolver::from_env(Vec::new()),
        ..Options::default()
    };
    let validation = validate(&urdf, &options).expect("the PR2 validates");
    let report = &validation.report;
    let html = render_html(&validation);
    let scratch = Scratch::new("pr2");
    let page = scratch.0.join("pr2_report.html");
    std::fs::write(&page, &html).unwrap();

    // The DOM as the browser parsed it: the plots, both arms, one row per finding.
    let (dom, png) = dom_and_screenshot(&browser, &scratch, &page);
    let arms = report.workspace.as_ref().map_or(0, |w| w.arms.len());
    assert!(arms >= 2, "the PR2 has two arms");
    let mut ids = vec![
        "stability-plot".to_string(),
        "statics-plot".to_string(),
        "findings".to_string(),
    ];
    for k in 0..arms {
        ids.push(format!("reach-side-{k}"));
        ids.push(format!("reach-top-{k}"));
    }
    for id in ids {
        assert!(
            dom.contains(&format!("id=\"{id}\"")),
            "{id} missing from the DOM"
        );
    }
    assert_eq!(
        dom.matches("<tr id=\"finding-").count(),
        report.findings.len(),
        "one table row per finding"
    );
    if let Some(copy) = std::env::var_os("URDF_VALIDATOR_HTML_SCREENSHOT") {
        std::fs::write(copy, png).unwrap();
    }
}

/// The deep section of the cart that falls onto its boom (`tests/data/deep/boom_cart.urdf`, MuJoCo's pass
/// running by itself): its card, its panel and the tilt plot with one vertex per sample of the trace.
#[test]
fn the_deep_section_renders_in_headless_chromium() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let Some(browser) = chromium() else {
        return;
    };
    // A relative path, as a user would type it: the page shows it.
    let urdf = Path::new("tests/data/deep/boom_cart.urdf");
    let options = Options {
        deep: urdf_validator::analysis::deep::DeepOptions {
            python: Some(python),
            ..Default::default()
        },
        ..Options::default()
    };
    let validation = validate(urdf, &options).expect("the cart validates");
    let drop = validation
        .report
        .deep
        .as_ref()
        .and_then(|d| d.drop_test.as_ref())
        .expect("a drop test");
    assert_eq!(drop.fallen_onto, ["boom"]);
    let html = render_html(&validation);
    let scratch = Scratch::new("deep");
    let page = scratch.0.join("boom_cart_report.html");
    std::fs::write(&page, &html).unwrap();
    let (dom, png) = dom_and_screenshot(&browser, &scratch, &page);
    for needle in [
        "id=\"deep\"",
        "href=\"#deep\"",
        "id=\"drop-tilt-plot\"",
        "<span class=\"name fallen\">boom</span>",
    ] {
        assert!(dom.contains(needle), "{needle} missing from the DOM");
    }
    let at = dom.find("<polyline class=\"tilt fail\" points=\"").unwrap();
    let points = dom[at..].split('"').nth(3).unwrap();
    assert_eq!(points.split(' ').count(), drop.tilt_trace.len());
    assert!(!html.contains(&*std::env::current_dir().unwrap().to_string_lossy()));
    if let Some(copy) = std::env::var_os("URDF_VALIDATOR_HTML_DEEP_SCREENSHOT") {
        std::fs::write(copy, png).unwrap();
    }
}
