//! The mutations: the fuzz input, read a byte at a time, is a program of edits to the seed's tree.

use crate::tree::{Child, Tree};

/// Most edits applied to one document.
pub const MAX_OPS: usize = 64;

/// Edits that add elements are skipped once the document has this many (quadratic analyses of huge
/// models are known and not what this target looks for; 10 s timeouts still catch a slow small one).
pub const MAX_ELEMENTS: usize = 3000;

/// The fuzz input as a stream of small numbers; reads past the end give 0.
pub struct Bytes<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Bytes<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Bytes { data, pos: 0 }
    }

    pub fn next(&mut self) -> Option<u8> {
        let b = self.data.get(self.pos).copied();
        self.pos += 1;
        b
    }

    pub fn u8(&mut self) -> u8 {
        self.next().unwrap_or(0)
    }

    pub fn u16(&mut self) -> u16 {
        u16::from(self.u8()) | (u16::from(self.u8()) << 8)
    }

    /// An index below `len` (`len` > 0).
    pub fn index(&mut self, len: usize) -> usize {
        usize::from(self.u16()) % len
    }

    pub fn pick<'t, T>(&mut self, items: &'t [T]) -> Option<&'t T> {
        if items.is_empty() {
            None
        } else {
            Some(&items[self.index(items.len())])
        }
    }
}

/// What a format's mutations draw from.
pub struct Dict {
    pub values: &'static [&'static str],
    pub tags: &'static [&'static str],
    pub attrs: &'static [&'static str],
}

/// Tokens of the seed (its main file and included files): every attribute value and text, the names,
/// tags and attribute names.
#[derive(Default)]
pub struct Pools {
    pub values: Vec<String>,
    pub names: Vec<String>,
    pub tags: Vec<String>,
    pub attr_names: Vec<String>,
}

impl Pools {
    pub fn add(&mut self, tree: &Tree) {
        for el in &tree.elements {
            push_unique(&mut self.tags, &el.tag);
            for (k, v) in &el.attrs {
                push_unique(&mut self.attr_names, k);
                push_unique(&mut self.values, v);
                if k == "name" {
                    push_unique(&mut self.names, v);
                }
            }
            for child in &el.children {
                if let Child::Text(t) = child {
                    let t = t.trim();
                    if !t.is_empty() {
                        push_unique(&mut self.values, t);
                        // SDFormat names frames in text too (<parent>, <child>, <name>).
                        if matches!(el.tag.as_str(), "parent" | "child" | "name") {
                            push_unique(&mut self.names, t);
                        }
                    }
                }
            }
        }
    }
}

fn push_unique(v: &mut Vec<String>, s: &str) {
    if !v.iter().any(|x| x == s) {
        v.push(s.to_string());
    }
}

/// Where the `<include>` of a seed's file leads, for the "expand include" edit: the included tree.
pub trait Includes {
    /// The elements that replace `include` (an `<include>` element of `tree`): copies grafted into
    /// `tree`, detached. Empty when the include does not lead to a file of the seed.
    fn expand(&self, tree: &mut Tree, include: usize) -> Vec<usize>;
}

/// The context of the edits.
pub struct Mutator<'c> {
    pub dict: &'c Dict,
    pub pools: &'c Pools,
    pub includes: &'c dyn Includes,
}

