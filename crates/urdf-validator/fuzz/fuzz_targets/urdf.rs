//! URDF or SDFormat text (an `<sdf>` root; the seeds hold both) → the whole validation pipeline (parse,
//! rules, physics, statics, stability, workspace, self-collision). Mesh references resolve against an empty
//! sandbox folder and a resolver without package paths, so runs stay fast and independent of the machine's
//! files (absolute paths excepted).
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use urdf_validator::input::resolve::PackageResolver;
use urdf_validator::{validate_text, Options};

fn sandbox() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("urdf-fuzz-sandbox-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("create sandbox dir");
        dir.join("fuzz.urdf")
    })
}

fuzz_target!(|data: &[u8]| {
    // validate_text takes text; invalid UTF-8 is rejected by read_text before it (tested elsewhere).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let mut options = Options {
        resolver: PackageResolver::new(Vec::new(), None, None),
        ..Options::default()
    };
    options.workspace.samples = 16;
    let _ = validate_text(text.to_string(), sandbox(), &options);
});
