"""``urdf_validate_mcp`` and ``python -m urdf_validator``: the ``urdf_validate`` binary the wheel installs
beside this package's scripts, run in place of this process."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
from typing import List, Optional


def main() -> None:
    """Run ``urdf_validate`` with this process's arguments and exit with its status."""
    _run(sys.argv[1:])


def mcp() -> None:
    """``urdf_validate_mcp``: the MCP server (``urdf_validate mcp``), under the Python tool's name."""
    _run(["mcp", *sys.argv[1:]])


def binary() -> Optional[str]:
    """The ``urdf_validate`` binary of this installation: in the scripts folder of the entry point that
    is running (a venv's ``bin``, ``~/.local/bin``), else of this interpreter's scheme, else on ``PATH``."""
    name = "urdf_validate.exe" if os.name == "nt" else "urdf_validate"
    folders = [os.path.dirname(os.path.abspath(sys.argv[0])) if sys.argv and sys.argv[0] else ""]
    folders.append(sysconfig.get_path("scripts"))
    if sys.platform != "win32":
        folders.append(sysconfig.get_path("scripts", f"{os.name}_user"))
    for folder in folders:
        candidate = os.path.join(folder, name) if folder else ""
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return shutil.which(name)


def _run(arguments: List[str]) -> None:
    command = binary()
    if command is None:
        sys.exit("error: the urdf_validate binary of this installation was not found (reinstall urdf-validator)")
    # --deep runs MuJoCo in a Python process: this one's, where `pip install "urdf-validator[mujoco]"` put it.
    os.environ.setdefault("URDF_VALIDATOR_PYTHON", sys.executable)
    if os.name == "nt":
        sys.exit(subprocess.call([command, *arguments]))
    os.execv(command, [command, *arguments])


if __name__ == "__main__":
    main()
