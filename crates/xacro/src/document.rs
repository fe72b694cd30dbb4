//! The tree the expander works on: source files parsed with roxmltree into shared, immutable nodes that
//! remember where they were written, and the output nodes built from them (same type, so macro blocks can
//! be evaluated again as Python xacro does).

use std::rc::Rc;

use crate::error::{ErrorKind, XacroError};
use crate::source_map::FrameKind;

/// A shared node.
pub(crate) type NodeRef = Rc<Node>;

/// A node with its origin.
#[derive(Debug)]
pub(crate) struct Node {
    pub kind: Kind,
    pub src: Src,
}

/// What a node is.
#[derive(Debug)]
pub(crate) enum Kind {
    Element(Element),
    Text(Rc<str>),
    /// A CDATA section: kept as written, never evaluated.
    CData(Rc<str>),
    Comment(Rc<str>),
    Pi {
        target: String,
        data: Option<String>,
    },
    /// Python xacro's `_empty_text_node` singleton ("\n\n"), moved around by `remove_previous_comments`:
    /// only the instance with the latest generation exists; older ones are treated as absent.
    Separator(u64),
}

/// An element: its qualified name as written (`xacro:macro`), attributes in document order (namespace
/// declarations first, as minidom has them), children.
#[derive(Debug)]
pub(crate) struct Element {
    pub name: Rc<str>,
    pub attrs: Vec<Attr>,
    pub children: Vec<NodeRef>,
}

/// An attribute and where its name and value were written.
#[derive(Clone, Debug)]
pub(crate) struct Attr {
    pub name: Rc<str>,
    pub value: Rc<str>,
    pub name_loc: Loc,
    /// Origin of the value.
    pub src: Src,
}

/// A byte range in a source file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Loc {
    pub file: u32,
    pub start: u32,
    pub end: u32,
}

/// Where a node was written, and the macro/include frame it was instantiated in (`None` = not yet
/// instantiated: a node straight from a parsed file or a macro body; `Some(None)` = at the top level).
#[derive(Clone, Debug)]
pub(crate) struct Src {
    pub loc: Loc,
    pub frame: Option<Option<FrameRef>>,
}

impl Src {
    /// The same origin, placed in `frame` unless it was already placed (block contents keep the frame of
    /// the call site where they were written).
    pub fn placed(&self, frame: &Option<FrameRef>) -> Src {
        Src {
            loc: self.loc,
            frame: Some(match &self.frame {
                Some(f) => f.clone(),
                None => frame.clone(),
            }),
        }
    }
}

/// A shared frame.
pub(crate) type FrameRef = Rc<FrameData>;

/// One macro call or include during the expansion.
#[derive(Debug)]
pub(crate) struct FrameData {
    pub kind: FrameKind,
    /// Macro name or included path.
    pub name: String,
    /// The call's or include's start tag.
    pub loc: Loc,
    pub parent: Option<FrameRef>,
}

/// A parsed source file: the document's top-level nodes and which one is the root element.
#[derive(Debug)]
pub(crate) struct ParsedDoc {
    pub children: Vec<NodeRef>,
    pub root: usize,
}

impl ParsedDoc {
    pub fn root(&self) -> Option<&NodeRef> {
        self.children.get(self.root)
    }
}

