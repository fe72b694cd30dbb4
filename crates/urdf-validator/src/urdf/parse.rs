//! XML → [`Robot`]: a tolerant parser over roxmltree that keeps the span of every value and collects
//! findings instead of stopping at the first problem.

use std::path::Path;

use roxmltree::Node;

use crate::diagnostics::finding::Finding;
use crate::diagnostics::fix::{Edit, Fix};
use crate::diagnostics::rules;
use crate::diagnostics::span::{Span, Spanned};
use crate::input::unbound_prefixes::rewrite_unbound_prefixes;
use crate::input::{xml_options, LoadError};
use crate::urdf::robot::*;

/// Parse URDF text. `path` is only used in error messages.
pub fn parse_urdf(text: &str, path: &Path) -> Result<(Robot, Vec<Finding>), LoadError> {
    let prepared = UrdfText::new(text);
    let doc = prepared.document(path)?;
    Ok(prepared.parse(&doc))
}

/// URDF text ready for the XML parser (a misplaced `<?xml ...?>` declaration blanked out, byte offsets
/// unchanged), with the findings about the text itself. The pipeline parses its XML document once and
/// keeps it for the report's element paths.
pub struct UrdfText<'t> {
    text: std::borrow::Cow<'t, str>,
    findings: Vec<Finding>,
}

impl<'t> UrdfText<'t> {
    /// Prepare `text`.
    pub fn new(text: &'t str) -> Self {
        let mut prepared = match late_declaration(text) {
            Some((blanked, declaration)) => UrdfText {
                text: blanked.into(),
                findings: vec![Finding::new(
                    &rules::LATE_XML_DECLARATION,
                    declaration,
                    "whitespace before the <?xml ...?> declaration: urdfdom accepts it, strict XML parsers (xacro, Python's xml, lxml) refuse the file",
                )
                .with_help("delete everything before `<?xml`")
                // Only whitespace goes: the document is the same.
                .with_fix(Fix::safe(
                    "delete the whitespace before `<?xml`",
                    vec![Edit::Delete {
                        span: Span {
                            start: 0,
                            end: declaration.start,
                        },
                    }],
                ))],
            },
            None => UrdfText {
                text: text.into(),
                findings: Vec::new(),
            },
        };
        prepared.unbind_prefixes();
        prepared
    }

    /// Undeclared namespace prefixes (`<sensor:camera>` without `xmlns:sensor`), which urdfdom reads as
    /// unknown elements: their names rewritten in place (offsets unchanged), one finding per prefix.
    fn unbind_prefixes(&mut self) {
        let Some((rewritten, prefixes)) = rewrite_unbound_prefixes(&self.text) else {
            return;
        };
        for unbound in prefixes {
            let prefix = &unbound.prefix;
            self.findings.push(
                Finding::new(
                    &rules::UNBOUND_NAMESPACE_PREFIX,
                    unbound.span,
                    format!(
                        "namespace prefix `{prefix}:` is used without an `xmlns:{prefix}` declaration: urdfdom, Pinocchio and Gazebo read the file and skip its `{prefix}:` elements, namespace-aware XML tools (lxml, xacro, Python's xml.dom) refuse it; read here as unknown elements"
                    ),
                )
                .with_help(format!(
                    "declare the namespace on <robot> (`xmlns:{prefix}=\"...\"`) or drop the `{prefix}:` prefix"
                )),
            );
        }
        self.text = rewritten.into();
    }

    /// The XML document; an error names `path` and where the XML breaks.
    pub fn document(&self, path: &Path) -> Result<roxmltree::Document<'_>, LoadError> {
        roxmltree::Document::parse_with_options(&self.text, xml_options()).map_err(|e| {
            let pos = e.pos();
            let (line, column, message) = match e {
                // roxmltree points at the start of the document: what is missing is at its end.
                roxmltree::Error::UnclosedRootNode => {
                    let (line, column) = end_of(&self.text);
                    let message = "the root element is never closed (expected its end tag, \
                                   such as </robot>, at the end of the file)"
                        .to_string();
                    (line, column, message)
                }
                other => (pos.row, pos.col, other.to_string()),
            };
            LoadError::Xml {
                path: path.to_path_buf(),
                line,
                column,
                message,
            }
        })
    }

    /// The robot of `doc` (this text's [`document`](Self::document)) and every finding.
    pub fn parse(&self, doc: &roxmltree::Document) -> (Robot, Vec<Finding>) {
        let mut parser = Parser {
            findings: self.findings.clone(),
            ..Parser::default()
        };
        let robot = parser.robot(doc.root_element());
        (robot, parser.findings)
    }
}

