//! Inputs → the list of files to validate (directories walked), and xacro's `name:=value` arguments.

use std::path::{Path, PathBuf};

/// Deepest directory level searched below a directory input.
const MAX_DEPTH: usize = 32;

/// Positional `name:=value` words (xacro's argument syntax) set apart from the paths.
pub fn split_xacro_args(inputs: &[PathBuf]) -> (Vec<PathBuf>, Vec<(String, String)>) {
    let mut paths = Vec::new();
    let mut args = Vec::new();
    for input in inputs {
        match input.to_str().and_then(xacro::parse_arg) {
            Some(arg) if !input.exists() => args.push(arg),
            _ => paths.push(input.clone()),
        }
    }
    (paths, args)
}

/// A `--xacro-arg` value: `NAME=VALUE` or xacro's own `NAME:=VALUE`, split at the first `=` (the value
/// may hold `=` and `:=`); the name trimmed, without `:` or spaces.
pub fn parse_xacro_arg_flag(arg: &str) -> Result<(String, String), String> {
    let (name, value) = arg
        .split_once('=')
        .ok_or_else(|| format!("--xacro-arg expects NAME=VALUE, got '{arg}'"))?;
    let name = name.strip_suffix(':').unwrap_or(name).trim();
    if name.is_empty() || name.contains(':') || name.contains(char::is_whitespace) {
        return Err(format!(
            "--xacro-arg expects NAME=VALUE with a name without ':' or spaces, got '{arg}'"
        ));
    }
    Ok((name.to_string(), value.to_string()))
}

/// Files named directly are kept as given (with `skip_libraries`, a named `*.xacro` that builds no robot,
/// a macro library, is left out, as in directories); directories contribute every `*.urdf`, `*.sdf` and
/// `*.world` below them, every `*.xml` whose root element is `<mujoco>` (an MJCF model) and every
/// `*.xacro` whose root element is `<robot>` (not the macro libraries it includes), sorted; hidden
/// folders and
/// files ignored by `.gitignore` are skipped. Inputs that
/// do not exist come back as error lines.
pub fn expand(inputs: &[PathBuf], skip_libraries: bool) -> (Vec<PathBuf>, Vec<String>) {
    let mut files = Vec::new();
    let mut errors = Vec::new();
    for input in inputs {
        if input.is_dir() {
            let before = files.len();
            collect_urdfs(input, &mut files);
            files[before..].sort();
            if files.len() == before {
                errors.push(format!(
                    "{}: directory holds no *.urdf, *.sdf or *.world file, no MJCF *.xml and no *.xacro robot",
                    input.display()
                ));
            }
        } else if input.exists() {
            let library = skip_libraries
                && input
                    .extension()
                    .is_some_and(|e| e.eq_ignore_ascii_case("xacro"))
                && !is_robot_xacro(input);
            if !library {
                files.push(input.clone());
            }
        } else {
            errors.push(format!(
                "{}: no such file or directory (expected a URDF file or a directory)",
                input.display()
            ));
        }
    }
    (files, errors)
}

/// Every `*.urdf`, `*.sdf`, `*.world`, MJCF `*.xml` and robot `*.xacro` below `dir`, skipping hidden
/// folders and what `.gitignore` / `.ignore` files exclude (build and install trees).
fn collect_urdfs(dir: &Path, files: &mut Vec<PathBuf>) {
    let walk = ignore::WalkBuilder::new(dir)
        .max_depth(Some(MAX_DEPTH))
        .require_git(false)
        .build();
    for entry in walk.flatten() {
        if !entry.file_type().is_some_and(|t| t.is_file()) {
            continue;
        }
        let path = entry.path();
        let extension = path
            .extension()
            .map(|e| e.to_ascii_lowercase())
            .unwrap_or_default();
        let description = ["urdf", "sdf", "world"].iter().any(|e| extension == *e);
        if description
            || (extension == "xacro" && is_robot_xacro(path))
            || (extension == "xml" && is_mjcf(path))
        {
            files.push(path.to_path_buf());
        }
    }
}

/// How much of an `*.xml` file is read to find its root element.
const MJCF_PEEK: u64 = 64 * 1024;

/// True when the `*.xml` file's root element is `<mujoco>` (within its first [`MJCF_PEEK`] bytes).
fn is_mjcf(path: &Path) -> bool {
    use std::io::Read;
    let mut head = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MJCF_PEEK).read_to_end(&mut head))
        .is_ok_and(|_| urdf_validator::input::xml_files::is_mjcf(&String::from_utf8_lossy(&head)))
}

/// Largest xacro file looked into when deciding whether it is a robot.
const MAX_XACRO_PEEK: u64 = 16 * 1024 * 1024;

/// True when the xacro file's root element is `<robot>` and it builds a robot: a `<link>` or `<joint>`, or a
/// macro call, at its top level (an entry file rather than a library of macros, properties, materials or
/// gazebo blocks, whose root is also `<robot>`).
fn is_robot_xacro(path: &Path) -> bool {
    if std::fs::metadata(path).map_or(true, |m| m.len() > MAX_XACRO_PEEK) {
        return false;
    }
    std::fs::read_to_string(path).is_ok_and(|text| is_robot_xacro_text(&text))
}

/// Whether a xacro file's `text` builds a robot (see [`expand`]: its root element is `<robot>` with a link, a
/// joint or a macro call at the top level); false when it is not well-formed XML.
pub fn is_robot_xacro_text(text: &str) -> bool {
    let Ok(doc) = roxmltree::Document::parse(text) else {
        return false;
    };
    let root = doc.root_element();
    root.tag_name().name() == "robot"
        && root.children().filter(|n| n.is_element()).any(|n| {
            let xacro = n
                .tag_name()
                .namespace()
                .is_some_and(|ns| ns.contains("xacro"));
            if xacro {
                is_call(n)
            } else {
                matches!(n.tag_name().name(), "link" | "joint")
            }
        })
}

/// A `<xacro:...>` element that is not a definition or an include (a macro call, or a condition around
/// one).
fn is_call(node: roxmltree::Node) -> bool {
    !matches!(
        node.tag_name().name(),
        "property" | "macro" | "arg" | "include"
    )
}

#[cfg(test)]
mod tests {
    use super::parse_xacro_arg_flag;

    #[test]
    fn xacro_arg_flags_split_at_the_first_equals_sign() {
        let parsed = |arg: &str| parse_xacro_arg_flag(arg).map_err(|_| ());
        assert_eq!(parsed("mass=4"), Ok(("mass".into(), "4".into())));
        assert_eq!(parsed("mass:=4"), Ok(("mass".into(), "4".into())));
        assert_eq!(parsed("url=a:=b"), Ok(("url".into(), "a:=b".into())));
        assert_eq!(parsed("x=y z:=w"), Ok(("x".into(), "y z:=w".into())));
        assert_eq!(parsed(" name := v"), Ok(("name".into(), " v".into())));
        assert_eq!(parsed("ma:ss=1"), Err(()));
        assert_eq!(parsed("novalue"), Err(()));
        assert_eq!(parsed("=1"), Err(()));
    }
}