/// Parse `text` (file number `file`) into nodes. DTDs are refused. Errors carry the byte offset.
/// `stack_ok` is asked before each level of element nesting.
pub(crate) fn parse(
    text: &str,
    file: u32,
    max_depth: usize,
    stack_ok: &dyn Fn() -> bool,
) -> Result<ParsedDoc, (String, usize)> {
    let (body, shift) = match text.strip_prefix('\u{feff}') {
        Some(rest) => (rest, 3),
        None => (text, 0),
    };
    if body.len() > u32::MAX as usize - 8 {
        return Err(("file too large".into(), 0));
    }
    let opts = roxmltree::ParsingOptions {
        allow_dtd: false,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(body, opts).map_err(|e| {
        let pos = e.pos();
        (
            format!("{e}"),
            shift + byte_of(body, pos.row as usize, pos.col as usize),
        )
    })?;
    let conv = Converter {
        text: body,
        file,
        shift: shift as u32,
        max_depth,
        stack_ok,
    };
    let mut children = Vec::new();
    let mut root = 0;
    for child in doc.root().children() {
        if child.is_element() {
            root = children.len();
        }
        if let Some(n) = conv.node(child, 0)? {
            children.push(n);
        }
    }
    Ok(ParsedDoc { children, root })
}

/// Byte offset of 1-based (row, col-in-chars) in `text`.
fn byte_of(text: &str, row: usize, col: usize) -> usize {
    let mut line_start = 0;
    for _ in 1..row {
        match text[line_start..].find('\n') {
            Some(i) => line_start += i + 1,
            None => break,
        }
    }
    text[line_start..]
        .char_indices()
        .nth(col.saturating_sub(1))
        .map_or(text.len(), |(i, _)| line_start + i)
}

struct Converter<'t> {
    text: &'t str,
    file: u32,
    shift: u32,
    max_depth: usize,
    /// Whether there is stack left for one more level (see `Expander::check_stack`).
    stack_ok: &'t dyn Fn() -> bool,
}

impl Converter<'_> {
    fn loc(&self, start: usize, end: usize) -> Loc {
        Loc {
            file: self.file,
            start: start as u32 + self.shift,
            end: end as u32 + self.shift,
        }
    }

    fn src(&self, start: usize, end: usize) -> Src {
        Src {
            loc: self.loc(start, end),
            frame: None,
        }
    }

    fn node(&self, n: roxmltree::Node, depth: usize) -> Result<Option<NodeRef>, (String, usize)> {
        let r = n.range();
        let kind = match n.node_type() {
            roxmltree::NodeType::Element => {
                if !(self.stack_ok)() {
                    return Err(("stack budget exhausted".into(), r.start));
                }
                if depth > self.max_depth {
                    return Err((
                        format!("elements nested deeper than {} levels", self.max_depth),
                        r.start,
                    ));
                }
                return self.element(n, depth).map(Some);
            }
            roxmltree::NodeType::Text => Kind::Text(n.text().unwrap_or_default().into()),
            roxmltree::NodeType::Comment => Kind::Comment(n.text().unwrap_or_default().into()),
            roxmltree::NodeType::PI => match n.pi() {
                Some(pi) => Kind::Pi {
                    target: pi.target.to_string(),
                    data: pi.value.map(str::to_string),
                },
                None => return Ok(None),
            },
            roxmltree::NodeType::Root => return Ok(None),
        };
        Ok(Some(Rc::new(Node {
            kind,
            src: self.src(r.start, r.end),
        })))
    }

    /// A text node holding CDATA sections becomes, as in minidom, text nodes and CDATA nodes (roxmltree
    /// merges them). `raw` is its source text, starting at byte `start`.
    fn split_cdata(&self, raw: &str, start: usize, out: &mut Vec<NodeRef>) {
        let mut pos = 0;
        while pos < raw.len() {
            let (kind, end) = match raw[pos..].strip_prefix("<![CDATA[") {
                Some(rest) => {
                    let len = rest.find("]]>").unwrap_or(rest.len());
                    let data = &rest[..len];
                    (Kind::CData(data.into()), (pos + 9 + len + 3).min(raw.len()))
                }
                None => {
                    let end = raw[pos..].find("<![CDATA[").map_or(raw.len(), |i| pos + i);
                    (Kind::Text(decode_text(&raw[pos..end]).into()), end)
                }
            };
            out.push(Rc::new(Node {
                kind,
                src: self.src(start + pos, start + end),
            }));
            pos = end;
        }
    }

    fn element(&self, n: roxmltree::Node, depth: usize) -> Result<NodeRef, (String, usize)> {
        let r = n.range();
        let tag_text = self.text.get(r.start + 1..).unwrap_or("");
        let name_len = tag_text
            .find(|c: char| c.is_whitespace() || c == '/' || c == '>')
            .unwrap_or(tag_text.len());
        let name = &tag_text[..name_len];
        let mut tag_end = r.start + 1 + name_len;
        for a in n.attributes() {
            tag_end = tag_end.max(a.range().end);
        }
        if let Some(i) = self.text.get(tag_end..).and_then(|t| t.find('>')) {
            tag_end += i + 1;
        }
        let tag_end = tag_end.min(r.end);
        let mut attrs = Vec::with_capacity(n.attributes().len());
        // Namespace declarations made on this element (minidom keeps them as attributes, first).
        let parent = n.parent_element();
        for ns in n.namespaces() {
            let inherited = parent.is_some_and(|p| {
                p.namespaces()
                    .any(|q| q.name() == ns.name() && q.uri() == ns.uri())
            });
            if ns.name() == Some("xml") || inherited {
                continue;
            }
            let name = match ns.name() {
                Some(p) => format!("xmlns:{p}"),
                None => "xmlns".to_string(),
            };
            // Its position: found in the start tag.
            let tag = self.text.get(r.start..tag_end).unwrap_or("");
            let at = tag.find(&name).map_or(r.start, |i| r.start + i);
            attrs.push(Attr {
                value: ns.uri().into(),
                name_loc: self.loc(at, at + name.len()),
                src: self.src(at, at + name.len()),
                name: name.into(),
            });
        }
        for a in n.attributes() {
            let (qn, v) = (a.range_qname(), a.range_value());
            attrs.push(Attr {
                name: self.text.get(qn.clone()).unwrap_or(a.name()).into(),
                value: a.value().into(),
                name_loc: self.loc(qn.start, qn.end),
                src: self.src(v.start, v.end),
            });
        }
        let mut children = Vec::new();
        for c in n.children() {
            // roxmltree merges text and CDATA sections into one node whose range covers only the first
            // piece: the node's source runs to the next sibling or the parent's end tag.
            let raw = if c.is_text() {
                let end = match c.next_sibling() {
                    Some(next) => next.range().start,
                    None => self
                        .text
                        .get(r.clone())
                        .and_then(|t| t.rfind("</"))
                        .map_or(c.range().end, |i| r.start + i),
                };
                self.text.get(c.range().start..end).unwrap_or("")
            } else {
                ""
            };
            if raw.contains("<![CDATA[") {
                self.split_cdata(raw, c.range().start, &mut children);
            } else if let Some(node) = self.node(c, depth + 1)? {
                children.push(node);
            }
        }
        Ok(Rc::new(Node {
            kind: Kind::Element(Element {
                name: name.into(),
                attrs,
                children,
            }),
            src: self.src(r.start, tag_end),
        }))
    }
}

