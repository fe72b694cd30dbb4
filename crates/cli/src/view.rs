//! `urdf_validate view ROBOT [--port N] [--open] [FLAGS...]`: the robot in 3-D in a browser, served from
//! 127.0.0.1 only. The page (the library's viewer, bundled in the binary), the scene JSON and a pose
//! endpoint: `POST /pose` with joint positions answers the link placements and the statics and stability
//! overlays at that pose, computed by the validator's own analyses. The file and what it includes are
//! polled; when one changes the robot is validated again and the page reloads its scene. The server reads
//! nothing but the robot (through the same options and sandbox as the command, `--untrusted` included)
//! and serves nothing but its four routes.

mod http;

use std::collections::BTreeMap;
use std::ffi::OsString;
use std::io::Write;
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::sync::{Arc, RwLock};
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
    let listener = TcpListener::bind(("127.0.0.1", parsed.port))
        .map_err(|e| format!("cannot listen on 127.0.0.1:{}: {e}", parsed.port))?;
    let address = listener
        .local_addr()
        .map_err(|e| format!("cannot read the listening address: {e}"))?;
    let shown = Shown::load(path, &session, 1)?;
    let state = Arc::new(RwLock::new(shown));
    let url = format!("http://{address}/");
    outln!(
        "serving {} at {url} (validated in {} ms; Ctrl-C stops)",
        path.display(),
        started.elapsed().as_millis()
    );
    if parsed.open {
        open_browser(&url);
    }
    {
        let (state, path) = (Arc::clone(&state), path.clone());
        std::thread::spawn(move || watch(&path, &session, &state));
    }
    let port = address.port();
    for stream in listener.incoming().flatten() {
        let state = Arc::clone(&state);
        // A thread per connection: a slow client does not hold up the page's other requests.
        std::thread::spawn(move || serve(&stream, &state, port));
    }
    Ok(())
}

/// What is shown: the robot's poser, its scene (serialised once), the files it was read from with their
/// modification times, and a version the page polls.
struct Shown {
    poser: Poser,
    scene: String,
    title: String,
    files: Vec<(PathBuf, Option<SystemTime>)>,
    version: u64,
}

impl Shown {
    fn load(path: &Path, session: &Session, version: u64) -> Result<Shown, String> {
        let inspection =
            urdf_validator::inspect(path, session.options()).map_err(|e| e.to_string())?;
        let files = inspection
            .validation
            .sources
            .iter()
            .map(|s| s.path().to_path_buf())
            .chain(std::iter::once(path.to_path_buf()))
            .map(|p| {
                let time = modified(&p);
                (p, time)
            })
            .collect();
        let title = inspection.validation.report.robot_name.clone();
        let poser = Poser::new(inspection, session.options());
        let scene = serde_json::to_string(&scene::build(&poser))
            .map_err(|e| format!("{}: cannot serialise the scene: {e}", path.display()))?;
        Ok(Shown {
            poser,
            scene,
            title,
            files,
            version,
        })
    }

    fn changed(&self) -> bool {
        self.files.iter().any(|(p, time)| modified(p) != *time)
    }
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// Poll the files every half second; validate again when one changed (a file that does not validate
/// keeps the last scene, and says why on stderr).
fn watch(path: &Path, session: &Session, state: &RwLock<Shown>) {
    loop {
        std::thread::sleep(Duration::from_millis(500));
        let (changed, version) = match state.read() {
            Ok(shown) => (shown.changed(), shown.version),
            Err(_) => return,
        };
        if !changed {
            continue;
        }
        match Shown::load(path, session, version + 1) {
            Ok(shown) => {
                if let Ok(mut slot) = state.write() {
                    *slot = shown;
                }
                errln!("{}: changed, reloaded", path.display());
            }
            Err(message) => {
                errln!("{message} (the page keeps the last version)");
                // Do not try again until the files change again.
                if let Ok(mut slot) = state.write() {
                    for (p, time) in &mut slot.files {
                        *time = modified(p);
                    }
                }
            }
        }
    }
}

fn serve(stream: &TcpStream, state: &RwLock<Shown>, port: u16) {
    let response = match read_request(stream) {
        Ok(request) => respond(&request, state, port),
        Err(response) => response,
    };
    write_response(stream, &response);
}

/// Only requests addressed to this server by name (a page elsewhere cannot make a browser talk to it
/// through DNS rebinding), and only its four routes.
fn respond(request: &Request, state: &RwLock<Shown>, port: u16) -> Response {
    let allowed = [format!("127.0.0.1:{port}"), format!("localhost:{port}")];
    if !request
        .host
        .as_ref()
        .is_some_and(|h| allowed.iter().any(|a| a == h))
    {
        return Response::error(403, "this server answers requests to 127.0.0.1 only");
    }
    let Ok(shown) = state.read() else {
        return Response::error(500, "the server's state is unusable");
    };
    match (request.method.as_str(), request.path.as_str()) {
        ("GET", "/") => Response::new(
            200,
            "text/html; charset=utf-8",
            page::live_page(&shown.title),
        ),
        ("GET", "/scene.json") => Response::new(200, "application/json", shown.scene.clone()),
        ("GET", "/version") => Response::new(200, "text/plain", shown.version.to_string()),
        ("POST", "/pose") => match serde_json::from_slice::<BTreeMap<String, f64>>(&request.body) {
            Ok(values) => match serde_json::to_vec(&shown.poser.evaluate(&values)) {
                Ok(body) => Response::new(200, "application/json", body),
                Err(e) => Response::error(500, &format!("cannot serialise the pose: {e}")),
            },
            Err(e) => Response::error(
                400,
                &format!("expected a JSON object of joint names to numbers: {e}"),
            ),
        },
        (_, "/" | "/scene.json" | "/version" | "/pose") => {
            Response::error(405, "method not allowed")
        }
        _ => Response::error(404, "not found"),
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
