#!/usr/bin/env bash
# The README's picture of the language server in a real editor: Neovim (Debian's) under tmux, a small broken
# arm open with its diagnostics shown, and a hover on a joint; the terminal captured with its colours,
# turned into HTML (ansi2html) and photographed by headless Chromium to docs/lsp-neovim.png.
#   bash scripts/lsp-screenshot.sh [OUT.png]
# Needs tmux, nvim and chromium, the venv .venv-lsp of scripts/test-lsp.sh, and a built binary
# (URDF_VALIDATE_BIN, default target/release/urdf_validate).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
png="${1:-$repo_root/docs/lsp-neovim.png}"
bin="${URDF_VALIDATE_BIN:-$repo_root/target/release/urdf_validate}"
venv="$repo_root/.venv-lsp"
for tool in tmux nvim chromium; do
    command -v "$tool" >/dev/null || { echo "lsp-screenshot: $tool is not installed" >&2; exit 1; }
done
[[ -x "$bin" ]] || { echo "lsp-screenshot: no binary at $bin (cargo build --release, or set URDF_VALIDATE_BIN)" >&2; exit 1; }
[[ -x "$venv/bin/python" ]] || { echo "lsp-screenshot: run scripts/test-lsp.sh first (creates $venv)" >&2; exit 1; }
"$venv/bin/pip" install --quiet --disable-pip-version-check "ansi2html==1.9.2"

work="$(mktemp -d)"
session="urdf-lsp-shot-$$"
trap 'tmux kill-session -t "$session" 2>/dev/null || true; rm -rf "$work"' EXIT
cat >"$work/init.lua" <<'LUA'
vim.o.termguicolors = true
vim.o.number = true
vim.o.signcolumn = "yes"
vim.cmd("autocmd BufRead,BufNewFile *.urdf,*.xacro setfiletype xml")
vim.cmd("syntax on")
vim.api.nvim_create_autocmd("FileType", {
  pattern = "xml",
  callback = function(args)
    local client = vim.lsp.start_client({ name = "urdf_validate", cmd = { os.getenv("URDF_VALIDATE_BIN"), "server" } })
    vim.lsp.buf_attach_client(args.buf, client)
  end,
})
LUA
cat >"$work/arm.urdf" <<'URDF'
<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <inertial>
      <mass value="5"/>
      <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="upper"/>
    <axis xyz="0 2 0"/>
    <limit lower="-1" upper="1" effort="2" velocity="1"/>
  </joint>
  <link name="upper">
    <inertial>
      <origin xyz="0.5 0 0"/>
      <mass value="1"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <joint name="elbow" type="revolute">
    <parent link="upper"/>
    <child link="forearm"/>
  </joint>
</robot>
URDF
tmux new-session -d -s "$session" -x 120 -y 30 -c "$work" \
    "env URDF_VALIDATE_BIN='$bin' nvim -i NONE -u '$work/init.lua' arm.urdf"
sleep 4 # the server starts, both passes publish
tmux send-keys -t "$session" "9G" ""
sleep 0.3
tmux send-keys -t "$session" 'f"l' ""
sleep 0.3
tmux send-keys -t "$session" ":lua vim.lsp.buf.hover()" Enter
sleep 2
tmux capture-pane -t "$session" -p -e >"$work/pane.ansi"
grep -q "gravity torque" "$work/pane.ansi" || { echo "lsp-screenshot: no hover in the pane" >&2; cat "$work/pane.ansi" >&2; exit 1; }
grep -q "does not exist" "$work/pane.ansi" || { echo "lsp-screenshot: no diagnostics in the pane" >&2; exit 1; }
"$venv/bin/ansi2html" --scheme=xterm <"$work/pane.ansi" >"$work/pane.html"
sed -i 's|</style>|.ansi2html-content { font-family: "DejaVu Sans Mono", monospace; font-size: 15px; line-height: 1.25; } body { margin: 8px; }</style>|' "$work/pane.html"
mkdir -p "$(dirname "$png")"
chromium --headless --no-sandbox --disable-gpu --no-first-run --hide-scrollbars \
    --window-size=1130,680 --screenshot="$png" "file://$work/pane.html" >/dev/null 2>&1
size="$(wc -c <"$png")"
((size > 10000)) || { echo "lsp-screenshot: $png is only $size bytes" >&2; exit 1; }
echo "lsp-screenshot: $png ($size bytes)"
