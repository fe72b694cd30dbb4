//! COLLADA: the positions its visual scene instantiates, with node transforms, unit and up axis.

use std::collections::HashMap;
use std::sync::Arc;

use nalgebra::{Matrix4, Rotation3, Unit, Vector3};
use roxmltree::{Document, Node};

use super::{
    number, shown, ColladaUpAxis, MeshOptions, RawMesh, UpAxisPolicy, VertexSink,
    MAX_INSTANCED_PER_BYTE, MAX_NODE_DEPTH, MAX_NODE_INSTANCES, MAX_VERTICES,
    MIN_INSTANCED_VERTICES,
};

/// Largest number of XML nodes accepted in a COLLADA file.
const MAX_XML_NODES: u32 = 5_000_000;

impl ColladaUpAxis {
    /// The rotation that takes this axis to +Z (right-handed, a proper rotation).
    fn to_z_up(self) -> Matrix4<f64> {
        #[rustfmt::skip]
        let m = match self {
            ColladaUpAxis::X => Matrix4::new(
                0.0, -1.0, 0.0, 0.0,
                0.0, 0.0, -1.0, 0.0,
                1.0, 0.0, 0.0, 0.0,
                0.0, 0.0, 0.0, 1.0,
            ),
            ColladaUpAxis::Y => Matrix4::new(
                1.0, 0.0, 0.0, 0.0,
                0.0, 0.0, -1.0, 0.0,
                0.0, 1.0, 0.0, 0.0,
                0.0, 0.0, 0.0, 1.0,
            ),
            ColladaUpAxis::Z => Matrix4::identity(),
        };
        m
    }
}

/// A geometry's positions in file units, and its triangle count.
struct Geometry {
    positions: Vec<[f64; 3]>,
    triangles: usize,
}

struct Collada<'a, 'input> {
    doc: &'a Document<'input>,
    ids: HashMap<&'a str, Node<'a, 'input>>,
    geometries: HashMap<&'a str, Arc<Geometry>>,
    sink: VertexSink,
    triangles: usize,
    instances: usize,
}

pub(super) fn parse_dae(bytes: &[u8], options: &MeshOptions) -> Result<RawMesh, String> {
    if bytes.is_empty() {
        return Err("empty file (expected COLLADA XML)".to_string());
    }
    let text = std::str::from_utf8(bytes).map_err(|e| {
        format!(
            "byte offset {}: not UTF-8 (expected COLLADA XML in UTF-8)",
            e.valid_up_to()
        )
    })?;
    let parsing = roxmltree::ParsingOptions {
        allow_dtd: true,
        nodes_limit: MAX_XML_NODES,
        ..Default::default()
    };
    let doc = Document::parse_with_options(text, parsing).map_err(|e| {
        let pos = e.pos();
        format!("line {}, column {}: invalid XML: {e}", pos.row, pos.col)
    })?;
    let root = doc.root_element();
    if root.tag_name().name() != "COLLADA" {
        return Err(format!(
            "line {}: expected a <COLLADA> root element, found <{}>",
            line_of(&doc, root),
            root.tag_name().name()
        ));
    }
    let mut c = Collada {
        doc: &doc,
        ids: HashMap::new(),
        geometries: HashMap::new(),
        sink: VertexSink {
            limit: bytes
                .len()
                .saturating_mul(MAX_INSTANCED_PER_BYTE)
                .clamp(MIN_INSTANCED_VERTICES, MAX_VERTICES),
            ..VertexSink::default()
        },
        triangles: 0,
        instances: 0,
    };
    for node in root.descendants().filter(|n| n.is_element()) {
        if let Some(id) = node.attribute("id") {
            c.ids.entry(id).or_insert(node);
        }
    }

    let (unit, declared_up_axis) = c.asset(root)?;
    let mut top = Matrix4::new_scaling(unit);
    if let (Some(axis), UpAxisPolicy::Honour) = (declared_up_axis, options.up_axis) {
        top = axis.to_z_up() * top;
    }

    match c.scene(root)? {
        Some(scene) => {
            for node in elements(scene).filter(|n| tag(*n) == "node") {
                c.node(node, &top, 1)?;
            }
        }
        None => {
            // No visual scene: every geometry, untransformed (unit and up axis still apply).
            let geometries: Vec<Node> = root
                .descendants()
                .filter(|n| n.is_element() && tag(*n) == "geometry")
                .collect();
            for geometry in geometries {
                c.instantiate(geometry, &top)?;
            }
        }
    }
    let triangles = c.triangles;
    Ok(RawMesh {
        vertices: c
            .sink
            .finish("COLLADA <mesh> positions instantiated by the visual scene")?,
        triangles,
        declared_up_axis,
        binary_stl: false,
        faces: None,
    })
}

