//! `urdf_validate view ROBOT [--port N] [--open] [FLAGS...]`: the robot in 3-D in a browser, served from
//! 127.0.0.1 only. The page (the library's viewer, bundled in the binary), the scene JSON and a pose
//! endpoint: `POST /pose` with joint positions answers the link placements and the statics and stability
//! overlays at that pose, computed by the validator's own analyses. The page is served at once and the
//! robot validated meanwhile (the other routes wait for it); a file that does not validate is served with
//! its error. The file and what it includes are polled; when one changes the robot is validated again and
//! the page reloads its scene. The server reads
//! nothing but the robot (through the same options and sandbox as the command, `--untrusted` included)
//! and serves nothing but its four routes.

mod http;

use std::collections::BTreeMap;
use std::ffi::OsString;
use std::io::Write;
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant, SystemTime};

use clap::{CommandFactory, FromArgMatches};
use urdf_validate_session::Session;
use urdf_validator::render::view::{page, scene, Poser};

use crate::args::Args;
use crate::request::{first_line, option_value, request_of};
use http::{read_request, write_response, Request, Response};

pub(crate) const HELP: &str = "\
Look at the robot: a local web page drawing it in 3-D with its centre of mass, support polygon, joints
coloured by gravity-torque margin, workspace and findings; joint sliders re-evaluate the statics.

Usage: urdf_validate view ROBOT [--port N] [--open] [FLAGS...]

  --port N   the port on 127.0.0.1 (default 8765; 0 picks a free one)
  --open     open the page in the system browser

FLAGS are those of urdf_validate (--package-path, --untrusted, --pose, --payload-mass, ...). The page
reloads when the file or a file it includes changes. Stop with Ctrl-C.
";

/// Run `urdf_validate view` with the words after `view`.
pub(crate) fn main(argv: &[OsString]) -> u8 {
    match run(argv) {
        Ok(()) => 0,
        Err(message) => {
            errln!("error: {message}");
            2
        }
    }
}

/// The words of `view`: its own flags, and the rest for the validation.
struct ViewArgs {
    port: u16,
    open: bool,
    rest: Vec<OsString>,
}

fn parse(argv: &[OsString]) -> Result<Option<ViewArgs>, String> {
    let mut parsed = ViewArgs {
        port: 8765,
        open: false,
        rest: vec!["urdf_validate".into()],
    };
    let mut words = argv.iter();
    while let Some(word) = words.next() {
        let text = word.to_string_lossy();
        if text == "-h" || text == "--help" {
            return Ok(None);
        }
        let port = option_value(&text, "--port", &mut words);
        match port {
            Some(value) => {
                parsed.port = value
                    .parse()
                    .map_err(|_| format!("view --port '{value}': expected a port number"))?;
            }
            None if text == "--open" => parsed.open = true,
            None => parsed.rest.push(word.clone()),
        }
    }
    Ok(Some(parsed))
}

fn run(argv: &[OsString]) -> Result<(), String> {
    let Some(parsed) = parse(argv)? else {
        out!("{HELP}");
        return Ok(());
    };
    let started = Instant::now();
    let matches = Args::command()
        .try_get_matches_from(&parsed.rest)
        .map_err(|e| first_line(&e.to_string()))?;
    let args = Args::from_arg_matches(&matches).map_err(|e| first_line(&e.to_string()))?;
    let (paths, request) = request_of(&args, &matches)?;
    let [path] = paths.as_slice() else {
        return Err(format!(
            "view takes one robot file (got {}); see urdf_validate view --help",
            paths.len()
        ));
    };
    let session = Session::new(&request, Some(path))?;
    if !path.is_file() {
        return Err(format!("{}: no such file", path.display()));
    }
    let listener = TcpListener::bind(("127.0.0.1", parsed.port))
        .map_err(|e| format!("cannot listen on 127.0.0.1:{}: {e}", parsed.port))?;
    let address = listener
        .local_addr()
        .map_err(|e| format!("cannot read the listening address: {e}"))?;
    // Served at once, validated meanwhile: the browser reads the page (and starts WebGL) while the
    // robot is validated; its scene request waits for the validation.
    let url = format!("http://{address}/");
    outln!("serving {} at {url} (Ctrl-C stops)", path.display());
    if parsed.open {
        open_browser(&url);
    }
    let state = Arc::new(State::default());
    {
        let (state, path) = (Arc::clone(&state), path.clone());
        std::thread::spawn(move || watch(&path, &session, &state, started));
    }
    let port = address.port();
    let title = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let title: Arc<str> = title.into();
    for stream in listener.incoming().flatten() {
        let (state, title) = (Arc::clone(&state), Arc::clone(&title));
        // A thread per connection: a slow client does not hold up the page's other requests.
        std::thread::spawn(move || serve(&stream, &state, &title, port));
    }
    Ok(())
}

/// What the page is shown, shared by the connections and the watcher: nothing until the first validation
/// has finished.
#[derive(Default)]
struct State {
    shown: Mutex<Option<Arc<Shown>>>,
    settled: Condvar,
}

impl State {
    /// What is shown, once the first validation has finished (`None`: the state is unusable).
    fn current(&self) -> Option<Arc<Shown>> {
        let guard = self.shown.lock().ok()?;
        let guard = self.settled.wait_while(guard, |s| s.is_none()).ok()?;
        guard.clone()
    }

    fn show(&self, shown: Shown) {
        if let Ok(mut slot) = self.shown.lock() {
            *slot = Some(Arc::new(shown));
            self.settled.notify_all();
        }
    }
}

/// One version of what is shown: the robot, or why the file could not be validated.
struct Shown {
    robot: Result<Robot, String>,
    version: u64,
}

