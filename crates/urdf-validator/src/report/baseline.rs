//! Baselines: the findings a robot already had when the validator was adopted, so that only new ones
//! count (`--write-baseline FILE`, `--baseline FILE`).
//!
//! A finding is identified by its [`Fingerprint`]: rule code, severity, the path of the element it points
//! at in the (expanded) URDF (`robot/joint[@name='elbow']/limit`), and its message with the numbers taken
//! out ([`message_key`]). Line numbers play no part, so blank lines, comments or a moved element change
//! nothing; a torque that moves from 5.1 to 5.2 N·m still matches, another joint does not. For xacro the
//! element path is taken in the expanded document, which is one per robot, so a finding in an included file
//! is told apart from its twin in another include by the element it lands on.
//!
//! Matching is a multiset: a baseline entry with `count: 2` hides two identical findings, a third is new.
//! Entries that match nothing any more are *stale*: the problem was fixed and the baseline can shrink.
//!
//! A report JSON written by `urdf_validate` (`<robot>_validation.json`, or a JSON array of them) also
//! serves as a baseline; reports older than the `element` field match on rule, severity and message key.

use std::collections::{BTreeMap, HashMap};
use std::path::{Component, Path, PathBuf};

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::diagnostics::span::Span;
use crate::diagnostics::Severity;
use crate::report::{FindingReport, Report};

/// The version of the baseline file format this library writes and reads.
pub const FORMAT_VERSION: u32 = 1;

/// `message` with every number (outside quoted names) replaced by `#`: `Joint 'j2' needs 49.50 N·m ...
/// (margin 0.61×)` → `Joint 'j2' needs # N·m ... (margin #×)`. Digits inside a word (`link3`) and inside
/// quotes are kept, so names still tell findings apart.
pub fn message_key(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut chars = message.chars().peekable();
    let mut quote: Option<char> = None;
    let mut previous: Option<char> = None;
    while let Some(c) = chars.next() {
        if let Some(q) = quote {
            out.push(c);
            if c == q {
                quote = None;
            }
        } else if (c == '\'' || c == '"') && !previous.is_some_and(char::is_alphanumeric) {
            quote = Some(c);
            out.push(c);
        } else if c.is_ascii_digit() && !previous.is_some_and(|p| p.is_alphanumeric() || p == '_') {
            // A sign belongs to the number when it does not follow a word (`-0.5`, not `a-1`).
            if out.ends_with(['-', '+'])
                && !out[..out.len() - 1]
                    .chars()
                    .next_back()
                    .is_some_and(|p| p.is_alphanumeric())
            {
                out.pop();
            }
            let mut last = c;
            while let Some(&next) = chars.peek() {
                let exponent_sign = (next == '-' || next == '+') && (last == 'e' || last == 'E');
                if next.is_ascii_digit()
                    || (next == '.' && chars.clone().nth(1).is_some_and(|d| d.is_ascii_digit()))
                    || ((next == 'e' || next == 'E')
                        && chars
                            .clone()
                            .nth(1)
                            .is_some_and(|d| d.is_ascii_digit() || d == '-' || d == '+'))
                    || exponent_sign
                {
                    last = next;
                    chars.next();
                } else {
                    break;
                }
            }
            out.push('#');
            previous = Some('0');
            continue;
        } else {
            out.push(c);
        }
        previous = Some(c);
    }
    out
}

/// The XML document of `text` for [`ElementPaths`]; `None` when `text` is not XML.
pub fn document(text: &str) -> Option<roxmltree::Document<'_>> {
    roxmltree::Document::parse_with_options(text, crate::input::xml_options()).ok()
}

/// The element paths of one URDF document: the element holding a byte, as
/// `robot/link[@name='arm']/inertial`.
pub struct ElementPaths<'a, 'input> {
    doc: Option<&'a roxmltree::Document<'input>>,
    /// The root element's element children (byte range, node), in document order: searched by halving,
    /// since a robot has thousands of them and each finding looks one up.
    top: Vec<(std::ops::Range<usize>, roxmltree::NodeId)>,
}

impl<'a, 'input> ElementPaths<'a, 'input> {
    /// Index the document the spans point into (none: no paths).
    pub fn of(doc: Option<&'a roxmltree::Document<'input>>) -> Self {
        let top = doc
            .map(|d| {
                d.root_element()
                    .children()
                    .filter(roxmltree::Node::is_element)
                    .map(|c| (c.range(), c.id()))
                    .collect()
            })
            .unwrap_or_default();
        ElementPaths { doc, top }
    }

