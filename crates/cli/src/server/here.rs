//! What the cursor is on: a link, joint, material or SDFormat frame name (where defined or where used, an
//! SDFormat `<parent>`/`<child>` text included), a xacro property, argument or
//! macro name, a mesh or include path, or a rule code in a suppression comment, read from the text as the
//! editor has it now.

use std::ops::Range;
use std::path::{Path, PathBuf};

use urdf_validator::input::resolve::{PackageResolver, Resolution};

use super::xacro_names::{self, XacroKind};
use super::xml::{Attribute, Element, Scan};

/// A named thing of the robot, and how a name refers to it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `<link name>`, `<parent link>`, `<child link>`, `reference=`.
    Link,
    /// `<joint name>`, `<mimic joint>`, `<transmission><joint name>`.
    Joint,
    /// `<robot><material name>` (defined), `<visual><material name>` (used).
    Material,
}

/// What is under the cursor.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    /// A link or joint name, where it is defined (`definition`) or used.
    Name {
        /// Link or joint.
        kind: Kind,
        /// The name.
        name: String,
        /// The bytes of the name.
        span: Range<usize>,
    },
    /// A file path: a mesh `filename`, a xacro include.
    Path {
        /// The value as written.
        value: String,
        /// Its bytes.
        span: Range<usize>,
    },
    /// A xacro property (or macro parameter), argument or macro name, where defined or used.
    Xacro {
        /// Which kind.
        kind: XacroKind,
        /// The name.
        name: String,
        /// Its bytes.
        span: Range<usize>,
    },
    /// A rule code in a `<!-- urdf-validate: ignore ... -->` comment.
    Rule {
        /// The code or name as written.
        code: String,
        /// Its bytes.
        span: Range<usize>,
    },
}

/// What the cursor at byte `offset` of `text` is on.
pub fn target(text: &str, scan: &Scan, offset: usize) -> Option<Target> {
    if let Some(rule) = rule_at(text, offset) {
        return Some(rule);
    }
    if let Some((kind, name, span)) = xacro_names::at(text, scan, offset) {
        return Some(Target::Xacro { kind, name, span });
    }
    if let Some(name) = content_at(text, scan, offset) {
        return Some(name);
    }
    let (index, attribute) = scan.at(offset)?;
    let attribute = attribute?;
    let element = &scan.elements[index];
    if let Some(kind) = reference_kind(element, &attribute.name) {
        return Some(Target::Name {
            kind,
            name: attribute.value.clone(),
            span: attribute.value_span.clone(),
        });
    }
    let path_attribute = match element.local_name() {
        "mesh" | "texture" => attribute.name == "filename",
        "include" => attribute.name == "filename" && element.name.starts_with("xacro:"),
        _ => false,
    };
    path_attribute.then(|| Target::Path {
        value: attribute.value.clone(),
        span: attribute.value_span.clone(),
    })
}

/// What an attribute `attribute` of `element` names, if a link, joint or material.
pub fn reference_kind(element: &Element, attribute: &str) -> Option<Kind> {
    match (element.name.as_str(), attribute) {
        ("link", "name") | ("parent" | "child", "link") | ("gazebo", "reference") => {
            Some(Kind::Link)
        }
        ("joint", "name") | ("mimic", "joint") => Some(Kind::Joint),
        ("material", "name") => Some(Kind::Material),
        // SDFormat: frames share the links' names; poses and axes are expressed in either.
        ("frame", "name") | (_, "relative_to" | "attached_to" | "expressed_in") => Some(Kind::Link),
        _ => None,
    }
}

/// SDFormat's `<parent>` and `<child>` of a joint name a link or frame in their text (URDF's carry a `link`
/// attribute instead): the bytes of that name, trimmed, when `element` is one.
fn content_name(text: &str, element: &Element) -> Option<Range<usize>> {
    if !matches!(element.name.as_str(), "parent" | "child") || !element.attributes.is_empty() {
        return None;
    }
    let start = element.tag.end;
    let end = start + text.get(start..)?.find('<')?;
    let body = &text[start..end];
    let first = start + (body.len() - body.trim_start().len());
    let last = end - (body.len() - body.trim_end().len());
    (first < last).then_some(first..last)
}

/// The SDFormat `<parent>`/`<child>` name under `offset`.
fn content_at(text: &str, scan: &Scan, offset: usize) -> Option<Target> {
    scan.elements.iter().find_map(|element| {
        let span = content_name(text, element)?;
        (span.start <= offset && offset <= span.end).then(|| Target::Name {
            kind: Kind::Link,
            name: text[span.clone()].to_string(),
            span,
        })
    })
}

