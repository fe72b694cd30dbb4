#!/usr/bin/env bash
# The `urdf-validate-cargo` pre-commit hook: builds urdf_validate from this checkout (release; a no-op
# once built; $CARGO_TARGET_DIR is honoured) and runs it on the files pre-commit passes.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="${CARGO_TARGET_DIR:-$here/target}"
cargo build --quiet --release --locked --manifest-path "$here/Cargo.toml" -p urdf-validate-cli >&2
exec "$target/release/urdf_validate" "$@"