fn tag<'a>(node: Node<'a, '_>) -> &'a str {
    node.tag_name().name()
}

fn elements<'a, 'i>(node: Node<'a, 'i>) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(|n| n.is_element())
}

fn child<'a, 'i>(node: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    elements(node).find(|n| tag(*n) == name)
}

fn line_of(doc: &Document, node: Node) -> u32 {
    doc.text_pos_at(node.range().start).row
}

/// The element's text as numbers (at most `limit` of them: the rest is not read), each finite; errors
/// give the line of the offending token.
fn floats(doc: &Document, node: Node, limit: usize) -> Result<Vec<f64>, String> {
    let Some(text_node) = node.first_child().filter(|n| n.is_text()) else {
        return Ok(Vec::new());
    };
    let text = text_node.text().unwrap_or("");
    let base = text_node.range().start;
    let mut out = Vec::new();
    for token in text.split_ascii_whitespace().take(limit) {
        match number(token.as_bytes()) {
            Some(v) => out.push(v),
            None => {
                // Offsets in the text are offsets in the file only when the text is the file's bytes
                // as they are: entity and character references change its length (and an entity's
                // text lies in the DTD), so then the element's position is given instead.
                let offset = token.as_ptr() as usize - text.as_ptr() as usize;
                let verbatim = doc.input_text().get(text_node.range()) == Some(text);
                let pos = doc.text_pos_at(if verbatim {
                    base + offset
                } else {
                    node.range().start
                });
                return Err(format!(
                    "line {}, column {}: expected a finite number in <{}>, found '{}'",
                    pos.row,
                    pos.col,
                    tag(node),
                    shown(token.as_bytes())
                ));
            }
        }
    }
    Ok(out)
}

/// Exactly `n` numbers from an element (transforms, bind_shape_matrix).
fn fixed_floats(doc: &Document, node: Node, n: usize) -> Result<Vec<f64>, String> {
    let values = floats(doc, node, n + 1)?;
    if values.len() != n {
        return Err(format!(
            "line {}: expected {n} numbers in <{}>, found {}",
            line_of(doc, node),
            tag(node),
            values.len()
        ));
    }
    Ok(values)
}

/// A non-negative integer attribute (absent → `default`).
fn usize_attr(doc: &Document, node: Node, name: &str, default: usize) -> Result<usize, String> {
    match node.attribute(name) {
        None => Ok(default),
        Some(text) => text.trim().parse::<usize>().map_err(|_| {
            format!(
                "line {}: expected a non-negative integer for <{} {name}>, found '{}'",
                line_of(doc, node),
                tag(node),
                shown(text.as_bytes())
            )
        }),
    }
}

/// Whitespace-separated tokens in an element's text.
fn token_count(node: Node) -> usize {
    node.text()
        .map(|t| t.split_ascii_whitespace().count())
        .unwrap_or(0)
}

