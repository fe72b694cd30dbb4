//! The sandbox policy for untrusted robot files: which files a validation may read and which environment
//! variables it may see. Every stage that opens a file the robot names (xacro includes and `load_yaml`,
//! `package://`, `file://` and `model://` meshes, SDFormat includes, the SRDF) or reads a variable
//! (`$(env)`, `$(optenv)`, `ROS_PACKAGE_PATH`, `AMENT_PREFIX_PATH`, `GZ_SIM_RESOURCE_PATH`) asks this one
//! policy first; a refusal becomes an `access-refused` finding at the span that asked.
//!
//! Trusted (the default, the CLI without `--untrusted`): everything is allowed, as before. Untrusted:
//! - files are read only from the roots (the input's folder tree, or its git work tree; `--package-path`
//!   folders; `--root` folders), every path canonicalised (symlinks resolved) before the check;
//! - only regular files are read (no devices, FIFOs or sockets);
//! - only the variables of the allow-list (`--allow-env`) are seen; by default none.

use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Which files and environment variables a validation may read; cheap to clone.
#[derive(Clone, Debug, Default)]
pub struct Sandbox {
    /// `None`: trusted, everything is allowed.
    policy: Option<Arc<Policy>>,
}

#[derive(Debug)]
struct Policy {
    /// Canonical folders files may be read from.
    roots: Vec<PathBuf>,
    /// Environment variables that may be read.
    env: Vec<String>,
}

/// Why an access was refused, in one phrase (never the file's content).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal(pub String);

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl Sandbox {
    /// The untrusted policy: files only below `roots` (canonicalised; folders that do not exist are
    /// dropped), only the variables named in `allow_env`.
    pub fn untrusted(
        roots: impl IntoIterator<Item = PathBuf>,
        allow_env: impl IntoIterator<Item = String>,
    ) -> Sandbox {
        let mut policy = Policy {
            roots: Vec::new(),
            env: allow_env.into_iter().collect(),
        };
        add_roots(&mut policy.roots, roots);
        Sandbox {
            policy: Some(Arc::new(policy)),
        }
    }

    /// Whether the policy restricts anything.
    pub fn is_untrusted(&self) -> bool {
        self.policy.is_some()
    }

    /// The canonical root folders (empty when trusted).
    pub fn roots(&self) -> &[PathBuf] {
        self.policy.as_ref().map_or(&[], |p| &p.roots)
    }

    /// The policy for validating the file `input`: its folder tree (the git work tree holding it, when
    /// there is one) is added to the roots. Trusted stays trusted.
    pub fn for_input(&self, input: &Path) -> Sandbox {
        let Some(policy) = &self.policy else {
            return self.clone();
        };
        let dir = match input.parent() {
            Some(dir) if !dir.as_os_str().is_empty() => dir,
            _ => Path::new("."),
        };
        let Ok(dir) = dir.canonicalize() else {
            return self.clone();
        };
        let tree = dir
            .ancestors()
            .find(|a| a.join(".git").exists())
            .unwrap_or(&dir)
            .to_path_buf();
        let mut roots = policy.roots.clone();
        add_roots(&mut roots, [tree]);
        Sandbox {
            policy: Some(Arc::new(Policy {
                roots,
                env: policy.env.clone(),
            })),
        }
    }

    /// The value of environment variable `name` (`Ok(None)` when unset), or a refusal when the policy
    /// does not let it be read.
    pub fn var(&self, name: &str) -> Result<Option<String>, Refusal> {
        match &self.policy {
            Some(policy) if !policy.env.iter().any(|n| n == name) => Err(Refusal(format!(
                "not on the allow-list (untrusted mode; --allow-env {name} lets it through)"
            ))),
            _ => Ok(std::env::var(name).ok()),
        }
    }

    /// Whether the file at `path` may be read: always when trusted; when untrusted, a path that does not
    /// exist is left to the caller's not-found handling, and an existing one must be a regular file whose
    /// canonical path is inside a root.
    pub fn check_file(&self, path: &Path) -> Result<(), Refusal> {
        let Some(canonical) = self.check_inside(path)? else {
            return Ok(());
        };
        match std::fs::metadata(&canonical) {
            Ok(meta) if !meta.is_file() => Err(Refusal(
                "not a regular file (untrusted mode reads no devices, FIFOs, sockets or folders)"
                    .to_string(),
            )),
            _ => Ok(()),
        }
    }

    /// Whether the folder `path` may be looked into (listed, or files below it probed): the same root
    /// check as [`Self::check_file`], without the regular-file one.
    pub fn check_dir(&self, path: &Path) -> Result<(), Refusal> {
        self.check_inside(path).map(|_| ())
    }

    /// `path` canonicalised when the policy applies and the path exists, refused when outside the roots.
    fn check_inside(&self, path: &Path) -> Result<Option<PathBuf>, Refusal> {
        let Some(policy) = &self.policy else {
            return Ok(None);
        };
        let Ok(canonical) = path.canonicalize() else {
            return Ok(None);
        };
        if policy.roots.iter().any(|root| canonical.starts_with(root)) {
            Ok(Some(canonical))
        } else {
            Err(Refusal(
                "outside the folders untrusted mode may read (the input's folder tree, --package-path, --root)"
                    .to_string(),
            ))
        }
    }
}

