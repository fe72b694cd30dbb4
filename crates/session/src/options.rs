//! A request, merged with its configuration file, as the library's [`Options`].

use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use urdf_validator::analysis::deep::DeepOptions;
use urdf_validator::analysis::pose::{PoseKind, PoseOptions};
use urdf_validator::analysis::statics::StaticsOptions;
use urdf_validator::analysis::workspace::target::{parse_axis, Orientation, Task};
use urdf_validator::analysis::workspace::WorkspaceOptions;
use urdf_validator::analysis::Overrides;
use urdf_validator::diagnostics::Settings;
use urdf_validator::input::mesh::{DiskCache, MeshCache};
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::input::sandbox::Sandbox;
use urdf_validator::model::overrides::ValueOverride;
use urdf_validator::report::baseline::Baseline;
use urdf_validator::{Options, DEFAULT_SAMPLES, DEFAULT_SEED};

use crate::request::{
    Request, DEFAULT_ORIENTATION_TOLERANCE_DEG, DEFAULT_STATE, DEFAULT_TIMEOUT_SECONDS,
};

/// The library options of `request` (already merged with its configuration file) with the rule
/// `settings`, sharing the run's `meshes`.
pub(crate) fn options_for(
    request: &Request,
    settings: Settings,
    meshes: &MeshCache,
) -> Result<Options, String> {
    if let Some(mass) = request
        .payload_mass
        .filter(|m| !(m.is_finite() && *m >= 0.0))
    {
        return Err(format!("--payload-mass {mass}: expected a mass ≥ 0 in kg"));
    }
    let sandbox = sandbox_of(request);
    Ok(Options {
        workspace: workspace_options(request)?,
        xacro_args: request.xacro_args.clone(),
        resolver: PackageResolver::from_env_in(request.package_path.clone(), &sandbox),
        sandbox,
        statics: StaticsOptions {
            pose: PoseOptions {
                kind: request.pose.clone().unwrap_or(PoseKind::Zero),
                joint_angles: request.joint_angles.clone(),
                srdf: request.srdf.clone(),
                state: request
                    .state
                    .clone()
                    .unwrap_or_else(|| DEFAULT_STATE.to_string()),
                samples: request.samples.unwrap_or(DEFAULT_SAMPLES),
                seed: request.seed.unwrap_or(DEFAULT_SEED),
            },
            payload_mass: request.payload_mass,
            payload_link: request.payload_link.clone(),
        },
        overrides: Overrides {
            robot_type: request.robot_type,
            up_axis: request.up_axis,
            contact_links: request.contact_links.clone(),
            arms: request
                .arm_root
                .iter()
                .cloned()
                .zip(request.arm_tip.iter().cloned())
                .collect(),
        },
        timings: request.timings,
        meshes: meshes.clone(),
        progress: None,
        settings,
        deep: DeepOptions {
            requested: request.deep,
            python: Some(urdf_validator::input::interpreter::python()),
            ..Default::default()
        },
        simulators: request.simulator.clone(),
        baseline: request
            .baseline
            .as_deref()
            .map(|path| Baseline::load(path).map(Arc::new))
            .transpose()?,
        sdf_model: request.model.clone(),
        value_overrides: value_overrides(request)?,
        structure_only: false,
        view: request.view,
    })
}

/// The sandbox a request asks for: trusted, or `--untrusted` with the `--package-path` and `--root`
/// folders as roots and the `--allow-env` variables. The roots come from the request only: a
/// configuration file beside an untrusted input is as untrusted as the input.
pub fn sandbox_of(request: &Request) -> Sandbox {
    if !request.untrusted {
        return Sandbox::default();
    }
    Sandbox::untrusted(
        request.package_path.iter().chain(&request.root).cloned(),
        request.allow_env.iter().cloned(),
    )
}

/// `--timeout`: `None` for no limit (0, or more seconds than a `Duration` holds).
pub(crate) fn timeout_of(request: &Request) -> Result<Option<Duration>, String> {
    match request.timeout.unwrap_or(DEFAULT_TIMEOUT_SECONDS) {
        t if t >= 0.0 => Ok(Duration::try_from_secs_f64(t).ok().filter(|d| !d.is_zero())),
        t => Err(format!("--timeout {t}: expected seconds ≥ 0 (0: no limit)")),
    }
}

