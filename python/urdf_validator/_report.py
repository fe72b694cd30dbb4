"""The report of one robot."""

from __future__ import annotations

import copy
import json
from typing import Any, Dict, List, Optional


class Report:
    """One robot's validation report: the JSON report file's content with typed attributes.

    ``to_dict()`` equals the ``<robot>_validation.json`` file the command writes (for a file that
    could not be validated: ``urdf_path``, ``overall_status`` ``UNKNOWN`` and ``error``). Reports
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
    def deep(self) -> Optional[Dict[str, Any]]:
        """The ``[DEEP]`` MuJoCo pass (``deep=True``, or by itself on a robot that tips over), if it ran."""
        return self._data.get("deep")
