"""Keyword arguments to the options the Rust side takes: a JSON object keyed by the command's flags."""

from __future__ import annotations

import json
import os
from typing import Any, Dict


def options_json(options: Dict[str, Any]) -> str:
    """``{"robot_type": "wheeled", "no_cache": True, "package_path": [Path("a")]}`` as the JSON object
    ``{"robot_type": "wheeled", "no_cache": true, "package_path": ["a"]}``.

    ``None`` and ``False`` leave a flag out (the Rust side skips them); paths become text. An unknown
    name or a bad value reaches the Rust side, which raises ``ValueError`` naming the flag.
    """
    return json.dumps(options, default=_plain)


def _plain(value: Any) -> Any:
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, (set, frozenset)):
        return sorted(value, key=str)
    # Anything else (a NumPy number, an enum) as its text, as a flag value would be.
    return str(value)
