//! Positions: byte offsets of a text ↔ LSP positions (0-based line, UTF-16 code units), and the
//! validator's 1-based (line, column in characters) → LSP positions.

use lsp_types::{Position, Range};

/// The line starts of one text, to turn byte offsets and character columns into LSP positions.
#[derive(Clone, Debug)]
pub struct LineIndex {
    /// Byte offset of the start of each line (the first is 0).
    starts: Vec<usize>,
}

impl LineIndex {
    /// The index of `text`. A line ends at `\n` (a `\r` before it stays part of the line, as editors
    /// count `\r\n` as one break: it is never inside a position's column).
    pub fn new(text: &str) -> LineIndex {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        LineIndex { starts }
    }

    /// The LSP position of byte `offset` of `text` (clamped to the text, and back to a character
    /// boundary).
    pub fn position(&self, text: &str, offset: usize) -> Position {
        let mut offset = offset.min(text.len());
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        let start = self.starts[line];
        let column = text[start..offset].encode_utf16().count();
        Position::new(to_u32(line), to_u32(column))
    }

    /// The LSP range of bytes `start..end` of `text`.
    pub fn range(&self, text: &str, start: usize, end: usize) -> Range {
        Range::new(self.position(text, start), self.position(text, end))
    }

    /// The byte offset of LSP `position` in `text` (a position past the end of its line is the line's
    /// end; past the last line, the end of the text).
    pub fn offset(&self, text: &str, position: Position) -> usize {
        let Some(&start) = self.starts.get(position.line as usize) else {
            return text.len();
        };
        let line = line_text(text, start);
        let mut units = 0;
        for (i, c) in line.char_indices() {
            if units >= position.character as usize {
                return start + i;
            }
            units += c.len_utf16();
        }
        start + line.len()
    }

    /// [`LineIndex::offset`] of a position on a line of the text (`None` past the last line).
    pub fn checked_offset(&self, text: &str, position: Position) -> Option<usize> {
        ((position.line as usize) < self.starts.len()).then(|| self.offset(text, position))
    }

    /// The number of lines (a text ending with a line break has an empty last line).
    pub fn lines(&self) -> usize {
        self.starts.len()
    }

    /// The LSP position of the validator's 1-based `line` and 1-based `column` counted in characters.
    pub fn position_of_line_column(&self, text: &str, line: u32, column: u32) -> Position {
        let Some(&start) = self.starts.get(line.saturating_sub(1) as usize) else {
            return self.position(text, text.len());
        };
        let characters = column.saturating_sub(1) as usize;
        let offset = line_text(text, start)
            .char_indices()
            .nth(characters)
            .map_or(start + line_text(text, start).len(), |(i, _)| start + i);
        self.position(text, offset)
    }
}

/// The text of the line starting at byte `start`, without its line break.
fn line_text(text: &str, start: usize) -> &str {
    let rest = &text[start..];
    let line = rest.split('\n').next().unwrap_or(rest);
    line.strip_suffix('\r').unwrap_or(line)
}

fn to_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// Where `range` is after an edit that replaced `edited` with `text` (`None` for the whole document):
/// unchanged before the edit, moved with the text after it, `None` when the edit touched it.
pub fn through_edit(range: Range, edited: Option<Range>, text: &str) -> Option<Range> {
    let edited = edited?;
    if range.end < edited.start || (range.end == edited.start && range.start < range.end) {
        return Some(range);
    }
    if range.start < edited.end {
        return None;
    }
    // Where the inserted text ends.
    let breaks = text.matches('\n').count();
    let last_line = text.rsplit('\n').next().unwrap_or("");
    let last_width = to_u32(last_line.encode_utf16().count());
    let end = if breaks == 0 {
        Position::new(edited.start.line, edited.start.character + last_width)
    } else {
        Position::new(edited.start.line + to_u32(breaks), last_width)
    };
    let moved = |p: Position| {
        if p.line == edited.end.line {
            Position::new(
                end.line,
                end.character + (p.character - edited.end.character),
            )
        } else {
            Position::new(p.line - edited.end.line + end.line, p.character)
        }
    };
    Some(Range::new(moved(range.start), moved(range.end)))
}

