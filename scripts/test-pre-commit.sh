#!/usr/bin/env bash
# Tests .pre-commit-hooks.yaml with `pre-commit try-repo` in a scratch git repository: the
# `urdf-validate` hook must run on *.urdf / *.xacro files, pass a clean robot, fail a broken one with
# urdf_validate's exit code 2, pass a WARN robot silenced by an inline comment, and skip a xacro macro
# library. pre-commit (from PyPI) goes into a throw-away venv. Exits non-zero on any deviation.
#
# Usage: bash scripts/test-pre-commit.sh            (builds target/debug/urdf_validate first)
#        URDF_VALIDATE_BIN=/path/to/urdf_validate bash scripts/test-pre-commit.sh
#        TEST_CARGO_HOOK=1 bash scripts/test-pre-commit.sh   (also the urdf-validate-cargo hook, built in
#            pre-commit's clone with the dev profile into this checkout's target/: several minutes)
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT

if [[ -n "${URDF_VALIDATE_BIN:-}" ]]; then
    bin_dir="$(cd "$(dirname "$URDF_VALIDATE_BIN")" && pwd)"
else
    (cd "$repo_root" && cargo build --quiet -p urdf-validate-cli)
    bin_dir="${CARGO_TARGET_DIR:-$repo_root/target}/debug"
fi
[[ -x "$bin_dir/urdf_validate" ]] || { echo "test-pre-commit: no urdf_validate in $bin_dir" >&2; exit 1; }

python3 -m venv "$scratch/venv"
"$scratch/venv/bin/pip" install --quiet --disable-pip-version-check pre-commit
export PATH="$bin_dir:$scratch/venv/bin:$PATH"
export PRE_COMMIT_HOME="$scratch/pre-commit-home"

work="$scratch/robots"
mkdir -p "$work"
cd "$work"
git init --quiet
git config user.email test@example.com
git config user.name test

cat > good.urdf <<'URDF'
<robot name="good">
  <link name="base"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <link name="arm">
    <inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
  </link>
</robot>
URDF
cat > broken.urdf <<'URDF'
<robot name="broken">
  <link name="base"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="nowhere"/></joint>
</robot>
URDF
cat > silenced.urdf <<'URDF'
<robot name="silenced">
  <link name="base"/>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
  <!-- urdf-validate: ignore U201 -->
  <link name="arm"/>
</robot>
URDF
# Twelve robots made of two mesh files: a commit touching more files with meshes than there are threads
# (such a run once hung until its timeout and reported nothing).
mkdir -p meshes
box_stl() {
    local h="$1" i j k
    echo "solid box"
    # Two triangles per face of a cube of half-size $h.
    for face in "x" "y" "z"; do
        for s in "-$h" "$h"; do
            case "$face" in
                x) set -- "$s -$h -$h" "$s $h -$h" "$s $h $h" "$s -$h $h" ;;
                y) set -- "-$h $s -$h" "$h $s -$h" "$h $s $h" "-$h $s $h" ;;
                z) set -- "-$h -$h $s" "$h -$h $s" "$h $h $s" "-$h $h $s" ;;
            esac
            printf 'facet normal 0 0 0\nouter loop\nvertex %s\nvertex %s\nvertex %s\nendloop\nendfacet\n' "$1" "$2" "$3"
            printf 'facet normal 0 0 0\nouter loop\nvertex %s\nvertex %s\nvertex %s\nendloop\nendfacet\n' "$1" "$3" "$4"
        done
    done
    echo "endsolid box"
}
box_stl 0.1 > meshes/base.stl
box_stl 0.05 > meshes/arm.stl
# 1 kg cubes of 0.2 m and 0.1 m: the inertia (m·(2·side²)/12) and centre of their geometry, so U208/U209 stay quiet.
base_inertial='<inertial><mass value="1"/><inertia ixx="0.00667" ixy="0" ixz="0" iyy="0.00667" iyz="0" izz="0.00667"/></inertial>'
arm_inertial='<inertial><origin xyz="0 0 0.3"/><mass value="1"/><inertia ixx="0.00167" ixy="0" ixz="0" iyy="0.00167" iyz="0" izz="0.00167"/></inertial>'
mesh_robots=()
for n in $(seq 1 12); do
    cat > "arm_$n.urdf" <<URDF
<robot name="arm_$n">
  <link name="base">$base_inertial<collision><geometry><mesh filename="meshes/base.stl"/></geometry></collision></link>
  <link name="arm">$arm_inertial<collision><origin xyz="0 0 0.3"/><geometry><mesh filename="meshes/arm.stl"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="50" velocity="1"/></joint>
</robot>
URDF
    mesh_robots+=("arm_$n.urdf")
done
cat > macros.xacro <<'XACRO'
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="name"><link name="${name}"/></xacro:macro>
</robot>
XACRO
git add .

failures=0
# try_hook HOOK EXPECTED_PRE_COMMIT_EXIT EXPECTED_TEXT FILE...
try_hook() {
    local hook="$1" expected="$2" text="$3"
    shift 3
    local out code=0
    # Bounded: a hung run is a failure, not a stuck CI job.
    out="$(timeout 300 pre-commit try-repo "$repo_root" "$hook" --verbose --files "$@" 2>&1)" || code=$?
    if [[ "$code" != "$expected" ]] || ! grep -qE -- "$text" <<<"$out"; then
        echo "FAIL: $hook on $*: pre-commit exited $code (expected $expected), output should match '$text':" >&2
        echo "$out" >&2
        failures=$((failures + 1))
    else
        echo "ok: $hook on $* (pre-commit exit $code)"
    fi
}

try_hook urdf-validate 0 'urdf-validate\.+Passed' good.urdf
try_hook urdf-validate 1 'exit code: 2' broken.urdf
try_hook urdf-validate 1 'urdf-validate\.+Failed' good.urdf broken.urdf
try_hook urdf-validate 0 'urdf-validate\.+Passed' silenced.urdf
try_hook urdf-validate 0 'urdf-validate\.+Passed' macros.xacro
# Without its comment the same robot warns: the hook fails with exit code 1.
for threads in 1 2; do
    RAYON_NUM_THREADS="$threads" try_hook urdf-validate 0 'urdf-validate\.+Passed' "${mesh_robots[@]}"
done
sed -i '/urdf-validate: ignore/d' silenced.urdf
try_hook urdf-validate 1 'exit code: 1' silenced.urdf
if [[ "${TEST_CARGO_HOOK:-0}" == 1 ]]; then
    # PATH must not provide urdf_validate: the hook builds its own.
    (
        export PATH="${PATH#"$bin_dir:"}"
        export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$repo_root/target}"
        export URDF_VALIDATE_HOOK_PROFILE=dev
        try_hook urdf-validate-cargo 1 'exit code: 2' broken.urdf
        try_hook urdf-validate-cargo 0 'Passed' good.urdf
        [[ "$failures" -eq 0 ]]
    ) || failures=$((failures + 1))
fi

if [[ "$failures" -gt 0 ]]; then
    echo "test-pre-commit: $failures check(s) failed" >&2
    exit 1
fi
echo "test-pre-commit: all checks passed"
