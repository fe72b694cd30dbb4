//! Fixes: the edit a finding with one right answer comes with, and applying edits to a text.
//!
//! A rule that knows the right value attaches a [`Fix`] to its finding. Its edits are written against the
//! text the parser read (a URDF file, or a xacro file's expansion) as operations on an attribute value or a
//! span; the report turns them into byte edits of the files the user edits ([`Edit::resolve`]), and
//! [`apply`] applies byte edits to a text: pure text in, text out (writing files belongs to the CLI).

use crate::diagnostics::span::Span;

/// Whether applying a fix keeps the robot's physics and meaning (`safe`: `--fix`) or changes them
/// (`unsafe`: also `--unsafe-fixes`).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum Applicability {
    /// Nothing a simulator or solver computes changes (a non-unit axis normalised, limits a continuous
    /// joint ignores removed).
    Safe,
    /// The robot changes: mass, inertia, limits, scale, effort.
    Unsafe,
}

/// A change to the text the parser read.
#[derive(Clone, Debug, PartialEq)]
pub enum Edit {
    /// Replace the attribute value at `value` (the span of the value's text, without quotes).
    ReplaceValue {
        /// The value's span.
        value: Span,
        /// The new value, as written between the quotes.
        with: String,
    },
    /// Remove the whole attribute whose value is at `value` (name, `=`, quotes and the space before it).
    RemoveAttribute {
        /// The value's span.
        value: Span,
    },
    /// Insert ` name="text"` right after the attribute whose value is at `value`.
    InsertAttributeAfter {
        /// The value's span of the attribute to insert after.
        value: Span,
        /// The attribute's name.
        name: String,
        /// Its value.
        text: String,
    },
    /// Delete the text at `span` (only in the file itself: never traced through a xacro expansion).
    Delete {
        /// What to delete.
        span: Span,
    },
    /// Insert `lines` as the first children of the element at `element` (right after its start tag),
    /// one per line, indented like the element's other children (only in the file itself, like
    /// [`Edit::Delete`]). Lines may carry their own further indentation, in steps of two spaces.
    InsertChild {
        /// The element's span (it must have an end tag).
        element: Span,
        /// The child's lines.
        lines: Vec<String>,
    },
}

/// A byte edit of one text: replace `start..end` with `replacement`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
pub struct TextEdit {
    /// First byte replaced.
    pub start: usize,
    /// One past the last byte replaced (= `start` for an insertion).
    pub end: usize,
    /// The new text.
    pub replacement: String,
}

impl TextEdit {
    /// Whether `self` and `other` cannot both be applied: their spans overlap, or one inserts where the
    /// other starts (which goes first is ambiguous). The same edit twice is one edit, not a conflict.
    pub fn conflicts_with(&self, other: &TextEdit) -> bool {
        self != other
            && (self.start < other.end && other.start < self.end
                || self.start == other.start
                    && (self.start == self.end || other.start == other.end))
    }
}

impl Edit {
    /// The span of the text the edit is anchored at (an attribute value, or the span to delete).
    pub fn anchor(&self) -> Span {
        match self {
            Edit::ReplaceValue { value, .. }
            | Edit::RemoveAttribute { value }
            | Edit::InsertAttributeAfter { value, .. } => *value,
            Edit::Delete { span } => *span,
            Edit::InsertChild { element, .. } => *element,
        }
    }

    /// Whether the edit only makes sense in the text it was written against (not traced into a xacro
    /// source).
    pub fn is_textual(&self) -> bool {
        matches!(self, Edit::Delete { .. } | Edit::InsertChild { .. })
    }

    /// The byte edit of `text` when the anchor's text is at `at` in it (`None` when the text around it is
    /// not an attribute as expected).
    pub fn resolve(&self, text: &str, at: Span) -> Option<TextEdit> {
        let (start, end) = (at.start as usize, at.end as usize);
        text.get(start..end)?;
        match self {
            Edit::ReplaceValue { with, .. } => Some(TextEdit {
                start,
                end,
                replacement: with.clone(),
            }),
            Edit::RemoveAttribute { .. } => {
                let (name_start, value_end) = attribute_bounds(text, start, end)?;
                // The whitespace before the name goes with it.
                let before = text.get(..name_start)?;
                let start = before.trim_end().len();
                Some(TextEdit {
                    start,
                    end: value_end,
                    replacement: String::new(),
                })
            }
            Edit::InsertAttributeAfter {
                name, text: value, ..
            } => {
                let (_, value_end) = attribute_bounds(text, start, end)?;
                Some(TextEdit {
                    start: value_end,
                    end: value_end,
                    replacement: format!(" {name}=\"{value}\""),
                })
            }
            Edit::Delete { .. } => Some(TextEdit {
                start,
                end,
                replacement: String::new(),
            }),
            Edit::InsertChild { lines, .. } => insert_child(text, start, end, lines),
        }
    }
}

