//! What the MCP server lets its clients read. An agent passes on paths and text it got from anywhere (a
//! downloaded robot, a web page), so the server runs in untrusted mode unless started with `--trusted`:
//! every path argument must be inside the `--root` folders (default: the server's working directory),
//! validations run with the sandbox (`--untrusted`, those roots, `--allow-env`), `xml` is bounded in
//! size and every call in time.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Largest `xml` / `urdf_xml` argument accepted in untrusted mode.
pub const MAX_XML_BYTES: usize = 4 * 1024 * 1024;

/// The server's policy, set once at start.
static POLICY: OnceLock<Policy> = OnceLock::new();

/// What the server's clients may read.
#[derive(Clone, Debug)]
pub struct Policy {
    /// `--trusted`: no restriction (the CLI's default behaviour).
    trusted: bool,
    /// Canonical folders path arguments must be inside.
    roots: Vec<PathBuf>,
    /// `--allow-env` variables.
    allow_env: Vec<String>,
}

impl Policy {
    /// The policy of `urdf_validate mcp ARGS`: `--root DIR` and `--allow-env NAME` (repeatable),
    /// `--trusted`. An unknown argument or a root that is not a folder is an error naming it.
    pub fn parse(args: &[OsString]) -> Result<Policy, String> {
        let mut policy = Policy {
            trusted: false,
            roots: Vec::new(),
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
                        policy.roots.push(root.ok_or_else(|| {
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
        if policy.roots.is_empty() {
            policy
                .roots
                .extend(std::env::current_dir().and_then(|d| d.canonicalize()).ok());
        }
        Ok(policy)
    }

    /// Make this the server's policy (once; later calls change nothing).
    pub fn install(self) {
        let _ = POLICY.set(self);
    }

    /// The server's policy (untrusted, rooted at the working directory, when none was installed).
    pub fn current() -> &'static Policy {
        POLICY.get_or_init(|| {
            Policy::parse(&[]).unwrap_or(Policy {
                trusted: false,
                roots: Vec::new(),
                allow_env: Vec::new(),
            })
        })
    }

    /// The `urdf_validate` flags that run a validation under this policy.
    pub fn flags(&self) -> Vec<String> {
        if self.trusted {
            return Vec::new();
        }
        let mut flags = vec!["--untrusted".to_string()];
        flags.extend(self.roots.iter().map(|r| format!("--root={}", r.display())));
        flags.extend(self.allow_env.iter().map(|n| format!("--allow-env={n}")));
        flags
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
        if self.roots.iter().any(|root| canonical.starts_with(root)) {
            return Ok(());
        }
        let roots: Vec<String> = self.roots.iter().map(|r| r.display().to_string()).collect();
        Err(format!(
            "{name} {}: outside the folders this server may read ({}); start the server with --root DIR to allow another folder",
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
