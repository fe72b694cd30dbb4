//! MuJoCo's minimum for moving bodies ("mass and inertia of moving bodies must be larger than mjMINVAL"):
//! for each small model, our U030 at the body exactly when MuJoCo 4.0 (from `URDF_VALIDATOR_PYTHON`,
//! compiled during the test) refuses it. MuJoCo accepts a moving body when it, or a body welded to it, has
//! by itself a mass and three principal moments of at least 1e-15; the group's combined inertia does not
//! count. Without MuJoCo the test skips, except under `CI=true`, where it fails.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

mod common;

use std::process::Command;

use urdf_validator::{validate, Options};

const TINY: &str = r#"<inertial pos="0 0 0" mass="1" diaginertia="1e-20 1e-20 1e-20"/>"#;
const HEAVY: &str = r#"<inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/>"#;

/// (what, the body `b`'s content): each a case either side of MuJoCo's rule.
fn cases() -> Vec<(&'static str, String)> {
    let inertial =
        |mass: &str, i: &str| format!(r#"<inertial pos="0 0 0" mass="{mass}" diaginertia="{i}"/>"#);
    vec![
        ("heavy hinge", format!("<joint/>{HEAVY}")),
        ("tiny inertia", format!("<joint/>{TINY}")),
        (
            "one moment tiny",
            format!("<joint/>{}", inertial("1", "1 1 1e-20")),
        ),
        (
            "moments at 1e-15",
            format!("<joint/>{}", inertial("1", "1e-15 1e-15 1e-15")),
        ),
        (
            "moments at 5e-16",
            format!("<joint/>{}", inertial("1", "5e-16 5e-16 5e-16")),
        ),
        (
            "mass tiny",
            format!("<joint/>{}", inertial("1e-20", "1 1 1")),
        ),
        ("free, tiny inertia", format!("<freejoint/>{TINY}")),
        (
            "ball, tiny inertia",
            format!(r#"<joint type="ball"/>{TINY}"#),
        ),
        (
            "slide, tiny inertia",
            format!(r#"<joint type="slide"/>{TINY}"#),
        ),
        ("tiny sphere", r#"<joint/><geom size="1e-4"/>"#.to_string()),
        ("small sphere", r#"<joint/><geom size="1e-2"/>"#.to_string()),
        (
            "tiny, welded heavy child",
            format!("<joint/>{TINY}<body>{HEAVY}</body>"),
        ),
        (
            "tiny, welded tiny, welded heavy",
            format!("<joint/>{TINY}<body>{TINY}<body>{HEAVY}</body></body>"),
        ),
        (
            "no inertial, welded heavy child",
            format!("<joint/><body>{HEAVY}</body>"),
        ),
        (
            "tiny, moving heavy child",
            format!("<joint/>{TINY}<body><joint/>{HEAVY}</body>"),
        ),
        (
            "three welded point masses",
            format!(
                r#"<joint/>{TINY}<body pos="1 0 0">{TINY}</body><body pos="0 1 0">{TINY}</body><body pos="0 0 1">{TINY}</body>"#
            ),
        ),
        (
            "two bodies each missing another moment",
            format!(
                "<joint/>{}<body>{}</body>",
                inertial("1", "1 1e-20 1"),
                inertial("1", "1 1 1e-20")
            ),
        ),
        (
            "mass in one, inertia in the other",
            format!("<joint/>{TINY}<body>{}</body>", inertial("1e-20", "1 1 1")),
        ),
    ]
}

fn mujoco_refuses(python: &std::path::Path, path: &std::path::Path) -> Option<String> {
    let out = Command::new(python)
        .args([
            "-c",
            "import sys, mujoco\ntry:\n    mujoco.MjModel.from_xml_path(sys.argv[1])\nexcept ValueError as e:\n    print(str(e).splitlines()[0])",
        ])
        .arg(path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let message = String::from_utf8_lossy(&out.stdout).trim().to_string();
    (!message.is_empty()).then_some(message)
}

#[test]
fn u030_for_a_moving_body_exactly_when_mujoco_refuses_it() {
    let Some(python) = common::mujoco_python() else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("urdf-validator-mjminval-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut options = Options::default();
    options.workspace.samples = 50;
    options.deep.automatic = false;
    let mut refused = 0;
    for (i, (what, body)) in cases().iter().enumerate() {
        let path = dir.join(format!("case{i}.xml"));
        std::fs::write(
            &path,
            format!(
                "<mujoco>\n<worldbody>\n<body name=\"b\" pos=\"0 0 1\">{body}</body>\n</worldbody>\n</mujoco>\n"
            ),
        )
        .unwrap();
        let theirs = mujoco_refuses(&python, &path);
        let report = validate(&path, &options).unwrap().report;
        let ours: Vec<_> = report
            .findings
            .iter()
            .filter(|f| f.rule == "U030" && f.message.contains("mjMINVAL"))
            .collect();
        match &theirs {
            Some(message) => {
                assert!(
                    message.contains("mjMINVAL"),
                    "{what}: MuJoCo says {message}"
                );
                assert_eq!(ours.len(), 1, "{what}: MuJoCo refuses it, we say {ours:#?}");
                assert_eq!(ours[0].line, Some(3), "{what}: at the body");
                refused += 1;
            }
            None => assert!(
                ours.is_empty(),
                "{what}: MuJoCo accepts it, we say {ours:#?}"
            ),
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    // Both sides of the rule are exercised.
    assert!(
        refused >= 8 && refused + 5 <= cases().len(),
        "{refused} refused"
    );
}