/// The run's mesh cache: in memory, and on disk unless `no_cache` (or no cache folder is known).
pub fn mesh_cache(no_cache: bool) -> MeshCache {
    match DiskCache::user_default().filter(|_| !no_cache) {
        Some(disk) => MeshCache::new().with_disk_cache(disk),
        None => MeshCache::new(),
    }
}

/// The workspace values of a request, checked.
pub(crate) fn workspace_options(request: &Request) -> Result<WorkspaceOptions, String> {
    let task = match (&request.task, request.height) {
        (Some(name), height) => Some(Task::parse(name, height)?),
        (None, Some(_)) => return Err("--height needs --task custom".to_string()),
        (None, None) => None,
    };
    let samples = request.samples.unwrap_or(DEFAULT_SAMPLES);
    if samples == 0 {
        return Err("--samples must be at least 1".to_string());
    }
    let tolerance = request
        .orientation_tolerance
        .unwrap_or(DEFAULT_ORIENTATION_TOLERANCE_DEG);
    if !(tolerance.is_finite() && (0.0..=180.0).contains(&tolerance)) {
        return Err(format!(
            "--orientation-tolerance must be between 0 and 180 degrees, not {tolerance}"
        ));
    }
    Ok(WorkspaceOptions {
        samples,
        seed: request.seed.unwrap_or(DEFAULT_SEED),
        task,
        orientation: request
            .orientation
            .as_deref()
            .map(Orientation::parse)
            .transpose()?,
        orientation_tolerance_deg: tolerance,
        approach_axis: request
            .approach_axis
            .as_deref()
            .map(parse_axis)
            .transpose()?,
        progress: None,
        memo: None,
        sample_from: None,
    })
}

/// `--override KEY=VALUE`s, after those of `--override-file` (so the command line wins).
fn value_overrides(request: &Request) -> Result<Vec<ValueOverride>, String> {
    let mut texts = Vec::new();
    if let Some(path) = &request.override_file {
        texts.extend(override_file(path)?);
    }
    texts.extend(request.overrides.iter().cloned());
    texts
        .iter()
        .map(|text| ValueOverride::parse(text))
        .collect()
}

/// The `KEY=VALUE`s of an override file: `[joint.NAME]` tables with `effort`/`lower`/`upper`/`velocity`,
/// `[link.NAME]` with `mass` and `com = [x, y, z]`, `[payload]` with `mass`.
fn override_file(path: &Path) -> Result<Vec<String>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("--override-file {}: cannot read it ({e})", path.display()))?;
    let table: toml::Table = text
        .parse()
        .map_err(|e| format!("--override-file {}: not TOML ({e})", path.display()))?;
    let number = |value: &toml::Value| match value {
        toml::Value::Float(v) => Some(v.to_string()),
        toml::Value::Integer(v) => Some(v.to_string()),
        _ => None,
    };
    let mut texts = Vec::new();
    for (kind, entries) in &table {
        let entries = entries.as_table().ok_or_else(|| {
            format!(
                "--override-file {}: '{kind}' must be a table",
                path.display()
            )
        })?;
        let mut add = |key: String, value: &toml::Value| -> Result<(), String> {
            let value = match value {
                toml::Value::Array(items) => items
                    .iter()
                    .map(number)
                    .collect::<Option<Vec<_>>>()
                    .map(|v| v.join(",")),
                other => number(other),
            }
            .ok_or_else(|| {
                format!(
                    "--override-file {}: '{key}' must be a number (or [x, y, z])",
                    path.display()
                )
            })?;
            texts.push(format!("{key}={value}"));
            Ok(())
        };
        if kind == "payload" {
            for (attribute, value) in entries {
                add(format!("payload.{attribute}"), value)?;
            }
            continue;
        }
        for (name, attributes) in entries {
            let attributes = attributes.as_table().ok_or_else(|| {
                format!(
                    "--override-file {}: '{kind}.{name}' must be a table",
                    path.display()
                )
            })?;
            for (attribute, value) in attributes {
                add(format!("{kind}.{name}.{attribute}"), value)?;
            }
        }
    }
    Ok(texts)
}
