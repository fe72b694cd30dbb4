//! xacro's own names in the editor: properties (`<xacro:property name>`, a macro's `params`, used as
//! `${name}`), arguments (`<xacro:arg name>`, used as `$(arg name)`) and macros (`<xacro:macro name>`,
//! called as `<xacro:name …>`): what the cursor is on, where each is defined and used across the robot's
//! files, and what to complete. Names are matched by spelling across the files (xacro's scopes — a macro
//! parameter shadowing a property — are not modelled); a definition inside a macro body counts like any other.

use std::ops::Range;

use super::navigation::File;
use super::xml::{Element, Scan};

/// Which kind of xacro name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum XacroKind {
    /// A property or a macro parameter: `${name}`.
    Property,
    /// An argument: `$(arg name)`.
    Arg,
    /// A macro: `<xacro:name>`.
    Macro,
}

/// The elements of the xacro namespace that are directives, not macro calls.
const DIRECTIVES: [&str; 12] = [
    "property",
    "macro",
    "include",
    "if",
    "unless",
    "arg",
    "insert_block",
    "element",
    "attribute",
    "call",
    "eval-comments",
    "load_yaml",
];

/// The xacro name under byte `offset` of `text`: kind, name and its bytes.
pub fn at(text: &str, scan: &Scan, offset: usize) -> Option<(XacroKind, String, Range<usize>)> {
    let (index, attribute) = scan.at(offset)?;
    let element = &scan.elements[index];
    let Some(attribute) = attribute else {
        // On the tag name of a macro call.
        let (name, span) = called_macro(element)?;
        return span
            .contains(&offset)
            .then_some((XacroKind::Macro, name, span));
    };
    if attribute.name == "name" {
        if let Some(kind) = defined_kind(element) {
            return Some((kind, attribute.value.clone(), attribute.value_span.clone()));
        }
    }
    if element.name == "xacro:macro" && attribute.name == "params" {
        return parameters(&attribute.value, attribute.value_span.start)
            .find(|(_, span)| span.start <= offset && offset <= span.end)
            .map(|(name, span)| (XacroKind::Property, name, span));
    }
    uses(text, attribute.value_span.clone())
        .find(|(_, _, span)| span.start <= offset && offset <= span.end)
}

/// Every place of `file` naming the `kind` name `name`: (bytes of the name, whether it defines it).
pub fn occurrences(file: &File, kind: XacroKind, name: &str) -> Vec<(Range<usize>, bool)> {
    let mut found = Vec::new();
    for element in &file.scan.elements {
        if let (Some(defined), Some(attribute)) = (defined_kind(element), element.attribute("name"))
        {
            if defined == kind && attribute.value == name {
                found.push((attribute.value_span.clone(), true));
            }
        }
        if kind == XacroKind::Property && element.name == "xacro:macro" {
            if let Some(params) = element.attribute("params") {
                found.extend(
                    parameters(&params.value, params.value_span.start)
                        .filter(|(param, _)| param == name)
                        .map(|(_, span)| (span, true)),
                );
            }
        }
        if kind == XacroKind::Macro {
            if let Some((called, span)) = called_macro(element) {
                if called == name {
                    found.push((span, false));
                }
            }
        }
        for attribute in &element.attributes {
            found.extend(
                uses(&file.text, attribute.value_span.clone())
                    .filter(|(k, n, _)| *k == kind && n == name)
                    .map(|(_, _, span)| (span, false)),
            );
        }
    }
    found
}

/// What a definition of `kind` `name` says, for a hover: `value="…"`, a parameter's macro, a macro's
/// parameters, an argument's default.
pub fn describe(files: &[File], kind: XacroKind, name: &str) -> Option<String> {
    for file in files {
        for element in &file.scan.elements {
            let defines = defined_kind(element) == Some(kind)
                && element.attribute("name").is_some_and(|a| a.value == name);
            let place = |span: &Range<usize>| {
                let position = file.index.range(&file.text, span.start, span.end).start;
                let file_name = file
                    .uri
                    .path_segments()
                    .and_then(|mut s| s.next_back().map(str::to_string))
                    .unwrap_or_default();
                format!("defined at {file_name}:{}", position.line + 1)
            };
            if defines {
                let attribute = |key: &str| element.attribute(key).map(|a| a.value.as_str());
                let head = match kind {
                    XacroKind::Property => format!(
                        "**xacro property `{name}`** = `{}`",
                        attribute("value").unwrap_or("(its content)")
                    ),
                    XacroKind::Arg => format!(
                        "**xacro arg `{name}`**, default `{}`",
                        attribute("default").unwrap_or("(none: must be given)")
                    ),
                    XacroKind::Macro => format!(
                        "**xacro macro `{name}`**({})",
                        attribute("params").unwrap_or("")
                    ),
                };
                return Some(format!("{head}  \n{}", place(&element.tag)));
            }
            if kind == XacroKind::Property && element.name == "xacro:macro" {
                let Some(params) = element.attribute("params") else {
                    continue;
                };
                let Some((_, span)) = parameters(&params.value, params.value_span.start)
                    .find(|(param, _)| param == name)
                else {
                    continue;
                };
                let token = &file.text[span.start..params.value_span.end];
                let token = token.split_whitespace().next().unwrap_or(name);
                let macro_name = element.attribute("name").map_or("", |a| a.value.as_str());
                return Some(format!(
                    "**parameter `{token}`** of xacro macro `{macro_name}`  \n{}",
                    place(&span)
                ));
            }
        }
    }
    None
}

