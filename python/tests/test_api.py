"""The Python API: validate, validate_many, validate_string, Report."""

from __future__ import annotations

import json
import os
import pickle
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

import urdf_validator
from urdf_validator import Report, ValidationError

from conftest import shared_robot


def test_validate_gives_the_report_the_command_writes(example: Path, tmp_path: Path) -> None:
    report = urdf_validator.validate(example, samples=2000, no_cache=True)
    assert isinstance(report, Report)
    assert report.overall_status == "PASS"
    assert report.exit_code == 0 and report.ok and report.error is None
    assert report.robot_type == "wheeled"
    assert report.statics is not None and report.statics["total_mass"] > 0
    assert report.workspace is not None and report.workspace["samples"] == 2000
    assert report.symmetry is not None and report.symmetry["status"] == "PASS"
    assert all(j["effort_needed"] is not None for j in report.statics["joints"] if j["status"] != "N/A")

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


@pytest.mark.parametrize(
    "options, named",
    [
        ({"sampels": 10}, "--sampels"),
        ({"samples": 0}, "--samples"),
        ({"payload_mass": -3}, "--payload-mass -3"),
        ({"robot_type": "boat"}, "possible values: wheeled"),
        ({"orientation": "1,2,3,4,5"}, "got 5"),
    ],
)
def test_bad_options_raise_value_error_before_any_work(example: Path, options: dict, named: str) -> None:
    with pytest.raises(ValueError, match=named.replace("(", r"\(")):
        urdf_validator.validate(example, **options)


def test_unreadable_input_raises_validation_error(tmp_path: Path) -> None:
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='x'>\n  <link name='a'>\n</robot>\n")
    with pytest.raises(ValidationError) as caught:
        urdf_validator.validate(broken)
    error = caught.value
    assert error.file == str(broken) and error.line == 3 and error.column is not None
    assert "not well-formed XML" in error.message and str(broken) in str(error)
    with pytest.raises(ValidationError) as caught:
        urdf_validator.validate(tmp_path / "missing.urdf")
    assert caught.value.line is None and "missing.urdf" in str(caught.value)
    with pytest.raises(ValidationError):
        urdf_validator.validate_string("<robot name='r'><link name='a'>")
    # The exception pickles too (it crosses process boundaries with the reports).
    again = pickle.loads(pickle.dumps(error))
    assert (again.file, again.line, again.message) == (error.file, error.line, error.message)


def test_pr2_fails_on_its_shoulders() -> None:
    report = urdf_validator.validate(shared_robot("pr2/pr2_description/robots/pr2.urdf"), samples=2000)
    assert report.overall_status == "FAIL" and report.exit_code == 2
    undersized = {f["message"].split("'")[1] for f in report.findings if f["rule"] == "U701"}
    assert undersized == {"l_shoulder_lift_joint", "r_shoulder_lift_joint"}
    assert report.statics["weakest_joint_name"] in undersized


