//! Completion: link names in `parent`/`child`/`reference`, joint names in `mimic`, joint types, xacro
//! property and argument names in `${…}`/`$(arg …)`, macro names after `<xacro:`, and rule codes in
//! suppression comments, from the robot's files as the editor has them.

use std::collections::BTreeSet;

use lsp_types::{CompletionItem, CompletionItemKind};
use urdf_validator::diagnostics::rules;

use super::here::{self, Kind};
use super::navigation::File;
use super::xacro_names::{self, XacroKind};

/// The joint types URDF knows.
const JOINT_TYPES: [&str; 6] = [
    "revolute",
    "continuous",
    "prismatic",
    "fixed",
    "floating",
    "planar",
];

/// The completions at byte `offset` of `file` (the document being typed in), with names from `files`
/// (the robot's files, that one included).
pub fn items(file: &File, offset: usize, files: &[File]) -> Vec<CompletionItem> {
    if let Some((body, _)) = here::suppression_comment_at(&file.text, offset) {
        return if body.contains("ignore") {
            rule_items()
        } else {
            Vec::new()
        };
    }
    if let Some(kind) = xacro_names::completion_kind(file, offset) {
        let item_kind = match kind {
            XacroKind::Macro => CompletionItemKind::FUNCTION,
            XacroKind::Property | XacroKind::Arg => CompletionItemKind::VARIABLE,
        };
        return xacro_names::defined_names(files, kind)
            .iter()
            .map(|name| item(name, item_kind, xacro_names::describe(files, kind, name)))
            .collect();
    }
    let Some((index, Some(attribute))) = file.scan.at(offset) else {
        return Vec::new();
    };
    let element = &file.scan.elements[index];
    if element.name == "joint" && attribute.name == "type" {
        return JOINT_TYPES
            .iter()
            .map(|t| item(t, CompletionItemKind::ENUM_MEMBER, None))
            .collect();
    }
    let kind = match here::reference_kind(element, &attribute.name) {
        Some(kind) if !here::is_definition(&file.scan, element, attribute) => kind,
        _ => return Vec::new(),
    };
    let names: BTreeSet<&str> = files
        .iter()
        .flat_map(|f| {
            f.scan.elements.iter().filter_map(move |e| {
                let name = e.attribute("name")?;
                let defines = here::is_definition(&f.scan, e, name)
                    && here::reference_kind(e, "name") == Some(kind);
                defines.then_some(name.value.as_str())
            })
        })
        .filter(|n| !n.is_empty())
        .collect();
    let item_kind = match kind {
        Kind::Link => CompletionItemKind::CLASS,
        Kind::Joint => CompletionItemKind::FIELD,
        Kind::Material => CompletionItemKind::COLOR,
    };
    names
        .into_iter()
        .map(|name| item(name, item_kind, None))
        .collect()
}

/// Every rule code, with its name and what it checks.
fn rule_items() -> Vec<CompletionItem> {
    rules::ALL
        .iter()
        .map(|rule| {
            item(
                rule.code,
                CompletionItemKind::CONSTANT,
                Some(format!("{}: {}", rule.name, rule.what)),
            )
        })
        .collect()
}

fn item(label: &str, kind: CompletionItemKind, detail: Option<String>) -> CompletionItem {
    CompletionItem {
        label: label.to_string(),
        kind: Some(kind),
        detail,
        ..CompletionItem::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lsp_types::Url;

    fn labels(text: &str, cursor: &str) -> Vec<String> {
        let file = File::new(Url::parse("file:///r.urdf").expect("uri"), text.into());
        let offset = text.find(cursor).expect("cursor") + cursor.len();
        items(&file, offset, std::slice::from_ref(&file))
            .into_iter()
            .map(|i| i.label)
            .collect()
    }

    #[test]
    fn names_types_and_codes_where_they_go() {
        let text = "<robot><link name=\"base\"/><link name=\"arm\"/>\
                    <joint name=\"j\" type=\"\"><parent link=\"\"/><mimic joint=\"\"/></joint>\
                    <!-- urdf-validate: ignore U2 --></robot>";
        assert_eq!(labels(text, "<parent link=\""), ["arm", "base"]);
        assert_eq!(labels(text, "<mimic joint=\""), ["j"]);
        assert!(labels(text, "type=\"").contains(&"continuous".to_string()));
        assert!(labels(text, "ignore U2").contains(&"U201".to_string()));
        assert!(labels(text, "<link name=\"").is_empty());
    }
}