    /// The path of the innermost element whose text holds the start of `span`.
    pub fn at(&self, span: Span) -> Option<String> {
        let byte = span.start as usize;
        let doc = self.doc?;
        let root = doc.root_element();
        if !root.range().contains(&byte) {
            return None;
        }
        let mut path = step(root);
        let after = self.top.partition_point(|(range, _)| range.end <= byte);
        let mut next = self
            .top
            .get(after)
            .filter(|(range, _)| range.contains(&byte))
            .and_then(|(_, id)| doc.get_node(*id));
        while let Some(child) = next {
            path.push('/');
            path.push_str(&step(child));
            next = child
                .children()
                .find(|c| c.is_element() && c.range().contains(&byte));
        }
        Some(path)
    }
}

/// One step of an element path: `joint[@name='elbow']`, `gazebo[@reference='arm']`, `visual[2]` (an
/// unnamed element among several of its tag: its 1-based position among them, as in XPath), or the tag.
fn step(node: roxmltree::Node) -> String {
    let tag = node.tag_name().name();
    for key in ["name", "reference"] {
        if let Some(value) = node.attribute(key) {
            return format!("{tag}[@{key}='{value}']");
        }
    }
    let same = |n: &roxmltree::Node| n.is_element() && n.tag_name().name() == tag;
    let Some(parent) = node.parent() else {
        return tag.to_string();
    };
    if parent.children().filter(same).count() < 2 {
        return tag.to_string();
    }
    // `prev_siblings` starts at the node itself: the count is 1-based.
    format!("{tag}[{}]", node.prev_siblings().filter(same).count())
}

/// What identifies a finding across runs.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Fingerprint {
    /// Rule code.
    pub rule: String,
    /// Severity in effect.
    pub severity: Severity,
    /// Element path (`None`: the finding has no element).
    pub element: Option<String>,
    /// [`message_key`] of the message.
    pub key: String,
}

impl Fingerprint {
    /// The fingerprint of a reported finding.
    pub fn of(finding: &FindingReport) -> Fingerprint {
        Fingerprint {
            rule: finding.rule.clone(),
            severity: finding.severity,
            element: finding.element.clone(),
            key: message_key(&finding.message),
        }
    }
}

/// One entry of a baseline: a fingerprint and how many findings have it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct BaselineEntry {
    /// Rule code.
    pub rule: String,
    /// Severity when the baseline was written.
    pub severity: Severity,
    /// Path of the element the finding points at (absent: it has none, or the baseline is an old report).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub element: Option<String>,
    /// The message with its numbers replaced by `#`.
    pub key: String,
    /// How many findings have this fingerprint.
    #[serde(default = "one")]
    pub count: usize,
    /// The first of those messages, for people reading the file.
    #[serde(default)]
    pub message: String,
}

fn one() -> usize {
    1
}

/// The baselined findings of one robot.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct BaselineRobot {
    /// The robot file, relative to the baseline file's folder (`/`-separated).
    pub file: String,
    /// `name` of `<robot>`.
    #[serde(default)]
    pub robot: String,
    /// Its entries, sorted.
    pub findings: Vec<BaselineEntry>,
}

/// The baseline file as written.
#[derive(Debug, Serialize, Deserialize)]
struct BaselineFile {
    urdf_validate_baseline: u32,
    robots: Vec<BaselineRobot>,
}

/// A report JSON used as a baseline: what it needs of it.
#[derive(Deserialize)]
struct OldReport {
    urdf_path: String,
    #[serde(default)]
    robot_name: String,
    findings: Vec<OldFinding>,
}

#[derive(Deserialize)]
struct OldFinding {
    rule: String,
    severity: Severity,
    message: String,
    #[serde(default)]
    element: Option<String>,
}

/// A baseline, read.
#[derive(Debug)]
pub struct Baseline {
    /// The file, as named.
    pub path: PathBuf,
    robots: Vec<(Option<PathBuf>, BaselineRobot)>,
}

