//! The language server's message loop on bytes in memory, for the fuzz target `lsp_messages`
//! (crates/cli/fuzz): the real reader (`transport::read_messages`), main loop (`serve`, lifecycle
//! included) and writer (`transport::write_messages`), with channels in place of stdin and stdout. Not
//! an API (hidden from the docs): it changes with the fuzz target. Messages are JSON values here, so the
//! fuzz crate needs no LSP crate of its own.

use std::io::Cursor;
use std::time::Duration;

use lsp_server::{Connection, Message};
use serde_json::Value;

use super::transport;

/// What the reader made of a byte stream.
pub struct Read {
    /// The messages read, in order, as JSON (`lsp_server::Message` serialized).
    pub messages: Vec<Value>,
    /// The error replies to the bad ones, in order.
    pub errors: Vec<Value>,
    /// How many bytes of the stream the reader took (all of it, unless it stopped after `exit`).
    pub consumed: usize,
}

/// Read `input` as stdin is read.
pub fn read(input: &[u8]) -> Read {
    let (messages, received) = crossbeam_channel::unbounded();
    let (errors, replies) = crossbeam_channel::unbounded();
    let mut cursor = Cursor::new(input);
    transport::read_messages(&mut cursor, &messages, &errors);
    drop((messages, errors));
    Read {
        messages: received
            .iter()
            .map(|m: Message| serde_json::to_value(m).unwrap_or(Value::Null))
            .collect(),
        errors: replies.iter().collect(),
        consumed: usize::try_from(cursor.position()).unwrap_or(usize::MAX),
    }
}

/// What the server did with a session.
pub struct Served {
    /// Everything written to the client (framed, as on stdout): the server's messages and the reader's
    /// error replies.
    pub output: Vec<u8>,
    /// What the main loop returned (`Err`: the server would exit with status 2).
    pub result: Result<(), String>,
}

/// Run the server, with command-line `flags`, on `messages` (JSON values of LSP messages; one that is not
/// is an `Err`) followed by the end of the input, with `errors` (error replies) to write beside its
/// output. Returns when the main loop has ended and every analysis thread it started has finished.
pub fn serve(messages: &[Value], errors: &[Value], flags: &[&str]) -> Served {
    // Rayon's workers, started from an analysis thread, would take its name (Linux threads inherit
    // it): named here, they are not waited for.
    let _ = rayon::ThreadPoolBuilder::new()
        .thread_name(|i| format!("rayon {i}"))
        .build_global();
    let flags: Vec<String> = flags.iter().map(|f| f.to_string()).collect();
    let checked = crate::request::request_from_flags(&flags).and_then(|settings| {
        urdf_validate_session::Session::new(&settings, None).map(|s| (settings, s.timeout()))
    });
    let (settings, timeout) = match checked {
        Ok(checked) => checked,
        Err(message) => {
            return Served {
                output: Vec::new(),
                result: Err(message),
            }
        }
    };
    let (to_server, receiver) = crossbeam_channel::unbounded();
    let (sender, from_server) = crossbeam_channel::unbounded();
    let (error_sender, error_receiver) = crossbeam_channel::unbounded();
    for message in messages {
        match serde_json::from_value::<Message>(message.clone()) {
            Ok(message) => {
                let _ = to_server.send(message);
            }
            Err(error) => {
                return Served {
                    output: Vec::new(),
                    result: Err(format!("not an LSP message ({error}): {message}")),
                }
            }
        }
    }
    for error in errors {
        let _ = error_sender.send(error.clone());
    }
    // The end of the input, as when stdin closes.
    drop((to_server, error_sender));
    let writer = std::thread::spawn(move || {
        let mut output = Vec::new();
        transport::write_messages(&mut output, &from_server, &error_receiver);
        output
    });
    let connection = Connection { sender, receiver };
    let result = super::serve(&connection, settings, timeout);
    drop(connection);
    let output = writer.join().unwrap_or_default();
    wait_for_analyses();
    Served { output, result }
}

/// Wait until no analysis thread of this process is left (their names start with `analyse`; Linux's
/// /proc; elsewhere nothing is waited for), so one session's runs do not overlap the next. A run that
/// never ends hangs here: libFuzzer's time limit reports it.
fn wait_for_analyses() {
    let analysing = || {
        std::fs::read_dir("/proc/self/task")
            .map(|tasks| {
                tasks.flatten().any(|task| {
                    std::fs::read_to_string(task.path().join("comm"))
                        .is_ok_and(|name| name.starts_with("analyse"))
                })
            })
            .unwrap_or(false)
    };
    while analysing() {
        std::thread::sleep(Duration::from_millis(1));
    }
}