/// The part of `before` that differs from `after`: its byte range, and what `after` has there.
pub fn changed_part<'a>(before: &str, after: &'a str) -> (usize, usize, &'a str) {
    let mut prefix = before
        .bytes()
        .zip(after.bytes())
        .take_while(|(a, b)| a == b)
        .count();
    while !before.is_char_boundary(prefix) || !after.is_char_boundary(prefix) {
        prefix -= 1;
    }
    let limit = before.len().min(after.len()) - prefix;
    let mut suffix = before
        .bytes()
        .rev()
        .zip(after.bytes().rev())
        .take(limit)
        .take_while(|(a, b)| a == b)
        .count();
    while !before.is_char_boundary(before.len() - suffix)
        || !after.is_char_boundary(after.len() - suffix)
    {
        suffix -= 1;
    }
    (
        prefix,
        before.len() - suffix,
        &after[prefix..after.len() - suffix],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_changed_part_is_the_span_between_common_ends() {
        assert_eq!(changed_part("a=\"1 0 0\"", "a=\"1 0 0\""), (9, 9, ""));
        assert_eq!(
            changed_part("<j axis=\"2 0 0\"/>", "<j axis=\"1 0 0\"/>"),
            (9, 10, "1")
        );
        assert_eq!(changed_part("xé y", "xè y"), (1, 3, "è"));
        assert_eq!(changed_part("ab", "aXb"), (1, 1, "X"));
    }

    #[test]
    fn ranges_follow_the_edits_before_them() {
        let range = |l0, c0, l1, c1| Range::new(Position::new(l0, c0), Position::new(l1, c1));
        let finding = range(5, 17, 5, 24);
        // Five lines inserted above: five lines down.
        assert_eq!(
            through_edit(finding, Some(range(0, 0, 0, 0)), "a\nb\nc\nd\ne\n"),
            Some(range(10, 17, 10, 24))
        );
        // Text typed earlier on its line: further right.
        assert_eq!(
            through_edit(finding, Some(range(5, 2, 5, 2)), "xyz"),
            Some(range(5, 20, 5, 27))
        );
        // A line deleted above, and an edit after it: as it was, but one line up; unchanged.
        assert_eq!(
            through_edit(finding, Some(range(1, 0, 2, 0)), ""),
            Some(range(4, 17, 4, 24))
        );
        assert_eq!(
            through_edit(finding, Some(range(6, 0, 6, 3)), ""),
            Some(finding)
        );
        // An edit inside it, or the whole text replaced: withdrawn.
        assert_eq!(through_edit(finding, Some(range(5, 18, 5, 19)), "Q"), None);
        assert_eq!(through_edit(finding, None, "new text"), None);
    }

    #[test]
    fn columns_count_utf16_code_units() {
        // "é" is 2 bytes and 1 UTF-16 unit; "𝄞" is 4 bytes and 2 units.
        let text = "a\n<é𝄞 x=\"1\"/>\r\nend";
        let index = LineIndex::new(text);
        let x = text.find('x').expect("x");
        assert_eq!(index.position(text, x), Position::new(1, 5));
        assert_eq!(index.offset(text, Position::new(1, 5)), x);
        assert_eq!(
            index.position_of_line_column(text, 2, 5),
            Position::new(1, 5)
        );
        // Past the end of a line: its end, before the \r\n.
        let line_end = text.find('\r').expect("cr");
        assert_eq!(index.offset(text, Position::new(1, 99)), line_end);
        assert_eq!(index.offset(text, Position::new(9, 0)), text.len());
        assert_eq!(index.position(text, text.len()), Position::new(2, 3));
        // Inside a character: back to its start.
        let clef = text.find('𝄞').expect("clef");
        assert_eq!(index.position(text, clef + 1), Position::new(1, 2));
    }
}
