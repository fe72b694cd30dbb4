//! Resolution of mesh and resource URIs (`package://`, `file://`, plain
//! paths) to files on disk, without a ROS installation.
//!
//! Package lookup order: explicit `--package-path` entries, then
//! `ROS_PACKAGE_PATH`, then `AMENT_PREFIX_PATH`, then the ancestors of the
//! URDF's directory.
//!
//! `model://NAME` (SDFormat) lookup order: `GZ_SIM_RESOURCE_PATH`, `IGN_GAZEBO_RESOURCE_PATH` and
//! `SDF_PATH` entries, then the `--package-path` folders, then the ancestors of the file's directory
//! (`A/NAME`, or `A` itself when named NAME).

use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};
use std::sync::{Arc, Mutex};

use crate::input::sandbox::{Refusal, Sandbox};

/// Maximum depth of the recursive search below a `ROS_PACKAGE_PATH` entry.
const ROS_SEARCH_DEPTH: usize = 4;
/// Maximum number of directories visited when walking up from the URDF.
const MAX_WALK_UP: usize = 64;

/// Where to look for ROS packages, collected once per run.
#[derive(Debug, Clone, Default)]
pub struct PackageResolver {
    explicit: Vec<PathBuf>,
    ros_paths: Vec<PathBuf>,
    ament_prefixes: Vec<PathBuf>,
    /// Gazebo model folders (`GZ_SIM_RESOURCE_PATH`, `IGN_GAZEBO_RESOURCE_PATH`, `SDF_PATH`), in order.
    model_paths: Vec<PathBuf>,
    /// Package name -> candidate package roots from the explicit,
    /// `ROS_PACKAGE_PATH` and `AMENT_PREFIX_PATH` sources (in order).
    cache: Arc<Mutex<HashMap<String, Vec<PathBuf>>>>,
    /// (package name, start folder) -> package roots found by walking up;
    /// every mesh of a URDF asks the same question.
    walk_cache: Arc<Mutex<WalkCache>>,
    /// What files may be read (every resolution is checked against it).
    sandbox: Sandbox,
}

type WalkCache = HashMap<(String, PathBuf), Vec<PathBuf>>;

/// Outcome of resolving one URI.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Resolution {
    /// The file exists at this path.
    Found(PathBuf),
    /// The URI is well-formed but no file exists; `searched` lists every
    /// candidate path tried, in order (for the user message "looked in ...").
    /// For `package://` URIs it is empty when the package itself was not
    /// found anywhere.
    NotFound {
        /// Candidate file paths tried, in search order, without duplicates.
        searched: Vec<PathBuf>,
    },
    /// A scheme we cannot resolve offline (http://, https://, model://, etc.)
    /// or a malformed URI; the String says why in one short sentence.
    Unsupported(String),
    /// The file exists but the sandbox does not let it be read (untrusted mode).
    Refused(Refusal),
    /// ROS refuses the URI (`why`), but Pinocchio, MuJoCo and Gazebo find the file at `path`: the
    /// analyses read it, and the check says ROS will not.
    Lenient {
        /// The file the other loaders read.
        path: PathBuf,
        /// Why ROS's resource_retriever refuses the URI, in one sentence.
        why: String,
    },
}

impl Resolution {
    /// The file the analyses read: a found file, or one found only by the loaders more lenient than ROS.
    pub fn found(&self) -> Option<&PathBuf> {
        match self {
            Resolution::Found(path) | Resolution::Lenient { path, .. } => Some(path),
            _ => None,
        }
    }
}

/// Why an SDFormat `<include>` gives no file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum IncludeFailure {
    /// Not found, or not a model; says what was tried.
    Unresolved(String),
    /// Found, but the sandbox does not let it be read.
    Refused(Refusal),
}

impl PackageResolver {
    /// Explicit `--package-path DIR` entries (in order) plus the
    /// `ROS_PACKAGE_PATH` and `AMENT_PREFIX_PATH` values given
    /// (colon-separated strings, may be None).
    pub fn new(
        package_paths: Vec<PathBuf>,
        ros_package_path: Option<&str>,
        ament_prefix_path: Option<&str>,
    ) -> Self {
        Self {
            explicit: package_paths
                .into_iter()
                .filter(|p| !p.as_os_str().is_empty())
                .collect(),
            ros_paths: split_path_list(ros_package_path),
            ament_prefixes: split_path_list(ament_prefix_path),
            model_paths: Vec::new(),
            cache: Arc::default(),
            walk_cache: Arc::default(),
            sandbox: Sandbox::default(),
        }
    }

    /// This resolver checking every file it resolves against `sandbox` (the search caches are shared).
    pub fn with_sandbox(&self, sandbox: Sandbox) -> Self {
        Self {
            sandbox,
            ..self.clone()
        }
    }

    /// The sandbox every resolution is checked against.
    pub fn sandbox(&self) -> &Sandbox {
        &self.sandbox
    }

    /// Same, reading `ROS_PACKAGE_PATH`, `AMENT_PREFIX_PATH` and the Gazebo model path variables
    /// (`GZ_SIM_RESOURCE_PATH`, `IGN_GAZEBO_RESOURCE_PATH`, `SDF_PATH`) from the process environment.
    pub fn from_env(package_paths: Vec<PathBuf>) -> Self {
        Self::from_env_in(package_paths, &Sandbox::default())
    }

    /// Same, reading only the variables `sandbox` lets through (untrusted mode: none unless allowed), and
    /// checking every resolution against it.
    pub fn from_env_in(package_paths: Vec<PathBuf>, sandbox: &Sandbox) -> Self {
        let var = |name| sandbox.var(name).ok().flatten();
        let ros = var("ROS_PACKAGE_PATH");
        let ament = var("AMENT_PREFIX_PATH");
        let models = [
            "GZ_SIM_RESOURCE_PATH",
            "IGN_GAZEBO_RESOURCE_PATH",
            "SDF_PATH",
        ]
        .map(var);
        Self::new(package_paths, ros.as_deref(), ament.as_deref())
            .with_model_paths(models.iter().map(Option::as_deref))
            .with_sandbox(sandbox.clone())
    }

