"""One run in a real editor: headless Neovim's built-in LSP client opens a broken URDF, and what
vim.diagnostic.get() shows is checked. Neovim comes from Debian (scripts/test-lsp.sh installs it); without
it the test skips, or fails under CI=true."""

import json
import os
import pathlib
import shutil
import subprocess

import pytest

from conftest import BIN

BROKEN = """<?xml version="1.0"?>
<robot name="broken">
  <link name="base"/>
  <joint name="j" type="fixed">
    <parent link="base"/>
    <child link="missing"/>
  </joint>
</robot>
"""


def test_neovim_shows_the_diagnostics(tmp_path):
    nvim = shutil.which("nvim")
    if nvim is None:
        if os.environ.get("CI") == "true":
            pytest.fail("nvim is not installed (scripts/test-lsp.sh installs Debian's neovim)")
        pytest.skip("nvim is not installed")
    robot = tmp_path / "broken.urdf"
    robot.write_text(BROKEN)
    out = tmp_path / "diagnostics.json"
    init = pathlib.Path(__file__).with_name("neovim_init.lua")
    env = dict(os.environ, URDF_VALIDATE_BIN=BIN, URDF_LSP_OUT=str(out), HOME=str(tmp_path))
    subprocess.run(
        [nvim, "--headless", "-i", "NONE", "-u", str(init), str(robot)],
        env=env,
        timeout=120,
        check=True,
        stdin=subprocess.DEVNULL,
        capture_output=True,
    )
    shown = json.loads(out.read_text())
    undefined = [d for d in shown if d["code"] == "U102"]
    assert undefined, shown
    [d] = undefined
    assert d["lnum"] == 5, d  # 0-based: the <child link="missing"/> line
    assert BROKEN.split("\n")[5][d["col"] : d["end_col"]] == "missing", d
    assert d["severity"] == 1  # vim.diagnostic.severity.ERROR
    assert "missing" in d["message"]