/// The names of `kind` defined in `files`, sorted and once each.
pub fn defined_names(files: &[File], kind: XacroKind) -> Vec<String> {
    let mut names: Vec<String> = files
        .iter()
        .flat_map(|file| {
            file.scan.elements.iter().flat_map(move |element| {
                let own = (defined_kind(element) == Some(kind))
                    .then(|| element.attribute("name").map(|a| a.value.clone()))
                    .flatten();
                let params: Vec<String> = match (kind, element.attribute("params")) {
                    (XacroKind::Property, Some(params)) if element.name == "xacro:macro" => {
                        parameters(&params.value, 0).map(|(n, _)| n).collect()
                    }
                    _ => Vec::new(),
                };
                own.into_iter().chain(params)
            })
        })
        .filter(|n| !n.is_empty())
        .collect();
    names.sort();
    names.dedup();
    names
}

/// What to complete at byte `offset` of `file`: property names after an unclosed `${`, argument names after
/// `$(arg `, macro names in a tag name after `<xacro:`.
pub fn completion_kind(file: &File, offset: usize) -> Option<XacroKind> {
    let (index, attribute) = file.scan.at(offset)?;
    let element = &file.scan.elements[index];
    let Some(attribute) = attribute else {
        let typed = file.text.get(element.tag.start..offset)?;
        let name = typed.strip_prefix("<xacro:")?;
        return name
            .chars()
            .all(|c| c.is_alphanumeric() || c == '_' || c == '-' || c == '.')
            .then_some(XacroKind::Macro);
    };
    let before = file.text.get(attribute.value_span.start..offset)?;
    if let Some(open) = before.rfind("${") {
        if !before[open..].contains('}') {
            return Some(XacroKind::Property);
        }
    }
    if let Some(open) = before.rfind("$(arg ") {
        if !before[open..].contains(')') {
            return Some(XacroKind::Arg);
        }
    }
    None
}

/// The kind of name `element`'s `name` attribute defines, if a xacro definition.
fn defined_kind(element: &Element) -> Option<XacroKind> {
    match element.name.as_str() {
        "xacro:property" => Some(XacroKind::Property),
        "xacro:arg" => Some(XacroKind::Arg),
        "xacro:macro" => Some(XacroKind::Macro),
        _ => None,
    }
}

/// The macro `element` calls (`<xacro:wheel …>`) and the bytes of its name in the tag.
fn called_macro(element: &Element) -> Option<(String, Range<usize>)> {
    let name = element.name.strip_prefix("xacro:")?;
    if name.is_empty() || DIRECTIVES.contains(&name) {
        return None;
    }
    let start = element.tag.start + 1 + "xacro:".len();
    Some((name.to_string(), start..start + name.len()))
}

/// The property parameters of a macro's `params` value starting at byte `base` (`a b:=1 c:=^|2`; block
/// parameters, `*block` and `**blocks`, are inserted with `<xacro:insert_block>`, not used as `${}`), each
/// with the bytes of its name.
fn parameters(value: &str, base: usize) -> impl Iterator<Item = (String, Range<usize>)> + '_ {
    let mut at = 0;
    value.split(char::is_whitespace).filter_map(move |token| {
        let start = at;
        at += token.len() + 1;
        let name = token.split(":=").next().unwrap_or("").split('=').next()?;
        (!name.is_empty() && !name.starts_with('*')).then(|| {
            let from = base + start;
            (name.to_string(), from..from + name.len())
        })
    })
}

