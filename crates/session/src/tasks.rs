//! The spec's task queries over many robots: each request answered with the session of its robot's file
//! (that file's configuration applies, as for the command), the requests on threads of their own
//! ([`crate::batch`]).

use std::collections::HashMap;
use std::path::PathBuf;

use urdf_validator::input::mesh::MeshCache;
use urdf_validator::task_query::{run_pick_task, TaskQueryRequest, TaskQueryResponse};

use crate::{Batch, Request};

/// The response to every request, in order. A request that cannot run (a missing file, a bad orientation)
/// gets its own UNKNOWN response and the others still run; a configuration file that cannot be used is
/// the error.
pub fn pick_sweep(
    request: &Request,
    queries: &[TaskQueryRequest],
    meshes: &MeshCache,
) -> Result<Vec<TaskQueryResponse>, String> {
    // One session per robot file (queries on one robot share its options).
    let mut robot_of: HashMap<&PathBuf, usize> = HashMap::new();
    let mut robots: Vec<PathBuf> = Vec::new();
    for query in queries {
        robot_of.entry(&query.urdf_path).or_insert_with(|| {
            robots.push(query.urdf_path.clone());
            robots.len() - 1
        });
    }
    let sessions = Batch::new(request, &robots, meshes)?;
    let indexed: Vec<(usize, &TaskQueryRequest)> = queries
        .iter()
        .map(|query| (robot_of[&query.urdf_path], query))
        .collect();
    Ok(crate::batch::map_files(&indexed, |(robot, query)| {
        run_pick_task(query, sessions.session(*robot).options())
    }))
}
