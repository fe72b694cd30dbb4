//! Differential tests: our expansion against Python xacro 2.1.1 (`URDF_VALIDATOR_XACRO`) on the real
//! robot trees and on the fixtures, compared after canonicalisation (element names, attributes as sorted
//! maps, trimmed non-whitespace text; comments and whitespace between elements ignored) and then byte for
//! byte (comments and layout as xacro writes them, banner included). When both fail, the error classes must
//! agree.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

mod common;

use std::path::{Path, PathBuf};

use common::*;

fn xacro_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "xacro") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

#[test]
fn pr2_every_xacro_file() {
    let (Some(oracle), Some(robots)) = (oracle(), shared_robots()) else {
        return;
    };
    let pkg = robots.join("pr2/pr2_description");
    let prefix = ament_prefix("pr2", &[("pr2_description", pkg.clone())]);
    let share = prefix.join("share/pr2_description");
    // Through the package path, as `$(find)` sees it (relative includes then agree too).
    let files = xacro_files(&pkg);
    assert!(
        files.len() >= 50,
        "expected the 53 PR2 xacro files, found {}",
        files.len()
    );
    let cases: Vec<_> = files
        .iter()
        .map(|f| (share.join(f.strip_prefix(&pkg).expect("below pkg")), vec![]))
        .collect();
    assert!(cases
        .iter()
        .any(|(f, _)| f.ends_with("robots/pr2.urdf.xacro")));
    check_all(&oracle, &cases, &env_for(&prefix));
}

#[test]
fn franka_frankie() {
    let (Some(oracle), Some(robots)) = (oracle(), shared_robots()) else {
        return;
    };
    let pkg = robots.join("franka_panda/franka_description");
    let prefix = ament_prefix("franka", &[("franka_description", pkg.clone())]);
    let share = prefix.join("share/franka_description/robots");
    let cases = [
        "frankie_arm_hand.urdf.xacro",
        "frankie_arm.xacro",
        "hand.xacro",
    ]
    .iter()
    .map(|f| (share.join(f), vec![]))
    .collect::<Vec<_>>();
    check_all(&oracle, &cases, &env_for(&prefix));
}

#[test]
fn husky_with_and_without_laser() {
    let (Some(oracle), Some(robots)) = (oracle(), shared_robots()) else {
        return;
    };
    let husky = robots.join("husky/husky_description");
    let lms = robots.join("husky/lms1xx");
    let prefix = ament_prefix("husky", &[("husky_description", husky), ("lms1xx", lms)]);
    let main = prefix.join("share/husky_description/urdf/husky.urdf.xacro");
    let cases = vec![
        (main.clone(), vec![]),
        (main.clone(), vec![("laser_enabled", "true")]),
        (
            main.clone(),
            vec![("laser_enabled", "true"), ("realsense_enabled", "true")],
        ),
        (
            prefix.join("share/lms1xx/urdf/sick_lms1xx.urdf.xacro"),
            vec![],
        ),
    ];
    check_all(&oracle, &cases, &env_for(&prefix));
}

#[test]
fn hector_quadrotor() {
    let (Some(oracle), Some(corpus)) = (oracle(), corpus()) else {
        return;
    };
    let files = xacro_files(&corpus.join("hector_description"));
    assert_eq!(
        files.len(),
        2,
        "expected example-robot-data's two hector xacros: {files:?}"
    );
    let prefix = ament_prefix(
        "hector",
        &[("hector_description", corpus.join("hector_description"))],
    );
    let cases: Vec<_> = files.into_iter().map(|f| (f, vec![])).collect();
    check_all(&oracle, &cases, &env_for(&prefix));
}

/// `python.set` / `python.frozenset` as shadow-robot/sr_common uses them (issue 42): membership, `len`,
/// `sorted`, `| & - ^`, the methods, and sets passed to macros to validate parameters, on valid and invalid
/// parameters (an unknown one reaches `xacro.error`; a bool in the error text fails in both).
#[test]
fn python_sets_like_sr_common() {
    let Some(oracle) = oracle() else { return };
    let file = fixtures().join("sets.xacro");
    let cases: Vec<(PathBuf, Vec<(&str, &str)>)> = [
        vec![],
        vec![
            ("side", "left"),
            ("fingers", "th lf rf"),
            ("mounting_plate", "true"),
        ],
        vec![("side", "middle"), ("fingers", "th zz")],
        vec![("mounting_plate", "maybe")],
    ]
    .into_iter()
    .map(|args| (file.clone(), args))
    .collect();
    check_all(&oracle, &cases, &[]);
}

/// `python.isinstance` as shadow-robot/sr_common normalises its parameters (issue 42): fingers given as
/// `all` or a string, sensors as a string, a list or a dict, the built-in classes (bool an int, tuples of
/// classes), and the failures: an unknown finger reaches `xacro.fatal`, a non-class is a `TypeError`.
#[test]
fn python_isinstance_like_sr_common() {
    let Some(oracle) = oracle() else { return };
    let file = fixtures().join("isinstance.xacro");
    let cases: Vec<(PathBuf, Vec<(&str, &str)>)> = [
        vec![],
        vec![
            ("fingers", "TH,ff"),
            ("tip_sensors", "th=BT_SP, ff=pst"),
            ("kind", "seq"),
        ],
        vec![
            ("fingers", "th mf"),
            ("tip_sensors", "bt_2p"),
            ("kind", "dict"),
        ],
        vec![("fingers", "th,zz")],
        vec![("kind", "bad")],
    ]
    .into_iter()
    .map(|args| (file.clone(), args))
    .collect();
    check_all(&oracle, &cases, &[]);
}

/// `fixtures/*.xacro`; a `NAME.args` file beside one holds `name:=value` arguments, one per line.
#[test]
fn fixtures_match_python_xacro() {
    let Some(oracle) = oracle() else { return };
    let dir = fixtures();
    let prefix = ament_prefix("fixtures", &[("fixture_pkg", dir.join("fixture_pkg"))]);
    let mut env = env_for(&prefix);
    env.push(("XACRO_TEST_VAR".into(), "from_env".into()));
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("fixtures dir")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "xacro"))
        .collect();
    files.sort();
    let arg_texts: Vec<String> = files
        .iter()
        .map(|f| std::fs::read_to_string(f.with_extension("args")).unwrap_or_default())
        .collect();
    let cases: Vec<(PathBuf, Vec<(&str, &str)>)> = files
        .iter()
        .zip(&arg_texts)
        .map(|(f, text)| {
            let args = text
                .lines()
                .filter_map(|l| l.split_once(":="))
                .map(|(k, v)| (k.trim(), v.trim()))
                .collect();
            (f.clone(), args)
        })
        .collect();
    assert!(cases.len() >= 20, "fixtures missing");
    check_all(&oracle, &cases, &env);
}
