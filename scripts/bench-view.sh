#!/usr/bin/env bash
# Times `urdf_validate view` on PR2 (../shared/robots, or URDF_VALIDATOR_SHARED_ROBOTS): the first frame
# (the command started → its URL printed, then the page opened → its first frame drawn, in headless
# Chromium with SwiftShader WebGL, driven by crates/cli/tests/view_browser/drive.mjs), and slider moves
# (a joint slider moved → POST /pose answered → the next frame drawn). Prints the medians of RUNS starts
# (default 5) and of POSES slider moves per start (default 20). Both end when the GPU has finished the frame
# (a pixel read back). The first frame is timed twice: in a browser just started ("cold": its first WebGL
# context starts Chromium's GPU side, about 0.3 s here) and in one that has drawn WebGL before ("warm", as
# the browser a user already has open).
#
# URDF_VALIDATE=path/to/urdf_validate (default: target/release/urdf_validate, built when missing);
# CHROMIUM (default chromium); needs node.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
robots="${URDF_VALIDATOR_SHARED_ROBOTS:-$here/../shared/robots}"
robot="${1:-$robots/pr2/pr2_description/robots/pr2.urdf}"
bin="${URDF_VALIDATE:-${CARGO_TARGET_DIR:-$here/target}/release/urdf_validate}"
chromium="${CHROMIUM:-chromium}"
runs="${RUNS:-5}"
poses="${POSES:-20}"
if [ ! -x "$bin" ]; then
  cargo build --release -p urdf-validate-cli --manifest-path "$here/Cargo.toml"
fi
work="$(mktemp -d)"
server=""
cleanup() { if [ -n "$server" ]; then kill "$server" 2>/dev/null || true; fi; rm -rf "$work"; }
trap cleanup EXIT
for mode in cold warm; do
  for run in $(seq "$runs"); do
    rm -f "$work/out"
    start=$(date +%s%N)
    "$bin" view --port 0 "$robot" >"$work/out" 2>/dev/null &
    server=$!
    until grep -q "http://127.0.0.1:[0-9]*/" "$work/out" 2>/dev/null; do sleep 0.005; done
    listening=$(( ($(date +%s%N) - start) / 1000000 ))
    url=$(grep -o "http://127.0.0.1:[0-9]*/" "$work/out")
    flags=(--poses "$poses")
    if [ "$mode" = warm ]; then flags+=(--warm); fi
    node "$here/crates/cli/tests/view_browser/drive.mjs" "$chromium" "$url" "$work/shot.png" "${flags[@]}" >"$work/$mode$run.json"
    kill "$server"; wait "$server" 2>/dev/null || true; server=""
    echo "$listening" >"$work/listening-$mode$run"
  done
done
node - "$work" "$runs" <<'JS'
const fs = require("fs");
const [work, runs] = process.argv.slice(2);
const median = (xs) => { const s = [...xs].sort((a, b) => a - b); const m = s.length >> 1; return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2; };
const pose = [];
for (const mode of ["cold", "warm"]) {
  const listening = [], page = [], total = [];
  for (let i = 1; i <= Number(runs); i++) {
    const r = JSON.parse(fs.readFileSync(`${work}/${mode}${i}.json`, "utf8"));
    if (r.error) throw new Error(r.error);
    const l = Number(fs.readFileSync(`${work}/listening-${mode}${i}`, "utf8"));
    listening.push(l); page.push(r.readyMs); total.push(l + r.readyMs); pose.push(...r.poseMs);
  }
  console.log(`${mode} browser, runs ${runs}: command start → URL ${median(listening)} ms, page open → first frame drawn ${median(page)} ms, first frame from start ${median(total)} ms (median)`);
}
console.log(`slider moves ${pose.length}: input → POST /pose → frame drawn ${median(pose).toFixed(1)} ms median, ${Math.max(...pose).toFixed(1)} ms max`);
JS
