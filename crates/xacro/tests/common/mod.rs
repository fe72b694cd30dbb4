//! Shared helpers of the xacro tests: locating the oracle and the robots, running Python xacro, and
//! comparing expansions after canonicalisation.

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

use xacro::{ErrorKind, Options};

/// Whether a missing resource must fail the test (CI) rather than skip it.
pub fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true")
}

/// Skip (or fail under CI) with a message.
pub fn unavailable(what: &str) -> Option<PathBuf> {
    assert!(!in_ci(), "{what} (required under CI=true)");
    eprintln!("SKIP: {what}");
    None
}

/// The Python xacro 2.1.1 executable (`URDF_VALIDATOR_XACRO`, exported by scripts/test.sh).
pub fn oracle() -> Option<PathBuf> {
    match std::env::var_os("URDF_VALIDATOR_XACRO").map(PathBuf::from) {
        Some(p) if p.is_file() => Some(p),
        Some(p) => unavailable(&format!(
            "URDF_VALIDATOR_XACRO={} does not exist; run scripts/test.sh",
            p.display()
        )),
        None => unavailable(
            "URDF_VALIDATOR_XACRO is not set: the differential tests against Python xacro need it \
             (bash scripts/test.sh sets it up)",
        ),
    }
}

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `../shared/robots` (or `URDF_VALIDATOR_SHARED_ROBOTS`).
pub fn shared_robots() -> Option<PathBuf> {
    let dir = std::env::var_os("URDF_VALIDATOR_SHARED_ROBOTS")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo_root().join("../shared/robots"));
    if dir.is_dir() {
        Some(dir)
    } else {
        unavailable(&format!(
            "shared robots not found at {} (set URDF_VALIDATOR_SHARED_ROBOTS)",
            dir.display()
        ))
    }
}

/// The example-robot-data corpus (`URDF_VALIDATOR_CORPUS`).
pub fn corpus() -> Option<PathBuf> {
    match std::env::var_os("URDF_VALIDATOR_CORPUS").map(PathBuf::from) {
        Some(p) if p.is_dir() => Some(p),
        _ => unavailable(
            "URDF_VALIDATOR_CORPUS is not set or missing (bash scripts/test.sh sets it up)",
        ),
    }
}

/// The fixtures folder.
pub fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures")
}

/// An ament prefix (`share/<pkg>` symlinks and resource-index markers) serving `packages`, so Python
/// xacro's `$(find)` (ament_index_python) and ours resolve to the same paths.
pub fn ament_prefix(name: &str, packages: &[(&str, PathBuf)]) -> PathBuf {
    let prefix = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("ament-{name}"));
    let index = prefix.join("share/ament_index/resource_index/packages");
    std::fs::create_dir_all(&index).expect("create ament index");
    for (pkg, dir) in packages {
        std::fs::write(index.join(pkg), "").expect("marker");
        let link = prefix.join("share").join(pkg);
        let _ = std::fs::remove_file(&link);
        #[cfg(unix)]
        std::os::unix::fs::symlink(dir, &link).expect("symlink package");
    }
    prefix
}

/// The environment both expanders see: only `AMENT_PREFIX_PATH` (and `PATH` for Python).
pub fn env_for(prefix: &Path) -> Vec<(String, String)> {
    vec![("AMENT_PREFIX_PATH".into(), prefix.display().to_string())]
}

/// Our options for the same environment and arguments.
pub fn options(env: &[(String, String)], args: &[(&str, &str)]) -> Options {
    let env: Vec<(String, String)> = env.to_vec();
    Options {
        args: args
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect(),
        env: Some(Arc::new(move |name: &str| {
            env.iter().find(|(k, _)| k == name).map(|(_, v)| v.clone())
        })),
        // Python's banner, so the whole output can be compared byte for byte.
        banner: true,
        ..Default::default()
    }
}

/// Python xacro's result: the XML, or its error message.
pub fn run_python(
    oracle: &Path,
    file: &Path,
    env: &[(String, String)],
    args: &[(&str, &str)],
) -> Result<String, String> {
    let mut cmd = Command::new(oracle);
    cmd.arg(file)
        .env_clear()
        .env("PATH", std::env::var("PATH").unwrap_or_default());
    for (k, v) in env {
        cmd.env(k, v);
    }
    for (k, v) in args {
        cmd.arg(format!("{k}:={v}"));
    }
    let out = cmd.output().expect("run python xacro");
    if out.status.success() {
        Ok(String::from_utf8_lossy(&out.stdout).into_owned())
    } else {
        Err(strip_ansi(&String::from_utf8_lossy(&out.stderr)))
    }
}

