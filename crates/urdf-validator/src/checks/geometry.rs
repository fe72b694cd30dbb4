//! Geometry checks: degenerate shapes, meshes that cannot be found, visuals without collisions.

use crate::finding::Finding;
use crate::resolve::Resolution;
use crate::robot::{Geometry, Robot};
use crate::rules;

use super::CheckContext;

pub(super) fn check(robot: &Robot, ctx: &CheckContext) -> Vec<Finding> {
    let mut findings = Vec::new();
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
            if let Geometry::Mesh { filename, .. } = &geometry.value {
                match ctx.resolver.resolve(&filename.value, ctx.urdf_dir) {
                    Resolution::Found(_) => {}
                    Resolution::NotFound { searched } => {
                        let looked: Vec<String> =
                            searched.iter().map(|p| p.display().to_string()).collect();
                        let mut finding = Finding::new(
                            &rules::MESH_NOT_FOUND,
                            filename.span,
                            format!("{owner}: mesh '{}' not found", filename.value),
                        );
                        finding = if looked.is_empty() {
                            finding.with_help(
                                "no package folder of that name was found; pass --package-path DIR",
                            )
                        } else {
                            finding.with_help(format!("looked in: {}", looked.join(", ")))
                        };
                        findings.push(finding);
                    }
                    Resolution::Unsupported(why) => findings.push(Finding::new(
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