/// The 1-based line and column (in characters) just past the last non-blank character of `text`.
fn end_of(text: &str) -> (u32, u32) {
    let content = text.trim_end();
    let line = content.matches('\n').count() + 1;
    let column = content.rsplit('\n').next().unwrap_or("").chars().count() + 1;
    (
        u32::try_from(line).unwrap_or(u32::MAX),
        u32::try_from(column).unwrap_or(u32::MAX),
    )
}

/// XML whitespace (the `S` production).
fn is_xml_space(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\r' | '\n')
}

/// When whitespace comes before the `<?xml ...?>` declaration, which XML forbids but TinyXML2 (urdfdom)
/// skips (`XMLDocument::Parse` calls `SkipWhiteSpace` before anything else): the text with the declaration
/// overwritten by spaces — every other byte, and so every line and column, unchanged — and the
/// declaration's span. roxmltree then reads the document as whitespace before the root element.
fn late_declaration(text: &str) -> Option<(String, Span)> {
    let body = text.trim_start_matches(is_xml_space);
    let start = text.len() - body.len();
    if start == 0 {
        return None;
    }
    let after = body.strip_prefix("<?xml")?;
    if !after.starts_with(|c: char| is_xml_space(c) || c == '?') {
        return None; // `<?xml-stylesheet ...?>` and the like are processing instructions.
    }
    let end = start + "<?xml".len() + after.find("?>")? + "?>".len();
    let mut blanked = String::with_capacity(text.len());
    blanked.push_str(text.get(..start)?);
    for c in text.get(start..end)?.chars() {
        if c == '\n' || c == '\r' {
            blanked.push(c);
        } else {
            // As many spaces as the character has bytes: byte offsets stay put.
            blanked.extend(std::iter::repeat_n(' ', c.len_utf8()));
        }
    }
    blanked.push_str(text.get(end..)?);
    Some((blanked, Span::from_range(start..end)))
}

/// `<robot version>` as urdfdom's `urdf_export_helpers::URDFVersion` reads it: exactly two `.`-separated
/// fields, each read by `strtol` (leading whitespace and a sign allowed, nothing after the digits, not
/// negative) and truncated to 32 bits. The error is urdfdom's message.
pub fn urdf_version(text: &str) -> Result<(u32, u32), &'static str> {
    // urdf::split_string: no empty field after a trailing separator.
    let mut fields: Vec<&str> = text.split('.').collect();
    if fields.last() == Some(&"") {
        fields.pop();
    }
    let [major, minor] = fields[..] else {
        return Err("The version attribute should be in the form 'x.y'");
    };
    Ok((version_field(major)?, version_field(minor)?))
}

fn version_field(field: &str) -> Result<u32, &'static str> {
    if field.is_empty() {
        return Err("One of the fields of the version attribute is blank");
    }
    // strtol: C isspace, then an optional sign, then decimal digits (saturating at the 64-bit LONG range).
    let body = field.trim_start_matches([' ', '\t', '\n', '\x0b', '\x0c', '\r']);
    let (negative, digits) = match body.as_bytes().first() {
        Some(b'-') => (true, &body[1..]),
        Some(b'+') => (false, &body[1..]),
        _ => (false, body),
    };
    let count = digits.bytes().take_while(u8::is_ascii_digit).count();
    if count == 0 {
        return Err("Version attribute is not an integer");
    }
    if count < digits.len() {
        return Err("Extra characters after the version number");
    }
    let magnitude = digits.bytes().fold(0i64, |acc, d| {
        acc.saturating_mul(10).saturating_add(i64::from(d - b'0'))
    });
    if negative && magnitude > 0 {
        return Err("Version number must be positive");
    }
    // urdfdom returns the `long` as uint32_t: truncation, as C++ does.
    Ok(magnitude as u32)
}

