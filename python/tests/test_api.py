"""The Python API: validate, validate_many, validate_string, Report."""

from __future__ import annotations

import json
import pickle
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

import urdf_validator
from urdf_validator import Report


def test_validate_gives_the_report_the_command_writes(example: Path, tmp_path: Path) -> None:
    report = urdf_validator.validate(example, samples=2000, no_cache=True)
    assert isinstance(report, Report)
    assert report.overall_status == "PASS"
    assert report.exit_code == 0 and report.ok and report.error is None
    assert report.robot_type == "wheeled"
    assert report.statics is not None and report.statics["total_mass"] > 0
    assert report.workspace is not None and report.workspace["samples"] == 2000

    # The console command of the same wheel writes the same document (timestamps aside).
    done = subprocess.run(
        ["urdf_validate", str(example), "--samples", "2000", "--no-cache", "--output-dir", str(tmp_path)],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    written = json.loads((tmp_path / "mobile_manipulator_validation.json").read_text())
    ours = report.to_dict()
    for document in (written, ours):
        document.pop("timestamp")
    assert ours == written


def test_options_are_the_command_flags(example: Path) -> None:
    heavy = urdf_validator.validate(example, samples=1000, payload_mass=400.0, robot_type="wheeled")
    assert heavy.statics["payload_mass"] == 400.0
    assert heavy.overall_status == "FAIL"
    assert any(f["rule"] == "U701" for f in heavy.findings)
    with pytest.raises(ValueError, match="--sampels"):
        urdf_validator.validate(example, sampels=10)
    with pytest.raises(ValueError, match="--samples"):
        urdf_validator.validate(example, samples=0)


def test_validate_many_keeps_order_and_isolates_failures(example: Path, tmp_path: Path) -> None:
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='x'><link name='a'></robot>")
    missing = tmp_path / "missing.urdf"
    reports = urdf_validator.validate_many([example, missing, broken, example], samples=1000)
    assert [r.overall_status for r in reports] == ["PASS", "UNKNOWN", reports[2].overall_status, "PASS"]
    assert "missing.urdf" in (reports[1].error or "")
    assert reports[1].exit_code == 2
    assert reports[2].exit_code == 2
    assert reports[2].urdf_path.endswith("broken.urdf")


def test_validate_string_resolves_relative_paths_from_base_dir(example: Path) -> None:
    xml = example.read_text()
    report = urdf_validator.validate_string(xml, base_dir=example.parent, samples=1000)
    assert report.overall_status == "PASS"
    assert report.urdf_path.endswith("robot.urdf")
    bad = urdf_validator.validate_string("<robot name='r'><link name='a'/><link name='a'/></robot>")
    assert bad.overall_status == "FAIL"
    assert any(f["severity"] == "CRITICAL" for f in bad.findings)


def test_reports_pickle_and_serialise(example: Path) -> None:
    report = urdf_validator.validate(example, samples=500)
    again = pickle.loads(pickle.dumps(report))
    assert again == report and again.to_json() == report.to_json()
    assert json.loads(report.to_json()) == report.to_dict()
    copy = report.to_dict()
    copy["overall_status"] = "changed"
    assert report.overall_status == "PASS"


def test_the_gil_is_released_while_rust_works(example: Path) -> None:
    ticks = []
    stop = threading.Event()

    def count() -> None:
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    thread = threading.Thread(target=count)
    thread.start()
    try:
        started = time.perf_counter()
        urdf_validator.validate(example, samples=200_000)
        finished = time.perf_counter()
    finally:
        stop.set()
        thread.join()
    during = [t for t in ticks if started < t < finished]
    # A held GIL would leave the other thread no tick at all while Rust samples.
    assert finished - started > 0.05
    assert len(during) >= 5, (len(during), finished - started)


def test_python_dash_m_runs_the_command(example: Path) -> None:
    done = subprocess.run(
        [sys.executable, "-m", "urdf_validator", "--explain", "U701"], capture_output=True, text=True
    )
    assert done.returncode == 0 and "joint-undersized" in done.stdout
    listed = subprocess.run(["urdf_validate", "--list-rules"], capture_output=True, text=True)
    assert listed.returncode == 0 and listed.stdout.startswith("U0")
