//! `urdf_validate server`: the binary spoken to over LSP's framing (Content-Length headers) as an editor
//! does: initialize, open a broken URDF, its diagnostics, a request answered while the physics pass runs,
//! shutdown and exit. The client-library and Neovim tests are in tests/lsp (scripts/test-lsp.sh).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{self, Receiver};
use std::time::Duration;

use serde_json::{json, Value};

/// A running server and the messages it writes.
struct Server {
    child: Child,
    stdin: ChildStdin,
    messages: Receiver<Value>,
    /// Messages read while waiting for another, in order.
    skipped: Vec<Value>,
}

impl Server {
    fn start() -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
            .arg("server")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start the server");
        let stdin = child.stdin.take().expect("stdin");
        let mut stdout = BufReader::new(child.stdout.take().expect("stdout"));
        let (sender, messages) = mpsc::channel();
        std::thread::spawn(move || loop {
            let mut length = 0;
            loop {
                let mut line = String::new();
                if stdout.read_line(&mut line).unwrap_or(0) == 0 {
                    return;
                }
                if let Some(n) = line.strip_prefix("Content-Length: ") {
                    length = n.trim().parse().expect("length");
                }
                if line == "\r\n" {
                    break;
                }
            }
            let mut body = vec![0; length];
            stdout.read_exact(&mut body).expect("body");
            if sender
                .send(serde_json::from_slice(&body).expect("JSON"))
                .is_err()
            {
                return;
            }
        });
        Server {
            child,
            stdin,
            messages,
            skipped: Vec::new(),
        }
    }

    fn send(&mut self, message: Value) {
        let body = message.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).expect("write");
        self.stdin.flush().expect("flush");
    }

    /// Write `bytes` as they are (a malformed message).
    fn send_raw(&mut self, bytes: &str) {
        self.stdin.write_all(bytes.as_bytes()).expect("write");
        self.stdin.flush().expect("flush");
    }

    /// The first message satisfying `wanted` (others are kept for later waits).
    fn wait(&mut self, wanted: impl Fn(&Value) -> bool) -> Value {
        if let Some(i) = self.skipped.iter().position(&wanted) {
            return self.skipped.remove(i);
        }
        loop {
            let message = self
                .messages
                .recv_timeout(Duration::from_secs(60))
                .expect("a message within 60 s");
            if wanted(&message) {
                return message;
            }
            self.skipped.push(message);
        }
    }
}

const BROKEN: &str = r#"<?xml version="1.0"?>
<robot name="broken">
  <link name="base"/>
  <joint name="j" type="fixed">
    <parent link="base"/>
    <child link="missing"/>
  </joint>
</robot>
"#;

/// Bad messages before and after `initialize` — not JSON, a JSON array, an object that is no JSON-RPC
/// message, a misspelt header, a change past the end of the document — each get their error (or a line
/// on stderr) and the server goes on answering. It used to exit at the first one, silently.
#[test]
fn bad_messages_are_answered_and_the_server_goes_on() {
    let frame = |body: &str| format!("Content-Length: {}\r\n\r\n{body}", body.len());
    let mut server = Server::start();
    server.send_raw(&frame("not json"));
    let error = server.wait(|m| m["error"]["code"] == -32700);
    assert_eq!(error["id"], Value::Null, "{error}");
    server.send_raw(&frame("[1, 2]"));
    server.wait(|m| m["error"]["code"] == -32600);
    server.send_raw(&frame(r#"{"jsonrpc":"2.0"}"#));
    server.wait(|m| m["error"]["code"] == -32600);
    server.send(json!({"jsonrpc": "2.0", "id": 1, "method": "initialize",
        "params": {"processId": null, "capabilities": {}, "rootUri": null}}));
    let init = server.wait(|m| m["id"] == 1);
    assert!(init["result"]["capabilities"].is_object(), "{init}");
    server.send(json!({"jsonrpc": "2.0", "method": "initialized", "params": {}}));
    let hello = r#"{"jsonrpc":"2.0","id":2,"method":"shutdown","params":null}"#;
    // A misspelt header: its message is lost (there is no length to read it by), the next one is read.
    server.send_raw(&format!("Content-Lenght: {}\r\n\r\n{hello}", hello.len()));
    server.wait(|m| m["error"]["code"] == -32700);
    let dir = tempfile_dir();
    let uri = format!("file://{}", dir.join("robot.urdf").display());
    server.send(
        json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {
        "textDocument": {"uri": uri, "languageId": "xml", "version": 1, "text": BROKEN}}}),
    );
    server.send(
        json!({"jsonrpc": "2.0", "method": "textDocument/didChange", "params": {
        "textDocument": {"uri": uri, "version": 2},
        "contentChanges": [{"range": {"start": {"line": 400, "character": 0},
            "end": {"line": 400, "character": 0}}, "text": "<link name='lost'/>"}]}}),
    );
    server.send(
        json!({"jsonrpc": "2.0", "id": 3, "method": "textDocument/documentSymbol",
        "params": {"textDocument": {"uri": uri}}}),
    );
    let symbols = server.wait(|m| m["id"] == 3);
    let names: Vec<&Value> = symbols["result"]
        .as_array()
        .expect("symbols")
        .iter()
        .map(|s| &s["name"])
        .collect();
    assert!(
        !names.contains(&&json!("lost")),
        "a change past the end is not applied: {symbols}"
    );
    server.send(json!({"jsonrpc": "2.0", "id": 4, "method": "shutdown", "params": null}));
    server.wait(|m| m["id"] == 4);
    server.send(json!({"jsonrpc": "2.0", "method": "exit", "params": null}));
    let status = server.child.wait().expect("exit");
    assert!(status.success(), "{status}");
}

