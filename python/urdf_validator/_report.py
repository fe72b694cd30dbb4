"""The report of one robot."""

from __future__ import annotations

import copy
import json
from typing import Any, Dict, List, Optional


class ValidationError(Exception):
    """A file that could not be validated at all: unreadable, not well-formed XML, a xacro that does not
    expand. ``line`` and ``column`` are ``None`` when the error has no position."""

    def __init__(self, message: str, file: str, line: Optional[int], column: Optional[int], detail: str) -> None:
        super().__init__(message)
        self.file = file
        self.line = line
        self.column = column
        #: The error without its position.
        self.message = detail

    def __reduce__(self):  # type: ignore[no-untyped-def]
        return (ValidationError, (str(self), self.file, self.line, self.column, self.message))


class Report:
    """One robot's validation report: the JSON report file's content with typed attributes.

    ``to_dict()`` equals the ``<robot>_validation.json`` file the command writes (for a file that
    could not be validated, in ``validate_many``: ``urdf_path``, ``overall_status`` ``UNKNOWN``,
    ``error`` and ``error_location``). Reports
    pickle, so they cross process boundaries (multiprocessing, Dask, Ray).
    """

    __slots__ = ("_json", "_data")

    def __init__(self, document: Dict[str, Any]) -> None:
        self._data = document
        self._json = json.dumps(document, indent=2)

    @classmethod
    def _from_json(cls, text: str) -> "Report":
        report = cls.__new__(cls)
        report._json = text
        report._data = json.loads(text)
        return report

    def _raise_error(self) -> "Report":
        """This report, or ``ValidationError`` when it is the error document of an unreadable file."""
        if self.error is None:
            return self
        where = self._data.get("error_location") or {}
        raise ValidationError(
            self.error,
            where.get("file", self.urdf_path),
            where.get("line"),
            where.get("column"),
            where.get("message", self.error),
        )

    # Pickling keeps the JSON text, so a round trip gives the same document.
    def __getstate__(self) -> str:
        return self._json

    def __setstate__(self, state: str) -> None:
        self._json = state
        self._data = json.loads(state)

    def __repr__(self) -> str:
        return f"<Report {self.robot_name or self.urdf_path!r}: {self.overall_status}>"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Report) and self._data == other._data

    def to_dict(self) -> Dict[str, Any]:
        """The report as the JSON file holds it (a copy)."""
        return copy.deepcopy(self._data)

    def to_json(self) -> str:
        """The JSON text of the report file."""
        return self._json

    @property
    def ok(self) -> bool:
        """True when the command would exit 0 (PASS)."""
        return self.overall_status == "PASS"

    @property
    def exit_code(self) -> int:
        """The command's exit code for this report: 0 PASS, 1 WARN, 2 otherwise."""
        return {"PASS": 0, "WARN": 1}.get(self.overall_status, 2)

    @property
    def error(self) -> Optional[str]:
        """Why the file could not be validated, or ``None``."""
        return self._data.get("error")

    @property
    def urdf_path(self) -> str:
        """The file validated."""
        return self._data.get("urdf_path", "")

    @property
    def robot_name(self) -> Optional[str]:
        """The ``<robot name>``."""
        return self._data.get("robot_name")

    @property
    def overall_status(self) -> str:
        """``PASS``, ``WARN``, ``FAIL`` or ``UNKNOWN``."""
        return self._data["overall_status"]

    @property
    def confidence_level(self) -> Optional[str]:
        """``HIGH``, ``MEDIUM`` or ``LOW``."""
        return self._data.get("confidence_level")

    @property
    def robot_type(self) -> Optional[str]:
        """The robot category (``wheeled``, ``legged``, ``arm``, ...)."""
        return self._data.get("robot_type")

    @property
    def critical_issues(self) -> List[str]:
        """CRITICAL and FAIL messages."""
        return self._data.get("critical_issues", [])

    @property
    def warnings(self) -> List[str]:
        """WARN messages."""
        return self._data.get("warnings", [])

    @property
    def findings(self) -> List[Dict[str, Any]]:
        """Every finding: ``rule``, ``name``, ``severity``, ``section``, ``message``, ``file``,
        ``line``, ``column``, ``help``..."""
        return self._data.get("findings", [])

    @property
    def schema(self) -> Optional[Dict[str, Any]]:
        """The ``[SCHEMA]`` section."""
        return self._data.get("schema")

    @property
    def statics(self) -> Optional[Dict[str, Any]]:
        """The ``[STATICS]`` section (total mass, COM, per-joint gravity torques), if computed."""
        return self._data.get("statics")

    @property
    def stability(self) -> Optional[Dict[str, Any]]:
        """The ``[STABILITY]`` section, if computed."""
        return self._data.get("stability")

    @property
    def workspace(self) -> Optional[Dict[str, Any]]:
        """The ``[WORKSPACE]`` section, if computed."""
        return self._data.get("workspace")

    @property
    def symmetry(self) -> Optional[Dict[str, Any]]:
        """Mirrored left/right pairs and what differs between them (``pairs``, ``status``), if computed."""
        return self._data.get("symmetry")

    @property
    def deep(self) -> Optional[Dict[str, Any]]:
        """The ``[DEEP]`` MuJoCo pass (``deep=True``, or by itself on a robot that tips over), if it ran."""
        return self._data.get("deep")