    /// Add Gazebo model folders, each value a `PATH`-style list (`GZ_SIM_RESOURCE_PATH`, ...), searched
    /// in order for `model://NAME`.
    pub fn with_model_paths<'a>(
        mut self,
        lists: impl IntoIterator<Item = Option<&'a str>>,
    ) -> Self {
        for list in lists {
            for path in split_path_list(list) {
                push_unique(&mut self.model_paths, path);
            }
        }
        self
    }

    /// Resolve a URI as it appears in a `<mesh filename="...">` (or any
    /// resource attribute), for a URDF living in `urdf_dir`.
    pub fn resolve(&self, uri: &str, urdf_dir: &Path) -> Resolution {
        match self.resolve_unchecked(uri, urdf_dir) {
            Resolution::Found(path) => match self.sandbox.check_file(&path) {
                Ok(()) => Resolution::Found(path),
                Err(refusal) => Resolution::Refused(refusal),
            },
            Resolution::Lenient { path, why } => match self.sandbox.check_file(&path) {
                Ok(()) => Resolution::Lenient { path, why },
                Err(refusal) => Resolution::Refused(refusal),
            },
            // Untrusted mode says why a device or a FIFO named like a mesh is not read.
            Resolution::NotFound { searched } if self.sandbox.is_untrusted() => {
                let refused = searched
                    .iter()
                    .filter(|path| path.exists())
                    .find_map(|path| self.sandbox.check_file(path).err());
                match refused {
                    Some(refusal) => Resolution::Refused(refusal),
                    None => Resolution::NotFound { searched },
                }
            }
            other => other,
        }
    }

    /// [`Self::resolve`] before the sandbox check.
    fn resolve_unchecked(&self, uri: &str, urdf_dir: &Path) -> Resolution {
        let uri = uri.trim();
        if uri.is_empty() {
            return Resolution::Unsupported("the URI is empty".to_string());
        }
        let Some((scheme, rest)) = split_scheme(uri) else {
            return resolve_file(absolute_or_relative(Path::new(uri), urdf_dir));
        };
        if scheme.eq_ignore_ascii_case("package") {
            self.resolve_package(rest, urdf_dir)
        } else if scheme.eq_ignore_ascii_case("file") {
            resolve_file_uri(rest, urdf_dir)
        } else if scheme.eq_ignore_ascii_case("model") {
            self.resolve_model(rest, urdf_dir)
        } else {
            Resolution::Unsupported(format!("URI scheme '{scheme}' cannot be resolved offline"))
        }
    }

    /// Resolve just a package name to its directory (used by xacro
    /// `$(find pkg)`), with the same search order as [`Self::resolve`];
    /// None when not found.
    pub fn find_package(&self, package: &str, start_dir: &Path) -> Option<PathBuf> {
        self.find_package_searched(package, start_dir).0
    }

    /// Like [`Self::find_package`], also returning every candidate package
    /// directory tried, in order and without duplicates.
    pub fn find_package_searched(
        &self,
        package: &str,
        start_dir: &Path,
    ) -> (Option<PathBuf>, Vec<PathBuf>) {
        if !valid_package_name(package) {
            return (None, Vec::new());
        }
        first_folder(self.package_roots(package, start_dir))
    }

    /// The folder of Gazebo model `name` (`model://name`), searched from `start_dir`, and every folder
    /// tried, in order.
    pub fn find_model_searched(
        &self,
        name: &str,
        start_dir: &Path,
    ) -> (Option<PathBuf>, Vec<PathBuf>) {
        if !valid_package_name(name) {
            return (None, Vec::new());
        }
        first_folder(self.model_roots(name, start_dir))
    }

    /// The SDFormat file an `<include><uri>` names, for a file in `dir`: `model://NAME[/path]`, `file://`
    /// or a plain path, to a file or to a model folder (then its `model.config` decides, see
    /// [`model_sdf_file`]). The error says what was tried.
    pub fn resolve_include(&self, uri: &str, dir: &Path) -> Result<PathBuf, IncludeFailure> {
        let path = self
            .resolve_include_unchecked(uri, dir)
            .map_err(IncludeFailure::Unresolved)?;
        self.sandbox
            .check_file(&path)
            .map_err(IncludeFailure::Refused)?;
        Ok(path)
    }

    /// [`Self::resolve_include`] before the sandbox check of the file found (a model folder's
    /// `model.config` is read only when the sandbox allows it).
    fn resolve_include_unchecked(&self, uri: &str, dir: &Path) -> Result<PathBuf, String> {
        let uri = uri.trim();
        let target = match split_scheme(uri) {
            Some((scheme, rest)) if scheme.eq_ignore_ascii_case("model") => {
                let (name, inner) = rest.split_once('/').unwrap_or((rest, ""));
                inside(
                    self.find_model_searched(name, dir),
                    inner,
                    &format!("model '{name}'"),
                    "GZ_SIM_RESOURCE_PATH, IGN_GAZEBO_RESOURCE_PATH, SDF_PATH and --package-path are unset, and no folder of that name is above the file",
                    "set GZ_SIM_RESOURCE_PATH or pass --package-path with the folder holding it",
                )?
            }
            // Drake resolves it through its package map, Gazebo through the ROS package path: the
            // package search of URDF meshes (--package-path, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH,
            // package.xml above the file).
            Some((scheme, rest)) if scheme.eq_ignore_ascii_case("package") => {
                let (name, inner) = rest.split_once('/').unwrap_or((rest, ""));
                inside(
                    self.find_package_searched(name, dir),
                    inner,
                    &format!("package '{name}'"),
                    "--package-path, ROS_PACKAGE_PATH and AMENT_PREFIX_PATH are unset, and no folder of that name holding a package.xml is above the file",
                    "pass --package-path with the folder holding it, or set ROS_PACKAGE_PATH or AMENT_PREFIX_PATH",
                )?
            }
            Some((scheme, rest)) if scheme.eq_ignore_ascii_case("file") => {
                absolute_or_relative(Path::new(&percent_decode(rest)), dir)
            }
            Some((scheme, _)) => {
                return Err(format!(
                    "URI scheme '{scheme}' cannot be resolved offline (download the model and use model://, package:// or a path)"
                ))
            }
            None => absolute_or_relative(Path::new(uri), dir),
        };
        if target.is_file() {
            Ok(target)
        } else if target.is_dir() {
            self.sandbox
                .check_file(&target.join("model.config"))
                .map_err(|refusal| format!("{}: {refusal}", target.display()))?;
            model_sdf_file(&target)
        } else {
            Err(format!("{} does not exist", target.display()))
        }
    }

    /// Resolve the part of a `model://` URI after the scheme.
    fn resolve_model(&self, rest: &str, dir: &Path) -> Resolution {
        let (name, file) = rest.split_once('/').unwrap_or((rest, ""));
        let file = file.trim_start_matches('/');
        if !valid_package_name(name) || file.is_empty() {
            return Resolution::Unsupported(format!(
                "model://{rest} does not name a file inside a model folder"
            ));
        }
        first_file(self.model_roots(name, dir), file)
    }

    /// Candidate folders of model `name`: the Gazebo model paths, the `--package-path` folders, then the
    /// ancestors of `start_dir`.
    fn model_roots(&self, name: &str, start_dir: &Path) -> Vec<PathBuf> {
        let mut roots = Vec::new();
        for dir in self.model_paths.iter().chain(&self.explicit) {
            push_unique(&mut roots, dir.join(name));
            if dir_basename_is(dir, name) {
                push_unique(&mut roots, dir.clone());
            }
        }
        let abs = std::path::absolute(start_dir).unwrap_or_else(|_| start_dir.to_path_buf());
        for ancestor in normalize_lexically(&abs).ancestors().take(MAX_WALK_UP) {
            let child = ancestor.join(name);
            if child.is_dir() {
                push_unique(&mut roots, child);
            }
            if ancestor.file_name().is_some_and(|n| n == name) {
                push_unique(&mut roots, ancestor.to_path_buf());
            }
        }
        roots
    }

    /// Whether any package folder is configured (`--package-path`, `ROS_PACKAGE_PATH` or
    /// `AMENT_PREFIX_PATH`); without one, only the walk up from the file can find packages.
    pub fn has_configured_paths(&self) -> bool {
        !self.explicit.is_empty() || !self.ros_paths.is_empty() || !self.ament_prefixes.is_empty()
    }

    /// Resolve the part of a `package://` URI after the scheme.
    fn resolve_package(&self, rest: &str, urdf_dir: &Path) -> Resolution {
        let (package, file) = rest.split_once('/').unwrap_or((rest, ""));
        if package.is_empty() {
            // `package:///abs/path` (empty package name) is not a way to write an absolute path for ROS:
            // resource_retriever's `Retriever::get` (ros/resource_retriever, branch rolling at c87c432,
            // resource_retriever/src/retriever.cpp) takes the package name up to the first '/' and throws
            // "Package name must not be empty" when it is empty; ROS 1 (kinetic-devel at 8a83c6b,
            // src/retriever.cpp) asks `ros::package::getPath("")` and throws "Package [] does not exist".
            // RViz and MoveIt load meshes through it, so the mesh is not found there. Pinocchio joins each
            // package folder with the rest of the URI (`retrieveResourcePath`: `dir + "/" + path`), so
            // `package:///pkg/file` is `package://pkg/file` to it (example-robot-data's talos_full_v2 has
            // 93 such meshes), and MuJoCo's URDF import keeps only the file name: the analyses read that
            // file, and the check keeps saying that ROS does not.
            let why = "package:// URI has an empty package name; ROS's resource_retriever refuses it (\"Package name must not be empty\")";
            let as_package = file.trim_start_matches('/');
            if !as_package.is_empty() {
                if let Resolution::Found(path) = self.resolve_package(as_package, urdf_dir) {
                    return Resolution::Lenient {
                        path,
                        why: format!("{why}: write package://{as_package}"),
                    };
                }
            }
            return Resolution::Unsupported(format!(
                "{why}: write file://{} for an absolute path",
                file_part_for_hint(file)
            ));
        }
        if !valid_package_name(package) {
            return Resolution::Unsupported(format!("'{package}' is not a valid package name"));
        }
        let file = file.trim_start_matches('/');
        if file.is_empty() {
            return Resolution::Unsupported(format!(
                "package://{package} URI names no file inside the package"
            ));
        }
        first_file(self.package_roots(package, urdf_dir), file)
    }

    /// All candidate roots for `package`, in search order: the cached
    /// environment-based roots followed by the walk-up roots from `start_dir`.
    fn package_roots(&self, package: &str, start_dir: &Path) -> Vec<PathBuf> {
        let mut roots = self.configured_roots(package);
        let key = (package.to_string(), start_dir.to_path_buf());
        let cached = lock(&self.walk_cache).get(&key).cloned();
        let walked = cached.unwrap_or_else(|| {
            let walked = walk_up_roots(package, start_dir);
            lock(&self.walk_cache).insert(key, walked.clone());
            walked
        });
        roots.extend(walked);
        roots
    }

    /// Roots from (a) explicit paths, (b) `ROS_PACKAGE_PATH`,
    /// (c) `AMENT_PREFIX_PATH`; cached per package name.
    fn configured_roots(&self, package: &str) -> Vec<PathBuf> {
        if let Some(roots) = self.lock_cache().get(package) {
            return roots.clone();
        }
        let mut roots = Vec::new();
        for dir in &self.explicit {
            push_unique(&mut roots, dir.join(package));
            if dir_basename_is(dir, package)
                || self.package_xml_name(dir).as_deref() == Some(package)
            {
                push_unique(&mut roots, dir.clone());
            }
        }
        for entry in self
            .ros_paths
            .iter()
            .filter(|entry| self.sandbox.check_dir(entry).is_ok())
        {
            if dir_basename_is(entry, package) && has_package_xml(entry) {
                push_unique(&mut roots, entry.clone());
            }
            let direct = entry.join(package);
            if has_package_xml(&direct) {
                push_unique(&mut roots, direct);
            }
            let mut found = Vec::new();
            self.search_ros_tree(entry, package, &mut found);
            for dir in found {
                push_unique(&mut roots, dir);
            }
        }
        for prefix in &self.ament_prefixes {
            push_unique(&mut roots, prefix.join("share").join(package));
        }
        self.lock_cache().insert(package.to_string(), roots.clone());
        roots
    }

    /// The `<name>` declared in `dir/package.xml`, if readable and the sandbox allows it.
    fn package_xml_name(&self, dir: &Path) -> Option<String> {
        self.sandbox.check_file(&dir.join("package.xml")).ok()?;
        package_xml_name(dir)
    }

    /// Recursively collect packages named `package` below `dir`, at most [`ROS_SEARCH_DEPTH`] levels down
    /// (ROS 1 crawl): hidden directories are skipped and package directories are not descended into; a
    /// folder the sandbox refuses (a symlink out of the roots) is not entered. A package matches by folder
    /// name or by its `package.xml` `<name>`.
    fn search_ros_tree(&self, dir: &Path, package: &str, found: &mut Vec<PathBuf>) {
        let mut walk = walkdir::WalkDir::new(dir)
            .min_depth(1)
            .max_depth(ROS_SEARCH_DEPTH)
            .follow_links(true)
            .sort_by_file_name()
            .into_iter();
        while let Some(entry) = walk.next() {
            let Ok(entry) = entry else { continue };
            if !entry.file_type().is_dir() {
                continue;
            }
            let child = entry.path();
            if entry.file_name().to_string_lossy().starts_with('.')
                || self.sandbox.check_dir(child).is_err()
            {
                walk.skip_current_dir();
            } else if has_package_xml(child) {
                let matches = child.file_name().is_some_and(|n| n == package)
                    || self.package_xml_name(child).as_deref() == Some(package);
                if matches {
                    found.push(child.to_path_buf());
                }
                walk.skip_current_dir();
            }
        }
    }

    /// Lock the cache, recovering from a poisoned mutex (the map is always
    /// left consistent).
    fn lock_cache(&self) -> std::sync::MutexGuard<'_, HashMap<String, Vec<PathBuf>>> {
        lock(&self.cache)
    }
}

