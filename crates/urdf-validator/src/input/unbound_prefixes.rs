//! Namespace prefixes no `xmlns:` declares (`<sensor:camera>` in old Fetch-style files). XML with
//! namespaces refuses them; urdfdom (TinyXML2), Pinocchio and Gazebo read such a file, and the element is
//! one they do not know. This module rewrites the prefixed names so that a namespace-aware parser reads
//! them as plain unknown names: the colon becomes `_`, every other byte (and so every line, column and
//! byte offset a finding or a fix points at) stays where it was.

use crate::diagnostics::span::Span;

/// A prefix used without a declaration, and where it is first used.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnboundPrefix {
    /// The prefix, without the colon (`sensor`).
    pub prefix: String,
    /// The first prefixed name (`sensor:camera`).
    pub span: Span,
}

/// Most distinct unbound prefixes rewritten in one document; past that the parser's error stands.
const MAX_PREFIXES: usize = 32;

/// When `text` parses (with [`xml_options`](super::xml_options)) only once its undeclared prefixes are rewritten: the rewritten text and the
/// prefixes. `None` when the text parses as it is, or fails for any other reason (the caller reports the
/// parser's error as usual).
pub fn rewrite_unbound_prefixes(text: &str) -> Option<(String, Vec<UnboundPrefix>)> {
    let mut rewritten: Option<String> = None;
    let mut prefixes = Vec::new();
    loop {
        let current = rewritten.as_deref().unwrap_or(text);
        let prefix = match roxmltree::Document::parse_with_options(current, super::xml_options()) {
            Ok(_) => return rewritten.map(|text| (text, prefixes)),
            Err(roxmltree::Error::UnknownNamespace(prefix, _)) => prefix,
            Err(_) => return None,
        };
        if prefixes.len() >= MAX_PREFIXES || prefix.is_empty() {
            return None;
        }
        let (next, first) = unbind(current, &prefix);
        let first = first?;
        prefixes.push(UnboundPrefix {
            prefix,
            span: first,
        });
        rewritten = Some(next);
    }
}

/// `text` with the colon of every element or attribute name prefixed `prefix:` replaced by `_`, and the
/// span of the first such name. Comments, CDATA, processing instructions, the DOCTYPE, attribute values
/// and character data are left alone.
fn unbind(text: &str, prefix: &str) -> (String, Option<Span>) {
    let bytes = text.as_bytes();
    let mut out = bytes.to_vec();
    let mut first = None;
    let mut i = 0;
    // Inside a start or end tag, and the quote of the attribute value being read there.
    let mut in_tag = false;
    let mut quote: Option<u8> = None;
    // A name may start here (just after `<`, `</` or whitespace inside a tag).
    let mut name_may_start = false;
    while i < bytes.len() {
        let rest = &bytes[i..];
        if in_tag {
            let c = bytes[i];
            if let Some(q) = quote {
                if c == q {
                    quote = None;
                }
            } else if c == b'"' || c == b'\'' {
                quote = Some(c);
                name_may_start = false;
            } else if c == b'>' {
                in_tag = false;
            } else if c.is_ascii_whitespace() || c == b'/' {
                name_may_start = true;
            } else {
                if name_may_start && prefixed(rest, prefix) {
                    out[i + prefix.len()] = b'_';
                    first.get_or_insert(name_span(bytes, i));
                }
                name_may_start = false;
            }
            i += 1;
            continue;
        }
        let skip_to = |end: &[u8]| find(rest, end).map_or(bytes.len(), |at| i + at + end.len());
        if rest.starts_with(b"<!--") {
            i = skip_to(b"-->");
        } else if rest.starts_with(b"<![CDATA[") {
            i = skip_to(b"]]>");
        } else if rest.starts_with(b"<?") {
            i = skip_to(b"?>");
        } else if rest.starts_with(b"<!") {
            i = skip_doctype(bytes, i);
        } else if rest.starts_with(b"<") {
            in_tag = true;
            name_may_start = true;
            i += 1;
        } else {
            i += 1;
        }
    }
    // Only an ASCII colon became an ASCII underscore: the bytes are still UTF-8.
    (
        String::from_utf8(out).unwrap_or_else(|_| text.to_string()),
        first,
    )
}