impl Mutator<'_> {
    /// Apply the program in `bytes` to `tree`; returns the number of edits made.
    pub fn apply(&self, tree: &mut Tree, bytes: &mut Bytes) -> usize {
        let mut done = 0;
        while done < MAX_OPS {
            let Some(op) = bytes.next() else { break };
            let live = tree.live();
            let grow = live.len() < MAX_ELEMENTS;
            // The element edited; `inner` is the same unless it is the root, then another one (structural
            // edits keep the root: a retagged root is another format, which the other targets cover).
            let pick = usize::from(bytes.u16());
            let el = live[pick % live.len()];
            let inner = (live.len() > 1).then(|| {
                if el == tree.root {
                    live[1 + pick % (live.len() - 1)]
                } else {
                    el
                }
            });
            match op % 16 {
                0 | 1 => {
                    let name = self.attr_name(tree, el, bytes);
                    let value = self.value(tree, el, tree.attr(el, &name), bytes);
                    tree.set_attr(el, &name, value);
                }
                2 => {
                    let attrs = &mut tree.elements[el].attrs;
                    if !attrs.is_empty() {
                        let i = bytes.index(attrs.len());
                        attrs.remove(i);
                    }
                }
                3 => {
                    // Text: SDFormat's values (<pose>, <parent>, <uri>, <mass>...); for an element with
                    // children, that of a leaf below it.
                    let leaf = leaf_below(tree, el, bytes);
                    let current = tree.text(leaf);
                    let value = self.value(tree, leaf, Some(current.trim()), bytes);
                    tree.set_text(leaf, value);
                }
                4 => self.tweak(tree, el, bytes),
                5 => {
                    if let Some(e) = inner {
                        tree.detach(e);
                    }
                }
                6 => {
                    if let Some(e) = inner.filter(|&e| grow && tree.subtree_size(e) < MAX_ELEMENTS / 2)
                    {
                        let copy = tree.clone_subtree(e);
                        let (parent, pos) = tree.detach(e).expect("inner has a parent");
                        tree.insert(parent, pos, e);
                        tree.insert(parent, pos + 1 + usize::from(bytes.u8() % 2), copy);
                    }
                }
                7 => {
                    // A copy of `inner` under any element, often one of its own descendants.
                    if let Some(e) = inner.filter(|&e| grow && tree.subtree_size(e) < MAX_ELEMENTS / 2)
                    {
                        let target = if bytes.u8() % 2 == 0 {
                            let below = subtree(tree, e);
                            below[bytes.index(below.len())]
                        } else {
                            live[bytes.index(live.len())]
                        };
                        let copy = tree.clone_subtree(e);
                        let pos = bytes.index(tree.elements[target].children.len() + 1);
                        tree.insert(target, pos, copy);
                    }
                }
                8 | 9 => {
                    if let Some(e) = inner {
                        let tag = if op % 16 == 8 {
                            bytes.pick(self.dict.tags).map(|t| t.to_string())
                        } else {
                            bytes.pick(&self.pools.tags).cloned()
                        };
                        if let Some(tag) = tag {
                            tree.elements[e].tag = tag;
                        }
                    }
                }
                10 => {
                    // Move `inner` under another element. When that one is inside `inner`'s subtree,
                    // it takes `inner`'s place and `inner` (with the rest of its subtree) goes under it.
                    if let Some(e) = inner {
                        let target = if bytes.u8() % 2 == 0 {
                            let below = subtree(tree, e);
                            below[bytes.index(below.len())]
                        } else {
                            live[bytes.index(live.len())]
                        };
                        let pos = usize::from(bytes.u8());
                        if target == e {
                        } else if tree.contains(e, target) {
                            let (parent, at) = tree.detach(e).expect("inner has a parent");
                            tree.detach(target);
                            tree.insert(parent, at, target);
                            tree.insert(target, pos, e);
                        } else {
                            tree.detach(e);
                            tree.insert(target, pos, e);
                        }
                    }
                }
                11 => {
                    if let Some(e) = inner {
                        let (parent, _) = tree.detach(e).expect("inner has a parent");
                        let pos = bytes.index(tree.elements[parent].children.len() + 1);
                        tree.insert(parent, pos, e);
                    }
                }
                12 => {
                    // Paste an included file's contents in place of its <include> (the first include
                    // at or after the element picked).
                    let includes: Vec<usize> =
                        live.iter().copied().filter(|&i| tree.elements[i].tag == "include").collect();
                    if grow && !includes.is_empty() {
                        let at = includes
                            .iter()
                            .copied()
                            .find(|&i| i >= el)
                            .unwrap_or(includes[0]);
                        let pasted = self.includes.expand(tree, at);
                        if !pasted.is_empty() {
                            if let Some((parent, pos)) = tree.detach(at) {
                                for (k, p) in pasted.into_iter().enumerate() {
                                    tree.insert(parent, pos + k, p);
                                }
                            }
                        }
                    }
                }
                13 => {
                    // Copy one attribute of another element (a name, a class, a pose...).
                    let other = live[bytes.index(live.len())];
                    if let Some((k, v)) = bytes.pick(&tree.elements[other].attrs).cloned() {
                        tree.set_attr(el, &k, v);
                    }
                }
                14 => {
                    // The name of an ancestor, a sibling or another element of the same tag: the
                    // repeated names of issue 43 item 6.
                    let candidates: Vec<String> = match bytes.u8() % 3 {
                        0 => tree
                            .ancestors(el)
                            .into_iter()
                            .filter_map(|a| tree.attr(a, "name").map(str::to_string))
                            .collect(),
                        1 => tree
                            .parent[el]
                            .map(|p| tree.element_children(p))
                            .unwrap_or_default()
                            .into_iter()
                            .filter_map(|s| tree.attr(s, "name").map(str::to_string))
                            .collect(),
                        _ => live
                            .iter()
                            .filter(|&&o| tree.elements[o].tag == tree.elements[el].tag)
                            .filter_map(|&o| tree.attr(o, "name").map(str::to_string))
                            .collect(),
                    };
                    if let Some(name) = bytes.pick(&candidates).cloned() {
                        tree.set_attr(el, "name", name);
                    }
                }
                _ => {
                    if grow {
                        if let Some(tag) = bytes.pick(self.dict.tags) {
                            let new = tree.create(tag);
                            if bytes.u8() % 2 == 0 {
                                let name = self.attr_name(tree, new, bytes);
                                let value = self.value(tree, el, None, bytes);
                                tree.set_attr(new, &name, value);
                            }
                            let pos = bytes.index(tree.elements[el].children.len() + 1);
                            tree.insert(el, pos, new);
                        }
                    }
                }
            }
            done += 1;
        }
        done
    }

    /// An attribute name for `el`: one it has, one of the document's, or one of the format's.
    fn attr_name(&self, tree: &Tree, el: usize, bytes: &mut Bytes) -> String {
        let attrs = &tree.elements[el].attrs;
        match bytes.u8() % 4 {
            0 | 1 if !attrs.is_empty() => attrs[bytes.index(attrs.len())].0.clone(),
            2 => bytes
                .pick(&self.pools.attr_names)
                .cloned()
                .unwrap_or_else(|| "name".to_string()),
            _ => bytes.pick(self.dict.attrs).unwrap_or(&"name").to_string(),
        }
    }

    /// A value for an attribute or text of `el` whose value is `current`.
    fn value(&self, tree: &Tree, el: usize, current: Option<&str>, bytes: &mut Bytes) -> String {
        let word = |bytes: &mut Bytes, list: &[&str]| bytes.pick(list).unwrap_or(&"").to_string();
        match bytes.u8() % 10 {
            0 => word(bytes, crate::dict::NUMBERS),
            1 => word(bytes, crate::dict::COMMON),
            2 => word(bytes, self.dict.values),
            3 | 4 => bytes.pick(&self.pools.values).cloned().unwrap_or_default(),
            5 => bytes.pick(&self.pools.names).cloned().unwrap_or_default(),
            6 => {
                // An ancestor's name (or, failing that, any name).
                let names: Vec<String> = tree
                    .ancestors(el)
                    .into_iter()
                    .filter_map(|a| tree.attr(a, "name").map(str::to_string))
                    .collect();
                bytes
                    .pick(&names)
                    .or_else(|| bytes.pick(&self.pools.names))
                    .cloned()
                    .unwrap_or_default()
            }
            7 => {
                // A vector of numbers.
                let n = 1 + usize::from(bytes.u8() % 13);
                let mut tokens = Vec::with_capacity(n);
                for _ in 0..n {
                    tokens.push(word(bytes, crate::dict::NUMBERS));
                }
                tokens.join(" ")
            }
            8 => tweak_tokens(current.unwrap_or(""), bytes),
            _ => {
                // Two tokens together: a scoped SDFormat name, or a value with a number after it.
                let a = bytes.pick(&self.pools.names).cloned().unwrap_or_default();
                let b = bytes.pick(&self.pools.names).cloned().unwrap_or_default();
                match bytes.u8() % 3 {
                    0 => format!("{a}::{b}"),
                    1 => format!("{a} {}", word(bytes, crate::dict::NUMBERS)),
                    _ => format!("{a}{b}"),
                }
            }
        }
    }

    /// Change one number of an attribute's (or the text's) token list.
    fn tweak(&self, tree: &mut Tree, el: usize, bytes: &mut Bytes) {
        let attrs = tree.elements[el].attrs.len();
        if attrs > 0 && bytes.u8() % 4 != 0 {
            let i = bytes.index(attrs);
            let new = tweak_tokens(&tree.elements[el].attrs[i].1, bytes);
            tree.elements[el].attrs[i].1 = new;
        } else {
            let leaf = leaf_below(tree, el, bytes);
            let new = tweak_tokens(tree.text(leaf).trim(), bytes);
            tree.set_text(leaf, new);
        }
    }
}