/// Lock a cache, recovering from a poisoned mutex (caches are always left consistent).
fn lock<T>(mutex: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(|e| e.into_inner())
}

/// Split `scheme://rest`; None when `uri` has no valid URI scheme.
fn split_scheme(uri: &str) -> Option<(&str, &str)> {
    let (scheme, rest) = uri.split_once("://")?;
    let mut chars = scheme.chars();
    let first_ok = chars.next().is_some_and(|c| c.is_ascii_alphabetic());
    let rest_ok = chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'));
    (first_ok && rest_ok).then_some((scheme, rest))
}

/// The path of a `package:///path` URI as an absolute path, for the `file://` hint.
fn file_part_for_hint(file: &str) -> String {
    format!("/{}", file.trim_start_matches('/'))
}

/// Resolve the part of a `file://` URI after the scheme.
fn resolve_file_uri(rest: &str, urdf_dir: &Path) -> Resolution {
    let rest = match rest.strip_prefix("localhost") {
        Some(path) if path.starts_with('/') => path,
        _ => rest,
    };
    if rest.is_empty() {
        return Resolution::Unsupported("file:// URI has no path".to_string());
    }
    let decoded = percent_decode(rest);
    resolve_file(absolute_or_relative(Path::new(&decoded), urdf_dir))
}

