//! MuJoCo as the judge of what it does with a file: which models it refuses (every refusal rule on a
//! crafted case, beside a near miss it accepts), and which contacts it applies the moment it starts
//! (U042 between bodies, U603 with the floor, at `qpos0` and at each keyframe). Each case states our
//! verdict, so the test runs without MuJoCo; with it (the test venv, always under CI) MuJoCo's own
//! verdict on every case must be the same.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use common::Scratch;
use urdf_validator::diagnostics::finding::Severity;
use urdf_validator::{validate, Options, Validation};

/// Each case's text as `caseN.xml` in `dir`.
fn write_cases<'a>(dir: &Scratch, texts: impl Iterator<Item = &'a String>) -> Vec<PathBuf> {
    texts
        .enumerate()
        .map(|(i, text)| dir.file(&format!("case{i}.xml"), text))
        .collect()
}

fn options() -> Options {
    let mut options = Options::default();
    options.workspace.samples = 50;
    options.deep.automatic = false;
    options
}

/// A one-joint model with `body` inside its moving body `a` and `top` after `<worldbody>`.
fn model(body: &str, top: &str) -> String {
    format!(
        r#"<mujoco>
  <worldbody>
    <body name="a">
      <joint name="j" axis="0 0 1"/>
      <geom size="0.1"/>
      {body}
    </body>
  </worldbody>
  {top}
</mujoco>
"#
    )
}

