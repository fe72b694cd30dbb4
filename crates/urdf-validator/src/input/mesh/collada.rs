//! COLLADA: the positions its visual scene instantiates, with node transforms, unit and up axis.

use std::collections::HashMap;
use std::sync::Arc;

use nalgebra::{Matrix4, Rotation3, Unit, Vector3};
use roxmltree::{Document, Node};

use super::{
    number, shown, ColladaUpAxis, MeshOptions, RawMesh, Surface, UpAxisPolicy, VertexSink,
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

/// A geometry's positions in file units, its triangle count, and (only when they are read, for the
/// view) its triangles as indices into `positions`.
struct Geometry {
    positions: Vec<[f64; 3]>,
    triangles: usize,
    faces: Vec<[u32; 3]>,
}

struct Collada<'a, 'input> {
    doc: &'a Document<'input>,
    ids: HashMap<&'a str, Node<'a, 'input>>,
    geometries: HashMap<&'a str, Arc<Geometry>>,
    sink: VertexSink,
    triangles: usize,
    instances: usize,
    /// Whether the primitives' index lists are read ([`triangles`]); [`parse_dae`] does not.
    read_faces: bool,
    /// The instantiated triangles, indices into the sink's vertices (when `read_faces`).
    faces: Vec<[u32; 3]>,
}

pub(super) fn parse_dae(bytes: &[u8], options: &MeshOptions) -> Result<RawMesh, String> {
    read(bytes, options, false).map(|(raw, _)| raw)
}

/// The triangles the visual scene instantiates, for drawing: the vertices [`parse_dae`] reads and the
/// triangles of every `<triangles>`, `<polylist>`, `<polygons>`, `<trifans>` and `<tristrips>` (polygons
/// fanned) as indices into them, with the same limits; at most as many triangles as vertices may be
/// instantiated (an error past that). What the validator computes never reads these.
pub(super) fn triangles(bytes: &[u8], options: &MeshOptions) -> Result<Surface, String> {
    read(bytes, options, true).map(|(raw, triangles)| Surface {
        vertices: raw.vertices,
        triangles,
    })
}

/// Walk the visual scene: the positions (and, when `read_faces`, the triangles) it instantiates.
fn read(
    bytes: &[u8],
    options: &MeshOptions,
    read_faces: bool,
) -> Result<(RawMesh, Vec<[u32; 3]>), String> {
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
        read_faces,
        faces: Vec::new(),
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
    let raw = RawMesh {
        vertices: c
            .sink
            .finish("COLLADA <mesh> positions instantiated by the visual scene")?,
        triangles,
        declared_up_axis,
        binary_stl: false,
        faces: None,
    };
    Ok((raw, c.faces))
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
        let mut map = Vec::with_capacity(if self.read_faces {
            data.positions.len()
        } else {
            0
        });
        for p in &data.positions {
            let q = rows.map(|r| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3]);
            let index = self.sink.push(q).map_err(|e| {
                format!(
                    "line {}: geometry instantiated by the visual scene: {e}",
                    line_of(self.doc, geometry)
                )
            })?;
            if self.read_faces {
                map.push(index);
            }
        }
        self.triangles = self.triangles.saturating_add(data.triangles);
        if self.read_faces {
            self.place_faces(geometry, &data.faces, &map)?;
        }
        Ok(())
    }

    /// Add a geometry instance's triangles, `map` taking its position indices to the sink's vertices.
    fn place_faces(
        &mut self,
        geometry: Node<'a, 'input>,
        faces: &[[u32; 3]],
        map: &[u32],
    ) -> Result<(), String> {
        if self.faces.len().saturating_add(faces.len()) > self.sink.limit {
            return Err(format!(
                "line {}: more than {} triangles instantiated (limit: as many as vertices)",
                line_of(self.doc, geometry),
                self.sink.limit
            ));
        }
        for face in faces {
            let corners = face.map(|i| map.get(i as usize).copied());
            if let [Some(a), Some(b), Some(c)] = corners {
                // Corners that deduplicate to one vertex make no triangle.
                if a != b && b != c && a != c {
                    self.faces.push([a, b, c]);
                }
            }
        }
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
        let positions = self.positions(mesh)?;
        let faces = if self.read_faces {
            self.mesh_faces(mesh, positions.len())?
        } else {
            Vec::new()
        };
        let data = Arc::new(Geometry {
            positions,
            triangles: self.mesh_triangles(mesh)?,
            faces,
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

    /// The triangles of a `<mesh>`'s primitives as indices into its `count` positions: `<triangles>`,
    /// `<polylist>` (polygons of `<vcount>` corners), `<polygons>` (each `<p>`, or a `<ph>`'s outer
    /// `<p>`, one polygon), `<trifans>` and `<tristrips>` (each `<p>` one fan or strip); polygons are
    /// fanned from their first corner. Other primitives (lines) have none.
    fn mesh_faces(&self, mesh: Node<'a, 'input>, count: usize) -> Result<Vec<[u32; 3]>, String> {
        let mut faces = Vec::new();
        for prim in elements(mesh) {
            let kind = tag(prim);
            if !matches!(
                kind,
                "triangles" | "polylist" | "polygons" | "trifans" | "tristrips"
            ) {
                continue;
            }
            let corners = |p: Node<'a, 'input>| self.corners(prim, p, count, self.sink.limit);
            match kind {
                "triangles" | "polylist" => {
                    let Some(p) = child(prim, "p") else {
                        continue;
                    };
                    let v = corners(p)?;
                    if kind == "triangles" {
                        if v.len() % 3 != 0 {
                            return Err(format!(
                                "line {}: <triangles> <p> holds {} vertices, not a multiple of 3",
                                line_of(self.doc, p),
                                v.len()
                            ));
                        }
                        faces.extend(v.chunks_exact(3).map(|t| [t[0], t[1], t[2]]));
                    } else {
                        let sizes = self.vcount(prim)?;
                        let mut at = 0usize;
                        for k in sizes {
                            let polygon = at
                                .checked_add(k)
                                .and_then(|end| v.get(at..end))
                                .ok_or_else(|| {
                                    format!(
                                        "line {}: <polylist> <vcount> adds up to more than the {} vertices of its <p>",
                                        line_of(self.doc, prim),
                                        v.len()
                                    )
                                })?;
                            fan(polygon, &mut faces);
                            at += k;
                        }
                    }
                }
                _ => {
                    let ps = elements(prim).filter_map(|c| match tag(c) {
                        "p" => Some(c),
                        // polygons with holes: the outer boundary.
                        "ph" => child(c, "p"),
                        _ => None,
                    });
                    for p in ps {
                        let v = corners(p)?;
                        if kind == "tristrips" {
                            strip(&v, &mut faces);
                        } else {
                            fan(&v, &mut faces);
                        }
                    }
                }
            }
            if faces.len() > self.sink.limit {
                return Err(format!(
                    "line {}: more than {} triangles (limit: as many as vertices)",
                    line_of(self.doc, prim),
                    self.sink.limit
                ));
            }
        }
        Ok(faces)
    }

    /// A primitive's `<vcount>`: the corner count of each polygon.
    fn vcount(&self, prim: Node<'a, 'input>) -> Result<Vec<usize>, String> {
        let Some(vcount) = child(prim, "vcount") else {
            return Ok(Vec::new());
        };
        vcount
            .text()
            .unwrap_or("")
            .split_ascii_whitespace()
            .map(|token| {
                token.parse::<usize>().map_err(|_| {
                    format!(
                        "line {}: expected a vertex count in <vcount>, found '{}'",
                        line_of(self.doc, vcount),
                        shown(token.as_bytes())
                    )
                })
            })
            .collect()
    }

    /// The position index of each vertex in a `<p>` of primitive `prim` (its VERTEX input's index among
    /// the `stride` indices per vertex), each below `count`; at most `limit` of them.
    fn corners(
        &self,
        prim: Node<'a, 'input>,
        p: Node<'a, 'input>,
        count: usize,
        limit: usize,
    ) -> Result<Vec<u32>, String> {
        let stride = self.input_stride(prim)?;
        let input = elements(prim)
            .find(|i| {
                tag(*i) == "input" && matches!(i.attribute("semantic"), Some("VERTEX" | "POSITION"))
            })
            .ok_or_else(|| {
                format!(
                    "line {}: <{}> has no <input semantic=\"VERTEX\"> (expected vertex indices)",
                    line_of(self.doc, prim),
                    tag(prim)
                )
            })?;
        let offset = usize_attr(self.doc, input, "offset", 0)?;
        let mut out = Vec::new();
        let tokens = p.text().unwrap_or("").split_ascii_whitespace();
        for token in tokens.skip(offset).step_by(stride) {
            if out.len() >= limit {
                return Err(format!(
                    "line {}: <p> holds more than {limit} vertices (limit)",
                    line_of(self.doc, p)
                ));
            }
            let index = token
                .parse::<u32>()
                .ok()
                .filter(|&i| (i as usize) < count)
                .ok_or_else(|| {
                    format!(
                        "line {}: expected a vertex index below {count} in <p>, found '{}'",
                        line_of(self.doc, p),
                        shown(token.as_bytes())
                    )
                })?;
            out.push(index);
        }
        Ok(out)
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

/// A polygon's triangles, fanned from its first corner (none for fewer than 3 corners).
fn fan(polygon: &[u32], faces: &mut Vec<[u32; 3]>) {
    if let Some((&first, rest)) = polygon.split_first() {
        faces.extend(rest.windows(2).map(|w| [first, w[0], w[1]]));
    }
}

/// A triangle strip's triangles, every other one reversed so that all wind alike.
fn strip(corners: &[u32], faces: &mut Vec<[u32; 3]>) {
    for (i, w) in corners.windows(3).enumerate() {
        faces.push(if i % 2 == 0 {
            [w[0], w[1], w[2]]
        } else {
            [w[1], w[0], w[2]]
        });
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

    /// A square (two triangles, z = 0) and a quad polylist (z = 1) with a triangle, instanced once
    /// untransformed and once translated by (10, 0, 0); unit 0.5 m.
    const SMALL: &str = r##"<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="0.5"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries>
    <geometry id="g">
      <mesh>
        <source id="pos">
          <float_array id="pos-a" count="21">0 0 0  1 0 0  1 1 0  0 1 0  0 0 1  1 0 1  1 1 1</float_array>
          <technique_common>
            <accessor source="#pos-a" count="7" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="v"><input semantic="POSITION" source="#pos"/></vertices>
        <triangles count="2">
          <input semantic="VERTEX" source="#v" offset="0"/>
          <input semantic="NORMAL" source="#n" offset="1"/>
          <p>0 9 1 9 2 9  0 9 2 9 3 9</p>
        </triangles>
        <polylist count="2">
          <input semantic="NORMAL" source="#n" offset="0"/>
          <input semantic="VERTEX" source="#v" offset="1"/>
          <vcount>4 3</vcount>
          <p>9 4 9 5 9 6 9 0  9 1 9 2 9 3</p>
        </polylist>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="s">
      <node><instance_geometry url="#g"/></node>
      <node><translate>10 0 0</translate><instance_geometry url="#g"/></node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>"##;

    /// The triangles as corner positions.
    fn drawn(bytes: &[u8]) -> Vec<[[f64; 3]; 3]> {
        let Surface {
            vertices: v,
            triangles: t,
        } = triangles(bytes, &MeshOptions::default()).unwrap();
        t.iter().map(|f| f.map(|i| v[i as usize])).collect()
    }

    #[test]
    fn triangles_polylists_and_node_transforms_give_the_triangles() {
        let t = drawn(SMALL.as_bytes());
        let h = 0.5;
        let local = [
            [[0.0, 0.0, 0.0], [h, 0.0, 0.0], [h, h, 0.0]],
            [[0.0, 0.0, 0.0], [h, h, 0.0], [0.0, h, 0.0]],
            // The quad 4 5 6 0, fanned from 4.
            [[0.0, 0.0, h], [h, 0.0, h], [h, h, h]],
            [[0.0, 0.0, h], [h, h, h], [0.0, 0.0, 0.0]],
            [[h, 0.0, 0.0], [h, h, 0.0], [0.0, h, 0.0]],
        ];
        let moved = local.map(|f| f.map(|p| [p[0] + 5.0, p[1], p[2]]));
        let expected: Vec<_> = local.iter().chain(moved.iter()).copied().collect();
        assert_eq!(t, expected);
        // The vertices and counts are those the physics reads, which reads no triangles.
        let raw = parse_dae(SMALL.as_bytes(), &MeshOptions::default()).unwrap();
        let surface = triangles(SMALL.as_bytes(), &MeshOptions::default()).unwrap();
        assert_eq!(raw.vertices, surface.vertices);
        assert_eq!(raw.triangles, 10);
        assert!(raw.faces.is_none());
    }

    #[test]
    fn fans_strips_polygons_and_bad_index_lists() {
        let doc = |prims: &str| {
            format!(
                r##"<COLLADA><library_geometries><geometry id="g"><mesh>
<source id="pos"><float_array id="a">0 0 0 1 0 0 1 1 0 0 1 0 2 2 0</float_array></source>
<vertices id="v"><input semantic="POSITION" source="#pos"/></vertices>{prims}
</mesh></geometry></library_geometries></COLLADA>"##
            )
        };
        let input = r##"<input semantic="VERTEX" source="#v" offset="0"/>"##;
        let count = |prims: &str| {
            triangles(doc(prims).as_bytes(), &MeshOptions::default()).map(|s| s.triangles)
        };
        assert_eq!(
            count(&format!("<trifans>{input}<p>0 1 2 3</p></trifans>")),
            Ok(vec![[0, 1, 2], [0, 2, 3]])
        );
        assert_eq!(
            count(&format!("<tristrips>{input}<p>0 1 2 3</p></tristrips>")),
            Ok(vec![[0, 1, 2], [2, 1, 3]])
        );
        assert_eq!(
            count(&format!(
                "<polygons>{input}<p>0 1 2 3</p><ph><p>1 4 2</p><h>0</h></ph></polygons>"
            )),
            Ok(vec![[0, 1, 2], [0, 2, 3], [1, 4, 2]])
        );
        for bad in [
            format!("<triangles>{input}<p>0 1 5</p></triangles>"),
            format!("<triangles>{input}<p>0 1 -1</p></triangles>"),
            format!("<triangles>{input}<p>0 1 2 3</p></triangles>"),
            format!("<polylist>{input}<vcount>3 3</vcount><p>0 1 2 3</p></polylist>"),
            format!("<polylist>{input}<vcount>3 x</vcount><p>0 1 2</p></polylist>"),
            "<triangles><p>0 1 2</p></triangles>".to_string(),
        ] {
            let e = count(&bad).unwrap_err();
            assert!(e.starts_with("line "), "{bad}: {e}");
        }
        assert_eq!(
            count(&format!(
                "<polylist>{input}<vcount>3 3</vcount><p>0 1 2 3</p></polylist>"
            )),
            Err(
                "line 3: <polylist> <vcount> adds up to more than the 4 vertices of its <p>".into()
            )
        );
        // Polygons of fewer than 3 corners make none.
        assert_eq!(
            count(&format!(
                "<polylist>{input}<vcount>2 0 3</vcount><p>0 1 2 3 4</p></polylist>"
            )),
            Ok(vec![[2, 3, 4]])
        );
    }

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
