//! The start and the end of a session, read so that no message out of order ends the server.
//! lsp-server's `initialize_start`, `initialize_finish` and `handle_shutdown` stop it at the first one: a
//! response or `exit` before `initialize`, anything but `initialized` right after it (a client's
//! `$/cancelRequest`, a request sent early), anything but `exit` after `shutdown` (or no `exit` within
//! 30 s). Here, before `initialize` a request gets −32002 (the server is not initialised) and the rest is
//! ignored; `initialized` is not waited for (the main loop ignores it); after `shutdown` a request gets
//! −32600, as LSP asks, until `exit` or the end of the input.

use lsp_server::{Connection, ErrorCode, Message, Request, RequestId, Response};
use serde_json::Value;

/// Wait for `initialize`: its id and parameters, or `None` when the input ends (or `exit` comes) first.
pub fn initialize(connection: &Connection) -> Option<(RequestId, Value)> {
    for message in &connection.receiver {
        match message {
            Message::Request(request) if request.method == "initialize" => {
                return Some((request.id, request.params));
            }
            Message::Request(request) => send(
                connection,
                Response::new_err(
                    request.id,
                    ErrorCode::ServerNotInitialized as i32,
                    format!("{}: the server is not initialized yet", request.method),
                ),
            ),
            Message::Notification(notification) if notification.method == "exit" => return None,
            Message::Notification(_) | Message::Response(_) => {}
        }
    }
    None
}

/// Whether `request` is `shutdown`: if so it is answered, and so is every request after it (−32600),
/// until `exit` or the end of the input; the main loop then ends.
pub fn shut_down(connection: &Connection, request: &Request) -> bool {
    if request.method != "shutdown" {
        return false;
    }
    send(connection, Response::new_ok(request.id.clone(), ()));
    for message in &connection.receiver {
        match message {
            Message::Notification(notification) if notification.method == "exit" => break,
            Message::Request(request) => send(
                connection,
                Response::new_err(
                    request.id,
                    ErrorCode::InvalidRequest as i32,
                    format!("{}: the server is shutting down", request.method),
                ),
            ),
            Message::Notification(_) | Message::Response(_) => {}
        }
    }
    true
}

/// Send `response` (a client gone is not an error here: the reader ends next).
fn send(connection: &Connection, response: Response) {
    let _ = connection.sender.send(Message::Response(response));
}

#[cfg(test)]
mod tests {
    use super::*;
    use lsp_server::Notification;
    use serde_json::json;

    fn request(id: i32, method: &str) -> Message {
        Message::Request(Request::new(id.into(), method.into(), json!(null)))
    }

    fn notification(method: &str) -> Message {
        Message::Notification(Notification::new(method.into(), json!(null)))
    }

    /// `(client, server)`: the client's messages already sent, then its side closed.
    fn session(messages: Vec<Message>) -> (Connection, crossbeam_channel::Receiver<Message>) {
        let (to_server, receiver) = crossbeam_channel::unbounded();
        let (sender, from_server) = crossbeam_channel::unbounded();
        for message in messages {
            to_server.send(message).expect("open channel");
        }
        (Connection { sender, receiver }, from_server)
    }

    fn error_codes(replies: &crossbeam_channel::Receiver<Message>) -> Vec<Option<i32>> {
        replies
            .try_iter()
            .map(|m| match m {
                Message::Response(r) => r.error.map(|e| e.code),
                other => panic!("not a response: {other:?}"),
            })
            .collect()
    }

    #[test]
    fn messages_before_initialize_are_answered_or_ignored() {
        let response = Message::Response(Response::new_ok(9.into(), ()));
        let (connection, replies) = session(vec![
            response,
            notification("$/cancelRequest"),
            request(1, "textDocument/hover"),
            request(2, "initialize"),
            notification("textDocument/didOpen"),
        ]);
        let (id, _) = initialize(&connection).expect("initialize is read");
        assert_eq!(id, 2.into());
        assert_eq!(
            error_codes(&replies),
            [Some(ErrorCode::ServerNotInitialized as i32)]
        );
        assert!(
            connection.receiver.try_recv().is_ok(),
            "what follows initialize is left for the main loop"
        );
        let (connection, _) = session(vec![notification("exit"), request(1, "initialize")]);
        assert!(initialize(&connection).is_none(), "exit first: no session");
    }

    #[test]
    fn requests_after_shutdown_get_invalid_request_until_exit() {
        let (connection, replies) = session(vec![
            notification("textDocument/didChange"),
            request(4, "textDocument/hover"),
            notification("exit"),
            request(5, "textDocument/hover"),
        ]);
        assert!(!shut_down(
            &connection,
            &Request::new(2.into(), "x".into(), json!(null))
        ));
        assert!(shut_down(
            &connection,
            &Request::new(3.into(), "shutdown".into(), json!(null))
        ));
        assert_eq!(
            error_codes(&replies),
            [None, Some(ErrorCode::InvalidRequest as i32)]
        );
        assert!(
            connection.receiver.try_recv().is_ok(),
            "nothing is read after exit"
        );
    }
}
