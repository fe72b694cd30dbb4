//! Findings → LSP diagnostics, each published on the file it is in (an included xacro file gets its own),
//! with the rule code linked to its page in the book, the severity, the exact range and the xacro
//! macro calls that produced it as related information. A file that cannot be read as a robot (XML not
//! well-formed, a xacro error) gets one diagnostic at the place the reader stopped.

use std::collections::HashMap;

use lsp_types::{
    CodeDescription, Diagnostic, DiagnosticRelatedInformation, DiagnosticSeverity, Location,
    NumberOrString, Position, Range, Url,
};
use urdf_validator::diagnostics::rules;
use urdf_validator::diagnostics::Severity;
use urdf_validator::input::LoadError;
use urdf_validator::report::FindingReport;
use urdf_validator::{Error, Validation};

use super::positions::LineIndex;

/// The `source` of every diagnostic.
pub const SOURCE: &str = "urdf_validate";

/// The texts findings point into, with their line indexes, by file name as findings name them.
pub struct Texts<'v> {
    files: HashMap<String, (&'v str, LineIndex)>,
}

impl<'v> Texts<'v> {
    /// The source texts of `validation`.
    pub fn of(validation: &'v Validation) -> Texts<'v> {
        let files = validation
            .sources
            .iter()
            .map(|s| {
                let text = s.text();
                (s.path().display().to_string(), (text, LineIndex::new(text)))
            })
            .collect();
        Texts { files }
    }

    /// The text and index of `file`.
    pub fn get(&self, file: &str) -> Option<(&'v str, &LineIndex)> {
        self.files.get(file).map(|(text, index)| (*text, index))
    }

    /// Every file, by name.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.files.keys().map(String::as_str)
    }

    /// The LSP position of the validator's 1-based `line`:`column` in `file`.
    fn position(&self, file: &str, line: u32, column: u32) -> Position {
        match self.get(file) {
            Some((text, index)) => index.position_of_line_column(text, line, column),
            None => Position::new(line.saturating_sub(1), column.saturating_sub(1)),
        }
    }
}

/// The range of `finding` in its file (the start of the file when it has no place).
pub fn finding_range(finding: &FindingReport, texts: &Texts) -> Range {
    let (Some(file), Some(line), Some(column)) = (&finding.file, finding.line, finding.column)
    else {
        return Range::default();
    };
    let start = texts.position(file, line, column);
    let end = match (finding.end_line, finding.end_column) {
        (Some(line), Some(column)) => texts.position(file, line, column),
        _ => start,
    };
    Range::new(start, end.max(start))
}

/// The diagnostics of the findings of a validation of `root` that `wanted` keeps, by file: an entry for
/// every file the validation read (empty when it has none, so that the editor clears what it showed).
pub fn of_validation(
    root: &Url,
    validation: &Validation,
    wanted: impl Fn(&FindingReport) -> bool,
) -> HashMap<Url, Vec<Diagnostic>> {
    let texts = Texts::of(validation);
    let mut by_file: HashMap<Url, Vec<Diagnostic>> = texts
        .names()
        .filter_map(|name| Url::from_file_path(name).ok())
        .map(|uri| (uri, Vec::new()))
        .collect();
    by_file.entry(root.clone()).or_default();
    for finding in validation.report.findings.iter().filter(|f| wanted(f)) {
        let uri = finding
            .file
            .as_deref()
            .and_then(|f| Url::from_file_path(f).ok())
            .unwrap_or_else(|| root.clone());
        let diagnostic = Diagnostic {
            range: finding_range(finding, &texts),
            severity: Some(severity(finding.severity)),
            code: Some(NumberOrString::String(finding.rule.clone())),
            code_description: rule_link(&finding.rule),
            source: Some(SOURCE.to_string()),
            message: message(finding),
            related_information: related(finding, &texts),
            tags: None,
            data: None,
        };
        by_file.entry(uri).or_default().push(diagnostic);
    }
    by_file
}

/// The code of the diagnostic of a file that could not be validated.
const LOAD_ERROR_CODES: [&str; 3] = ["xml-syntax", "xacro", "not-validated"];

/// What a finding shown from an older text says (the last analysis that read the file; its place has
/// followed the edits since).
const STALE: &str = " (from the last text that parsed)";

