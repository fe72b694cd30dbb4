#!/usr/bin/env bash
# Times one `urdf_validate` call over the whole example-robot-data corpus (69 URDFs), and over
# ../shared/robots when present, with the release binary; then the long-chain budget and the per-robot
# budget (each corpus robot in <= 100 ms); exits 1 when a budget does not hold.
#
#   bash scripts/bench-corpus.sh
#
# Uses hyperfine when installed (--warmup 2 --runs 10), otherwise 10 timed runs in a bash loop.
# A non-zero exit code of urdf_validate is expected (1 = WARN, 2 = FAIL: some corpus robots have findings);
# only an exit code > 2 or a crash (killed by a signal) counts as a failure of the benchmark.
# Runs without MuJoCo (see below), so a robot's time does not depend on what the calling Python holds.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

runs=10
warmup=2

echo "== building the release binary" >&2
cargo build --release -p urdf-validate-cli
bin="${CARGO_TARGET_DIR:-$repo_root/target}/release/urdf_validate"
[[ -x "$bin" ]] || {
    echo "bench-corpus: $bin not found after cargo build" >&2
    exit 1
}

echo "== ensuring the corpus" >&2
corpus="$(bash scripts/setup-test-env.sh)"

tmp="$(mktemp -d)"
trap 'rm -rf -- "$tmp"' EXIT

# The MuJoCo pass runs by itself on a negative stability margin when the Python it is given has MuJoCo
# (human has one): the budgets are the validator's own work, timed with a Python that has no MuJoCo (an
# empty venv), whatever the calling environment holds.
python3 -m venv --without-pip "$tmp/python"
export URDF_VALIDATOR_PYTHON="$tmp/python/bin/python"

declare -a names=() medians=()

# One checked run: exit codes 0, 1 and 2 are results; anything else (> 2, or a signal) is a failure.
check_run() {
    local dir="$1" out="$2" status=0
    "$bin" "$dir" --output-dir "$out" >/dev/null 2>"$tmp/stderr" || status=$?
    if ((status > 2)); then
        echo "bench-corpus: urdf_validate exited $status on $dir (crash or error):" >&2
        cat "$tmp/stderr" >&2
        exit 1
    fi
    echo "$status"
}

bench() {
    local name="$1" dir="$2" out="$tmp/reports-$1" n status median
    mkdir -p "$out"
    n="$(find "$dir" -name '*.urdf' | wc -l)"
    status="$(check_run "$dir" "$out")"
    echo
    echo "== $name: $dir ($n URDF files; urdf_validate exit code $status)"
    if command -v hyperfine >/dev/null 2>&1; then
        local cmd
        cmd="$(printf '%q ' "$bin" "$dir" --output-dir "$out")"
        hyperfine --warmup "$warmup" --runs "$runs" -i --export-json "$tmp/$name.json" \
            --command-name "$name" "$cmd"
        median="$(python3 -c 'import json, sys; print("%.1f" % (json.load(open(sys.argv[1]))["results"][0]["median"] * 1000))' "$tmp/$name.json")"
    else
        echo "(hyperfine not installed: $runs timed runs after $warmup warm-up runs)"
        local i start end times=()
        for ((i = 0; i < warmup; i++)); do check_run "$dir" "$out" >/dev/null; done
        for ((i = 1; i <= runs; i++)); do
            start="$(date +%s%N)"
            check_run "$dir" "$out" >/dev/null
            end="$(date +%s%N)"
            times+=("$(((end - start) / 1000))")
            printf '  run %2d: %6d.%d ms\n' "$i" "$((times[-1] / 1000))" "$((times[-1] % 1000 / 100))"
        done
        median="$(python3 -c 'import statistics, sys; print("%.1f" % (statistics.median(int(t) for t in sys.argv[1:]) / 1000))' "${times[@]}")"
    fi
    names+=("$name ($n files)")
    medians+=("$median")
}

