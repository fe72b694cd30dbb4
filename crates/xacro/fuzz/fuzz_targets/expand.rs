//! Whole documents: arbitrary bytes (as UTF-8) expanded as the file `$SANDBOX/robot.urdf.xacro`.
//!
//! File access stays in the sandbox directory (`XACRO_FUZZ_SANDBOX`, default `/sandbox`): `$(find pkg)`
//! resolves to `$SANDBOX/pkg`, the environment is empty apart from two fixed variables, and `run.sh` runs
//! this binary chrooted into a directory holding only the sandbox, so absolute include / `load_yaml` paths
//! cannot reach the host's files either.
#![no_main]

use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use libfuzzer_sys::fuzz_target;

fn sandbox() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        std::env::var_os("XACRO_FUZZ_SANDBOX")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("/sandbox"))
    })
}

fn options() -> &'static xacro::Options {
    static OPTS: OnceLock<xacro::Options> = OnceLock::new();
    OPTS.get_or_init(|| {
        let dir = sandbox().clone();
        xacro::Options {
            args: vec![
                ("arg_a".into(), "1".into()),
                ("arg_b".into(), "true".into()),
            ],
            package_paths: vec![dir.clone()],
            find_package: Some(Arc::new(move |pkg: &str| {
                let valid =
                    !pkg.is_empty() && !pkg.contains(['/', '\\']) && pkg != "." && pkg != "..";
                valid.then(|| dir.join(pkg)).ok_or_else(Vec::new)
            })),
            env: Some(Arc::new(|name: &str| match name {
                "FUZZ_VAR" => Some("value".into()),
                "FUZZ_NUM" => Some("3".into()),
                _ => None,
            })),
            ..Default::default()
        }
    })
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = sandbox().join("robot.urdf.xacro");
    match xacro::expand_str(text, &path, options()) {
        Ok(expansion) => {
            // Exercise the source map over the whole output.
            for byte in (0..expansion.xml.len()).step_by(7) {
                let _ = expansion.trace(byte);
            }
        }
        Err(e) => {
            let message = e.to_string();
            assert!(!message.is_empty());
            assert_ne!(e.kind, xacro::ErrorKind::Internal, "{message}");
        }
    }
});
