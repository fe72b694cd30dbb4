//! The memo of sampled arms (what the language server keeps between runs on one document): a run whose
//! arms' inputs did not change takes them from the memo, and its report is the one a run without the memo
//! gives; an edit of what sampling reads (a joint origin, a collision shape, the samples asked) samples
//! again; a cancelled run keeps nothing.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::path::Path;

use urdf_validator::analysis::memo::Memo;
use urdf_validator::analysis::statics::StaticsOptions;
use urdf_validator::analysis::workspace::WorkspaceOptions;
use urdf_validator::analysis::{self, Inputs, Overrides};
use urdf_validator::assets::{AssetSource, Assets};
use urdf_validator::input::mesh::MeshCache;
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::model::Model;
use urdf_validator::timings::{Progress, Stopwatch};
use urdf_validator::urdf::parse::parse_urdf;
use urdf_validator::{validate_text, Options};

/// What one edit of [`dual_arm`] changes.
#[derive(Clone, Copy)]
struct Edit {
    /// The left shoulder's effort limit.
    effort: f64,
    /// The right upper arm's mass.
    mass: f64,
    /// The left shoulder's height above the torso.
    left_shoulder_z: f64,
    /// The right forearm's collision box length.
    right_box: f64,
    /// The left tool frame's (no geometry) offset from the left forearm.
    left_tool_z: f64,
    /// The camera frame's (no geometry) height on the torso.
    camera_z: f64,
}

const ORIGINAL: Edit = Edit {
    effort: 40.0,
    mass: 2.0,
    left_shoulder_z: 0.4,
    right_box: 0.3,
    left_tool_z: 0.3,
    camera_z: 0.5,
};

fn box_link(name: &str, mass: f64, length: f64) -> String {
    format!(
        r#"<link name="{name}"><inertial><origin xyz="0 0 {c}"/><mass value="{mass}"/><inertia ixx="0.02" iyy="0.02" izz="0.005" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><origin xyz="0 0 {c}"/><geometry><box size="0.06 0.06 {length}"/></geometry></collision></link>"#,
        c = length / 2.0
    )
}

fn revolute(name: &str, parent: &str, child: &str, xyz: &str, effort: f64) -> String {
    format!(
        r#"<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/><origin xyz="{xyz}"/><axis xyz="1 0 0"/><limit lower="-2" upper="2" effort="{effort}" velocity="1"/></joint>"#
    )
}

/// A torso with two arms that can reach each other (so each arm's self-collision pairs hold the other's
/// links), a comment to type in.
fn dual_arm(edit: Edit) -> String {
    let links = [
        box_link("torso", 20.0, 0.5),
        box_link("l_upper", 2.0, 0.3),
        box_link("l_fore", 1.0, 0.3),
        box_link("r_upper", edit.mass, 0.3),
        box_link("r_fore", 1.0, edit.right_box),
    ];
    let joints = [
        revolute(
            "l_shoulder",
            "torso",
            "l_upper",
            &format!("0 0.12 {}", edit.left_shoulder_z),
            edit.effort,
        ),
        revolute("l_elbow", "l_upper", "l_fore", "0 0 0.3", 20.0),
        revolute("r_shoulder", "torso", "r_upper", "0 -0.12 0.4", 40.0),
        revolute("r_elbow", "r_upper", "r_fore", "0 0 0.3", 20.0),
    ];
    let frames = format!(
        r#"<link name="l_tool"/><joint name="l_tool_joint" type="fixed"><parent link="l_fore"/><child link="l_tool"/><origin xyz="0 0 {}"/></joint>
<link name="camera"/><joint name="camera_joint" type="fixed"><parent link="torso"/><child link="camera"/><origin xyz="0.05 0 {}"/></joint>"#,
        edit.left_tool_z, edit.camera_z
    );
    format!(
        "<robot name=\"dual\">\n<!-- a comment -->\n{}\n{}\n{frames}\n</robot>\n",
        links.join("\n"),
        joints.join("\n")
    )
}

/// Both arms declared (two joints each are too few for the detector), sampled with the memo.
fn options(memo: Option<&Memo>) -> Options {
    Options {
        workspace: WorkspaceOptions {
            samples: 3000,
            memo: memo.cloned(),
            ..WorkspaceOptions::default()
        },
        overrides: arms(),
        ..Options::default()
    }
}

fn arms() -> Overrides {
    Overrides {
        arms: vec![
            ("torso".to_string(), "l_tool".to_string()),
            ("torso".to_string(), "r_fore".to_string()),
        ],
        ..Overrides::default()
    }
}

