//! The SRDF beside a URDF, found and read once: its named poses (`<group_state>`) and its allowed-collision
//! entries as MoveIt reads them (`<disable_collisions>`, `<enable_collisions>`,
//! `<disable_default_collisions>`).

use std::path::{Path, PathBuf};

use crate::input::source::SourceText;

/// An SRDF file and its text (or why it could not be read).
#[derive(Clone, Debug)]
pub struct Srdf {
    /// The file.
    pub path: PathBuf,
    /// Its text, or the read error.
    pub text: Result<String, String>,
}

impl Srdf {
    /// Read the SRDF at `path` (size-limited like every input).
    pub fn read(path: PathBuf) -> Srdf {
        let text = crate::input::read_text(&path).map_err(|e| match e {
            crate::input::LoadError::Io { error, .. } => error.to_string(),
            other => other.to_string(),
        });
        Srdf { path, text }
    }
}

/// The SRDF to use: the explicit one, else `<stem>.srdf`, else `<robot name>.srdf` (the name MoveIt's
/// setup assistant gives it), each beside the URDF or in a sibling `srdf/` folder.
pub fn find(
    urdf_path: &Path,
    robot_name: Option<&str>,
    explicit: Option<&Path>,
) -> Option<PathBuf> {
    if let Some(path) = explicit {
        return path.is_file().then(|| path.to_path_buf());
    }
    let file_name = urdf_path.file_name()?.to_str()?;
    let stem = file_name.strip_suffix(".xacro").unwrap_or(file_name);
    let stem = stem.strip_suffix(".urdf").unwrap_or(stem);
    let dir = urdf_path.parent().unwrap_or(Path::new("."));
    // A robot name is a file name only when it cannot leave the folder.
    let safe_name = robot_name.filter(|n| !n.is_empty() && !n.contains(['/', '\\']) && *n != "..");
    [Some(stem), safe_name]
        .into_iter()
        .flatten()
        .flat_map(|name| {
            let name = format!("{name}.srdf");
            [dir.join(&name), dir.join("../srdf").join(&name)]
        })
        .find(|p| p.is_file())
}

/// One `<group_state>` of an SRDF.
#[derive(Clone, Debug, PartialEq)]
pub struct GroupState {
    /// `name`.
    pub name: String,
    /// `group`.
    pub group: String,
    /// `<joint name value>` entries (multi-value joints keep their first value).
    pub joints: Vec<(String, f64)>,
}

/// Every `group_state` of an SRDF document.
pub fn group_states(text: &str) -> Result<Vec<GroupState>, String> {
    let doc = roxmltree::Document::parse(text).map_err(|e| format!("not well-formed XML: {e}"))?;
    Ok(doc
        .root_element()
        .children()
        .filter(|n| n.has_tag_name("group_state"))
        .map(|state| GroupState {
            name: state.attribute("name").unwrap_or_default().to_string(),
            group: state.attribute("group").unwrap_or_default().to_string(),
            joints: state
                .children()
                .filter(|n| n.has_tag_name("joint"))
                .filter_map(|j| {
                    let value = j
                        .attribute("value")?
                        .split_whitespace()
                        .next()?
                        .parse::<f64>()
                        .ok()?;
                    Some((j.attribute("name")?.to_string(), value))
                })
                .collect(),
        })
        .collect())
}

/// One `<disable_collisions>` or `<enable_collisions>` entry (`link1`, `link2`, `reason`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SrdfPair {
    /// `link1`.
    pub link1: String,
    /// `link2`.
    pub link2: String,
    /// `reason` (`Adjacent`, `Never`, `Default`, ...), when written.
    pub reason: Option<String>,
    /// 1-based line of the element.
    pub line: u32,
    /// 1-based column of the element.
    pub column: u32,
}

/// One `<disable_default_collisions link>` entry: the link collides with nothing unless an
/// `<enable_collisions>` names the pair.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SrdfLink {
    /// `link`.
    pub link: String,
    /// 1-based line of the element.
    pub line: u32,
    /// 1-based column of the element.
    pub column: u32,
}

/// The allowed-collision entries of one SRDF, each kind in document order.
///
/// A pair is never checked when a `<disable_collisions>` names it, or when one of its links has
/// `<disable_default_collisions>` and no `<enable_collisions>` names the pair (MoveIt's precedence:
/// disabled beats enabled beats the default).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SrdfCollisions {
    /// `<disable_collisions>`.
    pub disabled: Vec<SrdfPair>,
    /// `<enable_collisions>`.
    pub enabled: Vec<SrdfPair>,
    /// `<disable_default_collisions>`.
    pub disabled_by_default: Vec<SrdfLink>,
}