/// A validated robot: its poser and its scene (serialised once).
struct Robot {
    poser: Poser,
    scene: String,
}

/// The files a robot was read from, with their modification times when read.
type Files = Vec<(PathBuf, Option<SystemTime>)>;

impl Robot {
    fn load(path: &Path, session: &Session) -> Result<(Robot, Files), String> {
        let inspection =
            urdf_validator::inspect(path, session.options()).map_err(|e| e.to_string())?;
        let files = stamped(
            inspection
                .validation
                .sources
                .iter()
                .map(|s| s.path().to_path_buf())
                .chain(std::iter::once(path.to_path_buf())),
        );
        let poser = Poser::new(inspection, session.options());
        let scene = serde_json::to_string(&scene::build(&poser))
            .map_err(|e| format!("{}: cannot serialise the scene: {e}", path.display()))?;
        Ok((Robot { poser, scene }, files))
    }
}

fn stamped(paths: impl Iterator<Item = PathBuf>) -> Files {
    paths
        .map(|p| {
            let time = modified(&p);
            (p, time)
        })
        .collect()
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// Validate the robot, then poll its files every half second and validate again when one changed. A
/// file that does not validate keeps the last robot shown (and says why on stderr); before any robot was
/// shown, the page says why.
fn watch(path: &Path, session: &Session, state: &State, started: Instant) {
    let mut files = stamped(std::iter::once(path.to_path_buf()));
    let mut version = 0;
    let mut shown_robot = false;
    loop {
        // A bug in the validator must not leave the page's requests waiting for ever.
        let loaded =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| Robot::load(path, session)))
                .unwrap_or_else(|_| {
                    Err(format!(
                        "{}: the validator stopped on an internal error (a bug: please report it)",
                        path.display()
                    ))
                });
        let failed = loaded.is_err();
        match loaded {
            Ok((robot, read)) => {
                files = read;
                version += 1;
                state.show(Shown {
                    robot: Ok(robot),
                    version,
                });
                if shown_robot {
                    errln!("{}: changed, reloaded", path.display());
                } else {
                    outln!(
                        "{}: validated in {} ms",
                        path.display(),
                        started.elapsed().as_millis()
                    );
                }
                shown_robot = true;
            }
            Err(message) if shown_robot => {
                errln!("{message} (the page keeps the last version)");
            }
            Err(message) => {
                errln!("{message} (the page shows it, and loads the file when it changes)");
                version += 1;
                state.show(Shown {
                    robot: Err(message),
                    version,
                });
            }
        }
        if failed {
            // Do not try again until the files change again.
            for (p, time) in &mut files {
                *time = modified(p);
            }
        }
        while !files.iter().any(|(p, time)| modified(p) != *time) {
            std::thread::sleep(Duration::from_millis(500));
        }
    }
}

fn serve(stream: &TcpStream, state: &State, title: &str, port: u16) {
    let response = match read_request(stream) {
        Ok(request) => respond(&request, state, title, port),
        Err(response) => response,
    };
    write_response(stream, &response);
}

/// Only requests addressed to this server by name (a page elsewhere cannot make a browser talk to it
/// through DNS rebinding), and only its four routes. The page is served at once; the others wait for the
/// first validation.
fn respond(request: &Request, state: &State, title: &str, port: u16) -> Response {
    let allowed = [format!("127.0.0.1:{port}"), format!("localhost:{port}")];
    if !request
        .host
        .as_ref()
        .is_some_and(|h| allowed.iter().any(|a| a == h))
    {
        return Response::error(403, "this server answers requests to 127.0.0.1 only");
    }
    let route = (request.method.as_str(), request.path.as_str());
    match route {
        ("GET", "/") => {
            return Response::new(200, "text/html; charset=utf-8", page::live_page(title))
        }
        ("GET", "/scene.json" | "/version") | ("POST", "/pose") => {}
        (_, "/" | "/scene.json" | "/version" | "/pose") => {
            return Response::error(405, "method not allowed")
        }
        _ => return Response::error(404, "not found"),
    }
    let Some(shown) = state.current() else {
        return Response::error(500, "the server's state is unusable");
    };
    let robot = match (&shown.robot, route) {
        (_, (_, "/version")) => return Response::new(200, "text/plain", shown.version.to_string()),
        (Err(message), (_, "/scene.json")) => {
            return Response::error(422, message).with_header("X-Scene-Version", shown.version)
        }
        (Err(message), _) => return Response::error(409, message),
        (Ok(robot), _) => robot,
    };
    if route.1 == "/scene.json" {
        return Response::new(200, "application/json", robot.scene.clone())
            .with_header("X-Scene-Version", shown.version);
    }
    match serde_json::from_slice::<BTreeMap<String, f64>>(&request.body) {
        Ok(values) => match serde_json::to_vec(&robot.poser.evaluate(&values)) {
            Ok(body) => Response::new(200, "application/json", body),
            Err(e) => Response::error(500, &format!("cannot serialise the pose: {e}")),
        },
        Err(e) => Response::error(
            400,
            &format!("expected a JSON object of joint names to numbers: {e}"),
        ),
    }
}

/// Open `url` in the system browser (xdg-open, open, start); a failure is said, not fatal.
fn open_browser(url: &str) {
    let mut command = if cfg!(target_os = "macos") {
        std::process::Command::new("open")
    } else if cfg!(windows) {
        let mut c = std::process::Command::new("cmd");
        c.args(["/C", "start", ""]);
        c
    } else {
        std::process::Command::new("xdg-open")
    };
    if let Err(e) = command.arg(url).spawn() {
        errln!("cannot open a browser ({e}); open {url}");
    }
}