/// The URDF versions urdfdom reads: 1.0 (the default), 1.1 (urdfdom 5.1: `quat_xyzw`, capsules) and 1.2
/// (urdfdom 6.0: acceleration, deceleration and jerk limits).
const SUPPORTED_VERSIONS: [(u32, u32); 3] = [(1, 0), (1, 1), (1, 2)];

fn span(node: Node) -> Span {
    Span::from_range(node.range())
}

/// Where a finding about the whole robot points: the `name` of `<robot>`, else the tag's name (never the
/// whole element: an editor would underline the whole file).
fn robot_span(root: Node) -> Span {
    match root.attribute_node("name") {
        Some(name) => Span::from_range(name.range_value()),
        None => {
            let start = root.range().start;
            Span::from_range(start..start + 1 + root.tag_name().name().len())
        }
    }
}

/// Whether a `<gazebo>` block turns off fixed-joint lumping for its reference (sdformat's parser_urdf.cc
/// accepts `true`, `yes` or `1`, case-insensitive for the words).
fn keeps_fixed_joint(node: Node) -> bool {
    elements(node).any(|child| {
        matches!(
            child.tag_name().name(),
            "preserveFixedJoint" | "disableFixedJointLumping"
        ) && child.text().map(str::trim).is_some_and(|v| {
            v.eq_ignore_ascii_case("true") || v.eq_ignore_ascii_case("yes") || v == "1"
        })
    })
}

fn elements<'a, 'i>(node: Node<'a, 'i>) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(|n| n.is_element())
}

fn child<'a, 'i>(node: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    elements(node).find(|n| n.has_tag_name(tag))
}

fn is_xacro(node: Node) -> bool {
    node.tag_name()
        .namespace()
        .is_some_and(|ns| ns.contains("xacro"))
}

#[derive(Default)]
struct Parser {
    findings: Vec<Finding>,
    /// The declared URDF version's minor number (major is 1), which decides what urdfdom reads:
    /// `quat_xyzw` and `<capsule>` need 1.1.
    minor: u32,
}

impl Parser {
    fn push(&mut self, finding: Finding) {
        self.findings.push(finding);
    }

    /// INFO for attributes outside `allowed` (namespaced attributes are extensions and pass).
    fn check_attributes(&mut self, node: Node, allowed: &[&str], owner: &str) {
        for attr in node.attributes() {
            if attr.namespace().is_some() || allowed.contains(&attr.name()) {
                continue;
            }
            let tag = node.tag_name().name();
            self.push(Finding::new(
                &rules::UNKNOWN_ATTRIBUTE,
                Span::from_range(attr.range_qname()),
                format!("{owner}: unknown attribute '{}' on <{tag}>", attr.name()),
            ));
        }
    }

    /// INFO for child elements outside `allowed`.
    fn check_children(&mut self, node: Node, allowed: &[&str], owner: &str) {
        for element in elements(node) {
            if !(allowed.contains(&element.tag_name().name())
                && element.tag_name().namespace().is_none())
            {
                self.unknown_element(element, node, owner);
            }
        }
    }

    fn unknown_element(&mut self, element: Node, parent: Node, owner: &str) {
        let name = element.tag_name().name();
        let parent = parent.tag_name().name();
        let finding = if is_xacro(element) {
            Finding::new(
                &rules::UNKNOWN_ELEMENT,
                span(element),
                format!("{owner}: unexpanded xacro element <xacro:{name}> in <{parent}>"),
            )
            .with_help(
                "this file is xacro source: validate the .xacro file itself, or expand it first",
            )
        } else {
            Finding::new(
                &rules::UNKNOWN_ELEMENT,
                span(element),
                format!("{owner}: unknown element <{name}> in <{parent}>"),
            )
        };
        self.push(finding);
    }

