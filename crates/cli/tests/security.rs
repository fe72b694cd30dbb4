//! The security suite (issue 29, SECURITY.md): hostile robot files against the sandbox.
//!
//! A canary secret is in the environment and a canary file is outside the roots. For every hostile input,
//! in untrusted mode, no output format (text, JSON, SARIF, JUnit, GitHub, HTML) holds either canary, the
//! output says what was refused, the run ends, and under `strace -f -e trace=openat,open` the process opens
//! nothing outside the roots but the system files the binary itself needs. In trusted mode (the default)
//! every input ends too, and the inputs that read the environment or a file outside still do (today's
//! behaviour, and the proof that the canary checks can fail). The fixtures are made at test time in a
//! temporary folder: symlinks, a FIFO, a symlink to /dev/zero.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// The secret in the environment.
const ENV_CANARY: &str = "CANARYENVq9x4t";
/// The variable holding it.
const ENV_NAME: &str = "URDF_SECURITY_CANARY";
/// The secret in the files outside the roots.
const FILE_CANARY: &str = "CANARYFILEz8w2k";

/// A tetrahedron, in ASCII STL, its solid named after the file canary.
fn stl() -> String {
    format!(
        "solid {FILE_CANARY}\n{}endsolid {FILE_CANARY}\n",
        [
            ("0 0 0", "1 0 0", "0 1 0"),
            ("0 0 0", "0 1 0", "0 0 1"),
            ("0 0 0", "0 0 1", "1 0 0"),
            ("1 0 0", "0 1 0", "0 0 1"),
        ]
        .iter()
        .map(|(a, b, c)| format!(
            "facet normal 0 0 0\nouter loop\nvertex {a}\nvertex {b}\nvertex {c}\nendloop\nendfacet\n"
        ))
        .collect::<String>()
    )
}

/// A URDF whose one link has a mesh `uri`.
fn mesh_robot(uri: &str) -> String {
    format!(
        "<robot name=\"m\"><link name=\"base\"><visual><geometry><mesh filename=\"{uri}\"/></geometry></visual>\
         <collision><geometry><mesh filename=\"{uri}\"/></geometry></collision></link></robot>\n"
    )
}

/// A xacro robot with `body` inside `<robot>`.
fn xacro(name: &str, body: &str) -> String {
    format!(
        "<robot name=\"{name}\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n{body}\n<link name=\"base\"/>\n</robot>\n"
    )
}

/// An SDFormat world including `uri`.
fn sdf_including(uri: &str) -> String {
    format!(
        "<?xml version=\"1.0\"?>\n<sdf version=\"1.9\"><world name=\"w\"><include><uri>{uri}</uri></include></world></sdf>\n"
    )
}

/// What an input must make the untrusted run say.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Expect {
    /// A U013 finding or a refusal message.
    Refused,
    /// Nothing to refuse (a parser bound): the run ends, without the canaries.
    Bounded,
}

/// One hostile input: its file name in the root, what untrusted mode says, and whether the trusted run
/// shows a canary (today's behaviour).
struct Hostile {
    file: &'static str,
    expect: Expect,
    leaks_when_trusted: bool,
}

/// The temporary tree: `root/` (the input folder), `outside/` (canary files), and package and model
/// folders beside `root` that the walk up from it finds.
struct Tree {
    base: PathBuf,
}

impl Tree {
    fn root(&self) -> PathBuf {
        self.base.join("root")
    }

    fn outside(&self) -> PathBuf {
        self.base.join("outside")
    }
}

impl Drop for Tree {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.base);
    }
}