/// The insertion of `lines` right after the start tag of the element at `start..end` of `text`, indented
/// like its first child (else two spaces deeper than the element's line); `None` for an element without an
/// end tag.
fn insert_child(text: &str, start: usize, end: usize, lines: &[String]) -> Option<TextEdit> {
    let element = text.get(start..end)?;
    if !element.starts_with('<') || element.ends_with("/>") {
        return None;
    }
    // The start tag ends at the first '>' outside quotes.
    let mut quote = None;
    let close = element.char_indices().find_map(|(i, c)| match (quote, c) {
        (None, '"' | '\'') => {
            quote = Some(c);
            None
        }
        (Some(q), c) if c == q => {
            quote = None;
            None
        }
        (None, '>') => Some(i),
        _ => None,
    })?;
    let at = start + close + 1;
    let line_start = text.get(..start)?.rfind('\n').map_or(0, |i| i + 1);
    let own: String = text
        .get(line_start..start)?
        .chars()
        .take_while(|c| c.is_whitespace())
        .collect();
    let after = text.get(at..)?;
    let child = match after
        .strip_prefix('\n')
        .or_else(|| after.strip_prefix("\r\n"))
    {
        Some(rest) => {
            let indent: String = rest
                .chars()
                .take_while(|c| *c == ' ' || *c == '\t')
                .collect();
            if indent.len() > own.len() {
                indent
            } else {
                format!("{own}  ")
            }
        }
        None => format!("{own}  "),
    };
    let replacement: String = lines.iter().map(|l| format!("\n{child}{l}")).collect();
    Some(TextEdit {
        start: at,
        end: at,
        replacement,
    })
}

/// `value` rounded to `digits` significant digits, written briefly: plainly from 1e-4 to 1e6
/// (`0.0123457`), else in exponent notation (`1.66667e-10`), which every URDF parser reads.
pub fn significant(value: f64, digits: usize) -> String {
    let exponent = format!("{value:.*e}", digits.saturating_sub(1));
    let Ok(rounded) = exponent.parse::<f64>() else {
        return number(value);
    };
    if rounded == 0.0 || (1e-4..1e6).contains(&rounded.abs()) {
        return number(rounded);
    }
    // `1.50000e-7` → `1.5e-7`.
    match exponent.split_once('e') {
        Some((mantissa, power)) if mantissa.contains('.') => {
            let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
            format!("{mantissa}e{power}")
        }
        _ => exponent,
    }
}

/// For an attribute value at `start..end`: where its name starts and where its closing quote ends.
fn attribute_bounds(text: &str, start: usize, end: usize) -> Option<(usize, usize)> {
    let bytes = text.as_bytes();
    let quote = *bytes.get(start.checked_sub(1)?)?;
    if !(quote == b'"' || quote == b'\'') || *bytes.get(end)? != quote {
        return None;
    }
    let before_quote = text.get(..start - 1)?.trim_end();
    let before_equals = before_quote.strip_suffix('=')?.trim_end();
    let name_start = before_equals
        .rfind(|c: char| c.is_whitespace())
        .map_or(0, |i| i + 1);
    (name_start < before_equals.len()).then_some((name_start, end + 1))
}

/// What a finding's fix is: what it does, whether it is safe, and its edits.
#[derive(Clone, Debug, PartialEq)]
pub struct Fix {
    /// Safe or unsafe.
    pub applicability: Applicability,
    /// What applying it does, in one sentence (`set effort to 48.2 N·m`).
    pub description: String,
    /// The edits, all or none applied.
    pub edits: Vec<Edit>,
    /// Its edits are MJCF (elements and attributes of MuJoCo's format): only such fixes are written
    /// into MJCF files, every other is written for URDF.
    pub mjcf: bool,
}

impl Fix {
    /// A safe fix.
    pub fn safe(description: impl Into<String>, edits: Vec<Edit>) -> Fix {
        Fix {
            applicability: Applicability::Safe,
            description: description.into(),
            edits,
            mjcf: false,
        }
    }

    /// An unsafe fix.
    pub fn unsafe_(description: impl Into<String>, edits: Vec<Edit>) -> Fix {
        Fix {
            applicability: Applicability::Unsafe,
            description: description.into(),
            edits,
            mjcf: false,
        }
    }

    /// The fix, its edits written for MJCF files.
    pub fn in_mjcf(mut self) -> Fix {
        self.mjcf = true;
        self
    }
}