bench corpus "$corpus"
shared="$repo_root/../shared/robots"
if [[ -d "$shared" ]]; then
    bench shared-robots "$(cd "$shared" && pwd)"
else
    echo "(../shared/robots absent: skipped)" >&2
fi

# Long chains lying on the ground (issue 26: 10 g links, revolute joints 1 mm apart along x, no geometry):
# every stage must stay linear in the links. Budget: the 20,000-link chain in <= 2 s and <= 25x the
# 1,000-link one.
chain_dir() {
    local links="$1" dir="$tmp/chain-$1"
    mkdir -p "$dir"
    python3 - "$links" "$dir/chain_$links.urdf" <<'PY'
import sys
links, path = int(sys.argv[1]), sys.argv[2]
inertial = ('<inertial><mass value="0.01"/>'
            '<inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>')
with open(path, "w") as f:
    f.write('<robot name="chain">\n')
    for i in range(links + 1):
        f.write(f'<link name="l{i}">{inertial}</link>\n')
    for i in range(links):
        f.write(f'<joint name="j{i}" type="revolute"><parent link="l{i}"/><child link="l{i + 1}"/>'
                '<origin xyz="0.001 0 0"/><axis xyz="0 0 1"/>'
                '<limit lower="-1" upper="1" effort="100" velocity="1"/></joint>\n')
    f.write('</robot>\n')
PY
    echo "$dir"
}
runs=5
warmup=1
bench chain-1000 "$(chain_dir 1000)"
short_chain="${medians[-1]}"
bench chain-20000 "$(chain_dir 20000)"
long_chain="${medians[-1]}"

echo
echo "== medians (one urdf_validate call, release build)"
for i in "${!names[@]}"; do
    printf '  %-28s median %8s ms\n' "${names[$i]}" "${medians[$i]}"
done
over_budget=0
python3 - "$short_chain" "$long_chain" <<'PY' || over_budget=1
import sys
short, long = map(float, sys.argv[1:])
ratio = long / short
print(f"  chain 20,000 / 1,000 links: {ratio:.1f}x (budget 25x); 20,000 links {long:.0f} ms (budget 2000 ms)")
sys.exit(0 if ratio <= 25 and long <= 2000 else 1)
PY

# Per robot (issue 26): every example-robot-data robot in <= 100 ms at default settings, wall time, median
# of 3 runs after a warm-up, warm mesh cache. Prints the ten slowest and every robot over the budget.
echo
echo "== per robot: example-robot-data, median of 3 runs after a warm-up (budget 100 ms each)"
python3 - "$bin" "$corpus" "$tmp/per-robot" <<'PY' || over_budget=1
import pathlib, statistics, subprocess, sys, time
binary, corpus, out = sys.argv[1], pathlib.Path(sys.argv[2]), sys.argv[3]
times = {}
for urdf in sorted(corpus.rglob("*.urdf")):
    command = [binary, str(urdf), "--output-dir", out, "-q"]
    runs = []
    for i in range(4):
        start = time.perf_counter()
        status = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
        if i:
            runs.append((time.perf_counter() - start) * 1000)
        if status > 2 or status < 0:
            sys.exit(f"bench-corpus: urdf_validate exited {status} on {urdf}")
    times[urdf.relative_to(corpus)] = statistics.median(runs)
ranked = sorted(times.items(), key=lambda item: -item[1])
over = [name for name, ms in ranked if ms > 100]
print(f"  {len(times)} robots: median {statistics.median(times.values()):.0f} ms; {len(over)} over 100 ms")
for name, ms in ranked[:10]:
    print(f"  {ms:7.1f} ms  {name}{'  OVER BUDGET' if ms > 100 else ''}")
sys.exit(1 if over else 0)
PY
if ((over_budget)); then
    echo "bench-corpus: a budget does not hold (the long chain's or the per-robot one, see above)" >&2
    exit 1
fi