/// An edit moves what is shown with the text at once, for the edited version, before any new analysis:
/// five lines inserted above the undefined link, and its U102 is five lines down in the very next
/// publication (it stayed at its old line until the analysis caught up).
#[test]
fn published_diagnostics_follow_an_edit_at_once() {
    let dir = tempfile_dir();
    let uri = format!("file://{}", dir.join("moving.urdf").display());
    let mut server = Server::start();
    server.send(json!({"jsonrpc": "2.0", "id": 1, "method": "initialize",
        "params": {"processId": null, "capabilities": {}, "rootUri": null}}));
    server.wait(|m| m["id"] == 1);
    server.send(json!({"jsonrpc": "2.0", "method": "initialized", "params": {}}));
    server.send(
        json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {
        "textDocument": {"uri": uri, "languageId": "xml", "version": 1, "text": BROKEN}}}),
    );
    let u102_line = |published: &Value| {
        published["params"]["diagnostics"]
            .as_array()
            .and_then(|all| all.iter().find(|d| d["code"] == "U102"))
            .map(|d| d["range"]["start"]["line"].clone())
    };
    let first =
        server.wait(|m| m["method"] == "textDocument/publishDiagnostics" && u102_line(m).is_some());
    assert_eq!(u102_line(&first), Some(json!(5)), "{first}");
    server.skipped.clear();
    server.send(json!({"jsonrpc": "2.0", "method": "textDocument/didChange", "params": {
        "textDocument": {"uri": uri, "version": 2},
        "contentChanges": [{"range": {"start": {"line": 2, "character": 0},
            "end": {"line": 2, "character": 0}}, "text": "<!-- -->\n<!-- -->\n<!-- -->\n<!-- -->\n<!-- -->\n"}]}}));
    // Answered at once, while the new analysis waits for more typing: what came before it is the
    // moved publication.
    server.send(
        json!({"jsonrpc": "2.0", "id": 2, "method": "textDocument/documentSymbol",
        "params": {"textDocument": {"uri": uri}}}),
    );
    server.wait(|m| m["id"] == 2);
    let moved = server
        .skipped
        .iter()
        .find(|m| m["method"] == "textDocument/publishDiagnostics" && m["params"]["version"] == 2)
        .unwrap_or_else(|| {
            panic!(
                "no publication for version 2 before the answer: {:?}",
                server.skipped
            )
        })
        .clone();
    assert_eq!(u102_line(&moved), Some(json!(10)), "{moved}");
    server.send(json!({"jsonrpc": "2.0", "id": 3, "method": "shutdown", "params": null}));
    server.wait(|m| m["id"] == 3);
    server.send(json!({"jsonrpc": "2.0", "method": "exit", "params": null}));
    assert!(server.child.wait().expect("exit").success());
}

#[test]
fn diagnostics_answers_and_a_clean_exit() {
    let dir = tempfile_dir();
    let path = dir.join("broken.urdf");
    std::fs::write(&path, BROKEN).expect("write");
    let uri = format!("file://{}", path.display());
    let mut server = Server::start();
    server.send(json!({"jsonrpc": "2.0", "id": 1, "method": "initialize",
        "params": {"processId": null, "capabilities": {}, "rootUri": null}}));
    let init = server.wait(|m| m["id"] == 1);
    assert!(
        server.skipped.is_empty(),
        "nothing before the answer to initialize"
    );
    let capabilities = &init["result"]["capabilities"];
    assert_eq!(capabilities["hoverProvider"], true, "{init}");
    assert_eq!(capabilities["textDocumentSync"]["change"], 2, "incremental");
    server.send(json!({"jsonrpc": "2.0", "method": "initialized", "params": {}}));
    server.send(
        json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {
        "textDocument": {"uri": uri, "languageId": "xml", "version": 1, "text": BROKEN}}}),
    );
    // A request right after the open is answered from the text, whatever the analysis is doing.
    server.send(
        json!({"jsonrpc": "2.0", "id": 2, "method": "textDocument/documentSymbol",
        "params": {"textDocument": {"uri": uri}}}),
    );
    let symbols = server.wait(|m| m["id"] == 2);
    assert_eq!(symbols["result"][0]["name"], "base", "{symbols}");
    let published = server.wait(|m| m["method"] == "textDocument/publishDiagnostics");
    assert_eq!(published["params"]["uri"], uri.as_str());
    let diagnostics = published["params"]["diagnostics"]
        .as_array()
        .expect("diagnostics");
    let undefined = diagnostics
        .iter()
        .find(|d| d["code"] == "U102")
        .unwrap_or_else(|| panic!("no U102 in {published}"));
    assert_eq!(
        undefined["range"],
        json!({"start": {"line": 5, "character": 17}, "end": {"line": 5, "character": 24}})
    );
    assert_eq!(undefined["severity"], 1);
    server.send(json!({"jsonrpc": "2.0", "id": 3, "method": "shutdown", "params": null}));
    server.wait(|m| m["id"] == 3);
    server.send(json!({"jsonrpc": "2.0", "method": "exit", "params": null}));
    let status = server.child.wait().expect("exit");
    assert!(status.success(), "{status}");
}

#[test]
fn help_names_the_editors_section() {
    let output = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(["server", "--help"])
        .output()
        .expect("run");
    let help = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success());
    assert!(help.contains("Language Server Protocol"), "{help}");
    assert!(help.contains("/integrations/editors.html"), "{help}");
}

#[test]
fn a_bad_flag_stops_the_server_with_a_message() {
    let output = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .args(["server", "--samples", "0"])
        .stdin(Stdio::null())
        .output()
        .expect("run");
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("--samples"), "{stderr}");
}

/// A fresh folder under the target directory's temporary space.
fn tempfile_dir() -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("urdf-lsp-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}
