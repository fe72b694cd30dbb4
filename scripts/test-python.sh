#!/usr/bin/env bash
# Tests of the Python wheel as a user gets it: builds the wheel from pyproject.toml with pip (maturin,
# fetched by pip's build isolation), checks it is one abi3 wheel, installs it with the spec's extras into
# a fresh venv, and runs python/tests there (the Python API, the spec's task-query API, the console
# command, the Dask example on a 2-worker LocalCluster, the MCP server through the `mcp` client).
#
#   bash scripts/test-python.sh            # extra arguments go to pytest
#
# Needs only Rust and Python 3.9+ with pip (and PyPI). The venv is target/python-venv, made anew each run.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
python="${PYTHON:-python3}"
venv="$repo_root/target/python-venv"
wheels="$repo_root/target/wheels"

log() { printf 'test-python: %s\n' "$*" >&2; }

rm -rf "$venv" "$wheels"
"$python" -m venv "$venv"
"$venv/bin/python" -m pip install -q --upgrade pip
# The wheel ships the `urdf_validate` binary (crates/python/build.rs): the one built here from this
# checkout, rather than a second release build of the same sources inside the wheel's build.
log "building the urdf_validate binary the wheel ships"
cargo build -q --release --locked -p urdf-validate-cli --bin urdf_validate
export URDF_VALIDATE_WHEEL_BINARY="$repo_root/target/release/urdf_validate"
log "building the wheel (pip wheel . → maturin)"
"$venv/bin/python" -m pip wheel -q --no-deps -w "$wheels" .
shopt -s nullglob
built=("$wheels"/urdf_validator-*.whl)
shopt -u nullglob
if ((${#built[@]} != 1)); then
    log "error: expected one wheel in $wheels, found ${#built[@]}"
    exit 1
fi
wheel="${built[0]}"
# The console command is the binary, installed as a script.
if ! "$python" -m zipfile -l "$wheel" | grep -q "\.data/scripts/urdf_validate"; then
    log "error: $(basename "$wheel") does not ship the urdf_validate binary as a script"
    exit 1
fi
case "$(basename "$wheel")" in
    *-cp39-abi3-*) log "wheel: $(basename "$wheel")" ;;
    *)
        log "error: $(basename "$wheel") is not an abi3 wheel for CPython >= 3.9"
        exit 1
        ;;
esac
# The spec's install line with an extra (xacro is native: the extra is empty, but must exist), and the
# test tools, pinned.
"$venv/bin/python" -m pip install -q "${wheel}[xacro]" \
    "pytest==9.2.0" "dask[distributed]==2026.8.0" "mcp==2.3.0"
export PATH="$venv/bin:$PATH"
export URDF_VALIDATE_BIN="$venv/bin/urdf_validate"
# Mesh hulls of the tests stay under target/, not in the user's cache.
export URDF_VALIDATOR_CACHE_DIR="$repo_root/target/mesh-cache"
cd "$repo_root/python/tests"
"$venv/bin/python" -m pytest -q "$@"