impl Baseline {
    /// Read a baseline file, or a report JSON (one report or an array); a one-line error naming the file.
    pub fn load(path: &Path) -> Result<Baseline, String> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("baseline {}: cannot read it: {e}", path.display()))?;
        Baseline::parse(&text, path)
    }

    /// Read baseline `text` that came from `path` (robot files are relative to its folder).
    pub fn parse(text: &str, path: &Path) -> Result<Baseline, String> {
        let bad = |what: String| format!("baseline {}: {what}", path.display());
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| bad(format!("not JSON ({e})")))?;
        let dir = path.parent().unwrap_or(Path::new(""));
        let robots: Vec<(Option<PathBuf>, BaselineRobot)> =
            if value.get("urdf_validate_baseline").is_some() {
                let file: BaselineFile = serde_json::from_value(value)
                    .map_err(|e| bad(format!("not a baseline file ({e})")))?;
                if file.urdf_validate_baseline != FORMAT_VERSION {
                    return Err(bad(format!(
                        "format version {} (this urdf_validate reads version {FORMAT_VERSION})",
                        file.urdf_validate_baseline
                    )));
                }
                file.robots
                    .into_iter()
                    .map(|robot| (dir.join(&robot.file).canonicalize().ok(), robot))
                    .collect()
            } else {
                let reports: Vec<OldReport> = if value.is_array() {
                    serde_json::from_value(value)
                } else {
                    serde_json::from_value(value).map(|r| vec![r])
                }
                .map_err(|e| {
                    bad(format!(
                        "neither a baseline file nor an urdf_validate report ({e})"
                    ))
                })?;
                reports.into_iter().map(|r| from_report(r, dir)).collect()
            };
        Ok(Baseline {
            path: path.to_path_buf(),
            robots,
        })
    }

    /// The entries of the robot validated from `file` named `name`: the robot of that file; else, among
    /// the robots whose file is no longer there (moved, or a report written elsewhere), the one robot of
    /// that name, else the only robot of the baseline.
    pub fn robot(&self, file: &Path, name: &str) -> Option<&BaselineRobot> {
        let file = file.canonicalize().ok();
        let by_file = self
            .robots
            .iter()
            .find(|(path, _)| path.is_some() && *path == file);
        let gone = || self.robots.iter().filter(|(path, _)| path.is_none());
        let named = || {
            let mut named = gone().filter(|(_, r)| r.robot == name);
            match (named.next(), named.next()) {
                (Some(one), None) if !name.is_empty() => Some(one),
                _ => None,
            }
        };
        let only = || match self.robots.as_slice() {
            [only] if only.0.is_none() => Some(only),
            _ => None,
        };
        by_file.or_else(named).or_else(only).map(|(_, r)| r)
    }
}

/// A report's findings as baseline entries (its `urdf_path` is relative to the working directory, else
/// to the report's folder).
fn from_report(report: OldReport, dir: &Path) -> (Option<PathBuf>, BaselineRobot) {
    let path = Path::new(&report.urdf_path);
    let canonical = path
        .canonicalize()
        .or_else(|_| dir.join(path).canonicalize())
        .ok();
    let findings = entries(report.findings.into_iter().map(|f| {
        let fingerprint = Fingerprint {
            rule: f.rule,
            severity: f.severity,
            element: f.element,
            key: message_key(&f.message),
        };
        (fingerprint, f.message)
    }));
    let robot = BaselineRobot {
        file: report.urdf_path,
        robot: report.robot_name,
        findings,
    };
    (canonical, robot)
}

/// Fingerprints counted and sorted into entries (each keeps its first message).
fn entries(findings: impl Iterator<Item = (Fingerprint, String)>) -> Vec<BaselineEntry> {
    let mut counted: BTreeMap<Fingerprint, (usize, String)> = BTreeMap::new();
    for (fingerprint, message) in findings {
        counted.entry(fingerprint).or_insert((0, message)).0 += 1;
    }
    counted
        .into_iter()
        .map(|(f, (count, message))| BaselineEntry {
            rule: f.rule,
            severity: f.severity,
            element: f.element,
            key: f.key,
            count,
            message,
        })
        .collect()
}

/// What a baseline did to one report: `baseline` in the JSON.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct BaselineSummary {
    /// The baseline file, as named.
    pub file: String,
    /// Findings not in the baseline: those reported (they alone make the status and the exit code).
    pub new: usize,
    /// Findings the baseline holds: not reported, not counted.
    pub matched: usize,
    /// Baseline entries no finding matches any more (fixed): rewrite the baseline to drop them.
    pub stale: Vec<BaselineEntry>,
    /// The findings the baseline matched, as they would have been reported.
    pub baselined: Vec<FindingReport>,
}

