//! `docs/json_schema.md`, generated from the report's JSON Schema so the documentation cannot drift from
//! the types (a test fails when the committed file is stale).

use serde_json::Value;

use crate::report::json_schema;

const INTRO: &str = "# JSON report\n\n\
<!-- Generated from crates/urdf-validator/src/report.rs by `urdf_validate --json-schema-markdown`; a test fails when this file is stale. -->\n\n\
`urdf_validate` writes `<stem>_validation.json` beside each input (or in `--output-dir`), where `<stem>` is the \
file name without `.urdf` / `.xacro`. With `--format json` the same report is printed on stdout (an array when \
several files are validated). The machine-readable schema (JSON Schema draft 2020-12) is \
[`report.schema.json`](report.schema.json), also printed by `urdf_validate --json-schema`.\n\n\
Conventions:\n\n\
- Numbers are SI (kg, m, kg·m²). Values that are not known are `null`, never `NaN` or `Infinity`: every report \
  is strict JSON.\n\
- Field names follow the Python `urdf-validator` so CI scripts keep working. Sections that are not implemented \
  yet (`statics`, `stability`, `workspace`) are absent rather than filled with placeholders.\n\
- `overall_status` maps to the exit code: `PASS` → 0, `WARN` → 1, `FAIL` / `UNKNOWN` → 2.\n";

/// The Markdown reference of the report.
pub fn json_schema_markdown() -> String {
    let schema: Value = serde_json::from_str(&json_schema()).unwrap_or(Value::Null);
    let mut out = String::from(INTRO);
    section(&mut out, "Report", &schema);
    if let Some(defs) = schema.get("$defs").and_then(Value::as_object) {
        for (name, def) in defs {
            section(&mut out, name, def);
        }
    }
    out
}

fn section(out: &mut String, name: &str, def: &Value) {
    out.push_str(&format!("\n## {name}\n\n"));
    if let Some(text) = def.get("description").and_then(Value::as_str) {
        out.push_str(&format!("{}\n\n", one_line(text)));
    }
    if let Some(properties) = def.get("properties").and_then(Value::as_object) {
        out.push_str("| Field | Type | Description |\n|---|---|---|\n");
        for (field, property) in properties {
            let description = property
                .get("description")
                .and_then(Value::as_str)
                .unwrap_or("");
            out.push_str(&format!(
                "| `{field}` | {} | {} |\n",
                type_name(property),
                one_line(description)
            ));
        }
    } else if let Some(variants) = def.get("oneOf").and_then(Value::as_array) {
        out.push_str("| Value | Meaning |\n|---|---|\n");
        for variant in variants {
            let value = variant
                .get("const")
                .map(Value::to_string)
                .unwrap_or_default();
            let description = variant
                .get("description")
                .and_then(Value::as_str)
                .unwrap_or("");
            out.push_str(&format!("| `{value}` | {} |\n", one_line(description)));
        }
    } else if let Some(values) = def.get("enum").and_then(Value::as_array) {
        let list: Vec<String> = values.iter().map(|v| format!("`{v}`")).collect();
        out.push_str(&format!("One of {}.\n", list.join(", ")));
    }
}

fn one_line(text: &str) -> String {
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('|', "\\|")
}

fn type_name(property: &Value) -> String {
    if let Some(reference) = property.get("$ref").and_then(Value::as_str) {
        let name = reference.rsplit('/').next().unwrap_or(reference);
        return format!("[{name}](#{})", name.to_lowercase());
    }
    if let Some(options) = property.get("anyOf").and_then(Value::as_array) {
        let names: Vec<String> = options.iter().map(type_name).collect();
        return names.join(" \\| ");
    }
    let types: Vec<&str> = match property.get("type") {
        Some(Value::String(one)) => vec![one.as_str()],
        Some(Value::Array(many)) => many.iter().filter_map(Value::as_str).collect(),
        _ => vec![],
    };
    let names: Vec<String> = types
        .iter()
        .map(|&t| match (t, property.get("items")) {
            ("array", Some(items)) => {
                let size = property
                    .get("minItems")
                    .filter(|m| property.get("maxItems") == Some(*m));
                match size {
                    Some(n) => format!("array[{n}] of {}", type_name(items)),
                    None => format!("array of {}", type_name(items)),
                }
            }
            ("integer", _) => "integer".to_string(),
            (other, _) => other.to_string(),
        })
        .collect();
    if names.is_empty() {
        "any".to_string()
    } else {
        names.join(" \\| ")
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    fn committed(name: &str) -> String {
        std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../docs")
                .join(name),
        )
        .unwrap_or_default()
    }

    #[test]
    fn docs_json_schema_md_is_up_to_date() {
        assert!(
            committed("json_schema.md") == super::json_schema_markdown(),
            "docs/json_schema.md is stale: run `cargo run -p urdf-validate-cli -- --json-schema-markdown > docs/json_schema.md`"
        );
    }

    #[test]
    fn docs_report_schema_json_is_up_to_date() {
        assert!(
            committed("report.schema.json") == crate::report::json_schema(),
            "docs/report.schema.json is stale: run `cargo run -p urdf-validate-cli -- --json-schema > docs/report.schema.json`"
        );
    }

    #[test]
    fn every_report_field_is_documented() {
        let doc = super::json_schema_markdown();
        for field in [
            "urdf_path",
            "overall_status",
            "confidence_level",
            "mass_confidence",
            "end_column",
            "infos",
        ] {
            assert!(doc.contains(&format!("| `{field}` |")), "{field} missing");
        }
    }
}
