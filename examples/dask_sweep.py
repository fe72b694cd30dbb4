#!/usr/bin/env python3
"""Validate a folder of robots and run a task-query sweep on a Dask cluster.

    pip install urdf-validator "dask[distributed]"
    python examples/dask_sweep.py ROBOTS_DIR                         # a LocalCluster on this machine
    python examples/dask_sweep.py ROBOTS_DIR --scheduler tcp://scheduler:8786   # a real cluster

The unit of work is the Python API: one robot per task (``urdf_validator.validate``), and chunks of
task-query requests (``run_pick_sweep``, itself parallel in Rust on each worker). Reports and responses
pickle, so they come back to the client as objects. The same two functions run unchanged on Ray
(``ray.remote(validate_robot)``) or any executor that ships pickled calls.

Prints each robot's status, the sweep's verdict counts and the throughput (robots/s, requests/s);
``--json FILE`` also writes them as JSON.
"""

from __future__ import annotations

import argparse
import itertools
from dataclasses import asdict
import json
import sys
import time
from collections import Counter
from pathlib import Path
from typing import List

import urdf_validator
from urdf_validator_main.api.task_runner import run_pick_sweep
from urdf_validator_main.api.task_schema import TaskQueryRequest, TaskQueryResponse


def validate_robot(path: str, samples: int) -> urdf_validator.Report:
    """One robot (runs on a worker). ``validate_many`` rather than ``validate``: a file that cannot be
    read gives a report with ``error`` instead of an exception, so one bad file does not fail the job."""
    return urdf_validator.validate_many([path], samples=samples)[0]


def sweep_chunk(requests: List[TaskQueryRequest], samples: int) -> List[TaskQueryResponse]:
    """A chunk of task queries (runs on a worker; parallel in Rust there)."""
    return run_pick_sweep(requests, n_samples=samples)


def sweep_requests(robots: List[Path], count: int) -> List[TaskQueryRequest]:
    """``count`` pick requests: a grid of targets (distance, height, heading), payloads and orientations,
    over the robots in turn."""
    distances = [0.3, 0.5, 0.7, 0.9, 1.2]
    heights = [0.05, 0.4, 0.75, 1.0, 1.4]
    headings = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)]
    masses = [None, 0.5, 2.0, 10.0]
    orientations = [None, "top_down", "side"]
    grid = itertools.cycle(itertools.product(distances, heights, headings, masses, orientations))
    requests = []
    for index, (distance, height, (hx, hy), mass, orientation) in enumerate(itertools.islice(grid, count)):
        requests.append(
            TaskQueryRequest(
                urdf_path=str(robots[index % len(robots)]),
                task_type="pick",
                target_position=[distance * hx, distance * hy, height],
                target_orientation=orientation,
                object_mass_kg=mass,
            )
        )
    return requests


def main(argv: List[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("robots", type=Path, help="a folder: every *.urdf below it is validated")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster workers (default 2)")
    parser.add_argument("--requests", type=int, default=1000, help="task queries in the sweep (default 1000)")
    parser.add_argument("--sweep-robot", type=Path, action="append",
                        help="robot(s) the sweep asks about (default: the robots validated as PASS or WARN)")
    parser.add_argument("--samples", type=int, default=30_000, help="workspace samples per arm (default 30000)")
    parser.add_argument("--chunk", type=int, default=25, help="task queries per Dask task (default 25)")
    parser.add_argument("--json", type=Path, help="also write the results here")
    args = parser.parse_args(argv)

    from dask.distributed import Client, LocalCluster

    robots = sorted(args.robots.rglob("*.urdf"))
    if not robots:
        print(f"dask_sweep: no *.urdf under {args.robots}", file=sys.stderr)
        return 2
    if args.scheduler:
        client = Client(args.scheduler)
        cluster = None
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    try:
        started = time.perf_counter()
        futures = client.map(validate_robot, [str(p) for p in robots], samples=args.samples, pure=False)
        reports = client.gather(futures)
        robots_s = time.perf_counter() - started
        for path, report in zip(robots, reports):
            print(f"{report.overall_status:8} {path}" + (f"  ({report.error})" if report.error else ""))

        sweep_robots = args.sweep_robot or [p for p, r in zip(robots, reports) if r.overall_status in ("PASS", "WARN")]
        requests = sweep_requests(sweep_robots or robots, args.requests)
        chunks = [requests[i:i + args.chunk] for i in range(0, len(requests), args.chunk)]
        started = time.perf_counter()
        futures = client.map(sweep_chunk, chunks, samples=args.samples, pure=False)
        responses = [r for chunk in client.gather(futures) for r in chunk]
        sweep_s = time.perf_counter() - started
    finally:
        client.close()
        if cluster is not None:
            cluster.close()

    verdicts = Counter(r.overall_status for r in responses)
    summary = {
        "workers": args.workers if cluster is not None else args.scheduler,
        "robots": len(robots),
        "robot_status": dict(Counter(r.overall_status for r in reports)),
        "robots_seconds": round(robots_s, 3),
        "robots_per_second": round(len(robots) / robots_s, 2),
        "requests": len(responses),
        "request_status": dict(verdicts),
        "requests_seconds": round(sweep_s, 3),
        "requests_per_second": round(len(responses) / sweep_s, 2),
        "samples": args.samples,
    }
    print(f"{len(robots)} robots in {robots_s:.2f} s ({summary['robots_per_second']} robots/s); "
          f"{len(responses)} task queries in {sweep_s:.2f} s ({summary['requests_per_second']} requests/s): "
          + ", ".join(f"{k} {v}" for k, v in sorted(verdicts.items())))
    if args.json:
        args.json.write_text(json.dumps({"summary": summary,
                                         "reports": [r.to_dict() for r in reports],
                                         "responses": [asdict(r) for r in responses]}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
