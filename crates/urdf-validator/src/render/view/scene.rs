//! The scene the 3-D view draws, built once per file: the links with their visual and collision
//! geometry (meshes decimated and encoded once, shared by URI), the joints with their axes and limits,
//! the findings with the link or joint each concerns, the workspace's sampled tip positions and the
//! self-collision pair the workspace reports. Where links sit is a [`super::pose::PoseView`].

use std::collections::HashMap;

use serde::Serialize;

use super::mesh::{self, EncodedMesh};
use super::pose::{PoseView, Poser};
use crate::assets::Assets;
use crate::input::resolve::Resolution;
use crate::model::Model;
use crate::urdf::robot::{pose_isometry, Geometry, Robot, Shape};
use crate::Inspection;

/// Most triangles one mesh keeps (larger ones are decimated to it).
pub const MESH_TRIANGLE_BUDGET: usize = 4_000;

/// The whole scene, serialised as the view's JSON.
#[derive(Clone, Debug, Serialize)]
pub struct Scene {
    /// The robot's name.
    pub robot: String,
    /// The file, as the report names it.
    pub file: String,
    /// Overall status of the report (PASS, WARN, ...).
    pub status: String,
    /// Every link, in document order.
    pub links: Vec<SceneLink>,
    /// Every joint, in document order.
    pub joints: Vec<SceneJoint>,
    /// Meshes, referenced by index from the geometry.
    pub meshes: Vec<EncodedMesh>,
    /// The report's findings.
    pub findings: Vec<SceneFinding>,
    /// Tip positions the workspace analysis sampled (every arm), root frame, metres.
    pub workspace_points: Vec<[f64; 3]>,
    /// The pair found in self-collision in the most sampled poses (else the closest pair).
    pub collision_pair: Option<[String; 2]>,
    /// The links and overlays at the report's pose.
    pub reference: PoseView,
}

/// One link.
#[derive(Clone, Debug, Serialize)]
pub struct SceneLink {
    /// The name.
    pub name: String,
    /// `<visual>` shapes.
    pub visuals: Vec<SceneGeometry>,
    /// `<collision>` shapes.
    pub collisions: Vec<SceneGeometry>,
}

/// One shape, placed in its link's frame.
#[derive(Clone, Debug, Serialize)]
pub struct SceneGeometry {
    /// box, cylinder (along z), sphere, capsule (along z) or mesh.
    pub kind: &'static str,
    /// Box side lengths; for a mesh its `scale`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub size: Option<[f64; 3]>,
    /// Radius of a cylinder, sphere or capsule.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Length of a cylinder or of a capsule's cylindrical part.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// Index into [`Scene::meshes`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<usize>,
    /// Placement in the link frame: x, y, z, then the rotation quaternion x, y, z, w.
    pub origin: [f64; 7],
    /// `<material>` colour, RGBA.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub color: Option<[f64; 4]>,
    /// How the drawing differs from the file: `decimated`, `convex_hull` (a mesh whose triangles could
    /// not be read, e.g. past the loader's limits, though its vertices could), `bounding_box` or
    /// `placeholder` (a mesh that cannot be read).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub approximation: Option<&'static str>,
    /// Why a mesh is drawn as a box.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub problem: Option<String>,
}

/// One joint.
#[derive(Clone, Debug, Serialize)]
pub struct SceneJoint {
    /// The name.
    pub name: String,
    /// revolute, continuous, prismatic, fixed, floating or planar.
    pub kind: &'static str,
    /// Index of the parent link in [`Scene::links`].
    pub parent: Option<usize>,
    /// Index of the child link.
    pub child: Option<usize>,
    /// Unit axis in the joint frame.
    pub axis: [f64; 3],
    /// Lower position limit.
    pub lower: Option<f64>,
    /// Upper position limit.
    pub upper: Option<f64>,
    /// Declared effort.
    pub effort: Option<f64>,
    /// The leader it mimics (then it has no slider).
    pub mimic: Option<String>,
}

/// One finding, with what it concerns.
#[derive(Clone, Debug, Serialize)]
pub struct SceneFinding {
    /// Rule code.
    pub rule: String,
    /// CRITICAL, FAIL, WARN or INFO.
    pub severity: String,
    /// The message.
    pub message: String,
    /// `file:line`, when positioned.
    pub location: Option<String>,
    /// Index of the link it concerns.
    pub link: Option<usize>,
    /// Index of the joint it concerns.
    pub joint: Option<usize>,
}