/// `path` as is when absolute, otherwise joined onto `base`.
fn absolute_or_relative(path: &Path, base: &Path) -> PathBuf {
    if path.is_absolute() {
        path.to_path_buf()
    } else {
        base.join(path)
    }
}

/// Found when `path` is an existing file, otherwise NotFound listing it.
fn resolve_file(path: PathBuf) -> Resolution {
    if path.is_file() {
        Resolution::Found(path)
    } else {
        Resolution::NotFound {
            searched: vec![path],
        }
    }
}

/// Decode `%XX` escapes; malformed escapes are kept literally.
fn percent_decode(s: &str) -> String {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hi = bytes.get(i + 1).and_then(|b| (*b as char).to_digit(16));
            let lo = bytes.get(i + 2).and_then(|b| (*b as char).to_digit(16));
            if let (Some(hi), Some(lo)) = (hi, lo) {
                // Two hex digits always fit in a byte.
                out.push((hi * 16 + lo) as u8);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    String::from_utf8(out).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
}

/// `inner` inside the folder `found` (a package or model search: the folder, and every folder tried), or
/// an error naming `what` was not found, where it was looked for (`nowhere` says why when no folder was
/// tried) and `hint`.
fn inside(
    found: (Option<PathBuf>, Vec<PathBuf>),
    inner: &str,
    what: &str,
    nowhere: &str,
    hint: &str,
) -> Result<PathBuf, String> {
    match found {
        (Some(folder), _) => Ok(folder.join(inner.trim_start_matches('/'))),
        (None, searched) if searched.is_empty() => Err(format!(
            "{what} not found; looked in no folder: {nowhere} ({hint})"
        )),
        (None, searched) => Err(format!(
            "{what} not found; looked in {} ({hint})",
            searched
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// The newest SDFormat version this validator reads; `model.config` entries above it are passed over.
pub const NEWEST_SDF_VERSION: (u32, u32) = (1, 11);

/// Largest `model.config` read.
const MAX_MODEL_CONFIG_BYTES: u64 = 1024 * 1024;

/// The SDFormat file of the Gazebo model folder `dir`: the `<sdf version>` entry of its `model.config`
/// with the highest version not above [`NEWEST_SDF_VERSION`] (else the highest), or `model.sdf` when
/// there is no `model.config`.
pub fn model_sdf_file(dir: &Path) -> Result<PathBuf, String> {
    let config = dir.join("model.config");
    if !config.is_file() {
        let fallback = dir.join("model.sdf");
        return if fallback.is_file() {
            Ok(fallback)
        } else {
            Err(format!(
                "{} holds neither model.config nor model.sdf",
                dir.display()
            ))
        };
    }
    let unreadable = |why: String| format!("{}: {why}", config.display());
    let size = std::fs::metadata(&config)
        .map_err(|e| unreadable(e.to_string()))?
        .len();
    if size > MAX_MODEL_CONFIG_BYTES {
        return Err(unreadable(format!("{size} bytes; not a model.config")));
    }
    let text = std::fs::read_to_string(&config).map_err(|e| unreadable(e.to_string()))?;
    let doc = roxmltree::Document::parse(&text).map_err(|e| unreadable(e.to_string()))?;
    let version = |node: roxmltree::Node| -> (u32, u32) {
        node.attribute("version")
            .and_then(|v| v.trim().split_once('.'))
            .and_then(|(a, b)| Some((a.parse().ok()?, b.parse().ok()?)))
            .unwrap_or((0, 0))
    };
    let entries: Vec<((u32, u32), &str)> = doc
        .root_element()
        .children()
        .filter(|n| n.has_tag_name("sdf"))
        .filter_map(|n| Some((version(n), n.text()?.trim())))
        .filter(|(_, file)| !file.is_empty())
        .collect();
    let best = entries
        .iter()
        .filter(|(v, _)| *v <= NEWEST_SDF_VERSION)
        .max_by_key(|(v, _)| *v)
        .or_else(|| entries.iter().max_by_key(|(v, _)| *v))
        .ok_or_else(|| unreadable("no <sdf> entry names a file".to_string()))?;
    let file = dir.join(best.1);
    if file.is_file() {
        Ok(file)
    } else {
        Err(unreadable(format!(
            "names {}, which does not exist",
            file.display()
        )))
    }
}

/// Split a `PATH`-style list, dropping empty entries.
fn split_path_list(value: Option<&str>) -> Vec<PathBuf> {
    value
        .map(|v| {
            std::env::split_paths(v)
                .filter(|p| !p.as_os_str().is_empty())
                .collect()
        })
        .unwrap_or_default()
}

/// The first of `candidates` that is a folder, and the candidates tried up to it, each once, in order.
fn first_folder(candidates: impl IntoIterator<Item = PathBuf>) -> (Option<PathBuf>, Vec<PathBuf>) {
    let mut searched = Vec::new();
    for root in candidates {
        if searched.contains(&root) {
            continue;
        }
        let found = root.is_dir();
        searched.push(root.clone());
        if found {
            return (Some(root), searched);
        }
    }
    (None, searched)
}

/// A package name usable as a single path component.
fn valid_package_name(name: &str) -> bool {
    !name.is_empty() && name != "." && name != ".." && !name.contains(['/', '\\', '\0'])
}

/// `file` in the first of `roots` holding it, or every distinct place looked at.
fn first_file(roots: Vec<PathBuf>, file: &str) -> Resolution {
    let mut searched = Vec::new();
    for root in roots {
        let candidate = root.join(file);
        if searched.contains(&candidate) {
            continue;
        }
        if candidate.is_file() {
            return Resolution::Found(candidate);
        }
        searched.push(candidate);
    }
    Resolution::NotFound { searched }
}

fn push_unique(list: &mut Vec<PathBuf>, path: PathBuf) {
    if !list.contains(&path) {
        list.push(path);
    }
}

fn has_package_xml(dir: &Path) -> bool {
    dir.join("package.xml").is_file()
}

/// Whether the last component of `dir` (made absolute, so `.` works) is `name`.
fn dir_basename_is(dir: &Path, name: &str) -> bool {
    let abs = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
    normalize_lexically(&abs)
        .file_name()
        .is_some_and(|n| n == name)
}

/// Largest `package.xml` read (real ones are a few KB).
const MAX_PACKAGE_XML_BYTES: u64 = 1024 * 1024;

/// The `<name>` declared in `dir/package.xml`, if readable.
fn package_xml_name(dir: &Path) -> Option<String> {
    let path = dir.join("package.xml");
    if std::fs::metadata(&path).ok()?.len() > MAX_PACKAGE_XML_BYTES {
        return None;
    }
    let text = std::fs::read_to_string(path).ok()?;
    let doc = roxmltree::Document::parse(&text).ok()?;
    let name = doc
        .root_element()
        .children()
        .find(|n| n.has_tag_name("name"))?
        .text()?
        .trim();
    (!name.is_empty()).then(|| name.to_string())
}

/// Package roots found by walking up from `start_dir`: `A/package` holding a
/// `package.xml`, and `A` itself when named `package` with a `package.xml`.
fn walk_up_roots(package: &str, start_dir: &Path) -> Vec<PathBuf> {
    let start = if start_dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        start_dir
    };
    let abs = std::path::absolute(start).unwrap_or_else(|_| start.to_path_buf());
    let base = normalize_lexically(&abs);
    let mut roots = Vec::new();
    for ancestor in base.ancestors().take(MAX_WALK_UP) {
        if ancestor.as_os_str().is_empty() {
            break;
        }
        let child = ancestor.join(package);
        if has_package_xml(&child) {
            push_unique(&mut roots, child);
        }
        if ancestor.file_name().is_some_and(|n| n == package) && has_package_xml(ancestor) {
            push_unique(&mut roots, ancestor.to_path_buf());
        }
    }
    roots
}

/// Drop `.` components and fold `..` lexically (no symlink resolution).
fn normalize_lexically(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for component in path.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => match out.components().next_back() {
                Some(Component::Normal(_)) => {
                    out.pop();
                }
                Some(Component::RootDir | Component::Prefix(_)) => {}
                _ => out.push(".."),
            },
            other => out.push(other),
        }
    }
    out
}

/// Where MuJoCo finds the file of a `<mesh>` asset, relative to the model's folder `model_dir` (or
/// absolute): under the compiler's `meshdir`, else, for a mesh declared in an included file
/// (`included_from`: that file's path as it was opened), in that file's folder when the file is there and
/// not under `meshdir` (MuJoCo 4.0 looks there second).
pub fn mjcf_mesh_path(
    model_dir: &Path,
    mesh_dir: Option<&str>,
    included_from: Option<&Path>,
    file: &str,
) -> PathBuf {
    let under_meshdir = match mesh_dir {
        Some(dir) if !Path::new(file).is_absolute() => Path::new(dir).join(file),
        _ => PathBuf::from(file),
    };
    let beside_include = included_from
        .and_then(Path::parent)
        .map(|folder| folder.join(file));
    match beside_include {
        Some(path) if !model_dir.join(&under_meshdir).is_file() && path.is_file() => {
            match path.strip_prefix(model_dir) {
                Ok(relative) => relative.to_path_buf(),
                Err(_) => std::path::absolute(&path).unwrap_or(path),
            }
        }
        _ => under_meshdir,
    }
}

/// `path` when it is a file the sandbox lets the readers read.
pub fn readable_file(sandbox: &Sandbox, path: PathBuf) -> Option<PathBuf> {
    (sandbox.check_file(&path).is_ok() && path.is_file()).then_some(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;
    use std::sync::atomic::{AtomicUsize, Ordering};

    static COUNTER: AtomicUsize = AtomicUsize::new(0);

    /// A unique temporary directory removed on drop.
    struct TempTree(PathBuf);

    impl TempTree {
        fn new() -> Self {
            let n = COUNTER.fetch_add(1, Ordering::SeqCst);
            let dir = std::env::temp_dir().join(format!(
                "urdf_resolve_test_{}_{}",
                std::process::id(),
                n
            ));
            let _ = fs::remove_dir_all(&dir);
            fs::create_dir_all(&dir).unwrap();
            TempTree(dir)
        }

        fn path(&self, rel: &str) -> PathBuf {
            self.0.join(rel)
        }

        /// Create a file (and its parents) with some content.
        fn file(&self, rel: &str) -> PathBuf {
            let p = self.path(rel);
            fs::create_dir_all(p.parent().unwrap()).unwrap();
            fs::write(&p, "x").unwrap();
            p
        }

        /// Create `rel/package.xml` declaring `name`.
        fn package(&self, rel: &str, name: &str) -> PathBuf {
            let dir = self.path(rel);
            fs::create_dir_all(&dir).unwrap();
            fs::write(
                dir.join("package.xml"),
                format!(
                    "<?xml version=\"1.0\"?>\n<!-- <name>wrong</name> -->\n\
                     <package format=\"2\">\n  <name>{name}</name>\n</package>\n"
                ),
            )
            .unwrap();
            dir
        }

        fn dir(&self, rel: &str) -> PathBuf {
            let p = self.path(rel);
            fs::create_dir_all(&p).unwrap();
            p
        }
    }

    impl Drop for TempTree {
        fn drop(&mut self) {
            let _ = fs::remove_dir_all(&self.0);
        }
    }

    fn empty_resolver() -> PackageResolver {
        PackageResolver::new(Vec::new(), None, None)
    }

    #[test]
    fn explicit_path_without_package_xml() {
        let t = TempTree::new();
        let mesh = t.file("vendor/my_pkg/meshes/a.stl");
        let urdf_dir = t.dir("elsewhere");
        let r = PackageResolver::new(vec![t.path("vendor")], None, None);
        assert_eq!(
            r.resolve("package://my_pkg/meshes/a.stl", &urdf_dir),
            Resolution::Found(mesh)
        );
        assert_eq!(
            r.find_package("my_pkg", &urdf_dir),
            Some(t.path("vendor/my_pkg"))
        );
    }

    #[test]
    fn explicit_path_is_the_package_itself() {
        let t = TempTree::new();
        // Folder name differs from the declared package name.
        t.package("checkout", "real_name");
        let mesh = t.file("checkout/meshes/a.stl");
        let r = PackageResolver::new(vec![t.path("checkout")], None, None);
        assert_eq!(
            r.resolve("package://real_name/meshes/a.stl", &t.dir("x")),
            Resolution::Found(mesh)
        );
        // By basename, even without package.xml.
        let mesh2 = t.file("bare_pkg/m.dae");
        let r = PackageResolver::new(vec![t.path("bare_pkg")], None, None);
        assert_eq!(
            r.resolve("package://bare_pkg/m.dae", &t.dir("x")),
            Resolution::Found(mesh2)
        );
    }

    #[test]
    fn ros_package_path_direct_and_recursive() {
        let t = TempTree::new();
        t.package("ws/src/direct_pkg", "direct_pkg");
        let direct = t.file("ws/src/direct_pkg/meshes/d.stl");
        t.package("ws/src/group/sub/deep_pkg", "deep_pkg");
        let deep = t.file("ws/src/group/sub/deep_pkg/meshes/e.stl");
        // Hidden directories are skipped.
        t.package("ws/src/.hidden/hidden_pkg", "hidden_pkg");
        t.file("ws/src/.hidden/hidden_pkg/h.stl");
        // Too deep (depth 5 below the entry).
        t.package("ws/src/a/b/c/d/too_deep", "too_deep");
        t.file("ws/src/a/b/c/d/too_deep/t.stl");

        let entry = t.path("ws/src");
        let rpp = format!("{}:{}", t.path("nonexistent").display(), entry.display());
        let r = PackageResolver::new(Vec::new(), Some(&rpp), None);
        let urdf_dir = t.dir("other");
        assert_eq!(
            r.resolve("package://direct_pkg/meshes/d.stl", &urdf_dir),
            Resolution::Found(direct)
        );
        assert_eq!(
            r.resolve("package://deep_pkg/meshes/e.stl", &urdf_dir),
            Resolution::Found(deep)
        );
        // Cached second lookup gives the same answer.
        assert_eq!(
            r.find_package("deep_pkg", &urdf_dir),
            Some(t.path("ws/src/group/sub/deep_pkg"))
        );
        assert_eq!(
            r.resolve("package://hidden_pkg/h.stl", &urdf_dir),
            Resolution::NotFound { searched: vec![] }
        );
        assert_eq!(
            r.resolve("package://too_deep/t.stl", &urdf_dir),
            Resolution::NotFound { searched: vec![] }
        );
    }

    #[test]
    fn ros_package_path_entry_is_the_package() {
        let t = TempTree::new();
        let pkg = t.package("solo_pkg", "solo_pkg");
        let mesh = t.file("solo_pkg/m.stl");
        let rpp = pkg.display().to_string();
        let r = PackageResolver::new(Vec::new(), Some(&rpp), None);
        assert_eq!(
            r.resolve("package://solo_pkg/m.stl", &t.dir("x")),
            Resolution::Found(mesh)
        );
    }

    #[test]
    fn ament_prefix_path() {
        let t = TempTree::new();
        let mesh = t.file("install/share/amt_pkg/meshes/m.stl");
        let app = format!("{}:", t.path("install").display());
        let r = PackageResolver::new(Vec::new(), None, Some(&app));
        assert_eq!(
            r.resolve("package://amt_pkg/meshes/m.stl", &t.dir("x")),
            Resolution::Found(mesh)
        );
    }

    #[test]
    fn walk_up_finds_sibling_package() {
        let t = TempTree::new();
        t.package("repo/robot_description", "robot_description");
        let mesh = t.file("repo/robot_description/meshes/base.stl");
        let urdf_dir = t.dir("repo/robot_bringup/urdf/deeper");
        assert_eq!(
            empty_resolver().resolve("package://robot_description/meshes/base.stl", &urdf_dir),
            Resolution::Found(mesh)
        );
    }

    #[test]
    fn walk_up_finds_enclosing_package() {
        let t = TempTree::new();
        t.package("my_robot", "my_robot");
        let mesh = t.file("my_robot/meshes/base.stl");
        let urdf_dir = t.dir("my_robot/urdf");
        assert_eq!(
            empty_resolver().resolve("package://my_robot/meshes/base.stl", &urdf_dir),
            Resolution::Found(mesh)
        );
        // `..` in urdf_dir does not break the walk.
        let dotted = urdf_dir.join("../urdf");
        assert_eq!(
            empty_resolver().find_package("my_robot", &dotted),
            Some(t.path("my_robot"))
        );
    }

    #[test]
    fn package_found_but_file_missing_lists_all_candidates() {
        let t = TempTree::new();
        t.file("vendor/pkg_m/other.stl");
        t.package("repo/pkg_m", "pkg_m");
        let urdf_dir = t.dir("repo/urdf");
        let r = PackageResolver::new(
            vec![t.path("vendor")],
            None,
            Some(&t.path("prefix").display().to_string()),
        );
        let got = r.resolve("package://pkg_m/meshes/missing.stl", &urdf_dir);
        let walk_candidate = std::path::absolute(t.path("repo/pkg_m/meshes/missing.stl")).unwrap();
        assert_eq!(
            got,
            Resolution::NotFound {
                searched: vec![
                    t.path("vendor/pkg_m/meshes/missing.stl"),
                    t.path("prefix/share/pkg_m/meshes/missing.stl"),
                    walk_candidate,
                ]
            }
        );
    }

    #[test]
    fn later_copy_of_package_has_the_file() {
        let t = TempTree::new();
        t.file("first/pkg_c/meshes/unrelated.stl");
        let mesh = t.file("second/pkg_c/meshes/m.stl");
        let r = PackageResolver::new(vec![t.path("first"), t.path("second")], None, None);
        assert_eq!(
            r.resolve("package://pkg_c/meshes/m.stl", &t.dir("x")),
            Resolution::Found(mesh)
        );
    }

    #[test]
    fn explicit_path_wins_over_walk_up() {
        let t = TempTree::new();
        t.package("repo/ord_pkg", "ord_pkg");
        t.file("repo/ord_pkg/m.stl");
        let explicit = t.file("vendor/ord_pkg/m.stl");
        let urdf_dir = t.dir("repo/urdf");
        let r = PackageResolver::new(vec![t.path("vendor")], None, None);
        assert_eq!(
            r.resolve("package://ord_pkg/m.stl", &urdf_dir),
            Resolution::Found(explicit)
        );
    }

    #[test]
    fn file_uri_absolute_and_percent_decoded() {
        let t = TempTree::new();
        let mesh = t.file("with space/m.stl");
        let uri = format!("file://{}", mesh.display()).replace(' ', "%20");
        assert_eq!(
            empty_resolver().resolve(&uri, &t.dir("x")),
            Resolution::Found(mesh.clone())
        );
        let localhost = format!("file://localhost{}", mesh.display());
        assert_eq!(
            empty_resolver().resolve(&localhost, &t.dir("x")),
            Resolution::Found(mesh)
        );
    }

    #[test]
    fn file_uri_relative() {
        let t = TempTree::new();
        let mesh = t.file("urdf/meshes/m.stl");
        assert_eq!(
            empty_resolver().resolve("file://meshes/m.stl", &t.path("urdf")),
            Resolution::Found(t.path("urdf").join("meshes/m.stl"))
        );
        assert!(mesh.is_file());
    }

    #[test]
    fn bare_relative_and_absolute_paths() {
        let t = TempTree::new();
        t.file("robot/meshes/m.stl");
        let urdf_dir = t.dir("robot/urdf");
        assert_eq!(
            empty_resolver().resolve("../meshes/m.stl", &urdf_dir),
            Resolution::Found(urdf_dir.join("../meshes/m.stl"))
        );
        let abs = t.path("robot/meshes/m.stl");
        assert_eq!(
            empty_resolver().resolve(&abs.display().to_string(), &t.dir("x")),
            Resolution::Found(abs)
        );
        assert_eq!(
            empty_resolver().resolve("meshes/none.stl", &urdf_dir),
            Resolution::NotFound {
                searched: vec![urdf_dir.join("meshes/none.stl")]
            }
        );
    }

    #[test]
    fn remote_schemes_are_unsupported() {
        let r = empty_resolver();
        let dir = Path::new("/nonexistent");
        for (uri, scheme) in [
            ("http://example.com/m.stl", "http"),
            ("https://example.com/m.stl", "https"),
        ] {
            assert_eq!(
                r.resolve(uri, dir),
                Resolution::Unsupported(format!(
                    "URI scheme '{scheme}' cannot be resolved offline"
                ))
            );
        }
    }

    #[test]
    fn empty_package_name_is_refused_as_resource_retriever_does() {
        // Even when the absolute path exists: resource_retriever throws "Package name must not be empty".
        let t = TempTree::new();
        let mesh = t.file("meshes/a.stl");
        let uri = format!("package://{}", mesh.display());
        assert!(uri.starts_with("package:///"), "{uri}");
        let got = empty_resolver().resolve(&uri, &t.dir("x"));
        let Resolution::Unsupported(why) = got else {
            panic!("{uri}: expected Unsupported, got {got:?}");
        };
        assert!(why.contains("empty package name"), "{why}");
        assert!(why.contains("resource_retriever"), "{why}");
        assert!(why.contains(&format!("file://{}", mesh.display())), "{why}");
        // The file:// spelling the message suggests resolves.
        assert_eq!(
            empty_resolver().resolve(&format!("file://{}", mesh.display()), &t.dir("x")),
            Resolution::Found(mesh)
        );
    }

    #[test]
    fn empty_package_name_before_a_package_is_found_as_pinocchio_finds_it() {
        // `package:///pkg/meshes/a.stl`: ROS refuses it, Pinocchio reads package `pkg`'s file.
        let t = TempTree::new();
        t.file("pkg/package.xml");
        let mesh = t.file("pkg/meshes/a.stl");
        let resolver = PackageResolver::new(vec![t.path("")], None, None);
        let got = resolver.resolve("package:///pkg/meshes/a.stl", &t.dir("x"));
        let Resolution::Lenient { path, why } = &got else {
            panic!("expected Lenient, got {got:?}");
        };
        assert_eq!(path, &mesh);
        assert!(why.contains("resource_retriever"), "{why}");
        assert!(why.contains("package://pkg/meshes/a.stl"), "{why}");
        assert_eq!(got.found(), Some(&mesh));
        // Nothing there: refused as before.
        assert!(matches!(
            resolver.resolve("package:///pkg/meshes/b.stl", &t.dir("x")),
            Resolution::Unsupported(_)
        ));
    }

    #[test]
    fn malformed_and_odd_inputs_do_not_panic() {
        let r = PackageResolver::new(vec![PathBuf::from("")], Some("::"), Some(":"));
        let dir = Path::new("");
        for uri in [
            "package://",
            "package:///x",
            "package://../etc",
            "package://pkg",
            "package://pkg/",
        ] {
            assert!(
                matches!(r.resolve(uri, dir), Resolution::Unsupported(_)),
                "{uri}"
            );
        }
        assert!(matches!(r.resolve("", dir), Resolution::Unsupported(_)));
        assert!(matches!(r.resolve("   ", dir), Resolution::Unsupported(_)));
        assert!(matches!(
            r.resolve("file://", dir),
            Resolution::Unsupported(_)
        ));
        for uri in [
            "package://pkg//abs/../../x.stl",
            "package://ünï/çødé/🤖.stl",
            "file:///%zz%4",
            "file:///%ff%fe",
            "://x",
            "1abc://x",
            "../../../../..",
            "\0",
            "%",
        ] {
            let _ = r.resolve(uri, dir);
            let _ = r.resolve(uri, Path::new("/"));
        }
        assert_eq!(r.find_package("", dir), None);
        assert_eq!(r.find_package("..", dir), None);
    }

    #[test]
    fn double_slash_after_package_does_not_escape() {
        let t = TempTree::new();
        let mesh = t.file("vendor/pkg_s/meshes/m.stl");
        let r = PackageResolver::new(vec![t.path("vendor")], None, None);
        assert_eq!(
            r.resolve("package://pkg_s//meshes/m.stl", &t.dir("x")),
            Resolution::Found(mesh)
        );
    }

    #[test]
    fn resolver_is_send_sync_clone() {
        fn check<T: Send + Sync + Clone>() {}
        check::<PackageResolver>();
    }

    #[test]
    fn real_turtlebot3_data() {
        let relative = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/robots");
        let robots = [relative, PathBuf::from("/work/shared/robots")]
            .into_iter()
            .find(|p| p.is_dir());
        let Some(robots) = robots else {
            eprintln!("skipping: ../shared/robots is absent");
            return;
        };
        let urdf_dir = robots.join("turtlebot3/turtlebot3_description/urdf");
        let got = empty_resolver().resolve(
            "package://turtlebot3_description/meshes/bases/burger_base.stl",
            &urdf_dir,
        );
        match got {
            Resolution::Found(p) => assert!(p.ends_with("meshes/bases/burger_base.stl")),
            other => panic!("expected Found, got {other:?}"),
        }
    }

    #[test]
    fn model_uris_resolve_through_the_gazebo_paths_then_package_paths_then_upwards() {
        let t = TempTree::new();
        let mesh = t.file("gz/arm/meshes/a.stl");
        t.file("pp/arm/meshes/a.stl");
        let r = PackageResolver::new(vec![t.path("pp")], None, None)
            .with_model_paths([Some(t.path("gz").to_str().unwrap())]);
        assert_eq!(
            r.resolve("model://arm/meshes/a.stl", &t.dir("x")),
            Resolution::Found(mesh)
        );
        let beside = t.file("world/models/../wheel/w.dae");
        let found = empty_resolver().resolve("model://wheel/w.dae", &t.dir("world/models"));
        assert_eq!(
            found,
            Resolution::Found(t.path("world/wheel/w.dae")),
            "{beside:?}"
        );
        assert!(matches!(
            empty_resolver().resolve("model://absent/m.stl", &t.dir("x")),
            Resolution::NotFound { .. }
        ));
    }

    #[test]
    fn model_config_picks_the_newest_supported_sdf() {
        let t = TempTree::new();
        let dir = t.dir("m");
        fs::write(
            dir.join("model.config"),
            "<model><sdf version=\"1.5\">old.sdf</sdf><sdf version=\"1.10\">new.sdf</sdf><sdf version=\"2.0\">future.sdf</sdf></model>",
        )
        .unwrap();
        for f in ["old.sdf", "new.sdf", "future.sdf"] {
            t.file(&format!("m/{f}"));
        }
        assert_eq!(model_sdf_file(&dir), Ok(dir.join("new.sdf")));
        let bare = t.dir("bare");
        assert!(model_sdf_file(&bare).is_err());
        t.file("bare/model.sdf");
        assert_eq!(model_sdf_file(&bare), Ok(bare.join("model.sdf")));
        assert_eq!(
            empty_resolver().resolve_include("m", &t.0),
            Ok(dir.join("new.sdf"))
        );
        assert!(matches!(
            empty_resolver().resolve_include("https://fuel.gazebosim.org/x", &t.0),
            Err(IncludeFailure::Unresolved(why)) if why.contains("offline")
        ));
        // Untrusted: the model folder is outside the roots, so it is refused, not read.
        let sandboxed = empty_resolver().with_sandbox(Sandbox::untrusted([t.dir("elsewhere")], []));
        assert!(matches!(
            sandboxed.resolve_include("m", &t.0),
            Err(IncludeFailure::Unresolved(why)) if why.contains("outside")
        ));
        assert!(matches!(
            sandboxed.resolve_include("bare/model.sdf", &t.0),
            Err(IncludeFailure::Refused(_))
        ));
    }
}