    fn string(&mut self, node: Node, attr: &str) -> Option<Spanned<String>> {
        let a = node.attribute_node(attr)?;
        Some(Spanned {
            value: a.value().to_string(),
            span: Span::from_range(a.range_value()),
        })
    }

    fn required_string(&mut self, node: Node, attr: &str, owner: &str) -> Option<Spanned<String>> {
        let value = self.string(node, attr);
        if value.is_none() {
            self.missing(node, attr, owner);
        }
        value
    }

    fn missing(&mut self, node: Node, attr: &str, owner: &str) {
        let tag = node.tag_name().name();
        self.push(Finding::new(
            &rules::MISSING_ATTRIBUTE,
            span(node),
            format!("{owner}: <{tag}> has no '{attr}' attribute"),
        ));
    }

    /// `N` whitespace-separated numbers; `None` when absent or invalid (invalid gets a finding).
    fn numbers<const N: usize>(
        &mut self,
        node: Node,
        attr: &str,
        owner: &str,
    ) -> Option<Spanned<[f64; N]>> {
        let a = node.attribute_node(attr)?;
        let at = Span::from_range(a.range_value());
        let tag = node.tag_name().name();
        let mut values = [0.0; N];
        let mut words = a.value().split_whitespace();
        let mut ok = true;
        for slot in values.iter_mut() {
            match words.next().map(str::parse::<f64>) {
                Some(Ok(v)) => *slot = v,
                _ => ok = false,
            }
        }
        if !ok || words.next().is_some() {
            let expected = if N == 1 {
                "a number".to_string()
            } else {
                format!("{N} numbers")
            };
            self.push(Finding::new(
                &rules::INVALID_NUMBER,
                at,
                format!(
                    "{owner}: <{tag} {attr}=\"{}\"> is not {expected}",
                    a.value()
                ),
            ));
            return None;
        }
        if values.iter().any(|v| !v.is_finite()) {
            self.push(Finding::new(
                &rules::NON_FINITE_VALUE,
                at,
                format!("{owner}: <{tag} {attr}=\"{}\"> is not finite", a.value()),
            ));
        }
        Some(Spanned {
            value: values,
            span: at,
        })
    }

    fn number(&mut self, node: Node, attr: &str, owner: &str) -> Option<Spanned<f64>> {
        self.numbers::<1>(node, attr, owner).map(|s| Spanned {
            value: s.value[0],
            span: s.span,
        })
    }

    fn plain_number(&mut self, node: Node, attr: &str, owner: &str) -> Option<f64> {
        self.number(node, attr, owner).map(|s| s.value)
    }

    fn required_number(&mut self, node: Node, attr: &str, owner: &str) -> Option<f64> {
        if !node.has_attribute(attr) {
            self.missing(node, attr, owner);
        }
        self.plain_number(node, attr, owner)
    }

    fn robot(&mut self, root: Node) -> Robot {
        let mut robot = Robot {
            span: robot_span(root),
            ..Robot::default()
        };
        if !root.has_tag_name("robot") {
            self.push(Finding::new(
                &rules::NOT_A_ROBOT,
                span(root),
                format!(
                    "root element is <{}>, expected <robot>",
                    root.tag_name().name()
                ),
            ));
            return robot;
        }
        robot.name = self.required_string(root, "name", "robot");
        self.check_attributes(root, &["name", "version"], "robot");
        self.version(root);
        for node in elements(root) {
            let tag = node.tag_name();
            if tag.namespace().is_some() {
                if is_xacro(node) {
                    self.unknown_element(node, root, "robot");
                }
                continue; // Another tool's namespaced extension.
            }
            match tag.name() {
                "link" => robot.links.extend(self.link(node)),
                "joint" => robot.joints.extend(self.joint(node)),
                "material" => robot.materials.extend(self.material(node, "robot")),
                "transmission" => robot.transmissions.push(self.transmission(node)),
                "gazebo" => robot.gazebo.push(GazeboBlock {
                    span: span(node),
                    reference: self.string(node, "reference"),
                    keeps_fixed_joint: keeps_fixed_joint(node),
                }),
                "ros2_control" => robot.ros2_control.push(self.ros2_control(node)),
                _ => self.unknown_element(node, root, "robot"),
            }
        }
        robot
    }