impl<'a, 'input> Collada<'a, 'input> {
    /// `<asset><unit meter>` (default 1) and `<asset><up_axis>` (absent → `None`, no rotation).
    fn asset(&self, root: Node<'a, 'input>) -> Result<(f64, Option<ColladaUpAxis>), String> {
        let Some(asset) = child(root, "asset") else {
            return Ok((1.0, None));
        };
        let mut unit = 1.0;
        if let Some(node) = child(asset, "unit") {
            if let Some(text) = node.attribute("meter") {
                unit = text
                    .trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite() && *v > 0.0)
                    .ok_or_else(|| {
                        format!(
                            "line {}: expected a positive number for <unit meter>, found '{}'",
                            line_of(self.doc, node),
                            shown(text.as_bytes())
                        )
                    })?;
            }
        }
        let up = match child(asset, "up_axis") {
            None => None,
            Some(node) => match node.text().unwrap_or("").trim() {
                "X_UP" => Some(ColladaUpAxis::X),
                "Y_UP" => Some(ColladaUpAxis::Y),
                "Z_UP" => Some(ColladaUpAxis::Z),
                other => {
                    return Err(format!(
                        "line {}: expected X_UP, Y_UP or Z_UP in <up_axis>, found '{}'",
                        line_of(self.doc, node),
                        shown(other.as_bytes())
                    ))
                }
            },
        };
        Ok((unit, up))
    }

    /// The visual scene to instantiate: the one `<scene><instance_visual_scene url>` names, else the
    /// first `<visual_scene>`, else none.
    fn scene(&self, root: Node<'a, 'input>) -> Result<Option<Node<'a, 'input>>, String> {
        if let Some(instance) = child(root, "scene").and_then(|s| child(s, "instance_visual_scene"))
        {
            return self.target(instance, "url", "visual_scene").map(Some);
        }
        Ok(root
            .descendants()
            .find(|n| n.is_element() && tag(*n) == "visual_scene"))
    }

    /// The element a `#id` reference in attribute `attr` of `from` points to, which must be a `<kind>`.
    fn target(&self, from: Node, attr: &str, kind: &str) -> Result<Node<'a, 'input>, String> {
        let line = || line_of(self.doc, from);
        let name = tag(from);
        let Some(url) = from.attribute(attr) else {
            return Err(format!(
                "line {}: <{name}> has no '{attr}' attribute",
                line()
            ));
        };
        let Some(id) = url.strip_prefix('#') else {
            return Err(format!(
                "line {}: <{name} {attr}=\"{}\">: only references inside the file ('#id') are supported",
                line(),
                shown(url.as_bytes())
            ));
        };
        let Some(&node) = self.ids.get(id) else {
            return Err(format!(
                "line {}: <{name} {attr}=\"{}\">: no element with id '{}'",
                line(),
                shown(url.as_bytes()),
                shown(id.as_bytes())
            ));
        };
        if tag(node) != kind {
            return Err(format!(
                "line {}: <{name} {attr}=\"{}\"> points to a <{}> (line {}), expected a <{kind}>",
                line(),
                shown(url.as_bytes()),
                tag(node),
                line_of(self.doc, node)
            ));
        }
        Ok(node)
    }

    /// Instantiate `node` under `parent` (the transform to metres, Z up, of its parent frame).
    fn node(
        &mut self,
        node: Node<'a, 'input>,
        parent: &Matrix4<f64>,
        depth: usize,
    ) -> Result<(), String> {
        if depth > MAX_NODE_DEPTH {
            return Err(format!(
                "line {}: node hierarchy deeper than {MAX_NODE_DEPTH} levels (an <instance_node> cycle?)",
                line_of(self.doc, node)
            ));
        }
        self.instances += 1;
        if self.instances > MAX_NODE_INSTANCES {
            return Err(format!(
                "line {}: more than {MAX_NODE_INSTANCES} node instances (limit)",
                line_of(self.doc, node)
            ));
        }
        let mut m = *parent;
        for t in elements(node) {
            m *= match tag(t) {
                "matrix" => {
                    let v = fixed_floats(self.doc, t, 16)?;
                    Matrix4::from_row_slice(&v)
                }
                "translate" => {
                    let v = fixed_floats(self.doc, t, 3)?;
                    Matrix4::new_translation(&Vector3::new(v[0], v[1], v[2]))
                }
                "rotate" => {
                    let v = fixed_floats(self.doc, t, 4)?;
                    match Unit::try_new(Vector3::new(v[0], v[1], v[2]), f64::MIN_POSITIVE) {
                        Some(axis) => {
                            Rotation3::from_axis_angle(&axis, v[3].to_radians()).to_homogeneous()
                        }
                        None => Matrix4::identity(),
                    }
                }
                "scale" => {
                    let v = fixed_floats(self.doc, t, 3)?;
                    Matrix4::new_nonuniform_scaling(&Vector3::new(v[0], v[1], v[2]))
                }
                "lookat" => {
                    let v = fixed_floats(self.doc, t, 9)?;
                    look_at(&v)
                }
                // <skew> is not supported (practically unused); other children are not transforms.
                _ => continue,
            };
        }
        for item in elements(node) {
            match tag(item) {
                "node" => self.node(item, &m, depth + 1)?,
                "instance_node" => {
                    let target = self.target(item, "url", "node")?;
                    self.node(target, &m, depth + 1)?;
                }
                "instance_geometry" => {
                    let geometry = self.target(item, "url", "geometry")?;
                    self.instantiate(geometry, &m)?;
                }
                "instance_controller" => self.controller(item, &m)?,
                _ => {}
            }
        }
        Ok(())
    }

    /// `<instance_controller>` → `<controller><skin source="#geometry">` (with its
    /// `<bind_shape_matrix>`) or `<morph source="#geometry">`.
    fn controller(&mut self, item: Node<'a, 'input>, m: &Matrix4<f64>) -> Result<(), String> {
        let controller = self.target(item, "url", "controller")?;
        if let Some(skin) = child(controller, "skin") {
            let geometry = self.target(skin, "source", "geometry")?;
            let bind = match child(skin, "bind_shape_matrix") {
                Some(b) => Matrix4::from_row_slice(&fixed_floats(self.doc, b, 16)?),
                None => Matrix4::identity(),
            };
            self.instantiate(geometry, &(m * bind))
        } else if let Some(morph) = child(controller, "morph") {
            let geometry = self.target(morph, "source", "geometry")?;
            self.instantiate(geometry, m)
        } else {
            Ok(())
        }
    }

    /// Add the positions of `geometry`, transformed by `m`, and its triangles.
    fn instantiate(&mut self, geometry: Node<'a, 'input>, m: &Matrix4<f64>) -> Result<(), String> {
        let Some(data) = self.geometry(geometry)? else {
            return Ok(());
        };
        // The affine part (COLLADA transforms are affine), in plain arithmetic for unoptimised builds.
        let row = |r: usize| [m[(r, 0)], m[(r, 1)], m[(r, 2)], m[(r, 3)]];
        let rows = [row(0), row(1), row(2)];
        for p in &data.positions {
            let q = rows.map(|r| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3]);
            self.sink.push(q).map_err(|e| {
                format!(
                    "line {}: geometry instantiated by the visual scene: {e}",
                    line_of(self.doc, geometry)
                )
            })?;
        }
        self.triangles = self.triangles.saturating_add(data.triangles);
        Ok(())
    }

    /// A `<geometry>`'s `<mesh>` (parsed once); `None` for other geometry kinds (splines…).
    fn geometry(&mut self, geometry: Node<'a, 'input>) -> Result<Option<Arc<Geometry>>, String> {
        let key = geometry.attribute("id").unwrap_or("");
        if !key.is_empty() {
            if let Some(data) = self.geometries.get(key) {
                return Ok(Some(Arc::clone(data)));
            }
        }
        let Some(mesh) = child(geometry, "mesh") else {
            return Ok(None);
        };
        let data = Arc::new(Geometry {
            positions: self.positions(mesh)?,
            triangles: self.mesh_triangles(mesh)?,
        });
        if !key.is_empty() {
            self.geometries.insert(key, Arc::clone(&data));
        }
        Ok(Some(data))
    }

    /// `<vertices><input semantic="POSITION" source="#…">` → `<source>` → accessor → float_array.
    fn positions(&self, mesh: Node<'a, 'input>) -> Result<Vec<[f64; 3]>, String> {
        let input = child(mesh, "vertices")
            .and_then(|v| {
                elements(v).find(|i| tag(*i) == "input" && i.attribute("semantic") == Some("POSITION"))
            })
            .ok_or_else(|| {
                format!(
                    "line {}: <mesh> has no <vertices><input semantic=\"POSITION\"> (expected vertex positions)",
                    line_of(self.doc, mesh)
                )
            })?;
        let source = self.target(input, "source", "source")?;
        let accessor = child(source, "technique_common").and_then(|t| child(t, "accessor"));
        let array = match accessor {
            Some(a) if a.attribute("source").is_some() => {
                self.target(a, "source", "float_array")?
            }
            _ => child(source, "float_array").ok_or_else(|| {
                format!(
                    "line {}: POSITION <source> has no <float_array>",
                    line_of(self.doc, source)
                )
            })?,
        };
        let (count, stride, offset, slots, values) = match accessor {
            Some(a) => {
                let stride = usize_attr(self.doc, a, "stride", 1)?;
                let offset = usize_attr(self.doc, a, "offset", 0)?;
                let count = usize_attr(self.doc, a, "count", 0)?;
                let params: Vec<Node> = elements(a).filter(|p| tag(*p) == "param").collect();
                let slots: Vec<usize> = if params.is_empty() {
                    vec![0, 1, 2]
                } else {
                    params
                        .iter()
                        .enumerate()
                        .filter(|(_, p)| p.attribute("name").is_some_and(|n| !n.is_empty()))
                        .map(|(i, _)| i)
                        .take(3)
                        .collect()
                };
                if slots.len() < 3 || slots.iter().any(|&s| s >= stride) {
                    return Err(format!(
                        "line {}: POSITION <accessor> must bind 3 named params within its stride {stride}",
                        line_of(self.doc, a)
                    ));
                }
                if count > MAX_VERTICES {
                    return Err(format!(
                        "line {}: POSITION <accessor> count {count} is more than {MAX_VERTICES} vertices (limit)",
                        line_of(self.doc, a)
                    ));
                }
                // Only the numbers the accessor reads are parsed.
                let needed = count
                    .saturating_sub(1)
                    .saturating_mul(stride)
                    .saturating_add(offset)
                    .saturating_add(stride);
                let values = floats(self.doc, array, needed)?;
                (count, stride, offset, slots, values)
            }
            None => {
                let values = floats(self.doc, array, 3 * MAX_VERTICES + 1)?;
                if values.len() > 3 * MAX_VERTICES {
                    return Err(format!(
                        "line {}: POSITION <float_array> holds more than {MAX_VERTICES} vertices (limit)",
                        line_of(self.doc, array)
                    ));
                }
                (values.len() / 3, 3, 0, vec![0, 1, 2], values)
            }
        };
        if count == 0 {
            return Ok(Vec::new());
        }
        let last = (count - 1)
            .checked_mul(stride)
            .and_then(|n| n.checked_add(offset))
            .and_then(|n| n.checked_add(slots[2].max(slots[1]).max(slots[0])));
        if last.is_none_or(|n| n >= values.len()) {
            return Err(format!(
                "line {}: accessor reads {count} points with stride {stride} from offset {offset}, \
                 but the <float_array> (line {}) has {} numbers",
                line_of(self.doc, accessor.unwrap_or(source)),
                line_of(self.doc, array),
                token_count(array)
            ));
        }
        Ok((0..count)
            .map(|i| {
                let at = offset + i * stride;
                [
                    values[at + slots[0]],
                    values[at + slots[1]],
                    values[at + slots[2]],
                ]
            })
            .collect())
    }

    /// Triangles of a `<mesh>`'s primitives: `<triangles count>`, `<polylist>` `<vcount>`,
    /// `<polygons>`/`<trifans>`/`<tristrips>` `<p>` lengths; lines count none.
    fn mesh_triangles(&self, mesh: Node<'a, 'input>) -> Result<usize, String> {
        let mut total = 0usize;
        for prim in elements(mesh) {
            let n = match tag(prim) {
                "triangles" => usize_attr(self.doc, prim, "count", 0)?,
                "polylist" => match child(prim, "vcount") {
                    Some(vcount) => {
                        let mut sum = 0usize;
                        for token in vcount.text().unwrap_or("").split_ascii_whitespace() {
                            let k = token.parse::<usize>().map_err(|_| {
                                format!(
                                    "line {}: expected a vertex count in <vcount>, found '{}'",
                                    line_of(self.doc, vcount),
                                    shown(token.as_bytes())
                                )
                            })?;
                            sum = sum.saturating_add(k.saturating_sub(2));
                        }
                        sum
                    }
                    None => 0,
                },
                "polygons" | "trifans" | "tristrips" => {
                    let stride = self.input_stride(prim)?;
                    let mut sum = 0usize;
                    let ps = elements(prim).flat_map(|c| match tag(c) {
                        "p" => vec![c],
                        // polygons with holes: the outer boundary.
                        "ph" => child(c, "p").into_iter().collect(),
                        _ => Vec::new(),
                    });
                    for p in ps {
                        sum = sum.saturating_add((token_count(p) / stride).saturating_sub(2));
                    }
                    sum
                }
                _ => 0,
            };
            total = total.saturating_add(n);
        }
        Ok(total)
    }

    /// Indices per vertex in a primitive's `<p>`: largest input offset + 1.
    fn input_stride(&self, prim: Node<'a, 'input>) -> Result<usize, String> {
        let mut stride = 1;
        for input in elements(prim).filter(|i| tag(*i) == "input") {
            let offset = usize_attr(self.doc, input, "offset", 0)?;
            stride = stride.max(offset.saturating_add(1));
        }
        Ok(stride)
    }
}