/// The report as JSON, without what differs from run to run (the time it was made).
fn report_json(text: &str, options: &Options) -> serde_json::Value {
    let validation =
        validate_text(text.to_string(), Path::new("dual.urdf"), options).expect("loads");
    json_of(&validation)
}

fn json_of(validation: &urdf_validator::Validation) -> serde_json::Value {
    let mut json = serde_json::to_value(&validation.report).expect("serialises");
    json.as_object_mut().expect("an object").remove("timestamp");
    json
}

/// Runs `text` with the memo: its report (checked equal to the report without a memo) and the arms
/// (taken from the memo, sampled) of that run.
fn run(memo: &Memo, text: &str) -> (serde_json::Value, (usize, usize)) {
    let before = (memo.reused(), memo.computed());
    let with = report_json(text, &options(Some(memo)));
    let arms = (memo.reused() - before.0, memo.computed() - before.1);
    assert_eq!(
        with,
        report_json(text, &options(None)),
        "the report with the memo is the report without it"
    );
    (with, arms)
}

#[test]
fn an_edit_sampling_does_not_read_takes_the_arms_from_the_memo() {
    let memo = Memo::default();
    let (first, arms) = run(&memo, &dual_arm(ORIGINAL));
    assert_eq!(arms, (0, 2), "the first run samples both arms");
    assert!(first["workspace"]["arms"][0]["self_collision_free_fraction"].is_number());

    let (_, arms) = run(
        &memo,
        &dual_arm(ORIGINAL).replace("a comment", "a longer comment"),
    );
    assert_eq!(arms, (2, 0), "a comment");
    let (weaker, arms) = run(
        &memo,
        &dual_arm(Edit {
            effort: 0.5,
            ..ORIGINAL
        }),
    );
    assert_eq!(arms, (2, 0), "an effort");
    assert_ne!(
        weaker["statics"], first["statics"],
        "the statics follow the edit"
    );
    let (_, arms) = run(
        &memo,
        &dual_arm(Edit {
            mass: 3.5,
            ..ORIGINAL
        }),
    );
    assert_eq!(arms, (2, 0), "a mass");
}

#[test]
fn an_edit_of_what_sampling_reads_samples_again() {
    let memo = Memo::default();
    run(&memo, &dual_arm(ORIGINAL));
    // The left shoulder moves: the left arm, and the right one, whose pairs hold the left arm's links.
    let (_, arms) = run(
        &memo,
        &dual_arm(Edit {
            left_shoulder_z: 0.35,
            ..ORIGINAL
        }),
    );
    assert_eq!(arms, (0, 2), "a joint origin");
    let (_, arms) = run(
        &memo,
        &dual_arm(Edit {
            left_shoulder_z: 0.35,
            right_box: 0.25,
            ..ORIGINAL
        }),
    );
    assert_eq!(arms, (0, 2), "a collision box");
    // The left tool frame (no geometry) moves: the left arm's tip, not a link the right arm can hit.
    let (_, arms) = run(
        &memo,
        &dual_arm(Edit {
            left_tool_z: 0.32,
            ..ORIGINAL
        }),
    );
    assert_eq!(arms, (1, 1), "the left tool frame");
    // A frame without geometry that no arm moves.
    let (_, arms) = run(
        &memo,
        &dual_arm(Edit {
            camera_z: 0.45,
            ..ORIGINAL
        }),
    );
    assert_eq!(arms, (2, 0), "a camera frame");
    // Back to the original: both arms are still kept.
    let (_, arms) = run(&memo, &dual_arm(ORIGINAL));
    assert_eq!(arms, (2, 0), "the original again");

    let more_samples = Options {
        workspace: WorkspaceOptions {
            samples: 4000,
            ..options(Some(&memo)).workspace
        },
        ..options(None)
    };
    let before = memo.computed();
    report_json(&dual_arm(ORIGINAL), &more_samples);
    assert_eq!(memo.computed() - before, 2, "other options");
}

#[test]
fn a_cancelled_run_keeps_nothing() {
    let path = Path::new("dual.urdf");
    let (robot, _) = parse_urdf(&dual_arm(ORIGINAL), path).expect("parses");
    let (model, _) = Model::build(&robot);
    let (resolver, meshes) = (PackageResolver::default(), MeshCache::new());
    let assets = Assets::load(
        &robot,
        &AssetSource {
            urdf_path: path,
            resolver: &resolver,
            meshes: &meshes,
            srdf: None,
        },
    );
    let memo = Memo::default();
    let progress = Progress::default();
    progress.cancel();
    // The stages before the workspace do not look at the progress: sampling starts, and stops at once.
    let workspace = WorkspaceOptions {
        progress: Some(progress),
        ..options(Some(&memo)).workspace
    };
    let inputs = Inputs {
        assets: &assets,
        statics: &StaticsOptions::default(),
        workspace: &workspace,
        overrides: &arms(),
    };
    analysis::analyse(&robot, &model, &inputs, &mut Stopwatch::start()).expect("analyses");
    assert_eq!((memo.reused(), memo.computed()), (0, 0), "nothing kept");
    let (report, arms) = run(&memo, &dual_arm(ORIGINAL));
    assert_eq!(arms, (0, 2), "the next run samples both arms");
    assert!(report["workspace"]["arms"][0]["max_reach"].as_f64() > Some(0.29));
}