/// Add the canonical form of each existing folder of `new` to `roots`, once.
fn add_roots(roots: &mut Vec<PathBuf>, new: impl IntoIterator<Item = PathBuf>) {
    for root in new {
        if let Ok(canonical) = root.canonicalize() {
            if canonical.is_dir() && !roots.contains(&canonical) {
                roots.push(canonical);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("sandbox_{name}_{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("root/sub")).unwrap();
        std::fs::create_dir_all(dir.join("outside")).unwrap();
        std::fs::write(dir.join("root/sub/a.stl"), "x").unwrap();
        std::fs::write(dir.join("outside/secret"), "x").unwrap();
        dir
    }

    #[test]
    fn trusted_allows_everything() {
        let sandbox = Sandbox::default();
        assert!(sandbox.check_file(Path::new("/etc/hostname")).is_ok());
        assert!(sandbox.var("PATH").is_ok());
    }

    #[test]
    fn untrusted_reads_only_regular_files_inside_the_roots() {
        let dir = temp("roots");
        let sandbox = Sandbox::untrusted([dir.join("root")], []);
        assert!(sandbox.check_file(&dir.join("root/sub/a.stl")).is_ok());
        assert!(sandbox
            .check_file(&dir.join("root/sub/../../outside/secret"))
            .is_err());
        assert!(sandbox.check_file(&dir.join("outside/secret")).is_err());
        assert!(
            sandbox.check_file(&dir.join("root/sub")).is_err(),
            "a folder is not a regular file"
        );
        assert!(sandbox.check_dir(&dir.join("root/sub")).is_ok());
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(dir.join("outside/secret"), dir.join("root/link.stl"))
                .unwrap();
            std::os::unix::fs::symlink("/dev/zero", dir.join("root/zero.stl")).unwrap();
            assert!(sandbox.check_file(&dir.join("root/link.stl")).is_err());
            assert!(sandbox.check_file(&dir.join("root/zero.stl")).is_err());
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn untrusted_sees_only_allowed_variables() {
        let sandbox = Sandbox::untrusted([], ["PATH".to_string()]);
        assert!(sandbox.var("PATH").is_ok());
        assert!(sandbox.var("HOME").is_err());
    }

    #[test]
    fn the_input_folder_becomes_a_root() {
        let dir = temp("input");
        let sandbox = Sandbox::untrusted([], []).for_input(&dir.join("root/sub/robot.urdf"));
        assert!(sandbox.check_file(&dir.join("root/sub/a.stl")).is_ok());
        assert!(sandbox.check_file(&dir.join("outside/secret")).is_err());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
