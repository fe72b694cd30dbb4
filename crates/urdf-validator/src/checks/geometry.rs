//! Geometry checks: degenerate shapes, meshes that cannot be found, visuals without collisions.

use crate::diagnostics::finding::Finding;
use crate::diagnostics::fix::{Edit, Fix};
use crate::diagnostics::rules;
use crate::diagnostics::span::Spanned;
use crate::input::resolve::Resolution;
use crate::model::kinematics::{forward_kinematics, Data};
use crate::model::Model;
use crate::urdf::robot::{Geometry, Robot};

use crate::assets::Assets;

pub(super) fn check(robot: &Robot, model: &Model, assets: &Assets) -> Vec<Finding> {
    let mut findings = Vec::new();
    let robot_size = joint_extent(model);
    for link in &robot.links {
        let owner = format!("Link '{}'", link.name.value);
        for shape in link.visuals.iter().chain(&link.collisions) {
            let Some(geometry) = &shape.geometry else {
                continue;
            };
            if let Some(problem) = degenerate(&geometry.value) {
                findings.push(Finding::new(
                    &rules::INVALID_GEOMETRY_SIZE,
                    geometry.span,
                    format!("{owner}: {problem}"),
                ));
            }
            if let Geometry::Mesh { filename, scale } = &geometry.value {
                match assets.resolution(&filename.value) {
                    None => {}
                    Some(Resolution::Found(_)) => {
                        findings.extend(check_mesh(assets, &owner, filename, *scale, robot_size));
                    }
                    Some(Resolution::Lenient { path, why }) => {
                        findings.push(Finding::new(
                            &rules::MESH_NOT_FOUND,
                            filename.span,
                            format!(
                                "{owner}: mesh '{}' cannot be resolved by ROS (RViz, MoveIt): {why}; Pinocchio and MuJoCo load {}, and the analyses here use it",
                                filename.value,
                                path.display()
                            ),
                        ));
                        findings.extend(check_mesh(assets, &owner, filename, *scale, robot_size));
                    }
                    Some(Resolution::NotFound { searched }) => {
                        let looked: Vec<String> =
                            searched.iter().map(|p| p.display().to_string()).collect();
                        let mut finding = Finding::new(
                            &rules::MESH_NOT_FOUND,
                            filename.span,
                            format!("{owner}: mesh '{}' not found", filename.value),
                        );
                        finding = if looked.is_empty() && filename.value.starts_with("model://") {
                            finding.with_help(
                                "no model folder of that name was found; set GZ_SIM_RESOURCE_PATH or pass --package-path DIR",
                            )
                        } else if looked.is_empty() {
                            finding.with_help(
                                "no package folder of that name was found; pass --package-path DIR",
                            )
                        } else {
                            finding.with_help(format!("looked in: {}", looked.join(", ")))
                        };
                        findings.push(finding);
                    }
                    Some(Resolution::Refused(why)) => findings.push(Finding::new(
                        &rules::ACCESS_REFUSED,
                        filename.span,
                        format!("{owner}: refused to read mesh '{}': {why}", filename.value),
                    )),
                    Some(Resolution::Unsupported(why)) => findings.push(Finding::new(
                        &rules::MESH_NOT_FOUND,
                        filename.span,
                        format!(
                            "{owner}: mesh '{}' cannot be resolved: {why}",
                            filename.value
                        ),
                    )),
                }
            }
        }
        if !link.visuals.is_empty() && link.collisions.is_empty() {
            let kind = link
                .visuals
                .iter()
                .find_map(|v| v.geometry.as_ref())
                .map_or("geometry", |g| match g.value {
                    Geometry::Mesh { .. } => "mesh",
                    Geometry::Box { .. } => "box",
                    Geometry::Cylinder { .. } => "cylinder",
                    Geometry::Sphere { .. } => "sphere",
                    Geometry::Capsule { .. } => "capsule",
                });
            findings.push(Finding::new(
                &rules::VISUAL_WITHOUT_COLLISION,
                link.span,
                format!("{owner} has visual geometry ({kind}) but no collision geometry — will be invisible to physics engines"),
            ));
        }
    }
    findings
}

