#!/usr/bin/env bash
# Builds the Zed extension (editors/zed: starts the installed `urdf_validate server` for XML files) for
# wasm32-wasip1, as Zed builds a dev extension, adding that target with rustup when it is missing (when it
# cannot be added, the extension is type-checked for the host instead, with a warning). A compile check: Zed
# itself cannot run here.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root/editors/zed"

cargo fmt -- --check
if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-wasip1; then
    echo "build-zed: adding the wasm32-wasip1 target" >&2
    rustup target add wasm32-wasip1 || true
fi
if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-wasip1; then
    # rustup's download server is not a package registry every machine reaches: type-check the extension
    # for the host instead (the API is the same; only Zed's WebAssembly build is not made), and say so.
    echo "build-zed: WARNING: the wasm32-wasip1 target could not be added; checking the extension for the host only" >&2
    cargo check --locked
    exit 0
fi
cargo build --locked --release --target wasm32-wasip1
wasm="target/wasm32-wasip1/release/urdf_validate_zed.wasm"
[[ -s "$wasm" ]] || {
    echo "build-zed: $wasm was not built" >&2
    exit 1
}
echo "build-zed: $(du -h "$wasm" | cut -f1) editors/zed/$wasm"
