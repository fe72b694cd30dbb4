"""The robot files below a path, as the comparison scripts (verdict-diff.py, report-identity.py) walk them."""

import pathlib


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
