//! LSP's framing on stdin and stdout (`Content-Length` headers, JSON-RPC bodies), read so that no message
//! ends the server. lsp-server's own stdio transport stops reading at the first message it cannot parse,
//! and the server with it (the editor loses it without a word); here a bad message gets the JSON-RPC error
//! reply (−32700 for text that is not JSON, −32600 for JSON that is not a request, response or
//! notification), a line on stderr, and the next message is read.

use std::io::{self, BufRead, Read, Write};
use std::thread::JoinHandle;

use crossbeam_channel::{select, Receiver, Sender};
use lsp_server::{Connection, Message};
use serde_json::{json, Value};

/// Largest message body read (an open file's text travels in one, JSON-escaped: above the largest input
/// file accepted); a bigger one is skipped with an error reply.
const MAX_BODY_BYTES: usize = 2 * urdf_validator::input::MAX_FILE_BYTES as usize;

/// Longest header line read.
const MAX_HEADER_LINE: u64 = 8 * 1024;

/// The reader and writer threads of [`stdio`].
pub struct Threads {
    reader: JoinHandle<()>,
    writer: JoinHandle<()>,
}

impl Threads {
    /// Wait for both threads (the reader ends with stdin or after `exit`, the writer when the connection
    /// is dropped).
    pub fn join(self) {
        let _ = self.reader.join();
        let _ = self.writer.join();
    }
}

/// A connection on stdin and stdout.
pub fn stdio() -> (Connection, Threads) {
    let (reader_sender, reader_receiver) = crossbeam_channel::unbounded::<Message>();
    let (writer_sender, writer_receiver) = crossbeam_channel::unbounded::<Message>();
    let (error_sender, error_receiver) = crossbeam_channel::unbounded::<Value>();
    let reader = std::thread::spawn(move || {
        read_messages(&mut io::stdin().lock(), &reader_sender, &error_sender);
    });
    let writer = std::thread::spawn(move || {
        write_messages(&mut io::stdout().lock(), &writer_receiver, &error_receiver);
    });
    let connection = Connection {
        sender: writer_sender,
        receiver: reader_receiver,
    };
    (connection, Threads { reader, writer })
}

/// Read framed messages from `input` until it ends (or after `exit`): each good one to `messages`, the
/// error reply of each bad one to `errors`.
pub fn read_messages(input: &mut impl BufRead, messages: &Sender<Message>, errors: &Sender<Value>) {
    loop {
        let body = match read_frame(input) {
            Ok(Some(body)) => body,
            Ok(None) => return,
            Err(Bad { reply, log }) => {
                log_bad(&log);
                if errors.send(reply).is_err() {
                    return;
                }
                continue;
            }
        };
        match parse(&body) {
            Ok(message) => {
                let exit = matches!(&message, Message::Notification(n) if n.method == "exit");
                if messages.send(message).is_err() || exit {
                    return;
                }
            }
            Err(Bad { reply, log }) => {
                log_bad(&log);
                if errors.send(reply).is_err() {
                    return;
                }
            }
        }
    }
}

/// Write the server's messages and the error replies to `output` until the server's channel closes (the
/// error replies queued by then are written too).
pub fn write_messages(
    output: &mut impl Write,
    messages: &Receiver<Message>,
    errors: &Receiver<Value>,
) {
    let mut errors_open = true;
    loop {
        let written = if errors_open {
            select! {
                recv(messages) -> message => match message {
                    Ok(message) => message.write(output),
                    Err(_) => {
                        // The server is done; the replies to bad messages read before are not lost.
                        for reply in errors.try_iter() {
                            if write_frame(output, &reply).is_err() {
                                break;
                            }
                        }
                        return;
                    }
                },
                recv(errors) -> reply => match reply {
                    Ok(reply) => write_frame(output, &reply),
                    Err(_) => {
                        errors_open = false;
                        Ok(())
                    }
                },
            }
        } else {
            match messages.recv() {
                Ok(message) => message.write(output),
                Err(_) => return,
            }
        };
        if written.is_err() {
            // The editor has gone: nothing more can reach it.
            return;
        }
    }
}

/// A message that could not be read: the reply for the client and the line for stderr.
struct Bad {
    reply: Value,
    log: String,
}

impl Bad {
    /// The JSON-RPC error `code` with `message`, for the request `id` (`null` when unknown).
    fn new(code: i64, message: String, id: Value) -> Bad {
        Bad {
            reply: json!({"jsonrpc": "2.0", "id": id, "error": {"code": code, "message": message}}),
            log: message,
        }
    }
}

