//! Hover: on a link, its mass, centre of mass, principal moments, whether its mass and inertia drew a
//! finding, and the mass it carries; on a joint, the gravity torque at the analysed pose, the declared
//! effort, the margin and the effort needed; on a mesh or include path, the file it resolves to (or where
//! it was looked for); on a material name, its colour or texture; on a xacro property, argument or macro, its value, default or parameters and where it
//! is defined; on a rule code in a suppression comment, the rule. Values come from the last
//! analysis that finished (the physics pass, when it has).

use std::collections::{HashMap, HashSet};
use std::path::Path;

use urdf_validator::analysis::statics::JointStatics;
use urdf_validator::diagnostics::rules;
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::report::Report;
use urdf_validator::urdf::robot::principal_moments;

use super::here::{self, Kind, Target};
use super::navigation::File;
use super::xacro_names;

/// The hover text (Markdown) of `target`, from `report` (the last analysis) when it has one.
pub fn text(
    target: &Target,
    report: Option<&Report>,
    files: &[File],
    dir: &Path,
    resolver: &PackageResolver,
) -> Option<String> {
    match target {
        Target::Name {
            kind: Kind::Link,
            name,
            ..
        } => report.and_then(|r| link(r, files, name)),
        Target::Name {
            kind: Kind::Joint,
            name,
            ..
        } => match undefined_end(files, name, report) {
            // The joint is not in the tree the analyses read: say why rather than "not actuated".
            Some((end, link)) => Some(format!(
                "**joint `{name}`**  \nits {end} link `{link}` is not defined: the joint is not part of \
                 the kinematic tree, so no analysis reads it (U102)"
            )),
            None => report.and_then(|r| joint(r, name)),
        },
        Target::Name {
            kind: Kind::Material,
            name,
            ..
        } => material(files, name),
        Target::Xacro { kind, name, .. } => xacro_names::describe(files, *kind, name),
        Target::Path { value, .. } => Some(match here::resolve_path(value, dir, resolver) {
            Ok(path) => format!("`{value}`\n\n→ `{}`", path.display()),
            Err(why) => format!("`{value}`\n\nnot resolved: {why}"),
        }),
        Target::Rule { code, .. } => {
            let rule = rules::find(code)?;
            Some(format!(
                "**{} `{}`** ({})\n\n{}\n\n{}\n\n**Fix:** {}",
                rule.code,
                rule.name,
                rule.severity.label(),
                rule.what,
                rule.why,
                rule.fix
            ))
        }
    }
}

/// A robot-level material's colour or texture.
fn material(files: &[File], name: &str) -> Option<String> {
    files.iter().find_map(|file| {
        let scan = &file.scan;
        let index = scan.elements.iter().position(|e| {
            e.attribute("name").is_some_and(|a| {
                a.value == name
                    && here::reference_kind(e, "name") == Some(Kind::Material)
                    && here::is_definition(scan, e, a)
            })
        })?;
        let looks: Vec<String> = scan
            .children(index)
            .filter_map(|c| match c.name.as_str() {
                "color" => c
                    .attribute("rgba")
                    .map(|a| format!("colour rgba `{}`", a.value)),
                "texture" => c
                    .attribute("filename")
                    .map(|a| format!("texture `{}`", a.value)),
                _ => None,
            })
            .collect();
        Some(format!("**material `{name}`**  \n{}", looks.join("  \n")))
    })
}

/// A link's mass properties and the mass below it.
fn link(report: &Report, files: &[File], name: &str) -> Option<String> {
    let link = report.links.iter().find(|l| l.name == name)?;
    let mut lines = vec![format!("**link `{name}`**")];
    if link.frame {
        lines.push("a frame: no mass, no geometry".into());
    }
    lines.push(match link.mass {
        Some(mass) => format!("mass: {} kg", number(mass)),
        None => "mass: not declared".into(),
    });
    if let Some(com) = link.com_offset {
        lines.push(format!("centre of mass (link frame): {}", vector(&com)));
    }
    if let Some(moments) = link
        .inertia_tensor
        .and_then(|t| principal_moments(&rows(&t)))
    {
        lines.push(format!("principal moments: {} kg·m²", vector(&moments)));
    }
    let marker = format!("link[@name='{name}']");
    let mass_findings: Vec<String> = report
        .findings
        .iter()
        .filter(|f| f.element.as_deref().is_some_and(|e| e.contains(&marker)))
        .filter(|f| f.name.contains("inertia") || f.name.contains("mass"))
        .map(|f| format!("{} {}", f.rule, f.name))
        .collect();
    lines.push(if mass_findings.is_empty() {
        "mass and inertia: plausible (no finding)".into()
    } else {
        format!("mass and inertia: {}", mass_findings.join(", "))
    });
    if let Some(mass) = subtree_mass(report, files, name) {
        lines.push(format!(
            "mass carried (this link and below): {} kg",
            number(mass)
        ));
    }
    Some(lines.join("  \n"))
}

