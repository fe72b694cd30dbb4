//! Navigation: go to the definition of a link or joint name or of a xacro property, argument or macro (and
//! to the file a mesh or include path names), find every reference to a name across the files of the robot
//! (a xacro tree's includes too),
//! and the document's symbols as the kinematic tree (links holding the joints below them).

use std::collections::HashSet;
use std::path::Path;

use lsp_types::{DocumentSymbol, Location, Range, SymbolKind, Url};
use urdf_validator::input::resolve::PackageResolver;

use super::here::{self, Target};
use super::positions::LineIndex;
use super::xacro_names;
use super::xml::Scan;

/// One file of the robot as the editor has it: its URI, text, line index and scan.
pub struct File {
    /// The file.
    pub uri: Url,
    /// Its text.
    pub text: String,
    /// Its line starts.
    pub index: LineIndex,
    /// Its elements.
    pub scan: Scan,
}

impl File {
    /// `text` of the file at `uri`.
    pub fn new(uri: Url, text: String) -> File {
        let index = LineIndex::new(&text);
        let scan = Scan::new(&text);
        File {
            uri,
            text,
            index,
            scan,
        }
    }

    /// Whether the file is an SRDF (MoveIt's semantic description: it refers to links and joints).
    pub fn is_srdf(&self) -> bool {
        self.uri.path().ends_with(".srdf")
    }

    fn location(&self, span: &std::ops::Range<usize>) -> Location {
        Location::new(
            self.uri.clone(),
            self.index.range(&self.text, span.start, span.end),
        )
    }
}

/// Where `target` is defined: the `<link name>`/`<joint name>` of a name in any of `files`, or the file a
/// path resolves to (from `dir`).
pub fn definition(
    target: &Target,
    files: &[File],
    dir: &Path,
    resolver: &PackageResolver,
) -> Vec<Location> {
    match target {
        Target::Name { kind, name, .. } => files
            .iter()
            .flat_map(|file| {
                here::occurrences(&file.text, &file.scan, *kind, name, file.is_srdf())
                    .into_iter()
                    .filter(|(_, definition)| *definition)
                    .map(|(span, _)| file.location(&span))
            })
            .collect(),
        Target::Xacro { kind, name, .. } => files
            .iter()
            .flat_map(|file| {
                xacro_names::occurrences(file, *kind, name)
                    .into_iter()
                    .filter(|(_, definition)| *definition)
                    .map(|(span, _)| file.location(&span))
            })
            .collect(),
        Target::Path { value, .. } => here::resolve_path(value, dir, resolver)
            .ok()
            .and_then(|path| Url::from_file_path(path).ok())
            .map(|uri| vec![Location::new(uri, Range::default())])
            .unwrap_or_default(),
        Target::Rule { .. } => Vec::new(),
    }
}

/// Every place in `files` naming the thing `target` names (its definition too when
/// `include_declaration`).
pub fn references(target: &Target, files: &[File], include_declaration: bool) -> Vec<Location> {
    let occurrences = |file: &File| match target {
        Target::Name { kind, name, .. } => {
            here::occurrences(&file.text, &file.scan, *kind, name, file.is_srdf())
        }
        Target::Xacro { kind, name, .. } => xacro_names::occurrences(file, *kind, name),
        Target::Path { .. } | Target::Rule { .. } => Vec::new(),
    };
    files
        .iter()
        .flat_map(|file| {
            occurrences(file)
                .into_iter()
                .filter(|(_, definition)| include_declaration || !definition)
                .map(|(span, _)| file.location(&span))
        })
        .collect()
}