    /// Read `<robot version>` as urdfdom does; an unreadable or unsupported version is U011 and the rest of
    /// the file is read with the newest syntax, so one wrong attribute does not cascade.
    fn version(&mut self, root: Node) {
        let Some(attr) = root.attribute_node("version") else {
            return; // urdfdom: no attribute means 1.0.
        };
        let at = Span::from_range(attr.range_value());
        let problem = match urdf_version(attr.value()) {
            Ok((major, minor)) if SUPPORTED_VERSIONS.contains(&(major, minor)) => {
                self.minor = minor;
                return;
            }
            Ok((major, minor)) => format!(
                "URDF version {major}.{minor} is not one urdfdom reads (1.0, 1.1, 1.2); it refuses the file"
            ),
            Err(why) => format!("urdfdom cannot read this version: {why}; it refuses the file"),
        };
        self.minor = SUPPORTED_VERSIONS.iter().map(|v| v.1).max().unwrap_or(0);
        self.push(
            Finding::new(
                &rules::UNSUPPORTED_URDF_VERSION,
                at,
                format!("robot: version=\"{}\": {problem}", attr.value()),
            )
            .with_help("write version=\"1.0\" (or drop it), \"1.1\" or \"1.2\""),
        );
    }

    /// An `<origin>` as urdfdom's `parsePoseInternal` reads it. From URDF 1.1 `quat_xyzw` gives the rotation
    /// and may not be combined with `rpy`; in a 1.0 file urdfdom ignores it (with a warning).
    fn pose(&mut self, node: Option<Node>, owner: &str) -> Pose {
        let Some(node) = node else {
            return Pose::default();
        };
        self.check_attributes(node, &["xyz", "rpy", "quat_xyzw"], owner);
        let xyz = self
            .numbers::<3>(node, "xyz", owner)
            .map_or([0.0; 3], |s| s.value);
        let rpy = self.numbers::<3>(node, "rpy", owner);
        let quat_xyzw = match node.attribute_node("quat_xyzw") {
            None => None,
            Some(attr) if self.minor < 1 => {
                self.push(
                    Finding::new(
                        &rules::UNKNOWN_ATTRIBUTE,
                        Span::from_range(attr.range_qname()),
                        format!(
                            "{owner}: quat_xyzw is URDF 1.1 and this file is version 1.0: urdfdom ignores it, so the origin is not rotated by it"
                        ),
                    )
                    .with_help("add version=\"1.1\" to <robot> (urdfdom 5.1 or later), or write the rotation as rpy"),
                );
                None
            }
            Some(attr) => {
                if rpy.is_some() {
                    self.push(
                        Finding::new(
                            &rules::UNSUPPORTED_URDF_VERSION,
                            Span::from_range(attr.range_qname()),
                            format!(
                                "{owner}: <origin> gives both rpy and quat_xyzw; urdfdom refuses the file"
                            ),
                        )
                        .with_help("keep one of the two (quat_xyzw is used here)"),
                    );
                }
                self.numbers::<4>(node, "quat_xyzw", owner).map(|s| s.value)
            }
        };
        let value = |name: &str| {
            node.attribute_node(name)
                .map(|a| Span::from_range(a.range_value()))
        };
        Pose {
            xyz,
            rpy: rpy.map_or([0.0; 3], |s| s.value),
            quat_xyzw,
            span: Some(span(node)),
            values: PoseValues {
                xyz: value("xyz"),
                rpy: value("rpy"),
                quat_xyzw: value("quat_xyzw"),
            },
        }
    }

