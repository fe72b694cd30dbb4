//! The smallest HTTP/1.1 the view needs: one request per connection (`Connection: close`), a request
//! line, headers and a `Content-Length` body, each bounded, read from a local socket. Anything else is
//! answered 400 (or 413) and the connection closed; nothing here panics on what a client sends.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::time::Duration;

/// Largest request head (request line and headers), bytes.
const MAX_HEAD: usize = 16 * 1024;
/// Largest body (a pose: joint names and values), bytes.
const MAX_BODY: usize = 1024 * 1024;

/// One request.
pub(crate) struct Request {
    /// `GET`, `POST`, ...
    pub method: String,
    /// The path, without the query.
    pub path: String,
    /// The `Host` header.
    pub host: Option<String>,
    /// The body.
    pub body: Vec<u8>,
}

/// One response.
pub(crate) struct Response {
    /// 200, 404, ...
    pub status: u16,
    /// `Content-Type`.
    pub content_type: &'static str,
    /// The body.
    pub body: Vec<u8>,
    /// Other headers.
    pub headers: Vec<(&'static str, String)>,
}

impl Response {
    /// A response with `body`.
    pub fn new(status: u16, content_type: &'static str, body: impl Into<Vec<u8>>) -> Response {
        Response {
            status,
            content_type,
            body: body.into(),
            headers: Vec::new(),
        }
    }

    /// The response with one more header.
    pub fn with_header(mut self, name: &'static str, value: impl std::fmt::Display) -> Response {
        self.headers.push((name, value.to_string()));
        self
    }

    /// A plain-text error.
    pub fn error(status: u16, message: &str) -> Response {
        Response::new(status, "text/plain; charset=utf-8", format!("{message}\n"))
    }
}

/// Read one request from `stream` (`Err`: the response that says why not).
pub(crate) fn read_request(stream: &TcpStream) -> Result<Request, Response> {
    let _ = stream.set_read_timeout(Some(Duration::from_secs(5)));
    let mut reader = BufReader::new(stream.take((MAX_HEAD + MAX_BODY) as u64));
    let mut head = 0usize;
    let mut line = String::new();
    let mut next_line = |reader: &mut BufReader<_>, line: &mut String| -> Result<(), Response> {
        line.clear();
        let n = reader
            .read_line(line)
            .map_err(|_| Response::error(400, "unreadable request"))?;
        head += n;
        if n == 0 || head > MAX_HEAD {
            return Err(Response::error(400, "request head too long or cut short"));
        }
        Ok(())
    };
    next_line(&mut reader, &mut line)?;
    let mut words = line.split_whitespace();
    let (Some(method), Some(target)) = (words.next(), words.next()) else {
        return Err(Response::error(400, "expected a request line"));
    };
    let method = method.to_string();
    let path = target.split('?').next().unwrap_or_default().to_string();
    let mut length = 0usize;
    let mut host = None;
    loop {
        next_line(&mut reader, &mut line)?;
        let header = line.trim_end();
        if header.is_empty() {
            break;
        }
        let Some((name, value)) = header.split_once(':') else {
            return Err(Response::error(400, "malformed header"));
        };
        let value = value.trim();
        if name.eq_ignore_ascii_case("content-length") {
            length = value
                .parse()
                .map_err(|_| Response::error(400, "bad Content-Length"))?;
        } else if name.eq_ignore_ascii_case("host") {
            host = Some(value.to_string());
        }
    }
    if length > MAX_BODY {
        return Err(Response::error(413, "body too large"));
    }
    let mut body = vec![0; length];
    reader
        .read_exact(&mut body)
        .map_err(|_| Response::error(400, "body shorter than its Content-Length"))?;
    Ok(Request {
        method,
        path,
        host,
        body,
    })
}

/// Write `response` and close.
pub(crate) fn write_response(mut stream: &TcpStream, response: &Response) {
    let reason = match response.status {
        200 => "OK",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        409 => "Conflict",
        413 => "Payload Too Large",
        422 => "Unprocessable Content",
        _ => "Error",
    };
    let mut head = format!(
        "HTTP/1.1 {} {reason}\r\nContent-Type: {}\r\nContent-Length: {}\r\nCache-Control: no-store\r\n\
         X-Content-Type-Options: nosniff\r\nConnection: close\r\n",
        response.status,
        response.content_type,
        response.body.len()
    );
    for (name, value) in &response.headers {
        head.push_str(&format!("{name}: {value}\r\n"));
    }
    head.push_str("\r\n");
    let _ = stream.write_all(head.as_bytes());
    let _ = stream.write_all(&response.body);
    let _ = stream.flush();
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::net::TcpListener;

    fn round_trip(raw: &[u8]) -> Result<Request, Response> {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let address = listener.local_addr().unwrap();
        let raw = raw.to_vec();
        let client = std::thread::spawn(move || {
            let mut stream = TcpStream::connect(address).unwrap();
            stream.write_all(&raw).unwrap();
            stream.shutdown(std::net::Shutdown::Write).unwrap();
            stream
        });
        let (stream, _) = listener.accept().unwrap();
        let request = read_request(&stream);
        drop(client.join().unwrap());
        request
    }

    #[test]
    fn a_post_is_read_with_its_body_and_host() {
        let request = round_trip(
            b"POST /pose?x=1 HTTP/1.1\r\nHost: 127.0.0.1:9\r\nContent-Length: 4\r\n\r\n{}  ",
        )
        .ok()
        .unwrap();
        assert_eq!(
            (request.method.as_str(), request.path.as_str()),
            ("POST", "/pose")
        );
        assert_eq!(request.host.as_deref(), Some("127.0.0.1:9"));
        assert_eq!(request.body, b"{}  ");
    }

    #[test]
    fn bad_requests_are_answered_not_panicked_on() {
        for raw in [
            &b"\r\n\r\n"[..],
            b"GET / HTTP/1.1\r\nno colon\r\n\r\n",
            b"POST / HTTP/1.1\r\nContent-Length: 99999999999\r\n\r\n",
            b"POST / HTTP/1.1\r\nContent-Length: 10\r\n\r\nab",
        ] {
            let status = round_trip(raw).err().map(|r| r.status);
            assert!(matches!(status, Some(400 | 413)), "{raw:?}: {status:?}");
        }
    }
}
