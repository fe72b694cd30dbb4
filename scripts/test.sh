#!/usr/bin/env bash
# Runs the whole test suite: installs the test corpus into .venv (first use only), points the tests at
# it and at ../shared/robots, then `cargo test --workspace --all-targets`. Extra arguments go to cargo
# test, e.g. `bash scripts/test.sh -- --nocapture` or `bash scripts/test.sh -p urdf-validator`.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

corpus="$(bash scripts/setup-test-env.sh)" || {
    echo "test.sh: scripts/setup-test-env.sh failed; cannot install the test corpus" >&2
    exit 1
}
export URDF_VALIDATOR_CORPUS="$corpus"
echo "test.sh: URDF_VALIDATOR_CORPUS=$URDF_VALIDATOR_CORPUS" >&2
# Python xacro 2.1.1 (installed by setup-test-env.sh): the oracle of crates/xacro's differential tests.
export URDF_VALIDATOR_XACRO="$repo_root/.venv/bin/xacro"
# The venv's Python with junitparser: reads the --format junit output as a CI would (crates/cli/tests/formats.rs).
export URDF_VALIDATOR_PYTHON="$repo_root/.venv/bin/python"

shared_robots="$repo_root/../shared/robots"
if [[ -d "$shared_robots" ]]; then
    URDF_VALIDATOR_SHARED_ROBOTS="$(cd "$shared_robots" && pwd)"
    export URDF_VALIDATOR_SHARED_ROBOTS
    echo "test.sh: URDF_VALIDATOR_SHARED_ROBOTS=$URDF_VALIDATOR_SHARED_ROBOTS" >&2
else
    echo "test.sh: $shared_robots is absent; its tests skip (or fail under CI=true)" >&2
fi

# dm_control's suite models, unpacked by setup-test-env.sh: the MJCF reader's MuJoCo oracle corpus.
export URDF_VALIDATOR_MJCF_CORPUS="$repo_root/target/dm-control/dm_control/suite"
echo "test.sh: URDF_VALIDATOR_MJCF_CORPUS=$URDF_VALIDATOR_MJCF_CORPUS" >&2
# gymnasium's MuJoCo environments, unpacked by setup-test-env.sh: the second MJCF oracle corpus.
export URDF_VALIDATOR_GYMNASIUM_CORPUS="$repo_root/target/gymnasium/gymnasium/envs/mujoco/assets"
echo "test.sh: URDF_VALIDATOR_GYMNASIUM_CORPUS=$URDF_VALIDATOR_GYMNASIUM_CORPUS" >&2

# The CLI keeps mesh hulls between runs; the tests keep theirs under target/, not in the user's cache.
export URDF_VALIDATOR_CACHE_DIR="$repo_root/target/mesh-cache"

cargo test --workspace --all-targets "$@"
# Examples in the documentation compile and run too (--all-targets leaves doc tests out).
cargo test --workspace --doc