    fn link(&mut self, node: Node) -> Option<Link> {
        let name = self.required_string(node, "name", "link")?;
        let owner = format!("Link '{}'", name.value);
        self.check_attributes(node, &["name", "type"], &owner);
        self.check_children(node, &["inertial", "visual", "collision"], &owner);
        let inertial = child(node, "inertial").map(|n| self.inertial(n, &owner));
        let visuals = elements(node)
            .filter(|n| n.has_tag_name("visual"))
            .map(|n| self.shape(n, &owner, true))
            .collect();
        let collisions = elements(node)
            .filter(|n| n.has_tag_name("collision"))
            .map(|n| self.shape(n, &owner, false))
            .collect();
        Some(Link {
            name,
            span: span(node),
            inertial,
            visuals,
            collisions,
        })
    }

    fn inertial(&mut self, node: Node, owner: &str) -> Inertial {
        self.check_children(node, &["origin", "mass", "inertia"], owner);
        let origin = self.pose(child(node, "origin"), owner);
        let mass = match child(node, "mass") {
            Some(m) => {
                self.check_attributes(m, &["value"], owner);
                if !m.has_attribute("value") {
                    self.missing(m, "value", owner);
                }
                self.number(m, "value", owner)
            }
            None => {
                self.push(Finding::new(
                    &rules::MISSING_ATTRIBUTE,
                    span(node),
                    format!("{owner}: <inertial> has no <mass>"),
                ));
                None
            }
        };
        let inertia = match child(node, "inertia") {
            Some(i) => self.inertia(i, owner),
            None => {
                self.push(Finding::new(
                    &rules::MISSING_ATTRIBUTE,
                    span(node),
                    format!("{owner}: <inertial> has no <inertia>"),
                ));
                None
            }
        };
        Inertial {
            span: span(node),
            origin,
            mass,
            inertia,
        }
    }

    fn inertia(&mut self, node: Node, owner: &str) -> Option<Inertia> {
        const NAMES: [&str; 6] = ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"];
        self.check_attributes(node, &NAMES, owner);
        let mut v = [0.0; 6];
        let mut complete = true;
        for (slot, attr) in v.iter_mut().zip(NAMES) {
            match self.required_number(node, attr, owner) {
                Some(x) => *slot = x,
                None => complete = false,
            }
        }
        let values = NAMES.map(|name| {
            node.attribute_node(name)
                .map_or_else(|| span(node), |a| Span::from_range(a.range_value()))
        });
        complete.then_some(Inertia {
            span: span(node),
            values,
            ixx: v[0],
            ixy: v[1],
            ixz: v[2],
            iyy: v[3],
            iyz: v[4],
            izz: v[5],
        })
    }

    fn shape(&mut self, node: Node, owner: &str, visual: bool) -> Shape {
        let tag = if visual { "visual" } else { "collision" };
        let allowed: &[&str] = if visual {
            &["origin", "geometry", "material"]
        } else {
            &["origin", "geometry", "verbose"]
        };
        self.check_children(node, allowed, owner);
        self.check_attributes(node, &["name"], owner);
        let geometry = match child(node, "geometry") {
            Some(g) => self.geometry(g, owner),
            None => {
                self.push(Finding::new(
                    &rules::MISSING_GEOMETRY,
                    span(node),
                    format!("{owner}: <{tag}> has no <geometry>"),
                ));
                None
            }
        };
        let material = if visual {
            child(node, "material").map(|m| self.material_ref(m, owner))
        } else {
            None
        };
        Shape {
            span: span(node),
            name: node.attribute("name").map(str::to_string),
            origin: self.pose(child(node, "origin"), owner),
            geometry,
            material,
        }
    }