/// `text` with its first effort limit doubled (a comment added when it declares none).
fn with_effort_edited(text: &str) -> String {
    match text.find("effort=\"") {
        Some(at) => {
            let start = at + "effort=\"".len();
            let end = start + text[start..].find('"').expect("a closing quote");
            let doubled = text[start..end]
                .trim()
                .parse::<f64>()
                .map_or(1.0, |e| 2.0 * e + 1.0);
            format!("{}{doubled}{}", &text[..start], &text[end..])
        }
        None => text.replacen("</robot>", "<!-- edited --></robot>", 1),
    }
}

/// `text` with the first `attribute="x y z"` inside the `nth` (modulo their count) element starting with
/// `element`: its first number raised by 0.01 (`None` when no such element holds the attribute).
fn with_first_number_raised(
    text: &str,
    element: &str,
    end: &str,
    attribute: &str,
    nth: usize,
) -> Option<String> {
    let starts: Vec<usize> = text.match_indices(element).map(|(at, _)| at).collect();
    let start = *starts.get(nth % starts.len().max(1))?;
    let close = start + text[start..].find(end)?;
    let value = start + text[start..close].find(attribute)? + attribute.len();
    let number_end = value + text[value..].find([' ', '"'])?;
    let raised = text[value..number_end].trim().parse::<f64>().ok()? + 0.01;
    Some(format!("{}{raised}{}", &text[..value], &text[number_end..]))
}

/// Every real robot of the corpora, validated, then validated again after edits: after an effort edit
/// every sampled arm comes from the memo; after a joint-origin or a collision-box edit some may be sampled
/// again; and the report is always the one a run without the memo gives.
#[test]
fn on_real_robots_the_memo_never_changes_a_report() {
    let mut files: Vec<std::path::PathBuf> = Vec::new();
    for dir in [common::corpus(), common::shared_robots()]
        .into_iter()
        .flatten()
    {
        files.extend(common::urdfs_below(&dir));
    }
    let (mut sampled_arms, mut kinematic_edits) = (0, 0);
    for (index, path) in files.iter().enumerate() {
        let text = std::fs::read_to_string(path).expect("readable");
        let memo = Memo::default();
        // Fewer samples than the default: what is kept does not depend on how many.
        let without_memo = Options {
            workspace: WorkspaceOptions {
                samples: 4000,
                ..WorkspaceOptions::default()
            },
            ..Options::default()
        };
        let with_memo = Options {
            workspace: WorkspaceOptions {
                memo: Some(memo.clone()),
                ..without_memo.workspace.clone()
            },
            ..Options::default()
        };
        if validate_text(text.clone(), path, &with_memo).is_err() {
            continue; // refused files are another test's business
        }
        let first = memo.computed();
        sampled_arms += first;
        let same_report = |edited: &str, what: &str| {
            let again = validate_text(edited.to_string(), path, &with_memo).expect("validates");
            let without =
                validate_text(edited.to_string(), path, &without_memo).expect("validates");
            assert!(
                json_of(&again) == json_of(&without),
                "{} after {what}: the report with the memo differs from the one without",
                path.display()
            );
        };
        same_report(&with_effort_edited(&text), "an effort edit");
        assert_eq!(
            (memo.reused(), memo.computed()),
            (first, first),
            "{}: every arm kept after an effort edit",
            path.display()
        );
        let kinematic = [
            with_first_number_raised(&text, "<joint ", "</joint>", "xyz=\"", index),
            with_first_number_raised(&text, "<collision", "</collision>", "size=\"", index),
        ];
        for edited in kinematic.iter().flatten() {
            same_report(edited, "a joint-origin or collision-box edit");
            kinematic_edits += 1;
        }
    }
    if !files.is_empty() {
        assert!(
            sampled_arms > 20,
            "only {sampled_arms} arms sampled in {} files",
            files.len()
        );
        assert!(
            kinematic_edits > 50,
            "only {kinematic_edits} kinematic edits"
        );
    }
}
