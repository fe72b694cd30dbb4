//! Untrusted input: every document or mesh here once made the validator panic, hang or run out of
//! memory (most were found by the fuzz targets in `crates/urdf-validator/fuzz`). Each test checks the
//! clear finding or error that replaces the failure, and that the rest of the report still runs.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::Path;
use std::time::{Duration, Instant};

use urdf_validator::input::mesh::load_mesh;
use urdf_validator::model::Model;
use urdf_validator::report::Report;
use urdf_validator::urdf::parse::parse_urdf;
use urdf_validator::{validate_text, Options};

/// Validate `urdf` with few workspace samples (the failures are not about the sampler's budget).
fn run(urdf: &str) -> Report {
    let mut options = Options::default();
    options.workspace.samples = 64;
    validate_text(urdf.to_string(), Path::new("t.urdf"), &options)
        .unwrap_or_else(|e| panic!("expected a parsed document, got LoadError: {e}"))
        .report
}

fn codes(report: &Report, code: &str) -> usize {
    report.findings.iter().filter(|f| f.rule == code).count()
}

/// A chain of `n` revolute joints, each (but the first) mimicking the one before it.
fn mimic_chain(n: usize) -> String {
    chain(
        n,
        "<inertial><mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>",
        |i| {
            let mimic = if i > 0 {
                format!("<mimic joint=\"j{}\"/>", i - 1)
            } else {
                String::new()
            };
            format!("<axis xyz=\"0 0 1\"/>{mimic}")
        },
    )
}

/// A chain of `n` revolute joints `j{i}` (limits ±1) from `l{i}` to `l{i+1}`: each link holds `link`,
/// joint `i` also holds `joint(i)`.
fn chain(n: usize, link: &str, joint: impl Fn(usize) -> String) -> String {
    let mut s = String::from("<robot name=\"r\">\n");
    for i in 0..=n {
        s += &format!("<link name=\"l{i}\">{link}</link>\n");
    }
    for i in 0..n {
        s += &format!(
            "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{i}\"/><child link=\"l{}\"/>\
             {}<limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"1\"/></joint>\n",
            i + 1,
            joint(i)
        );
    }
    s + "</robot>\n"
}

/// Found by review while fuzzing: mimic cycle detection walked every chain from every joint with a
/// linear `contains` (cubic: 12 s in the fuzz build for 2,000 chained mimics, a 600 KB file; many
/// minutes for 20,000), and
/// `apply_mimic` walked each follower's whole chain on every workspace and statics sample (quadratic per
/// sample). Both are linear now: the resolution order is computed once in `Model::build`.
#[test]
fn a_long_mimic_chain_builds_and_resolves_in_linear_time() {
    let urdf = mimic_chain(20_000);
    let started = Instant::now();
    let (robot, _) = parse_urdf(&urdf, Path::new("t.urdf")).expect("well-formed");
    let (model, findings) = Model::build(&robot);
    assert!(findings.is_empty(), "{findings:?}");
    let mut q = model.zero_configuration();
    for k in 0..200 {
        q[0] = k as f64 * 1e-3;
        model.apply_mimic(&mut q);
    }
    let elapsed = started.elapsed();
    assert_eq!(
        q[19_999], q[0],
        "every follower follows j0 with multiplier 1"
    );
    assert_eq!(model.mimic_order.len(), 19_999);
    assert!(
        elapsed < Duration::from_secs(10),
        "20,000 chained mimic joints took {elapsed:?}"
    );
}

/// The whole pipeline on a long mimic chain: every section still runs.
#[test]
fn a_long_mimic_chain_is_validated() {
    let report = run(&mimic_chain(1000));
    assert_eq!(codes(&report, "U312"), 0, "a chain is not a cycle");
    assert!(report.statics.is_some() && report.workspace.is_some());
}

/// A long chain of mimics ending in a cycle is reported once, from the cycle's first joint.
#[test]
fn a_mimic_cycle_at_the_end_of_a_long_tail_is_reported_once() {
    let urdf = mimic_chain(5).replace("<mimic joint=\"j3\"/>", "<mimic joint=\"j3\"/><!-- j4 -->");
    // j0 follows j4: j0 → j4 → j3 → j2 → j1 → j0.
    let urdf = urdf.replacen(
        "<limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"1\"/></joint>",
        "<limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"1\"/><mimic joint=\"j4\"/></joint>",
        1,
    );
    let report = run(&urdf);
    let cycles: Vec<_> = report
        .findings
        .iter()
        .filter(|f| f.rule == "U312")
        .collect();
    assert_eq!(cycles.len(), 1, "{cycles:#?}");
    assert!(
        cycles[0].message.ends_with("j0 → j4 → j3 → j2 → j1 → j0"),
        "{}",
        cycles[0].message
    );
}

