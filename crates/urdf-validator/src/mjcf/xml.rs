//! The MJCF files as one document: elements with the file they are in, `<include>`s replaced by the
//! children of the included file's `<mujoco>` root (as MuJoCo pastes them in), and where findings go.

use roxmltree::{Document, Node};

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::input::xml_files::{FindingSink, IncludeTarget, XmlFiles, MAX_INCLUDE_DEPTH};

/// Most `<include>`s expanded in one model (a file included twice by a file included twice... is read
/// once but expanded each time: bounded work on untrusted input).
const MAX_EXPANSIONS: usize = 10_000;

pub use crate::input::xml_files::El;

/// The parsed files, and the findings of the reading.
pub struct Reader<'a> {
    sink: FindingSink<'a>,
    docs: &'a [Option<Document<'a>>],
    expansions: usize,
}

/// A reader is a finding sink (spans, `report`, `findings`) that also walks the files.
impl<'a> std::ops::Deref for Reader<'a> {
    type Target = FindingSink<'a>;
    fn deref(&self) -> &FindingSink<'a> {
        &self.sink
    }
}

impl std::ops::DerefMut for Reader<'_> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.sink
    }
}

impl<'a> Reader<'a> {
    /// A reader of `files`, parsed as `docs` (one per file, `None` when it does not parse).
    pub fn new(files: &'a XmlFiles, docs: &'a [Option<Document<'a>>]) -> Self {
        Reader {
            sink: FindingSink::new(files),
            docs,
            expansions: 0,
        }
    }

    /// The root element of the entry file.
    pub fn root(&self) -> Option<El<'a>> {
        self.docs.first()?.as_ref().map(|doc| El {
            file: 0,
            node: doc.root_element(),
        })
    }

    /// The files read.
    pub fn files(&self) -> &'a XmlFiles {
        self.sink.files
    }

    /// The findings of the reading.
    pub fn into_findings(self) -> Vec<Finding> {
        self.sink.findings
    }

    /// The child elements of `el`, each `<include>` replaced by the children of the included file's root
    /// (recursively); an include that cannot be read is a U031 finding.
    pub fn children(&mut self, el: El<'a>) -> Vec<El<'a>> {
        let mut out = Vec::new();
        self.expand_into(el, 0, &mut out);
        out
    }

    fn expand_into(&mut self, el: El<'a>, depth: usize, out: &mut Vec<El<'a>>) {
        for node in el.node.children().filter(Node::is_element) {
            let child = El {
                file: el.file,
                node,
            };
            if child.tag() != "include" {
                out.push(child);
                continue;
            }
            let span = self.span(child);
            let target = self.files.include(span).cloned();
            let problem = match target {
                Some(IncludeTarget::File(file)) => {
                    match self.docs.get(file).and_then(Option::as_ref) {
                        Some(_) if depth > MAX_INCLUDE_DEPTH => {
                            Some(format!("includes more than {MAX_INCLUDE_DEPTH} deep"))
                        }
                        Some(_) if self.expansions >= MAX_EXPANSIONS => Some(format!(
                            "more than {MAX_EXPANSIONS} includes expanded: this one is not"
                        )),
                        Some(doc) => {
                            self.expansions += 1;
                            let root = El {
                                file,
                                node: doc.root_element(),
                            };
                            self.expand_into(root, depth + 1, out);
                            None
                        }
                        None => Some("the included file does not parse".to_string()),
                    }
                }
                Some(IncludeTarget::Unresolved(why) | IncludeTarget::Refused(why)) => Some(why),
                None => Some("the include was not read".to_string()),
            };
            if let Some(why) = problem {
                self.report(
                    &rules::MJCF_INCLUDE_UNRESOLVED,
                    span,
                    format!("<include>: {why}"),
                );
            }
        }
    }
}

/// The numbers of an attribute value (whitespace-separated); an error when one does not parse or is not
/// finite.
pub fn numbers(text: &str) -> Result<Vec<f64>, String> {
    text.split_whitespace()
        .map(|word| match word.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(format!("'{word}' is not finite")),
            Err(_) => Err(format!("'{word}' is not a number")),
        })
        .collect()
}