/// (case, MJCF text, whether MuJoCo refuses it). Each refusal the reader knows, and beside most of
/// them the near miss MuJoCo accepts.
fn refusal_cases() -> Vec<(&'static str, String, bool)> {
    let refused = true;
    vec![
        ("the base model", model("", ""), !refused),
        ("an unknown section", model("", "<widget/>"), refused),
        (
            "an unknown element in a body",
            model("<widget/>", ""),
            refused,
        ),
        (
            "a zero joint axis",
            model(
                r#"<body name="b"><joint axis="0 0 0"/><geom size="0.1"/></body>"#,
                "",
            ),
            refused,
        ),
        (
            "a joint axis of any length",
            model(
                r#"<body name="b"><joint axis="0 0 2"/><geom size="0.1"/></body>"#,
                "",
            ),
            !refused,
        ),
        (
            "an unknown class",
            model(r#"<geom class="nope" size="0.1"/>"#, ""),
            refused,
        ),
        (
            "an unknown childclass",
            model(
                r#"<body name="b" childclass="nope"><geom size="0.1"/></body>"#,
                "",
            ),
            refused,
        ),
        (
            "a known class",
            model(
                r#"<geom class="big" size="0.1"/>"#,
                r#"<default><default class="big"><geom size="0.2"/></default></default>"#,
            ),
            !refused,
        ),
        (
            "a nested default without a class",
            model(
                "",
                "<default><default><geom size=\"0.2\"/></default></default>",
            ),
            refused,
        ),
        (
            "two orientations",
            model(r#"<geom size="0.1" quat="1 0 0 0" euler="0 0 1"/>"#, ""),
            refused,
        ),
        (
            "one orientation",
            model(r#"<geom size="0.1" euler="0 0 1"/>"#, ""),
            !refused,
        ),
        (
            "a free joint below the top level",
            model(
                r#"<body name="b"><freejoint/><geom size="0.1"/></body>"#,
                "",
            ),
            refused,
        ),
        (
            "a range without limited, autolimits off",
            model(
                r#"<body name="b"><joint axis="0 1 0" range="-1 1"/><geom size="0.1"/></body>"#,
                "",
            )
            .replace("<mujoco>", "<mujoco><compiler autolimits=\"false\"/>"),
            refused,
        ),
        (
            "a range with autolimits (the default)",
            model(
                r#"<body name="b"><joint axis="0 1 0" range="-1 1"/><geom size="0.1"/></body>"#,
                "",
            ),
            !refused,
        ),
        (
            "diaginertia and fullinertia",
            model(
                r#"<body name="b"><inertial pos="0 0 0" mass="1" diaginertia="1 1 1" fullinertia="1 1 1 0 0 0"/></body>"#,
                "",
            ),
            refused,
        ),
        (
            "an inertial without a tensor on a static body",
            model(
                "",
                r#"<worldbody><body name="s" pos="1 0 0"><inertial pos="0 0 0" mass="1"/></body></worldbody>"#,
            ),
            !refused,
        ),
        (
            "two inertials in one body",
            model(
                r#"<body name="b"><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/></body>"#,
                "",
            ),
            refused,
        ),
        (
            "a mesh geom without a mesh",
            model(r#"<geom type="mesh"/>"#, ""),
            refused,
        ),
        (
            "a mesh that is not an asset",
            model(r#"<geom type="mesh" mesh="ghost"/>"#, ""),
            refused,
        ),
        (
            "a moving body without mass",
            model(
                r#"<body name="b"><joint axis="0 1 0"/><geom size="0.1" mass="0"/></body>"#,
                "",
            ),
            refused,
        ),
        (
            "a massless moving body welded to a massive one",
            model(
                r#"<body name="b"><joint axis="0 1 0"/><geom size="0.1" mass="0"/><body name="c"><geom size="0.1"/></body></body>"#,
                "",
            ),
            !refused,
        ),
        (
            "ctrlrange and inheritrange",
            model(
                r#"<body name="b"><joint name="k" axis="0 1 0" range="-1 1"/><geom size="0.1"/></body>"#,
                r#"<actuator><position joint="k" ctrlrange="-1 1" inheritrange="1"/></actuator>"#,
            ),
            refused,
        ),
        (
            "inheritrange of a joint without a range",
            model(
                r#"<body name="b"><joint name="k" axis="0 1 0"/><geom size="0.1"/></body>"#,
                r#"<actuator><position joint="k" inheritrange="1"/></actuator>"#,
            ),
            refused,
        ),
        (
            "inheritrange of a joint with a range",
            model(
                r#"<body name="b"><joint name="k" axis="0 1 0" range="-1 1"/><geom size="0.1"/></body>"#,
                r#"<actuator><position joint="k" inheritrange="1"/></actuator>"#,
            ),
            !refused,
        ),
        (
            "an unknown equality",
            model("", "<equality><gizmo/></equality>"),
            refused,
        ),
        (
            "an equality of an unknown joint",
            model("", r#"<equality><joint joint1="nope"/></equality>"#),
            refused,
        ),
        (
            "an equality of a known joint",
            model("", r#"<equality><joint joint1="j"/></equality>"#),
            !refused,
        ),
        (
            "a keyframe child that is not a key",
            model("", "<keyframe><pose/></keyframe>"),
            refused,
        ),
        (
            "a key with too many qpos",
            model("", r#"<keyframe><key qpos="0 0"/></keyframe>"#),
            refused,
        ),
        (
            "a key with qpos for every joint",
            model("", r#"<keyframe><key qpos="0.5"/></keyframe>"#),
            !refused,
        ),
        (
            "nkey that is no int",
            model("", r#"<size nkey="1e308"/>"#),
            refused,
        ),
        (
            "nkey that is an int",
            model("", r#"<size nkey="3"/>"#),
            !refused,
        ),
        (
            "two values for a position",
            model(r#"<geom size="0.1" pos="1 2"/>"#, ""),
            refused,
        ),
        (
            "a position that is not a number",
            model(r#"<geom size="0.1" pos="0 0 nan"/>"#, ""),
            refused,
        ),
        (
            "an unknown angle unit",
            model("", "").replace("<mujoco>", "<mujoco><compiler angle=\"gradians\"/>"),
            refused,
        ),
        (
            "two bodies of one name",
            model(
                r#"<body name="b"><geom size="0.1"/></body><body name="b"><geom size="0.1"/></body>"#,
                "",
            ),
            refused,
        ),
        (
            "a body inside an ancestor of its name",
            model(r#"<body name="a"><geom size="0.1"/></body>"#, ""),
            refused,
        ),
        (
            "an include of a missing file",
            model("", r#"<include file="missing.xml"/>"#),
            refused,
        ),
    ]
}

/// What `python ARGS PATHS...` prints; the test fails when it does not succeed.
fn python_output(python: &Path, args: &[&str], paths: &[PathBuf]) -> String {
    let output = std::process::Command::new(python)
        .args(args)
        .args(paths)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).unwrap()
}

/// Whether we refuse the model: it cannot be read, or a finding is CRITICAL.
fn we_refuse(path: &Path) -> bool {
    match validate(path, &options()) {
        Err(_) => true,
        Ok(v) => v
            .report
            .findings
            .iter()
            .any(|f| f.severity == Severity::Critical),
    }
}

/// MuJoCo's verdict on each of `paths`: whether `MjModel.from_xml_path` refuses it.
fn mujoco_refuses(python: &Path, paths: &[PathBuf]) -> Vec<bool> {
    let script = "import sys, mujoco\nfor path in sys.argv[1:]:\n    try:\n        mujoco.MjModel.from_xml_path(path)\n        print('accepted')\n    except Exception:\n        print('refused')\n";
    python_output(python, &["-c", script], paths)
        .lines()
        .map(|l| l == "refused")
        .collect()
}

#[test]
fn we_refuse_what_mujoco_refuses_and_accept_what_it_accepts() {
    let dir = Scratch::new("mujoco-agreement-refusals");
    let cases = refusal_cases();
    let paths = write_cases(&dir, cases.iter().map(|(_, text, _)| text));
    let ours: Vec<bool> = paths.iter().map(|p| we_refuse(p)).collect();
    for ((name, _, refused), ours) in cases.iter().zip(&ours) {
        assert_eq!(
            ours,
            refused,
            "{name}: we {} it",
            if *ours { "refuse" } else { "accept" }
        );
    }
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let theirs = mujoco_refuses(&python, &paths);
    assert_eq!(theirs.len(), cases.len());
    let differ: Vec<String> = cases
        .iter()
        .zip(&theirs)
        .filter(|((_, _, refused), theirs)| refused != *theirs)
        .map(|((name, _, _), theirs)| {
            format!(
                "{name}: MuJoCo {}",
                if *theirs { "refuses it" } else { "accepts it" }
            )
        })
        .collect();
    assert!(differ.is_empty(), "MuJoCo disagrees: {differ:#?}");
}

/// Start contacts as (pose, kind, names...): `pair` for U042, `floor` for U603.
type Facts = BTreeSet<Vec<String>>;

/// (case, MJCF text, the start contacts).
fn contact_cases() -> Vec<(&'static str, String, Vec<&'static str>)> {
    // A fixed arm whose shoulder overlaps its base by 12 mm, and whose arm a key swings into the base
    // and the floor.
    let arm = |base_extra: &str, shoulder_geom: &str, top: &str| {
        format!(
            r#"<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="base_link" pos="0 0 0.1">
      {base_extra}
      <geom type="cylinder" size="0.05 0.05" mass="1"/>
      <body name="shoulder_link" pos="0 0 0.088">
        <joint name="joint_1" axis="0 0 1" range="-3 3"/>
        {shoulder_geom}
        <body name="arm_link" pos="0 0 0.1">
          <joint name="joint_2" axis="0 1 0" range="-2 2"/>
          <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03" mass="1"/>
        </body>
      </body>
    </body>
  </worldbody>
  {top}
</mujoco>
"#
        )
    };
    let cylinder = r#"<geom type="cylinder" size="0.04 0.05" mass="1"/>"#;
    let down = r#"<keyframe><key name="down" qpos="0 1.5"/></keyframe>"#;
    // A humanoid-like body lying on the floor, one limb 35 mm inside it; a key lifts the base.
    let lying = |top: &str| {
        format!(
            r#"<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="torso" pos="0 0 0.1">
      <freejoint/>
      <geom type="capsule" fromto="-0.3 0 0 0.3 0 0" size="0.1"/>
      <body name="arm" pos="0 0.2 0">
        <joint name="shoulder" axis="1 0 0" range="-1 1"/>
        <geom type="capsule" fromto="0 0 -0.035 0.4 0 -0.035" size="0.1"/>
      </body>
    </body>
  </worldbody>
  {top}
</mujoco>
"#
        )
    };
    vec![
        (
            "a child overlapping its world-welded parent, and a key into the floor",
            arm("", cylinder, down),
            vec![
                "qpos0 pair base_link shoulder_link",
                "down pair base_link shoulder_link",
                "down pair arm_link base_link",
                "down floor arm_link",
            ],
        ),
        (
            "the parent moves: MuJoCo's parent filter applies",
            arm(r#"<joint name="base_yaw" axis="0 0 1"/>"#, cylinder, ""),
            vec![],
        ),
        (
            "the pair excluded",
            arm(
                "",
                cylinder,
                r#"<contact><exclude body1="base_link" body2="shoulder_link"/></contact>"#,
            ),
            vec![],
        ),
        (
            "incompatible bit masks",
            arm(
                "",
                r#"<geom type="cylinder" size="0.04 0.05" mass="1" contype="2" conaffinity="2"/>"#,
                "",
            ),
            vec![],
        ),
        (
            "a compatible geom beside an incompatible one that overlaps",
            arm(
                "",
                r#"<geom type="cylinder" size="0.04 0.05" mass="1" contype="2" conaffinity="2"/><geom type="sphere" size="0.01" pos="0.2 0 0" mass="0.1"/>"#,
                "",
            ),
            vec![],
        ),
        (
            "bit masks from a default class",
            arm(
                "",
                r#"<geom class="visual" type="cylinder" size="0.04 0.05" mass="1"/>"#,
                r#"<default><default class="visual"><geom contype="0" conaffinity="0"/></default></default>"#,
            ),
            vec![],
        ),
        (
            "contacts disabled",
            arm(
                "",
                cylinder,
                r#"<option><flag contact="disable"/></option>"#,
            ),
            vec![],
        ),
        (
            "a body lying in the floor, a key lifting it",
            lying(r#"<keyframe><key name="up" qpos="0 0 1 1 0 0 0 0"/></keyframe>"#),
            vec!["qpos0 floor arm"],
        ),
        (
            "the floor does not collide with the body",
            lying("").replace(
                r#"type="plane""#,
                r#"type="plane" contype="0" conaffinity="0""#,
            ),
            vec![],
        ),
    ]
}

fn ours(v: &Validation) -> Facts {
    let quoted = |text: &str| -> Vec<String> {
        text.split('\'')
            .skip(1)
            .step_by(2)
            .map(str::to_string)
            .collect()
    };
    let mut facts = Facts::new();
    for f in &v.report.findings {
        // "bodies 'a' and 'b' overlap 12.0 mm deep at qpos0 and key 'down', and MuJoCo ...";
        // "body 'a' starts 5.0 mm deep at qpos0, 155.0 mm at key 'home' inside world plane ...".
        let (kind, names, depths) = match f.rule.as_str() {
            "U042" => {
                let (head, rest) = f.message.split_once(" overlap ").unwrap();
                let mut names = quoted(head);
                names.sort();
                ("pair", names, rest.split_once(", and MuJoCo").unwrap().0)
            }
            "U603" => {
                let (head, rest) = f.message.split_once(" starts ").unwrap();
                (
                    "floor",
                    quoted(head),
                    rest.split_once(" inside ").unwrap().0,
                )
            }
            _ => continue,
        };
        let mut poses = quoted(depths);
        if depths.contains("qpos0") {
            poses.insert(0, "qpos0".to_string());
        }
        for pose in poses {
            let mut fact = vec![pose, kind.to_string()];
            fact.extend(names.iter().cloned());
            facts.insert(fact);
        }
    }
    facts
}

fn facts(list: &[&str]) -> Facts {
    list.iter()
        .map(|f| f.split(' ').map(str::to_string).collect())
        .collect()
}

#[test]
fn the_contacts_at_the_start_are_mujocos() {
    let dir = Scratch::new("mujoco-agreement-contacts");
    let cases = contact_cases();
    let paths = write_cases(&dir, cases.iter().map(|(_, text, _)| text));
    for ((name, _, expected), path) in cases.iter().zip(&paths) {
        let v = validate(path, &options()).unwrap();
        assert_eq!(ours(&v), facts(expected), "{name}");
    }
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let script = common::repo_root().join("scripts/oracle/mjcf_start_contacts.py");
    let script = script.display().to_string();
    let output = python_output(&python, &[script.as_str(), "--facts"], &paths);
    let theirs: std::collections::HashMap<String, Option<Vec<Vec<String>>>> =
        serde_json::from_str(&output).unwrap();
    for ((name, _, expected), path) in cases.iter().zip(&paths) {
        let found = theirs[&path.display().to_string()]
            .clone()
            .unwrap_or_else(|| panic!("{name}: MuJoCo refuses the model"));
        assert_eq!(
            found.into_iter().collect::<Facts>(),
            facts(expected),
            "{name}: MuJoCo's start contacts"
        );
    }
}

#[test]
fn the_exclude_fix_stops_the_contacts_it_names() {
    let dir = Scratch::new("mujoco-agreement-fix");
    let (_, text, _) = contact_cases().swap_remove(0);
    let path = dir.file("arm.xml", &text);
    let v = validate(&path, &options()).unwrap();
    let u042: Vec<_> = v
        .report
        .findings
        .iter()
        .filter(|f| f.rule == "U042")
        .collect();
    // The pair at qpos0 has the fix; the pair only the key puts in contact has none (the key is wrong).
    let fixes: Vec<bool> = u042.iter().map(|f| f.fix.is_some()).collect();
    assert_eq!(fixes, [true, false], "{u042:#?}");
    let fix = u042[0].fix.as_ref().unwrap();
    assert!(fix.not_applicable.is_none(), "{fix:?}");
    let edits: Vec<_> = fix.edits.iter().map(|e| e.edit.clone()).collect();
    let (fixed, dropped) = urdf_validator::diagnostics::fix::apply(&text, &edits);
    assert!(dropped.is_empty());
    assert!(
        fixed.contains(
            "<contact>\n    <exclude body1=\"base_link\" body2=\"shoulder_link\"/>\n  </contact>"
        ),
        "{fixed}"
    );
    std::fs::write(&path, &fixed).unwrap();
    let again = validate(&path, &options()).unwrap();
    let left: Vec<&str> = again
        .report
        .findings
        .iter()
        .filter(|f| f.rule == "U042")
        .map(|f| f.message.as_str())
        .collect();
    assert_eq!(left.len(), 1, "{left:#?}");
    assert!(left[0].contains("'base_link' and 'arm_link'"), "{left:#?}");
    // Two siblings in contact at qpos0 get no exclude: it would let them pass through each other in
    // every pose (the FR3 with a hand: its fingers in link4).
    let siblings = dir.file(
        "siblings.xml",
        r#"<mujoco><worldbody><body name="base"><geom type="box" size="0.1 0.1 0.05"/>
<body name="left" pos="0 0.04 0.3"><joint axis="1 0 0"/><geom type="box" size="0.05 0.05 0.1"/></body>
<body name="right" pos="0 -0.04 0.3"><joint axis="1 0 0"/><geom type="box" size="0.05 0.05 0.1"/></body>
</body></worldbody></mujoco>"#,
    );
    let v = validate(&siblings, &options()).unwrap();
    let u042: Vec<_> = v
        .report
        .findings
        .iter()
        .filter(|f| f.rule == "U042")
        .collect();
    assert_eq!(u042.len(), 1, "{u042:#?}");
    assert!(u042[0].fix.is_none(), "{:?}", u042[0].fix);
}
