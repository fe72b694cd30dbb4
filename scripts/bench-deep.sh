#!/usr/bin/env bash
# Times `urdf_validate --deep` on example-robot-data's PR2: the whole run (parse, analyses, the MuJoCo
# model build, the cross-check and the 2-second drop test), one warm-up run then RUNS timed runs, and
# prints each, the median, and the deep phase alone (from --timings).
#
#   bash scripts/bench-deep.sh              # RUNS=5; builds the release binary first (cargo build --release)
#   BIN=target/debug/urdf_validate bash scripts/bench-deep.sh
#
# Needs the test venv (scripts/setup-test-env.sh: the corpus and mujoco).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
corpus="$(bash scripts/setup-test-env.sh)"
export URDF_VALIDATOR_PYTHON="$repo_root/.venv/bin/python"
runs="${RUNS:-5}"
bin="${BIN:-}"
if [[ -z "$bin" ]]; then
    cargo build --release -q -p urdf-validate-cli
    bin="$repo_root/target/release/urdf_validate"
fi
pr2="$corpus/pr2_description/urdf/pr2.urdf"
"$bin" "$pr2" --deep --no-write -q >/dev/null || true # warm-up (mesh cache, Python's bytecode)
times=()
for ((i = 1; i <= runs; i++)); do
    start=$(date +%s.%N)
    deep_ms="$("$bin" "$pr2" --deep --no-write --timings --format json | "$URDF_VALIDATOR_PYTHON" -c \
        'import json, sys; print(json.load(sys.stdin)["timings_ms"]["deep"])')" || true
    end=$(date +%s.%N)
    t=$(echo "$end - $start" | bc -l)
    times+=("$t")
    printf 'run %d: %.3f s (deep pass %.0f ms)\n' "$i" "$t" "$deep_ms"
done
median=$(printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
printf 'PR2 --deep, median of %d: %.3f s\n' "$runs" "$median"
