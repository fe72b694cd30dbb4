#!/usr/bin/env bash
# Builds the Zed extension (editors/zed: starts the installed `urdf_validate server` for XML files) for
# wasm32-wasip1, as Zed builds a dev extension, adding that target with rustup when it is missing. A compile
# check: Zed itself cannot run here.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root/editors/zed"

if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-wasip1; then
    echo "build-zed: adding the wasm32-wasip1 target" >&2
    rustup target add wasm32-wasip1
fi
cargo build --locked --release --target wasm32-wasip1
cargo fmt -- --check
wasm="target/wasm32-wasip1/release/urdf_validate_zed.wasm"
[[ -s "$wasm" ]] || {
    echo "build-zed: $wasm was not built" >&2
    exit 1
}
echo "build-zed: $(du -h "$wasm" | cut -f1) editors/zed/$wasm"
