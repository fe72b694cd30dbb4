//! The `<disable_collisions>` entries of an SRDF (MoveIt's allowed-collision pairs).

/// One `<disable_collisions link1 link2 reason>` entry.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DisabledPair {
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

/// Every `<disable_collisions>` of an SRDF document, in document order.
///
/// Errors name the position as `line:col`: XML that is not well-formed, or an entry without `link1` or
/// `link2`.
pub fn disabled_collisions(text: &str) -> Result<Vec<DisabledPair>, String> {
    let doc = roxmltree::Document::parse(text).map_err(|e| {
        let at = e.pos();
        format!("{}:{}: not well-formed XML: {e}", at.row, at.col)
    })?;
    doc.root_element()
        .children()
        .filter(|n| n.has_tag_name("disable_collisions"))
        .map(|node| {
            let position = doc.text_pos_at(node.range().start);
            let attribute = |name: &str| {
                node.attribute(name).map(str::to_string).ok_or_else(|| {
                    format!(
                        "{}:{}: <disable_collisions> has no {name} attribute",
                        position.row, position.col
                    )
                })
            };
            Ok(DisabledPair {
                link1: attribute("link1")?,
                link2: attribute("link2")?,
                reason: node.attribute("reason").map(str::to_string),
                line: position.row,
                column: position.col,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_keep_their_positions() {
        let srdf = "<robot name=\"r\">\n  <group name=\"arm\"/>\n  <disable_collisions link1=\"a\" link2=\"b\" reason=\"Adjacent\"/>\n  <disable_collisions link1=\"c\" link2=\"d\"/>\n</robot>";
        let pairs = disabled_collisions(srdf).unwrap();
        assert_eq!(pairs.len(), 2);
        assert_eq!(
            pairs[0],
            DisabledPair {
                link1: "a".into(),
                link2: "b".into(),
                reason: Some("Adjacent".into()),
                line: 3,
                column: 3
            }
        );
        assert_eq!((pairs[1].line, pairs[1].reason.as_deref()), (4, None));
    }

    #[test]
    fn errors_say_where() {
        let missing = "<robot name=\"r\">\n<disable_collisions link1=\"a\"/></robot>";
        assert_eq!(
            disabled_collisions(missing).unwrap_err(),
            "2:1: <disable_collisions> has no link2 attribute"
        );
        let broken = disabled_collisions("<robot>\n<a></b></robot>").unwrap_err();
        assert!(broken.starts_with("2:4: not well-formed XML"), "{broken}");
    }
}
