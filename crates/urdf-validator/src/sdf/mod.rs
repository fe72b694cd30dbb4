//! SDFormat (1.4–1.11) → [`Robot`]: the model (or the robot model of a `<world>`), its nested models and
//! includes, with SDFormat's pose semantics (`relative_to`, `<frame>`s, `expressed_in`, the legacy 1.4–1.6
//! rules) turned into URDF's (each link in its parent joint's frame). Every value keeps its span in the
//! SDFormat file it was read from, so findings point at SDF lines.

mod build;
mod frames;
mod link;
mod pose;
mod scene;

use roxmltree::Document;

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::input::xml_files::XmlFiles;
use crate::input::xml_options;
use crate::urdf::robot::Robot;
use scene::{Collector, El, Overrides, Scene, Scope, Sink, Version};

/// The SDFormat versions read: 1.4 to 1.11.
pub const SUPPORTED: (Version, Version) = ((1, 4), (1, 11));

/// Parse the SDFormat `files` into the robot of their model (for a `<world>`: the model named `wanted`,
/// else its first non-static model with joints), with the findings of the reading. The error names the
/// models there are when none is named `wanted`.
pub fn parse_sdf(files: &XmlFiles, wanted: Option<&str>) -> Result<(Robot, Vec<Finding>), String> {
    let docs: Vec<Option<Document>> = (0..files.len())
        .map(|i| Document::parse_with_options(files.text(i), xml_options()).ok())
        .collect();
    let mut sink = Sink::new(files);
    let versions: Vec<Version> = docs
        .iter()
        .enumerate()
        .map(|(file, doc)| match doc {
            Some(doc) => version(
                El {
                    file,
                    node: doc.root_element(),
                },
                &mut sink,
            ),
            None => SUPPORTED.1,
        })
        .collect();
    let Some(root) = docs.first().and_then(Option::as_ref).map(|d| El {
        file: 0,
        node: d.root_element(),
    }) else {
        return Ok((Robot::default(), sink.into_findings()));
    };
    let mut collector = Collector {
        sink,
        docs: &docs,
        versions: &versions,
        scene: Scene::default(),
        models_read: 0,
    };
    match pick_model(root, &mut collector, wanted)? {
        Some((model, overrides)) => {
            let root = Scope::default();
            collector.model(model, &root, &root, overrides, 0)
        }
        None => {
            let span = collector.sink.span(root);
            collector.sink.report(
                &rules::SDF_STRUCTURE,
                span,
                "the file holds no <model> (nor a <world> with one)".to_string(),
            );
            let robot = Robot {
                span,
                ..Robot::default()
            };
            return Ok((robot, collector.sink.into_findings()));
        }
    }
    let Collector {
        mut sink, scene, ..
    } = collector;
    let robot = build::robot(&scene, &mut sink);
    Ok((robot, sink.into_findings()))
}

/// `<sdf version>` of a file's root, read as `(major, minor)`; a missing, malformed or unsupported version
/// is U021 and read with the nearest supported rules.
fn version(root: El, sink: &mut Sink) -> Version {
    let span = sink.attr_span(root, "version");
    let written = root.node.attribute("version");
    let parsed = written
        .and_then(|v| v.trim().split_once('.'))
        .and_then(|(a, b)| Some((a.parse::<u32>().ok()?, b.parse::<u32>().ok()?)));
    let (lowest, newest) = SUPPORTED;
    match parsed {
        Some(v) if v >= lowest && v <= newest => v,
        Some(v) => {
            let nearest = v.clamp(lowest, newest);
            sink.report(
                &rules::SDF_UNSUPPORTED_VERSION,
                span,
                format!(
                    "SDFormat {}.{} is outside 1.4–1.11: read with the {}.{} rules",
                    v.0, v.1, nearest.0, nearest.1
                ),
            );
            nearest
        }
        None => {
            sink.report(
                &rules::SDF_UNSUPPORTED_VERSION,
                span,
                match written {
                    Some(text) => format!("<sdf version=\"{text}\"> is not a version (major.minor): read with the 1.11 rules"),
                    None => "<sdf> has no version attribute (sdformat refuses the file): read with the 1.11 rules".to_string(),
                },
            );
            newest
        }
    }
}

