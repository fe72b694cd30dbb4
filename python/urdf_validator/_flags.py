"""Keyword arguments to the command's flags."""

from __future__ import annotations

import os
from typing import Any, Dict, List


def flags_from_options(options: Dict[str, Any]) -> List[str]:
    """``{"robot_type": "wheeled", "no_cache": True, "package_path": ["a", "b"]}`` to
    ``["--robot-type=wheeled", "--no-cache", "--package-path=a", "--package-path=b"]``.

    ``None`` and ``False`` leave a flag out; an unknown name reaches the Rust side, which raises
    ``ValueError`` naming it.
    """
    flags: List[str] = []
    for name, value in options.items():
        flag = "--" + name.replace("_", "-")
        if value is None or value is False:
            continue
        # `--flag=value`, so a value starting with '-' (a negative number) is not read as a flag.
        if value is True:
            flags.append(flag)
        elif isinstance(value, (list, tuple)):
            flags += [f"{flag}={_text(item)}" for item in value]
        else:
            flags.append(f"{flag}={_text(value)}")
    return flags


def _text(value: Any) -> str:
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return str(value)
