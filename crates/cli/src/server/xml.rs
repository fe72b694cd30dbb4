//! A tolerant scan of the elements and attributes of XML as it is being typed: start tags with their
//! attributes and byte spans, nested as written. Half-typed text (an unclosed tag, a missing quote) ends
//! the element there; nothing fails. Hover, navigation and completion read the editor's text with it, so
//! they work on the text as it is now, even when it is not well-formed.

use std::ops::Range;

/// One attribute of a start tag.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Attribute {
    /// Its name as written (`link`, `xacro:name`).
    pub name: String,
    /// Its value, as written (entities left alone).
    pub value: String,
    /// The bytes of the value, without the quotes.
    pub value_span: Range<usize>,
}

/// One element's start tag.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Element {
    /// Its name as written (`joint`, `xacro:macro`).
    pub name: String,
    /// The bytes of the start tag, `<` to `>` (to the end of what was typed when unclosed).
    pub tag: Range<usize>,
    /// Its attributes.
    pub attributes: Vec<Attribute>,
    /// The index of the enclosing element in [`Scan::elements`].
    pub parent: Option<usize>,
}

impl Element {
    /// The attribute `name`.
    pub fn attribute(&self, name: &str) -> Option<&Attribute> {
        self.attributes.iter().find(|a| a.name == name)
    }

    /// Its local name (`macro` for `xacro:macro`).
    pub fn local_name(&self) -> &str {
        self.name.rsplit(':').next().unwrap_or(&self.name)
    }
}

/// Every start tag of a text, in document order.
#[derive(Clone, Debug, Default)]
pub struct Scan {
    /// The elements.
    pub elements: Vec<Element>,
}

impl Scan {
    /// Scan `text`.
    pub fn new(text: &str) -> Scan {
        let bytes = text.as_bytes();
        let mut elements: Vec<Element> = Vec::new();
        let mut open: Vec<usize> = Vec::new();
        let mut at = 0;
        while let Some(lt) = find(bytes, at, b"<") {
            let rest = &text[lt..];
            if rest.starts_with("<!--") {
                at = find(bytes, lt + 4, b"-->").map_or(bytes.len(), |end| end + 3);
            } else if rest.starts_with("<![CDATA[") {
                at = find(bytes, lt, b"]]>").map_or(bytes.len(), |end| end + 3);
            } else if rest.starts_with("<?") || rest.starts_with("<!") {
                at = find(bytes, lt, b">").map_or(bytes.len(), |end| end + 1);
            } else if rest.starts_with("</") {
                let (name, end) = name_at(text, lt + 2);
                // Close up to the matching open element (an unclosed one inside ends here too).
                if let Some(depth) = open.iter().rposition(|&i| elements[i].name == name) {
                    open.truncate(depth);
                }
                at = find(bytes, end, b">").map_or(bytes.len(), |end| end + 1);
            } else {
                let (element, end, self_closing) = start_tag(text, lt, open.last().copied());
                at = end.max(lt + 1);
                if element.name.is_empty() {
                    continue;
                }
                elements.push(element);
                if !self_closing {
                    open.push(elements.len() - 1);
                }
            }
        }
        Scan { elements }
    }

    /// The element whose start tag holds byte `offset`, and the attribute whose value holds it (its end
    /// included, where the cursor is after typing).
    pub fn at(&self, offset: usize) -> Option<(usize, Option<&Attribute>)> {
        let index = self
            .elements
            .iter()
            .rposition(|e| e.tag.start <= offset && offset <= e.tag.end)?;
        let attribute = self.elements[index]
            .attributes
            .iter()
            .find(|a| a.value_span.start <= offset && offset <= a.value_span.end);
        Some((index, attribute))
    }

    /// The elements directly inside element `parent`.
    pub fn children(&self, parent: usize) -> impl Iterator<Item = &Element> {
        self.elements
            .iter()
            .filter(move |e| e.parent == Some(parent))
    }

    /// Whether `element` is inside an element named `name` (at any depth): a `<link>` inside `<gazebo>`
    /// is Gazebo's, not the robot's.
    pub fn is_inside(&self, element: &Element, name: &str) -> bool {
        let mut parent = element.parent;
        while let Some(index) = parent {
            let Some(enclosing) = self.elements.get(index) else {
                return false;
            };
            if enclosing.name == name {
                return true;
            }
            parent = enclosing.parent;
        }
        false
    }
}