/// What an attribute of an SRDF element refers to (MoveIt's names of the URDF's links and joints: groups,
/// chains, collision entries, the virtual joint). An SRDF defines none of them.
pub fn srdf_reference_kind(element: &Element, attribute: &str) -> Option<Kind> {
    match (element.name.as_str(), attribute) {
        ("link", "name")
        | ("chain", "base_link" | "tip_link")
        | ("disable_collisions" | "enable_collisions", "link1" | "link2")
        | ("disable_default_collisions", "link")
        | ("virtual_joint", "child_link")
        | ("end_effector", "parent_link") => Some(Kind::Link),
        ("joint" | "passive_joint", "name") => Some(Kind::Joint),
        _ => None,
    }
}

/// Whether `element`'s `attribute` defines the name (rather than refers to it). What a `<gazebo>` block
/// holds (Gazebo's own links and joints, SDFormat inside URDF) defines nothing of the robot.
pub fn is_definition(scan: &Scan, element: &Element, attribute: &Attribute) -> bool {
    let parent = element.parent.map(|p| scan.elements[p].name.as_str());
    attribute.name == "name"
        && !scan.is_inside(element, "gazebo")
        && (element.name == "link"
            || element.name == "frame"
            || element.name == "joint" && parent != Some("transmission")
            || element.name == "material" && parent == Some("robot"))
}

/// Every place of `text` (scanned as `scan`) naming the `kind` thing `name`: (span of the name, whether it
/// defines it). `srdf`: the text is an SRDF (it only refers to names).
pub fn occurrences(
    text: &str,
    scan: &Scan,
    kind: Kind,
    name: &str,
    srdf: bool,
) -> Vec<(Range<usize>, bool)> {
    let in_content = scan.elements.iter().filter_map(|element| {
        let span = content_name(text, element)?;
        (kind == Kind::Link && &text[span.clone()] == name).then_some((span, false))
    });
    let mut found: Vec<(Range<usize>, bool)> = scan
        .elements
        .iter()
        .flat_map(|element| {
            element
                .attributes
                .iter()
                .filter(move |attribute| {
                    let refers = if srdf {
                        srdf_reference_kind(element, &attribute.name)
                    } else {
                        reference_kind(element, &attribute.name)
                    };
                    attribute.value == name && refers == Some(kind)
                })
                .map(move |attribute| {
                    (
                        attribute.value_span.clone(),
                        !srdf && is_definition(scan, element, attribute),
                    )
                })
        })
        .collect();
    found.extend(in_content);
    found.sort_by_key(|(span, _)| span.start);
    found
}

/// The file a path attribute names: `package://`, `file://`, `$(find pkg)/...` or relative to `dir`.
pub fn resolve_path(
    value: &str,
    dir: &Path,
    resolver: &PackageResolver,
) -> Result<PathBuf, String> {
    if let Some(rest) = value.strip_prefix("$(find ") {
        let (package, tail) = rest
            .split_once(')')
            .ok_or_else(|| format!("{value}: expected $(find PACKAGE)/path"))?;
        let root = resolver.find_package(package.trim(), dir).ok_or_else(|| {
            format!(
                "package '{}' not found from {}",
                package.trim(),
                dir.display()
            )
        })?;
        let path = root.join(tail.trim_start_matches('/'));
        return if path.exists() {
            Ok(path)
        } else {
            Err(format!("{} does not exist", path.display()))
        };
    }
    if value.contains("${") || value.contains("$(") {
        return Err(format!(
            "{value}: computed by xacro; hover the expanded value's source"
        ));
    }
    match resolver.resolve(value, dir) {
        Resolution::Found(path) | Resolution::Lenient { path, .. } => Ok(path),
        Resolution::NotFound { searched } if searched.is_empty() => {
            Err(format!("{value}: package not found"))
        }
        Resolution::NotFound { searched } => Err(format!(
            "{value}: not found; looked in {}",
            searched
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        )),
        Resolution::Unsupported(why) => Err(format!("{value}: {why}")),
        Resolution::Refused(refusal) => Err(format!("{value}: {}", refusal.0)),
    }
}

/// The rule code under `offset` in a suppression comment.
fn rule_at(text: &str, offset: usize) -> Option<Target> {
    let (body, body_start) = suppression_comment_at(text, offset)?;
    let directive = body.find("urdf-validate:")? + "urdf-validate:".len();
    let mut at = body_start + directive;
    for word in body[directive..].split(|c: char| c.is_whitespace() || c == ',') {
        let span = at..at + word.len();
        at += word.len() + 1;
        if word.starts_with(';') {
            break;
        }
        if span.contains(&offset) || span.end == offset && !word.is_empty() {
            let is_code = word != "ignore" && word != "ignore-file" && !word.is_empty();
            return is_code.then(|| Target::Rule {
                code: word.to_string(),
                span,
            });
        }
    }
    None
}

