"""The task-query schema, with the spec's field names.

Plain dataclasses, as in the Python tool this package replaces: no extra dependency, and
``dataclasses.asdict`` gives the JSON the MCP server and ``run_pick_sweep`` exchange with Rust.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Union

Confidence = str  # "exact" | "estimated" | "missing"

#: ``"top_down"``, ``"side"``, ``[r, p, y]`` (radians) or ``[qw, qx, qy, qz]``.
TargetOrientation = Union[str, Sequence[float]]


@dataclass
class SubCheckResult:
    """One sub-check: ``reach``, ``reach_orientation``, ``payload_strength``,
    ``stability_during_reach`` or ``self_collision`` (``urdf_load``, ``request`` or
    ``terrain_gravity`` when those could not run)."""

    name: str
    status: str  # "PASS" | "FAIL" | "N/A" | "UNKNOWN"
    reason: str  # with the numbers
    bottleneck: Optional[str] = None  # the link, joint or link pair that limits the result
    confidence: Confidence = "estimated"


@dataclass
class TaskQueryRequest:
    """A pick: can the robot at ``urdf_path`` hold ``object_mass_kg`` at ``target_position`` (x, y, z
    metres in the robot's root frame) in ``target_orientation``?"""

    urdf_path: str
    task_type: str  # only "pick"
    target_position: Optional[List[float]] = None
    target_orientation: Optional[TargetOrientation] = None
    object_mass_kg: Optional[float] = None
    terrain_angle_deg: float = 0.0

    def to_dict(self) -> Dict[str, Any]:
        """The request as JSON-ready data."""
        orientation = self.target_orientation
        if orientation is not None and not isinstance(orientation, str):
            orientation = [float(v) for v in orientation]
        return {
            "urdf_path": str(self.urdf_path),
            "task_type": self.task_type,
            "target_position": None
            if self.target_position is None
            else [float(v) for v in self.target_position],
            "target_orientation": orientation,
            "object_mass_kg": self.object_mass_kg,
            "terrain_angle_deg": float(self.terrain_angle_deg),
        }


@dataclass
class TaskQueryResponse:
    """The answer: ``overall_status`` is FAIL when a sub-check fails, else UNKNOWN when one could not
    be assessed, else PASS."""

    task_type: str
    overall_status: str  # "PASS" | "FAIL" | "UNKNOWN"
    sub_checks: List[SubCheckResult] = field(default_factory=list)
    terrain_angle_deg: float = 0.0
    terrain_note: Optional[str] = None

    @classmethod
    def from_dict(cls, data: Dict[str, Any]) -> "TaskQueryResponse":
        """A response from its JSON form."""
        return cls(
            task_type=data["task_type"],
            overall_status=data["overall_status"],
            sub_checks=[SubCheckResult(**check) for check in data["sub_checks"]],
            terrain_angle_deg=data.get("terrain_angle_deg", 0.0),
            terrain_note=data.get("terrain_note"),
        )
