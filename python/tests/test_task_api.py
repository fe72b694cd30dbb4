"""The spec's task-query API, verbatim imports and field names."""

from __future__ import annotations

from pathlib import Path

from urdf_validator_main.api.task_runner import run_pick_sweep, run_pick_task
from urdf_validator_main.api.task_schema import SubCheckResult, TaskQueryRequest, TaskQueryResponse

from conftest import shared_robot

SUB_CHECKS = ["reach", "reach_orientation", "payload_strength", "stability_during_reach", "self_collision"]


def test_the_spec_snippet_runs(example: Path) -> None:
    req = TaskQueryRequest(
        urdf_path=str(example),
        task_type="pick",
        target_position=[0.5, 0.0, 0.8],
        target_orientation="top_down",
        object_mass_kg=0.5,
        terrain_angle_deg=0.0,
    )
    resp = run_pick_task(req, n_samples=3000)
    assert isinstance(resp, TaskQueryResponse)
    assert resp.overall_status in ("PASS", "FAIL", "UNKNOWN")
    assert [c.name for c in resp.sub_checks] == SUB_CHECKS
    for check in resp.sub_checks:
        assert isinstance(check, SubCheckResult)
        assert check.status in ("PASS", "FAIL", "N/A", "UNKNOWN") and check.reason
    assert resp.overall_status == "PASS", resp


def test_orientations_in_every_spec_form(example: Path) -> None:
    forms = ["top_down", "side", [0.0, 3.14159, 0.0], [0.0, 1.0, 0.0, 0.0]]
    requests = [
        TaskQueryRequest(str(example), "pick", target_position=[0.5, 0.0, 0.75], target_orientation=form)
        for form in forms
    ]
    for response in run_pick_sweep(requests, n_samples=2000):
        orientation = response.sub_checks[1]
        assert orientation.name == "reach_orientation"
        assert orientation.status in ("PASS", "FAIL"), orientation


def test_a_sweep_preserves_order_and_isolates_failures(example: Path, tmp_path: Path) -> None:
    requests = [
        TaskQueryRequest(str(example), "pick", target_position=[0.5, 0.0, 0.75]),
        TaskQueryRequest(str(tmp_path / "missing.urdf"), "pick", target_position=[0.5, 0.0, 0.75]),
        TaskQueryRequest(str(example), "pick", target_position=[4.0, 0.0, 0.75]),
        TaskQueryRequest(str(example), "pick", target_position=[0.5, 0.0, 0.75], target_orientation=[1.0]),
    ]
    responses = run_pick_sweep(requests, n_samples=2000)
    assert [r.overall_status for r in responses] == ["PASS", "UNKNOWN", "FAIL", "UNKNOWN"]
    assert responses[1].sub_checks[0].name == "urdf_load"
    assert "missing.urdf" in responses[1].sub_checks[0].reason
    reach = responses[2].sub_checks[0]
    assert reach.name == "reach" and reach.status == "FAIL" and "deficit" in reach.reason
    assert "1 numbers" in responses[3].sub_checks[0].reason


def test_payload_strength_names_the_bottleneck(example: Path) -> None:
    resp = run_pick_task(
        TaskQueryRequest(str(example), "pick", target_position=[0.5, 0.0, 0.75], object_mass_kg=300.0),
        n_samples=2000,
    )
    payload = resp.sub_checks[2]
    assert payload.name == "payload_strength" and payload.status == "FAIL"
    assert payload.bottleneck
    assert resp.overall_status == "FAIL"


def test_the_spec_snippet_verbatim_on_fetch(monkeypatch, capsys) -> None:
    fetch = shared_robot("fetch/fetch_description/robots/fetch.urdf")
    monkeypatch.chdir(fetch.parent)
    # From ../shared/spec/seed-README.md, "Task-query API", unchanged:
    from urdf_validator_main.api.task_runner import run_pick_task, run_pick_sweep
    from urdf_validator_main.api.task_schema import TaskQueryRequest

    req = TaskQueryRequest(
        urdf_path="fetch.urdf",
        task_type="pick",
        target_position=[0.5, 0.0, 0.8],    # [x, y, z] metres, robot frame
        target_orientation="top_down",        # or "side", [r,p,y], [qw,qx,qy,qz]
        object_mass_kg=0.5,
        terrain_angle_deg=0.0,
    )
    resp = run_pick_task(req)
    print(resp.overall_status)               # "PASS" | "FAIL" | "UNKNOWN"
    for check in resp.sub_checks:
        print(check.name, check.status, check.reason)
    # (end of the snippet)
    printed = capsys.readouterr().out.splitlines()
    assert printed[0] in ("PASS", "FAIL", "UNKNOWN")
    assert [line.split()[0] for line in printed[1:]] == SUB_CHECKS
    names = {c.name: c for c in resp.sub_checks}
    assert names["reach"].status == "PASS", names["reach"]
    assert names["payload_strength"].status in ("PASS", "FAIL", "UNKNOWN")
