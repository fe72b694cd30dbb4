//! Property tests over random kinematic graphs: loops, several roots, self-parenting joints, joints naming
//! links that do not exist, duplicate names and mimic cycles. Every document is validated within a time
//! bound, the tree the Model keeps is a forest (every walk up the parents ends), and the structural
//! findings are the ones an independent reading of the graph expects.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::collections::HashMap;
use std::path::Path;
use std::time::Duration;

use proptest::prelude::*;
use urdf_validator::model::Model;
use urdf_validator::urdf::parse_urdf;
use urdf_validator::{validate_text, Options};

/// One joint of a random graph: endpoints by index (at or past the link count: a link that does not
/// exist), a type, and a mimic leader by joint index (past the joint count: a joint that does not exist).
#[derive(Clone, Debug)]
struct JointSpec {
    parent: usize,
    child: usize,
    kind: &'static str,
    mimic: Option<usize>,
}

#[derive(Clone, Debug)]
struct Graph {
    /// Link names by index; equal names are duplicates.
    links: Vec<String>,
    joints: Vec<JointSpec>,
    /// Joint names by index (equal names are duplicates).
    joint_names: Vec<String>,
}

fn graph() -> impl Strategy<Value = Graph> {
    (1usize..40).prop_flat_map(|n| {
        let link_names = proptest::collection::vec(0..n + n / 8 + 1, n).prop_map(|ids| {
            // Mostly unique names, sometimes a duplicate.
            ids.iter()
                .enumerate()
                .map(|(i, &id)| {
                    if id % 9 == 0 && i > 0 {
                        format!("l{}", i - 1)
                    } else {
                        format!("l{i}")
                    }
                })
                .collect::<Vec<_>>()
        });
        let joint = (
            0..n + 2,
            0..n + 2,
            prop_oneof![
                Just("revolute"),
                Just("continuous"),
                Just("prismatic"),
                Just("fixed")
            ],
            proptest::option::weighted(0.2, 0..n + 1),
        )
            .prop_map(|(parent, child, kind, mimic)| JointSpec {
                parent,
                child,
                kind,
                mimic,
            });
        let joints = proptest::collection::vec(joint, 0..n + 4);
        (link_names, joints).prop_map(|(links, joints)| {
            let joint_names = (0..joints.len())
                .map(|i| {
                    if i > 0 && i % 11 == 0 {
                        format!("j{}", i - 1)
                    } else {
                        format!("j{i}")
                    }
                })
                .collect();
            Graph {
                links,
                joints,
                joint_names,
            }
        })
    })
}

fn link_name(graph: &Graph, index: usize) -> String {
    graph
        .links
        .get(index)
        .cloned()
        .unwrap_or_else(|| format!("ghost{index}"))
}

fn urdf(graph: &Graph) -> String {
    let mut text = String::from("<robot name=\"random\">\n");
    for name in &graph.links {
        text.push_str(&format!(
            "<link name=\"{name}\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>\
             <collision><geometry><box size=\"0.02 0.02 0.02\"/></geometry></collision></link>\n"
        ));
    }
    for (i, joint) in graph.joints.iter().enumerate() {
        let mimic = joint
            .mimic
            .map_or(String::new(), |m| format!("<mimic joint=\"j{m}\"/>"));
        text.push_str(&format!(
            "<joint name=\"{}\" type=\"{}\"><parent link=\"{}\"/><child link=\"{}\"/>\
             <origin xyz=\"0 0 0.05\"/><axis xyz=\"0 1 0\"/>\
             <limit lower=\"-1\" upper=\"1\" effort=\"50\" velocity=\"1\"/>{mimic}</joint>\n",
            graph.joint_names[i],
            joint.kind,
            link_name(graph, joint.parent),
            link_name(graph, joint.child),
        ));
    }
    text.push_str("</robot>\n");
    text
}