    fn geometry(&mut self, node: Node, owner: &str) -> Option<Spanned<Geometry>> {
        let shapes: Vec<Node> = elements(node).collect();
        let Some(&shape) = shapes.first() else {
            self.push(Finding::new(
                &rules::MISSING_GEOMETRY,
                span(node),
                format!("{owner}: <geometry> holds no shape"),
            ));
            return None;
        };
        for extra in shapes.iter().skip(1) {
            self.unknown_element(*extra, node, owner);
        }
        let at = span(shape);
        let geometry = match shape.tag_name().name() {
            "box" => {
                self.check_attributes(shape, &["size"], owner);
                if !shape.has_attribute("size") {
                    self.missing(shape, "size", owner);
                }
                Geometry::Box {
                    size: self.numbers::<3>(shape, "size", owner)?.value,
                }
            }
            "cylinder" | "capsule" => {
                self.check_attributes(shape, &["radius", "length"], owner);
                let radius = self.required_number(shape, "radius", owner);
                let length = self.required_number(shape, "length", owner);
                let (radius, length) = (radius?, length?);
                if shape.has_tag_name("cylinder") {
                    Geometry::Cylinder { radius, length }
                } else {
                    if self.minor < 1 {
                        self.push(
                            Finding::new(
                                &rules::UNSUPPORTED_URDF_VERSION,
                                at,
                                format!(
                                    "{owner}: <capsule> is URDF 1.1 and this file is version 1.0: urdfdom refuses the file"
                                ),
                            )
                            .with_help("add version=\"1.1\" to <robot> (urdfdom 5.1 or later)"),
                        );
                    }
                    Geometry::Capsule { radius, length }
                }
            }
            "sphere" => {
                self.check_attributes(shape, &["radius"], owner);
                Geometry::Sphere {
                    radius: self.required_number(shape, "radius", owner)?,
                }
            }
            "mesh" => {
                self.check_attributes(shape, &["filename", "scale"], owner);
                let filename = self.required_string(shape, "filename", owner)?;
                let scale = self
                    .numbers::<3>(shape, "scale", owner)
                    .map_or([1.0; 3], |s| s.value);
                Geometry::Mesh { filename, scale }
            }
            _ => {
                self.push(Finding::new(
                    &rules::MISSING_GEOMETRY,
                    at,
                    format!(
                        "{owner}: <{}> is not a URDF shape (box, cylinder, sphere, mesh, capsule)",
                        shape.tag_name().name()
                    ),
                ));
                return None;
            }
        };
        Some(Spanned {
            value: geometry,
            span: at,
        })
    }

    fn material_ref(&mut self, node: Node, owner: &str) -> MaterialRef {
        self.check_attributes(node, &["name"], owner);
        self.check_children(node, &["color", "texture"], owner);
        let defines_appearance = child(node, "color").is_some() || child(node, "texture").is_some();
        if let Some(color) = child(node, "color") {
            self.numbers::<4>(color, "rgba", owner);
        }
        MaterialRef {
            span: span(node),
            name: node.attribute("name").map(str::to_string),
            defines_appearance,
        }
    }

    fn material(&mut self, node: Node, owner: &str) -> Option<Material> {
        let name = self.required_string(node, "name", owner)?;
        let owner = format!("Material '{}'", name.value);
        self.check_attributes(node, &["name"], &owner);
        self.check_children(node, &["color", "texture"], &owner);
        let rgba = child(node, "color")
            .and_then(|c| self.numbers::<4>(c, "rgba", &owner))
            .map(|s| s.value);
        let texture = child(node, "texture")
            .and_then(|t| t.attribute("filename"))
            .map(str::to_string);
        Some(Material {
            name,
            rgba,
            texture,
        })
    }