/// `value`'s whitespace-separated tokens with one edit: a token replaced, negated, scaled, removed or
/// duplicated, or one appended.
fn tweak_tokens(value: &str, bytes: &mut Bytes) -> String {
    let mut tokens: Vec<String> = value.split_whitespace().map(str::to_string).collect();
    let op = bytes.u8() % 7;
    if tokens.is_empty() || op == 6 {
        tokens.push(
            bytes
                .pick(crate::dict::NUMBERS)
                .unwrap_or(&"0")
                .to_string(),
        );
        return tokens.join(" ");
    }
    let i = bytes.index(tokens.len());
    match op {
        0 => tokens[i] = bytes.pick(crate::dict::NUMBERS).unwrap_or(&"0").to_string(),
        1 => {
            tokens[i] = match tokens[i].strip_prefix('-') {
                Some(rest) => rest.to_string(),
                None => format!("-{}", tokens[i]),
            }
        }
        2 => {
            let factor = [1e-9, 1e-3, 0.5, 2.0, 10.0, 1e3, 1e9, 1e300][usize::from(bytes.u8() % 8)];
            if let Ok(x) = tokens[i].parse::<f64>() {
                tokens[i] = format!("{}", x * factor);
            }
        }
        3 => {
            tokens.remove(i);
        }
        4 => {
            let t = tokens[i].clone();
            tokens.insert(i, t);
        }
        _ => {
            // Every token the same special number.
            let n = bytes.pick(crate::dict::NUMBERS).unwrap_or(&"nan").to_string();
            for t in &mut tokens {
                *t = n.clone();
            }
        }
    }
    tokens.join(" ")
}

/// The elements of `id`'s subtree (itself first).
fn subtree(tree: &Tree, id: usize) -> Vec<usize> {
    let mut out = Vec::new();
    let mut stack = vec![id];
    while let Some(e) = stack.pop() {
        out.push(e);
        let children = tree.element_children(e);
        stack.extend(children.into_iter().rev());
    }
    out
}

/// An element without element children at or below `id`.
fn leaf_below(tree: &Tree, id: usize, bytes: &mut Bytes) -> usize {
    let leaves: Vec<usize> = subtree(tree, id)
        .into_iter()
        .filter(|&e| tree.element_children(e).is_empty())
        .collect();
    bytes.pick(&leaves).copied().unwrap_or(id)
}