/// The model to analyse: the `<model>` under `<sdf>`, or in the first `<world>` the model named `wanted`,
/// else the first non-static model with joints (else the first model), with a U027 finding naming the
/// models left out. The error lists the models when none is named `wanted`.
fn pick_model<'a>(
    root: El<'a>,
    collector: &mut Collector<'a>,
    wanted: Option<&str>,
) -> Result<Option<(El<'a>, Overrides)>, String> {
    let models: Vec<El> = root.children("model").collect();
    let mut candidates: Vec<(El, Overrides)> = Vec::new();
    let world = root.child("world");
    if let Some(first) = models.first() {
        if let Some(second) = models.get(1) {
            let span = collector.sink.span(*second);
            collector.sink.report(
                &rules::SDF_STRUCTURE,
                span,
                "<sdf> holds more than one <model>: only the first is read".to_string(),
            );
        }
        candidates.push((*first, Overrides::default()));
    } else if let Some(world) = world {
        for child in world.node.children().filter(|n| n.is_element()) {
            let child = El {
                file: world.file,
                node: child,
            };
            match child.node.tag_name().name() {
                "model" => candidates.push((child, Overrides::default())),
                "include" => candidates.extend(collector.included_model(child, &Scope::default())),
                _ => {}
            }
        }
    }
    let name = |(model, overrides): &(El, Overrides)| {
        overrides
            .name
            .as_ref()
            .map(|n| n.value.clone())
            .unwrap_or_else(|| model.node.attribute("name").unwrap_or("").to_string())
    };
    let is_static = |(model, overrides): &(El, Overrides)| {
        overrides.is_static.map(|(v, _)| v).unwrap_or_else(|| {
            model
                .child("static")
                .is_some_and(|s| matches!(s.text(), "true" | "1"))
        })
    };
    let has_joints =
        |(model, _): &(El, Overrides)| model.node.descendants().any(|n| n.has_tag_name("joint"));
    let chosen = match wanted {
        Some(wanted) => {
            let names: Vec<String> = candidates.iter().map(name).collect();
            let Some(i) = names.iter().position(|n| n == wanted) else {
                let listed = names
                    .iter()
                    .map(|n| format!("'{n}'"))
                    .collect::<Vec<_>>()
                    .join(", ");
                return Err(format!(
                    "--model {wanted}: no such model in the file (models: {}); {}",
                    if listed.is_empty() {
                        "none".to_string()
                    } else {
                        listed
                    },
                    crate::diagnostics::suggest::did_you_mean(
                        wanted,
                        names.iter().map(String::as_str)
                    )
                ));
            };
            i
        }
        None => {
            let found = candidates
                .iter()
                .position(|c| !is_static(c) && has_joints(c))
                .or_else(|| candidates.iter().position(|c| !is_static(c)))
                .or_else(|| (!candidates.is_empty()).then_some(0));
            let Some(found) = found else {
                return Ok(None);
            };
            found
        }
    };
    let left_out: Vec<String> = candidates
        .iter()
        .enumerate()
        .filter(|(i, _)| *i != chosen)
        .map(|(_, c)| format!("'{}'", name(c)))
        .collect();
    let picked = candidates.swap_remove(chosen);
    if let (Some(world), false) = (world, left_out.is_empty()) {
        let span = collector.sink.span(world);
        collector.sink.report(
            &rules::SDF_MODELS_LEFT_OUT,
            span,
            format!(
                "the world holds {} models: '{}' is analysed; left out: {}",
                left_out.len() + 1,
                name(&picked),
                left_out.join(", ")
            ),
        );
    }
    Ok(Some(picked))
}