/// A scratch folder for mesh files, unique per test.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "urdf-validator-robustness-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    dir
}

/// Found while fuzzing the mesh loader: a 47 KB COLLADA file whose four levels of ten `<instance_node>`s
/// (each with its own translation) instantiate one 2,000-position geometry 10,000 times, 20 million
/// distinct vertices: 1.6 GB and 30 s, just within the file-independent vertex limit. Instantiated
/// vertices are now bounded by the file size.
#[test]
fn a_collada_instancing_bomb_is_refused_with_a_clear_error() {
    let positions: Vec<String> = (0..6000)
        .map(|i| format!("{:.4}", (i * 7919 % 6007) as f64 / 6007.0))
        .collect();
    let mut nodes = Vec::new();
    for level in 0..4 {
        let next = if level < 3 {
            format!("<instance_node url=\"#n{}\"/>", level + 1)
        } else {
            "<instance_geometry url=\"#g\"/>".to_string()
        };
        let kids: String = (0..10)
            .map(|i| {
                format!(
                    "<node><translate>{} {} 0</translate>{next}</node>",
                    i * 2 * 10i64.pow(level),
                    i
                )
            })
            .collect();
        nodes.push(format!("<node id=\"n{level}\">{kids}</node>"));
    }
    let dae = format!(
        "<?xml version=\"1.0\"?>\n<COLLADA>\n<library_geometries><geometry id=\"g\"><mesh>\
         <source id=\"s\"><float_array id=\"f\" count=\"6000\">{}</float_array></source>\
         <vertices id=\"v\"><input semantic=\"POSITION\" source=\"#s\"/></vertices></mesh></geometry>\
         </library_geometries>\n<library_nodes>{}</library_nodes>\n<library_visual_scenes>\
         <visual_scene id=\"vs\">{}</visual_scene></library_visual_scenes>\n\
         <scene><instance_visual_scene url=\"#vs\"/></scene></COLLADA>\n",
        positions.join(" "),
        nodes[1..].concat(),
        nodes[0]
    );
    let path = scratch("bomb").join("bomb.dae");
    std::fs::write(&path, &dae).expect("write mesh");
    let started = Instant::now();
    let error = load_mesh(&path).expect_err("20 million instantiated vertices from 47 KB");
    assert!(started.elapsed() < Duration::from_secs(10));
    assert_eq!(error.path, path);
    assert!(
        error.message.starts_with("line 3: geometry instantiated by the visual scene: more than 1000000 vertices instantiated"),
        "{}",
        error.message
    );
}

/// Found while fuzzing the mesh loader: the position of a bad number in a COLLADA `<float_array>` was
/// its offset in the expanded text added to the text's start in the file. Text from an entity lies in
/// the DTD and has another length, so that position could fall inside a multi-byte character of a
/// later declaration, and roxmltree's `text_pos_at` panicked ("byte index is not a char boundary").
/// Such text is now located at its element.
#[test]
fn a_bad_number_from_an_entity_in_collada_is_located_at_its_element() {
    let dae = format!(
        "<?xml version=\"1.0\"?>\n\
         <!DOCTYPE COLLADA [<!ENTITY a \"1 1 1 1 1 1 1 1 1 1 \"><!ENTITY z \"{}\">\
         <!ENTITY e \"&a;&a;&a;&a;&a; x\">]>\n\
         <COLLADA><library_geometries><geometry id=\"g\"><mesh><source id=\"s\">\
         <float_array id=\"f\">&e;</float_array></source><vertices id=\"v\">\
         <input semantic=\"POSITION\" source=\"#s\"/></vertices></mesh></geometry>\
         </library_geometries></COLLADA>\n",
        "é".repeat(60)
    );
    let column = dae
        .lines()
        .nth(2)
        .and_then(|l| l.find("<float_array"))
        .expect("line 3")
        + 1;
    let path = scratch("entity").join("entity.dae");
    std::fs::write(&path, &dae).expect("write mesh");
    let error = load_mesh(&path).expect_err("'x' is not a number");
    assert_eq!(
        error.message,
        format!("line 3, column {column}: expected a finite number in <float_array>, found 'x'")
    );
    // Without references, the token itself is located.
    let plain = "<COLLADA><library_geometries><geometry id=\"g\"><mesh><source id=\"s\">\n\
                 <float_array id=\"f\">1 2 3\n 4 oops 6</float_array></source><vertices id=\"v\">\
                 <input semantic=\"POSITION\" source=\"#s\"/></vertices></mesh></geometry>\
                 </library_geometries></COLLADA>\n";
    let path = scratch("entity").join("plain.dae");
    std::fs::write(&path, plain).expect("write mesh");
    let error = load_mesh(&path).expect_err("'oops' is not a number");
    assert_eq!(
        error.message,
        "line 3, column 4: expected a finite number in <float_array>, found 'oops'"
    );
}