impl SrdfCollisions {
    /// Every link name the entries mention, as `(tag, link, line, column)`.
    pub fn named_links(&self) -> Vec<(&'static str, &str, u32, u32)> {
        let mut named = Vec::new();
        for (tag, pairs) in [
            ("disable_collisions", &self.disabled),
            ("enable_collisions", &self.enabled),
        ] {
            for pair in pairs {
                for link in [&pair.link1, &pair.link2] {
                    named.push((tag, link.as_str(), pair.line, pair.column));
                }
            }
        }
        named.extend(self.disabled_by_default.iter().map(|entry| {
            let tag = "disable_default_collisions";
            (tag, entry.link.as_str(), entry.line, entry.column)
        }));
        named
    }
}

/// The allowed-collision entries of an SRDF document.
///
/// Errors name the position as `line:col`: XML that is not well-formed, or an entry without a link
/// attribute it needs.
pub fn srdf_collisions(text: &str) -> Result<SrdfCollisions, String> {
    let doc = roxmltree::Document::parse(text).map_err(|e| {
        let at = e.pos();
        format!("{}:{}: not well-formed XML: {e}", at.row, at.col)
    })?;
    // A line index: roxmltree's `text_pos_at` scans from the start each time (quadratic on a big SRDF).
    let lines = SourceText::new("", text.to_string());
    let mut collisions = SrdfCollisions::default();
    for node in doc.root_element().children().filter(|n| n.is_element()) {
        let (row, col) = lines.line_col(node.range().start);
        let position = roxmltree::TextPos { row, col };
        let tag = node.tag_name().name();
        let attribute = |name: &str| {
            node.attribute(name).map(str::to_string).ok_or_else(|| {
                format!(
                    "{}:{}: <{tag}> has no {name} attribute",
                    position.row, position.col
                )
            })
        };
        let pair = || -> Result<SrdfPair, String> {
            Ok(SrdfPair {
                link1: attribute("link1")?,
                link2: attribute("link2")?,
                reason: node.attribute("reason").map(str::to_string),
                line: position.row,
                column: position.col,
            })
        };
        match tag {
            "disable_collisions" => collisions.disabled.push(pair()?),
            "enable_collisions" => collisions.enabled.push(pair()?),
            "disable_default_collisions" => collisions.disabled_by_default.push(SrdfLink {
                link: attribute("link")?,
                line: position.row,
                column: position.col,
            }),
            _ => {}
        }
    }
    Ok(collisions)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_keep_their_positions() {
        let srdf = "<robot name=\"r\">\n  <group name=\"arm\"/>\n  <disable_collisions link1=\"a\" link2=\"b\" reason=\"Adjacent\"/>\n  <disable_collisions link1=\"c\" link2=\"d\"/>\n  <enable_collisions link1=\"e\" link2=\"f\"/>\n  <disable_default_collisions link=\"g\"/>\n</robot>";
        let collisions = srdf_collisions(srdf).unwrap();
        assert_eq!(collisions.disabled.len(), 2);
        assert_eq!(
            collisions.disabled[0],
            SrdfPair {
                link1: "a".into(),
                link2: "b".into(),
                reason: Some("Adjacent".into()),
                line: 3,
                column: 3
            }
        );
        assert_eq!(
            (
                collisions.disabled[1].line,
                collisions.disabled[1].reason.as_deref()
            ),
            (4, None)
        );
        assert_eq!(
            (
                collisions.enabled[0].line,
                collisions.enabled[0].link2.as_str()
            ),
            (5, "f")
        );
        assert_eq!(
            collisions.disabled_by_default,
            vec![SrdfLink {
                link: "g".into(),
                line: 6,
                column: 3
            }]
        );
        let named: Vec<_> = collisions
            .named_links()
            .into_iter()
            .map(|(_, link, ..)| link)
            .collect();
        assert_eq!(named, ["a", "b", "c", "d", "e", "f", "g"]);
    }

    #[test]
    fn errors_say_where() {
        let missing = "<robot name=\"r\">\n<disable_collisions link1=\"a\"/></robot>";
        assert_eq!(
            srdf_collisions(missing).unwrap_err(),
            "2:1: <disable_collisions> has no link2 attribute"
        );
        let no_link = "<robot name=\"r\">\n  <disable_default_collisions/></robot>";
        assert_eq!(
            srdf_collisions(no_link).unwrap_err(),
            "2:3: <disable_default_collisions> has no link attribute"
        );
        let broken = srdf_collisions("<robot>\n<a></b></robot>").unwrap_err();
        assert!(broken.starts_with("2:4: not well-formed XML"), "{broken}");
    }

    #[test]
    fn group_states_are_read() {
        let srdf = r#"<robot name="r"><group name="arm"/>
          <group_state name="home" group="arm"><joint name="j1" value="0.5"/><joint name="j2" value="-1"/></group_state>
          <group_state name="up" group="arm"><joint name="j1" value="1"/></group_state></robot>"#;
        let states = group_states(srdf).unwrap();
        assert_eq!(states.len(), 2);
        assert_eq!(
            states[0].joints,
            vec![("j1".to_string(), 0.5), ("j2".to_string(), -1.0)]
        );
    }
}
