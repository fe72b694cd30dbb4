//! The job handed to MuJoCo: the URDF text itself with every mesh filename rewritten to a file MuJoCo can
//! read (COLLADA and ASCII STL as the convex hulls already loaded; missing meshes left out), the smallest
//! inertia changes to apply if MuJoCo refuses A + B < C, `<mimic>` as equality constraints; or an MJCF
//! file's path, which MuJoCo loads itself as it is (no fallback: what it refuses, the user's MuJoCo
//! refuses too). Then the configurations to compare and the drop test's servos.

use std::collections::HashMap;
use std::path::Path;

use nalgebra::{Matrix3, SymmetricEigen};
use serde_json::{json, Value};

use crate::assets::Assets;
use crate::diagnostics::span::Span;
use crate::input::resolve::Resolution;
use crate::model::{LinkId, Model};
use crate::urdf::robot::{Geometry, Robot};

/// Simulated time of the drop test, seconds.
pub const DROP_DURATION_S: f64 = 2.0;
/// Fixed time step of the drop test, seconds.
pub const DROP_TIMESTEP_S: f64 = 0.001;
/// Height of the lowest collision geometry above the ground when the robot is released, metres.
pub const DROP_HEIGHT_M: f64 = 0.02;
/// Most samples of the root link's tilt the drop test reports (`deep.drop_test.tilt_trace`).
pub const TILT_TRACE_POINTS: usize = 200;
/// A servo's error at which it reaches its joint's effort (rad, or m), before its integral term.
const SERVO_SATURATION: f64 = 0.02;
/// Largest servo natural frequency times the time step (keeps light links stable).
const SERVO_OMEGA_DT: f64 = 0.5;
/// Integral rate of the servos, 1/s.
const SERVO_INTEGRAL_RATE: f64 = 5.0;
/// Mass and inertia MuJoCo's `boundmass`/`boundinertia` are set to when it refuses a moving body
/// without mass (kg, kg·m²): far below anything a torque shows.
pub const BOUND_MASS: f64 = 1e-9;
/// See [`BOUND_MASS`].
pub const BOUND_INERTIA: f64 = 1e-12;
/// An inertia whose principal moments miss A + B ≥ C by less than this fraction of C is adjusted too
/// (if MuJoCo refuses the file), as MuJoCo's own eigenvalues may round the other way.
const TRIANGLE_SLACK: f64 = 1e-9;

/// A change made before MuJoCo saw the file, to report.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// `mesh`.
    pub kind: &'static str,
    /// The link.
    pub element: String,
    /// What was done.
    pub message: String,
    /// Where.
    pub span: Span,
}

/// An inertia made to satisfy A + B ≥ C.
#[derive(Clone, Debug)]
pub struct InertiaFix {
    /// The link.
    pub link: LinkId,
    /// Principal moments before, ascending.
    pub before: [f64; 3],
    /// After.
    pub after: [f64; 3],
    /// The shortfall C − (A + B) (negative for a near miss).
    pub shortfall: f64,
}

/// The job and what the verdicts need to read the reply.
#[derive(Debug)]
pub struct Job {
    /// The JSON the bridge reads.
    pub json: Value,
    /// Changes made while preparing it (meshes).
    pub prepared: Vec<Prepared>,
    /// Inertias adjusted if MuJoCo refuses them.
    pub inertia_fixes: Vec<InertiaFix>,
    /// The mesh asset names (without extension) MuJoCo may name in an error, with a span for each.
    pub mesh_spans: HashMap<String, Span>,
    /// MuJoCo loads the MJCF file itself: what it compiles is the user's model, not a URDF import.
    pub mjcf: bool,
}

/// The file MuJoCo loads.
#[derive(Clone, Copy, Debug)]
pub enum JobSource<'a> {
    /// The URDF text the robot was parsed from (spans point into it), handed over with its meshes.
    Urdf(&'a str),
    /// An MJCF file, loaded by MuJoCo from its path (includes, `meshdir`, defaults as MuJoCo reads them).
    Mjcf(&'a Path),
}

/// What the job is built from.
pub struct JobInput<'a> {
    /// The file.
    pub source: JobSource<'a>,
    /// The robot.
    pub robot: &'a Robot,
    /// Its tree.
    pub model: &'a Model,
    /// Its meshes.
    pub assets: &'a Assets,
    /// Configurations to compare: label and one value per joint (mimic applied).
    pub configurations: Vec<(String, Vec<f64>)>,
    /// The pose the drop test holds.
    pub drop_q: &'a [f64],
    /// Hold the root link in place (a fixed-base arm) instead of dropping it on the ground.
    pub fixed_base: bool,
    /// `--payload-mass` at its link.
    pub payload: Option<(LinkId, f64)>,
}

