//! Structure-aware fuzzing of the MJCF and SDFormat readers: the fuzz input picks one of the seed models
//! embedded from `seeds/<format>/models/` (its first byte) and is then a program of edits to its XML tree
//! ([`mutate`]): attribute values and texts replaced by other names, numbers and values of the document or
//! of a dictionary (ancestor names, empty, NaN, huge, negative), elements deleted, duplicated (as a sibling
//! or into a descendant), re-tagged, re-parented (also into their own descendant's place), included files
//! pasted in. The mutated document is validated as the seed's main file, in a folder that holds the seed's
//! other files (its includes and meshes) as they are.
//!
//! Environment, for reproducing a finding with the fuzz binary (`cargo fuzz run mjcf artifact`):
//! `URDF_FUZZ_DUMP=DIR` writes the seed's files and the mutated main file to DIR (a model the CLI can
//! validate: `urdf-validator DIR/model.xml`); `URDF_FUZZ_VERBOSE=1` prints the seed, the edits and the
//! findings to stderr.

pub mod dict;
pub mod mutate;
pub mod tree;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use mutate::{Bytes, Dict, Includes, Mutator, Pools};
use tree::Tree;
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::{validate_text, Options};

/// A seed model: its folder's files (paths relative to it), `main` the one validated.
pub struct Seed {
    pub name: &'static str,
    pub main: &'static str,
    pub files: &'static [(&'static str, &'static [u8])],
}

include!(concat!(env!("OUT_DIR"), "/seeds.rs"));

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Mjcf,
    Sdf,
}

impl Format {
    pub fn seeds(self) -> &'static [Seed] {
        match self {
            Format::Mjcf => MJCF,
            Format::Sdf => SDF,
        }
    }

    fn dict(self) -> &'static Dict {
        static MJCF_DICT: Dict = Dict {
            values: dict::MJCF_VALUES,
            tags: dict::MJCF_TAGS,
            attrs: dict::MJCF_ATTRS,
        };
        static SDF_DICT: Dict = Dict {
            values: dict::SDF_VALUES,
            tags: dict::SDF_TAGS,
            attrs: dict::SDF_ATTRS,
        };
        match self {
            Format::Mjcf => &MJCF_DICT,
            Format::Sdf => &SDF_DICT,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Format::Mjcf => "mjcf",
            Format::Sdf => "sdf",
        }
    }
}

/// A seed ready to mutate: its main tree, its other XML files parsed, the pools of its tokens, and the
/// path of its main file in the sandbox.
pub struct Prepared {
    pub seed: &'static Seed,
    pub main: PathBuf,
    tree: Tree,
    pools: Pools,
    others: Vec<(String, Tree)>,
}

fn fnv(hash: &mut u64, bytes: &[u8]) {
    for &b in bytes {
        *hash = (*hash ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
    }
}

/// Write `bytes` to `path` (through a temporary file and a rename: a reader never sees half a file).
fn write_file(path: &Path, bytes: &[u8]) {
    if std::fs::read(path).is_ok_and(|old| old == bytes) {
        return;
    }
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).expect("create seed folder");
    }
    let tmp = path.with_extension(format!("tmp{}", std::process::id()));
    std::fs::write(&tmp, bytes).expect("write seed file");
    std::fs::rename(&tmp, path).expect("rename seed file");
}

