//! LSP byte streams → the language server's own reader, main loop and writer, in process
//! (`urdf_validate_cli::fuzzing`: `transport::read_messages`, `serve` with its lifecycle, then
//! `transport::write_messages`), with channels for stdin and stdout. See the README for the input format.
//!
//! Invariants (a panic anywhere, in the reader, the main loop or an analysis thread, aborts the run):
//! * the reader takes the whole stream (unless it stopped after `exit`) and ends: it never hangs;
//! * every error reply is JSON-RPC's −32700 or −32600, with a null, number or string id;
//! * structured streams: each record read alone gives what its framing says (a well-framed body: exactly
//!   one message or one error reply; a generated message: exactly that message; a header block without a
//!   usable Content-Length: exactly one error reply; a body cut by the end: nothing), and the records read
//!   one after the other give what each gave alone: no frame spills into the next;
//! * raw streams: no more messages and replies than lines (each ends a header block);
//! * the main loop ends only at the end of the input (or `exit`), never with an error;
//! * what the server writes reads back as well-framed messages, and every request read gets exactly one
//!   response (with the error replies, one per id they name).
#![no_main]

use std::collections::{BTreeSet, HashMap};

use libfuzzer_sys::fuzz_target;
use serde_json::{json, Value};
use urdf_validate_cli::fuzzing;

/// Separates the records of a structured stream.
const SEPARATOR: u8 = 0xFF;
/// Most records read from one input.
const MAX_RECORDS: usize = 64;
/// Longest body kept after a header block without a usable Content-Length: the reader reads header lines
/// of up to 8 KiB, and a longer line of body text would split the next frame's header where it runs in.
const MAX_UNFRAMED_BODY: usize = 4096;

/// The server's flags: no mesh cache on disk, a small workspace sample, a time limit below libFuzzer's.
const FLAGS: &[&str] = &["--no-cache", "--samples", "16", "--timeout", "8"];

/// Documents of generated messages (the folder does not exist: meshes and includes do not resolve).
const URIS: [&str; 5] = [
    "file:///tmp/urdf-lsp-fuzz/robot.urdf",
    "file:///tmp/urdf-lsp-fuzz/arm.urdf.xacro",
    "file:///tmp/urdf-lsp-fuzz/macros.xacro",
    "file:///tmp/urdf-lsp-fuzz/model.sdf",
    "untitled:Untitled-1",
];

/// The text of a generated `didOpen` or whole-text change with no text of its own.
const ROBOT: &str = r#"<?xml version="1.0"?>
<robot name="fuzz">
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="5" velocity="1"/>
  </joint>
  <link name="arm">
    <inertial><origin xyz="0 0 0.2"/><mass value="0.5"/><inertia ixx="0.01" iyy="0.01" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><mesh filename="package://fuzz/meshes/arm.stl"/></geometry></visual>
    <collision><geometry><cylinder radius="0.03" length="0.4"/></geometry></collision>
  </link>
  <joint name="tip_joint" type="fixed"><parent link="arm"/><child link="tip"/></joint>
  <link name="tip"/>
  <gazebo reference="arm"><material>Gazebo/Grey</material></gazebo>
</robot>
"#;

/// What reading a record alone must give.
enum Expect {
    /// Exactly one message or one error reply.
    One,
    /// Exactly this message (method, id, params).
    Message(Value),
    /// Exactly one error reply and no message.
    Error,
    /// Nothing (a body cut by the end of the input).
    Nothing,
}

fn frame(header: &str, body: &[u8]) -> Vec<u8> {
    [header.as_bytes(), body].concat()
}

/// A record: its first byte the framing, the rest the body (or what a message is generated from).
fn record(data: &[u8], last: bool) -> (Vec<u8>, Expect) {
    let (kind, body) = data.split_first().map_or((0, &[][..]), |(k, b)| (*k, b));
    let unframed = || -> Vec<u8> {
        body.iter()
            .copied()
            .filter(|b| *b != b'\r' && *b != b'\n')
            .take(MAX_UNFRAMED_BODY)
            .collect()
    };
    match kind % 8 {
        0 | 1 => {
            let message = generated(body);
            let text = message.to_string();
            let header = format!("Content-Length: {}\r\n\r\n", text.len());
            (frame(&header, text.as_bytes()), Expect::Message(message))
        }
        3 => {
            let header = format!(
                "content-length: {}\r\nContent-Type: application/vscode-jsonrpc; charset=utf-8\r\n\r\n",
                body.len()
            );
            (frame(&header, body), Expect::One)
        }
        // Bare LF line ends, and blank lines after the body (skipped before the next header).
        4 => {
            let header = format!("Content-Length:{}\n\n", body.len());
            (frame(&header, &[body, b"\r\n\n"].concat()), Expect::One)
        }
        5 => (
            frame("Content-Type: application/json\r\n\r\n", &unframed()),
            Expect::Error,
        ),
        6 => {
            let body = unframed();
            let header = format!("Content-Length: {} bytes\r\n\r\n", body.len());
            (frame(&header, &body), Expect::Error)
        }
        7 if last => {
            let header = format!("Content-Length: {}\r\n\r\n", body.len() + 1);
            (frame(&header, body), Expect::Nothing)
        }
        _ => {
            let header = format!("Content-Length: {}\r\n\r\n", body.len());
            (frame(&header, body), Expect::One)
        }
    }
}

