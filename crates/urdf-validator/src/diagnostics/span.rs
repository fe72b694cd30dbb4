//! Where a value was written: byte spans inside the parsed text, and the file:line:column a user reads.

/// A byte range `[start, end)` inside the text a robot was parsed from (the input stage turns it into a
/// line and column).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Span {
    /// First byte.
    pub start: u32,
    /// One past the last byte.
    pub end: u32,
}

impl Span {
    /// A span from a `std::ops::Range<usize>` as roxmltree reports it (saturating at 4 GiB, roxmltree's own limit).
    pub fn from_range(range: std::ops::Range<usize>) -> Self {
        let clamp = |v: usize| u32::try_from(v).unwrap_or(u32::MAX);
        Span {
            start: clamp(range.start),
            end: clamp(range.end),
        }
    }
}

/// A value read from the file together with where it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Spanned<T> {
    /// The parsed value.
    pub value: T,
    /// Where its text is (the attribute value, or the element for derived values).
    pub span: Span,
}

/// A human-facing position: 1-based line and column (in characters).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
pub struct Location {
    /// The file as the user named it.
    pub file: String,
    /// 1-based line.
    pub line: u32,
    /// 1-based column, counted in characters.
    pub column: u32,
}
