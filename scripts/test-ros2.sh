#!/usr/bin/env bash
# Tests the ROS 2 linter packages (ros2/ament_urdf_validate, ros2/ament_cmake_urdf_validate) under a
# real `colcon build` / `colcon test` / `colcon test-result`: a scratch workspace holds both linter
# packages and two sample packages, sample_robots (ament_python: a pytest test calling
# ament_urdf_validate.main_with_errors) and sample_robots_cmake (ament_cmake: ament_lint_auto finds the
# ament_cmake_urdf_validate hook), each with a good robot (examples/robots/mobile_manipulator.urdf), a
# bad one (a shoulder whose effort cannot hold its link: U701 joint-undersized, FAIL) and a xacro
# macro library (skipped).
#   1. with the bad robots: `colcon test --return-code-on-test-failure` must fail, `colcon test-result`
#      must count failures in both packages' result files and `--verbose` must show U701 and its message;
#   2. with the bad robots removed: colcon test passes and test-result counts tests and 0 failures;
#   3. the linter's own command line: exit codes of a WARN robot with --fail-on warn / fail, --exclude,
#      -- args, urdf-validate.toml, --config and package.xml options; a folder of macro libraries
#      (passes), one without robots (exit 1); a bad package.xml and a missing urdf_validate (exit 2).
# colcon, ament_package, ament_cmake and ament_lint come from Debian (bookworm: colcon 0.12.1,
# python3-ament-package 0.15.1, ament-cmake 1.5.2, ament-lint 0.13.2), installed with apt-get when
# missing and running as root. Under CI=true a missing tool is a failure, never a skip.
#
# Usage: bash scripts/test-ros2.sh                      (cargo build --release of urdf_validate first)
#        URDF_VALIDATE_BIN=/path/to/urdf_validate bash scripts/test-ros2.sh
#        KEEP_WS=1 bash scripts/test-ros2.sh            (keep the scratch workspace and print its path)
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
start_s=$SECONDS
log() { printf 'test-ros2: %s\n' "$*" >&2; }
passed=0
fail() {
    log "FAIL: $*"
    echo "test-ros2: $passed passed, 1 failed"
    exit 1
}
ok() {
    passed=$((passed + 1))
    log "$*: ok"
}

# --- tools --------------------------------------------------------------------------------------
# bookworm has no python3-colcon-common-extensions: the extensions it would bring are colcon's Recommends,
# named here one by one (a system set to skip Recommends gets them too).
debs=(colcon python3-colcon-ros python3-colcon-cmake python3-colcon-python-setup-py python3-colcon-test-result
    python3-colcon-bash python3-ament-package ament-cmake ament-lint python3-pytest cmake)
missing=()
for deb in "${debs[@]}"; do
    dpkg-query -W -f='${Status}' "$deb" 2>/dev/null | grep -q 'install ok installed' || missing+=("$deb")