/// A description of what is degenerate about a shape, if anything.
fn degenerate(geometry: &Geometry) -> Option<String> {
    let bad = |v: f64| v.is_finite() && v <= 0.0;
    match geometry {
        Geometry::Box { size } if size.iter().any(|&v| bad(v)) => Some(format!(
            "box size {} {} {} has a side ≤ 0",
            size[0], size[1], size[2]
        )),
        Geometry::Cylinder { radius, length } | Geometry::Capsule { radius, length }
            if bad(*radius) || bad(*length) =>
        {
            Some(format!(
                "radius {radius} / length {length} must both be > 0"
            ))
        }
        Geometry::Sphere { radius } if bad(*radius) => {
            Some(format!("sphere radius {radius} must be > 0"))
        }
        // Negative scales are the usual way to mirror a mesh; only zero collapses it.
        Geometry::Mesh { scale, .. } if scale.contains(&0.0) => Some(format!(
            "mesh scale {} {} {} has a zero component",
            scale[0], scale[1], scale[2]
        )),
        _ => None,
    }
}

/// A mesh this many times larger than the whole robot's joint spacing is probably in millimetres (a
/// millimetre mesh is 1000× too large, so every part over a tenth of the robot's size is caught).
const MILLIMETRE_RATIO: f64 = 100.0;

/// The size of the robot's skeleton: the diagonal of the box holding every link frame at the zero pose,
/// metres. 0 for a single link (or links all at one point): then there is nothing to compare a mesh with.
fn joint_extent(model: &Model) -> f64 {
    let q = vec![0.0; model.joint_data.len()];
    let mut data = Data::new(model);
    forward_kinematics(model, &q, &mut data);
    let mut low = [f64::INFINITY; 3];
    let mut high = [f64::NEG_INFINITY; 3];
    for &link in &model.topological_order {
        let p = data.link_placement[link.0].translation.vector;
        for i in 0..3 {
            if p[i].is_finite() {
                low[i] = low[i].min(p[i]);
                high[i] = high[i].max(p[i]);
            }
        }
    }
    let diagonal = (0..3)
        .map(|i| (high[i] - low[i]).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt();
    if diagonal.is_finite() {
        diagonal
    } else {
        0.0
    }
}

/// A resolved mesh that cannot be loaded, or whose size says it is in millimetres.
fn check_mesh(
    assets: &Assets,
    owner: &str,
    filename: &Spanned<String>,
    scale: [f64; 3],
    robot_size: f64,
) -> Option<Finding> {
    let mesh = match assets.mesh_summary(&filename.value)? {
        Ok(mesh) => mesh,
        Err(error) => {
            return Some(Finding::new(
                &rules::MESH_UNREADABLE,
                filename.span,
                format!(
                    "{owner}: mesh '{}' cannot be used: {}",
                    filename.value, error.message
                ),
            ))
        }
    };
    let (min, max) = mesh.aabb;
    let extent = (0..3)
        .map(|i| (max[i] - min[i]) * scale[i].abs())
        .fold(0.0, f64::max);
    let reference = robot_size;
    (reference > 0.0 && extent > 1.0 && extent > MILLIMETRE_RATIO * reference).then(|| {
        Finding::new(
            &rules::MESH_IN_MILLIMETRES,
            filename.span,
            format!(
                "{owner}: mesh '{}' is {extent:.1} m across, {:.0}× the {reference:.3} m span of the whole robot's joints: it is probably in millimetres",
                filename.value,
                extent / reference
            ),
        )
        .with_help("add scale=\"0.001 0.001 0.001\" to the <mesh>, or re-export the mesh in metres")
        .with_fix_option((scale == [1.0; 3]).then(|| {
            Fix::unsafe_(
                "add scale=\"0.001 0.001 0.001\" to the <mesh> (the link's geometry shrinks 1000×)",
                vec![Edit::InsertAttributeAfter {
                    value: filename.span,
                    name: "scale".to_string(),
                    text: "0.001 0.001 0.001".to_string(),
                }],
            )
        }))
    })
}