fn strip_ansi(s: &str) -> String {
    let mut out = String::new();
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c == '\u{1b}' {
            for d in chars.by_ref() {
                if d.is_ascii_alphabetic() {
                    break;
                }
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// The error class of a Python xacro failure, from its message.
pub fn python_error_kind(message: &str) -> ErrorKind {
    let m = message;
    let has = |s: &str| m.contains(s);
    if has("XML parsing error") {
        ErrorKind::XmlParse
    } else if has("maximum recursion depth") {
        ErrorKind::Limit
    } else if has("circular variable definition") {
        ErrorKind::CircularProperty
    } else if has("Undefined substitution argument") {
        ErrorKind::UndefinedArgument
    } else if has("unknown macro name") {
        ErrorKind::UnknownMacro
    } else if has("Undefined parameters") {
        ErrorKind::MissingParameter
    } else if has("Invalid parameter") {
        ErrorKind::UnknownParameter
    } else if has("Not enough blocks") || has("Unused block") || has("Undefined block") {
        ErrorKind::Block
    } else if has("PackageNotFoundError") || has("not found, searching") {
        ErrorKind::PackageNotFound
    } else if has("missing attribute") {
        ErrorKind::MissingAttribute
    } else if has("not a boolean expression") {
        ErrorKind::BadCondition
    } else if has("Use of invalid name") || has("Property names must") || has("double underscore") {
        ErrorKind::InvalidName
    } else if has("is not defined") {
        ErrorKind::UndefinedProperty
    } else if has("No such file or directory") {
        ErrorKind::IncludeNotFound
    } else if has("SubstitutionException")
        || has("substitution command")
        || has("environment variable")
    {
        ErrorKind::Substitution
    } else if has("yaml") || has("YAML") {
        ErrorKind::Yaml
    } else if has("invalid expression")
        || has("SyntaxError")
        || has("TypeError")
        || has("ZeroDivisionError")
        || has("KeyError")
        || has("IndexError")
        || has("ValueError")
        || has("AttributeError")
        || has("when evaluating expression")
    {
        ErrorKind::Expression
    } else {
        ErrorKind::Other
    }
}

/// A canonical form of an XML document: element names, attributes as a sorted map, non-whitespace text
/// trimmed; comments, processing instructions and whitespace between elements ignored.
#[derive(Debug, PartialEq)]
pub enum Canon {
    Element {
        name: String,
        attrs: BTreeMap<String, String>,
        children: Vec<Canon>,
    },
    Text(String),
}

fn expanded_name(ns: Option<&str>, name: &str) -> String {
    match ns {
        Some(ns) => format!("{{{ns}}}{name}"),
        None => name.to_string(),
    }
}

fn canon_node(n: roxmltree::Node) -> Option<Canon> {
    if n.is_element() {
        let attrs = n
            .attributes()
            .map(|a| {
                (
                    expanded_name(a.namespace(), a.name()),
                    a.value().to_string(),
                )
            })
            .collect();
        let children = n.children().filter_map(canon_node).collect();
        Some(Canon::Element {
            name: expanded_name(n.tag_name().namespace(), n.tag_name().name()),
            attrs,
            children,
        })
    } else if n.is_text() {
        let t = n.text().unwrap_or("").trim();
        (!t.is_empty()).then(|| Canon::Text(t.to_string()))
    } else {
        None
    }
}

/// Canonicalise an XML text.
pub fn canonical(xml: &str) -> Result<Canon, String> {
    let doc = roxmltree::Document::parse(xml).map_err(|e| e.to_string())?;
    canon_node(doc.root_element()).ok_or_else(|| "no root".to_string())
}

/// The first difference between two canonical trees, as a path and description.
pub fn first_difference(a: &Canon, b: &Canon, path: &str) -> Option<String> {
    match (a, b) {
        (Canon::Text(x), Canon::Text(y)) => {
            (x != y).then(|| format!("{path}: text {x:?} != {y:?}"))
        }
        (
            Canon::Element {
                name: na,
                attrs: aa,
                children: ca,
            },
            Canon::Element {
                name: nb,
                attrs: ab,
                children: cb,
            },
        ) => {
            let here = format!("{path}/{na}");
            if na != nb {
                return Some(format!("{path}: element {na} != {nb}"));
            }
            if aa != ab {
                return Some(format!("{here}: attributes {aa:?} != {ab:?}"));
            }
            for (i, (x, y)) in ca.iter().zip(cb).enumerate() {
                if let Some(d) = first_difference(x, y, &format!("{here}[{i}]")) {
                    return Some(d);
                }
            }
            (ca.len() != cb.len()).then(|| format!("{here}: {} children != {}", ca.len(), cb.len()))
        }
        _ => Some(format!("{path}: {a:?} != {b:?}")),
    }
}

/// The outcome of one differential case.
pub enum Outcome {
    /// Same canonical XML.
    Same,
    /// Both failed with the same class.
    SameError(ErrorKind),
    /// A difference (described).
    Differs(String),
}

/// Expand `file` with both and compare.
pub fn compare(
    oracle: &Path,
    file: &Path,
    env: &[(String, String)],
    args: &[(&str, &str)],
) -> Outcome {
    let python = run_python(oracle, file, env, args);
    let ours = xacro::expand_file(file, &options(env, args));
    match (python, ours) {
        (Ok(py), Ok(ours)) => {
            let (a, b) = match (canonical(&py), canonical(&ours.xml)) {
                (Ok(a), Ok(b)) => (a, b),
                (Err(e), _) => {
                    return Outcome::Differs(format!("python output does not parse: {e}"))
                }
                (_, Err(e)) => return Outcome::Differs(format!("our output does not parse: {e}")),
            };
            if let Some(d) = first_difference(&a, &b, "") {
                return Outcome::Differs(format!("python vs ours: {d}"));
            }
            // Beyond the canonical form: comments and layout are kept as xacro keeps them.
            match py
                .lines()
                .zip(ours.xml.lines())
                .enumerate()
                .find(|(_, (p, o))| p != o)
            {
                Some((i, (p, o))) => Outcome::Differs(format!(
                    "same tree, different text at line {}: python {p:?} vs ours {o:?}",
                    i + 1
                )),
                None if py.len() != ours.xml.len() => {
                    Outcome::Differs("same tree, different text length".into())
                }
                None => Outcome::Same,
            }
        }
        (Err(py), Err(ours)) => {
            let kind = python_error_kind(&py);
            let ours_kind = match ours.kind {
                ErrorKind::IncludeCycle => ErrorKind::Limit,
                ErrorKind::Io => ErrorKind::IncludeNotFound,
                k => k,
            };
            // xacro.fatal(...) raises a bare XacroException with the caller's message.
            let fatal = ours.kind == ErrorKind::Fatal && py.contains(&ours.message);
            if kind == ours_kind || fatal {
                Outcome::SameError(kind)
            } else {
                Outcome::Differs(format!(
                    "python failed with {kind:?} ({}) but ours with {:?} ({ours})",
                    py.trim(),
                    ours.kind
                ))
            }
        }
        (Ok(_), Err(ours)) => Outcome::Differs(format!("python succeeded, ours failed: {ours}")),
        (Err(py), Ok(_)) => {
            Outcome::Differs(format!("ours succeeded, python failed: {}", py.trim()))
        }
    }
}

/// Run cases and assert that none differs; prints a summary.
pub fn check_all(oracle: &Path, cases: &[(PathBuf, Vec<(&str, &str)>)], env: &[(String, String)]) {
    let mut failures = Vec::new();
    let (mut same, mut same_err) = (0, 0);
    for (file, args) in cases {
        match compare(oracle, file, env, args) {
            Outcome::Same => same += 1,
            Outcome::SameError(k) => {
                same_err += 1;
                eprintln!("both fail ({k:?}): {}", file.display());
            }
            Outcome::Differs(d) => failures.push(format!("{} {args:?}: {d}", file.display())),
        }
    }
    eprintln!(
        "{same} identical, {same_err} same error, {} different",
        failures.len()
    );
    assert!(
        failures.is_empty(),
        "{} of {} cases differ:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}