/// The kinematic tree of `file`: each root link holding the joints whose parent it is, each joint its
/// child link, and so on; links and joints outside the tree follow at the top level.
#[allow(deprecated)] // DocumentSymbol::deprecated must be written; `tags` replaces it.
pub fn symbols(file: &File) -> Vec<DocumentSymbol> {
    let scan = &file.scan;
    // The robot's own: a `<gazebo>` block's links and joints are Gazebo's.
    let robots = |i: &usize| !scan.is_inside(&scan.elements[*i], "gazebo");
    let links: Vec<usize> = (0..scan.elements.len())
        .filter(|&i| {
            scan.elements[i].name == "link" && scan.elements[i].attribute("name").is_some()
        })
        .filter(robots)
        .collect();
    let joints: Vec<(usize, Option<String>, Option<String>)> = (0..scan.elements.len())
        .filter(|&i| {
            let element = &scan.elements[i];
            element.name == "joint"
                && element.attribute("type").is_some()
                && element.attribute("name").is_some()
        })
        .filter(robots)
        .map(|i| {
            let end = |tag: &str| {
                scan.children(i)
                    .find(|c| c.name == tag)
                    .and_then(|c| c.attribute("link"))
                    .map(|a| a.value.clone())
            };
            (i, end("parent"), end("child"))
        })
        .collect();
    let name = |i: usize| {
        scan.elements[i]
            .attribute("name")
            .map(|a| a.value.clone())
            .unwrap_or_default()
    };
    let children: HashSet<&str> = joints.iter().filter_map(|(_, _, c)| c.as_deref()).collect();
    let mut placed = HashSet::new();
    let mut tree: Vec<DocumentSymbol> = links
        .iter()
        .filter(|&&l| !children.contains(name(l).as_str()))
        .map(|&l| link_symbol(file, l, &links, &joints, &mut placed))
        .collect();
    for &i in links.iter().chain(joints.iter().map(|(j, _, _)| j)) {
        if !placed.contains(&i) {
            placed.insert(i);
            tree.push(symbol(file, i, Vec::new()));
        }
    }
    tree
}

/// The symbol of link `link` holding its joints (each element placed once: a cycle stops there).
fn link_symbol(
    file: &File,
    link: usize,
    links: &[usize],
    joints: &[(usize, Option<String>, Option<String>)],
    placed: &mut HashSet<usize>,
) -> DocumentSymbol {
    placed.insert(link);
    let scan = &file.scan;
    let name = scan.elements[link]
        .attribute("name")
        .map(|a| a.value.as_str())
        .unwrap_or_default();
    let mut children = Vec::new();
    for (joint, parent, child) in joints {
        if parent.as_deref() != Some(name) || placed.contains(joint) {
            continue;
        }
        placed.insert(*joint);
        let below: Vec<DocumentSymbol> = links
            .iter()
            .find(|&&l| {
                !placed.contains(&l)
                    && scan.elements[l].attribute("name").map(|a| a.value.as_str())
                        == child.as_deref()
            })
            .map(|&l| vec![link_symbol(file, l, links, joints, placed)])
            .unwrap_or_default();
        children.push(symbol(file, *joint, below));
    }
    symbol(file, link, children)
}

#[allow(deprecated)] // DocumentSymbol::deprecated must be written; `tags` replaces it.
fn symbol(file: &File, index: usize, children: Vec<DocumentSymbol>) -> DocumentSymbol {
    let element = &file.scan.elements[index];
    let name_span = element
        .attribute("name")
        .map_or(element.tag.clone(), |a| a.value_span.clone());
    let (kind, detail) = if element.name == "link" {
        (SymbolKind::CLASS, None)
    } else {
        (
            SymbolKind::FIELD,
            element
                .attribute("type")
                .map(|t| format!("{} joint", t.value)),
        )
    };
    let range = file
        .index
        .range(&file.text, element.tag.start, element.tag.end);
    let selection = file.index.range(&file.text, name_span.start, name_span.end);
    DocumentSymbol {
        name: element
            .attribute("name")
            .map(|a| a.value.clone())
            .filter(|n| !n.is_empty())
            .unwrap_or_else(|| "(unnamed)".into()),
        detail,
        kind,
        tags: None,
        deprecated: None,
        range: Range::new(range.start, range.end.max(selection.end)),
        selection_range: selection,
        children: (!children.is_empty()).then_some(children),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symbols_nest_links_and_joints_as_the_tree() {
        let text = "<robot name=\"r\"><link name=\"base\"/>\
                    <joint name=\"j1\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/></joint>\
                    <link name=\"arm\"/><link name=\"loose\"/></robot>";
        let file = File::new(Url::parse("file:///r.urdf").expect("uri"), text.into());
        let tree = symbols(&file);
        let names: Vec<&str> = tree.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["base", "loose"]);
        let joint = &tree[0].children.as_ref().expect("joints")[0];
        assert_eq!(joint.name, "j1");
        assert_eq!(joint.detail.as_deref(), Some("revolute joint"));
        assert_eq!(joint.children.as_ref().expect("child")[0].name, "arm");
    }
}
