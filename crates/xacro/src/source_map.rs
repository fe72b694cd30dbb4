//! Where each piece of the expanded XML came from: source files, origins and the include / macro-call
//! frames that produced them.

use std::ops::Range;
use std::path::PathBuf;

/// A source file read during the expansion (the entry file, includes, YAML files), with its text.
#[derive(Clone, Debug)]
pub struct SourceFile {
    /// The path as it was opened (relative paths stay relative).
    pub path: PathBuf,
    /// The whole text of the file.
    pub text: String,
    line_starts: Vec<usize>,
}

impl SourceFile {
    /// A source file with its text.
    pub fn new(path: PathBuf, text: String) -> Self {
        let mut line_starts = vec![0];
        line_starts.extend(
            text.bytes()
                .enumerate()
                .filter(|(_, b)| *b == b'\n')
                .map(|(i, _)| i + 1),
        );
        SourceFile {
            path,
            text,
            line_starts,
        }
    }

    /// The 1-based line and 1-based column (in characters) of byte offset `byte`. Offsets past the end are
    /// clamped to the end; an offset inside a multi-byte character counts as that character.
    pub fn line_col(&self, byte: usize) -> (usize, usize) {
        let byte = byte.min(self.text.len());
        let line = self.line_starts.partition_point(|&s| s <= byte).max(1);
        let start = self.line_starts.get(line - 1).copied().unwrap_or(0);
        let col = self.text.get(start..).map_or(0, |rest| {
            rest.char_indices()
                .take_while(|(i, _)| start + i < byte)
                .count()
        });
        (line, col + 1)
    }
}

/// What created a [`Frame`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FrameKind {
    /// A macro call (`<xacro:name ...>` or `<xacro:call macro="...">`).
    Macro,
    /// An `<xacro:include>`.
    Include,
}

/// One macro call or include through which an output node was produced.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Macro call or include.
    pub kind: FrameKind,
    /// The macro name (as called, e.g. `arm` or `ns.arm`), or the path of the included file.
    pub name: String,
    /// Index in [`crate::Expansion::sources`] of the file holding the call or the `xacro:include` tag.
    pub file: usize,
    /// Byte range of the call's (or include's) start tag in that file.
    pub span: Range<usize>,
    /// The enclosing frame (index into [`SourceMap::frames`]), `None` at the top level.
    pub parent: Option<usize>,
}

/// What part of the output an [`Entry`] covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Piece {
    /// An element's start tag, from `<` to `>`.
    StartTag,
    /// An attribute's name.
    AttrName,
    /// An attribute's value (between the quotes).
    AttrValue,
    /// A text node.
    Text,
}

/// Where one output piece was written in the sources.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Origin {
    /// Index in [`crate::Expansion::sources`].
    pub file: usize,
    /// Byte range in that file: the element's start tag, the attribute's name or value, or the text.
    /// For output produced by a macro this is inside the macro body.
    pub span: Range<usize>,
    /// The innermost macro call or include that produced it (index into [`SourceMap::frames`]); `None` when
    /// it was written directly in the entry file.
    pub frame: Option<usize>,
}

/// One mapped range of the output.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    /// Byte range in [`crate::Expansion::xml`].
    pub output: Range<usize>,
    /// What it is.
    pub piece: Piece,
    /// Index into [`SourceMap::origins`].
    pub origin: usize,
}

/// Maps byte ranges of the expanded XML back to the sources.
#[derive(Clone, Debug, Default)]
pub struct SourceMap {
    entries: Vec<Entry>,
    origins: Vec<Origin>,
    frames: Vec<Frame>,
}

impl SourceMap {
    /// The innermost mapped piece containing `output_byte` (an attribute value or name rather than its start
    /// tag), or `None` for bytes no source produced (indentation, end tags, the banner).
    pub fn origin(&self, output_byte: usize) -> Option<&Origin> {
        self.entry_at(output_byte)
            .and_then(|e| self.origins.get(e.origin))
    }

    /// Like [`SourceMap::origin`], with the entry (output range and kind of piece).
    pub fn entry_at(&self, output_byte: usize) -> Option<&Entry> {
        // Entries are sorted by start; only a start tag can contain later entries (its attributes), so the
        // innermost match is the last entry starting at or before the offset, or failing that its start tag.
        let idx = self
            .entries
            .partition_point(|e| e.output.start <= output_byte);
        let before = self.entries.get(..idx)?;
        let last = before.last()?;
        if last.output.contains(&output_byte) {
            return Some(last);
        }
        before
            .iter()
            .rev()
            .find(|e| e.piece == Piece::StartTag)
            .filter(|e| e.output.contains(&output_byte))
    }

    /// All mapped pieces, in output order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// All origins (indexed by [`Entry::origin`]).
    pub fn origins(&self) -> &[Origin] {
        &self.origins
    }

    /// All frames (indexed by [`Origin::frame`] and [`Frame::parent`]).
    pub fn frames(&self) -> &[Frame] {
        &self.frames
    }

    /// The macro calls and includes that produced `origin`, innermost first.
    pub fn stack<'a>(&'a self, origin: &Origin) -> impl Iterator<Item = &'a Frame> + 'a {
        let mut next = origin.frame;
        std::iter::from_fn(move || {
            let frame = self.frames.get(next?)?;
            next = frame.parent;
            Some(frame)
        })
    }

    pub(crate) fn push_entry(&mut self, output: Range<usize>, piece: Piece, origin: usize) {
        self.entries.push(Entry {
            output,
            piece,
            origin,
        });
    }

    pub(crate) fn push_origin(&mut self, origin: Origin) -> usize {
        self.origins.push(origin);
        self.origins.len() - 1
    }

    pub(crate) fn push_frame(&mut self, frame: Frame) -> usize {
        self.frames.push(frame);
        self.frames.len() - 1
    }
}
