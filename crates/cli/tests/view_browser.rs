//! `urdf_validate view` in a real browser: the command serves PR2, ANYmal and a MuJoCo Menagerie model;
//! headless Chromium (SwiftShader WebGL), driven over the DevTools protocol by `view_browser/drive.mjs`
//! (Node, no package), draws each with its centre of mass and support polygon. The screenshot is
//! measured: not blank, robot pixels in the middle of the frame, the overlay colours present. A finding is
//! clicked with real mouse events and its link or joint is highlighted; a slider pose comes back from the
//! server. Also: the server answers only its routes, only to 127.0.0.1, and never serves a file.
//!
//! Needs Chromium (`URDF_VALIDATOR_CHROMIUM`, else `chromium` on PATH) and Node (`node`); without them, or
//! without ../shared/robots, the tests skip with a message, except under `CI`, where they fail.
//! `URDF_VALIDATOR_VIEW_SCREENSHOTS=DIR` copies the screenshots there (docs/view-*.png).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

/// The URL in the command's first line.
fn url_in(line: &str) -> String {
    line.split_whitespace()
        .find(|w| w.starts_with("http://127.0.0.1:"))
        .unwrap_or_else(|| panic!("no URL in {line:?}"))
        .to_string()
}

/// A running `urdf_validate view`, stopped on drop.
struct Server {
    child: Child,
    url: String,
}