/// A parse failure as an error (location filled by the caller).
pub(crate) fn parse_error(path: &std::path::Path, message: &str) -> XacroError {
    XacroError::new(
        ErrorKind::XmlParse,
        format!("XML parsing error in {}: {message}", path.display()),
    )
}

/// Character data as the XML parser delivers it: line ends normalised, the predefined and numeric entity
/// references decoded (DTDs are refused, so there are no others).
fn decode_text(raw: &str) -> String {
    let raw = raw.replace("\r\n", "\n").replace('\r', "\n");
    let mut out = String::with_capacity(raw.len());
    let mut rest = raw.as_str();
    while let Some(i) = rest.find('&') {
        out.push_str(&rest[..i]);
        let after = &rest[i + 1..];
        let decoded = after.find(';').and_then(|end| {
            let name = &after[..end];
            let c = match name {
                "lt" => '<',
                "gt" => '>',
                "amp" => '&',
                "quot" => '"',
                "apos" => '\'',
                _ => {
                    let code = match name.strip_prefix("#x") {
                        Some(hex) => u32::from_str_radix(hex, 16).ok()?,
                        None => name.strip_prefix('#')?.parse().ok()?,
                    };
                    char::from_u32(code)?
                }
            };
            Some((c, end))
        });
        match decoded {
            Some((c, end)) => {
                out.push(c);
                rest = &after[end + 1..];
            }
            None => {
                out.push('&');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}