/// The declared mass of `link` and every link below it, through the joints the files declare (`None`
/// when none of them declares a mass).
fn subtree_mass(report: &Report, files: &[File], link: &str) -> Option<f64> {
    let mut below: HashMap<&str, Vec<&str>> = HashMap::new();
    for scan in files.iter().map(|f| &f.scan) {
        for (i, joint) in scan.elements.iter().enumerate() {
            if joint.name != "joint" {
                continue;
            }
            let end = |tag: &str| {
                scan.children(i)
                    .find(|c| c.name == tag)
                    .and_then(|c| c.attribute("link"))
                    .map(|a| a.value.as_str())
            };
            if let (Some(parent), Some(child)) = (end("parent"), end("child")) {
                below.entry(parent).or_default().push(child);
            }
        }
    }
    let mut seen = HashSet::new();
    let mut stack = vec![link];
    let mut total = None;
    while let Some(name) = stack.pop() {
        if !seen.insert(name) {
            continue;
        }
        if let Some(mass) = report
            .links
            .iter()
            .find(|l| l.name == name)
            .and_then(|l| l.mass)
        {
            total = Some(total.unwrap_or(0.0) + mass);
        }
        stack.extend(below.get(name).into_iter().flatten());
    }
    total
}

/// The end of joint `name` (`parent` or `child`) naming a link no file defines, and that link's name; when
/// the files define links through xacro expressions, only what the last analysis confirmed (its U102).
fn undefined_end(
    files: &[File],
    name: &str,
    report: Option<&Report>,
) -> Option<(&'static str, String)> {
    let templated = files.iter().any(|file| {
        file.scan.elements.iter().any(|e| {
            e.name == "link" && e.attribute("name").is_some_and(|a| a.value.contains("${"))
        })
    });
    let confirmed = |link: &str| {
        report.is_some_and(|r| {
            r.findings.iter().any(|f| {
                f.rule == rules::UNDEFINED_LINK.code && f.message.contains(&format!("'{link}'"))
            })
        })
    };
    let defined = |link: &str| {
        files.iter().any(|file| {
            file.scan.elements.iter().any(|element| {
                element.name == "link"
                    && element.attribute("name").is_some_and(|a| {
                        a.value == link && here::is_definition(&file.scan, element, a)
                    })
            })
        })
    };
    for file in files {
        let joints = file.scan.elements.iter().enumerate().filter(|(_, e)| {
            e.name == "joint"
                && !file.scan.is_inside(e, "gazebo")
                && e.attribute("name").is_some_and(|a| a.value == name)
        });
        for (index, _) in joints {
            for end in ["parent", "child"] {
                let link = file
                    .scan
                    .children(index)
                    .find(|e| e.name == end)
                    .and_then(|e| e.attribute("link"))
                    .map(|a| a.value.clone());
                let missing = |link: &String| {
                    !link.contains("${") && !defined(link) && (!templated || confirmed(link))
                };
                if let Some(link) = link.filter(missing) {
                    return Some((end, link));
                }
            }
        }
    }
    None
}

/// A joint's statics at the analysed pose.
fn joint(report: &Report, name: &str) -> Option<String> {
    let Some(statics) = report.statics.as_ref() else {
        return Some(format!(
            "**joint `{name}`**  \nstatics: not analysed yet (the physics pass follows the structural one)"
        ));
    };
    let Some(joint) = statics.joints.iter().find(|j| j.name == name) else {
        return Some(format!(
            "**joint `{name}`**  \nnot actuated: no gravity torque to hold"
        ));
    };
    Some(joint_lines(name, &statics.pose, joint).join("  \n"))
}

fn joint_lines(name: &str, pose: &str, joint: &JointStatics) -> Vec<String> {
    let optional = |value: Option<f64>, unit: &str| {
        value.map_or("unknown".to_string(), |v| format!("{} {unit}", number(v)))
    };
    let mut lines = vec![
        format!("**joint `{name}`** ({})", joint.status.label()),
        format!(
            "gravity torque at the {pose} pose: {}",
            optional(joint.required_torque_gravity, "N·m")
        ),
        format!(
            "declared effort: {}",
            optional(joint.declared_effort, "N·m")
        ),
        format!(
            "margin: {}",
            joint
                .margin
                .map_or("unknown".to_string(), |m| format!("{}×", number(m)))
        ),
        format!("`effort_needed`: {}", optional(joint.effort_needed, "N·m")),
    ];
    if let Some(leader) = &joint.mimics {
        lines.push(format!("mimics `{leader}` (its torque is folded there)"));
    }
    lines.push(joint.summary.clone());
    lines
}

/// A row-major 3×3 tensor (as the report writes it) as rows.
fn rows(tensor: &[f64; 9]) -> [[f64; 3]; 3] {
    [
        [tensor[0], tensor[1], tensor[2]],
        [tensor[3], tensor[4], tensor[5]],
        [tensor[6], tensor[7], tensor[8]],
    ]
}

/// A number with at most four decimals.
fn number(value: f64) -> String {
    let text = format!("{value:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" || text.is_empty() {
        "0".to_string()
    } else {
        text.to_string()
    }
}

fn vector(values: &[f64; 3]) -> String {
    format!(
        "({}, {}, {})",
        number(values[0]),
        number(values[1]),
        number(values[2])
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_lose_trailing_zeros_and_moments_are_eigenvalues() {
        assert_eq!(number(2.5), "2.5");
        assert_eq!(number(-0.00001), "0");
        assert_eq!(number(12.0), "12");
        let moments = principal_moments(&rows(&[2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 3.0]));
        assert_eq!(moments, Some([1.0, 2.0, 3.0]));
    }
}
