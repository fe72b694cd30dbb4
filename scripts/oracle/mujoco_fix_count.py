#!/usr/bin/env python3
"""How many of the robots MuJoCo refuses as written it compiles after `urdf_validate --fix --unsafe-fixes`.

For every robot file of the example-robot-data corpus and ../shared/robots (as a directory input finds
them), runs `urdf_validate FILE --deep` and reads the report's `deep.changes`: a change of
kind `refused` means MuJoCo would not load the file as written (the deep pass then loads it after a stated
adjustment). Each refused robot's package folder is copied to a temporary folder (same layout, so
`package://` and relative paths resolve as before), `--fix --unsafe-fixes` is run on the copy, and `--deep`
again tells whether MuJoCo now loads the file as written. The originals are never written.

    python3 scripts/oracle/mujoco_fix_count.py BIN [--markdown FILE]

BIN is the `urdf_validate` binary; URDF_VALIDATOR_CORPUS, URDF_VALIDATOR_SHARED_ROBOTS and
URDF_VALIDATOR_PYTHON (a Python with `mujoco`) are read as scripts/test.sh sets them. Prints one line per
refused robot and the totals; exits 1 when a run crashes (exit code > 2).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path


def deep_report(binary: str, path: Path) -> dict:
    """The JSON report of `path` with the deep pass."""
    run = subprocess.run(
        [binary, str(path), "--deep", "--format", "json", "--no-write", "--samples", "2000"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    if run.returncode > 2:
        raise RuntimeError(f"{path}: exit {run.returncode}: {run.stderr.strip()}")
    if not run.stdout.strip():
        raise RuntimeError(f"{path}: no report: {run.stderr.strip()}")
    return json.loads(run.stdout)


def refusals(report: dict) -> list[str]:
    """What MuJoCo refused in the file as written (empty: it loads it)."""
    deep = report.get("deep") or {}
    return [
        f"{c.get('element', '')} ({reason(c.get('message', ''))})"
        for c in deep.get("simulator_changes", [])
        if c.get("kind") == "refused"
    ]


def reason(message: str) -> str:
    """MuJoCo's refusal, in a few words."""
    if "A + B" in message:
        return "A + B < C"
    if "mjMINVAL" in message:
        return "moving body without mass or inertia"
    return message.split(";")[0]


def deep_ran(report: dict) -> bool:
    """Whether MuJoCo ran (it names its version)."""
    return bool((report.get("deep") or {}).get("simulator_version"))


def robots(binary: str, folder: Path) -> list[Path]:
    """The robot files `urdf_validate` finds in `folder` (as a directory input: macro libraries left out)."""
    run = subprocess.run(
        [binary, str(folder), "--format", "json", "--no-write", "--samples", "10"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    if run.returncode > 2 or not run.stdout.strip():
        raise RuntimeError(f"{folder}: exit {run.returncode}: {run.stderr.strip()}")
    return [Path(r["urdf_path"]) for r in json.loads(run.stdout)]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binary")
    parser.add_argument("--markdown", type=Path, help="also write the table as Markdown here")
    args = parser.parse_args()
    # (folder searched, folder copied for a fix: the package tree its files' paths resolve in)
    trees = []
    if corpus := os.environ.get("URDF_VALIDATOR_CORPUS"):
        # example-robot-data's package is the `example-robot-data` folder holding `robots/`.
        trees.append((Path(corpus), Path(corpus).parent))
    if shared := os.environ.get("URDF_VALIDATOR_SHARED_ROBOTS"):
        trees.append((Path(shared), None))
    files = []
    for folder, package in trees:
        for path in robots(args.binary, folder):
            # ../shared/robots: each robot's first folder below it holds its packages.
            tree = package or folder / path.relative_to(folder).parts[0]
            files.append((path, tree))
    if not files:
        print("mujoco_fix_count: no robots (set URDF_VALIDATOR_CORPUS / URDF_VALIDATOR_SHARED_ROBOTS)", file=sys.stderr)
        return 1
    rows = []
    loaded = refused = compiled_after = 0
    with tempfile.TemporaryDirectory() as tmp:
        for path, tree in files:
            report = deep_report(args.binary, path)
            if not deep_ran(report):
                continue
            why = refusals(report)
            if not why:
                loaded += 1
                continue
            refused += 1
            copy_root = Path(tmp) / f"{refused}"
            shutil.copytree(tree, copy_root / tree.name, symlinks=True)
            copy = copy_root / tree.name / path.relative_to(tree)
            fix = subprocess.run(
                [args.binary, str(copy), "--fix", "--unsafe-fixes", "--no-write", "--samples", "2000"],
                capture_output=True,
                text=True,
                timeout=600,
            )
            if fix.returncode > 2:
                raise RuntimeError(f"{copy}: --fix exit {fix.returncode}: {fix.stderr.strip()}")
            after = refusals(deep_report(args.binary, copy))
            compiled_after += not after
            rows.append((path.name, ", ".join(why), ", ".join(after) or "loads as written"))
            shutil.rmtree(copy_root)
    lines = [
        "| robot | MuJoCo refused as written | after `--fix --unsafe-fixes` |",
        "|---|---|---|",
        *(f"| {name} | {before} | {after} |" for name, before, after in rows),
        "",
        f"{loaded + refused} robots loaded by the deep pass; MuJoCo refused {refused} as written; "
        f"after --fix --unsafe-fixes it loads {compiled_after} of them as written.",
    ]
    print("\n".join(lines))
    if args.markdown:
        args.markdown.write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