/// Build the scene of the robot `poser` inspected, with the report's pose.
pub fn build(poser: &Poser) -> Scene {
    let Inspection {
        validation,
        robot,
        model,
        assets,
    } = poser.inspection();
    let report = &validation.report;
    let mut meshes = MeshTable::default();
    let links = robot
        .links
        .iter()
        .map(|link| {
            let mut shapes = |list: &[Shape], visual: bool| -> Vec<SceneGeometry> {
                list.iter()
                    .filter_map(|s| geometry(robot, s, visual, assets.as_ref(), &mut meshes))
                    .collect()
            };
            SceneLink {
                name: link.name.value.clone(),
                visuals: shapes(&link.visuals, true),
                collisions: shapes(&link.collisions, false),
            }
        })
        .collect();
    let findings = report
        .findings
        .iter()
        .map(|f| {
            let (link, joint) = concerns(robot, f.element.as_deref(), &f.message);
            SceneFinding {
                rule: f.rule.clone(),
                severity: f.severity.label().to_string(),
                message: f.message.clone(),
                location: f
                    .file
                    .as_ref()
                    .map(|file| format!("{file}:{}", f.line.unwrap_or(0))),
                link,
                joint,
            }
        })
        .collect();
    let workspace = report.workspace.as_ref();
    Scene {
        robot: report.robot_name.clone(),
        file: report.urdf_path.clone(),
        status: report.overall_status.label().to_string(),
        links,
        joints: joints(robot, model),
        meshes: meshes.encoded,
        findings,
        workspace_points: workspace
            .map(|w| w.arms.iter().flat_map(|a| a.tip_samples.clone()).collect())
            .unwrap_or_default(),
        collision_pair: workspace.and_then(|w| w.self_collision_worst_pair.clone()),
        reference: poser.evaluate(&poser.reference()),
    }
}

fn joints(robot: &Robot, model: &Model) -> Vec<SceneJoint> {
    robot
        .joints
        .iter()
        .enumerate()
        .map(|(j, joint)| {
            let data = &model.joint_data[j];
            let links = model.joint_links[j];
            SceneJoint {
                name: joint.name.value.clone(),
                kind: data.kind.as_str(),
                parent: links.map(|(p, _)| p.0),
                child: links.map(|(_, c)| c.0),
                axis: data.axis.into(),
                lower: data.lower,
                upper: data.upper,
                effort: data.effort,
                mimic: model.mimic[j].map(|m| robot.joints[m.leader.0].name.value.clone()),
            }
        })
        .collect()
}

/// The link and joint a finding concerns: from its element path (`.../link[@name='x']/...`), else the
/// first quoted name in its message that names a link or joint.
fn concerns(robot: &Robot, element: Option<&str>, message: &str) -> (Option<usize>, Option<usize>) {
    let link_index = |name: &str| robot.links.iter().position(|l| l.name.value == name);
    let joint_index = |name: &str| robot.joints.iter().position(|j| j.name.value == name);
    if let Some(element) = element {
        let named = |tag: &str| {
            let start = element.find(&format!("{tag}[@name='"))? + tag.len() + 8;
            let rest = element.get(start..)?;
            Some(rest[..rest.find('\'')?].to_string())
        };
        let link = named("link").and_then(|n| link_index(&n));
        let joint = named("joint").and_then(|n| joint_index(&n));
        if link.is_some() || joint.is_some() {
            return (link, joint);
        }
    }
    for name in message.split('\'').skip(1).step_by(2) {
        if let Some(joint) = joint_index(name) {
            return (None, Some(joint));
        }
        if let Some(link) = link_index(name) {
            return (Some(link), None);
        }
    }
    (None, None)
}