/// Split `findings` into those the baseline `robot` does not hold (returned) and those it does (in the
/// summary), multiset-wise: exact element matches first, then entries without an element (old reports).
pub fn apply<T>(
    findings: Vec<(T, FindingReport)>,
    robot: Option<&BaselineRobot>,
    file: &Path,
) -> (Vec<(T, FindingReport)>, BaselineSummary) {
    let mut left: Vec<BaselineEntry> = robot.map(|r| r.findings.clone()).unwrap_or_default();
    // Entries by what they match, in file order: one lookup per finding, not a scan of the baseline.
    let mut by_print: HashMap<(&str, Severity, &str, Option<&str>), Vec<usize>> = HashMap::new();
    for (index, e) in left.iter().enumerate() {
        by_print
            .entry((&e.rule, e.severity, &e.key, e.element.as_deref()))
            .or_default()
            .push(index);
    }
    let mut counts: Vec<usize> = left.iter().map(|e| e.count).collect();
    let mut matched = vec![false; findings.len()];
    for wildcard in [false, true] {
        for (index, (_, report)) in findings.iter().enumerate() {
            if matched[index] {
                continue;
            }
            let print = Fingerprint::of(report);
            let element = if wildcard {
                None
            } else {
                print.element.as_deref()
            };
            let entry = by_print
                .get(&(
                    print.rule.as_str(),
                    print.severity,
                    print.key.as_str(),
                    element,
                ))
                .and_then(|entries| entries.iter().find(|&&e| counts[e] > 0));
            if let Some(&entry) = entry {
                counts[entry] -= 1;
                matched[index] = true;
            }
        }
    }
    for (entry, count) in left.iter_mut().zip(counts) {
        entry.count = count;
    }
    let mut new = Vec::new();
    let mut baselined = Vec::new();
    for ((finding, report), matched) in findings.into_iter().zip(matched) {
        if matched {
            baselined.push(report);
        } else {
            new.push((finding, report));
        }
    }
    let summary = BaselineSummary {
        file: file.display().to_string(),
        new: new.len(),
        matched: baselined.len(),
        stale: left.into_iter().filter(|e| e.count > 0).collect(),
        baselined,
    };
    (new, summary)
}

/// The baseline file for `reports` (every finding that counts, baselined ones included), written to
/// `path`: robots sorted by file, entries by fingerprint, pretty-printed.
pub fn render(reports: &[&Report], path: &Path) -> String {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut robots: Vec<BaselineRobot> = reports
        .iter()
        .map(|report| {
            let baselined = report.baseline.iter().flat_map(|b| &b.baselined);
            BaselineRobot {
                file: relative(Path::new(&report.urdf_path), dir),
                robot: report.robot_name.clone(),
                findings: entries(
                    report
                        .findings
                        .iter()
                        .chain(baselined)
                        .map(|f| (Fingerprint::of(f), f.message.clone())),
                ),
            }
        })
        .collect();
    robots.sort_by(|a, b| a.file.cmp(&b.file));
    let file = BaselineFile {
        urdf_validate_baseline: FORMAT_VERSION,
        robots,
    };
    serde_json::to_string_pretty(&file).unwrap_or_default() + "\n"
}