/// The body of the `<!-- urdf-validate: ... -->` comment holding `offset` (to the cursor when it is not
/// closed yet), and the byte it starts at.
pub fn suppression_comment_at(text: &str, offset: usize) -> Option<(&str, usize)> {
    let offset = offset.min(text.len());
    let open = text.get(..offset)?.rfind("<!--")?;
    let start = open + 4;
    let end = text[start..].find("-->").map_or(text.len(), |i| start + i);
    if end < offset {
        return None;
    }
    let body = &text[start..end];
    body.trim_start()
        .starts_with("urdf-validate:")
        .then_some((body, start))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_paths_and_rule_codes_under_the_cursor() {
        let text = "<robot>\n<link name=\"base\"/>\n<joint name=\"j\" type=\"fixed\">\
                    <parent link=\"base\"/><child link=\"arm\"/><mimic joint=\"k\"/></joint>\n\
                    <link name=\"arm\"><visual><geometry><mesh filename=\"package://p/m.stl\"/>\
                    </geometry></visual></link>\n<!-- urdf-validate: ignore U201, U203 -->\n</robot>";
        let scan = Scan::new(text);
        let at = |needle: &str| text.find(needle).expect("needle") + 1;
        let name = |target: Option<Target>| match target {
            Some(Target::Name { kind, name, .. }) => Some((kind, name)),
            _ => None,
        };
        assert_eq!(
            name(target(text, &scan, at("base\"/><child"))),
            Some((Kind::Link, "base".into()))
        );
        assert_eq!(
            name(target(text, &scan, at("k\"/>"))),
            Some((Kind::Joint, "k".into()))
        );
        assert!(matches!(
            target(text, &scan, at("package://")),
            Some(Target::Path { value, .. }) if value == "package://p/m.stl"
        ));
        assert!(matches!(
            target(text, &scan, at("U203")),
            Some(Target::Rule { code, .. }) if code == "U203"
        ));
        assert_eq!(target(text, &scan, at("ignore U")), None);
        let uses = occurrences(text, &scan, Kind::Link, "base", false);
        assert_eq!(uses.iter().filter(|(_, d)| *d).count(), 1);
        assert_eq!(uses.len(), 2);
        let text = "<robot><material name=\"blue\"><color rgba=\"0 0 1 1\"/></material>\
                    <link name=\"a\"><visual><material name=\"blue\"/></visual></link></robot>";
        let scan = Scan::new(text);
        let blue = occurrences(text, &scan, Kind::Material, "blue", false);
        assert_eq!(
            blue.iter().map(|(_, d)| *d).collect::<Vec<_>>(),
            [true, false]
        );
        assert_eq!(
            name(target(text, &scan, text.rfind("blue").expect("use") + 1)),
            Some((Kind::Material, "blue".into()))
        );
        let srdf = "<robot><group name=\"arm\"><link name=\"a\"/><joint name=\"j\"/></group>\
                    <disable_collisions link1=\"a\" link2=\"b\" reason=\"Adjacent\"/></robot>";
        let scan = Scan::new(srdf);
        assert_eq!(
            occurrences(srdf, &scan, Kind::Link, "a", true)
                .iter()
                .map(|(span, defines)| (&srdf[span.clone()], *defines))
                .collect::<Vec<_>>(),
            [("a", false), ("a", false)]
        );
        assert_eq!(occurrences(srdf, &scan, Kind::Joint, "j", true).len(), 1);
        let sdf = "<sdf><model name=\"m\"><link name=\"base\"/><frame name=\"tool\" attached_to=\"base\"/>\
                   <joint name=\"j\" type=\"revolute\"><parent> base </parent><child>arm</child>\
                   <pose relative_to=\"tool\"/></joint></model></sdf>";
        let scan = Scan::new(sdf);
        let at = |needle: &str| sdf.find(needle).expect("needle") + 1;
        assert_eq!(
            name(target(sdf, &scan, at("base </parent>"))),
            Some((Kind::Link, "base".into()))
        );
        let base = occurrences(sdf, &scan, Kind::Link, "base", false);
        assert_eq!(
            base.iter()
                .map(|(span, defines)| (&sdf[span.clone()], *defines))
                .collect::<Vec<_>>(),
            [("base", true), ("base", false), ("base", false)]
        );
        let tool = occurrences(sdf, &scan, Kind::Link, "tool", false);
        assert_eq!(
            tool.iter().map(|(_, d)| *d).collect::<Vec<_>>(),
            [true, false]
        );
    }
}
