//! `urdf_validate mcp`: the binary spoken to as an MCP client does, newline-delimited JSON-RPC over its
//! stdin and stdout.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{self, Receiver};
use std::time::{Duration, Instant};

use serde_json::{json, Value};

/// Longest wait for one answer (a debug build validating with few samples takes well under this).
const WAIT: Duration = Duration::from_secs(120);

/// A running `urdf_validate mcp` and the lines it writes on stdout.
struct Server {
    child: Child,
    stdin: Option<ChildStdin>,
    lines: Receiver<String>,
    next_id: u64,
}

impl Server {
    /// Start the server in `dir`, allowed to read the repository's example robots, and initialise the
    /// session.
    fn start(dir: &Path) -> Server {
        let examples = common::repo_root().join("examples");
        let temp = std::env::temp_dir();
        let roots = [
            "--root".as_ref(),
            examples.as_os_str(),
            "--root".as_ref(),
            temp.as_os_str(),
        ];
        Server::start_with(dir, &roots)
    }

    /// Start the server in `dir` with `args` (`--root DIR`, ...) and initialise the session.
    fn start_with(dir: &Path, args: &[&std::ffi::OsStr]) -> Server {
        Server::start_as(dir, args, json!({}))
    }

    /// [`Server::start_with`], the client declaring `capabilities`.
    fn start_as(dir: &Path, args: &[&std::ffi::OsStr], capabilities: Value) -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
            .arg("mcp")
            .args(args)
            .env("URDF_MCP_CANARY", "CANARYENVmcp47")
            .current_dir(dir)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("starts");
        let stdin = child.stdin.take();
        let stdout = child.stdout.take().expect("stdout");
        let (send, lines) = mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines() {
                let Ok(line) = line else { break };
                if send.send(line).is_err() {
                    break;
                }
            }
        });
        let mut server = Server {
            child,
            stdin,
            lines,
            next_id: 0,
        };
        let init = server.request(
            "initialize",
            json!({
                "protocolVersion": "2025-06-18",
                "capabilities": capabilities,
                "clientInfo": {"name": "mcp-test", "version": "0"}
            }),
        );
        assert_eq!(
            init["result"]["serverInfo"]["name"], "urdf_validator",
            "{init}"
        );
        assert!(
            init["result"]["capabilities"]["tools"].is_object(),
            "{init}"
        );
        server.send(&json!({"jsonrpc": "2.0", "method": "notifications/initialized"}));
        server
    }

    fn send(&mut self, message: &Value) {
        let stdin = self.stdin.as_mut().expect("stdin open");
        writeln!(stdin, "{message}").expect("write");
        stdin.flush().expect("flush");
    }

    /// Send a request; its id.
    fn ask(&mut self, method: &str, params: Value) -> u64 {
        self.next_id += 1;
        let id = self.next_id;
        self.send(&json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        id
    }

    /// The next response (notifications skipped).
    fn response(&mut self) -> Value {
        let deadline = Instant::now() + WAIT;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            let line = self
                .lines
                .recv_timeout(left)
                .expect("an answer in time, on stdout");
            let message: Value = serde_json::from_str(&line)
                .unwrap_or_else(|e| panic!("stdout holds only JSON-RPC, got {line:?}: {e}"));
            if message.get("id").is_some() {
                return message;
            }
        }
    }

    /// Wait for the server's `roots/list` request and answer it with `folders` as `file://` roots.
    fn answer_roots(&mut self, folders: &[&Path]) {
        let request = self.response();
        assert_eq!(
            request["method"], "roots/list",
            "the server asks for the roots: {request}"
        );
        let roots: Vec<Value> = folders
            .iter()
            .map(|folder| json!({"uri": format!("file://{}", folder.display()), "name": "work"}))
            .collect();
        self.send(&json!({"jsonrpc": "2.0", "id": request["id"], "result": {"roots": roots}}));
    }

    fn request(&mut self, method: &str, params: Value) -> Value {
        let id = self.ask(method, params);
        let response = self.response();
        assert_eq!(response["id"], id, "{response}");
        response
    }

    /// `tools/call`: the result.
    fn call(&mut self, tool: &str, arguments: Value) -> Value {
        let response = self.request("tools/call", json!({"name": tool, "arguments": arguments}));
        assert!(response.get("error").is_none(), "a tool result: {response}");
        response["result"].clone()
    }

    /// Close stdin; the exit status within the wait.
    fn close(mut self) -> std::process::ExitStatus {
        drop(self.stdin.take());
        let deadline = Instant::now() + Duration::from_secs(20);
        loop {
            if let Some(status) = self.child.try_wait().expect("wait") {
                return status;
            }
            if Instant::now() > deadline {
                let _ = self.child.kill();
                panic!("the server did not exit when stdin closed");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

fn example_robot() -> String {
    common::repo_root()
        .join("examples/robots/mobile_manipulator.urdf")
        .display()
        .to_string()
}

fn error_text(result: &Value) -> String {
    assert_eq!(result["isError"], true, "an error result: {result}");
    result["content"][0]["text"]
        .as_str()
        .expect("text")
        .to_string()
}

#[test]
fn a_session_lists_validates_answers_and_ends_with_stdin() {
    let dir = std::env::temp_dir();
    let mut server = Server::start(&dir);

    let tools = server.request("tools/list", json!({}));
    let names: Vec<&str> = tools["result"]["tools"]
        .as_array()
        .expect("tools")
        .iter()
        .map(|t| t["name"].as_str().expect("name"))
        .collect();
    for name in [
        "validate_urdf",
        "validate_urdf_string",
        "check_pick_task",
        "run_pick_task",
        "run_pick_sweep",
        "fix_urdf",
        "list_rules",
        "explain_rule",
    ] {
        assert!(names.contains(&name), "{name} in {names:?}");
    }
    let validate = &tools["result"]["tools"][0];
    let properties = &validate["inputSchema"]["properties"];
    for argument in ["path", "xml", "base_dir", "urdf_path"] {
        assert!(properties.get(argument).is_some(), "{argument}: {validate}");
    }
    assert!(
        validate["inputSchema"]["properties"]["robot_type"]["enum"]
            .as_array()
            .is_some_and(|values| values.contains(&json!("wheeled"))),
        "robot_type lists the CLI's values: {validate}"
    );

    // The report as structured content, the verdict and findings as text.
    let result = server.call(
        "validate_urdf",
        json!({"path": example_robot(), "samples": 300}),
    );
    assert_eq!(result["isError"], false, "{result}");
    let report = &result["structuredContent"];
    assert_eq!(report["overall_status"], "PASS", "{report}");
    assert_eq!(report["robot_name"], "mobile_manipulator");
    let text = result["content"][0]["text"].as_str().expect("text");
    assert!(text.starts_with("mobile_manipulator: PASS"), "{text}");
    // Inline XML, and a finding with its rule and position in the text.
    let result = server.call(
        "validate_urdf",
        json!({"xml": "<robot name='dup'><link name='a'/><link name='a'/></robot>"}),
    );
    let text = result["content"][0]["text"].as_str().expect("text");
    assert!(text.starts_with("dup: FAIL"), "{text}");
    assert!(text.contains("CRITICAL U"), "{text}");
    assert!(text.contains("robot.urdf:1:"), "{text}");
    assert!(error_text(&server.call("validate_urdf", json!({}))).contains("missing path"));

    // An MJCF keyframe as the pose, as --pose key:NAME takes it.
    let mjcf =
        "<mujoco><worldbody><body name='arm'><joint name='j'/><geom size='0.1' pos='0.2 0 0'/>\
                </body></worldbody><keyframe><key name='up' qpos='1'/></keyframe></mujoco>";
    let result = server.call(
        "validate_urdf",
        json!({"xml": mjcf, "samples": 300, "pose": "key:up"}),
    );
    assert_eq!(result["isError"], false, "{result}");
    assert_eq!(
        result["structuredContent"]["statics"]["pose"], "key:up",
        "{result}"
    );

    // The CLI's flags reach the analysis.
    let result = server.call(
        "validate_urdf",
        json!({"urdf_path": example_robot(), "samples": 300, "task": "pick_from_table"}),
    );
    let workspace = &result["structuredContent"]["workspace"];
    assert_eq!(workspace["samples"], 300, "{workspace}");
    assert!(
        workspace["task_target_height_m"].is_number(),
        "the task was analysed: {workspace}"
    );

    let result = server.call(
        "run_pick_task",
        json!({
            "urdf_path": example_robot(),
            "target_position": [0.5, 0.0, 0.75],
            "target_orientation": "top_down",
            "object_mass_kg": 0.5,
            "samples": 300
        }),
    );
    assert_eq!(result["isError"], false, "{result}");
    let response = &result["structuredContent"];
    assert_eq!(
        response["task_type"], "pick",
        "defaults to pick: {response}"
    );
    let checks: Vec<&str> = response["sub_checks"]
        .as_array()
        .expect("sub_checks")
        .iter()
        .map(|c| c["name"].as_str().expect("name"))
        .collect();
    assert_eq!(
        checks,
        [
            "reach",
            "reach_orientation",
            "payload_strength",
            "stability_during_reach",
            "self_collision"
        ]
    );
    assert!(
        ["PASS", "FAIL", "UNKNOWN"].contains(&response["overall_status"].as_str().expect("status"))
    );

    let result = server.call(
        "run_pick_sweep",
        json!({
            "requests": [
                {"urdf_path": example_robot(), "target_position": [0.4, 0.0, 0.8]},
                {"urdf_path": "/nonexistent/robot.urdf", "target_position": [0.4, 0.0, 0.8]}
            ],
            "samples": 200
        }),
    );
    let responses = result["structuredContent"]["responses"]
        .as_array()
        .expect("responses");
    assert_eq!(responses.len(), 2);
    assert_eq!(responses[1]["sub_checks"][0]["name"], "urdf_load");

    let result = server.call("explain_rule", json!({"code": "U205"}));
    assert_eq!(
        result["structuredContent"]["name"],
        "inertia-not-positive-definite"
    );
    let result = server.call("list_rules", json!({}));
    assert!(
        result["structuredContent"]["rules"]
            .as_array()
            .expect("rules")
            .len()
            > 50
    );

    // Errors are results naming what was wrong; the server goes on.
    let missing = dir.join("no_such_robot.urdf").display().to_string();
    let message = error_text(&server.call("validate_urdf", json!({ "urdf_path": missing })));
    assert!(message.contains(&missing), "{message}");
    assert!(
        message.contains("expected a URDF or xacro file"),
        "{message}"
    );
    let message = error_text(&server.call(
        "validate_urdf",
        json!({"urdf_path": example_robot(), "pose": "sideways"}),
    ));
    assert!(message.contains("sideways"), "{message}");
    let message = error_text(&server.call(
        "validate_urdf",
        json!({"urdf_path": example_robot(), "samples": "many"}),
    ));
    assert!(message.contains("samples"), "{message}");
    let message = error_text(&server.call(
        "validate_urdf",
        json!({"urdf_path": example_robot(), "sample": 10}),
    ));
    assert!(message.contains("did you mean 'samples'"), "{message}");
    let message = error_text(&server.call("explain_rule", json!({"code": "U9999"})));
    assert!(message.contains("no rule 'U9999'"), "{message}");
    let message = error_text(&server.call(
        "validate_urdf_string",
        json!({"urdf_xml": "<robot name='x'><link name='a'/>"}),
    ));
    assert!(message.contains("robot.urdf"), "{message}");

    // A xacro file with its arguments.
    let xacro = dir.join(format!("mcp_test_{}.urdf.xacro", std::process::id()));
    std::fs::write(
        &xacro,
        r#"<robot name="x" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="base" default="base_link"/>
  <link name="$(arg base)"/>
</robot>
"#,
    )
    .expect("write xacro");
    let result = server.call(
        "validate_urdf",
        json!({"urdf_path": xacro, "xacro_args": {"base": "chassis"}}),
    );
    let _ = std::fs::remove_file(&xacro);
    assert_eq!(
        result["structuredContent"]["links"][0]["name"], "chassis",
        "{result}"
    );

    let unknown = server.request(
        "tools/call",
        json!({"name": "solve_target", "arguments": {}}),
    );
    assert!(unknown["error"].is_object(), "{unknown}");

    let result = server.call(
        "validate_urdf_string",
        json!({"urdf_xml": "<robot name='one'><link name='base'/></robot>", "base_dir": dir}),
    );
    assert_eq!(result["structuredContent"]["robot_name"], "one", "{result}");

    assert!(server.close().success());
}

#[test]
fn a_long_validation_does_not_hold_up_other_calls() {
    let mut server = Server::start(&std::env::temp_dir());
    let slow = server.ask(
        "tools/call",
        json!({"name": "validate_urdf", "arguments": {"urdf_path": example_robot(), "samples": 2000000}}),
    );
    let quick = server.ask(
        "tools/call",
        json!({"name": "explain_rule", "arguments": {"code": "U701"}}),
    );
    let first = server.response();
    assert_eq!(first["id"], quick, "the quick call answered first: {first}");
    let second = server.response();
    assert_eq!(second["id"], slow);
    assert_eq!(second["result"]["isError"], false, "{second}");
    assert!(server.close().success());
}

/// Calls at once on robots with meshes (PR2, Fetch, ANYmal, Spot): each is answered with its report, well
/// before the 60 s `--timeout` (a batch of files with meshes once waited for it and reported nothing).
#[test]
fn concurrent_validations_of_robots_with_meshes_all_answer() {
    let Some(robots) = common::shared_robots() else {
        return;
    };
    let files = [
        "pr2/pr2_description/robots/pr2.urdf",
        "fetch/fetch_description/robots/fetch.urdf",
        "anymal/anymal_b_simple_description/urdf/anymal.urdf",
        "spot/spot_description/model.urdf",
    ];
    let mut server = Server::start_with(
        &std::env::temp_dir(),
        &["--root".as_ref(), robots.as_os_str()],
    );
    let started = Instant::now();
    let ids: Vec<u64> = files
        .iter()
        .map(|file| {
            let path = robots.join(file).display().to_string();
            server.ask(
                "tools/call",
                json!({"name": "validate_urdf", "arguments": {"urdf_path": path, "samples": 500}}),
            )
        })
        .collect();
    let mut answered: Vec<u64> = Vec::new();
    for _ in &files {
        let response = server.response();
        let result = &response["result"];
        assert_eq!(result["isError"], false, "{response}");
        assert!(
            result["structuredContent"]["overall_status"].is_string(),
            "{response}"
        );
        answered.push(response["id"].as_u64().unwrap());
    }
    answered.sort_unstable();
    assert_eq!(answered, ids);
    assert!(
        started.elapsed() < Duration::from_secs(45),
        "{:?}",
        started.elapsed()
    );
    assert!(server.close().success());
}

/// `fix_urdf`: the diff `--diff` prints, safe fixes unless `unsafe_fixes`; the file is not written.
#[test]
fn fix_urdf_returns_the_diff_and_writes_nothing() {
    let dir = std::env::temp_dir().join(format!("mcp_fix_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("axis.urdf");
    let urdf = r#"<robot name="r">
  <link name="base"><inertial><mass value="5"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="a"/><origin xyz="0 0 0.5"/>
    <axis xyz="0 2 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="a"><inertial><origin xyz="0.5 0 0"/><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
</robot>
"#;
    std::fs::write(&file, urdf).unwrap();
    let mut server = Server::start_with(&dir, &["--root".as_ref(), dir.as_os_str()]);
    let safe = server.call("fix_urdf", json!({"path": "axis.urdf", "samples": 200}));
    let diff = safe["structuredContent"]["diff"].as_str().unwrap();
    assert!(diff.contains("+    <axis xyz=\"0 1 0\"/>"), "{safe}");
    assert!(!diff.contains("effort=\"14.72\""), "{safe}");
    assert_eq!(safe["structuredContent"]["unsafe_left"], 1, "{safe}");
    let all = server.call(
        "fix_urdf",
        json!({"path": "axis.urdf", "samples": 200, "unsafe_fixes": true}),
    );
    let diff = all["structuredContent"]["diff"].as_str().unwrap();
    assert!(diff.contains("effort=\"14.72\""), "{all}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), urdf);
    assert!(server.close().success());
}

#[test]
fn help_and_usage() {
    let exe = env!("CARGO_BIN_EXE_urdf_validate");
    let help = Command::new(exe)
        .args(["mcp", "--help"])
        .output()
        .expect("runs");
    assert!(help.status.success());
    assert!(String::from_utf8_lossy(&help.stdout).contains("Model Context Protocol"));
    let extra = Command::new(exe)
        .args(["mcp", "robot.urdf"])
        .output()
        .expect("runs");
    assert_eq!(extra.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&extra.stderr).contains("./mcp"));
    // Closing stdin before initialising is a quiet exit.
    let closed = Command::new(exe)
        .arg("mcp")
        .stdin(Stdio::null())
        .output()
        .expect("runs");
    assert!(closed.status.success(), "{closed:?}");
    assert!(closed.stdout.is_empty());
}

#[test]
fn a_file_named_mcp_is_validated_as_dot_slash_mcp() {
    let dir = std::env::temp_dir().join(format!("urdf_validate_mcp_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::write(
        dir.join("mcp"),
        "<robot name='m'><link name='base'/></robot>\n",
    )
    .expect("write");
    let output = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(["./mcp", "--no-write", "--samples", "100"])
        .current_dir(&dir)
        .output()
        .expect("runs");
    assert!(
        String::from_utf8_lossy(&output.stdout).contains("urdf_validate — mcp"),
        "{output:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_server_is_untrusted_by_default_and_keeps_to_its_roots() {
    let dir = std::env::temp_dir().join(format!("urdf_validate_mcp_roots_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("root")).expect("dir");
    std::fs::create_dir_all(dir.join("outside")).expect("dir");
    let secret = "CANARYFILEmcp31";
    std::fs::write(dir.join("outside/secret.yaml"), format!("name: {secret}\n")).expect("write");
    std::fs::write(
        dir.join("outside/robot.urdf"),
        "<robot name='r'><link name='a'/></robot>\n",
    )
    .expect("write");
    std::fs::write(
        dir.join("root/robot.urdf.xacro"),
        "<robot name='r' xmlns:xacro='http://www.ros.org/wiki/xacro'>\
         <xacro:property name='y' value=\"${load_yaml('../outside/secret.yaml')}\"/>\
         <link name='a'/><link name='b_$(env URDF_MCP_CANARY)'/></robot>\n",
    )
    .expect("write");
    let root = dir.join("root");
    let mut server = Server::start_with(&dir, &["--root".as_ref(), root.as_os_str()]);
    // A path outside --root: a clear error, naming the path and the roots.
    let outside = server.call(
        "validate_urdf",
        json!({"path": dir.join("outside/robot.urdf").display().to_string()}),
    );
    let message = error_text(&outside);
    assert!(
        message.contains("outside the folders this server may read"),
        "{message}"
    );
    assert!(message.contains("--root"), "{message}");
    let relative = server.call("validate_urdf", json!({"path": "outside/robot.urdf"}));
    assert!(error_text(&relative).contains("outside the folders"));
    // Inside: validated in untrusted mode, the refusals reported, no secret in the reply.
    let inside = server.call(
        "validate_urdf",
        json!({"path": root.join("robot.urdf.xacro").display().to_string(), "samples": 100}),
    );
    let reply = inside.to_string();
    assert!(!reply.contains(secret), "{reply}");
    assert!(!reply.contains("CANARYENVmcp47"), "{reply}");
    assert!(reply.contains("U013"), "{reply}");
    // Every call is bounded: no timeout 0, no xml above the limit.
    let unbounded = server.call(
        "validate_urdf",
        json!({"path": root.join("robot.urdf.xacro").display().to_string(), "timeout": 0}),
    );
    assert!(error_text(&unbounded).contains("bounds every call"));
    let huge = format!("<robot name='r'><!--{}--></robot>", "x".repeat(5 << 20));
    let too_big = server.call("validate_urdf", json!({"xml": huge}));
    assert!(error_text(&too_big).contains("at most"));
    let base_dir = server.call(
        "validate_urdf",
        json!({"xml": "<robot name='r'><link name='a'/></robot>", "base_dir": dir.join("outside").display().to_string()}),
    );
    assert!(error_text(&base_dir).contains("outside the folders"));
    assert!(server.close().success());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A client that declares roots: the tools read inside them (and no longer only inside the working
/// directory), follow `notifications/roots/list_changed`, and still refuse what is outside.
#[test]
fn the_client_roots_bound_what_the_tools_read() {
    let dir = std::env::temp_dir().join(format!("mcp-roots-{}", std::process::id()));
    let (first, second, cwd) = (dir.join("first"), dir.join("second"), dir.join("cwd"));
    for folder in [&first, &second, &cwd] {
        std::fs::create_dir_all(folder).expect("mkdir");
        std::fs::write(
            folder.join("robot.urdf"),
            "<robot name='r'><link name='a'/></robot>\n",
        )
        .expect("write");
    }
    let robot = |folder: &Path| json!({"path": folder.join("robot.urdf").display().to_string(), "samples": 50});
    let mut server = Server::start_as(&cwd, &[], json!({"roots": {"listChanged": true}}));
    server.answer_roots(&[&first]);
    // Inside the declared root, outside the working directory: validated (refused before roots).
    let inside = server.call("validate_urdf", robot(&first));
    assert_ne!(inside["isError"], true, "{inside}");
    // The working directory is no root once the client names its own.
    let message = error_text(&server.call("validate_urdf", robot(&cwd)));
    assert!(message.contains("outside the folders"), "{message}");
    // The client changes its roots: the server asks again, and follows.
    server.send(&json!({"jsonrpc": "2.0", "method": "notifications/roots/list_changed"}));
    server.answer_roots(&[&second]);
    let moved = server.call("validate_urdf", robot(&second));
    assert_ne!(moved["isError"], true, "{moved}");
    let message = error_text(&server.call("validate_urdf", robot(&first)));
    assert!(message.contains("outside the folders"), "{message}");
    assert!(server.close().success());
    let _ = std::fs::remove_dir_all(&dir);
}
