//! Files: `$(find pkg)` package lookup without ROS, include file names (relative to the including file,
//! globs), reading sources.

use std::path::{Path, PathBuf};

use crate::Options;

/// How many ancestors of the current file the walk-up of `$(find)` visits.
const MAX_WALK_UP: usize = 64;

/// Longest `package.xml` read while looking for a package.
const MAX_PACKAGE_XML: usize = 1 << 20;

/// Read a source file (xacro, YAML, `package.xml`): a regular file of at most `limit` bytes. Devices and
/// FIFOs (`/dev/zero`, `/dev/stdin`) or huge files would otherwise hang or exhaust memory.
pub(crate) fn read_text(path: &Path, limit: usize) -> std::io::Result<String> {
    use std::io::{Error, ErrorKind, Read};
    // Checked before opening: opening a FIFO blocks until something writes to it.
    if !std::fs::metadata(path)?.is_file() {
        return Err(Error::new(ErrorKind::InvalidInput, "not a regular file"));
    }
    let mut text = String::new();
    std::fs::File::open(path)?
        .take(limit as u64 + 1)
        .read_to_string(&mut text)?;
    if text.len() > limit {
        return Err(Error::new(
            ErrorKind::InvalidData,
            format!("larger than {limit} bytes"),
        ));
    }
    Ok(text)
}

/// `abs_filename_spec`: `spec` relative to the directory of `current` unless absolute.
pub(crate) fn abs_filename(spec: &str, current: &Path) -> PathBuf {
    let p = Path::new(spec);
    if p.is_absolute() {
        return p.to_path_buf();
    }
    // os.path.join(os.path.dirname(current), spec): no prefix when the current file has no directory.
    match current.parent() {
        Some(dir) => dir.join(p),
        None => p.to_path_buf(),
    }
}

/// Whether an include file name is a glob (Python xacro: it contains `*`, `[` or `?`).
pub(crate) fn is_glob(spec: &str) -> bool {
    spec.contains(['*', '[', '?'])
}

/// The folder a glob lists: its path up to the first component with a wildcard.
pub(crate) fn glob_folder(spec: &Path) -> PathBuf {
    spec.components()
        .take_while(|c| !is_glob(&c.as_os_str().to_string_lossy()))
        .collect()
}

/// The files matching a glob, sorted (Python's `sorted(glob.glob(spec))`).
pub(crate) fn glob_files(spec: &str) -> Vec<PathBuf> {
    let opts = glob::MatchOptions {
        require_literal_leading_dot: true,
        ..Default::default()
    };
    // Python's glob is not recursive unless asked: its `**` is `*`. The glob crate's recursive `**`
    // differed, and walked whole file systems (`/**/*.xacro`) for minutes.
    let mut spec = spec.to_string();
    while spec.contains("**") {
        spec = spec.replace("**", "*");
    }
    let mut files: Vec<PathBuf> = match glob::glob_with(&spec, opts) {
        Ok(paths) => paths.filter_map(Result::ok).collect(),
        Err(_) => Vec::new(),
    };
    files.sort();
    files
}

/// The `<name>` of a `package.xml` (none when the gate refuses the file).
fn package_xml_name(dir: &Path, opts: &Options) -> Option<String> {
    let file = dir.join("package.xml");
    if let Some(gate) = &opts.gate {
        gate.file(&file).ok()?;
    }
    let text = read_text(&file, MAX_PACKAGE_XML).ok()?;
    let start = text.find("<name>")? + "<name>".len();
    let end = start + text[start..].find("</name>")?;
    Some(text[start..end].trim().to_string())
}

/// Find package `pkg`: the caller's callback, the caller's package paths (`DIR/pkg`, or `DIR` itself when its
/// `package.xml` names `pkg`), `AMENT_PREFIX_PATH` (the ament resource index, as Python xacro does),
/// `ROS_PACKAGE_PATH`, then the ancestors of the current file (a directory, or a child directory of one,
/// whose `package.xml` names `pkg`; failing that, an ancestor directory named `pkg`). On failure, the places
/// searched.
pub(crate) fn find_package(
    pkg: &str,
    opts: &Options,
    env: &dyn Fn(&str) -> Option<String>,
    current: &Path,
) -> Result<PathBuf, Vec<String>> {
    let mut searched = Vec::new();
    if let Some(finder) = &opts.find_package {
        match finder(pkg) {
            Ok(p) => return Ok(p),
            Err(places) => searched.extend(places),
        }
    }
    let valid = !pkg.is_empty() && !pkg.contains(['/', '\\']) && pkg != "." && pkg != "..";
    if !valid {
        return Err(searched);
    }
    for dir in &opts.package_paths {
        let candidate = dir.join(pkg);
        if candidate.is_dir() {
            return Ok(candidate);
        }
        if package_xml_name(dir, opts).as_deref() == Some(pkg) {
            return Ok(dir.clone());
        }
        searched.push(candidate.display().to_string());
    }
    if let Some(prefixes) = env("AMENT_PREFIX_PATH") {
        for prefix in prefixes.split(':').filter(|p| !p.is_empty()) {
            let prefix = Path::new(prefix);
            let marker = prefix
                .join("share/ament_index/resource_index/packages")
                .join(pkg);
            if marker.is_file() {
                return Ok(prefix.join("share").join(pkg));
            }
            searched.push(format!("AMENT_PREFIX_PATH entry {}", prefix.display()));
        }
    }
    if let Some(paths) = env("ROS_PACKAGE_PATH") {
        for dir in paths.split(':').filter(|p| !p.is_empty()) {
            let dir = Path::new(dir);
            if package_xml_name(dir, opts).as_deref() == Some(pkg) {
                return Ok(dir.to_path_buf());
            }
            let candidate = dir.join(pkg);
            if candidate.is_dir() {
                return Ok(candidate);
            }
            searched.push(format!("ROS_PACKAGE_PATH entry {}", dir.display()));
        }
    }
    let start = std::path::absolute(current).unwrap_or_else(|_| current.to_path_buf());
    for dir in start.ancestors().skip(1).take(MAX_WALK_UP) {
        if package_xml_name(dir, opts).as_deref() == Some(pkg) {
            return Ok(dir.to_path_buf());
        }
        let child = dir.join(pkg);
        if package_xml_name(&child, opts).as_deref() == Some(pkg) {
            return Ok(child);
        }
    }
    // Last resort: an ancestor directory named like the package (trees copied without package.xml).
    let named = |d: &&Path| d.file_name().is_some_and(|n| n == pkg);
    if let Some(dir) = start.ancestors().skip(1).take(MAX_WALK_UP).find(named) {
        return Ok(dir.to_path_buf());
    }
    if let Some(dir) = start.parent() {
        searched.push(format!(
            "package.xml files in the ancestors of {}",
            dir.display()
        ));
    }
    Err(searched)
}