/// What an independent reading of the graph expects: (a joint names a missing link, a loop: a joint
/// from a link to itself, a second parent, or a cycle of parent joints).
fn expected(graph: &Graph) -> (bool, bool) {
    let mut first_link: HashMap<&str, usize> = HashMap::new();
    for (i, name) in graph.links.iter().enumerate() {
        first_link.entry(name).or_insert(i);
    }
    let mut first_joint: HashMap<&str, usize> = HashMap::new();
    for (i, name) in graph.joint_names.iter().enumerate() {
        first_joint.entry(name).or_insert(i);
    }
    let resolve = |index: usize| graph.links.get(index).map(|n| first_link[n.as_str()]);
    let (mut missing, mut looped) = (false, false);
    let mut parent_of: HashMap<usize, usize> = HashMap::new();
    for (i, joint) in graph.joints.iter().enumerate() {
        if first_joint[graph.joint_names[i].as_str()] != i {
            continue; // a duplicate joint name: only the first definition joins the tree
        }
        let (parent, child) = (resolve(joint.parent), resolve(joint.child));
        missing |= parent.is_none() || child.is_none();
        let (Some(parent), Some(child)) = (parent, child) else {
            continue;
        };
        if parent == child || parent_of.contains_key(&child) {
            looped = true;
            continue;
        }
        parent_of.insert(child, parent);
    }
    for &start in parent_of.keys() {
        let (mut at, mut steps) = (start, 0);
        while let Some(&up) = parent_of.get(&at) {
            at = up;
            steps += 1;
            if at == start || steps > parent_of.len() {
                looped = true;
                break;
            }
        }
    }
    (missing, looped)
}

fn has(codes: &[String], code: &str) -> bool {
    codes.iter().any(|c| c == code)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, .. ProptestConfig::default() })]

    #[test]
    fn random_graphs_validate_in_bounded_time_with_the_expected_findings(graph in graph()) {
        let text = urdf(&graph);

        // The Model is a forest: walking up the parents from any link ends within the link count.
        let (robot, _) = parse_urdf(&text, Path::new("g.urdf")).expect("well-formed XML");
        let (model, _) = Model::build(&robot);
        for start in 0..robot.links.len() {
            let (mut at, mut steps) = (start, 0);
            while let Some(joint) = model.parent_joint[at] {
                let (parent, _) = model.joint_links[joint.0].expect("a joint in the tree has links");
                at = parent.0;
                steps += 1;
                prop_assert!(steps <= robot.links.len(), "the walk up from link {start} does not end");
            }
        }
        let mut seen = vec![false; robot.links.len()];
        for link in &model.topological_order {
            prop_assert!(!std::mem::replace(&mut seen[link.0], true), "a link twice in the tree");
        }

        // The whole pipeline finishes, within a bound proportional to the size (generous for debug builds).
        let bound = Duration::from_millis(2_000 + 200 * (graph.links.len() + graph.joints.len()) as u64);
        let (done, result) = std::sync::mpsc::channel();
        let input = text.clone();
        std::thread::spawn(move || {
            let mut options = Options::default();
            options.workspace.samples = 64;
            options.statics.pose.samples = 64;
            let _ = done.send(validate_text(input, Path::new("g.urdf"), &options).map(|v| v.report));
        });
        let report = result.recv_timeout(bound);
        prop_assert!(report.is_ok(), "validation did not finish within {bound:?}:\n{text}");
        let report = report.unwrap().expect("a parsed document gives a report");
        let codes: Vec<String> = report.findings.iter().map(|f| f.rule.clone()).collect();

        let (missing, looped) = expected(&graph);
        prop_assert_eq!(has(&codes, "U102"), missing, "undefined-link: {:?}\n{}", codes, text);
        prop_assert_eq!(has(&codes, "U103"), looped, "kinematic-loop: {:?}\n{}", codes, text);
        let duplicates = {
            let mut names: Vec<&String> = graph.links.iter().chain(&graph.joint_names).collect();
            let before = names.len();
            names.sort();
            names.dedup();
            names.len() < before
        };
        prop_assert_eq!(has(&codes, "U101"), duplicates, "duplicate-name: {:?}", codes);
        let self_mimic = graph.joints.iter().enumerate().any(|(i, j)| {
            j.mimic == Some(i) && graph.joint_names.iter().position(|n| *n == graph.joint_names[i]) == Some(i)
        });
        if self_mimic {
            prop_assert!(has(&codes, "U312"), "a joint mimicking itself is a mimic cycle: {:?}", codes);
        }
    }
}
