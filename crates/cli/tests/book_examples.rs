//! Every ```` ```console ```` block of the book (`docs/**/*.md`) and of `README.md` runs as written, in the
//! style of trycmd: each `$ urdf_validate ...` line is run in a scratch copy of the repository's example
//! robots (present as `examples/robots/` and `robots/`), an optional `? N` line after it gives the exit
//! code it must end with (0 without one), and the lines up to the next `$` are its output (stdout and
//! stderr as a terminal shows them), compared with snapbox: `...` alone on a line matches any lines, `[..]`
//! any text within a line, `[CWD]` the scratch directory and `[VERSION]` the package version. The commands
//! of one block run in order in the same scratch directory (a later one may read what an earlier one
//! wrote); each block gets a fresh one. Blocks marked ```` ```sh ```` or ```` ```bash ```` are not run.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::io::Read as _;
mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// One `$` line of a console block and what it must do.
#[derive(Debug)]
struct Example {
    /// `file:line` of the `$` line.
    place: String,
    /// The words of the command after `urdf_validate`.
    args: Vec<String>,
    /// The exit code it must end with.
    code: i32,
    /// Its expected output, with snapbox's wildcards.
    expected: String,
}

/// The examples of every console block of `text` (the file `name`), one `Vec` per block.
fn console_blocks(name: &str, text: &str) -> Vec<Vec<Example>> {
    let mut blocks = Vec::new();
    let mut current: Option<Vec<Example>> = None;
    for (number, line) in text.lines().enumerate() {
        let place = format!("{name}:{}", number + 1);
        match current.as_mut() {
            None if line.trim_start() == "```console" => current = Some(Vec::new()),
            None => {}
            Some(_) if line.trim_start().starts_with("```") => blocks.extend(current.take()),
            Some(block) => {
                if let Some(command) = line.strip_prefix("$ ") {
                    let mut words = split_words(command);
                    assert_eq!(
                        words.first().map(String::as_str),
                        Some("urdf_validate"),
                        "{place}: a console block runs only urdf_validate; put other commands in a ```sh block"
                    );
                    words.remove(0);
                    block.push(Example {
                        place,
                        args: words,
                        code: 0,
                        expected: String::new(),
                    });
                } else if let Some(example) = block.last_mut() {
                    match line.strip_prefix("? ") {
                        Some(code) if example.expected.is_empty() => {
                            example.code = code.trim().parse().unwrap_or_else(|_| {
                                panic!("{place}: `? N` wants an exit code, got {code:?}")
                            });
                        }
                        _ => {
                            example.expected.push_str(line);
                            example.expected.push('\n');
                        }
                    }
                } else {
                    panic!("{place}: a console block starts with a `$ ` line");
                }
            }
        }
    }
    blocks
}

/// A command line split into words as a POSIX shell would for the plain cases the book uses: blanks
/// separate words, single and double quotes group, `#` after a blank starts a comment. Anything a shell
/// would expand (`~`, `$`, `*`, `|`, `>`) is refused, so a block cannot look run while meaning something
/// else.
fn split_words(command: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut quote: Option<char> = None;
    for c in command.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.get_or_insert_with(String::new).push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                word.get_or_insert_with(String::new);
            }
            (None, '#') if word.is_none() => break,
            (None, c) if c.is_whitespace() => words.extend(word.take()),
            (None, '~' | '$' | '*' | '|' | '>' | '<' | ';' | '&' | '`') => {
                panic!(
                    "{command:?}: shell syntax ({c}) in a console block; put it in a ```sh block"
                )
            }
            (None, c) => word.get_or_insert_with(String::new).push(c),
        }
    }
    assert!(quote.is_none(), "{command:?}: unbalanced quote");
    words.extend(word);
    words
}

/// Every Markdown file of the book, and the README.
fn book_files() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).expect("read docs").flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|ext| ext == "md") {
                out.push(path);
            }
        }
    }
    let mut files = vec![repo_root().join("README.md")];
    walk(&repo_root().join("docs"), &mut files);
    files.sort();
    files
}