/// Build the job.
pub fn build(input: &JobInput) -> Option<Job> {
    let root = input.model.root?;
    let mut job = match input.source {
        JobSource::Urdf(text) => urdf_job(input, text),
        JobSource::Mjcf(path) => Job {
            json: json!({"mjcf": path, "assets": [], "fallbacks": [], "mimic": []}),
            prepared: Vec::new(),
            inertia_fixes: Vec::new(),
            mesh_spans: HashMap::new(),
            mjcf: true,
        },
    };
    let (robot, model) = (input.robot, input.model);
    let joint_name = |j: usize| robot.joints[j].name.value.as_str();
    let in_tree = |j: usize| model.joint_links[j].is_some() && model.joint_data[j].is_actuated();
    let named = |q: &[f64]| -> serde_json::Map<String, Value> {
        (0..robot.joints.len())
            .filter(|&j| in_tree(j))
            .filter_map(|j| Some((joint_name(j).to_string(), json!(finite(*q.get(j)?)?))))
            .collect()
    };
    let servos: Vec<Value> = (0..robot.joints.len())
        .filter(|&j| in_tree(j) && model.mimic[j].is_none())
        .map(|j| {
            let effort = model.joint_data[j].effort.filter(|e| *e > 0.0);
            json!({"joint": joint_name(j), "effort": effort})
        })
        .collect();
    let configurations: Vec<Value> = input
        .configurations
        .iter()
        .map(|(label, q)| json!({"label": label, "q": named(q)}))
        .collect();
    if let Value::Object(fields) = &mut job.json {
        fields.extend(
            json!({
                "root": robot.links[root.0].name.value,
                "fixed_base": input.fixed_base,
                "payload": input.payload.map(|(link, mass)| json!({"link": robot.links[link.0].name.value, "mass": mass})),
                "configurations": configurations,
                "drop": {
                    "duration": DROP_DURATION_S,
                    "timestep": DROP_TIMESTEP_S,
                    "height": DROP_HEIGHT_M,
                    "omega_dt": SERVO_OMEGA_DT,
                    "saturation": SERVO_SATURATION,
                    "integral_rate": SERVO_INTEGRAL_RATE,
                    "q": named(input.drop_q),
                    "servos": servos,
                    "trace_points": TILT_TRACE_POINTS,
                },
            })
            .as_object()
            .into_iter()
            .flatten()
            .map(|(k, v)| (k.clone(), v.clone())),
        );
    }
    Some(job)
}