/// The property and argument uses in the attribute value at `span` of `text`: identifiers inside `${…}`
/// (not function names: followed by `(`; not attributes: after `.`) and the names of `$(arg …)`.
fn uses(
    text: &str,
    span: Range<usize>,
) -> impl Iterator<Item = (XacroKind, String, Range<usize>)> + '_ {
    let value = text.get(span.clone()).unwrap_or("");
    let base = span.start;
    let mut found = Vec::new();
    let mut rest = 0;
    while let Some(open) = value[rest..].find("${").map(|i| rest + i) {
        let body_start = open + 2;
        let body_end = value[body_start..]
            .find('}')
            .map_or(value.len(), |i| body_start + i);
        let body = &value[body_start..body_end];
        let bytes = body.as_bytes();
        let mut i = 0;
        while i < bytes.len() {
            let c = bytes[i];
            if c.is_ascii_alphabetic() || c == b'_' {
                let start = i;
                while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                    i += 1;
                }
                let after_dot = start > 0 && bytes[start - 1] == b'.';
                let called = body[i..].trim_start().starts_with('(');
                let word = &body[start..i];
                let keyword = matches!(
                    word,
                    "and" | "or" | "not" | "in" | "if" | "else" | "True" | "False" | "None"
                );
                if !after_dot && !called && !keyword {
                    let from = base + body_start + start;
                    found.push((
                        XacroKind::Property,
                        word.to_string(),
                        from..from + word.len(),
                    ));
                }
            } else if c.is_ascii_digit() {
                while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'.') {
                    i += 1;
                }
            } else if c == b'\'' || c == b'"' {
                // A string literal: its words are not names.
                i += 1;
                while i < bytes.len() && bytes[i] != c {
                    i += 1;
                }
                i += 1;
            } else {
                i += 1;
            }
        }
        rest = body_end.min(value.len());
        if rest == value.len() {
            break;
        }
    }
    let mut rest = 0;
    while let Some(open) = value[rest..].find("$(arg ").map(|i| rest + i) {
        let name_start = open + "$(arg ".len();
        let name_start =
            name_start + (value[name_start..].len() - value[name_start..].trim_start().len());
        let name_end = value[name_start..]
            .find(|c: char| c == ')' || c.is_whitespace())
            .map_or(value.len(), |i| name_start + i);
        let name = &value[name_start..name_end];
        if !name.is_empty() {
            let from = base + name_start;
            found.push((XacroKind::Arg, name.to_string(), from..from + name.len()));
        }
        rest = name_end;
    }
    found.into_iter()
}

#[cfg(test)]
mod tests {
    use super::*;
    use lsp_types::Url;

    const TEXT: &str = "<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n\
        <xacro:property name=\"width\" value=\"0.2\"/>\n\
        <xacro:arg name=\"prefix\" default=\"r_\"/>\n\
        <xacro:macro name=\"wheel\" params=\"side reflect:=1 *origin\">\n\
        <link name=\"$(arg prefix)${side}_wheel\"><visual><geometry>\
        <box size=\"${width*reflect} ${sin(width)} 'width'\"/></geometry></visual></link>\n\
        </xacro:macro>\n\
        <xacro:wheel side=\"left\"><origin/></xacro:wheel>\n</robot>";

    fn file() -> File {
        File::new(
            Url::parse("file:///w.urdf.xacro").expect("uri"),
            TEXT.into(),
        )
    }

    fn at_needle(needle: &str, skip: usize) -> Option<(XacroKind, String)> {
        let file = file();
        let offset = TEXT.find(needle).expect("needle") + skip;
        at(&file.text, &file.scan, offset).map(|(kind, name, span)| {
            assert_eq!(&TEXT[span], name);
            (kind, name)
        })
    }

    #[test]
    fn names_under_the_cursor() {
        let property = Some((XacroKind::Property, "width".to_string()));
        assert_eq!(at_needle("width*", 1), property);
        assert_eq!(at_needle("name=\"width\"", 7), property);
        assert_eq!(at_needle("sin(", 1), None, "a function is not a property");
        assert_eq!(at_needle("'width'", 2), None, "a string is not a name");
        assert_eq!(
            at_needle("reflect:=1", 2),
            Some((XacroKind::Property, "reflect".into()))
        );
        assert_eq!(
            at_needle("prefix)", 1),
            Some((XacroKind::Arg, "prefix".into()))
        );
        assert_eq!(
            at_needle("wheel side", 1),
            Some((XacroKind::Macro, "wheel".into()))
        );
        assert_eq!(
            at_needle("xacro:macro name", 1),
            None,
            "a directive is not a call"
        );
    }

    #[test]
    fn definitions_uses_descriptions_and_completions() {
        let file = file();
        let width = occurrences(&file, XacroKind::Property, "width");
        assert_eq!(width.iter().filter(|(_, d)| *d).count(), 1);
        assert_eq!(width.len(), 3, "{width:?}");
        let side = occurrences(&file, XacroKind::Property, "side");
        assert_eq!(side.len(), 2, "the parameter and ${{side}}");
        assert_eq!(occurrences(&file, XacroKind::Macro, "wheel").len(), 2);
        assert_eq!(occurrences(&file, XacroKind::Arg, "prefix").len(), 2);
        let files = [file];
        assert_eq!(
            describe(&files, XacroKind::Property, "width").as_deref(),
            Some("**xacro property `width`** = `0.2`  \ndefined at w.urdf.xacro:2")
        );
        assert!(describe(&files, XacroKind::Property, "reflect")
            .is_some_and(|d| d.starts_with("**parameter `reflect:=1`** of xacro macro `wheel`")));
        assert_eq!(
            defined_names(&files, XacroKind::Property),
            ["reflect", "side", "width"]
        );
        let typed = "<robot><xacro:property name=\"w\" value=\"1\"/><box size=\"${w\"/><xacro:wh";
        let typing = File::new(Url::parse("file:///t.xacro").expect("uri"), typed.into());
        let offset = typed.find("${w").expect("${") + 3;
        assert_eq!(completion_kind(&typing, offset), Some(XacroKind::Property));
        assert_eq!(
            completion_kind(&typing, typed.len()),
            Some(XacroKind::Macro)
        );
    }
}
