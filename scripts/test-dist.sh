#!/usr/bin/env bash
# Verifies here what the release workflow (.github/workflows/release.yml) ships, as far as one Linux
# x86_64 machine can: each step prints PASS or FAIL with its duration, and the script exits 1 if any failed.
#
#   bash scripts/test-dist.sh              # every step
#   bash scripts/test-dist.sh aarch64 wine # only those steps (names below)
#
# Steps:
#   packages  the crates' package lists (scripts/check-package-lists.sh) and `cargo publish --workspace
#             --dry-run` (packages and compiles the four crates from a local overlay registry)
#   lint      actionlint (+ shellcheck) on .github/workflows and action.yml (scripts/lint-workflows.sh)
#   aarch64   the manylinux aarch64 wheel (maturin --zig, urdf_validate built by cargo-zigbuild for glibc
#             2.17), its urdf_validate run under qemu-user on the example robot, and `import urdf_validator`
#             in Debian's aarch64 CPython 3.11 under qemu-user
#   wine      the Windows x86_64 binary (x86_64-pc-windows-gnu, mingw-w64), run under wine on the example robot
#   wheel     the manylinux x86_64 wheel (as for aarch64), installed in a fresh venv and run with a PATH that
#             has neither cargo nor rustc (env -i)
#   audit     auditwheel show on the wheels built: their platform tags
#
# Installs what it needs: Debian packages with apt-get (it runs as root), the Rust targets with rustup, and
# pinned maturin, ziglang, cargo-zigbuild, auditwheel in a venv; everything it builds or downloads goes
# under $CARGO_TARGET_DIR/dist (target/dist by default), nothing into the repository.
# The steps are called by name (step_$name): shellcheck cannot see that they are reachable.
# shellcheck disable=SC2317
set -euo pipefail
# A command substitution ($(build_wheel ...)) fails its step too.
shopt -s inherit_errexit

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
export CARGO_INCREMENTAL=0
target_dir="${CARGO_TARGET_DIR:-$repo_root/target}"
work="$target_dir/dist"
tools="$work/tools"
robot="examples/robots/mobile_manipulator.urdf"
mkdir -p "$work"

log() { printf 'test-dist: %s\n' "$*" >&2; }

# ---- set-up -------------------------------------------------------------------------------------------

