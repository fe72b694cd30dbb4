//! A mutable XML tree: elements in an arena (ids stay valid when elements move or are detached), read with
//! roxmltree and written back by a small serializer. Comments, processing instructions and namespaces are
//! dropped (the seeds use none that matter); text is kept, whitespace too, so line numbers stay close to
//! the seed's.

/// One element.
#[derive(Clone, Debug)]
pub struct Element {
    pub tag: String,
    pub attrs: Vec<(String, String)>,
    pub children: Vec<Child>,
}

/// A child of an element.
#[derive(Clone, Debug)]
pub enum Child {
    Element(usize),
    Text(String),
}

/// Elements in an arena; `parent[id]` is `None` for the root and for detached elements.
#[derive(Clone, Debug)]
pub struct Tree {
    pub elements: Vec<Element>,
    pub parent: Vec<Option<usize>>,
    pub root: usize,
}

impl Tree {
    /// The element tree of `text` (None when roxmltree refuses it).
    pub fn parse(text: &str) -> Option<Tree> {
        let options = roxmltree::ParsingOptions {
            allow_dtd: true,
            ..roxmltree::ParsingOptions::default()
        };
        let doc = roxmltree::Document::parse_with_options(text, options).ok()?;
        let mut tree = Tree {
            elements: Vec::new(),
            parent: Vec::new(),
            root: 0,
        };
        // Depth-first with an explicit stack: a node is appended to its parent when popped, and a parent's
        // children are pushed in reverse, so every parent receives its children in document order.
        let mut stack = vec![(doc.root_element(), None::<usize>)];
        while let Some((node, parent)) = stack.pop() {
            if node.is_text() {
                if let Some(p) = parent {
                    let text = node.text().unwrap_or("").to_string();
                    tree.elements[p].children.push(Child::Text(text));
                }
                continue;
            }
            let id = tree.new_element(
                node.tag_name().name().to_string(),
                node.attributes()
                    .map(|a| (a.name().to_string(), a.value().to_string()))
                    .collect(),
            );
            tree.parent[id] = parent;
            if let Some(p) = parent {
                tree.elements[p].children.push(Child::Element(id));
            }
            let children: Vec<_> = node
                .children()
                .filter(|c| c.is_element() || c.is_text())
                .collect();
            stack.extend(children.into_iter().rev().map(|c| (c, Some(id))));
        }
        Some(tree)
    }

    fn new_element(&mut self, tag: String, attrs: Vec<(String, String)>) -> usize {
        self.elements.push(Element {
            tag,
            attrs,
            children: Vec::new(),
        });
        self.parent.push(None);
        self.elements.len() - 1
    }

    /// A new detached element.
    pub fn create(&mut self, tag: &str) -> usize {
        self.new_element(tag.to_string(), Vec::new())
    }

    /// The elements reachable from the root, in document order.
    pub fn live(&self) -> Vec<usize> {
        let mut out = Vec::new();
        let mut stack = vec![self.root];
        while let Some(id) = stack.pop() {
            out.push(id);
            for child in self.elements[id].children.iter().rev() {
                if let Child::Element(c) = child {
                    stack.push(*c);
                }
            }
        }
        out
    }

    /// The element children of `id`.
    pub fn element_children(&self, id: usize) -> Vec<usize> {
        self.elements[id]
            .children
            .iter()
            .filter_map(|c| match c {
                Child::Element(e) => Some(*e),
                Child::Text(_) => None,
            })
            .collect()
    }

    /// `id`'s ancestors, nearest first.
    pub fn ancestors(&self, id: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut at = self.parent[id];
        while let Some(p) = at {
            out.push(p);
            at = self.parent[p];
        }
        out
    }

    /// Whether `a` is `b` or one of its ancestors.
    pub fn contains(&self, a: usize, b: usize) -> bool {
        a == b || self.ancestors(b).contains(&a)
    }

    /// Remove `id` from its parent's children (it keeps its subtree). Returns its former position.
    pub fn detach(&mut self, id: usize) -> Option<(usize, usize)> {
        let parent = self.parent[id]?;
        let pos = self.elements[parent]
            .children
            .iter()
            .position(|c| matches!(c, Child::Element(e) if *e == id))?;
        self.elements[parent].children.remove(pos);
        self.parent[id] = None;
        Some((parent, pos))
    }

    /// Insert the detached `id` as child number `pos` (clamped) of `parent`.
    pub fn insert(&mut self, parent: usize, pos: usize, id: usize) {
        let children = &mut self.elements[parent].children;
        let pos = pos.min(children.len());
        children.insert(pos, Child::Element(id));
        self.parent[id] = Some(parent);
    }