/// An LSP message built from `data`: `[op, uri, id, a, b, c, d, e, text…]` (missing bytes are 0).
fn generated(data: &[u8]) -> Value {
    let byte = |i: usize| data.get(i).copied().unwrap_or(0);
    let uri = URIS[usize::from(byte(1)) % URIS.len()];
    let id = i64::from(byte(2) % 8);
    let position = |line: usize, character: usize| json!({"line": byte(line) % 64, "character": byte(character)});
    let range = json!({"start": position(3, 4), "end": position(5, 6)});
    let text = String::from_utf8_lossy(data.get(8..).unwrap_or_default()).into_owned();
    let text_or_robot = if text.is_empty() {
        ROBOT.to_string()
    } else {
        text.clone()
    };
    let document = json!({"uri": uri});
    let at = json!({"textDocument": document, "position": position(3, 4)});
    let request = |method: &str, params: Value| json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params});
    let notification =
        |method: &str, params: Value| json!({"jsonrpc": "2.0", "method": method, "params": params});
    match byte(0) {
        0xFD => request("shutdown", Value::Null),
        0xFE => notification("exit", Value::Null),
        op => match op % 13 {
            0 => request(
                "initialize",
                json!({"processId": null, "capabilities": {}, "rootUri": null}),
            ),
            1 => notification("initialized", json!({})),
            2 => notification(
                "textDocument/didOpen",
                json!({"textDocument": {"uri": uri, "languageId": "xml",
                    "version": byte(3), "text": text_or_robot}}),
            ),
            3 => notification(
                "textDocument/didChange",
                json!({"textDocument": {"uri": uri, "version": byte(7)},
                    "contentChanges": [{"range": range, "text": text}]}),
            ),
            4 => notification(
                "textDocument/didChange",
                json!({"textDocument": {"uri": uri, "version": byte(7)},
                    "contentChanges": [{"text": text_or_robot}]}),
            ),
            5 => request("textDocument/hover", at),
            6 => request("textDocument/completion", at),
            7 => request("textDocument/definition", at),
            8 => {
                let mut params = at;
                params["context"] = json!({"includeDeclaration": byte(5) % 2 == 1});
                request("textDocument/references", params)
            }
            9 => request(
                "textDocument/documentSymbol",
                json!({"textDocument": document}),
            ),
            10 => {
                let only = match byte(7) % 3 {
                    0 => Value::Null,
                    1 => json!(["quickfix"]),
                    _ => json!(["source.fixAll"]),
                };
                request(
                    "textDocument/codeAction",
                    json!({"textDocument": document, "range": range,
                        "context": {"diagnostics": [], "only": only}}),
                )
            }
            11 => notification("$/cancelRequest", json!({"id": id})),
            _ if byte(3) % 2 == 0 => {
                notification("textDocument/didSave", json!({"textDocument": document}))
            }
            _ => notification("textDocument/didClose", json!({"textDocument": document})),
        },
    }
}

/// A message's method, id and parameters (a null or missing `params` alike), to compare a message sent
/// with the one read.
fn essence(message: &Value) -> (Value, Value, Value) {
    let field = |key: &str| message.get(key).cloned().unwrap_or(Value::Null);
    (field("method"), field("id"), field("params"))
}

/// An error reply's code and id (its message text may name what was around it).
fn reply_key(reply: &Value) -> (Value, Value) {
    (reply["error"]["code"].clone(), reply["id"].clone())
}

fn is_exit(message: &Value) -> bool {
    message.get("method") == Some(&json!("exit"))
}

fn check_replies(errors: &[Value]) {
    for reply in errors {
        let code = reply["error"]["code"].as_i64();
        assert!(
            matches!(code, Some(-32700 | -32600)),
            "an error reply's code: {reply}"
        );
        assert_eq!(reply["jsonrpc"], "2.0", "{reply}");
        assert!(reply["error"]["message"].is_string(), "{reply}");
        assert!(
            matches!(
                reply["id"],
                Value::Null | Value::Number(_) | Value::String(_)
            ),
            "{reply}"
        );
    }
}