/// A chain of `n` revolute links, each with a small box to collide with.
fn box_chain(n: usize) -> String {
    chain(
        n,
        "<inertial><mass value=\"0.1\"/>\
         <inertia ixx=\"1e-4\" ixy=\"0\" ixz=\"0\" iyy=\"1e-4\" iyz=\"0\" izz=\"1e-4\"/></inertial>\
         <collision><geometry><box size=\"0.01 0.01 0.01\"/></geometry></collision>",
        |_| "<origin xyz=\"0 0 0.02\"/><axis xyz=\"0 1 0\"/>".to_string(),
    )
}

/// Arm detection, leg search, the arm's chain and the payload capacity walk a 20,000-link chain once (each
/// was quadratic: 3.4 s and 447 MB in release); self-collision, whose matrix is quadratic by nature, says
/// it was not assessed past its link limit instead of taking minutes and gigabytes.
#[test]
fn a_long_chain_is_validated_in_linear_time_and_self_collision_is_bounded() {
    let urdf = box_chain(20_000);
    let started = Instant::now();
    let report = run(&urdf);
    let elapsed = started.elapsed();
    let workspace = report.workspace.expect("a workspace section");
    assert_eq!(workspace.arms.len(), 1);
    assert_eq!(workspace.self_collision_free_fraction, None);
    assert_eq!(
        workspace.self_collision_not_assessed.as_deref(),
        Some("the robot has more than 1024 links (a limit that bounds self-collision's time and memory)")
    );
    assert!(
        elapsed < Duration::from_secs(20),
        "a 20,000-link chain took {elapsed:?}"
    );
    // Below the limit, the same chain is checked.
    let short = run(&box_chain(200)).workspace.expect("a workspace section");
    assert!(short.self_collision_free_fraction.is_some());
}

/// Found by a user (issue 26): a 20,000-link chain lying on the ground (joints 1 mm apart along x) took
/// 27.7 s to classify in release, as every ground-touching link walked its names up to the body (quadratic,
/// a string per name); the names are counted once down the tree now (22 ms).
#[test]
fn a_long_chain_lying_on_the_ground_is_classified_in_linear_time() {
    let urdf = chain(
        20_000,
        "<inertial><mass value=\"0.01\"/>\
         <inertia ixx=\"1e-6\" ixy=\"0\" ixz=\"0\" iyy=\"1e-6\" iyz=\"0\" izz=\"1e-6\"/></inertial>",
        |_| "<origin xyz=\"0.001 0 0\"/><axis xyz=\"0 0 1\"/>".to_string(),
    );
    let mut options = Options::default();
    options.workspace.samples = 16;
    options.timings = true;
    let report = validate_text(urdf, Path::new("t.urdf"), &options)
        .unwrap_or_else(|e| panic!("{e}"))
        .report;
    let timings = report.timings_ms.expect("timings");
    let classify = timings
        .phases()
        .iter()
        .find(|(phase, _)| *phase == "classify")
        .map(|(_, ms)| *ms)
        .expect("a classify phase");
    assert!(classify < 3_000.0, "classify took {classify} ms");
}

/// Found in review: every link welded below the wrist copied its whole path of fixed joints (quadratic:
/// 20,000 welded links took 4.2 s and 2.5 GB).
#[test]
fn a_long_welded_chain_below_the_wrist_is_linear() {
    let mut urdf = box_chain(4);
    let mut welded = String::new();
    for i in 0..20_000 {
        let parent = if i == 0 {
            "l4".to_string()
        } else {
            format!("w{}", i - 1)
        };
        welded += &format!(
            "<link name=\"w{i}\"/><joint name=\"f{i}\" type=\"fixed\"><parent link=\"{parent}\"/><child link=\"w{i}\"/></joint>\n"
        );
    }
    urdf = urdf.replace("</robot>", &format!("{welded}</robot>"));
    let started = Instant::now();
    let workspace = run(&urdf).workspace.expect("a workspace section");
    assert_eq!(workspace.arms.len(), 1);
    assert!(
        started.elapsed() < Duration::from_secs(20),
        "took {:?}",
        started.elapsed()
    );
}