/// A URDF's part of the job: its text with meshes MuJoCo can read, the inertia and mass fallbacks, the
/// mimic equalities.
fn urdf_job(input: &JobInput, text: &str) -> Job {
    let JobInput {
        robot,
        model,
        assets,
        ..
    } = *input;
    let mut edits: Vec<(Span, String)> = Vec::new();
    let mut prepared = Vec::new();
    let mut asset_list: Vec<Value> = Vec::new();
    let mut asset_names: HashMap<(String, bool), String> = HashMap::new();
    let mut mesh_spans = HashMap::new();
    for link in &robot.links {
        for (shape, collision) in link
            .visuals
            .iter()
            .map(|s| (s, false))
            .chain(link.collisions.iter().map(|s| (s, true)))
        {
            let Some(Geometry::Mesh { filename, .. }) = shape.geometry.as_ref().map(|g| &g.value)
            else {
                continue;
            };
            let uri = &filename.value;
            match mesh_asset(assets, uri) {
                Ok((path, as_is)) => {
                    let key = (path.display().to_string(), as_is);
                    let count = asset_names.len();
                    let name = asset_names.entry(key).or_insert_with(|| {
                        let ext = if as_is {
                            path.extension()
                                .and_then(|e| e.to_str())
                                .unwrap_or("stl")
                                .to_ascii_lowercase()
                        } else {
                            "stl".to_string()
                        };
                        // MuJoCo names the mesh after the stem, appending a number for each other scale.
                        let name = format!("urdf_validate_mesh{count}_.{ext}");
                        asset_list.push(if as_is {
                            json!({"name": name, "path": path})
                        } else {
                            hull_asset(assets, uri, &name)
                        });
                        name
                    });
                    let stem = name.rsplit_once('.').map_or(name.as_str(), |(s, _)| s);
                    mesh_spans.entry(stem.to_string()).or_insert(filename.span);
                    edits.push((filename.span, name.clone()));
                    if collision && !as_is {
                        prepared.push(Prepared {
                            kind: "mesh",
                            element: link.name.value.clone(),
                            message: format!(
                                "collision mesh '{uri}' is in a format MuJoCo does not read (it reads binary STL, OBJ and MSH): passed as the convex hull this validator loaded"
                            ),
                            span: filename.span,
                        });
                    }
                }
                Err(why) => {
                    edits.push((shape.span, String::new()));
                    if collision {
                        prepared.push(Prepared {
                            kind: "mesh",
                            element: link.name.value.clone(),
                            message: format!(
                                "collision mesh '{uri}' {why}: left out of the MuJoCo model, so link '{}' has no shape there",
                                link.name.value
                            ),
                            span: filename.span,
                        });
                    }
                }
            }
        }
    }
    let inertia_fixes = inertia_fixes(robot);
    let fallbacks = vec![
        json!({
            "when": "A + B >= C",
            "kind": "inertia",
            "links": inertia_fixes.iter().filter_map(|fix| {
                let inertia = robot.links[fix.link.0].inertial.as_ref()?.inertia.as_ref()?;
                Some(json!({
                    "link": robot.links[fix.link.0].name.value,
                    "fullinertia": recomposed(&inertia.matrix(), fix.after),
                }))
            }).collect::<Vec<_>>(),
        }),
        json!({
            "when": "mass and inertia of moving bodies must be larger than mjMINVAL",
            "kind": "bound",
            "mass": BOUND_MASS,
            "inertia": BOUND_INERTIA,
        }),
    ];
    let joint_name = |j: usize| robot.joints[j].name.value.as_str();
    let in_tree = |j: usize| model.joint_links[j].is_some() && model.joint_data[j].is_actuated();
    let mimic: Vec<Value> = (0..robot.joints.len())
        .filter(|&j| in_tree(j))
        .filter_map(|j| {
            let link = model.mimic[j]?;
            in_tree(link.leader.0).then(|| {
                json!({
                    "follower": joint_name(j),
                    "leader": joint_name(link.leader.0),
                    "multiplier": link.multiplier,
                    "offset": link.offset,
                })
            })
        })
        .collect();
    Job {
        json: json!({
            "urdf": rewrite(text, edits),
            "assets": asset_list,
            "fallbacks": fallbacks,
            "mimic": mimic,
        }),
        prepared,
        inertia_fixes,
        mesh_spans,
        mjcf: false,
    }
}

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// The file MuJoCo gets for a mesh URI, and whether it is the file itself (`true`) or our hull; or why
/// there is none.
fn mesh_asset<'a>(assets: &'a Assets, uri: &str) -> Result<(&'a Path, bool), String> {
    let Some(path) = assets.resolution(uri).and_then(Resolution::found) else {
        return Err("cannot be found".to_string());
    };
    let mesh = match assets.mesh(uri).map(|m| m.as_ref()) {
        Some(Ok(mesh)) => mesh,
        Some(Err(e)) => return Err(format!("cannot be read ({})", e.message)),
        None => return Err("cannot be found".to_string()),
    };
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let readable = match ext.as_deref() {
        Some("stl") => mesh.binary_stl,
        Some("obj") => true,
        _ => false,
    };
    if readable {
        Ok((path, true))
    } else if mesh.hull.len() >= 4 && !mesh.hull_triangles.is_empty() {
        Ok((path, false))
    } else {
        Err("has no usable convex hull (flat or degenerate)".to_string())
    }
}

fn hull_asset(assets: &Assets, uri: &str, name: &str) -> Value {
    let (vertices, triangles) = match assets.mesh(uri).map(|m| m.as_ref()) {
        Some(Ok(mesh)) => (&mesh.hull[..], &mesh.hull_triangles[..]),
        _ => (&[][..], &[][..]),
    };
    json!({"name": name, "hull": {"vertices": vertices, "triangles": triangles}})
}