    /// A detached deep copy of `id`'s subtree (from `source`, which may be this tree or another).
    pub fn graft(&mut self, source: &Tree, id: usize) -> usize {
        let top = self.new_element(
            source.elements[id].tag.clone(),
            source.elements[id].attrs.clone(),
        );
        let mut stack = vec![(id, top)];
        while let Some((from, to)) = stack.pop() {
            for child in &source.elements[from].children {
                match child {
                    Child::Text(t) => self.elements[to].children.push(Child::Text(t.clone())),
                    Child::Element(c) => {
                        let copy = self.new_element(
                            source.elements[*c].tag.clone(),
                            source.elements[*c].attrs.clone(),
                        );
                        self.elements[to].children.push(Child::Element(copy));
                        self.parent[copy] = Some(to);
                        stack.push((*c, copy));
                    }
                }
            }
        }
        top
    }

    /// A detached deep copy of `id`'s subtree.
    pub fn clone_subtree(&mut self, id: usize) -> usize {
        let top = self.new_element(self.elements[id].tag.clone(), self.elements[id].attrs.clone());
        let mut stack = vec![(id, top)];
        while let Some((from, to)) = stack.pop() {
            for i in 0..self.elements[from].children.len() {
                match self.elements[from].children[i].clone() {
                    Child::Text(t) => self.elements[to].children.push(Child::Text(t)),
                    Child::Element(c) => {
                        let copy = self
                            .new_element(self.elements[c].tag.clone(), self.elements[c].attrs.clone());
                        self.elements[to].children.push(Child::Element(copy));
                        self.parent[copy] = Some(to);
                        stack.push((c, copy));
                    }
                }
            }
        }
        top
    }

    /// Number of elements in `id`'s subtree.
    pub fn subtree_size(&self, id: usize) -> usize {
        let mut n = 0;
        let mut stack = vec![id];
        while let Some(e) = stack.pop() {
            n += 1;
            stack.extend(self.element_children(e));
        }
        n
    }

    /// The text directly inside `id` (its text children, concatenated).
    pub fn text(&self, id: usize) -> String {
        self.elements[id]
            .children
            .iter()
            .filter_map(|c| match c {
                Child::Text(t) => Some(t.as_str()),
                Child::Element(_) => None,
            })
            .collect()
    }

    /// Replace the text directly inside `id` with `text` (element children stay, after it).
    pub fn set_text(&mut self, id: usize, text: String) {
        let children = &mut self.elements[id].children;
        children.retain(|c| matches!(c, Child::Element(_)));
        children.insert(0, Child::Text(text));
    }

    pub fn attr(&self, id: usize, name: &str) -> Option<&str> {
        self.elements[id]
            .attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    pub fn set_attr(&mut self, id: usize, name: &str, value: String) {
        let attrs = &mut self.elements[id].attrs;
        match attrs.iter_mut().find(|(k, _)| k == name) {
            Some((_, v)) => *v = value,
            None => attrs.push((name.to_string(), value)),
        }
    }

    /// The document as XML text.
    pub fn serialize(&self) -> String {
        enum Step<'t> {
            Open(usize),
            Text(&'t str),
            Close(usize),
        }
        let mut out = String::with_capacity(4096);
        out.push_str("<?xml version=\"1.0\"?>\n");
        let mut stack = vec![Step::Open(self.root)];
        while let Some(step) = stack.pop() {
            match step {
                Step::Open(id) => {
                    let el = &self.elements[id];
                    out.push('<');
                    out.push_str(&el.tag);
                    for (k, v) in &el.attrs {
                        out.push(' ');
                        out.push_str(k);
                        out.push_str("=\"");
                        escape(v, true, &mut out);
                        out.push('"');
                    }
                    if el.children.is_empty() {
                        out.push_str("/>");
                        continue;
                    }
                    out.push('>');
                    stack.push(Step::Close(id));
                    for child in el.children.iter().rev() {
                        stack.push(match child {
                            Child::Element(c) => Step::Open(*c),
                            Child::Text(t) => Step::Text(t),
                        });
                    }
                }
                Step::Text(t) => escape(t, false, &mut out),
                Step::Close(id) => {
                    out.push_str("</");
                    out.push_str(&self.elements[id].tag);
                    out.push('>');
                }
            }
        }
        out.push('\n');
        out
    }
}

/// XML-escape `s` into `out` (in an attribute value, also quotes and whitespace that normalisation
/// would fold).
fn escape(s: &str, attribute: bool, out: &mut String) {
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' if attribute => out.push_str("&quot;"),
            '\t' if attribute => out.push_str("&#9;"),
            '\n' if attribute => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            c => out.push(c),
        }
    }
}
