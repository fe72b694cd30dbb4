//! Simulator load profiles (`--simulator`): what each simulator's URDF importer does to this file, found
//! without the simulator, from the parsed robot and its tree alone.
//!
//! Each behaviour is one rule (U750–U761) whose documentation cites the importer's source; a behaviour
//! that could not be checked against the simulator's own source or documentation has no rule.

use std::fmt;
use std::str::FromStr;

use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::model::{LinkId, Model};
use crate::urdf::robot::{Inertia, JointKind, Link, Robot};

/// MuJoCo's `mjMINVAL` (include/mujoco/mjtype.h).
pub const MJ_MINVAL: f64 = 1e-15;

/// A simulator whose URDF importer has a profile.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Simulator {
    /// MuJoCo's URDF reader (src/xml/xml_urdf.cc) and compiler.
    Mujoco,
    /// Gazebo, through sdformat's URDF→SDF converter (src/parser_urdf.cc).
    Gazebo,
    /// PyBullet's `loadURDF` (Bullet's ImportURDFDemo importer).
    Pybullet,
    /// Drake's URDF parser (multibody/parsing/detail_urdf_parser.cc).
    Drake,
    /// Isaac Sim's URDF importer (isaac-sim/urdf-importer-extension, isaacsim.asset.importer.urdf).
    Isaac,
}

impl Simulator {
    /// Every profile, in the order their findings are reported.
    pub const ALL: [Simulator; 5] = [
        Simulator::Mujoco,
        Simulator::Gazebo,
        Simulator::Pybullet,
        Simulator::Drake,
        Simulator::Isaac,
    ];

    /// The name `--simulator` takes.
    pub fn name(self) -> &'static str {
        match self {
            Simulator::Mujoco => "mujoco",
            Simulator::Gazebo => "gazebo",
            Simulator::Pybullet => "pybullet",
            Simulator::Drake => "drake",
            Simulator::Isaac => "isaac",
        }
    }
}

impl fmt::Display for Simulator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Simulator {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        Simulator::ALL
            .into_iter()
            .find(|s| s.name().eq_ignore_ascii_case(text.trim()))
            .ok_or_else(|| {
                let names: Vec<_> = Simulator::ALL.iter().map(|s| s.name()).collect();
                format!(
                    "unknown simulator '{text}': expected one of {}",
                    names.join(", ")
                )
            })
    }
}

/// The findings of every requested profile, each profile's in document order.
pub fn check(robot: &Robot, model: &Model, simulators: &[Simulator]) -> Vec<Finding> {
    let mut wanted = simulators.to_vec();
    wanted.sort();
    wanted.dedup();
    let mut findings = Vec::new();
    for simulator in wanted {
        match simulator {
            Simulator::Mujoco => findings.extend(mujoco(robot, model)),
            Simulator::Gazebo => findings.extend(gazebo(robot, model)),
            Simulator::Pybullet => findings.extend(pybullet(robot)),
            Simulator::Drake => findings.extend(drake(robot)),
            Simulator::Isaac => findings.extend(isaac(robot)),
        }
    }
    findings
}

fn is_fixed(robot: &Robot, model: &Model, link: LinkId) -> bool {
    model.parent_joint[link.0]
        .and_then(|j| robot.joints[j.0].kind.as_ref())
        .is_some_and(|k| k.value == JointKind::Fixed)
}

fn declared_mass(link: &Link) -> Option<f64> {
    link.inertial
        .as_ref()
        .and_then(|i| i.mass.as_ref())
        .map(|m| m.value)
        .filter(|m| m.is_finite())
}

fn link_name(robot: &Robot, link: LinkId) -> &str {
    &robot.links[link.0].name.value
}

// ---------------------------------------------------------------------------------------------- Gazebo

