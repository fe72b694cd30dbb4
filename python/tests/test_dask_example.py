"""examples/dask_sweep.py on a 2-worker Dask LocalCluster."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

from conftest import EXAMPLE, REPO


def test_the_dask_example_runs_on_two_workers(tmp_path: Path) -> None:
    robots = tmp_path / "robots"
    robots.mkdir()
    shutil.copy(EXAMPLE, robots / "mobile_manipulator.urdf")
    (robots / "broken.urdf").write_text("<robot name='broken'><link name='a'>")
    out = tmp_path / "out.json"
    done = subprocess.run(
        [sys.executable, str(REPO / "examples" / "dask_sweep.py"), str(robots), "--workers", "2",
         "--requests", "60", "--chunk", "10", "--samples", "1000", "--json", str(out)],
        capture_output=True, text=True, timeout=600,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    result = json.loads(out.read_text())
    summary = result["summary"]
    assert summary["robots"] == 2 and summary["requests"] == 60
    assert summary["robot_status"] == {"PASS": 1, "UNKNOWN": 1}
    assert sum(summary["request_status"].values()) == 60
    # The grid holds reachable and unreachable targets: both verdicts appear.
    assert summary["request_status"].get("PASS", 0) > 0 and summary["request_status"].get("FAIL", 0) > 0
    assert "requests/s" in done.stdout
