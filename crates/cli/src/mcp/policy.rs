//! What the MCP server lets its clients read. An agent passes on paths and text it got from anywhere (a
//! downloaded robot, a web page), so the server runs in untrusted mode unless started with `--trusted`:
//! every path argument must be inside the `--root` folders and the roots the client declares
//! (`roots/list`; neither: the server's working directory),
//! validations run with the sandbox (`--untrusted`, those roots, `--allow-env`), `xml` is bounded in
//! size and every call in time.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::sync::{PoisonError, RwLock};

use urdf_validate_session::Request;

/// Largest `xml` / `urdf_xml` argument accepted in untrusted mode.
pub const MAX_XML_BYTES: usize = 4 * 1024 * 1024;

/// The server's policy: set at start, its client roots replaced when the client announces them.
static POLICY: RwLock<Option<Policy>> = RwLock::new(None);

/// What the server's clients may read.
#[derive(Clone, Debug)]
pub struct Policy {
    /// `--trusted`: no restriction (the CLI's default behaviour).
    trusted: bool,
    /// The `--root` folders, canonical.
    flag_roots: Vec<PathBuf>,
    /// The folders the client declared (`roots/list`), canonical; `None` while it has declared none.
    client_roots: Option<Vec<PathBuf>>,
    /// The working directory, canonical: the root when neither the flags nor the client name one.
    working_dir: Option<PathBuf>,
    /// `--allow-env` variables.
    allow_env: Vec<String>,
}

impl Policy {
    /// The policy of `urdf_validate mcp ARGS`: `--root DIR` and `--allow-env NAME` (repeatable),
    /// `--trusted`. An unknown argument or a root that is not a folder is an error naming it.
    pub fn parse(args: &[OsString]) -> Result<Policy, String> {
        let mut policy = Policy {
            trusted: false,
            flag_roots: Vec::new(),
            client_roots: None,
            working_dir: std::env::current_dir().and_then(|d| d.canonicalize()).ok(),
            allow_env: Vec::new(),
        };
        let mut args = args.iter().map(|a| a.to_string_lossy().into_owned());
        while let Some(arg) = args.next() {
            let (flag, inline) = match arg.split_once('=') {
                Some((flag, value)) => (flag.to_string(), Some(value.to_string())),
                None => (arg.clone(), None),
            };
            match flag.as_str() {
                "--trusted" if inline.is_none() => policy.trusted = true,
                "--root" | "--allow-env" => {
                    let value = inline.or_else(|| args.next()).ok_or_else(|| {
                        format!("{flag} needs a value (--root DIR, --allow-env NAME)")
                    })?;
                    if flag == "--root" {
                        let root = Path::new(&value).canonicalize().ok().filter(|p| p.is_dir());
                        policy.flag_roots.push(root.ok_or_else(|| {
                            format!("--root {value}: no such folder (expected a folder the server may read)")
                        })?);
                    } else {
                        policy.allow_env.push(value);
                    }
                }
                _ => {
                    return Err(format!(
                        "unexpected argument '{arg}' (expected --root DIR, --allow-env NAME or --trusted; to validate a file named mcp, write ./mcp)"
                    ))
                }
            }
        }
        Ok(policy)
    }

    /// Make this the server's policy.
    pub fn install(self) {
        *POLICY.write().unwrap_or_else(PoisonError::into_inner) = Some(self);
    }

    /// The server's policy (untrusted, rooted at the working directory, when none was installed).
    pub fn current() -> Policy {
        let installed = POLICY
            .read()
            .unwrap_or_else(PoisonError::into_inner)
            .clone();
        installed.unwrap_or_else(|| {
            Policy::parse(&[]).unwrap_or(Policy {
                trusted: false,
                flag_roots: Vec::new(),
                client_roots: None,
                working_dir: None,
                allow_env: Vec::new(),
            })
        })
    }

    /// The client declared `uris` as its roots (`roots/list`): they replace its earlier ones. A root that is
    /// not a `file://` URI of an existing folder is left out; the list of those left out comes back.
    pub fn set_client_roots(uris: &[String]) -> Vec<String> {
        let mut roots = Vec::new();
        let mut refused = Vec::new();
        for uri in uris {
            match url::Url::parse(uri)
                .ok()
                .filter(|url| url.scheme() == "file")
                .and_then(|url| url.to_file_path().ok())
                .and_then(|path| path.canonicalize().ok())
                .filter(|path| path.is_dir())
            {
                Some(root) => roots.push(root),
                None => refused.push(uri.clone()),
            }
        }
        let mut guard = POLICY.write().unwrap_or_else(PoisonError::into_inner);
        let mut policy = guard.take().unwrap_or_else(Policy::current);
        policy.client_roots = Some(roots);
        *guard = Some(policy);
        refused
    }

    /// True once the client declared its roots.
    pub fn has_client_roots(&self) -> bool {
        self.client_roots.is_some()
    }

    /// The folders path arguments must be inside: the `--root` folders and the client's roots; the
    /// working directory when there are neither.
    fn roots(&self) -> Vec<PathBuf> {
        let mut roots = self.flag_roots.clone();
        roots.extend(self.client_roots.iter().flatten().cloned());
        if roots.is_empty() {
            roots.extend(self.working_dir.clone());
        }
        roots
    }

    /// Put `request` under this policy: untrusted, reading only below the roots and the allowed variables
    /// (nothing changes for a `--trusted` server).
    pub fn apply(&self, request: &mut Request) {
        if self.trusted {
            return;
        }
        request.untrusted = true;
        request.root.extend(self.roots());
        request.allow_env.extend(self.allow_env.iter().cloned());
    }

    /// `Ok` when the path argument `name` = `path` is inside a root (symlinks resolved); a path that does
    /// not exist is left to the tool's own message.
    pub fn check_path(&self, name: &str, path: &Path) -> Result<(), String> {
        if self.trusted {
            return Ok(());
        }
        let Ok(canonical) = path.canonicalize() else {
            return Ok(());
        };
        let roots = self.roots();
        if roots.iter().any(|root| canonical.starts_with(root)) {
            return Ok(());
        }
        let roots: Vec<String> = roots.iter().map(|r| r.display().to_string()).collect();
        Err(format!(
            "{name} {}: outside the folders this server may read ({}); declare it as a root of the client, or start the server with --root DIR",
            path.display(),
            roots.join(", ")
        ))
    }

    /// `Ok` when an `xml` argument is within [`MAX_XML_BYTES`] (untrusted mode).
    pub fn check_xml(&self, xml: &str) -> Result<(), String> {
        if self.trusted || xml.len() <= MAX_XML_BYTES {
            return Ok(());
        }
        Err(format!(
            "xml is {} bytes; this server takes at most {MAX_XML_BYTES} bytes of URDF text",
            xml.len()
        ))
    }

    /// `Ok` unless `timeout` asks for no time limit (0) in untrusted mode: every call is bounded.
    pub fn check_timeout(&self, timeout: Option<f64>) -> Result<(), String> {
        match timeout {
            Some(seconds) if !self.trusted && (seconds.is_nan() || seconds <= 0.0) => Err(format!(
                "timeout {seconds}: this server bounds every call; give a number of seconds above 0 (default 60)"
            )),
            _ => Ok(()),
        }
    }
}