/// A mesh drawn: its index in [`Scene::meshes`] and its approximation (empty when none); or why it cannot
/// be drawn, with its bounds when they are known.
type MeshLookup = Result<(usize, &'static str), (String, Option<[[f64; 3]; 2]>)>;

/// Encoded meshes by URI (visual meshes and collision meshes are decimated alike).
#[derive(Default)]
struct MeshTable {
    by_uri: HashMap<String, MeshLookup>,
    encoded: Vec<EncodedMesh>,
}

impl MeshTable {
    /// The mesh a URI names, encoded once: its index and approximation, or why it cannot be drawn and
    /// its bounds when they are known.
    fn get(&mut self, uri: &str, assets: Option<&Assets>) -> MeshLookup {
        if let Some(known) = self.by_uri.get(uri) {
            return known.clone();
        }
        let result = self.load(uri, assets);
        self.by_uri.insert(uri.to_string(), result.clone());
        result
    }

    fn load(&mut self, uri: &str, assets: Option<&Assets>) -> MeshLookup {
        let assets = assets.ok_or_else(|| ("no assets were loaded".to_string(), None))?;
        let loaded = assets.mesh(uri).ok_or_else(|| {
            let why = match assets.resolution(uri) {
                Some(Resolution::Refused(refusal)) => format!("refused to read it: {refusal}"),
                Some(Resolution::Unsupported(why)) => why.clone(),
                _ => "not found".to_string(),
            };
            (format!("mesh '{uri}': {why}"), None)
        })?;
        let data = match loaded.as_ref() {
            Ok(data) => data,
            Err(e) => return Err((e.message.clone(), None)),
        };
        let (vertices, triangles, approximation) = match assets.surface(uri) {
            Some(Ok(surface)) if !surface.triangles.is_empty() => {
                (surface.vertices, surface.triangles, "")
            }
            _ if !data.hull_triangles.is_empty() => (
                data.hull.clone(),
                data.hull_triangles.clone(),
                "convex_hull",
            ),
            _ => {
                return Err((
                    "the mesh's triangles could not be read".to_string(),
                    Some([data.aabb.0, data.aabb.1]),
                ))
            }
        };
        let (v, t) = mesh::decimate(&vertices, &triangles, MESH_TRIANGLE_BUDGET);
        let approximation = if approximation.is_empty() && t.len() < triangles.len() {
            "decimated"
        } else {
            approximation
        };
        self.encoded.push(mesh::encode(&v, &t));
        Ok((self.encoded.len() - 1, approximation))
    }
}

fn geometry(
    robot: &Robot,
    shape: &Shape,
    visual: bool,
    assets: Option<&Assets>,
    meshes: &mut MeshTable,
) -> Option<SceneGeometry> {
    let placement = pose_isometry(&shape.origin);
    let t = placement.translation.vector;
    let r = placement.rotation.coords;
    let mut out = SceneGeometry {
        kind: "box",
        size: None,
        radius: None,
        length: None,
        mesh: None,
        origin: [t.x, t.y, t.z, r.x, r.y, r.z, r.w],
        color: visual.then(|| colour(robot, shape)).flatten(),
        approximation: None,
        problem: None,
    };
    match &shape.geometry.as_ref()?.value {
        Geometry::Box { size } => out.size = Some(*size),
        Geometry::Cylinder { radius, length } => {
            (out.kind, out.radius, out.length) = ("cylinder", Some(*radius), Some(*length));
        }
        Geometry::Sphere { radius } => (out.kind, out.radius) = ("sphere", Some(*radius)),
        Geometry::Capsule { radius, length } => {
            (out.kind, out.radius, out.length) = ("capsule", Some(*radius), Some(*length));
        }
        Geometry::Mesh { filename, scale } => match meshes.get(&filename.value, assets) {
            Ok((index, approximation)) => {
                (out.kind, out.mesh, out.size) = ("mesh", Some(index), Some(*scale));
                out.approximation = (!approximation.is_empty()).then_some(approximation);
            }
            Err((problem, bounds)) => {
                out.problem = Some(problem);
                match bounds {
                    Some([lo, hi]) => {
                        let centre = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0 * scale[k]);
                        let moved = placement * nalgebra::Point3::from(centre);
                        out.origin[..3].copy_from_slice(&[moved.x, moved.y, moved.z]);
                        out.size = Some([0, 1, 2].map(|k| ((hi[k] - lo[k]) * scale[k]).abs()));
                        out.approximation = Some("bounding_box");
                    }
                    None => {
                        out.size = Some([0.05; 3]);
                        out.approximation = Some("placeholder");
                    }
                }
            }
        },
    }
    Some(out)
}

/// The colour of a visual's `<material>`, looked up among the robot's materials by name.
fn colour(robot: &Robot, shape: &Shape) -> Option<[f64; 4]> {
    let name = shape.material.as_ref()?.name.as_deref()?;
    robot.materials.iter().find(|m| m.name.value == name)?.rgba
}
