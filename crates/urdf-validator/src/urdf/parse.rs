//! XML → [`Robot`]: a tolerant parser over roxmltree that keeps the span of every value and collects
//! findings instead of stopping at the first problem.

use std::path::Path;

use roxmltree::Node;

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::input::source::{Span, Spanned};
use crate::input::LoadError;
use crate::urdf::robot::*;

/// Largest number of XML nodes accepted.
const MAX_NODES: u32 = 5_000_000;

/// Parse URDF text. `path` is only used in error messages.
pub fn parse_urdf(text: &str, path: &Path) -> Result<(Robot, Vec<Finding>), LoadError> {
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        nodes_limit: MAX_NODES,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(text, options).map_err(|e| {
        let pos = e.pos();
        LoadError::Xml {
            path: path.to_path_buf(),
            line: pos.row,
            column: pos.col,
            message: e.to_string(),
        }
    })?;
    let mut parser = Parser::default();
    let robot = parser.robot(doc.root_element());
    Ok((robot, parser.findings))
}

fn span(node: Node) -> Span {
    Span::from_range(node.range())
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
            span: span(root),
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
                }),
                "ros2_control" => robot.ros2_control.push(self.ros2_control(node)),
                _ => self.unknown_element(node, root, "robot"),
            }
        }
        robot
    }

    fn pose(&mut self, node: Option<Node>, owner: &str) -> Pose {
        let Some(node) = node else {
            return Pose::default();
        };
        self.check_attributes(node, &["xyz", "rpy"], owner);
        Pose {
            xyz: self
                .numbers::<3>(node, "xyz", owner)
                .map_or([0.0; 3], |s| s.value),
            rpy: self
                .numbers::<3>(node, "rpy", owner)
                .map_or([0.0; 3], |s| s.value),
            span: Some(span(node)),
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
        complete.then_some(Inertia {
            span: span(node),
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
                        "{owner}: <{}> is not a URDF shape (box, cylinder, sphere, mesh)",
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