fn write(path: &Path, text: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

/// Make the tree and every hostile input; the inputs, in order.
fn hostile_tree(name: &str) -> (Tree, Vec<Hostile>) {
    let base = std::env::temp_dir().join(format!("urdf_security_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&base);
    let tree = Tree { base };
    let root = tree.root();
    let outside = tree.outside();
    std::fs::create_dir_all(&root).unwrap();
    let out = outside.display().to_string();
    // The canary files outside the roots.
    write(&outside.join("secret.txt"), &format!("{FILE_CANARY}\n"));
    write(
        &outside.join("secret.yaml"),
        &format!("name: {FILE_CANARY}\n"),
    );
    write(
        &outside.join("secret.xacro"),
        &format!("<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\"><link name=\"{FILE_CANARY}\"/></robot>\n"),
    );
    write(&outside.join("m.stl"), &stl());
    write(
        &outside.join("pkg/package.xml"),
        "<package><name>linkedpkg</name></package>\n",
    );
    write(&outside.join("pkg/m.stl"), &stl());
    write(
        &outside.join("model/model.sdf"),
        &format!("<sdf version=\"1.9\"><model name=\"{FILE_CANARY}\"><link name=\"{FILE_CANARY}\"/></model></sdf>\n"),
    );
    write(
        &outside.join("secret.srdf"),
        &format!("<robot name=\"{FILE_CANARY}\"/>\n"),
    );
    write(
        &outside.join("secret.urdf"),
        &format!("<robot name=\"{FILE_CANARY}\"><link name=\"a\"/></robot>\n"),
    );
    // A package and a Gazebo model beside the root: the walk up from the input finds them.
    write(
        &tree.base.join("evilpkg/package.xml"),
        "<package><name>evilpkg</name></package>\n",
    );
    write(&tree.base.join("evilpkg/m.stl"), &stl());
    write(
        &tree.base.join("evilpkg/secret.xacro"),
        &format!("<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\"><link name=\"{FILE_CANARY}\"/></robot>\n"),
    );
    write(
        &tree.base.join("evilmodel/model.sdf"),
        &format!("<sdf version=\"1.9\"><model name=\"{FILE_CANARY}\"><link name=\"{FILE_CANARY}\"/></model></sdf>\n"),
    );
    let symlink =
        |target: &Path, link: &str| std::os::unix::fs::symlink(target, root.join(link)).unwrap();
    symlink(&outside.join("secret.xacro"), "link.xacro");
    symlink(&outside.join("pkg"), "linkedpkg");
    symlink(Path::new("/dev/zero"), "zero.stl");
    symlink(&outside.join("secret.srdf"), "srdfbot.srdf");
    symlink(&outside.join("secret.urdf"), "entry_symlink.urdf");
    let fifo = Command::new("mkfifo")
        .arg(root.join("fifo.stl"))
        .status()
        .unwrap();
    assert!(fifo.success(), "mkfifo");
    write(
        &root.join("params.yaml"),
        &format!("name: \"$(env {ENV_NAME})\"\n"),
    );
    write(
        &root.join("inner/model.sdf"),
        &format!("<sdf version=\"1.9\"><model name=\"inner\"><include><uri>{out}/model</uri></include><link name=\"l\"/></model></sdf>\n"),
    );

    let env = format!("$(env {ENV_NAME})");
    let inputs: Vec<(&'static str, String, Expect, bool)> = vec![
        ("env_robot_name.urdf.xacro", xacro(&env, ""), Expect::Refused, true),
        ("env_link_attribute.urdf.xacro", xacro("r", &format!("<link name=\"l_{env}\"/>")), Expect::Refused, true),
        ("optenv_default.urdf.xacro", xacro(&format!("$(optenv {ENV_NAME} fallback)"), ""), Expect::Refused, true),
        ("env_in_text.urdf.xacro", xacro("r", &format!("<link name=\"t\"><visual><material name=\"m\">{env}</material></visual></link>")), Expect::Refused, false),
        ("env_arg_default.urdf.xacro", xacro("r", &format!("<xacro:arg name=\"a\" default=\"{env}\"/><link name=\"$(arg a)\"/>")), Expect::Refused, true),
        ("env_property.urdf.xacro", xacro("r", &format!("<xacro:property name=\"p\" value=\"{env}\"/><link name=\"${{p}}\"/>")), Expect::Refused, true),
        ("env_macro_default.urdf.xacro", xacro("r", &format!("<xacro:macro name=\"m\" params=\"n:={env}\"><link name=\"${{n}}\"/></xacro:macro><xacro:m/>")), Expect::Refused, true),
        ("env_in_yaml.urdf.xacro", xacro("r", "<xacro:property name=\"y\" value=\"${load_yaml('params.yaml')}\"/><link name=\"${y['name']}\"/>"), Expect::Bounded, false),
        ("include_absolute.urdf.xacro", xacro("r", &format!("<xacro:include filename=\"{out}/secret.xacro\"/>")), Expect::Refused, true),
        ("include_dotdot.urdf.xacro", xacro("r", "<xacro:include filename=\"../outside/secret.xacro\"/>"), Expect::Refused, true),
        ("include_symlink.urdf.xacro", xacro("r", "<xacro:include filename=\"link.xacro\"/>"), Expect::Refused, true),
        ("include_glob.urdf.xacro", xacro("r", &format!("<xacro:include filename=\"{out}/*.xacro\"/>")), Expect::Refused, true),
        ("include_text_file.urdf.xacro", xacro("r", "<xacro:include filename=\"../outside/secret.txt\"/>"), Expect::Refused, false),
        ("find_outside.urdf.xacro", xacro("r", "<xacro:include filename=\"$(find evilpkg)/secret.xacro\"/>"), Expect::Refused, true),
        ("load_yaml_outside.urdf.xacro", xacro("r", "<xacro:property name=\"y\" value=\"${load_yaml('../outside/secret.yaml')}\"/><link name=\"${y['name']}\"/>"), Expect::Refused, true),
        ("load_yaml_environ.urdf.xacro", xacro("r", "<xacro:property name=\"y\" value=\"${load_yaml('/proc/self/environ')}\"/><link name=\"${y}\"/>"), Expect::Refused, false),
        ("mesh_file_uri.urdf", mesh_robot(&format!("file://{out}/m.stl")), Expect::Refused, false),
        ("mesh_absolute.urdf", mesh_robot(&format!("{out}/m.stl")), Expect::Refused, false),
        ("mesh_dotdot.urdf", mesh_robot("../outside/m.stl"), Expect::Refused, false),
        ("mesh_package_outside.urdf", mesh_robot("package://evilpkg/m.stl"), Expect::Refused, false),
        ("mesh_symlinked_package.urdf", mesh_robot("package://linkedpkg/m.stl"), Expect::Refused, false),
        ("mesh_dev_zero.urdf", mesh_robot("zero.stl"), Expect::Refused, false),
        ("mesh_dev_uri.urdf", mesh_robot("file:///dev/zero"), Expect::Refused, false),
        ("mesh_fifo.urdf", mesh_robot("fifo.stl"), Expect::Refused, false),
        ("sdf_include_outside.sdf", sdf_including(&format!("file://{out}/model")), Expect::Refused, true),
        ("sdf_model_uri.sdf", sdf_including("model://evilmodel"), Expect::Refused, true),
        ("sdf_include_chain.sdf", sdf_including("inner"), Expect::Refused, true),
        ("srdfbot.urdf", "<robot name=\"srdfbot\"><link name=\"a\"/></robot>\n".to_string(), Expect::Refused, false),
        ("dtd_external_entity.urdf", format!("<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM \"file://{out}/secret.txt\">]>\n<robot name=\"&x;\"><link name=\"a\"/></robot>\n"), Expect::Bounded, false),
        ("billion_laughs.urdf", billion_laughs(), Expect::Bounded, false),
        ("deep_nesting.urdf", format!("<robot name=\"r\">{}{}</robot>", "<a>".repeat(200_000), "</a>".repeat(200_000)), Expect::Bounded, false),
        ("deep_nesting.urdf.xacro", xacro("r", &format!("{}{}", "<a>".repeat(50_000), "</a>".repeat(50_000))), Expect::Bounded, false),
    ];
    let mut hostile = Vec::new();
    for (file, text, expect, leaks_when_trusted) in inputs {
        write(&root.join(file), &text);
        hostile.push(Hostile {
            file,
            expect,
            leaks_when_trusted,
        });
    }
    // The entry file itself a symlink out of its folder (made above).
    hostile.push(Hostile {
        file: "entry_symlink.urdf",
        expect: Expect::Refused,
        leaks_when_trusted: true,
    });
    (tree, hostile)
}

/// Nested entities, ten to a level, nine levels deep.
fn billion_laughs() -> String {
    let mut dtd = String::from("<!ENTITY l0 \"lol\">");
    for level in 1..10 {
        let refs = format!("&l{};", level - 1).repeat(10);
        dtd.push_str(&format!("<!ENTITY l{level} \"{refs}\">"));
    }
    format!("<?xml version=\"1.0\"?>\n<!DOCTYPE robot [{dtd}]>\n<robot name=\"&l9;\"><link name=\"a\"/></robot>\n")
}

/// The formats, as `--format X --output -`.
const FORMATS: [&str; 5] = ["text", "json", "sarif", "junit", "github"];

/// Run the validator on `input` (in the root) with `flags`, the canary in its environment.
fn run(tree: &Tree, input: &str, flags: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
        .arg(input)
        .args([
            "--no-write",
            "--samples",
            "50",
            "--timeout",
            "60",
            "--no-cache",
            "--no-config",
        ])
        .args(flags)
        .current_dir(tree.root())
        .env(ENV_NAME, ENV_CANARY)
        .env("NO_COLOR", "1")
        .env_remove("GITHUB_ACTIONS")
        .env_remove("GITHUB_STEP_SUMMARY")
        .stdin(Stdio::null())
        .output()
        .unwrap()
}

/// Every output of one run: stdout, stderr and the HTML page when one was written.
fn everything(output: &Output, html: Option<&Path>) -> String {
    let mut all = format!(
        "{}\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    if let Some(page) = html.and_then(|p| std::fs::read_to_string(p).ok()) {
        all.push_str(&page);
    }
    all
}

/// The outputs of `input` in every format, untrusted: neither canary, and (for a refusal) the word.
fn check_untrusted(tree: &Tree, hostile: &Hostile) -> Vec<String> {
    let mut problems = Vec::new();
    let html = tree.base.join(format!("{}.html", hostile.file));
    let mut runs: Vec<(String, String)> = FORMATS
        .iter()
        .map(|format| {
            let output = run(
                tree,
                hostile.file,
                &["--untrusted", "--format", format, "--output", "-"],
            );
            (format.to_string(), everything(&output, None))
        })
        .collect();
    let page = run(
        tree,
        hostile.file,
        &[
            "--untrusted",
            "--format",
            "html",
            "--output",
            html.to_str().unwrap(),
        ],
    );
    runs.push(("html".to_string(), everything(&page, Some(&html))));
    // What was done with it, for the record (`cargo test --test security -- --nocapture`).
    let said: Vec<&str> = runs[0]
        .1
        .lines()
        .filter(|l| l.contains("refused") || l.starts_with("error:") || l.contains("[OVERALL]"))
        .collect();
    eprintln!("{}: {}", hostile.file, said.join(" | "));
    for (format, all) in &runs {
        for canary in [ENV_CANARY, FILE_CANARY] {
            if all.contains(canary) {
                problems.push(format!("{} ({format}): holds {canary}", hostile.file));
            }
        }
        let says =
            all.contains("refused") || all.contains("U013") || all.contains("access-refused");
        if hostile.expect == Expect::Refused && !says {
            problems.push(format!(
                "{} ({format}): does not say what was refused",
                hostile.file
            ));
        }
    }
    problems
}

#[test]
fn untrusted_mode_leaks_no_canary_in_any_format_and_says_what_it_refused() {
    let (tree, hostile) = hostile_tree("untrusted");
    assert!(hostile.len() >= 25, "at least 25 hostile inputs");
    let problems: Vec<String> = hostile
        .iter()
        .flat_map(|h| check_untrusted(&tree, h))
        .collect();
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn trusted_mode_keeps_todays_behaviour_and_every_input_ends() {
    let (tree, hostile) = hostile_tree("trusted");
    let mut problems = Vec::new();
    for h in &hostile {
        let output = run(&tree, h.file, &["--format", "json", "--output", "-"]);
        let all = everything(&output, None);
        let leaked = all.contains(ENV_CANARY) || all.contains(FILE_CANARY);
        if leaked != h.leaks_when_trusted {
            problems.push(format!(
                "{}: trusted mode {} a canary (expected today's behaviour: {})",
                h.file,
                if leaked { "shows" } else { "does not show" },
                h.leaks_when_trusted
            ));
        }
        if all.contains("U013") {
            problems.push(format!("{}: trusted mode refused something", h.file));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// System paths the binary itself opens (the dynamic loader, its libraries, its own memory map, the CPU
/// count), and the null device.
const SYSTEM_PATHS: [&str; 8] = [
    "/etc/ld.so.cache",
    "/lib/",
    "/lib64/",
    "/usr/lib/",
    "/proc/self/maps",
    "/proc/self/cgroup",
    "/proc/self/mountinfo",
    "/sys/",
];

/// The paths a run opened successfully, from `strace -f -e trace=openat,open` output.
fn opened(trace: &str) -> Vec<String> {
    trace
        .lines()
        .filter(|line| {
            line.contains("open") && !line.contains("= -1") && !line.contains("<unfinished")
        })
        .filter_map(|line| {
            let start = line.find('"')? + 1;
            let end = start + line[start..].find('"')?;
            Some(line[start..end].to_string())
        })
        .collect()
}

#[test]
fn untrusted_mode_opens_nothing_outside_the_roots() {
    if Command::new("strace").arg("-V").output().is_err() {
        assert!(
            std::env::var_os("CI").is_none(),
            "strace is missing: CI must install it (apt-get install -y strace)"
        );
        eprintln!("strace is missing: the open-file check did not run (apt-get install -y strace)");
        return;
    }
    let (tree, hostile) = hostile_tree("strace");
    let root = tree.root().canonicalize().unwrap();
    let mut problems = Vec::new();
    for h in &hostile {
        let log = tree.base.join(format!("{}.strace", h.file));
        let output = Command::new("strace")
            .args(["-f", "-e", "trace=openat,open", "-o"])
            .arg(&log)
            .arg(env!("CARGO_BIN_EXE_urdf_validate"))
            .arg(h.file)
            .args([
                "--untrusted",
                "--no-write",
                "--samples",
                "50",
                "--no-cache",
                "--no-config",
                "--format",
                "json",
                "--output",
                "-",
            ])
            .current_dir(tree.root())
            .env(ENV_NAME, ENV_CANARY)
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let trace = std::fs::read_to_string(&log).unwrap_or_default();
        assert!(
            !trace.is_empty(),
            "strace wrote nothing for {}: {output:?}",
            h.file
        );
        for path in opened(&trace) {
            let absolute = tree.root().join(&path);
            let inside = absolute
                .canonicalize()
                .map(|p| p.starts_with(&root))
                .unwrap_or(false);
            let system = SYSTEM_PATHS.iter().any(|p| path.starts_with(p));
            if !inside && !system {
                problems.push(format!("{}: opened {path}", h.file));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