def test_a_baseline_hides_the_findings_it_holds(tmp_path: Path) -> None:
    pr2 = shared_robot("pr2/pr2_description/robots/pr2.urdf")
    baseline = tmp_path / "baseline.json"
    done = subprocess.run(
        ["urdf_validate", str(pr2), "--samples", "2000", "--no-write", "--quiet", "--write-baseline", str(baseline)],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    report = urdf_validator.validate(pr2, samples=2000, baseline=baseline)
    assert report.overall_status == "PASS" and report.exit_code == 0
    assert report.findings == []
    assert report.to_dict()["baseline"]["matched"] > 0
    with pytest.raises(ValueError, match="--write-baseline"):
        urdf_validator.validate(pr2, write_baseline=baseline)


def test_validate_many_keeps_order_and_isolates_failures(example: Path, tmp_path: Path) -> None:
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='x'><link name='a'></robot>")
    missing = tmp_path / "missing.urdf"
    reports = urdf_validator.validate_many([example, missing, broken, example], samples=1000)
    assert [r.overall_status for r in reports] == ["PASS", "UNKNOWN", "UNKNOWN", "PASS"]
    assert "missing.urdf" in (reports[1].error or "")
    assert reports[1].exit_code == 2
    assert reports[2].urdf_path.endswith("broken.urdf")
    assert reports[2].to_dict()["error_location"]["line"] == 1


@pytest.mark.parametrize("threads", ["1", "2", None])
def test_validate_many_over_robots_with_meshes_reports_each(threads: str | None) -> None:
    """More files with meshes than rayon has threads: each gets its report and the call returns well before
    the 60 s timeout (such a batch once waited for it and came back UNKNOWN). In a process of its own, as the
    thread count is fixed once per process (RAYON_NUM_THREADS 1, 2, or the machine's cores)."""
    robots = [
        shared_robot("pr2/pr2_description/robots/pr2.urdf"),
        shared_robot("fetch/fetch_description/robots/fetch.urdf"),
        shared_robot("franka_panda/franka_description/robots/frankie_arm_hand.urdf"),
        shared_robot("anymal/anymal_b_simple_description/urdf/anymal.urdf"),
        shared_robot("spot/spot_description/model.urdf"),
        shared_robot("turtlebot3/turtlebot3_description/urdf/turtlebot3_burger.urdf"),
    ]
    script = (
        "import json, sys, urdf_validator\n"
        "reports = urdf_validator.validate_many(sys.argv[1:], samples=1000)\n"
        "print(json.dumps([[r.urdf_path, r.overall_status, r.error] for r in reports]))\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "RAYON_NUM_THREADS"}
    if threads is not None:
        env["RAYON_NUM_THREADS"] = threads
    done = subprocess.run(
        [sys.executable, "-c", script, *map(str, robots)],
        env=env,
        capture_output=True,
        text=True,
        timeout=45,
        check=True,
    )
    reports = json.loads(done.stdout)
    assert [Path(path).name for path, _, _ in reports] == [p.name for p in robots]
    for path, status, error in reports:
        assert status in ("PASS", "WARN", "FAIL"), (path, error)
        assert error is None, (path, error)


def test_validate_string_resolves_relative_paths_from_base_dir(example: Path) -> None:
    xml = example.read_text()
    report = urdf_validator.validate_string(xml, base_dir=example.parent, samples=1000)
    assert report.overall_status == "PASS"
    assert report.urdf_path.endswith("robot.urdf")
    bad = urdf_validator.validate_string("<robot name='r'><link name='a'/><link name='a'/></robot>")
    assert bad.overall_status == "FAIL"
    assert any(f["severity"] == "CRITICAL" for f in bad.findings)


def test_sdf_files_and_sdf_text_give_the_same_report() -> None:
    from conftest import REPO

    sdf = REPO / "crates" / "urdf-validator" / "tests" / "data" / "sdf" / "nested_arm.sdf"
    from_file = urdf_validator.validate(sdf, samples=500)
    from_text = urdf_validator.validate_string(sdf.read_text(), base_dir=sdf.parent, name=sdf.name, samples=500)
    assert from_file.statics is not None and from_file.statics["joints"]
    assert from_text.statics["joints"] == from_file.statics["joints"]
    assert [f["rule"] for f in from_text.findings] == [f["rule"] for f in from_file.findings]


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
        # The work is sized to the machine: a fast one samples 200,000 poses in well under 0.1 s, too short a
        # window to count ticks in, so the sample count doubles until one call lasts at least 0.2 s.
        samples = 200_000
        while True:
            started = time.perf_counter()
            urdf_validator.validate(example, samples=samples)
            finished = time.perf_counter()
            if finished - started >= 0.2 or samples >= 25_600_000:
                break
            samples *= 2
    finally:
        stop.set()
        thread.join()
    during = [t for t in ticks if started < t < finished]
    # A held GIL would leave the other thread no tick at all while Rust samples.
    assert finished - started >= 0.2, (samples, finished - started)
    assert len(during) >= 20, (len(during), samples, finished - started)


def test_python_dash_m_runs_the_command(example: Path) -> None:
    done = subprocess.run(
        [sys.executable, "-m", "urdf_validator", "--explain", "U701"], capture_output=True, text=True
    )
    assert done.returncode == 0 and "joint-undersized" in done.stdout
    listed = subprocess.run(["urdf_validate", "--list-rules"], capture_output=True, text=True)
    assert listed.returncode == 0 and listed.stdout.startswith("U0")


def test_the_python_tools_console_commands_exist() -> None:
    done = subprocess.run(["urdf_validate_mcp", "--help"], capture_output=True, text=True)
    assert done.returncode == 0 and "mcp" in done.stdout, done.stdout + done.stderr


def test_a_xacro_error_points_at_the_xacro_line(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="${undefined_width}"/>\n'
        "</robot>\n"
    )
    with pytest.raises(ValidationError) as caught:
        urdf_validator.validate(robot)
    error = caught.value
    assert error.file == str(robot) and error.line == 2 and error.column is not None, vars(error)
    assert "undefined_width" in error.message and not error.message.startswith(str(robot))


def test_validate_string_is_untrusted_by_default(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    secret_env, secret_file = "CANARYENVpy5q", "CANARYFILEpy7w"
    monkeypatch.setenv("URDF_PY_CANARY", secret_env)
    (tmp_path / "outside").mkdir()
    (tmp_path / "outside" / "m.stl").write_text(f"solid {secret_file}\nendsolid\n")
    (tmp_path / "root").mkdir()
    xml = (
        "<robot name='r'><link name='a'><visual><geometry>"
        f"<mesh filename='file://{tmp_path}/outside/m.stl'/></geometry></visual></link></robot>"
    )
    report = urdf_validator.validate_string(xml, base_dir=tmp_path / "root", samples=100, no_cache=True)
    document = json.dumps(report.to_dict())
    assert secret_file not in document
    assert any(f["rule"] == "U013" for f in report.findings), document
    # Trusted on request: the command's default behaviour (the mesh is read).
    trusted = urdf_validator.validate_string(
        xml, base_dir=tmp_path / "root", untrusted=False, samples=100, no_cache=True
    )
    assert not any(f["rule"] == "U013" for f in trusted.findings)
    assert secret_env not in document
