#!/usr/bin/env bash
# The SDFormat, inertia, MJCF and Menagerie goldens against their oracles: installs Drake (PyPI drake==1.51.1) in a throw-away venv under
# target/ and regenerates the goldens in memory (scripts/oracle/sdf_golden.py --check); exits 1 when a
# committed golden differs from what Drake computes now. The Rust test tests/sdf_golden.rs compares our
# reader to the committed goldens to 1e-9, so together they tie our values to Drake's.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

venv="${DRAKE_VENV:-$repo_root/target/drake-venv}"
if [[ ! -x "$venv/bin/python" ]]; then
    echo "test-oracles: creating $venv (drake==1.51.1)"
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q --disable-pip-version-check drake==1.51.1
fi
"$venv/bin/python" -c "import pydrake; from importlib.metadata import version; print('drake', version('drake'))"
"$venv/bin/python" scripts/oracle/sdf_golden.py --check
# Inertia from geometry: Drake's CalcSpatialInertia per link as fix_inertia sums it (tests/inertia.rs compares
# ours to these goldens to 1e-9); reads example-robot-data from the test venv and ../shared/robots.
"$venv/bin/python" scripts/oracle/inertia_golden.py --check
# MJCF: MuJoCo's own numbers for dm_control's suite models (tests/mjcf_golden.rs compares our reader to them
# to 1e-9); MuJoCo from the test venv (mujoco==4.0.0, scripts/setup-test-env.sh), the models it unpacks.
bash scripts/setup-test-env.sh >/dev/null
.venv/bin/python scripts/oracle/mjcf_goldens.py --check
# MuJoCo Menagerie, mesh-free variants (crates/urdf-validator/tests/data/menagerie, docs/menagerie.md): MuJoCo
# compiles each and our report's mass, centre of mass and gravity torques agree with it to 1e-9. The debug
# CLI (built by the test suite already) computes the same values as the release one.
cargo build --quiet -p urdf-validate-cli --bin urdf_validate
target_dir="$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json,sys; print(json.load(sys.stdin)["target_directory"])')"
URDF_VALIDATE="$target_dir/debug/urdf_validate" .venv/bin/python scripts/oracle/menagerie.py --check