/// True when `rest` starts with `prefix:` followed by a name character.
fn prefixed(rest: &[u8], prefix: &str) -> bool {
    rest.starts_with(prefix.as_bytes())
        && rest.get(prefix.len()) == Some(&b':')
        && rest
            .get(prefix.len() + 1)
            .is_some_and(|c| !c.is_ascii_whitespace() && !b"=/>\"'".contains(c))
}

/// The span of the name starting at `start` (up to whitespace, `=`, `/` or `>`).
fn name_span(bytes: &[u8], start: usize) -> Span {
    let end = bytes[start..]
        .iter()
        .position(|c| c.is_ascii_whitespace() || b"=/>".contains(c))
        .map_or(bytes.len(), |n| start + n);
    Span {
        start: u32::try_from(start).unwrap_or(u32::MAX),
        end: u32::try_from(end).unwrap_or(u32::MAX),
    }
}

/// The offset just past the `<!DOCTYPE ...>` (or other `<!` declaration) starting at `start`, skipping
/// an internal subset in brackets and quoted literals.
fn skip_doctype(bytes: &[u8], start: usize) -> usize {
    let mut depth = 0usize;
    let mut quote: Option<u8> = None;
    for (offset, &c) in bytes[start..].iter().enumerate() {
        match (quote, c) {
            (Some(q), _) if c == q => quote = None,
            (Some(_), _) => {}
            (None, b'"' | b'\'') => quote = Some(c),
            (None, b'[') => depth += 1,
            (None, b']') => depth = depth.saturating_sub(1),
            (None, b'>') if depth == 0 => return start + offset + 1,
            _ => {}
        }
    }
    bytes.len()
}

/// The offset of `needle` in `haystack`.
fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undeclared_prefixes_become_plain_names_at_the_same_offsets() {
        let text = "<robot name=\"r\">\n  <!-- <sensor:x> -->\n  <sensor:camera sensor:fov=\"a:b\" name='c'>\n    <sensor:image width=\"1\"/>\n  </sensor:camera>\n  <link name=\"base\"/>\n</robot>\n";
        assert!(roxmltree::Document::parse(text).is_err());
        let (rewritten, prefixes) = rewrite_unbound_prefixes(text).unwrap();
        assert_eq!(rewritten.len(), text.len());
        assert_eq!(
            rewritten,
            text.replace("<sensor:c", "<sensor_c")
                .replace(" sensor:fov", " sensor_fov")
                .replace("<sensor:image", "<sensor_image")
                .replace("</sensor:", "</sensor_")
        );
        assert_eq!(prefixes.len(), 1);
        assert_eq!(prefixes[0].prefix, "sensor");
        let span = prefixes[0].span;
        assert_eq!(
            &text[span.start as usize..span.end as usize],
            "sensor:camera"
        );
    }

    #[test]
    fn several_prefixes_and_declared_ones() {
        let text = r#"<robot xmlns:xacro="http://ros.org/wiki/xacro" name="r"><a:b/><c:d a:e="1"/><xacro:property name="x" value="1"/></robot>"#;
        let (rewritten, prefixes) = rewrite_unbound_prefixes(text).unwrap();
        let names: Vec<&str> = prefixes.iter().map(|p| p.prefix.as_str()).collect();
        assert_eq!(names, ["a", "c"]);
        assert!(rewritten.contains("<xacro:property"));
        assert!(rewritten.contains(r#"<c_d a_e="1"/>"#));
    }

    #[test]
    fn well_formed_or_otherwise_broken_text_is_left_to_the_parser() {
        assert!(rewrite_unbound_prefixes("<robot name=\"r\"/>").is_none());
        assert!(rewrite_unbound_prefixes("<robot><a:b></robot>").is_none());
        assert!(rewrite_unbound_prefixes("<robot").is_none());
    }
}