/// sdformat lumps a fixed joint unless a `<gazebo reference>` block keeps it; children of `world` are
/// always converted as links.
fn gazebo_lumps(robot: &Robot, model: &Model, link: LinkId) -> bool {
    let Some(joint) = model.parent_joint[link.0] else {
        return false;
    };
    let Some((parent, _)) = model.joint_links[joint.0] else {
        return false;
    };
    let name = &robot.joints[joint.0].name.value;
    is_fixed(robot, model, link)
        && link_name(robot, parent) != "world"
        && !robot
            .gazebo
            .iter()
            .any(|g| g.keeps_fixed_joint && g.reference.as_ref().is_some_and(|r| &r.value == name))
}

/// The link's mass after sdformat lumped its fixed children into it (negative or zero masses count as 0).
fn gazebo_lumped_mass(robot: &Robot, model: &Model, link: LinkId) -> f64 {
    let own = declared_mass(&robot.links[link.0]).unwrap_or(0.0).max(0.0);
    own + model.child_joints[link.0]
        .iter()
        .filter_map(|j| model.joint_links[j.0])
        .filter(|&(_, child)| gazebo_lumps(robot, model, child))
        .map(|(_, child)| gazebo_lumped_mass(robot, model, child))
        .sum::<f64>()
}

fn gazebo(robot: &Robot, model: &Model) -> Vec<Finding> {
    let mut findings = Vec::new();
    for &link in &model.topological_order {
        let Some(joint) = model.parent_joint[link.0].filter(|_| gazebo_lumps(robot, model, link))
        else {
            continue;
        };
        let mut target = link;
        while gazebo_lumps(robot, model, target) {
            match model.parent_joint[target.0].and_then(|j| model.joint_links[j.0]) {
                Some((parent, _)) => target = parent,
                None => break,
            }
        }
        let j = &robot.joints[joint.0];
        findings.push(
            Finding::new(
                &rules::GAZEBO_LUMPS_FIXED_JOINT,
                j.span,
                format!(
                    "Gazebo lumps fixed joint '{}': link '{}' is merged into '{}' and neither exists in the simulation",
                    j.name.value,
                    link_name(robot, link),
                    link_name(robot, target)
                ),
            )
            .with_help(format!(
                "to keep it: <gazebo reference=\"{}\"><preserveFixedJoint>true</preserveFixedJoint></gazebo>",
                j.name.value
            )),
        );
    }
    // Links sdformat does not model; everything below one is gone too, so only the topmost is reported.
    let mut dropped = vec![false; robot.links.len()];
    for &link in &model.topological_order {
        let parent = model.parent_joint[link.0]
            .and_then(|j| model.joint_links[j.0])
            .map(|(parent, _)| parent);
        if parent.is_some_and(|p| dropped[p.0]) {
            dropped[link.0] = true;
            continue;
        }
        let l = &robot.links[link.0];
        if l.name.value == "world"
            || gazebo_lumps(robot, model, link)
            || gazebo_lumped_mass(robot, model, link) > 0.0
        {
            continue;
        }
        dropped[link.0] = true;
        let below = count_below(model, link);
        let why = if l.inertial.is_none() {
            "has no <inertial>"
        } else {
            "has a mass ≤ 0"
        };
        let span = l
            .inertial
            .as_ref()
            .and_then(|i| i.mass.as_ref().map(|m| m.span))
            .unwrap_or(l.span);
        let joint = model.parent_joint[link.0]
            .map(|j| format!(", its parent joint '{}'", robot.joints[j.0].name.value))
            .unwrap_or_default();
        findings.push(Finding::new(
            &rules::GAZEBO_DROPS_LINK,
            span,
            format!(
                "Gazebo does not model link '{}' (it {why}){joint} and the {below} link(s) below it",
                l.name.value
            ),
        ));
    }
    findings
}

fn count_below(model: &Model, link: LinkId) -> usize {
    model.child_joints[link.0]
        .iter()
        .filter_map(|j| model.joint_links[j.0])
        .map(|(_, child)| 1 + count_below(model, child))
        .sum()
}