fn log_bad(message: &str) {
    let _ = writeln!(
        io::stderr().lock(),
        "urdf_validate server: {message} (the message is ignored; the server goes on)"
    );
}

/// JSON-RPC's "Parse error".
const PARSE_ERROR: i64 = -32700;
/// JSON-RPC's "Invalid Request".
const INVALID_REQUEST: i64 = -32600;

/// The next message body: `Ok(None)` at the end of the input. Headers are `Name: value` lines up to an
/// empty line; names are case-insensitive; only `Content-Length` is needed. A header block without one
/// is an error, and reading goes on from the next line that starts one (its body is skipped with it).
fn read_frame(input: &mut impl BufRead) -> Result<Option<Vec<u8>>, Bad> {
    let mut length: Option<usize> = None;
    let mut unknown: Vec<String> = Vec::new();
    let mut any_header = false;
    loop {
        let mut line = Vec::new();
        let read = input
            .by_ref()
            .take(MAX_HEADER_LINE)
            .read_until(b'\n', &mut line)
            .unwrap_or(0);
        if read == 0 {
            // The input ended (a partial header block at its end is dropped).
            return Ok(None);
        }
        let text = String::from_utf8_lossy(&line);
        let text = text.trim_end_matches(['\r', '\n']);
        if text.is_empty() {
            if !any_header {
                continue; // blank lines between messages
            }
            break;
        }
        any_header = true;
        // A body without a newline runs into the next header line: read the header from where it starts.
        let lower = text.to_ascii_lowercase();
        let header = match lower.rfind("content-length:") {
            Some(at) if at > 0 => &text[at..],
            _ => text,
        };
        match header.split_once(':') {
            Some((name, value)) if name.trim().eq_ignore_ascii_case("content-length") => {
                length = value.trim().parse().ok();
                if length.is_none() {
                    unknown.push(format!("Content-Length '{}'", value.trim()));
                }
            }
            Some((name, _)) if name.trim().eq_ignore_ascii_case("content-type") => {}
            _ => unknown.push(format!("'{}'", shorten(header))),
        }
    }
    let Some(length) = length else {
        return Err(Bad::new(
            PARSE_ERROR,
            format!(
                "a message without a Content-Length header (read {})",
                if unknown.is_empty() {
                    "no header".to_string()
                } else {
                    unknown.join(", ")
                }
            ),
            Value::Null,
        ));
    };
    if length > MAX_BODY_BYTES {
        let skipped =
            io::copy(&mut input.by_ref().take(length as u64), &mut io::sink()).unwrap_or(0);
        return Err(Bad::new(
            INVALID_REQUEST,
            format!("a message of {length} bytes ({skipped} skipped); the largest read is {MAX_BODY_BYTES} bytes"),
            Value::Null,
        ));
    }
    let mut body = vec![0; length];
    if input.read_exact(&mut body).is_err() {
        // The input ended inside the body.
        return Ok(None);
    }
    Ok(Some(body))
}

/// The message in `body`, or the error reply: not JSON (−32700), or JSON that is not one request,
/// response or notification (−32600; a batch array included, which LSP does not use).
fn parse(body: &[u8]) -> Result<Message, Bad> {
    let value: Value = serde_json::from_slice(body).map_err(|error| {
        Bad::new(
            PARSE_ERROR,
            format!(
                "a message body that is not JSON ({error}): {}",
                shorten(&String::from_utf8_lossy(body))
            ),
            Value::Null,
        )
    })?;
    // JSON-RPC: an id that cannot be told (not a number or a string) is answered with null.
    let id = value
        .get("id")
        .filter(|id| id.is_number() || id.is_string())
        .cloned()
        .unwrap_or(Value::Null);
    if !value.is_object() {
        return Err(Bad::new(
            INVALID_REQUEST,
            format!(
                "a message that is not a JSON object: {}",
                shorten(&value.to_string())
            ),
            Value::Null,
        ));
    }
    let has = |key: &str| value.get(key).is_some();
    let parsed = if has("method") || has("result") || has("error") {
        serde_json::from_value::<Message>(value.clone()).ok()
    } else {
        None
    };
    parsed.ok_or_else(|| {
        Bad::new(
            INVALID_REQUEST,
            format!(
                "a JSON-RPC message with neither a method nor a result: {}",
                shorten(&value.to_string())
            ),
            id,
        )
    })
}