/// The start tag at `lt`: the element, the byte after it, and whether it closes itself (`/>`).
fn start_tag(text: &str, lt: usize, parent: Option<usize>) -> (Element, usize, bool) {
    let bytes = text.as_bytes();
    let (name, mut at) = name_at(text, lt + 1);
    let mut attributes = Vec::new();
    loop {
        while at < bytes.len() && bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        match bytes.get(at) {
            None | Some(b'<') => break,
            Some(b'>') => {
                let element = element(name, lt..at + 1, attributes, parent);
                return (element, at + 1, false);
            }
            Some(b'/') if bytes.get(at + 1) == Some(&b'>') => {
                let element = element(name, lt..at + 2, attributes, parent);
                return (element, at + 2, true);
            }
            _ => {}
        }
        let (attribute, end) = name_at(text, at);
        if attribute.is_empty() {
            at += text[at..].chars().next().map_or(1, char::len_utf8);
            continue;
        }
        at = end;
        while at < bytes.len() && bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        if bytes.get(at) != Some(&b'=') {
            continue;
        }
        at += 1;
        while at < bytes.len() && bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        let Some(&quote) = bytes.get(at).filter(|q| **q == b'"' || **q == b'\'') else {
            continue;
        };
        let start = at + 1;
        // A value runs to its closing quote; an unclosed one to the end of its line.
        let end = (start..bytes.len())
            .find(|&i| bytes[i] == quote || bytes[i] == b'\n' || bytes[i] == b'<')
            .unwrap_or(bytes.len());
        attributes.push(Attribute {
            name: attribute,
            value: text[start..end].to_string(),
            value_span: start..end,
        });
        at = if bytes.get(end) == Some(&quote) {
            end + 1
        } else {
            end
        };
    }
    let element = element(name, lt..at, attributes, parent);
    (element, at, true)
}

fn element(
    name: String,
    tag: Range<usize>,
    attributes: Vec<Attribute>,
    parent: Option<usize>,
) -> Element {
    Element {
        name,
        tag,
        attributes,
        parent,
    }
}

/// The XML name starting at `at`, and the byte after it.
fn name_at(text: &str, at: usize) -> (String, usize) {
    let rest = text.get(at..).unwrap_or("");
    let len = rest
        .find(|c: char| c.is_whitespace() || matches!(c, '=' | '>' | '/' | '<' | '"' | '\''))
        .unwrap_or(rest.len());
    (rest[..len].to_string(), at + len)
}

/// The first `needle` in `bytes` from `from`.
fn find(bytes: &[u8], from: usize, needle: &[u8]) -> Option<usize> {
    bytes
        .get(from..)?
        .windows(needle.len())
        .position(|w| w == needle)
        .map(|i| from + i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elements_nest_and_half_typed_text_is_read_as_far_as_it_goes() {
        let text = "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n  <!-- <link name=\"no\"/> -->\n  \
                    <joint name=\"j\" type=\"fixed\">\n    <parent link=\"a\"/>\n    <child link=\"b\n  \
                    </joint>\n  <link name='a'/>\n  <link name=\"c";
        let scan = Scan::new(text);
        let names: Vec<&str> = scan.elements.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["robot", "joint", "parent", "child", "link", "link"]);
        let joint = &scan.elements[1];
        assert_eq!(joint.parent, Some(0));
        assert_eq!(
            scan.children(1)
                .map(|e| e.name.as_str())
                .collect::<Vec<_>>(),
            ["parent", "child"]
        );
        assert_eq!(
            scan.elements[3].attribute("link").map(|a| a.value.as_str()),
            Some("b")
        );
        assert_eq!(
            scan.elements[4].parent,
            Some(0),
            "</joint> closed the joint"
        );
        let a = scan.elements[2].attribute("link").expect("link");
        assert_eq!(&text[a.value_span.clone()], "a");
        let (element, attribute) = scan.at(a.value_span.end).expect("inside");
        assert_eq!(
            (element, attribute.map(|a| a.value.as_str())),
            (2, Some("a"))
        );
        assert_eq!(
            scan.elements[5].attribute("name").map(|a| a.value.as_str()),
            Some("c")
        );
    }
}