/// `file` relative to folder `dir`, `/`-separated (absolute when they share no root).
fn relative(file: &Path, dir: &Path) -> String {
    let absolute = |p: &Path| {
        p.canonicalize()
            .unwrap_or_else(|_| std::env::current_dir().unwrap_or_default().join(p))
    };
    let (file, dir) = (absolute(file), absolute(dir));
    let f: Vec<Component> = file.components().collect();
    let d: Vec<Component> = dir.components().collect();
    let common = f.iter().zip(&d).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return file.display().to_string().replace('\\', "/");
    }
    let ups = d.len() - common;
    let parts: Vec<String> = std::iter::repeat_n("..".to_string(), ups)
        .chain(
            f.iter()
                .skip(common)
                .map(|c| c.as_os_str().to_string_lossy().into_owned()),
        )
        .collect();
    parts.join("/")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn message_keys_drop_numbers_but_keep_names() {
        let a = "Joint 'r_shoulder_lift_joint' needs 49.50 N·m to hold the zero pose but declares effort 30 (margin 0.61×)";
        let b = "Joint 'r_shoulder_lift_joint' needs 52.1 N·m to hold the zero pose but declares effort 30 (margin 0.58×)";
        let c = "Joint 'l_shoulder_lift_joint' needs 49.50 N·m to hold the zero pose but declares effort 30 (margin 0.61×)";
        assert_eq!(message_key(a), message_key(b));
        assert_ne!(message_key(a), message_key(c));
        assert_eq!(
            message_key("link3 at line 40: -1.5e-3 kg, \"j_2\" x 2"),
            "link3 at line #: # kg, \"j_2\" x #"
        );
        assert_eq!(
            message_key("A + B ≥ C: 1.000000e-3 + 1e+2"),
            "A + B ≥ C: # + #"
        );
        assert_eq!(
            message_key("Robot's arm_2 has 88 links"),
            "Robot's arm_2 has # links"
        );
    }

    #[test]
    fn element_paths_name_the_element() {
        let text = "<robot name='r'>\n<link name='a'><inertial><mass value='1'/></inertial></link>\n<joint name='j'><limit effort='3'/></joint><gazebo reference='a'/><gazebo><x/></gazebo><gazebo/></robot>";
        let doc = document(text);
        let paths = ElementPaths::of(doc.as_ref());
        let at = |needle: &str| {
            let start = text.find(needle).map(|i| i as u32).unwrap_or(u32::MAX);
            paths.at(Span { start, end: start })
        };
        assert_eq!(
            at("value='1'").as_deref(),
            Some("robot[@name='r']/link[@name='a']/inertial/mass")
        );
        assert_eq!(
            at("effort").as_deref(),
            Some("robot[@name='r']/joint[@name='j']/limit")
        );
        assert_eq!(
            at("reference").as_deref(),
            Some("robot[@name='r']/gazebo[@reference='a']")
        );
        assert_eq!(at("<x/>").as_deref(), Some("robot[@name='r']/gazebo[2]/x"));
        let doc = document("not xml");
        assert_eq!(ElementPaths::of(doc.as_ref()).at(Span::default()), None);
    }

    fn finding(rule: &str, element: Option<&str>, message: &str) -> ((), FindingReport) {
        let report = FindingReport {
            rule: rule.to_string(),
            name: String::new(),
            severity: Severity::Warn,
            section: crate::diagnostics::Section::Schema,
            message: message.to_string(),
            file: None,
            line: None,
            column: None,
            end_line: None,
            end_column: None,
            help: None,
            element: element.map(str::to_string),
            expanded_from: Vec::new(),
            fix: None,
        };
        ((), report)
    }

    #[test]
    fn matching_counts_identical_findings() {
        let link = Some("robot/link[@name='a']");
        let twice = vec![
            finding("U206", link, "short by 1.5"),
            finding("U206", link, "short by 2.5"),
        ];
        let reports: Vec<FindingReport> = twice.iter().map(|(_, r)| r.clone()).collect();
        let robot = BaselineRobot {
            file: "r.urdf".into(),
            robot: "r".into(),
            findings: entries(
                reports
                    .iter()
                    .map(|r| (Fingerprint::of(r), r.message.clone())),
            ),
        };
        assert_eq!(robot.findings.len(), 1);
        assert_eq!(robot.findings[0].count, 2);
        // Three identical findings against a count of two: one is new.
        let mut thrice = twice.clone();
        thrice.push(finding("U206", link, "short by 3"));
        let (new, summary) = apply(thrice, Some(&robot), Path::new("b.json"));
        assert_eq!((new.len(), summary.matched), (1, 2));
        // One of them: the other is stale.
        let (new, summary) = apply(twice[..1].to_vec(), Some(&robot), Path::new("b.json"));
        assert_eq!((new.len(), summary.matched), (0, 1));
        assert_eq!(summary.stale.len(), 1);
        assert_eq!(summary.stale[0].count, 1);
        // Another element is another finding; an entry without one (an old report) matches any.
        let elsewhere = vec![finding("U206", Some("robot/link[@name='b']"), "short by 1")];
        assert_eq!(
            apply(elsewhere.clone(), Some(&robot), Path::new("b.json"))
                .0
                .len(),
            1
        );
        let mut old = robot.clone();
        old.findings[0].element = None;
        assert_eq!(apply(elsewhere, Some(&old), Path::new("b.json")).0.len(), 0);
    }

    #[test]
    fn a_malformed_baseline_names_the_file() {
        let error = Baseline::parse("{", Path::new("b.json")).expect_err("malformed");
        assert!(error.starts_with("baseline b.json: not JSON"), "{error}");
        let error = Baseline::parse(
            "{\"urdf_validate_baseline\": 9, \"robots\": []}",
            Path::new("b.json"),
        )
        .expect_err("version");
        assert!(error.contains("format version 9"), "{error}");
        let error = Baseline::parse("[1]", Path::new("b.json")).expect_err("not a report");
        assert!(error.contains("neither a baseline file"), "{error}");
    }
}