// ---------------------------------------------------------------------------------------------- MuJoCo

/// Whether MuJoCo compiles a mass and principal moments of at least mjMINVAL for one link on its own:
/// the declared ones, or (no `<inertial>`) those of its collision geometry (`inertiafromgeom="auto"`).
fn mujoco_mass_ok(link: &Link) -> bool {
    match &link.inertial {
        None => !link.collisions.is_empty(),
        Some(inertial) => {
            let mass = declared_mass(link).unwrap_or(0.0);
            let moments = inertial
                .inertia
                .as_ref()
                .and_then(Inertia::principal_moments)
                .unwrap_or([0.0; 3]);
            mass >= MJ_MINVAL && moments.iter().all(|&m| m >= MJ_MINVAL)
        }
    }
}

/// mjCModel::CheckBodyMassInertia: the body, or one static (fixed-joint) descendant, has mass and inertia.
fn mujoco_static_subtree_ok(robot: &Robot, model: &Model, link: LinkId) -> bool {
    mujoco_mass_ok(&robot.links[link.0])
        || model.child_joints[link.0]
            .iter()
            .filter_map(|j| model.joint_links[j.0])
            .any(|(_, child)| {
                is_fixed(robot, model, child) && mujoco_static_subtree_ok(robot, model, child)
            })
}

fn mujoco(robot: &Robot, model: &Model) -> Vec<Finding> {
    let mut findings = Vec::new();
    for (i, link) in robot.links.iter().enumerate() {
        let id = LinkId(i);
        let name = &link.name.value;
        // Checked per link, fused ones included: PR2's fixed `sensor_mount_link` is refused (--deep, U741).
        let fused = is_fixed(robot, model, id);
        if let Some(inertia) = link.inertial.as_ref().and_then(|i| i.inertia.as_ref()) {
            if let Some([a, b, c]) = inertia.principal_moments() {
                if a >= 0.0 && a + b < c {
                    findings.push(Finding::new(
                        &rules::MUJOCO_INERTIA_TRIANGLE,
                        inertia.span,
                        format!(
                            "MuJoCo refuses link '{name}': principal moments {a:.6e} + {b:.6e} < {c:.6e} (inertia must satisfy A + B >= C)"
                        ),
                    ));
                }
            }
        }
        if model.is_moving(robot, id) && !mujoco_static_subtree_ok(robot, model, id) {
            let span = link.inertial.as_ref().map_or(link.span, |i| i.span);
            findings.push(Finding::new(
                &rules::MUJOCO_MASS_BELOW_MINIMUM,
                span,
                format!(
                    "MuJoCo refuses moving link '{name}': its mass or a principal moment is below mjMINVAL (1e-15) and no link fused to it has both"
                ),
            ));
        }
        if let Some(joint) = model.parent_joint[i].filter(|_| fused) {
            let mut target = id;
            while is_fixed(robot, model, target) {
                match model.parent_joint[target.0].and_then(|j| model.joint_links[j.0]) {
                    Some((parent, _)) => target = parent,
                    None => break,
                }
            }
            let parent = link_name(robot, target);
            findings.push(Finding::new(
                &rules::MUJOCO_FUSES_STATIC,
                robot.joints[joint.0].span,
                format!(
                    "MuJoCo fuses link '{name}' into '{parent}' (fusestatic): no body named '{name}' in the compiled model"
                ),
            ));
        }
        if !link.visuals.is_empty() && link.collisions.is_empty() {
            findings.push(Finding::new(
                &rules::MUJOCO_DISCARDS_VISUAL,
                link.visuals[0].span,
                format!(
                    "MuJoCo discards the visuals of link '{name}' (discardvisual) and it has no collision: no geom at all"
                ),
            ));
        }
    }
    findings
}

// -------------------------------------------------------------------------------------------- PyBullet