/// The checks of a structured stream: each record alone, then all of them in a row.
fn check_records(records: &[(Vec<u8>, Expect)], whole: &fuzzing::Read) {
    let (mut messages, mut errors) = (Vec::new(), Vec::new());
    for (number, (bytes, expect)) in records.iter().enumerate() {
        let alone = fuzzing::read(bytes);
        check_replies(&alone.errors);
        let (m, e) = (alone.messages.len(), alone.errors.len());
        match expect {
            Expect::One => assert_eq!(m + e, 1, "record {number}: one message or reply"),
            Expect::Error => assert_eq!((m, e), (0, 1), "record {number}: one reply"),
            Expect::Nothing => assert_eq!((m, e), (0, 0), "record {number}: nothing"),
            Expect::Message(sent) => {
                assert_eq!((m, e), (1, 0), "record {number}: its message");
                assert_eq!(
                    essence(&alone.messages[0]),
                    essence(sent),
                    "record {number}: the message read is the one sent"
                );
            }
        }
        let exit = alone.messages.last().is_some_and(is_exit);
        messages.extend(alone.messages);
        errors.extend(alone.errors.iter().map(reply_key));
        if exit {
            break;
        }
    }
    assert_eq!(
        whole.messages, messages,
        "the records in a row give the messages each gives alone"
    );
    let whole_errors: Vec<_> = whole.errors.iter().map(reply_key).collect();
    assert_eq!(
        whole_errors, errors,
        "the records in a row give the error replies each gives alone"
    );
}

/// The messages of the server's output, read strictly as lsp-server writes them (`Content-Length: N`,
/// a blank line, N bytes of a JSON-RPC 2.0 object), which a client reads: the server's own reader is not
/// used, as it takes no response with a null id (an error reply's, which a client must read).
fn frames(mut output: &[u8]) -> Vec<Value> {
    let mut messages = Vec::new();
    while !output.is_empty() {
        let text = String::from_utf8_lossy(&output[..output.len().min(64)]).into_owned();
        let header_end = output
            .windows(4)
            .position(|w| w == b"\r\n\r\n")
            .unwrap_or_else(|| panic!("a frame without a blank line after its header: {text:?}"));
        let header = std::str::from_utf8(&output[..header_end]).expect("an ASCII header");
        let length: usize = header
            .strip_prefix("Content-Length: ")
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("a header that is not Content-Length: {header:?}"));
        let body = output
            .get(header_end + 4..header_end + 4 + length)
            .unwrap_or_else(|| panic!("a body shorter than its Content-Length: {text:?}"));
        let message: Value = serde_json::from_slice(body).expect("a body that is JSON");
        assert_eq!(message["jsonrpc"], "2.0", "{message}");
        messages.push(message);
        output = &output[header_end + 4 + length..];
    }
    messages
}

/// A JSON value as a map key.
fn key(value: &Value) -> String {
    value.to_string()
}

fuzz_target!(|data: &[u8]| {
    let Some((mode, data)) = data.split_first() else {
        return;
    };
    let raw = mode % 4 == 3;
    let (stream, records) = if raw {
        (data.to_vec(), Vec::new())
    } else {
        let pieces: Vec<&[u8]> = data.split(|b| *b == SEPARATOR).take(MAX_RECORDS).collect();
        let records: Vec<(Vec<u8>, Expect)> = pieces
            .iter()
            .enumerate()
            .map(|(i, piece)| record(piece, i + 1 == pieces.len()))
            .collect();
        (
            records.iter().flat_map(|(b, _)| b.clone()).collect(),
            records,
        )
    };

    let read = fuzzing::read(&stream);
    let exited = read.messages.last().is_some_and(is_exit);
    assert!(
        read.consumed == stream.len() || exited,
        "the reader stopped at byte {} of {} without an exit",
        read.consumed,
        stream.len()
    );
    check_replies(&read.errors);
    if raw {
        let lines = stream.iter().filter(|b| **b == b'\n').count();
        assert!(
            read.messages.len() + read.errors.len() <= lines,
            "more messages and replies ({} + {}) than lines ({lines})",
            read.messages.len(),
            read.errors.len()
        );
    } else {
        check_records(&records, &read);
    }

    // The session, then the editor closing what it opened (so that analyses under way are cancelled),
    // unless it said exit.
    let mut messages = read.messages.clone();
    if !exited {
        let opened: BTreeSet<String> = messages
            .iter()
            .filter(|m| m.get("method") == Some(&json!("textDocument/didOpen")))
            .filter_map(|m| {
                m["params"]["textDocument"]["uri"]
                    .as_str()
                    .map(String::from)
            })
            .collect();
        messages.extend(opened.into_iter().map(|uri| {
            json!({"method": "textDocument/didClose", "params": {"textDocument": {"uri": uri}}})
        }));
    }
    let served = fuzzing::serve(&messages, &read.errors, FLAGS);
    assert_eq!(served.result, Ok(()), "the main loop ended with an error");

    let written = frames(&served.output);
    // Per id: the responses written = the requests read + the error replies naming it.
    let mut expected: HashMap<String, i64> = HashMap::new();
    for message in &messages {
        if message.get("method").is_some() && message.get("id").is_some() {
            *expected.entry(key(&message["id"])).or_default() += 1;
        }
    }
    for reply in &read.errors {
        *expected.entry(key(&reply["id"])).or_default() += 1;
    }
    let mut answered: HashMap<String, i64> = HashMap::new();
    for message in &written {
        assert!(
            message.get("method").is_none() || message.get("id").is_none(),
            "the server sent a request: {message}"
        );
        if message.get("method").is_none() {
            *answered.entry(key(&message["id"])).or_default() += 1;
        }
    }
    assert_eq!(answered, expected, "responses per id");
});