/// The seeds of `format`, written once per process to a folder of the temporary directory named after
/// their content (so the processes of a `-fork` run share one copy).
pub fn prepared(format: Format) -> &'static [Prepared] {
    static MJCF_READY: OnceLock<Vec<Prepared>> = OnceLock::new();
    static SDF_READY: OnceLock<Vec<Prepared>> = OnceLock::new();
    let cell = match format {
        Format::Mjcf => &MJCF_READY,
        Format::Sdf => &SDF_READY,
    };
    cell.get_or_init(|| {
        let seeds = format.seeds();
        let mut hash = 0xcbf2_9ce4_8422_2325;
        for seed in seeds {
            fnv(&mut hash, seed.name.as_bytes());
            for (path, bytes) in seed.files {
                fnv(&mut hash, path.as_bytes());
                fnv(&mut hash, bytes);
            }
        }
        let root = std::env::temp_dir().join(format!("urdf-fuzz-{}-{hash:016x}", format.name()));
        seeds
            .iter()
            .map(|seed| {
                let dir = root.join(seed.name);
                let mut tree = None;
                let mut others = Vec::new();
                let mut pools = Pools::default();
                for (path, bytes) in seed.files {
                    write_file(&dir.join(path), bytes);
                    let is_xml = [".xml", ".sdf"].iter().any(|ext| path.ends_with(ext));
                    if !is_xml {
                        continue;
                    }
                    let text = std::str::from_utf8(bytes).expect("UTF-8 seed");
                    let parsed = Tree::parse(text)
                        .unwrap_or_else(|| panic!("seed {}/{path} does not parse", seed.name));
                    pools.add(&parsed);
                    if *path == seed.main {
                        tree = Some(parsed);
                    } else {
                        others.push((path.to_string(), parsed));
                    }
                }
                Prepared {
                    seed,
                    main: dir.join(seed.main),
                    tree: tree.expect("main file"),
                    pools,
                    others,
                }
            })
            .collect()
    })
}

/// The seed's XML files, for pasting includes in.
struct SeedIncludes<'p> {
    format: Format,
    others: &'p [(String, Tree)],
}

impl SeedIncludes<'_> {
    /// The seed file an include's file or URI names (relative to any folder of the seed).
    fn find(&self, written: &str) -> Option<&Tree> {
        let written = written.trim();
        let mut candidates = Vec::new();
        let plain = written
            .strip_prefix("model://")
            .or_else(|| written.strip_prefix("file://"))
            .unwrap_or(written)
            .trim_start_matches("./")
            .trim_end_matches('/');
        candidates.push(plain.to_string());
        candidates.push(format!("{plain}/model.sdf"));
        self.others.iter().find_map(|(path, tree)| {
            candidates
                .iter()
                .any(|c| !c.is_empty() && (path == c || path.ends_with(&format!("/{c}"))))
                .then_some(tree)
        })
    }
}

impl Includes for SeedIncludes<'_> {
    fn expand(&self, tree: &mut Tree, include: usize) -> Vec<usize> {
        match self.format {
            Format::Mjcf => {
                let Some(file) = tree.attr(include, "file").map(str::to_string) else {
                    return Vec::new();
                };
                let Some(source) = self.find(&file) else {
                    return Vec::new();
                };
                source
                    .element_children(source.root)
                    .into_iter()
                    .map(|c| tree.graft(source, c))
                    .collect()
            }
            Format::Sdf => {
                let child = |tree: &Tree, tag: &str| {
                    tree.element_children(include)
                        .into_iter()
                        .find(|&c| tree.elements[c].tag == tag)
                };
                let Some(uri) = child(tree, "uri").map(|u| tree.text(u)) else {
                    return Vec::new();
                };
                let Some(source) = self.find(&uri) else {
                    return Vec::new();
                };
                let Some(model) = source
                    .element_children(source.root)
                    .into_iter()
                    .find(|&c| source.elements[c].tag == "model")
                else {
                    return Vec::new();
                };
                let pasted = tree.graft(source, model);
                // What the include overrides: the name, the pose, static.
                if let Some(name) = child(tree, "name").map(|n| tree.text(n)) {
                    tree.set_attr(pasted, "name", name.trim().to_string());
                }
                for tag in ["pose", "static"] {
                    if let Some(from) = child(tree, tag) {
                        let old = tree
                            .element_children(pasted)
                            .into_iter()
                            .find(|&c| tree.elements[c].tag == tag);
                        if let Some(old) = old {
                            tree.detach(old);
                        }
                        let copy = tree.clone_subtree(from);
                        tree.insert(pasted, 0, copy);
                    }
                }
                vec![pasted]
            }
        }
    }
}

/// The seed the input picks and the mutated text of its main file (None for an empty input), with the
/// number of edits made.
pub fn mutated(format: Format, data: &[u8]) -> Option<(&'static Prepared, String, usize)> {
    let (seed, tree, edits) = mutated_tree(format, data)?;
    Some((seed, tree.serialize(), edits))
}

