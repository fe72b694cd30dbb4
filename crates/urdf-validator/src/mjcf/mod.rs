//! MJCF (MuJoCo's XML) → [`Robot`]: the `<worldbody>` tree with MuJoCo's compiler semantics — includes,
//! default classes, `<compiler>` settings, every orientation form, `<frame>`s, joints chained per body,
//! mass and inertia from `<inertial>` or from the geoms — so the analyses see the robot MuJoCo simulates.
//! Every value keeps its span in the MJCF file it was read from, so findings point at MJCF lines.
//!
//! Read as MuJoCo reads it:
//! - a body is a link named as the body (`body#N` when unnamed, N its MuJoCo body id); a body with several
//!   joints is a chain of massless links `body:joint`, its last joint leading to the body's link; a body
//!   without joints is welded to its parent (`parent_to_body`, fixed);
//! - `hinge` is revolute when limited (`limited`, or a `range` with `autolimits`), else continuous; `slide`
//!   is prismatic; `ball` is three continuous hinges about the body's x, y, z axes at the joint's `pos`
//!   (`name_x`, `name_y`, `name_z`; U033), whose gravity torques at a pose are MuJoCo's three ball dofs
//!   there; `free` is a floating joint to `world`, except on the only top-level body, which is then the
//!   root (a floating base, as URDF writes one). A joint's q is MuJoCo's `qpos − ref`;
//! - mass: `inertiafromgeom` (auto: `<inertial>` when the body has one, else its geoms); geoms of the
//!   groups in `inertiagrouprange` count, primitives with MuJoCo's formulas, meshes as the solid their
//!   surface bounds; `mass` or `density` (1000); then `boundmass`, `boundinertia`, `balanceinertia` and
//!   `settotalmass`;
//! - geoms with `contype` and `conaffinity` 0 are visual shapes, the others collision shapes; geoms of the
//!   world body (the floor) are not part of the robot;
//! - a joint's effort is what its `motor`, `position`, `velocity` and `general` actuators can apply
//!   (`build/actuators.rs`); a joint without actuator is passive (no effort: statics UNKNOWN);
//! - `<equality>`: a joint coupling is a mimic, a joint equality without joint2 a fixed joint, `connect`
//!   and `weld` loops are reported, not analysed (`build/equality.rs`);
//! - `<keyframe><key>`s become the robot's keyframes, poses for `--pose key:NAME`
//!   (`build/keyframes.rs`).
//!
//! Not read yet (U033): actuators on tendons, sites or bodies and other actuator kinds, tendon and flex
//! equalities, tendons, composite/flexcomp/replicate/attach, height fields, SDF geoms, shell inertia;
//! contact pairs are not read either.

mod build;
mod compiler;
mod defaults;
mod mass;
mod orientation;
mod xml;

use std::path::Path;

use roxmltree::Document;

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::input::mesh::MeshCache;
use crate::input::resolve::PackageResolver;
use crate::input::xml_files::XmlFiles;
use crate::input::xml_options;
use crate::urdf::robot::Robot;

/// Parse the MJCF `files` (entry file first) into the robot of their `<worldbody>`, with the findings of
/// the reading. Mesh files (for the mass of mesh geoms) are read through `resolver`'s sandbox and
/// `meshes`.
pub fn parse_mjcf(
    files: &XmlFiles,
    meshes: &MeshCache,
    resolver: &PackageResolver,
) -> (Robot, Vec<Finding>) {
    let docs: Vec<Option<Document>> = (0..files.len())
        .map(|i| Document::parse_with_options(files.text(i), xml_options()).ok())
        .collect();
    let mut reader = xml::Reader::new(files, &docs);
    let Some(root) = reader.root() else {
        return (Robot::default(), reader.into_findings());
    };
    let sections = reader.children(root);
    if !sections.iter().any(|s| s.tag() == "worldbody") {
        let span = reader.span(root);
        reader.report(
            &rules::MJCF_NOT_READ,
            span,
            "the model has no <worldbody>: no robot (a file of assets or defaults to include?)"
                .to_string(),
        );
    }
    let model_path: &Path = files.path(0);
    let builder = build::Builder::new(&mut reader, &sections, model_path, meshes, resolver);
    let robot = builder.robot(root, &sections);
    (robot, reader.into_findings())
}