impl Server {
    fn start(robot: &Path) -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
            .args(["view", "--port", "0"])
            .arg(robot)
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .unwrap();
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        Server {
            child,
            url: url_in(&line),
        }
    }

    fn port(&self) -> u16 {
        self.url
            .trim_end_matches('/')
            .rsplit(':')
            .next()
            .unwrap()
            .parse()
            .unwrap()
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The server's whole answer (head and body) to `raw`.
fn answer(port: u16, raw: &str) -> String {
    let mut stream = TcpStream::connect(("127.0.0.1", port)).unwrap();
    stream.write_all(raw.as_bytes()).unwrap();
    let mut answer = String::new();
    stream.read_to_string(&mut answer).unwrap();
    answer
}

/// `/version` once it is no longer `from` (polled for up to 5 s).
fn version_after(port: u16, host: &str, from: &str) -> String {
    let mut version = String::new();
    for _ in 0..50 {
        std::thread::sleep(std::time::Duration::from_millis(100));
        version = request(port, &format!("GET /version HTTP/1.1\r\n{host}\r\n\r\n")).1;
        if version != from {
            break;
        }
    }
    version
}

/// The driver's JSON for `url`.
fn drive(chromium: &Path, node: &Path, url: &str, png: &Path, extra: &[&str]) -> serde_json::Value {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/view_browser/drive.mjs");
    let out = Command::new(node)
        .arg(script)
        .arg(chromium)
        .arg(url)
        .arg(png)
        .args(extra)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    let value: serde_json::Value = serde_json::from_str(text.trim()).unwrap_or_else(|e| {
        panic!(
            "driver output {text:?} ({e}); stderr {}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    assert!(value.get("error").is_none(), "{value:#}");
    value
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("urdf-view-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Renders `robot` live and checks the screenshot; returns the driver's result.
fn renders(robot: &Path, name: &str, extra: &[&str]) -> Option<serde_json::Value> {
    let (chromium, node) = common::browser_tools()?;
    let server = Server::start(robot);
    let dir = scratch(name);
    let png = dir.join(format!("view-{name}.png"));
    let result = drive(&chromium, &node, &server.url, &png, extra);
    let console = result["console"].as_array().unwrap();
    assert!(console.is_empty(), "{name}: console messages {console:?}");
    let shot = &result["screenshot"];
    let f = |key: &str| shot[key].as_f64().unwrap();
    // A blank frame is the background and the grid: two or three colours, nothing off them.
    assert!(
        f("distinctColours") > 5.0 && f("robotFraction") > 0.02,
        "{name}: the frame is nearly blank: {shot}"
    );
    assert!(
        f("middleFraction") > 0.05,
        "{name}: no robot in the middle of the frame: {shot}"
    );
    let counts = &shot["counts"];
    assert!(
        counts["com"].as_u64().unwrap() > 20,
        "{name}: no COM marker drawn: {shot}"
    );
    let polygon =
        counts["polygonStable"].as_u64().unwrap() + counts["polygonUnstable"].as_u64().unwrap();
    assert!(polygon > 50, "{name}: no support polygon drawn: {shot}");
    if let Some(out) = std::env::var_os("URDF_VALIDATOR_VIEW_SCREENSHOTS") {
        let clicked = dir.join(format!("view-{name}-clicked.png"));
        for shot in [&png, &clicked].into_iter().filter(|p| p.is_file()) {
            std::fs::copy(shot, Path::new(&out).join(shot.file_name().unwrap())).unwrap();
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    Some(result)
}

#[test]
fn pr2_is_drawn_a_finding_click_highlights_its_joint_and_a_slider_pose_returns() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let robot = robots.join("pr2/pr2_description/robots/pr2.urdf");
    let Some(result) = renders(&robot, "pr2", &["--click", "--poses", "5"]) else {
        return;
    };
    let click = &result["click"];
    assert!(!click.is_null(), "PR2 has findings about joints");
    assert_eq!(click["highlighted"], click["expected"], "{click}");
    assert_eq!(
        click["selected"].as_str(),
        Some(&*click["index"].to_string())
    );
    assert!(
        click["highlightAfter"].as_u64().unwrap() > click["highlightBefore"].as_u64().unwrap() + 50,
        "the highlight colour appears on the robot: {click}"
    );
    let times = result["poseMs"].as_array().unwrap();
    assert_eq!(times.len(), 5, "every slider move came back: {result}");
}

#[test]
fn anymal_is_drawn_with_its_support_polygon() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    renders(
        &robots.join("anymal/anymal_b_simple_description/urdf/anymal.urdf"),
        "anymal",
        &[],
    );
}

#[test]
fn a_menagerie_model_is_drawn() {
    let robot = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../urdf-validator/tests/data/menagerie/unitree_go2/go2.xml");
    renders(&robot, "go2", &[]);
}

/// One raw request to the server: the status line and the body.
fn request(port: u16, raw: &str) -> (String, String) {
    let answer = answer(port, raw);
    let status = answer.lines().next().unwrap_or_default().to_string();
    let body = answer
        .split("\r\n\r\n")
        .nth(1)
        .unwrap_or_default()
        .to_string();
    (status, body)
}

#[test]
fn the_server_answers_its_routes_only_to_127_0_0_1_and_serves_no_file() {
    let dir = scratch("routes");
    let urdf = dir.join("r.urdf");
    std::fs::write(&urdf, "<robot name=\"r\"><link name=\"a\"/></robot>").unwrap();
    let server = Server::start(&urdf);
    let port = server.port();
    let host = format!("Host: 127.0.0.1:{port}");
    let (status, body) = request(port, &format!("GET /version HTTP/1.1\r\n{host}\r\n\r\n"));
    assert!(status.contains("200"), "{status}");
    assert_eq!(body, "1");
    for path in ["/r.urdf", "/../../etc/passwd", "/scene.json/../r.urdf"] {
        let (status, _) = request(port, &format!("GET {path} HTTP/1.1\r\n{host}\r\n\r\n"));
        assert!(status.contains("404"), "{path}: {status}");
    }
    let (status, _) = request(port, "GET / HTTP/1.1\r\nHost: evil.example:80\r\n\r\n");
    assert!(status.contains("403"), "{status}");
    let (status, _) = request(
        port,
        &format!("POST /pose HTTP/1.1\r\n{host}\r\nContent-Length: 3\r\n\r\n[1]"),
    );
    assert!(status.contains("400"), "{status}");
    let (status, body) = request(
        port,
        &format!("POST /pose HTTP/1.1\r\n{host}\r\nContent-Length: 2\r\n\r\n{{}}"),
    );
    assert!(
        status.contains("200") && body.contains("\"links\""),
        "{status} {body}"
    );

    // The file changes: the version moves on and the scene is the new robot's.
    std::fs::write(&urdf, "<robot name=\"r2\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint></robot>").unwrap();
    let version = version_after(port, &host, "1");
    assert_eq!(version, "2", "the change was seen");
    let (_, scene) = request(port, &format!("GET /scene.json HTTP/1.1\r\n{host}\r\n\r\n"));
    assert!(scene.contains("\"robot\":\"r2\""), "{scene}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_file_that_does_not_validate_is_served_with_why_and_loads_once_fixed() {
    let dir = scratch("broken");
    let urdf = dir.join("r.urdf");
    std::fs::write(&urdf, "<robot name=\"r\"><link name=\"a\">").unwrap();
    let server = Server::start(&urdf);
    let port = server.port();
    let host = format!("Host: 127.0.0.1:{port}");
    let (status, page) = request(port, &format!("GET / HTTP/1.1\r\n{host}\r\n\r\n"));
    assert!(
        status.contains("200") && page.contains("UrdfView.mount"),
        "{status}"
    );
    let (status, body) = request(port, &format!("GET /scene.json HTTP/1.1\r\n{host}\r\n\r\n"));
    assert!(status.contains("422"), "{status}");
    assert!(
        body.contains("r.urdf"),
        "the message names the file: {body}"
    );
    let (status, _) = request(
        port,
        &format!("POST /pose HTTP/1.1\r\n{host}\r\nContent-Length: 2\r\n\r\n{{}}"),
    );
    assert!(status.contains("409"), "{status}");

    // Fixed: the version moves on and the scene is the robot's.
    std::fs::write(&urdf, "<robot name=\"fixed\"><link name=\"a\"/></robot>").unwrap();
    let version = version_after(port, &host, "1");
    assert_eq!(version, "2", "the fix was seen");
    let answer = answer(port, &format!("GET /scene.json HTTP/1.1\r\n{host}\r\n\r\n"));
    assert!(answer.contains("X-Scene-Version: 2\r\n"), "{answer:.300}");
    assert!(answer.contains("\"robot\":\"fixed\""), "{answer:.300}");
    drop(server);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--open` hands the printed URL to the system's opener (`xdg-open` here; a stand-in on PATH records it).
#[cfg(target_os = "linux")]
#[test]
fn open_hands_the_url_to_the_system_browser() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch("open");
    let urdf = dir.join("r.urdf");
    std::fs::write(&urdf, "<robot name=\"r\"><link name=\"a\"/></robot>").unwrap();
    let opened = dir.join("opened");
    let opener = dir.join("xdg-open");
    std::fs::write(
        &opener,
        format!("#!/bin/sh\necho \"$1\" > '{}'\n", opened.display()),
    )
    .unwrap();
    std::fs::set_permissions(&opener, std::fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!(
        "{}:{}",
        dir.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(["view", "--port", "0", "--open"])
        .arg(&urdf)
        .env("PATH", path)
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let mut got = String::new();
    for _ in 0..50 {
        got = std::fs::read_to_string(&opened).unwrap_or_default();
        if !got.is_empty() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    let _ = child.kill();
    let _ = child.wait();
    assert_eq!(got.trim(), url_in(&line), "the opener got the URL printed");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_missing_file_is_refused_before_serving() {
    let output = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(["view", "--port", "0", "no/such/robot.urdf"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("no/such/robot.urdf: no such file"),
        "{stderr}"
    );
}

#[test]
fn the_pr2_html_report_carries_the_view_under_3_mb_and_draws_it_from_file() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let Some((chromium, node)) = common::browser_tools() else {
        return;
    };
    let dir = scratch("report");
    let page = dir.join("pr2.html");
    let status = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .arg(robots.join("pr2/pr2_description/robots/pr2.urdf"))
        .args(["--format", "html", "--output"])
        .arg(&page)
        .status()
        .unwrap();
    assert!(status.code().is_some_and(|c| c <= 2), "{status}");
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(
        html.len() <= 3_000_000,
        "the PR2 report is {} bytes",
        html.len()
    );
    assert!(html.contains("id=\"view3d-scene\"") && html.contains("id=\"stability-plot\""));
    assert!(html.contains("@media print{section.view3d{display:none}}"));
    let png = dir.join("view-pr2-report.png");
    let result = drive(
        &chromium,
        &node,
        &format!("file://{}", page.display()),
        &png,
        &["--click"],
    );
    assert!(result["console"].as_array().unwrap().is_empty(), "{result}");
    let shot = &result["screenshot"];
    assert!(shot["middleFraction"].as_f64().unwrap() > 0.05, "{shot}");
    assert!(shot["counts"]["com"].as_u64().unwrap() > 20, "{shot}");
    assert_eq!(result["click"]["highlighted"], result["click"]["expected"]);
    eprintln!("PR2 report: {} bytes", html.len());
    let _ = std::fs::remove_dir_all(&dir);
}