fn pybullet(robot: &Robot) -> Vec<Finding> {
    let mut findings = Vec::new();
    for link in &robot.links {
        if link.inertial.is_none() && link.name.value != "world" {
            findings.push(Finding::new(
                &rules::PYBULLET_DEFAULT_INERTIAL,
                link.span,
                format!(
                    "PyBullet gives link '{}' (no <inertial>) a mass of 1 kg and inertia diagonal 1, 1, 1 kg·m²",
                    link.name.value
                ),
            ));
        }
    }
    let tensors: Vec<_> = robot
        .links
        .iter()
        .filter_map(|l| l.inertial.as_ref()?.inertia.as_ref())
        .collect();
    if let Some(first) = tensors.first() {
        findings.push(
            Finding::new(
                &rules::PYBULLET_INERTIA_FROM_COLLISION,
                first.span,
                format!(
                    "PyBullet ignores the {} declared inertia tensor(s) and recomputes them from collision shapes unless loaded with URDF_USE_INERTIA_FROM_FILE",
                    tensors.len()
                ),
            )
            .with_help("p.loadURDF(path, flags=p.URDF_USE_INERTIA_FROM_FILE)"),
        );
    }
    findings
}

// ----------------------------------------------------------------------------------------------- Drake

fn drake(robot: &Robot) -> Vec<Finding> {
    let mut findings = Vec::new();
    for joint in &robot.joints {
        let name = &joint.name.value;
        let friction = joint.dynamics.as_ref().and_then(|d| d.friction);
        if friction.is_some_and(|f| f != 0.0) {
            findings.push(Finding::new(
                &rules::DRAKE_IGNORES_JOINT_FRICTION,
                joint.span,
                format!(
                    "Drake ignores the friction {} of joint '{name}' (MultibodyPlant does not support non-zero joint friction)",
                    friction.unwrap_or_default()
                ),
            ));
        }
        let ignored: Vec<&str> = [
            ("<calibration>", joint.calibration.is_some()),
            ("<safety_controller>", joint.safety_controller.is_some()),
        ]
        .into_iter()
        .filter_map(|(tag, present)| present.then_some(tag))
        .collect();
        if !ignored.is_empty() {
            findings.push(Finding::new(
                &rules::DRAKE_IGNORES_ELEMENT,
                joint.span,
                format!(
                    "Drake ignores {} of joint '{name}' (unsupported element)",
                    ignored.join(" and ")
                ),
            ));
        }
    }
    findings
}

// ----------------------------------------------------------------------------------------------- Isaac

/// Isaac Sim's small isotropic inertia for a link without colliders or inertia: 10 × `kNegligibleMass`
/// (1e-5) kg·m² on each axis (UrdfImporter::addRigidBody).
pub const ISAAC_DEFAULT_INERTIA: f64 = 1e-4;

fn isaac(robot: &Robot) -> Vec<Finding> {
    let mut findings = Vec::new();
    for link in &robot.links {
        let name = &link.name.value;
        let inertial = link.inertial.as_ref();
        if inertial.and_then(|i| i.mass.as_ref()).is_none() {
            findings.push(Finding::new(
                &rules::ISAAC_NO_MASS,
                link.span,
                format!(
                    "Isaac Sim's URDF importer sets no mass for link '{name}' (no <mass>): it warns 'No mass specified for link {name}' and leaves the mass to PhysX{}",
                    if link.collisions.is_empty() {
                        ""
                    } else {
                        " (or to the import's density setting, from its collision shapes)"
                    }
                ),
            ));
        }
        if link.collisions.is_empty() && inertial.and_then(|i| i.inertia.as_ref()).is_none() {
            findings.push(Finding::new(
                &rules::ISAAC_DEFAULT_INERTIA,
                link.span,
                format!(
                    "Isaac Sim's URDF importer gives link '{name}' (no collision, no inertia tensor) the isotropic inertia {ISAAC_DEFAULT_INERTIA:e} kg·m² on each axis"
                ),
            ));
        }
    }
    findings
}
