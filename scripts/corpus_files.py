"""What the comparison scripts (verdict-diff.py, report-identity.py) share: the robot files below a path, and
one binary's JSON report of one of them."""

import json
import pathlib
import subprocess


def robot_files(arguments):
    """Every file given, and below every folder given: `.urdf`, `.xacro`, `.sdf`, and `.xml` files holding
    `<mujoco` or `<robot` (within their first 4000 characters), sorted."""
    for argument in arguments:
        path = pathlib.Path(argument)
        candidates = sorted(path.rglob("*")) if path.is_dir() else [path]
        for candidate in candidates:
            if not candidate.is_file():
                continue
            if candidate.suffix in (".urdf", ".xacro", ".sdf"):
                yield candidate
            elif candidate.suffix == ".xml":
                try:
                    head = candidate.read_text(errors="replace")[:4000]
                except OSError:
                    continue
                if "<mujoco" in head or "<robot" in head:
                    yield candidate


def json_report(binary, path):
    """`binary`'s JSON report of `path` (`--format json --no-write --no-config`), or `None` when it gives
    none; and the finished process (exit status, stderr)."""
    run = subprocess.run(
        [binary, str(path), "--format", "json", "--no-write", "--no-config"],
        capture_output=True,
        text=True,
        timeout=900,
    )
    try:
        return json.loads(run.stdout), run
    except json.JSONDecodeError:
        return None, run