/// Run one block's examples in a fresh scratch directory; the mismatches, each described.
fn run_block(block: &[Example], scratch: &Path) -> Vec<String> {
    let _ = std::fs::remove_dir_all(scratch);
    let examples = repo_root().join("examples/robots");
    common::copy_dir(&examples, &scratch.join("examples/robots"));
    common::copy_dir(&examples, &scratch.join("robots"));
    let scratch = scratch.canonicalize().expect("scratch");
    let mut redactions = snapbox::Redactions::new();
    redactions
        .insert("[CWD]", scratch.display().to_string())
        .expect("redaction");
    redactions
        .insert("[VERSION]", env!("CARGO_PKG_VERSION"))
        .expect("redaction");
    // Plain diffs: the failure is read in CI logs more often than on a terminal.
    let assert = snapbox::Assert::new()
        .redact_with(redactions)
        .palette(snapbox::report::Palette::plain())
        .action(snapbox::assert::Action::Verify);
    let mut failures = Vec::new();
    for example in block {
        let (mut reader, writer) = std::io::pipe().expect("pipe");
        let mut child = Command::new(env!("CARGO_BIN_EXE_urdf_validate"))
            .args(&example.args)
            .current_dir(&scratch)
            .env("URDF_VALIDATOR_CACHE_DIR", scratch.join(".cache"))
            .env("HOME", &scratch)
            .env("NO_COLOR", "1")
            .env_remove("CI")
            .env_remove("GITHUB_ACTIONS")
            .stdin(std::process::Stdio::null())
            .stdout(writer.try_clone().expect("pipe"))
            .stderr(writer)
            .spawn()
            .expect("run urdf_validate");
        let mut output = String::new();
        reader.read_to_string(&mut output).expect("read output");
        let code = child.wait().expect("wait").code();
        if code != Some(example.code) {
            failures.push(format!(
                "{}: `urdf_validate {}` exited with {code:?}, the book says {}\n{output}",
                example.place,
                example.args.join(" "),
                example.code
            ));
        }
        if let Err(error) = assert.try_eq(
            Some(&example.place),
            snapbox::Data::text(output),
            snapbox::Data::text(example.expected.clone()),
        ) {
            failures.push(format!(
                "{}: `urdf_validate {}` printed something else than the book shows:\n{error}",
                example.place,
                example.args.join(" ")
            ));
        }
    }
    failures
}

#[test]
fn every_console_example_of_the_book_and_readme_runs_as_shown() {
    let root = repo_root();
    let mut failures = Vec::new();
    let mut count = 0;
    for (index, file) in book_files().iter().enumerate() {
        let name = file
            .strip_prefix(&root)
            .unwrap_or(file)
            .display()
            .to_string();
        let text = std::fs::read_to_string(file).expect("read page");
        for (block_index, block) in console_blocks(&name, &text).iter().enumerate() {
            count += block.len();
            let scratch = std::env::temp_dir().join(format!(
                "urdf-validator-book-{}-{index}-{block_index}",
                std::process::id()
            ));
            failures.extend(run_block(block, &scratch));
            let _ = std::fs::remove_dir_all(&scratch);
        }
    }
    eprintln!("{count} console examples run");
    assert!(count > 0, "no console example found");
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The runner itself: a block whose output or exit code is wrong is reported, one whose output matches
/// through the wildcards is not.
#[test]
fn a_wrong_example_is_reported() {
    let page = "```console\n$ urdf_validate --explain U304 # a comment\nU304 inverted-limits [..]\n...\n$ urdf_validate --explain U304\n? 2\nU999 nothing\n```\n";
    let blocks = console_blocks("page.md", page);
    assert_eq!(blocks.len(), 1);
    assert_eq!(blocks[0][0].args, ["--explain", "U304"]);
    assert_eq!(blocks[0][1].code, 2);
    let scratch = std::env::temp_dir().join(format!(
        "urdf-validator-book-selftest-{}",
        std::process::id()
    ));
    let failures = run_block(&blocks[0], &scratch);
    let _ = std::fs::remove_dir_all(&scratch);
    assert_eq!(failures.len(), 2, "{failures:?}");
    assert!(failures[0].starts_with("page.md:5:") && failures[0].contains("exited with Some(0)"));
    assert!(failures[1].starts_with("page.md:5:") && failures[1].contains("something else"));
}

#[test]
fn words_split_like_a_shell_and_expansions_are_refused() {
    assert_eq!(
        split_words("urdf_validate 'a b' \"c\"d  e # comment"),
        ["urdf_validate", "a b", "cd", "e"]
    );
    assert!(std::panic::catch_unwind(|| split_words("urdf_validate ~/ws")).is_err());
    assert!(std::panic::catch_unwind(|| split_words("urdf_validate a | jq")).is_err());
}