/// Found in review: an SRDF repeating `disable_default_collisions` and `enable_collisions` entries by the
/// thousand made the allowed-pair set-up cubic (823 KB: 20 s).
#[test]
fn a_huge_repetitive_srdf_is_applied_in_linear_time() {
    let dir = scratch("huge-srdf");
    let urdf = dir.join("chain.urdf");
    std::fs::write(&urdf, box_chain(200)).unwrap();
    let mut srdf = String::from("<robot name=\"r\">");
    for _ in 0..9_000 {
        srdf += "<disable_default_collisions link=\"l0\"/><enable_collisions link1=\"l0\" link2=\"l7\"/>";
    }
    srdf += "</robot>";
    std::fs::write(dir.join("chain.srdf"), srdf).unwrap();
    let mut options = Options::default();
    options.workspace.samples = 64;
    let started = Instant::now();
    let report = urdf_validator::validate(&urdf, &options).unwrap().report;
    assert!(report.workspace.unwrap().self_collision_srdf_disabled > 0);
    assert!(
        started.elapsed() < Duration::from_secs(20),
        "took {:?}",
        started.elapsed()
    );
}

/// Found by the `urdf` fuzz target (3 timeouts, each a hang): in the example robot, `wrist_1_joint` names a
/// child that does not exist and `wrist_3_joint`'s child is `wrist_1_link`, so wrist_1 → wrist_2 → wrist_1
/// is a loop of parent joints no root reaches. Walks up the parents (self-collision's path test) never
/// ended. The loop is reported and left out of the Model; the rest of the robot is still analysed.
#[test]
fn a_loop_cut_off_from_the_root_is_reported_and_does_not_hang() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/robots/mobile_manipulator.urdf");
    let text = std::fs::read_to_string(&path).expect("the example robot ships with the repo");
    let wrist_1 = "<joint name=\"wrist_1_joint\" type=\"revolute\">\n    <parent link=\"forearm_link\"/>\n    <child link=\"wrist_1_link\"/>";
    let wrist_3 = "<joint name=\"wrist_3_joint\" type=\"revolute\">\n    <parent link=\"wrist_2_link\"/>\n    <child link=\"wrist_3_link\"/>";
    assert!(
        text.contains(wrist_1) && text.contains(wrist_3),
        "the example robot changed"
    );
    let edited = text
        .replace(
            wrist_1,
            &wrist_1.replace("\"wrist_1_link\"", "\"nonexistent_link\""),
        )
        .replace(
            wrist_3,
            &wrist_3.replace("\"wrist_3_link\"", "\"wrist_1_link\""),
        );
    let (done, result) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = done.send(run(&edited));
    });
    let report = result
        .recv_timeout(Duration::from_secs(60))
        .expect("validation did not finish within 60 s (the loop hangs a walk)");
    let loops: Vec<_> = report
        .findings
        .iter()
        .filter(|f| f.rule == "U103")
        .collect();
    assert!(
        loops
            .iter()
            .any(|f| f.message.contains("wrist_1_link") && f.message.contains("wrist_2_link")),
        "the loop is named: {loops:#?}"
    );
    assert!(
        report.statics.is_some(),
        "the rest of the robot is still analysed"
    );
}

/// A run its watchdog has given up on stops before its next stage, naming it, instead of working on for
/// nobody (its threads are needed by the other files of the batch).
#[test]
fn a_cancelled_run_gives_up_before_its_next_stage() {
    let progress = urdf_validator::timings::Progress::with_time_limit(5.0);
    progress.cancel();
    let options = Options {
        progress: Some(progress),
        ..Options::default()
    };
    let urdf = box_chain(3);
    let Err(error) = validate_text(urdf, Path::new("chain.urdf"), &options) else {
        panic!("a cancelled run was not given up");
    };
    let message = error.to_string();
    assert!(
        message.contains("did not finish within 5 s (stage running: assets)"),
        "{message}"
    );
    // Without a cancellation the same run finishes.
    assert!(validate_text(box_chain(3), Path::new("chain.urdf"), &Options::default()).is_ok());
}