/// The text with each span replaced (spans do not overlap; a removed element leaves nothing).
fn rewrite(text: &str, mut edits: Vec<(Span, String)>) -> String {
    edits.sort_by_key(|(span, _)| span.start);
    let mut out = String::with_capacity(text.len());
    let mut at = 0usize;
    for (span, replacement) in edits {
        let (start, end) = (span.start as usize, span.end as usize);
        if start < at || end > text.len() || !text.is_char_boundary(start) {
            continue;
        }
        out.push_str(text.get(at..start).unwrap_or(""));
        out.push_str(&xml_escape(&replacement));
        at = end;
    }
    out.push_str(text.get(at..).unwrap_or(""));
    out
}

fn xml_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('"', "&quot;")
}

/// Principal moments, ascending, and the rotation to them.
fn principal(m: &[[f64; 3]; 3]) -> Option<(Matrix3<f64>, [f64; 3])> {
    let matrix = Matrix3::from_fn(|r, c| m[r][c]);
    if !matrix.iter().all(|v| v.is_finite()) {
        return None;
    }
    let eigen = SymmetricEigen::new(matrix);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
    let values = order.map(|i| eigen.eigenvalues[i]);
    let vectors = Matrix3::from_columns(&order.map(|i| eigen.eigenvectors.column(i).into_owned()));
    Some((vectors, values))
}

/// Links whose principal moments break (or nearly break) A + B ≥ C, with the smallest fix: the two
/// smaller moments each raised by half the shortfall.
fn inertia_fixes(robot: &Robot) -> Vec<InertiaFix> {
    robot
        .links
        .iter()
        .enumerate()
        .filter_map(|(i, link)| {
            let inertia = link.inertial.as_ref()?.inertia.as_ref()?;
            let (_, [a, b, c]) = principal(&inertia.matrix())?;
            if a <= 0.0 {
                return None; // not positive definite: another refusal, MuJoCo's message is reported
            }
            let target = c * (1.0 + TRIANGLE_SLACK);
            (a + b < target).then(|| {
                let raise = (target - a - b) / 2.0;
                InertiaFix {
                    link: LinkId(i),
                    before: [a, b, c],
                    after: [a + raise, b + raise, c],
                    shortfall: c - a - b,
                }
            })
        })
        .collect()
}

/// The tensor with its principal moments replaced, as MuJoCo's `fullinertia` (ixx iyy izz ixy ixz iyz).
fn recomposed(m: &[[f64; 3]; 3], moments: [f64; 3]) -> Vec<f64> {
    let Some((vectors, _)) = principal(m) else {
        return Vec::new();
    };
    let t = vectors * Matrix3::from_diagonal(&moments.into()) * vectors.transpose();
    vec![
        t[(0, 0)],
        t[(1, 1)],
        t[(2, 2)],
        t[(0, 1)],
        t[(0, 2)],
        t[(1, 2)],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fix_is_the_smallest_and_keeps_the_axes() {
        // Diagonal A=1, B=1, C=3: shortfall 1, each smaller moment raised by ~0.5.
        let m = [[1.0, 0.0, 0.0], [0.0, 3.0, 0.0], [0.0, 0.0, 1.0]];
        let (_, [a, b, c]) = principal(&m).unwrap_or((Matrix3::zeros(), [0.0; 3]));
        assert_eq!([a, b, c], [1.0, 1.0, 3.0]);
        let after = [1.5 + 1.5e-9, 1.5 + 1.5e-9, 3.0];
        let t = recomposed(&m, after);
        assert!(
            (t[1] - 3.0).abs() < 1e-12,
            "the largest moment stays on y: {t:?}"
        );
        assert!((t[0] - after[0]).abs() < 1e-12 && (t[2] - after[1]).abs() < 1e-12);
        assert!(t[3].abs() < 1e-12 && t[4].abs() < 1e-12 && t[5].abs() < 1e-12);
    }

    #[test]
    fn rewriting_replaces_spans_in_order() {
        let text = "<a f=\"x\"/><b f=\"yy\"/>";
        let out = rewrite(
            text,
            vec![
                (Span { start: 16, end: 18 }, "m1".to_string()),
                (Span { start: 6, end: 7 }, "m0".to_string()),
            ],
        );
        assert_eq!(out, "<a f=\"m0\"/><b f=\"m1\"/>");
    }
}
