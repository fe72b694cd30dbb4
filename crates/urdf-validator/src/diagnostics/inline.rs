//! Inline suppression comments in URDF and xacro files:
//!
//! ```xml
//! <!-- urdf-validate: ignore U201, U203 -->
//! <link name="caster"/>                  <!-- the comment covers the next element's start tag -->
//! <link name="marker"/> <!-- urdf-validate: ignore U207 -->   (a trailing comment covers its own line)
//! <!-- urdf-validate: ignore-file U105 -->  (anywhere: the whole file)
//! ```
//!
//! Codes (or rule names, or code prefixes) are separated by commas or spaces; anything after a `;` is a
//! free-form reason.

/// The marker that starts a suppression comment.
const MARKER: &str = "urdf-validate:";

/// One suppression comment.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InlineSuppression {
    /// 1-based line of `<!--`.
    pub line: u32,
    /// 1-based column of `<!--` (characters).
    pub column: u32,
    /// `ignore-file`: the whole file.
    pub whole_file: bool,
    /// The lines whose findings it covers (for `ignore`): first and last, inclusive.
    pub lines: (u32, u32),
    /// The codes as written, each with its 1-based column.
    pub codes: Vec<(String, u32)>,
    /// A comment that starts with the marker but is not `ignore`/`ignore-file` (a typo): its directive.
    pub malformed: Option<String>,
}

/// Every suppression comment of `text`, in order.
pub fn parse(text: &str) -> Vec<InlineSuppression> {
    if !text.contains(MARKER) {
        return Vec::new();
    }
    let lines: Vec<&str> = text.split('\n').collect();
    let mut found = Vec::new();
    let mut from = 0;
    while let Some(open) = text.get(from..).and_then(|rest| rest.find("<!--")) {
        let start = from + open;
        let body_start = start + 4;
        let Some(close) = text.get(body_start..).and_then(|rest| rest.find("-->")) else {
            break;
        };
        let body_end = body_start + close;
        from = body_end + 3;
        let body = text.get(body_start..body_end).unwrap_or("");
        let trimmed = body.trim_start();
        let Some(directive) = trimmed.strip_prefix(MARKER) else {
            continue;
        };
        let directive_offset = body_start + (body.len() - trimmed.len()) + MARKER.len();
        let (line, column) = line_col(text, start);
        let (end_line, _) = line_col(text, body_end);
        found.push(comment(
            text,
            &lines,
            directive,
            directive_offset,
            (line, column),
            end_line,
            start,
        ));
    }
    found
}

fn comment(
    text: &str,
    lines: &[&str],
    directive: &str,
    directive_offset: usize,
    (line, column): (u32, u32),
    end_line: u32,
    start: usize,
) -> InlineSuppression {
    let without_reason = directive.split(';').next().unwrap_or("");
    let lead = without_reason.len() - without_reason.trim_start().len();
    let rest = without_reason.trim_start();
    let (kind, after) = rest
        .split_once(|c: char| c.is_whitespace() || c == ',')
        .unwrap_or((rest, ""));
    let mut suppression = InlineSuppression {
        line,
        column,
        whole_file: kind == "ignore-file",
        lines: (line, end_line),
        codes: Vec::new(),
        malformed: None,
    };
    if kind != "ignore" && kind != "ignore-file" {
        suppression.malformed = Some(kind.to_string());
        return suppression;
    }
    let codes_offset = directive_offset + lead + kind.len() + 1;
    let mut offset = 0;
    for token in after.split(|c: char| c.is_whitespace() || c == ',') {
        if !token.is_empty() {
            let at = codes_offset + offset;
            suppression
                .codes
                .push((token.to_string(), line_col(text, at).1));
        }
        offset += token.len() + 1;
    }
    // A trailing comment (something precedes it on its line) covers its own line; a comment alone on
    // its line covers the next element: from the next line with content to the end of its start tag.
    let line_start = text
        .get(..start)
        .map_or(0, |t| t.rfind('\n').map_or(0, |i| i + 1));
    let before = text.get(line_start..start).unwrap_or("");
    if before.trim().is_empty() && !suppression.whole_file {
        suppression.lines = (
            line,
            next_element_lines(lines, end_line).unwrap_or(end_line),
        );
    }
    suppression
}

/// From 1-based `after` (the comment's last line): the last line of the next element's start tag (the
/// first line with content that is not a comment, up to the line holding its first `>`).
fn next_element_lines(lines: &[&str], after: u32) -> Option<u32> {
    let mut index = after as usize; // 0-based index of the line after `after`
    while let Some(line) = lines.get(index) {
        let trimmed = line.trim();
        let comment_only = trimmed.starts_with("<!--") && trimmed.ends_with("-->");
        if !trimmed.is_empty() && !comment_only {
            break;
        }
        index += 1;
    }
    lines.get(index)?;
    let mut last = index;
    while let Some(line) = lines.get(last) {
        if line.contains('>') {
            break;
        }
        last += 1;
    }
    u32::try_from(last.min(lines.len().saturating_sub(1)) + 1).ok()
}

/// 1-based (line, column in characters) of byte `at`.
fn line_col(text: &str, at: usize) -> (u32, u32) {
    let before = text.get(..at).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before.get(line_start..).map_or(0, |s| s.chars().count()) + 1;
    (
        u32::try_from(line).unwrap_or(u32::MAX),
        u32::try_from(column).unwrap_or(u32::MAX),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_cover_the_next_element_or_their_own_line() {
        let text = "<robot name=\"r\">\n  <!-- urdf-validate: ignore U201, U203 -->\n\n  <link\n    name=\"a\">\n  </link>\n  <link name=\"b\"/> <!-- urdf-validate: ignore missing-inertial ; a frame -->\n  <!-- urdf-validate: ignore-file U105 -->\n  <!-- urdf-validate: ignroe U1 -->\n  <!-- a plain comment -->\n</robot>\n";
        let found = parse(text);
        assert_eq!(found.len(), 4, "{found:?}");
        assert_eq!(found[0].line, 2);
        assert_eq!(found[0].column, 3);
        assert_eq!(found[0].lines, (2, 5));
        assert_eq!(
            found[0].codes,
            vec![("U201".to_string(), 30), ("U203".to_string(), 36)]
        );
        assert!(!found[0].whole_file);
        assert_eq!(found[1].lines, (7, 7));
        assert_eq!(found[1].codes, vec![("missing-inertial".to_string(), 47)]);
        assert!(found[2].whole_file);
        assert_eq!(found[2].codes, vec![("U105".to_string(), 35)]);
        assert_eq!(found[3].malformed.as_deref(), Some("ignroe"));
        assert!(parse("<!-- urdf-validate: ignore U1").is_empty());
        assert!(parse("no comments").is_empty());
    }
}