# Debian packages: qemu-user-static (aarch64 emulation), wine (Windows), mingw-w64 (the Windows linker),
# and shellcheck (actionlint runs it on the run: scripts of the workflows).
install_debs() {
    local missing=()
    command -v qemu-aarch64-static >/dev/null || missing+=(qemu-user-static)
    command -v wine >/dev/null || missing+=(wine wine64)
    command -v x86_64-w64-mingw32-gcc >/dev/null || missing+=(gcc-mingw-w64-x86-64)
    command -v shellcheck >/dev/null || missing+=(shellcheck)
    if ((${#missing[@]} > 0)); then
        log "apt-get install ${missing[*]}"
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq >/dev/null
        apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
    fi
}

# maturin, ziglang (the C toolchain and glibc 2.17 stubs for manylinux2014), cargo-zigbuild, auditwheel.
install_tools() {
    if [[ ! -x "$tools/bin/python" ]]; then
        python3 -m venv "$tools"
    fi
    "$tools/bin/python" -m pip install -q --disable-pip-version-check \
        "maturin==1.16.0" "ziglang==0.13.0.post1" "cargo-zigbuild==0.24.0" "auditwheel==6.8.2"
    rustup target add aarch64-unknown-linux-gnu x86_64-pc-windows-gnu >/dev/null 2>&1 ||
        rustup target add aarch64-unknown-linux-gnu x86_64-pc-windows-gnu
}

# An aarch64 root for qemu-user: Debian's arm64 CPython 3.11 and the libraries it and the wheel load,
# unpacked from their .debs (apt-get download: nothing of arm64 is installed on this machine; installing
# python3.11:arm64 through multiarch would replace the amd64 one). qemu-aarch64-static -L uses it as /.
arm64_root="$work/arm64-root"
arm64_debs=(python3.11-minimal libpython3.11-minimal libpython3.11-stdlib libc6 libgcc-s1 libexpat1 zlib1g
    libffi8 libssl3 libbz2-1.0 liblzma5 libsqlite3-0 libuuid1 libcrypt1)
make_arm64_root() {
    if [[ -x "$arm64_root/usr/bin/python3.11" ]]; then
        return 0
    fi
    if ! dpkg --print-foreign-architectures | grep -qx arm64; then
        log "dpkg --add-architecture arm64 (for apt-get download of arm64 .debs)"
        dpkg --add-architecture arm64
        apt-get update -qq >/dev/null
    fi
    local debs="$work/arm64-debs"
    rm -rf "$debs" "$arm64_root"
    mkdir -p "$debs" "$arm64_root"
    (cd "$debs" && apt-get download -qq "${arm64_debs[@]/%/:arm64}" 2>/dev/null)
    local deb
    for deb in "$debs"/*.deb; do
        dpkg-deb -x "$deb" "$arm64_root"
    done
}

# ---- checks shared by the steps -----------------------------------------------------------------------

# check_report DIR: the JSON report urdf_validate wrote for the example robot says PASS.
check_report() {
    local report="$1/mobile_manipulator_validation.json"
    python3 - "$report" <<'EOF'
import json, sys
status = json.load(open(sys.argv[1]))["overall_status"]
print(f"report: overall_status {status}")
sys.exit(0 if status == "PASS" else 1)
EOF
}

# run_robot LABEL CMD...: runs the command on the example robot (writing its JSON report into a scratch
# directory), expects exit 0 and a PASS report.
run_robot() {
    local label="$1"
    shift
    local out
    out="$(mktemp -d "$work/out.XXXXXX")"
    local code=0
    "$@" "$robot" --output-dir "$out" >"$out/stdout.txt" 2>"$out/stderr.txt" || code=$?
    tail -3 "$out/stdout.txt"
    if ((code != 0)); then
        log "$label: urdf_validate exited $code (expected 0)"
        cat "$out/stderr.txt" >&2
        return 1
    fi
    check_report "$out"
}

# ---- steps --------------------------------------------------------------------------------------------

step_packages() {
    bash scripts/check-package-lists.sh
    cargo publish --workspace --dry-run --locked 2>&1 | grep -v "^warning: ignoring \(test\|benchmark\)"
}

step_lint() {
    bash scripts/lint-workflows.sh
}

# build_wheel ARCH: the urdf_validate binary for ARCH-unknown-linux-gnu with glibc 2.17 symbols
# (cargo-zigbuild), then the manylinux2014 wheel around it (maturin --zig); the wheel's path on stdout.
build_wheel() {
    local arch="$1" triple="$1-unknown-linux-gnu"
    local out="$work/wheels-$arch"
    rm -rf "$out"
    PATH="$tools/bin:$PATH" cargo zigbuild --quiet --release --locked -p urdf-validate-cli \
        --bin urdf_validate --target "$triple.2.17" >&2
    PATH="$tools/bin:$PATH" URDF_VALIDATE_WHEEL_BINARY="$target_dir/$triple/release/urdf_validate" \
        "$tools/bin/maturin" build --quiet --release --locked --zig --target "$triple" \
        --compatibility manylinux2014 --out "$out" >&2
    ls "$out"/urdf_validator-*.whl
}

step_aarch64() {
    install_debs
    install_tools
    make_arm64_root
    local wheel
    wheel="$(build_wheel aarch64)"
    log "wheel: $(basename "$wheel")"
    local unpacked="$work/aarch64-unpacked"
    rm -rf "$unpacked"
    "$tools/bin/python" -m zipfile -e "$wheel" "$unpacked"
    local binary
    binary="$(ls "$unpacked"/urdf_validator-*.data/scripts/urdf_validate)"
    chmod +x "$binary"
    file "$binary" | sed "s|$unpacked/||"
    run_robot "aarch64 urdf_validate under qemu" qemu-aarch64-static -L "$arm64_root" "$binary"
    # The extension module in aarch64 CPython (the wheel unpacked on PYTHONPATH: no pip for aarch64 here).
    PYTHONPATH="$unpacked" qemu-aarch64-static -L "$arm64_root" "$arm64_root/usr/bin/python3.11" - "$robot" <<'EOF'
import platform, sys
import urdf_validator
report = urdf_validator.validate(sys.argv[1])
status = report.to_dict()["overall_status"]
print(f"aarch64 python {platform.python_version()} on {platform.machine()}: urdf_validator "
      f"{urdf_validator.__version__}, {report.urdf_path}: {status}, exit code {report.exit_code}")
sys.exit(0 if status == "PASS" and report.exit_code == 0 else 1)
EOF
}

step_wine() {
    install_debs
    install_tools
    cargo build --quiet --release --locked -p urdf-validate-cli --bin urdf_validate \
        --target x86_64-pc-windows-gnu
    local exe="$target_dir/x86_64-pc-windows-gnu/release/urdf_validate.exe"
    file "$exe" | sed "s|$target_dir/||"
    # A wine prefix of its own (created on first use, a few seconds), no debug chatter, no desktop.
    # mscoree, mshtml disabled: wine would offer to download Mono and Gecko when it makes the prefix.
    export WINEPREFIX="$work/wine-prefix" WINEDEBUG=-all DISPLAY='' WINEDLLOVERRIDES="mscoree,mshtml="
    wine_shim
    run_robot "Windows urdf_validate.exe under wine" wine "$exe"
}

# Rust's standard library (1.78 and later) draws random bytes with ProcessPrng from bcryptprimitives.dll
# (Windows 10 and later), which Debian 12's wine 8.0 does not have: every Rust program stops at load with
# "Library bcryptprimitives.dll not found". Put a stand-in into the prefix, built here with mingw-w64: its
# ProcessPrng calls advapi32's RtlGenRandom (SystemFunction036). The test harness gets the DLL; the binary
# under test is unchanged, and on Windows the system's DLL is the one loaded.
wine_shim() {
    local system32="$WINEPREFIX/drive_c/windows/system32"
    if [[ ! -d "$system32" ]]; then
        wineboot --init >/dev/null 2>&1 || true
    fi
    if [[ ! -d "$system32" ]]; then
        log "wine did not create $system32"
        return 1
    fi
    if [[ -f "$system32/bcryptprimitives.dll" ]]; then
        return 0
    fi
    local source="$work/bcryptprimitives.c"
    cat >"$source" <<'C'
#include <windows.h>
BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length); /* RtlGenRandom */
__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T length) {
    while (length > 0) {
        ULONG chunk = length > 0x7fffffff ? 0x7fffffff : (ULONG)length;
        if (!SystemFunction036(data, chunk)) return FALSE;
        data += chunk;
        length -= chunk;
    }
    return TRUE;
}
C
    x86_64-w64-mingw32-gcc -shared -O2 -o "$system32/bcryptprimitives.dll" "$source" -ladvapi32
    echo "wine: bcryptprimitives.dll stand-in (ProcessPrng) installed in the prefix"
}

step_wheel() {
    install_tools
    local wheel
    wheel="$(build_wheel x86_64)"
    log "wheel: $(basename "$wheel")"
    local venv="$work/wheel-venv"
    rm -rf "$venv"
    python3 -m venv "$venv"
    "$venv/bin/python" -m pip install -q --disable-pip-version-check --no-index "$wheel"
    local clean_path="$venv/bin:/usr/bin:/bin"
    # The PATH the installed wheel runs with must really lack the Rust toolchain.
    local tool
    for tool in cargo rustc; do
        if env -i PATH="$clean_path" bash -c "command -v $tool" >/dev/null; then
            log "$tool is on $clean_path: the check would prove nothing"
            return 1
        fi
    done
    echo "no cargo, no rustc on PATH=$clean_path"
    run_robot "x86_64 wheel's urdf_validate without cargo" env -i PATH="$clean_path" HOME="$work" urdf_validate
    env -i PATH="$clean_path" HOME="$work" python - "$robot" <<'EOF'
import sys
import urdf_validator
report = urdf_validator.validate(sys.argv[1])
status = report.to_dict()["overall_status"]
print(f"x86_64 wheel: urdf_validator {urdf_validator.__version__} from {urdf_validator.__file__}: {status}")
sys.exit(0 if status == "PASS" and report.exit_code == 0 else 1)
EOF
}

step_audit() {
    install_tools
    shopt -s nullglob
    local wheels=("$work"/wheels-*/urdf_validator-*.whl)
    shopt -u nullglob
    if ((${#wheels[@]} == 0)); then
        log "no wheel built (run the aarch64 or wheel step first)"
        return 1
    fi
    local wheel status=0
    for wheel in "${wheels[@]}"; do
        echo "== $(basename "$wheel")"
        local shown
        shown="$("$tools/bin/auditwheel" show "$wheel" 2>&1)" || status=1
        echo "$shown" | tr '\n' ' ' | fold -s -w 110
        echo
        # manylinux2014 = manylinux_2_17: the tag the wheel claims must be one auditwheel agrees with.
        if ! grep -q 'manylinux_2_17' <<<"$shown"; then
            log "$(basename "$wheel"): auditwheel does not find it manylinux_2_17-compatible"
            status=1
        fi
    done
    return "$status"
}

# ---- driver -------------------------------------------------------------------------------------------

all_steps=(packages lint aarch64 wine wheel audit)
steps=("$@")
if ((${#steps[@]} == 0)); then
    steps=("${all_steps[@]}")
fi
summary=()
failed=0
script_start=$SECONDS
for name in "${steps[@]}"; do
    if ! declare -F "step_$name" >/dev/null; then
        log "unknown step '$name' (steps: ${all_steps[*]})"
        exit 2
    fi
    printf '\n=== test-dist: %s ===\n' "$name"
    start=$SECONDS
    # Each step runs in a subshell with errexit, so a failing command fails its step and not the script
    # (not as an `if` condition: there bash would ignore errexit inside the step).
    set +e
    (
        set -e
        "step_$name"
    )
    code=$?
    set -e
    if ((code == 0)); then
        result=PASS
    else
        result=FAIL
        failed=1
    fi
    line="$(printf '%-9s %s (%d s)' "$name" "$result" $((SECONDS - start)))"
    echo "test-dist: $line"
    summary+=("$line")
done
printf '\n=== test-dist summary (%d s in all) ===\n' $((SECONDS - script_start))
printf '%s\n' "${summary[@]}"
exit "$failed"