    fn joint(&mut self, node: Node) -> Option<Joint> {
        let name = self.required_string(node, "name", "joint")?;
        let owner = format!("Joint '{}'", name.value);
        self.check_attributes(node, &["name", "type"], &owner);
        self.check_children(
            node,
            &[
                "origin",
                "parent",
                "child",
                "axis",
                "limit",
                "dynamics",
                "mimic",
                "safety_controller",
                "calibration",
            ],
            &owner,
        );
        let kind = match self.required_string(node, "type", &owner) {
            Some(text) => match JointKind::parse(&text.value) {
                Some(kind) => Some(Spanned {
                    value: kind,
                    span: text.span,
                }),
                None => {
                    self.push(Finding::new(
                        &rules::UNKNOWN_JOINT_TYPE,
                        text.span,
                        format!("{owner}: type '{}' is not a URDF joint type", text.value),
                    ));
                    None
                }
            },
            None => None,
        };
        let link_ref = |p: &mut Self, tag: &str| match child(node, tag) {
            Some(n) => {
                p.check_attributes(n, &["link"], &owner);
                p.required_string(n, "link", &owner)
            }
            None => {
                p.push(Finding::new(
                    &rules::MISSING_ATTRIBUTE,
                    span(node),
                    format!("{owner}: no <{tag} link=...>"),
                ));
                None
            }
        };
        let parent = link_ref(self, "parent");
        let child_link = link_ref(self, "child");
        let axis = child(node, "axis").and_then(|a| {
            self.check_attributes(a, &["xyz"], &owner);
            self.numbers::<3>(a, "xyz", &owner)
        });
        let limit = child(node, "limit").map(|l| {
            self.check_attributes(
                l,
                &[
                    "lower",
                    "upper",
                    "effort",
                    "velocity",
                    "acceleration",
                    "deceleration",
                    "jerk",
                ],
                &owner,
            );
            Limit {
                span: span(l),
                lower: self.number(l, "lower", &owner),
                upper: self.number(l, "upper", &owner),
                effort: self.number(l, "effort", &owner),
                velocity: self.number(l, "velocity", &owner),
            }
        });
        let dynamics = child(node, "dynamics").map(|d| {
            self.check_attributes(d, &["damping", "friction"], &owner);
            Dynamics {
                damping: self.plain_number(d, "damping", &owner),
                friction: self.plain_number(d, "friction", &owner),
            }
        });
        let mimic = child(node, "mimic").and_then(|m| {
            self.check_attributes(m, &["joint", "multiplier", "offset"], &owner);
            Some(Mimic {
                span: span(m),
                joint: self.required_string(m, "joint", &owner)?,
                multiplier: self.plain_number(m, "multiplier", &owner).unwrap_or(1.0),
                offset: self.plain_number(m, "offset", &owner).unwrap_or(0.0),
            })
        });
        let safety_controller = child(node, "safety_controller").map(|s| {
            self.check_attributes(
                s,
                &[
                    "soft_lower_limit",
                    "soft_upper_limit",
                    "k_position",
                    "k_velocity",
                ],
                &owner,
            );
            SafetyController {
                soft_lower_limit: self.plain_number(s, "soft_lower_limit", &owner),
                soft_upper_limit: self.plain_number(s, "soft_upper_limit", &owner),
                k_position: self.plain_number(s, "k_position", &owner),
                k_velocity: self.plain_number(s, "k_velocity", &owner),
            }
        });
        let calibration = child(node, "calibration").map(|c| {
            self.check_attributes(c, &["rising", "falling", "reference_position"], &owner);
            Calibration {
                rising: self.plain_number(c, "rising", &owner),
                falling: self.plain_number(c, "falling", &owner),
                reference_position: self.plain_number(c, "reference_position", &owner),
            }
        });
        Some(Joint {
            origin: self.pose(child(node, "origin"), &owner),
            name,
            span: span(node),
            kind,
            parent,
            child: child_link,
            axis,
            limit,
            dynamics,
            mimic,
            safety_controller,
            calibration,
        })
    }

    /// Both formats: `<transmission type="...">` with `<joint name>` (old, PR2 also uses `<flexJoint>`,
    /// `<rollJoint>`, ...) and `<type>` + `<joint name>` (ROS control). Contents are otherwise opaque.
    fn transmission(&mut self, node: Node) -> Transmission {
        let kind = node.attribute("type").map(str::to_string).or_else(|| {
            child(node, "type")
                .and_then(|t| t.text())
                .map(|t| t.trim().to_string())
        });
        let joints = elements(node)
            .filter(|n| n.tag_name().name().to_ascii_lowercase().contains("joint"))
            .filter_map(|n| self.string(n, "name"))
            .collect();
        Transmission {
            name: node.attribute("name").map(str::to_string),
            span: span(node),
            kind,
            joints,
        }
    }

    fn ros2_control(&mut self, node: Node) -> Ros2Control {
        let joints = elements(node)
            .filter(|n| n.has_tag_name("joint"))
            .filter_map(|n| self.string(n, "name"))
            .collect();
        Ros2Control {
            name: node.attribute("name").map(str::to_string),
            span: span(node),
            joints,
        }
    }
}
