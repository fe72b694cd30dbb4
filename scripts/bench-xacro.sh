#!/usr/bin/env bash
# Times the expansion of PR2's pr2.urdf.xacro by Python xacro 2.1.1 (in-process `process_file`, excluding
# interpreter start, and the `xacro` command's wall time) and by the native expander (in-process median and
# the example binary's wall time), and prints the ratios.
#
#   bash scripts/bench-xacro.sh [RUNS]        # default 20 runs each
#
# Needs the test venv (scripts/setup-test-env.sh) and ../shared/robots (or URDF_VALIDATOR_SHARED_ROBOTS).
set -euo pipefail

runs="${1:-20}"
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
bash scripts/setup-test-env.sh >/dev/null
robots="${URDF_VALIDATOR_SHARED_ROBOTS:-$repo_root/../shared/robots}"
pkg="$(cd "$robots/pr2/pr2_description" && pwd)"
file="$pkg/robots/pr2.urdf.xacro"
[[ -f "$file" ]] || { echo "bench-xacro: $file not found" >&2; exit 1; }

# Python xacro finds packages through the ament index: serve pr2_description from a scratch prefix.
prefix="$(mktemp -d)"
trap 'rm -rf -- "$prefix"' EXIT
mkdir -p "$prefix/share/ament_index/resource_index/packages"
touch "$prefix/share/ament_index/resource_index/packages/pr2_description"
ln -s "$pkg" "$prefix/share/pr2_description"
export AMENT_PREFIX_PATH="$prefix"
entry="$prefix/share/pr2_description/robots/pr2.urdf.xacro"

target_dir="${CARGO_TARGET_DIR:-$repo_root/target}"
cargo build --quiet --release -p urdf-validator-xacro --example expand
native="$target_dir/release/examples/expand"

median_ms() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

py_inproc="$(.venv/bin/python - "$entry" "$runs" <<'PY'
import sys, time, io, contextlib, statistics
import xacro
path, runs = sys.argv[1], int(sys.argv[2])
times = []
cpu = time.process_time()
for _ in range(runs):
    t = time.perf_counter()
    with contextlib.redirect_stderr(io.StringIO()):
        doc = xacro.process_file(path)
    doc.toprettyxml(indent='  ')
    times.append((time.perf_counter() - t) * 1e3)
print(statistics.median(times), (time.process_time() - cpu) / runs * 1e3)
PY
)"
py_median="${py_inproc% *}"
py_cpu="${py_inproc#* }"

wall_ms() { # command... -> median wall time in ms over $runs runs
    for _ in $(seq "$runs"); do
        local t0 t1
        t0=$(date +%s%N)
        "$@" >/dev/null 2>&1
        t1=$(date +%s%N)
        echo "$(( (t1 - t0) / 1000 ))" | awk '{print $1/1000}'
    done | median_ms
}

py_cli="$(wall_ms .venv/bin/xacro "$entry")"
ours_report="$("$native" "$entry" --repeat "$runs" 2>&1)"
ours_inproc="$(awk '/median/ {print $2}' <<<"$ours_report")"
ours_cpu="$(awk '/^cpu/ {print $2}' <<<"$ours_report")"
ours_cli="$(wall_ms "$native" "$entry")"

printf 'PR2 pr2.urdf.xacro, median of %s runs (load average %s)\n' "$runs" "$(cut -d' ' -f1 /proc/loadavg)"
printf '  Python xacro 2.1.1 process_file (in-process): %8.2f ms   (CPU %.2f ms per run)\n' "$py_median" "$py_cpu"
printf '  native expander (in-process):                 %8.2f ms   (CPU %.2f ms per run)\n' "$ours_inproc" "$ours_cpu"
printf '  ratio in-process: %.1fx wall (median), %.1fx CPU\n' \
    "$(awk -v a="$py_median" -v b="$ours_inproc" 'BEGIN {print a / b}')" \
    "$(awk -v a="$py_cpu" -v b="$ours_cpu" 'BEGIN {print (b > 0 ? a / b : 0)}')"
printf '  Python xacro command (wall):                  %8.2f ms\n' "$py_cli"
printf '  native example binary (wall):                 %8.2f ms   ratio %.1fx\n' "$ours_cli" \
    "$(awk -v a="$py_cli" -v b="$ours_cli" 'BEGIN {print a / b}')"
