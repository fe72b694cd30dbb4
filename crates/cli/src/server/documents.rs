//! The documents the editor has open: their text as typed (saved or not) and version, kept in step with
//! `didOpen`/`didChange`/`didClose`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use lsp_types::{TextDocumentContentChangeEvent, Url};

use super::positions::LineIndex;

/// One open document.
#[derive(Clone, Debug)]
pub struct Document {
    /// The text as the editor has it.
    pub text: String,
    /// The editor's version of it.
    pub version: i32,
    /// Its line starts.
    pub index: LineIndex,
}

impl Document {
    fn new(text: String, version: i32) -> Document {
        let index = LineIndex::new(&text);
        Document {
            text,
            version,
            index,
        }
    }
}

/// The open documents, by URI.
#[derive(Debug, Default)]
pub struct Documents {
    open: HashMap<Url, Document>,
}

impl Documents {
    /// `didOpen`.
    pub fn open(&mut self, uri: Url, text: String, version: i32) {
        self.open.insert(uri, Document::new(text, version));
    }

    /// `didChange`: apply the changes in order (a change without a range replaces the whole text). A
    /// change whose range starts or ends past the last line is an error, and none of the changes is
    /// applied (the text is as before); a position past the end of its line is the line's end, as LSP says.
    pub fn change(
        &mut self,
        uri: &Url,
        version: i32,
        changes: Vec<TextDocumentContentChangeEvent>,
    ) -> Result<(), String> {
        let Some(document) = self.open.get_mut(uri) else {
            return Err(format!("didChange for {uri}, which is not open"));
        };
        let mut text = document.text.clone();
        for (number, change) in changes.into_iter().enumerate() {
            match change.range {
                Some(range) => {
                    let index = LineIndex::new(&text);
                    let offset = |position: lsp_types::Position| {
                        index.checked_offset(&text, position).ok_or_else(|| {
                            format!(
                                "didChange of {uri} (version {version}): change {number} reaches line {} \
                                 of a {}-line text; none applied",
                                position.line + 1,
                                index.lines()
                            )
                        })
                    };
                    let start = offset(range.start)?;
                    let end = offset(range.end)?.max(start);
                    text.replace_range(start..end, &change.text);
                }
                None => text = change.text,
            }
        }
        *document = Document::new(text, version);
        Ok(())
    }

    /// `didClose`.
    pub fn close(&mut self, uri: &Url) {
        self.open.remove(uri);
    }

    /// The open document at `uri`.
    pub fn get(&self, uri: &Url) -> Option<&Document> {
        self.open.get(uri)
    }

    /// The open document at `path`, if any.
    pub fn by_path(&self, path: &Path) -> Option<&Document> {
        Url::from_file_path(path)
            .ok()
            .and_then(|uri| self.open.get(&uri))
    }
}

/// Whether the validator reads files like `path`: URDF, xacro, SDFormat.
pub fn is_robot_file(path: &Path) -> bool {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    [".urdf", ".xacro", ".sdf", ".world"]
        .iter()
        .any(|ext| name.ends_with(ext))
}

/// The file path of a `file://` URI.
pub fn path_of(uri: &Url) -> Option<PathBuf> {
    uri.to_file_path().ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use lsp_types::{Position, Range};

    #[test]
    fn incremental_changes_apply_in_order() {
        let uri = Url::parse("file:///r/robot.urdf").expect("uri");
        let mut documents = Documents::default();
        documents.open(uri.clone(), "<robot name=\"é\">\n</robot>".into(), 1);
        let change = |line, from, to, text: &str| TextDocumentContentChangeEvent {
            range: Some(Range::new(
                Position::new(line, from),
                Position::new(line, to),
            )),
            range_length: None,
            text: text.into(),
        };
        documents
            .change(
                &uri,
                2,
                vec![change(0, 13, 14, "ab"), change(1, 0, 0, "  <link/>\n")],
            )
            .expect("in range");
        let document = documents.get(&uri).expect("open");
        assert_eq!(document.text, "<robot name=\"ab\">\n  <link/>\n</robot>");
        assert_eq!(document.version, 2);
        // Past the end of a line: the line's end (LSP). Past the last line: an error, nothing applied.
        documents
            .change(&uri, 3, vec![change(2, 50, 50, "\n")])
            .expect("a column past the end of the line");
        let error = documents
            .change(&uri, 4, vec![change(0, 0, 0, "x"), change(9, 0, 0, "lost")])
            .expect_err("a line past the end");
        assert!(error.contains("line 10 of a 4-line text"), "{error}");
        let document = documents.get(&uri).expect("open");
        assert_eq!(document.text, "<robot name=\"ab\">\n  <link/>\n</robot>\n");
        assert_eq!(
            document.version, 3,
            "the failed change leaves text and version"
        );
        assert!(is_robot_file(Path::new("a/b.URDF.xacro")));
        assert!(!is_robot_file(Path::new("a/b.xml")));
    }
}