/// The diagnostic of a file that could not be validated: at the token where the reader stopped (in the
/// file it names), else at the start of `root`; with a code, and a message without the file's path
/// (the editor shows the file).
pub fn of_error(root: &Url, error: &Error, text: &str) -> (Url, Diagnostic) {
    let (uri, range, code, message) = match error {
        Error::Load(LoadError::Xml {
            line,
            column,
            message,
            ..
        }) => {
            let index = LineIndex::new(text);
            let at = index.position_of_line_column(text, *line, *column);
            (
                root.clone(),
                token_at(text, &index, at),
                LOAD_ERROR_CODES[0],
                format!("not well-formed XML: {message}"),
            )
        }
        Error::Load(LoadError::Xacro {
            message,
            location: Some(location),
            ..
        }) => {
            let uri = Url::from_file_path(&location.path).unwrap_or_else(|_| root.clone());
            let range = if uri == *root {
                let index = LineIndex::new(text);
                token_at(text, &index, index.position(text, location.byte))
            } else {
                // Another file's text is not at hand: its column in characters stands for UTF-16 units.
                let at = Position::new(
                    u32::try_from(location.line.saturating_sub(1)).unwrap_or(u32::MAX),
                    u32::try_from(location.col.saturating_sub(1)).unwrap_or(u32::MAX),
                );
                Range::new(at, at)
            };
            // The message without its `file:line:col: ` prefix.
            let prefix = format!(
                "{}:{}:{}: ",
                location.path.display(),
                location.line,
                location.col
            );
            let detail = message
                .find(&prefix)
                .map_or(message.as_str(), |i| &message[i + prefix.len()..]);
            (uri, range, LOAD_ERROR_CODES[1], detail.to_string())
        }
        other => {
            let text = other.to_string();
            let path = super::documents::path_of(root).map(|p| format!("{}: ", p.display()));
            let detail = path
                .and_then(|p| text.strip_prefix(&p).map(str::to_string))
                .unwrap_or(text);
            (root.clone(), Range::default(), LOAD_ERROR_CODES[2], detail)
        }
    };
    let diagnostic = Diagnostic {
        range,
        severity: Some(DiagnosticSeverity::ERROR),
        code: Some(NumberOrString::String(code.to_string())),
        source: Some(SOURCE.to_string()),
        message,
        ..Diagnostic::default()
    };
    (uri, diagnostic)
}

/// Whether `diagnostic` says a file could not be validated (not a finding).
pub fn is_load_error(diagnostic: &Diagnostic) -> bool {
    matches!(&diagnostic.code, Some(NumberOrString::String(code)) if LOAD_ERROR_CODES.contains(&code.as_str()))
}

/// `diagnostic` as shown from an older text: marked in its message (once).
pub fn stale(diagnostic: &Diagnostic) -> Diagnostic {
    let mut stale = diagnostic.clone();
    if !stale.message.ends_with(STALE) {
        stale.message.push_str(STALE);
    }
    stale
}

/// The range of the token starting at `at` (up to the next space, `<` or `>` on its line; empty at the
/// end of a line), so an editor underlines the word the reader stopped at.
fn token_at(text: &str, index: &LineIndex, at: Position) -> Range {
    let start = index.offset(text, at);
    let rest = &text[start..];
    let length = rest
        .char_indices()
        .skip(1)
        .find(|&(_, c)| c.is_whitespace() || c == '<' || c == '>')
        .map_or(rest.len(), |(i, c)| if c == '>' { i + 1 } else { i });
    let length = if rest.starts_with(char::is_whitespace) {
        0
    } else {
        length
    };
    index.range(text, start, start + length)
}

fn severity(severity: Severity) -> DiagnosticSeverity {
    match severity {
        Severity::Critical | Severity::Fail => DiagnosticSeverity::ERROR,
        Severity::Warn => DiagnosticSeverity::WARNING,
        Severity::Info => DiagnosticSeverity::INFORMATION,
    }
}

/// The message, with the finding's own hint when it has one.
fn message(finding: &FindingReport) -> String {
    match &finding.help {
        Some(help) => format!("{} ({})", finding.message, help),
        None => finding.message.clone(),
    }
}

/// The rule's page in the book (under the package metadata's `homepage`), never a file of the machine
/// that built the binary.
pub fn rule_link(code: &str) -> Option<CodeDescription> {
    let rule = rules::find(code)?;
    let href = Url::parse(&rules::reference_url(rule)).ok()?;
    Some(CodeDescription { href })
}

