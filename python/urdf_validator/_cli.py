"""The ``urdf_validate`` console command of the wheel: the Rust command itself, run in-process."""

from __future__ import annotations

import os
import signal
import sys

from . import _native


def main() -> None:
    """Run ``urdf_validate`` with this process's arguments and exit with its status."""
    _run(sys.argv[1:])


def mcp() -> None:
    """``urdf_validate_mcp``: the MCP server (``urdf_validate mcp``), under the Python tool's name."""
    _run(["mcp", *sys.argv[1:]])


def _run(arguments: list) -> None:
    # The Rust command runs with the GIL released, where Python's handler would only note a Ctrl-C:
    # let it end the process as it ends the native binary. (A closed pipe is already quiet: Python
    # ignores SIGPIPE, as Rust binaries do, and the command ends quietly on the write error.)
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    # --deep runs MuJoCo in a Python process: this one's, where `pip install "urdf-validator[mujoco]"` put it.
    os.environ.setdefault("URDF_VALIDATOR_PYTHON", sys.executable)
    sys.exit(_native.main(["urdf_validate", *arguments]))


if __name__ == "__main__":
    main()