/// A frame holding `value`, as lsp-server writes its messages.
fn write_frame(output: &mut impl Write, value: &Value) -> io::Result<()> {
    let text = value.to_string();
    write!(output, "Content-Length: {}\r\n\r\n{text}", text.len())?;
    output.flush()
}

/// At most 120 characters of `text`, for a log line.
fn shorten(text: &str) -> String {
    match text.char_indices().nth(120) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The messages and error replies read from `input`.
    fn read(input: &[u8]) -> (Vec<Message>, Vec<Value>) {
        let (messages, received) = crossbeam_channel::unbounded();
        let (errors, replies) = crossbeam_channel::unbounded();
        read_messages(&mut io::Cursor::new(input.to_vec()), &messages, &errors);
        drop((messages, errors));
        (received.iter().collect(), replies.iter().collect())
    }

    fn frame(body: &str) -> String {
        format!("Content-Length: {}\r\n\r\n{body}", body.len())
    }

    #[test]
    fn bad_messages_get_their_error_and_reading_goes_on() {
        let good = r#"{"jsonrpc":"2.0","method":"initialized","params":{}}"#;
        let input = [
            frame("not json"),
            frame("[1, 2]"),
            frame(r#"{"jsonrpc":"2.0"}"#),
            frame(r#"{"jsonrpc":"2.0","id":7}"#),
            frame(r#"{"jsonrpc":"2.0","id":{"not":"an id"}}"#),
            format!("Content-Lenght: {}\r\n\r\n{good}", good.len()),
            frame(good),
        ]
        .concat();
        let (messages, replies) = read(input.as_bytes());
        let codes: Vec<i64> = replies
            .iter()
            .map(|r| r["error"]["code"].as_i64().unwrap_or(0))
            .collect();
        assert_eq!(
            codes,
            [
                PARSE_ERROR,
                INVALID_REQUEST,
                INVALID_REQUEST,
                INVALID_REQUEST,
                INVALID_REQUEST,
                PARSE_ERROR
            ]
        );
        assert_eq!(
            replies[3]["id"], 7,
            "the id of a request that can be named: {replies:?}"
        );
        assert_eq!(
            replies[4]["id"],
            Value::Null,
            "an id that is neither a number nor a string is null: {replies:?}"
        );
        assert_eq!(
            messages.len(),
            1,
            "the good message after the bad ones is read: {messages:?}"
        );
    }

    /// The server ends while error replies are still queued (a bad message just before the end of the
    /// input): they are written. The writer used to return as soon as the server's channel closed, and
    /// dropped them (found by the `lsp_messages` fuzz target).
    #[test]
    fn error_replies_queued_when_the_server_ends_are_written() {
        let (messages, server) = crossbeam_channel::unbounded::<Message>();
        let (errors, replies) = crossbeam_channel::unbounded();
        for code in [PARSE_ERROR, INVALID_REQUEST, PARSE_ERROR] {
            errors
                .send(json!({"jsonrpc": "2.0", "id": null, "error": {"code": code, "message": "bad"}}))
                .expect("open");
        }
        drop(messages);
        let mut output = Vec::new();
        write_messages(&mut output, &server, &replies);
        let written = String::from_utf8(output).expect("UTF-8");
        assert_eq!(
            written.matches("Content-Length:").count(),
            3,
            "every queued reply: {written}"
        );
        drop(errors);
    }

    #[test]
    fn headers_are_case_insensitive_and_reading_stops_after_exit() {
        let exit = r#"{"jsonrpc":"2.0","method":"exit"}"#;
        let input = format!(
            "content-length: {}\r\nContent-Type: application/vscode-jsonrpc; charset=utf-8\r\n\r\n{exit}{}",
            exit.len(),
            frame(r#"{"jsonrpc":"2.0","method":"initialized","params":{}}"#)
        );
        let (messages, replies) = read(input.as_bytes());
        assert!(replies.is_empty(), "{replies:?}");
        assert_eq!(
            messages.len(),
            1,
            "nothing is read after exit: {messages:?}"
        );
    }

    #[test]
    fn an_oversized_or_cut_message_ends_nothing_but_itself() {
        let input = format!("Content-Length: {}\r\n\r\n", MAX_BODY_BYTES + 1);
        let (_, replies) = read(input.as_bytes());
        assert_eq!(replies[0]["error"]["code"], INVALID_REQUEST);
        let (messages, replies) = read(b"Content-Length: 100\r\n\r\n{\"jsonrpc\"");
        assert!(messages.is_empty() && replies.is_empty());
    }
}
