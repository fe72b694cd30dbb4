#!/usr/bin/env python3
"""The wide corpus (issue 42): urdf_validate on public robot descriptions nobody here wrote.

Every entry of manifest.json (beside this file) names a file in a public GitHub repository at a commit.
For each one this runs `urdf_validate --format json` (with the entry's xacro arguments and package
folders), records the exit code, the overall status, every CRITICAL / FAIL finding (rule and message),
refusals (exit 2 and no report), crashes (a signal, a panic, an exit code the CLI never gives) and hangs,
and the time; and, when Pinocchio (`pin`) or MuJoCo is importable, compares the report's total mass,
centre of mass and gravity torques with theirs at the report's configuration:

- URDF and xacro (the validator's own `--expand-only` output): `pinocchio.buildModelFromUrdf`, fixed
  base (the root link's frame is the world, as the report's root frame), mimic followers set to
  `multiplier * q_leader + offset` and their torque folded into the leader's (the report's convention);
  total mass and COM over every link with an `<inertial>` (Pinocchio's universe body holds the links
  welded to the root; `data.mass[0]` leaves them out, this does not).
- MJCF: MuJoCo at qpos0 moved by the report's configuration, `qfrc_bias` at zero velocity with gravity
  on, equality couplings as mimics (scripts/oracle/menagerie.py's `values_at`). A model whose mesh files
  the checkout lacks is compared on a stand-in written beside it (`<stem>.standin.xml`, those meshes and
  their geoms dropped, menagerie.py's `without_missing_meshes`), and the validator runs on the stand-in
  for that comparison.

The worst relative and absolute difference per file is reported (relative: |a - b| / max(|a|, |b|),
with floors of 1e-9 kg, 1e-9 m, 1e-6 N m below which a difference counts as none).

    python3 scripts/wide-corpus/run.py --fetch                   # clone + checkout every repository
    .venv-wc/bin/python scripts/wide-corpus/run.py \\
        --root target/wide-corpus --bin target/release/urdf_validate [--only ID|TEXT] [--out FILE]

Output: a summary table on stdout and a JSON results file (default target/wide-corpus-results.json).
Exit code 0 unless a run crashed or hung (1), or the binary / root is missing (2). Findings are the
corpus's business: they are listed, not failed on; TRIAGE.md judges them.

Dev-only tooling: stdlib, plus `pin` and `mujoco` when importable (PyPI: `pip install pin mujoco`).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
DEFAULT_ROOT = REPO / "target" / "wide-corpus"
DEFAULT_BIN = REPO / "target" / "release" / "urdf_validate"
DEFAULT_OUT = REPO / "target" / "wide-corpus-results.json"

MASS_FLOOR = 1e-9
POSITION_FLOOR = 1e-9
TORQUE_FLOOR = 1e-6
BAD_SEVERITIES = ("CRITICAL", "FAIL")

try:  # optional oracles
    import pinocchio as pin  # type: ignore
    import numpy as np  # type: ignore
except ImportError:  # pragma: no cover
    pin = None
try:
    import mujoco  # type: ignore

    sys.path.insert(0, str(REPO / "scripts" / "oracle"))
    import menagerie  # type: ignore  # noqa: E402  (values_at, without_missing_meshes)
except ImportError:  # pragma: no cover
    mujoco = None
    menagerie = None


# ------------------------------------------------------------------------------------------------ fetch
def fetch(manifest: dict, root: Path) -> int:
    """`git clone` + `git checkout <commit>` of every repository of the manifest into root/<owner>+<name>
    (a developer machine with network; the session that built this corpus used read-only snapshots)."""
    root.mkdir(parents=True, exist_ok=True)
    commits: dict[str, str] = dict(manifest.get("repositories") or {})
    for entry in manifest["entries"]:
        commits.setdefault(entry["repository"], entry["commit"])
    failed = 0
    for repo, commit in sorted(commits.items()):
        dest = root / repo.replace("/", "+")
        if not (dest / ".git").exists():
            if dest.exists() and any(dest.iterdir()):
                print(f"{repo}: {dest} exists and is not a clone; left alone")
                continue
            run = subprocess.run(["git", "clone", "--filter=blob:none", "--no-checkout",
                                  f"https://github.com/{repo}.git", str(dest)])
            if run.returncode != 0:
                failed += 1
                continue
        run = subprocess.run(["git", "-C", str(dest), "checkout", "--quiet", commit])
        if run.returncode != 0:
            subprocess.run(["git", "-C", str(dest), "fetch", "--quiet", "origin", commit])
            run = subprocess.run(["git", "-C", str(dest), "checkout", "--quiet", commit])
        failed += run.returncode != 0
        print(f"{repo} @ {commit[:12]}: {'ok' if run.returncode == 0 else 'FAILED'}")
    return 1 if failed else 0


# ------------------------------------------------------------------------------------------------ runs
def entry_file(entry: dict, root: Path) -> Path:
    return root / entry["repository"].replace("/", "+") / entry["path"]


def package_args(entry: dict, root: Path, links: Path) -> list[str]:
    """--package-path for the entry's folders (relative to its repository, or `owner/name:folder` in
    another repository of the manifest), and for `packages` (name -> folder of the repository that is
    that package but is not named after it, e.g. a repository root) a folder of symbolic links."""
    repo_dir = root / entry["repository"].replace("/", "+")
    args: list[str] = []
    for sub in entry.get("package_path") or []:
        if ":" in sub:
            other, sub = sub.split(":", 1)
            base = root / other.replace("/", "+")
        else:
            base = repo_dir
        args += ["--package-path", str((base / sub).resolve())]
    packages = entry.get("packages") or {}
    if packages:
        folder = links / entry["id"]
        folder.mkdir(parents=True, exist_ok=True)
        for name, sub in packages.items():
            link = folder / name
            if not link.exists():
                link.symlink_to((repo_dir / sub).resolve(), target_is_directory=True)
        args += ["--package-path", str(folder)]
    return args


EXTRA: list[str] = []
"""Further validator options for every run (`--extra=--deep`)."""


def command(binary: Path, entry: dict, file: Path, root: Path, links: Path, out_dir: Path) -> list[str]:
    cmd = [str(binary), "--format", "json", "--output-dir", str(out_dir), "--color", "never", *EXTRA]
    cmd += package_args(entry, root, links)
    for name, value in (entry.get("xacro_args") or {}).items():
        cmd += ["--xacro-arg", f"{name}:={value}"]
    return cmd + ["--", str(file)]


def validate(cmd: list[str], out_dir: Path, timeout: float, env: dict) -> dict:
    start = time.monotonic()
    for old in out_dir.glob("*_validation.json"):
        old.unlink()
    try:
        run = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return {"code": None, "seconds": round(time.monotonic() - start, 3), "report": None,
                "stderr": "", "hang": True}
    seconds = time.monotonic() - start
    reports = sorted(out_dir.glob("*_validation.json"))
    report = None
    if reports:
        try:
            report = json.loads(reports[0].read_text())
        except (json.JSONDecodeError, OSError):
            report = None
    return {"code": run.returncode, "seconds": round(seconds, 3), "report": report,
            "stderr": run.stderr, "stdout_head": run.stdout[:2000] if report is None else "", "hang": False}


def crashed(run: dict) -> str | None:
    if run["hang"]:
        return "hang"
    code = run["code"]
    if code < 0:
        return f"killed by signal {-code}"
    if "panicked" in run["stderr"]:
        return "panic: " + run["stderr"].strip().splitlines()[-1][:300]
    if code not in (0, 1, 2):
        return f"exit code {code}"
    return None


# ------------------------------------------------------------------------------------------------ oracles
def rel_abs(ours: float, theirs: float, floor: float) -> tuple[float, float]:
    diff = abs(ours - theirs)
    if diff <= floor:
        return 0.0, diff
    return diff / max(abs(ours), abs(theirs)), diff


class Worst:
    """The worst difference per quantity: relative and absolute, and where."""

    def __init__(self) -> None:
        self.items: dict[str, dict] = {}

    def add(self, kind: str, what: str, ours, theirs, floor: float) -> None:
        if ours is None or theirs is None:
            self.items.setdefault(f"{kind}_missing", {"what": what, "ours": ours, "theirs": theirs})
            return
        rel, ab = rel_abs(float(ours), float(theirs), floor)
        cur = self.items.get(kind)
        if cur is None or rel > cur["rel"] or (rel == cur["rel"] and ab > cur["abs"]):
            self.items[kind] = {"what": what, "ours": ours, "theirs": theirs, "rel": rel, "abs": ab}

    def worst_rel(self) -> float:
        return max((v.get("rel", 0.0) for v in self.items.values()), default=0.0)


def read_urdf_joints(root: ET.Element) -> dict[str, dict]:
    joints = {}
    for joint in root.findall("joint"):
        mimic = joint.find("mimic")
        info = {"type": joint.get("type"), "mimic": None}
        if mimic is not None and mimic.get("joint"):
            info["mimic"] = (mimic.get("joint"), float(mimic.get("multiplier", "1") or 1),
                             float(mimic.get("offset", "0") or 0))
        joints[joint.get("name")] = info
    return joints


def pinocchio_compare(urdf_text: str, report: dict) -> dict:
    """Pinocchio's total mass, COM and gravity torques at the report's configuration against the report."""
    statics = report.get("statics") or {}
    config = statics.get("configuration") or {}
    with tempfile.NamedTemporaryFile("w", suffix=".urdf", delete=False) as tmp:
        tmp.write(urdf_text)
    try:
        model = pin.buildModelFromUrdf(tmp.name)
    finally:
        os.unlink(tmp.name)
    data = model.createData()
    joints = read_urdf_joints(ET.fromstring(urdf_text))
    actuated = {n for n, j in joints.items() if j["type"] in ("revolute", "continuous", "prismatic")}

    def value(name: str, depth: int = 0) -> float:
        if name in config:
            return float(config[name])
        j = joints.get(name)
        if j and j["mimic"] and j["mimic"][0] in actuated and depth < 32:
            leader, mult, off = j["mimic"]
            return mult * value(leader, depth + 1) + off
        return 0.0

    q = pin.neutral(model)
    held = []
    for jid in range(1, model.njoints):
        jm = model.joints[jid]
        name = model.names[jid]
        if jm.nq == 1:
            q[jm.idx_q] = value(name)
        elif jm.nq == 2 and jm.nv == 1:
            q[jm.idx_q], q[jm.idx_q + 1] = math.cos(value(name)), math.sin(value(name))
        else:
            held.append(name)
    tau = pin.computeGeneralizedGravity(model, data, q)
    moving_mass = 0.0
    moving_com = np.zeros(3)
    if model.njoints > 1:
        moving_com = np.array(pin.centerOfMass(model, data, q))
        moving_mass = float(data.mass[0])
    if moving_mass <= 0.0:
        moving_mass, moving_com = 0.0, np.zeros(3)
    welded = model.inertias[0]
    total = moving_mass + float(welded.mass)
    com = None
    if total > 0:
        com = (moving_mass * moving_com + float(welded.mass) * np.array(welded.lever)) / total
    forces = {}
    for jid in range(1, model.njoints):
        jm = model.joints[jid]
        if jm.nv == 1:
            forces[model.names[jid]] = float(tau[jm.idx_v])
    # Fold followers into their first leader (own torque kept by the follower), as the report does.
    folded = dict(forces)
    for name, force in forces.items():
        at, factor, steps = name, 1.0, 0
        while joints.get(at, {}).get("mimic") and joints[at]["mimic"][0] in forces and steps < 32:
            leader, mult, _ = joints[at]["mimic"]
            at, factor, steps = leader, factor * mult, steps + 1
        if at != name:
            folded[at] += factor * force
    w = Worst()
    w.add("mass", "total mass", statics.get("total_mass"), total, MASS_FLOOR)
    ours_com = statics.get("full_body_com")
    if com is not None and total > MASS_FLOOR:
        for i, axis in enumerate("xyz"):
            w.add("com", f"COM {axis}", None if ours_com is None else ours_com[i], float(com[i]), POSITION_FLOOR)
    ours = {j["name"]: j.get("required_torque_gravity") for j in statics.get("joints") or []}
    for name, force in folded.items():
        w.add("torque", f"joint {name}", ours.get(name), force, TORQUE_FLOOR)
    return {"oracle": f"pinocchio {pin.__version__}", "worst": w.items, "worst_rel": w.worst_rel(),
            "joints": len(folded), "held_at_neutral": held}


def mujoco_compare(path: Path, report: dict) -> dict:
    statics = report.get("statics") or {}
    config = statics.get("configuration") or {}
    model = mujoco.MjModel.from_xml_path(str(path))
    theirs = menagerie.values_at(model, config)
    w = Worst()
    w.add("mass", "total mass", statics.get("total_mass"), theirs["mass"], MASS_FLOOR)
    ours_com = statics.get("full_body_com")
    if theirs["mass"] > MASS_FLOOR:
        for i, axis in enumerate("xyz"):
            w.add("com", f"COM {axis}", None if ours_com is None else ours_com[i], theirs["com"][i], POSITION_FLOOR)
    ours = {j["name"]: j.get("required_torque_gravity") for j in statics.get("joints") or []}
    for name, force in theirs["forces"].items():
        w.add("torque", f"joint {name}", ours.get(name), force, TORQUE_FLOOR)
    return {"oracle": f"mujoco {mujoco.__version__}", "worst": w.items, "worst_rel": w.worst_rel(),
            "joints": len(theirs["forces"]), "unnamed_joints": theirs["unnamed"]}


def mjcf_stand_in(path: Path) -> Path | None:
    """A copy of the model beside it without the meshes whose files are absent (None: nothing absent)."""
    text = path.read_text()
    root = ET.fromstring(text)
    compiler = root.find("compiler")
    meshdir = compiler.get("meshdir", compiler.get("assetdir", "")) if compiler is not None else ""

    def missing(file: str, meshdir: str) -> bool:
        return not ((path.parent / meshdir / file).is_file() or (path.parent / file).is_file())

    variant = menagerie.without_missing_meshes(text, missing)
    if variant is None:
        return None
    stand = path.with_name(path.stem + ".standin.xml")
    stand.write_text(variant[0])
    return stand


def oracle(entry: dict, file: Path, report: dict, expanded: str | None, cmd_for, out_dir: Path,
           timeout: float, env: dict) -> dict | None:
    if not (report.get("statics") or {}).get("joints") and (report.get("statics") or {}).get("total_mass") is None:
        return {"skipped": "no statics in the report"}
    try:
        if entry["format"] in ("urdf", "xacro"):
            if pin is None:
                return None
            text = expanded if expanded is not None else file.read_text()
            return pinocchio_compare(text, report)
        if entry["format"] == "mjcf":
            if mujoco is None:
                return None
            try:
                return mujoco_compare(file, report)
            except (ValueError, mujoco.FatalError) as error:
                first = str(error).splitlines()[0]
                stand = mjcf_stand_in(file)
                if stand is None:
                    return {"error": f"MuJoCo does not compile the file: {first}"}
                run = validate(cmd_for(stand), out_dir, timeout, env)
                if run["report"] is None:
                    return {"error": f"no report on the stand-in (exit {run['code']})"}
                try:
                    result = mujoco_compare(stand, run["report"])
                except (ValueError, mujoco.FatalError) as error2:
                    return {"error": f"MuJoCo does not compile the stand-in: {str(error2).splitlines()[0]}"}
                result["stand_in"] = f"meshes the checkout lacks dropped ({first})"
                return result
    except Exception as error:  # an oracle failure is data, not a crash of this script
        return {"error": f"{type(error).__name__}: {str(error).splitlines()[0] if str(error) else ''}"}
    return None


# ------------------------------------------------------------------------------------------------ main
def summarise_findings(report: dict) -> tuple[list[dict], dict]:
    bad, counts = [], {}
    for f in report.get("findings") or []:
        counts[f["severity"]] = counts.get(f["severity"], 0) + 1
        if f["severity"] in BAD_SEVERITIES:
            bad.append({"rule": f["rule"], "severity": f["severity"], "section": f.get("section"),
                        "message": f["message"], "line": f.get("line"), "file": f.get("file")})
    return bad, counts


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--manifest", type=Path, default=HERE / "manifest.json")
    parser.add_argument("--root", type=Path, default=DEFAULT_ROOT, help="checkouts as <owner>+<name>/")
    parser.add_argument("--bin", type=Path, default=DEFAULT_BIN, help="urdf_validate binary")
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT, help="JSON results file")
    parser.add_argument("--only", action="append", help="entry id or a substring of its path (repeatable)")
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds before a run counts as a hang")
    parser.add_argument("--python", default=str(REPO / ".venv" / "bin" / "python"),
                        help="URDF_VALIDATOR_PYTHON for the automatic MuJoCo pass ('' leaves it unset)")
    parser.add_argument("--no-oracle", action="store_true")
    parser.add_argument("--extra", action="append", default=[],
                        help="a further validator option for every run, e.g. --extra=--deep (repeatable)")
    parser.add_argument("--fetch", action="store_true", help="git clone + checkout every repository, then stop")
    args = parser.parse_args()
    EXTRA.extend(args.extra)
    manifest = json.loads(args.manifest.read_text())
    root = args.root.resolve()
    if args.fetch:
        return fetch(manifest, root)
    if not args.bin.is_file():
        print(f"run.py: no binary at {args.bin}", file=sys.stderr)
        return 2
    if not root.is_dir():
        print(f"run.py: no checkout folder {root} (run with --fetch)", file=sys.stderr)
        return 2
    env = dict(os.environ)
    if args.python and Path(args.python).exists():
        env["URDF_VALIDATOR_PYTHON"] = args.python
    entries = manifest["entries"]
    if args.only:
        entries = [e for e in entries if any(o == e["id"] or o in e["path"] or o in e["repository"] for o in args.only)]
    results = []
    failures = 0
    work = Path(tempfile.mkdtemp(prefix="wide-corpus-"))
    links, out_dir = work / "packages", work / "out"
    out_dir.mkdir(parents=True)
    print(f"{'id':>3} {'kind':9} {'fmt':5} {'exit':>4} {'status':7} {'sec':>6} {'C/F':>3} {'oracle':>9}  file")
    for entry in entries:
        file = entry_file(entry, root)
        result = {"id": entry["id"], "repository": entry["repository"], "path": entry["path"],
                  "format": entry["format"], "kind": entry["kind"]}
        if not file.is_file():
            result["error"] = "file not checked out"
            results.append(result)
            print(f"{entry['id']:>3} {entry['kind']:9} {entry['format']:5} {'-':>4} {'MISSING':7}")
            continue
        cmd_for = lambda f, e=entry: command(args.bin, e, f, root, links, out_dir)  # noqa: E731
        run = validate(cmd_for(file), out_dir, args.timeout, env)
        crash = crashed(run)
        report = run["report"]
        result.update({"exit_code": run["code"], "seconds": run["seconds"], "crash": crash,
                       "refused": run["code"] == 2 and report is None and not crash})
        if crash:
            failures += 1
        if report is None:
            result["stderr"] = run["stderr"].strip()[-1500:]
            result["stdout_head"] = run.get("stdout_head", "")
        else:
            bad, counts = summarise_findings(report)
            result.update({"overall_status": report.get("overall_status"), "robot_type": report.get("robot_type"),
                           "severity_counts": counts, "bad_findings": bad,
                           "warn_rules": sorted({f["rule"] for f in report.get("findings") or [] if f["severity"] == "WARN"}),
                           "total_mass": (report.get("statics") or {}).get("total_mass")})
            if not args.no_oracle:
                expanded = None
                if entry["format"] == "xacro":
                    xcmd = [str(args.bin), "--expand-only"] + package_args(entry, root, links)
                    for n, v in (entry.get("xacro_args") or {}).items():
                        xcmd += ["--xacro-arg", f"{n}:={v}"]
                    exp = subprocess.run(xcmd + ["--", str(file)], capture_output=True, text=True, timeout=120, env=env)
                    expanded = exp.stdout if exp.returncode == 0 and exp.stdout.strip() else None
                result["oracle"] = oracle(entry, file, report, expanded, cmd_for, out_dir, args.timeout, env)
        results.append(result)
        o = result.get("oracle") or {}
        otext = "-" if not o else (f"{o['worst_rel']:.1e}" if "worst_rel" in o else ("err" if "error" in o else "skip"))
        status = report.get("overall_status") if report else ("CRASH" if crash else "REFUSED" if result["refused"] else "noreport")
        print(f"{entry['id']:>3} {entry['kind']:9} {entry['format']:5} {str(run['code']):>4} {status:7} "
              f"{run['seconds']:6.2f} {len(result.get('bad_findings') or []):>3} {otext:>9}  "
              f"{entry['repository'].split('/')[-1]}/{entry['path']}", flush=True)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    summary = {
        "files": len(results),
        "crashes": sum(1 for r in results if r.get("crash")),
        "refusals": sum(1 for r in results if r.get("refused")),
        "critical_or_fail_findings": sum(len(r.get("bad_findings") or []) for r in results),
        "files_with_critical_or_fail": sum(1 for r in results if r.get("bad_findings")),
        "exit_codes": {str(c): sum(1 for r in results if r.get("exit_code") == c) for c in (0, 1, 2)},
        "oracle_compared": sum(1 for r in results if (r.get("oracle") or {}).get("worst_rel") is not None),
        "oracle_worst_rel": max(((r.get("oracle") or {}).get("worst_rel", 0.0) for r in results), default=0.0),
    }
    summary["oracle_worst_abs"] = max((v.get("abs", 0.0) for r in results
                                       for v in ((r.get("oracle") or {}).get("worst") or {}).values()), default=0.0)
    worst = max(results, key=lambda r: (r.get("oracle") or {}).get("worst_rel", -1.0), default=None)
    if worst and (worst.get("oracle") or {}).get("worst_rel") is not None:
        summary["oracle_worst_file"] = f"{worst['repository']}/{worst['path']}"
    args.out.write_text(json.dumps({"summary": summary, "results": results}, indent=1) + "\n")
    print()
    print(json.dumps(summary, indent=1))
    print(f"results: {args.out}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