/// The xacro macro calls and includes that produced the flagged text (`in macro 'wheel' called at
/// FILE:LINE:COL`), each at its place; and, for a finding about a pair of links (`Links 'a' and 'b' …`),
/// the other link's definition.
fn related(finding: &FindingReport, texts: &Texts) -> Option<Vec<DiagnosticRelatedInformation>> {
    let mut related: Vec<_> = finding
        .expanded_from
        .iter()
        .filter_map(|entry| {
            let (file, line, column) = trailing_location(entry)?;
            let at = texts.position(file, line, column);
            Some(DiagnosticRelatedInformation {
                location: Location::new(Url::from_file_path(file).ok()?, Range::new(at, at)),
                message: entry.clone(),
            })
        })
        .collect();
    let own = finding_range(finding, texts).start;
    for (file, start, end, name) in other_links(&finding.message, texts) {
        let Some((text, index)) = texts.get(file) else {
            continue;
        };
        let range = index.range(text, start, end);
        let Ok(uri) = Url::from_file_path(file) else {
            continue;
        };
        let same_place = finding.file.as_deref() == Some(file) && range.start.line == own.line;
        if !same_place {
            related.push(DiagnosticRelatedInformation {
                location: Location::new(uri, range),
                message: format!("link '{name}'"),
            });
        }
    }
    (!related.is_empty()).then_some(related)
}

/// When `message` names two or more links (`'name'`) defined in `texts` (`<link name="name"`), each
/// definition: (file, first and end byte of the name, name).
fn other_links<'t>(message: &str, texts: &'t Texts) -> Vec<(&'t str, usize, usize, String)> {
    let quoted: Vec<&str> = message
        .split('\'')
        .skip(1)
        .step_by(2)
        .filter(|name| !name.is_empty())
        .collect();
    let mut found = Vec::new();
    for name in quoted {
        for file in texts.names() {
            let Some((text, _)) = texts.get(file) else {
                continue;
            };
            for quote in ['"', '\''] {
                let needle = format!("<link name={quote}{name}{quote}");
                if let Some(at) = text.find(&needle) {
                    let start = at + "<link name=".len() + 1;
                    found.push((file, start, start + name.len(), name.to_string()));
                }
            }
        }
    }
    if found.len() < 2 {
        found.clear();
    }
    found
}

/// The `FILE:LINE:COL` that ends a stack entry (`... called at FILE:LINE:COL`).
fn trailing_location(entry: &str) -> Option<(&str, u32, u32)> {
    let (_, place) = entry.rsplit_once(" at ")?;
    let mut parts = place.rsplitn(3, ':');
    let column = parts.next()?.trim().parse().ok()?;
    let line = parts.next()?.parse().ok()?;
    Some((parts.next()?, line, column))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rule's link is its entry on the project's web site, wherever the binary runs (it was a
    /// `file://` path into the checkout the binary was built from).
    #[test]
    fn a_rule_links_to_the_published_reference() {
        let link = rule_link("U105").expect("a known rule").href;
        assert_eq!(link.scheme(), "https");
        assert_eq!(
            link.as_str(),
            format!("{}rules/u105.html", env!("CARGO_PKG_HOMEPAGE"))
        );
        assert!(rule_link("U999").is_none());
    }

    #[test]
    fn a_pair_of_links_names_both_definitions() {
        let text = "<robot>\n<link name=\"a\"/>\n<link name='b'/>\n</robot>";
        let texts = Texts {
            files: HashMap::from([("/r.urdf".to_string(), (text, LineIndex::new(text)))]),
        };
        let found = other_links(
            "Links 'a' and 'b' have collision geometry in contact",
            &texts,
        );
        let names: Vec<(&str, &str)> = found
            .iter()
            .map(|(_, start, end, name)| (&text[*start..*end], name.as_str()))
            .collect();
        assert_eq!(names, [("a", "a"), ("b", "b")]);
        assert!(other_links("Link 'a' has no inertial", &texts).is_empty());
        assert!(other_links("Links 'a' and 'zz'", &texts).is_empty());
    }

    #[test]
    fn stack_entries_end_with_their_place() {
        assert_eq!(
            trailing_location("in macro 'wheel' called at /r/robot.urdf.xacro:40:3"),
            Some(("/r/robot.urdf.xacro", 40, 3))
        );
        assert_eq!(trailing_location("in macro 'wheel'"), None);
    }
}