/// [`mutated`] before serialization.
pub fn mutated_tree(format: Format, data: &[u8]) -> Option<(&'static Prepared, Tree, usize)> {
    let (&pick, program) = data.split_first()?;
    let seeds = prepared(format);
    let seed = &seeds[usize::from(pick) % seeds.len()];
    let mut tree = seed.tree.clone();
    let mutator = Mutator {
        dict: format.dict(),
        pools: &seed.pools,
        includes: &SeedIncludes {
            format,
            others: &seed.others,
        },
    };
    let edits = mutator.apply(&mut tree, &mut Bytes::new(program));
    Some((seed, tree, edits))
}

/// The fuzz target: mutate, then validate the whole pipeline as `validate_text` runs it.
pub fn run(format: Format, data: &[u8]) {
    static DUMP: OnceLock<Option<PathBuf>> = OnceLock::new();
    static VERBOSE: OnceLock<bool> = OnceLock::new();
    let Some((seed, text, edits)) = mutated(format, data) else {
        return;
    };
    let dump = DUMP.get_or_init(|| std::env::var_os("URDF_FUZZ_DUMP").map(PathBuf::from));
    let verbose = *VERBOSE.get_or_init(|| std::env::var_os("URDF_FUZZ_VERBOSE").is_some());
    if let Some(dir) = dump {
        for (path, bytes) in seed.seed.files {
            write_file(&dir.join(path), bytes);
        }
        write_file(&dir.join(seed.seed.main), text.as_bytes());
        eprintln!("urdf-fuzz: wrote {}", dir.join(seed.seed.main).display());
    }
    if verbose {
        eprintln!(
            "urdf-fuzz: seed {} ({}), {edits} edits, {} bytes",
            seed.seed.name,
            seed.main.display(),
            text.len()
        );
    }
    let mut options = Options {
        resolver: PackageResolver::new(Vec::new(), None, None),
        ..Options::default()
    };
    options.workspace.samples = 16;
    let result = validate_text(text, &seed.main, &options);
    if verbose {
        match result {
            Ok(v) => {
                eprintln!(
                    "urdf-fuzz: {} links, {} findings",
                    v.report.links.len(),
                    v.report.findings.len()
                );
                for f in &v.report.findings {
                    eprintln!("  {} {}:{} {}", f.rule, f.file.as_deref().unwrap_or("-"), f.line.unwrap_or(0), f.message);
                }
            }
            Err(e) => eprintln!("urdf-fuzz: load error: {e}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tree::Child;

    #[test]
    fn every_seed_round_trips_through_the_serializer() {
        for format in [Format::Mjcf, Format::Sdf] {
            for seed in prepared(format) {
                let text = seed.tree.serialize();
                let again = Tree::parse(&text).expect("serialized seed parses");
                assert_eq!(again.serialize(), text, "{}", seed.seed.name);
                assert_eq!(again.live().len(), seed.tree.live().len());
            }
        }
    }

    #[test]
    fn random_programs_keep_the_tree_a_tree() {
        let mut state = 0x1234_5678_u64;
        for round in 0..3000 {
            let len = (round % 200) + 1;
            let data: Vec<u8> = (0..len)
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    state as u8
                })
                .collect();
            for format in [Format::Mjcf, Format::Sdf] {
                let (_, tree, _) = mutated_tree(format, &data).expect("non-empty input");
                // No element is reached twice (a cycle would never end: check before walking).
                let mut seen = vec![false; tree.elements.len()];
                let mut stack = vec![tree.root];
                while let Some(id) = stack.pop() {
                    assert!(!seen[id], "element {id} reached twice");
                    seen[id] = true;
                    stack.extend(tree.element_children(id));
                }
                assert!(tree.parent[tree.root].is_none());
                // Every live element's parent lists it exactly once.
                for id in tree.live() {
                    if let Some(p) = tree.parent[id] {
                        let n = tree.elements[p]
                            .children
                            .iter()
                            .filter(|c| matches!(c, Child::Element(e) if *e == id))
                            .count();
                        assert_eq!(n, 1);
                    }
                }
                let text = tree.serialize();
                let again = Tree::parse(&text).expect("mutated text parses");
                assert_eq!(again.live().len(), tree.live().len());
            }
        }
    }
}