/// `text` with `edits` applied (an edit given twice once), and the edits left out because they conflict
/// with one applied before them (in the order given) or do not fit the text. The spans of all of them refer
/// to `text` as given.
pub fn apply(text: &str, edits: &[TextEdit]) -> (String, Vec<TextEdit>) {
    let mut kept: Vec<&TextEdit> = Vec::new();
    let mut dropped = Vec::new();
    for edit in edits {
        if kept.contains(&edit) {
            continue;
        }
        let fits = edit.start <= edit.end && text.get(edit.start..edit.end).is_some();
        if fits && !kept.iter().any(|k| edit.conflicts_with(k)) {
            kept.push(edit);
        } else {
            dropped.push(edit.clone());
        }
    }
    kept.sort_by_key(|e| (e.start, e.end));
    let mut out = String::with_capacity(text.len());
    let mut at = 0;
    for edit in kept {
        out.push_str(&text[at..edit.start]);
        out.push_str(&edit.replacement);
        at = edit.end;
    }
    out.push_str(&text[at..]);
    (out, dropped)
}

/// `value` written as briefly as it round-trips (`1`, `0.7071067811865476`, `48.2`).
pub fn number(value: f64) -> String {
    if value == value.trunc() && value.abs() < 1e15 {
        format!("{}", value as i64)
    } else {
        format!("{value}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn span_of(text: &str, needle: &str) -> Span {
        let start = text.find(needle).expect("needle");
        Span::from_range(start..start + needle.len())
    }

    #[test]
    fn attribute_edits_resolve_around_the_value() {
        let text = r#"<limit lower="-1" upper='1' effort="10"/>"#;
        let lower = span_of(text, "-1");
        let removed = Edit::RemoveAttribute { value: lower }
            .resolve(text, lower)
            .expect("an attribute");
        assert_eq!(
            apply(text, &[removed]).0,
            r#"<limit upper='1' effort="10"/>"#
        );
        let upper = span_of(text, "1' ");
        let upper = Span {
            start: upper.start,
            end: upper.start + 1,
        };
        let inserted = Edit::InsertAttributeAfter {
            value: upper,
            name: "x".into(),
            text: "2".into(),
        }
        .resolve(text, upper)
        .expect("an attribute");
        assert_eq!(
            apply(text, &[inserted]).0,
            r#"<limit lower="-1" upper='1' x="2" effort="10"/>"#
        );
        // Not an attribute value: no edit.
        assert_eq!(
            Edit::RemoveAttribute { value: lower }.resolve(text, span_of(text, "limit")),
            None
        );
    }

    #[test]
    fn overlapping_and_out_of_range_edits_are_dropped() {
        let text = "abcdef";
        let edit = |start, end, r: &str| TextEdit {
            start,
            end,
            replacement: r.into(),
        };
        let (out, dropped) = apply(
            text,
            &[
                edit(1, 3, "X"),
                edit(2, 4, "Y"),
                edit(5, 9, "Z"),
                edit(4, 4, "-"),
            ],
        );
        assert_eq!(out, "aXd-ef");
        assert_eq!(dropped, vec![edit(2, 4, "Y"), edit(5, 9, "Z")]);
        // The same edit twice is applied once; an insertion where a replacement starts conflicts.
        let (out, dropped) = apply(text, &[edit(1, 3, "X"), edit(1, 3, "X"), edit(1, 1, "-")]);
        assert_eq!(out, "aXdef");
        assert_eq!(dropped, vec![edit(1, 1, "-")]);
    }

    #[test]
    fn a_child_goes_after_the_start_tag_indented_like_its_siblings() {
        let text = "<robot>\n  <link name=\"a>b\">\n    <visual/>\n  </link>\n</robot>";
        let element = span_of(text, "<link name=\"a>b\">\n    <visual/>\n  </link>");
        let edit = Edit::InsertChild {
            element,
            lines: vec![
                "<inertial>".into(),
                "  <mass value=\"1\"/>".into(),
                "</inertial>".into(),
            ],
        }
        .resolve(text, element)
        .expect("an element with an end tag");
        assert_eq!(
            apply(text, &[edit]).0,
            "<robot>\n  <link name=\"a>b\">\n    <inertial>\n      <mass value=\"1\"/>\n    </inertial>\n    <visual/>\n  </link>\n</robot>"
        );
        let empty = span_of(text, "<visual/>");
        assert_eq!(
            Edit::InsertChild {
                element: empty,
                lines: vec![]
            }
            .resolve(text, empty),
            None,
            "no end tag"
        );
    }

    #[test]
    fn numbers_are_written_briefly() {
        assert_eq!(significant(0.012345678, 6), "0.0123457");
        assert_eq!(significant(2.0, 6), "2");
        assert_eq!(significant(1.0 / 6.0 * 1e-9, 6), "1.66667e-10");
        assert_eq!(significant(-1.5e-7, 6), "-1.5e-7");
        assert_eq!(significant(0.0, 6), "0");
        assert_eq!(number(1.0), "1");
        assert_eq!(number(-0.5), "-0.5");
        assert_eq!(number(1.0 / 2f64.sqrt()), "0.7071067811865475");
    }
}
