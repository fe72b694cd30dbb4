"""Physics-aware validation of URDF and xacro robot descriptions, from Python.

The work is done by the same Rust library as the ``urdf_validate`` command, with the Python GIL
released, so other Python threads keep running::

    import urdf_validator

    report = urdf_validator.validate("robot.urdf", payload_mass=0.5, samples=10_000)
    print(report.overall_status)          # "PASS" | "WARN" | "FAIL" | "UNKNOWN"
    for finding in report.findings:
        print(finding["rule"], finding["severity"], finding["message"])

Keyword arguments are the command's long flags with ``_`` for ``-`` (``robot_type="wheeled"`` is
``--robot-type wheeled``; ``True`` gives a bare flag; a list repeats the flag; ``None`` and ``False``
leave it out). Configuration files
(``urdf-validate.toml``, ``[tool.urdf-validate]`` in ``pyproject.toml``) apply as they do for the
command; ``no_config=True`` turns them off.
"""

from __future__ import annotations

import os
from typing import Any, Iterable, List, Optional, Sequence, Union

from . import _native
from ._options import options_json
from ._report import Report, ValidationError

__all__ = ["Report", "ValidationError", "validate", "validate_many", "validate_string", "__version__"]

__version__: str = _native.__version__

PathLike = Union[str, "os.PathLike[str]"]


def validate(path: PathLike, **options: Any) -> Report:
    """Validate the URDF or xacro file at ``path``; ``options`` are the command's flags.

    Raises ``ValidationError`` (``file``, ``line``, ``column``, ``message``) when the file cannot be
    read (missing, not XML, a xacro that does not expand) and ``ValueError`` naming a bad option before
    any work starts; every problem of a readable file is in the report.
    """
    return Report._from_json(_native.validate(os.fspath(path), options_json(options)))._raise_error()


def validate_many(paths: Iterable[PathLike], **options: Any) -> List[Report]:
    """Validate every file, in parallel in Rust; one report per path, in the order given.

    A file that cannot be read gives its own report with ``error`` (``overall_status`` ``UNKNOWN``)
    instead of an exception, so the others are never lost.
    """
    documents = _native.validate_many([os.fspath(p) for p in paths], options_json(options))
    return [Report._from_json(document) for document in documents]


def validate_string(
    xml: str,
    base_dir: Optional[PathLike] = None,
    name: str = "robot.urdf",
    untrusted: bool = True,
    **options: Any,
) -> Report:
    """Validate URDF text. ``base_dir`` is where relative mesh paths (and configuration files) are
    looked up, default the current directory; ``name`` is the file name the report uses. Raises
    ``ValidationError`` for text that is not well-formed XML.

    Untrusted by default (text often comes from a request; see SECURITY.md): files are read only from
    ``base_dir`` when given and the ``root=[...]`` folders, only regular files, and no environment
    variable unless ``allow_env=[...]`` names it; what the text asked for and was refused is a U013
    finding. ``untrusted=False`` validates as the command does by default."""
    path = os.path.join(os.fspath(base_dir) if base_dir is not None else os.getcwd(), name)
    if untrusted:
        roots = list(options.pop("root", None) or [])
        if base_dir is not None:
            roots.append(base_dir)
        options = {"untrusted": True, "root": roots, **options}
    return Report._from_json(_native.validate_string(xml, path, options_json(options)))._raise_error()
