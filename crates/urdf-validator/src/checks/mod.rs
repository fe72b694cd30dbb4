//! Structural and physical-plausibility checks over a parsed robot and its tree.
//!
//! Each submodule owns one family of rules and is a plain function of (robot, model, context) → findings.

mod geometry;
mod inertia;
mod joints;
mod references;

use std::path::Path;

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::input::mesh::{MeshCache, MeshData, MeshError};
use crate::input::resolve::{PackageResolver, Resolution};
use crate::model::Model;
use crate::urdf::robot::Robot;

/// What the checks may need beyond the robot: where the file lives, how to find packages.
pub struct CheckContext<'a> {
    /// Folder of the URDF, for relative mesh paths and the package walk-up.
    pub urdf_dir: &'a Path,
    /// Package search paths.
    pub resolver: &'a PackageResolver,
    /// Loaded meshes.
    pub meshes: &'a MeshCache,
}

impl CheckContext<'_> {
    /// The mesh a URI names, loaded (or why not); `None` when the URI does not resolve to a file.
    pub fn mesh(&self, uri: &str) -> Option<std::sync::Arc<Result<MeshData, MeshError>>> {
        match self.resolver.resolve(uri, self.urdf_dir) {
            Resolution::Found(path) => Some(self.meshes.get(&path)),
            _ => None,
        }
    }

    /// Points of a mesh for contact geometry: its convex hull, or every vertex when the hull is degenerate.
    pub fn mesh_points(&self, uri: &str) -> Option<Vec<[f64; 3]>> {
        let loaded = self.mesh(uri)?;
        let mesh = loaded.as_ref().as_ref().ok()?;
        Some(if mesh.hull.is_empty() {
            mesh.vertices.clone()
        } else {
            mesh.hull.clone()
        })
    }
}

/// Links above this count get an INFO.
pub const MANY_LINKS: usize = 50;

/// Run every check; findings come back grouped by family, each family in document order.
pub fn run(robot: &Robot, model: &Model, ctx: &CheckContext) -> Vec<Finding> {
    let mut findings = Vec::new();
    if robot.links.is_empty() {
        findings.push(Finding::new(
            &rules::NO_LINKS,
            robot.span,
            format!(
                "Robot '{}' has no links",
                robot
                    .name
                    .as_ref()
                    .map_or("<unnamed>", |n| n.value.as_str())
            ),
        ));
    }
    findings.extend(inertia::check(robot, model));
    findings.extend(joints::check(robot, model));
    findings.extend(references::check(robot, model));
    findings.extend(geometry::check(robot, model, ctx));
    if robot.links.len() > MANY_LINKS {
        findings.push(Finding::new(
            &rules::TOO_MANY_LINKS,
            robot.span,
            format!(
                "Robot has {} links (>{MANY_LINKS}) — may be slow to simulate or validate",
                robot.links.len()
            ),
        ));
    }
    findings
}