/// COLLADA `<lookat>`: eye, interest, up → the frame at `eye` looking along −Z at `interest`.
fn look_at(v: &[f64]) -> Matrix4<f64> {
    let eye = Vector3::new(v[0], v[1], v[2]);
    let dir = Vector3::new(v[3], v[4], v[5]) - eye;
    let up = Vector3::new(v[6], v[7], v[8]);
    let (Some(dir), Some(up)) = (dir.try_normalize(0.0), up.try_normalize(0.0)) else {
        return Matrix4::new_translation(&eye);
    };
    let Some(right) = dir.cross(&up).try_normalize(0.0) else {
        return Matrix4::new_translation(&eye);
    };
    let up = right.cross(&dir);
    #[rustfmt::skip]
    let m = Matrix4::new(
        right.x, up.x, -dir.x, eye.x,
        right.y, up.y, -dir.y, eye.y,
        right.z, up.z, -dir.z, eye.z,
        0.0, 0.0, 0.0, 1.0,
    );
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    #[test]
    fn up_axes_are_proper_rotations_taking_up_to_z() {
        for (axis, up) in [
            (ColladaUpAxis::X, [1.0, 0.0, 0.0]),
            (ColladaUpAxis::Y, [0.0, 1.0, 0.0]),
            (ColladaUpAxis::Z, [0.0, 0.0, 1.0]),
        ] {
            let m = axis.to_z_up();
            let r = m.fixed_view::<3, 3>(0, 0).into_owned();
            assert!((r.determinant() - 1.0).abs() < 1e-15, "{axis:?}");
            let z = m.transform_point(&Point3::new(up[0], up[1], up[2]));
            assert_eq!([z.x, z.y, z.z], [0.0, 0.0, 1.0], "{axis:?}");
        }
        let y = ColladaUpAxis::Y
            .to_z_up()
            .transform_point(&Point3::new(1.0, 2.0, 3.0));
        assert_eq!([y.x, y.y, y.z], [1.0, -3.0, 2.0]);
    }
}