done
if ((${#missing[@]} > 0)); then
    if [[ "$(id -u)" == 0 ]] && command -v apt-get >/dev/null; then
        log "installing from Debian: ${missing[*]}"
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq >/dev/null
        apt-get install -y -qq "${missing[@]}" >/dev/null
    fi
fi
for tool in /usr/bin/colcon /usr/bin/cmake; do
    if [[ ! -x "$tool" ]]; then
        if [[ "${CI:-}" == true ]]; then
            fail "$tool is missing (apt-get install colcon python3-ament-package ament-cmake ament-lint)"
        fi
        log "SKIP: $tool is missing (run as root to install it with apt-get)"
        exit 0
    fi
done
# Debian's colcon, ament_cmake and pytest live in the system Python: put /usr/bin first so that CMake's
# find_package(Python3) and `python3` are that one (not a pyenv or venv Python without ament_package).
export PATH="/usr/bin:$PATH"
python3 -c 'import ament_package, catkin_pkg, pytest' ||
    fail "the system python3 lacks ament_package, catkin_pkg or pytest"
colcon_version="$(dpkg-query -W -f='${Version}' python3-colcon-core)"
log "colcon-core $colcon_version, ament_package $(dpkg-query -W -f='${Version}' python3-ament-package)," \
    "ament_cmake $(dpkg-query -W -f='${Version}' ament-cmake), ament_lint $(dpkg-query -W -f='${Version}' ament-lint) (Debian)"

if [[ -n "${URDF_VALIDATE_BIN:-}" ]]; then
    bin="$URDF_VALIDATE_BIN"
else
    # The same build as scripts/test-python.sh (an earlier CI step): nothing to compile again there.
    (cd "$repo_root" && cargo build -q --release --locked -p urdf-validate-cli --bin urdf_validate)
    bin="${CARGO_TARGET_DIR:-$repo_root/target}/release/urdf_validate"
fi
[[ -x "$bin" ]] || fail "no urdf_validate at $bin"
bin="$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")"
export URDF_VALIDATE="$bin"
log "urdf_validate: $bin ($("$bin" --version))"

# --- the scratch workspace ----------------------------------------------------------------------
scratch="$(mktemp -d)"
if [[ -n "${KEEP_WS:-}" ]]; then
    trap 'log "workspace kept: $scratch"' EXIT
else
    trap 'rm -rf -- "$scratch"' EXIT
fi
ws="$scratch/ws"
mkdir -p "$ws/src"
cp -r "$repo_root/ros2/ament_urdf_validate" "$repo_root/ros2/ament_cmake_urdf_validate" "$ws/src/"
# Nothing of the repository's own state goes in (egg-info, __pycache__ from a developer's runs).
find "$ws/src" \( -name '*.egg-info' -o -name __pycache__ \) -prune -exec rm -rf {} +

write_robots() { # DIR: the good robot, the bad one, a macro library
    mkdir -p "$1"
    cp "$repo_root/examples/robots/mobile_manipulator.urdf" "$1/mobile_manipulator.urdf"
    cat >"$1/weak_arm.urdf" <<'URDF'
<?xml version="1.0"?>
<!-- A one-joint arm whose shoulder cannot hold its own link against gravity: U701 joint-undersized. -->
<robot name="weak_arm">
  <link name="base_link">
    <inertial>
      <origin xyz="0 0 0.05"/>
      <mass value="20"/>
      <inertia ixx="0.2833" ixy="0" ixz="0" iyy="0.2833" iyz="0" izz="0.5333"/>
    </inertial>
    <collision>
      <origin xyz="0 0 0.05"/>
      <geometry><box size="0.4 0.4 0.1"/></geometry>
    </collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/>
    <child link="upper_arm"/>
    <origin xyz="0 0 0.1"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1.57" upper="1.57" effort="2" velocity="1"/>
  </joint>
  <link name="upper_arm">
    <inertial>
      <origin xyz="0.25 0 0"/>
      <mass value="3"/>
      <inertia ixx="0.00125" ixy="0" ixz="0" iyy="0.063125" iyz="0" izz="0.063125"/>
    </inertial>
    <collision>
      <origin xyz="0.25 0 0"/>
      <geometry><box size="0.5 0.05 0.05"/></geometry>
    </collision>
  </link>
</robot>
URDF
    cat >"$1/macros.xacro" <<'XACRO'
<?xml version="1.0"?>
<!-- A macro library: builds no robot on its own, so the linter leaves it out. -->
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="box_link" params="name mass size">
    <link name="${name}"/>
  </xacro:macro>
</robot>
XACRO
}

# sample_robots: ament_python, the linter called from a pytest test.
py="$ws/src/sample_robots"
mkdir -p "$py/resource" "$py/test" "$py/sample_robots"
touch "$py/resource/sample_robots" "$py/sample_robots/__init__.py"
write_robots "$py/urdf"
cat >"$py/package.xml" <<'XML'
<?xml version="1.0"?>
<package format="3">
  <name>sample_robots</name>
  <version>0.0.1</version>
  <description>Robots checked by ament_urdf_validate under colcon test (ament_python)</description>
  <maintainer email="test@example.com">test</maintainer>
  <license>MIT</license>
  <test_depend>ament_urdf_validate</test_depend>
  <test_depend>python3-pytest</test_depend>
  <export>
    <build_type>ament_python</build_type>
  </export>
</package>
XML
cat >"$py/setup.py" <<'PY'
from glob import glob

from setuptools import setup

package_name = 'sample_robots'
setup(
    name=package_name,
    version='0.0.1',
    packages=[package_name],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/urdf', glob('urdf/*')),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='test',
    maintainer_email='test@example.com',
    description='Robots checked by ament_urdf_validate',
    license='MIT',
    tests_require=['pytest'],
)
PY
cp "$repo_root/ros2/ament_urdf_validate/doc/test_urdf_validate.py" "$py/test/test_urdf_validate.py"

# sample_robots_cmake: ament_cmake, the test added by ament_lint_auto.
cm="$ws/src/sample_robots_cmake"
write_robots "$cm/urdf"
cat >"$cm/package.xml" <<'XML'
<?xml version="1.0"?>
<package format="3">
  <name>sample_robots_cmake</name>
  <version>0.0.1</version>
  <description>Robots checked by ament_urdf_validate under colcon test (ament_cmake)</description>
  <maintainer email="test@example.com">test</maintainer>
  <license>MIT</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <test_depend>ament_lint_auto</test_depend>
  <test_depend>ament_cmake_urdf_validate</test_depend>
  <export>
    <build_type>ament_cmake</build_type>
  </export>
</package>
XML
cat >"$cm/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.8)
project(sample_robots_cmake NONE)
find_package(ament_cmake REQUIRED)
install(DIRECTORY urdf DESTINATION share/${PROJECT_NAME})
if(BUILD_TESTING)
  find_package(ament_lint_auto REQUIRED)
  ament_lint_auto_find_test_dependencies()
endif()
ament_package()
CMAKE

cd "$ws"
colcon_quiet() { # runs colcon, its output in $scratch/colcon.log (printed when a check fails)
    "$@" >"$scratch/colcon.log" 2>&1
}
show_log() { sed 's/^/    | /' "$scratch/colcon.log" >&2; }

# --- 1. the bad robots fail ---------------------------------------------------------------------
log "colcon build (4 packages)"
colcon_quiet colcon build --event-handlers console_direct- || {
    show_log
    fail "colcon build failed"
}
log "colcon test, bad robots present: must fail"
status=0
colcon_quiet colcon test --return-code-on-test-failure --event-handlers console_direct- || status=$?
if ((status == 0)); then
    show_log
    fail "colcon test passed with weak_arm.urdf (U701) in both sample packages"
fi
ok "colcon test exited $status"
cmake_result="build/sample_robots_cmake/test_results/sample_robots_cmake/urdf_validate.xunit.xml"
py_result="build/sample_robots/pytest.xml"
for f in "$cmake_result" "$py_result"; do
    [[ -s "$f" ]] || {
        show_log
        fail "no result file $f"
    }
done
status=0
colcon test-result --verbose >"$scratch/result.txt" 2>&1 || status=$?
sed 's/^/    | /' "$scratch/result.txt" >&2
((status != 0)) || fail "colcon test-result exited 0 with the bad robots"
for f in "$cmake_result" "$py_result"; do
    grep -qE "^$f: [0-9]+ tests?, [0-9]+ errors?, [1-9][0-9]* failures?" "$scratch/result.txt" ||
        fail "colcon test-result lists no failure in $f"
done
want="U701 joint-undersized: Joint 'shoulder' needs 7.36 N·m to hold the zero pose against gravity but declares effort 2"
n="$(grep -cF "$want" "$scratch/result.txt" || true)"
((n >= 2)) || fail "colcon test-result --verbose shows the U701 finding $n time(s), expected 2 (one per package): $want"
grep -qF "urdf/weak_arm.urdf:20:47: FAIL U701" "$scratch/result.txt" ||
    fail "colcon test-result --verbose does not locate the finding (urdf/weak_arm.urdf:20:47)"
if grep -q "mobile_manipulator" <(grep -E "failure message|U[0-9]{3}" -A2 "$scratch/result.txt" | grep -vF "Checked files"); then
    fail "the good robot appears among the failures"
fi
ok "colcon test-result: both packages fail on U701 at urdf/weak_arm.urdf:20:47"

# --- 2. the good robot alone passes -------------------------------------------------------------
rm "$py/urdf/weak_arm.urdf" "$cm/urdf/weak_arm.urdf"
colcon test-result --delete-yes >/dev/null
log "colcon build + colcon test, good robot only: must pass"
colcon_quiet colcon build --packages-select sample_robots sample_robots_cmake --event-handlers console_direct- || {
    show_log
    fail "colcon build failed (good robot only)"
}
colcon_quiet colcon test --return-code-on-test-failure --event-handlers console_direct- || {
    show_log
    fail "colcon test failed with only the good robot"
}
status=0
colcon test-result --all >"$scratch/result.txt" 2>&1 || status=$?
sed 's/^/    | /' "$scratch/result.txt" >&2
((status == 0)) || fail "colcon test-result exited $status with only the good robot"
for f in "$cmake_result" "$py_result"; do
    grep -qE "^$f: [1-9][0-9]* tests?, 0 errors, 0 failures" "$scratch/result.txt" ||
        fail "colcon test-result: $f does not pass with tests counted"
done
grep -qF "* urdf/mobile_manipulator.urdf" "$cmake_result" || fail "$cmake_result does not list the good robot as checked"
if grep -qF "macros.xacro" "$cmake_result"; then fail "the macro library was validated"; fi
ok "good robot only: colcon test passes, test-result counts the checks"

# --- 3. the command line ------------------------------------------------------------------------
set +u
# shellcheck disable=SC1091
source install/setup.bash
set -u
cd "$py"
cat >urdf/warn_arm.urdf <<'URDF'
<?xml version="1.0"?>
<robot name="warn_arm">
  <link name="base"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <link name="arm"/>
</robot>
URDF
expect_rc() { # WANT DESCRIPTION CMD...
    local want="$1" what="$2" got=0
    shift 2
    "$@" >"$scratch/cli.log" 2>&1 || got=$?
    if ((got != want)); then
        sed 's/^/    | /' "$scratch/cli.log" >&2
        fail "$what: exit $got, expected $want"
    fi
    ok "$what: exit $got"
}
expect_rc 1 "a WARN robot, --fail-on warn (default)" ament_urdf_validate --xunit-file "$scratch/x/w.xunit.xml"
grep -q 'failures="1"' "$scratch/x/w.xunit.xml" || fail "the WARN robot is no failure in the xunit file"
grep -qF "WARN U201 missing-inertial" "$scratch/x/w.xunit.xml" || fail "the xunit file lacks the U201 line"
expect_rc 0 "a WARN robot, --fail-on fail" ament_urdf_validate --fail-on fail
expect_rc 0 "a WARN robot excluded" ament_urdf_validate --exclude warn_arm.urdf
expect_rc 0 "a WARN robot, -- --ignore U201" ament_urdf_validate -- --ignore U201
# urdf-validate.toml: urdf_validate finds it itself, from each input upwards (the package's root here).
printf 'ignore = ["U201"]\n' >urdf-validate.toml
expect_rc 0 "a WARN robot, U201 ignored in the package's urdf-validate.toml" ament_urdf_validate
mkdir -p config && mv urdf-validate.toml config/strict.toml
expect_rc 1 "the configuration moved away" ament_urdf_validate
expect_rc 0 "--config config/strict.toml" ament_urdf_validate --config config/strict.toml
sed -i 's|<export>|<export>\n    <urdf_validate fail-on="fail"/>|' package.xml
expect_rc 0 "a WARN robot, package.xml fail-on=\"fail\"" ament_urdf_validate
sed -i 's|<urdf_validate fail-on="fail"/>|<urdf_validate fial-on="fail"/>|' package.xml
expect_rc 2 "package.xml with a misspelt attribute" ament_urdf_validate
grep -qF "package.xml: <urdf_validate> has unknown attribute(s) fial-on" "$scratch/cli.log" ||
    fail "the error does not name package.xml and the attribute"
sed -i 's|    <urdf_validate fial-on="fail"/>||' package.xml
mkdir -p "$scratch/macros_only" "$scratch/no_robots"
cp urdf/macros.xacro "$scratch/macros_only/"
expect_rc 0 "a folder of xacro macro libraries only" ament_urdf_validate "$scratch/macros_only"
expect_rc 1 "a folder without robot descriptions" ament_urdf_validate "$scratch/no_robots"
grep -qF "No files found" "$scratch/cli.log" || fail "no 'No files found' for a folder without robots"
expect_rc 2 "URDF_VALIDATE pointing nowhere" env URDF_VALIDATE=/nonexistent/urdf_validate ament_urdf_validate --fail-on fail
grep -qF "URDF_VALIDATE='/nonexistent/urdf_validate' is not an executable file" "$scratch/cli.log" ||
    fail "the error does not name URDF_VALIDATE"

log "all checks passed in $((SECONDS - start_s)) s"
echo "test-ros2: $passed passed, 0 failed"
