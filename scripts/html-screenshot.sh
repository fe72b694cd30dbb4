#!/usr/bin/env bash
# Renders a robot's HTML report in headless Chromium and saves a screenshot: by default the PR2 of
# ../shared/robots (URDF_VALIDATOR_SHARED_ROBOTS) to docs/report-pr2.png, the README's picture. Fails when
# the page logs a console message or the screenshot is missing or nearly blank.
# The report shows the path it was given: ROBOT.urdf as typed (relative to the current directory), the
# default PR2 as pr2/pr2_description/robots/pr2.urdf (run from the robots folder), never a path of this
# machine. A robot whose stability margin is negative gets its deep section (MuJoCo) when
# URDF_VALIDATOR_PYTHON names a Python with `mujoco`.
#   bash scripts/html-screenshot.sh [ROBOT.urdf [OUT.png]]
# Environment: URDF_VALIDATOR_CHROMIUM (the browser), SHOT_WIDTH / SHOT_HEIGHT (window size, 1280x2830: down to the first arm).
# The test crates/urdf-validator/tests/html_browser.rs makes the same checks in `cargo test`.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
robots="${URDF_VALIDATOR_SHARED_ROBOTS:-$repo_root/../shared/robots}"
robots="$(cd "$robots" 2>/dev/null && pwd || echo "$robots")"
if [[ $# -ge 1 ]]; then
    from="$PWD"
    urdf="$1"
else
    from="$robots"
    urdf="pr2/pr2_description/robots/pr2.urdf"
fi
png="${2:-$repo_root/docs/report-pr2.png}"
[[ "$png" == /* ]] || png="$PWD/$png"
width="${SHOT_WIDTH:-1280}"
height="${SHOT_HEIGHT:-2830}"

browser="${URDF_VALIDATOR_CHROMIUM:-}"
if [[ -z "$browser" ]]; then
    for name in chromium chromium-browser google-chrome google-chrome-stable; do
        if command -v "$name" >/dev/null 2>&1; then
            browser="$(command -v "$name")"
            break
        fi
    done
fi
if [[ -z "$browser" ]]; then
    echo "html-screenshot.sh: no Chromium on PATH (apt-get install chromium, or set URDF_VALIDATOR_CHROMIUM)" >&2
    exit 1
fi
if ! (cd "$from" 2>/dev/null && [[ -f "$urdf" ]]); then
    echo "html-screenshot.sh: $urdf not found in $from (set URDF_VALIDATOR_SHARED_ROBOTS or pass a URDF)" >&2
    exit 1
fi

tmp="$(mktemp -d)"
trap 'rm -rf -- "$tmp"' EXIT
html="$tmp/report.html"
# `cargo run` keeps the current directory: the example reads the path as given, relative to "$from".
(cd "$from" && cargo run -q --manifest-path "$repo_root/Cargo.toml" -p urdf-validator --example html_report -- "$urdf" "$html")

"$browser" --headless --no-sandbox --disable-gpu --no-first-run --hide-scrollbars \
    --force-device-scale-factor=1 --user-data-dir="$tmp/profile" \
    --enable-logging=stderr --v=0 --window-size="$width,$height" \
    --screenshot="$png" "file://$html" >"$tmp/stdout" 2>"$tmp/stderr" || {
    cat "$tmp/stderr" >&2
    echo "html-screenshot.sh: chromium failed" >&2
    exit 1
}
if grep -E 'CONSOLE|Uncaught' "$tmp/stderr" >&2; then
    echo "html-screenshot.sh: the page logged console messages (above)" >&2
    exit 1
fi
size="$(wc -c <"$png")"
if ((size < 50000)); then
    echo "html-screenshot.sh: $png is only $size bytes: the page looks blank" >&2
    exit 1
fi
echo "html-screenshot.sh: $png ($size bytes, ${width}x${height}) from $(wc -c <"$html") bytes of HTML"
