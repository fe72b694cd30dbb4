"""Run task queries: the full physics pipeline in Rust, one response per request.

    from urdf_validator_main.api.task_runner import run_pick_task, run_pick_sweep
    from urdf_validator_main.api.task_schema import TaskQueryRequest

    resp = run_pick_task(TaskQueryRequest(urdf_path="fetch.urdf", task_type="pick",
                                          target_position=[0.5, 0.0, 0.8], object_mass_kg=0.5))
"""

from __future__ import annotations

import json
from typing import Any, List, Optional, Sequence

from urdf_validator import _native
from urdf_validator._options import options_json

from .task_schema import SubCheckResult, TaskQueryRequest, TaskQueryResponse

__all__ = ["run_pick_task", "run_pick_sweep", "SubCheckResult", "TaskQueryRequest", "TaskQueryResponse"]


def run_pick_task(
    request: TaskQueryRequest, n_samples: Optional[int] = None, **options: Any
) -> TaskQueryResponse:
    """Answer one request. ``n_samples``: workspace samples per arm (default 30,000); ``options``:
    the command's other flags (``package_path``, ``seed``, ...). Never raises for a bad robot file:
    that is an UNKNOWN ``urdf_load`` sub-check."""
    return run_pick_sweep([request], n_samples=n_samples, **options)[0]


def run_pick_sweep(
    requests: Sequence[TaskQueryRequest], n_samples: Optional[int] = None, **options: Any
) -> List[TaskQueryResponse]:
    """Answer every request, in parallel in Rust; the responses in the order of the requests. A
    request that cannot run (a missing file, a bad orientation) gets its own UNKNOWN response; the
    others still run."""
    settings = options_json({"samples": n_samples, **options})
    payload = json.dumps([request.to_dict() for request in requests])
    return [TaskQueryResponse.from_dict(data) for data in json.loads(_native.run_pick_sweep(payload, settings))]
