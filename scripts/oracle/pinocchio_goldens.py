#!/usr/bin/env python3
"""Golden statics values from Pinocchio for the urdf-validator statics tests.

For every .urdf under the corpus (recursively, sorted) this loads a FIXED-base Pinocchio model
(`pinocchio.buildModelFromUrdf(path)`, no root joint, default gravity (0, 0, -9.81), mimic joints
as ordinary joints), evaluates the zero pose plus N seeded random configurations and writes one
JSON file per URDF with gravity torques, link-frame world positions and centres of mass.
See scripts/oracle/README.md for the field meanings and how to regenerate.

    python scripts/oracle/pinocchio_goldens.py [--corpus DIR] [--out DIR] [--configs 10] [--seed 7]

Dev-only tooling: needs `pin` (Pinocchio) and `example-robot-data`, never a runtime dependency.
"""

from __future__ import annotations

import argparse
import glob
import importlib.metadata
import json
import math
import os
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin

REPO_ROOT = Path(__file__).resolve().parents[2]
DEFAULT_OUT = REPO_ROOT / "crates" / "urdf-validator" / "tests" / "golden" / "pinocchio"
CORPUS_SUBDIR = "cmeel.prefix/share/example-robot-data/robots"

ACTUATED = ("revolute", "continuous", "prismatic")
# link_positions are stored for the zero pose and the first LINK_POSITION_RANDOM_CONFIGS random ones.
LINK_POSITION_RANDOM_CONFIGS = 2
# Robots for the frame-composition self-check (their max discrepancy is printed by name).
SELF_CHECK_ROBOTS = ("ur5_robot", "panda", "talos_reduced")


# --------------------------------------------------------------------------------------------------
# Corpus discovery
# --------------------------------------------------------------------------------------------------
def default_corpus() -> Path:
    """The example-robot-data robots folder of the Python environment this script runs in."""
    try:
        dist = importlib.metadata.distribution("example-robot-data")
        candidate = Path(dist.locate_file(CORPUS_SUBDIR))
        if candidate.is_dir():
            return candidate
    except importlib.metadata.PackageNotFoundError:
        pass
    for site in glob.glob(os.path.join(sys.prefix, "lib", "python3*", "site-packages")):
        candidate = Path(site) / CORPUS_SUBDIR
        if candidate.is_dir():
            return candidate
    sys.exit(
        "pinocchio_goldens: cannot find the example-robot-data corpus in this environment; "
        "install example-robot-data==6.0.0 or pass --corpus DIR"
    )


# --------------------------------------------------------------------------------------------------
# URDF reading (independent of Pinocchio)
# --------------------------------------------------------------------------------------------------
def _floats(text: str | None, n: int) -> list[float]:
    if text is None:
        return [0.0] * n
    vals = [float(t) for t in text.split()]
    if len(vals) != n:
        raise ValueError(f"expected {n} numbers, got {text!r}")
    return vals


def _opt_float(text: str | None) -> float | None:
    if text is None:
        return None
    try:
        return float(text)
    except ValueError:
        return None


def read_urdf(path: Path) -> dict:
    """Links (with optional inertial mass + COM offset), joints in document order, root, welded links."""
    root = ET.parse(path).getroot()
    links: dict[str, dict | None] = {}
    for link in root.findall("link"):
        inertial = link.find("inertial")
        if inertial is None:
            links[link.get("name")] = None
            continue
        mass_el = inertial.find("mass")
        mass = float(mass_el.get("value")) if mass_el is not None and mass_el.get("value") is not None else 0.0
        origin = inertial.find("origin")
        xyz = _floats(origin.get("xyz") if origin is not None else None, 3)
        links[link.get("name")] = {"mass": mass, "xyz": xyz}

    joints: dict[str, dict] = {}  # insertion order = document order
    for joint in root.findall("joint"):  # top level only (not <transmission><joint>)
        info = {
            "type": joint.get("type"),
            "parent": joint.find("parent").get("link") if joint.find("parent") is not None else None,
            "child": joint.find("child").get("link") if joint.find("child") is not None else None,
            "lower": None,
            "upper": None,
            "mimic": None,
        }
        limit = joint.find("limit")
        if limit is not None:
            info["lower"] = _opt_float(limit.get("lower"))
            info["upper"] = _opt_float(limit.get("upper"))
        mimic = joint.find("mimic")
        if mimic is not None:
            info["mimic"] = {
                "joint": mimic.get("joint"),
                "multiplier": _opt_float(mimic.get("multiplier")) if mimic.get("multiplier") is not None else 1.0,
                "offset": _opt_float(mimic.get("offset")) if mimic.get("offset") is not None else 0.0,
            }
        joints[joint.get("name")] = info

    children = {j["child"] for j in joints.values()}
    roots = [name for name in links if name not in children]
    root_link = roots[0] if len(roots) == 1 else None

    welded: list[str] = []
    if root_link is not None:
        frontier = [root_link]
        seen = {root_link}
        while frontier:
            link = frontier.pop()
            welded.append(link)
            for j in joints.values():
                if j["parent"] == link and j["type"] == "fixed" and j["child"] not in seen:
                    seen.add(j["child"])
                    frontier.append(j["child"])
    return {"links": links, "joints": joints, "root_link": root_link, "welded": sorted(welded)}


# --------------------------------------------------------------------------------------------------
# Configurations
# --------------------------------------------------------------------------------------------------
def resolve_mimics(joints: dict[str, dict]) -> tuple[dict[str, tuple[str, float, float]], list[str]]:
    """follower -> (leader, multiplier, offset) for mimics whose leader is an actuated joint.

    A mimic whose leader does not exist, is not revolute/continuous/prismatic, or that is part of
    a cycle is *unresolved*: that joint is sampled as an independent joint. Chains are allowed
    (a follower may follow another follower); values are evaluated recursively.
    """
    def leader_of(name: str) -> str | None:
        m = joints[name]["mimic"]
        if joints[name]["type"] not in ACTUATED or m is None:
            return None
        leader = m["joint"]
        return leader if leader in joints and joints[leader]["type"] in ACTUATED else None

    resolved: dict[str, tuple[str, float, float]] = {}
    unresolved: list[str] = []
    for name, j in joints.items():
        if j["type"] not in ACTUATED or j["mimic"] is None:
            continue
        leader = leader_of(name)
        on_cycle = False
        seen = {name}
        cur = leader
        while cur is not None and joints[cur]["mimic"] is not None:
            if cur == name:
                on_cycle = True
                break
            if cur in seen:
                break  # a cycle further up; it does not contain us
            seen.add(cur)
            cur = leader_of(cur)
        if leader is None or on_cycle:
            unresolved.append(name)
        else:
            resolved[name] = (leader, j["mimic"]["multiplier"], j["mimic"]["offset"])
    return resolved, unresolved


def sample_range(j: dict) -> tuple[float, float]:
    lo, hi = j["lower"], j["upper"]
    usable = lo is not None and hi is not None and math.isfinite(lo) and math.isfinite(hi) and lo < hi
    if j["type"] == "continuous":
        return (-math.pi, math.pi)
    if usable:
        return (lo, hi)
    return (-math.pi, math.pi) if j["type"] == "revolute" else (-0.1, 0.1)


def make_configurations(joints: dict[str, dict], n_random: int, seed: int) -> tuple[list[tuple[str, dict]], list[str]]:
    resolved, unresolved = resolve_mimics(joints)
    actuated = [name for name, j in joints.items() if j["type"] in ACTUATED]
    independent = [name for name in actuated if name not in resolved]  # document order

    configs = [("zero", {name: 0.0 for name in actuated})]  # raw zero, no clamping, followers too
    rng = np.random.default_rng(seed)  # fresh per file: a file's goldens don't depend on the others
    for k in range(n_random):
        q = {}
        for name in independent:
            lo, hi = sample_range(joints[name])
            q[name] = float(rng.uniform(lo, hi))

        def value(name: str) -> float:
            if name not in q:
                leader, mult, off = resolved[name]
                q[name] = mult * value(leader) + off
            return q[name]

        for name in actuated:
            value(name)
        configs.append((f"random_{k}", q))
    return configs, unresolved


# --------------------------------------------------------------------------------------------------
# Pinocchio
# --------------------------------------------------------------------------------------------------
def load_model(path: Path) -> tuple[pin.Model | None, str | None]:
    """buildModelFromUrdf with the C++ (urdfdom) stderr captured into the error message."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile(mode="w+b") as tmp:
        os.dup2(tmp.fileno(), 2)
        try:
            model = pin.buildModelFromUrdf(str(path))
            err = None
        except Exception as exc:  # noqa: BLE001 - any loader failure is recorded, not fatal
            model, err = None, str(exc)
        finally:
            os.dup2(saved, 2)
            os.close(saved)
        tmp.seek(0)
        captured = tmp.read().decode("utf-8", "replace").strip()
    if err is not None and captured:
        err = " ".join(captured.split()) + " | " + err
    if err is not None:  # keep index.json machine-independent
        err = err.replace(str(path.parent) + os.sep, "")
    return model, err


def to_list(v) -> list[float]:
    return [float(x) for x in v]


def finite_or_none(v):
    vals = to_list(v)
    return vals if all(math.isfinite(x) for x in vals) else None


def mass_weighted_com(items) -> tuple[float, list[float] | None]:
    total = 0.0
    acc = np.zeros(3)
    for mass, pos in items:
        total += mass
        acc += mass * pos
    return float(total), (to_list(acc / total) if total > 0.0 else None)


def evaluate(model, urdf, configs, n_link_positions):
    """Returns (configuration dicts, held_at_neutral, self-check discrepancy)."""
    data = model.createData()
    body_frames: dict[str, int] = {}
    for fid, frame in enumerate(model.frames):
        if frame.type == pin.FrameType.BODY:
            if frame.name in body_frames:
                raise RuntimeError(f"duplicate BODY frame {frame.name!r}")
            body_frames[frame.name] = fid
    missing = [name for name in urdf["links"] if name not in body_frames]
    if missing:
        raise RuntimeError(f"URDF links without a Pinocchio BODY frame: {missing}")

    held: list[str] = []
    scalar_joints: list[tuple[str, int, int, int]] = []  # name, idx_q, nq, idx_v
    for jid in range(1, model.njoints):
        jm = model.joints[jid]
        name = model.names[jid]
        if jm.nv == 1 and jm.nq in (1, 2) and name in urdf["joints"]:
            scalar_joints.append((name, jm.idx_q, jm.nq, jm.idx_v))
        else:
            held.append(name)
    missing_joints = [
        n for n, j in urdf["joints"].items() if j["type"] in ACTUATED and n not in {s[0] for s in scalar_joints}
    ]
    if missing_joints:
        raise RuntimeError(f"actuated URDF joints missing from the Pinocchio model: {missing_joints}")

    welded = set(urdf["welded"])
    inertial_links = [(name, li) for name, li in urdf["links"].items() if li is not None]
    out = []
    max_dev = 0.0
    for index, (label, qdict) in enumerate(configs):
        q = pin.neutral(model)
        for name, iq, nq, _ in scalar_joints:
            v = qdict[name]
            if nq == 1:
                q[iq] = v
            else:  # continuous (revolute unbounded): (cos, sin)
                q[iq] = math.cos(v)
                q[iq + 1] = math.sin(v)

        tau = pin.computeGeneralizedGravity(model, data, q)
        com = pin.centerOfMass(model, data, q)
        pin_mass = float(data.mass[0])
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacements(model, data)

        world_com = {
            name: data.oMf[body_frames[name]].act(np.array(li["xyz"])) for name, li in inertial_links
        }
        total_mass, total_com = mass_weighted_com((li["mass"], world_com[name]) for name, li in inertial_links)

        # Self-check: the same composition restricted to non-welded links must reproduce Pinocchio.
        moving_mass, moving_com = mass_weighted_com(
            (li["mass"], world_com[name]) for name, li in inertial_links if name not in welded
        )
        max_dev = max(max_dev, abs(moving_mass - pin_mass))
        if moving_com is not None and pin_mass > 0:
            max_dev = max(max_dev, float(np.max(np.abs(np.array(moving_com) - com))))

        entry = {
            "label": label,
            "q": {name: float(qdict[name]) for name, *_ in scalar_joints},
            "gravity_torque": {name: float(tau[iv]) for name, _, _, iv in scalar_joints},
            "pinocchio_mass": pin_mass,
            "pinocchio_com": finite_or_none(com) if pin_mass > 0 else None,
            "total_mass": total_mass,
            "total_com": total_com,
        }
        if index < n_link_positions:
            entry["link_positions"] = {
                name: to_list(data.oMf[fid].translation) for name, fid in body_frames.items() if name in urdf["links"]
            }
        out.append(entry)
    welded_mass = sum(li["mass"] for name, li in inertial_links if name in welded)
    max_dev = max(max_dev, abs(welded_mass - float(model.inertias[0].mass)))
    return out, held, max_dev


# --------------------------------------------------------------------------------------------------
def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--corpus", type=Path, default=None, help="folder searched recursively for .urdf")
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT, help=f"output folder (default {DEFAULT_OUT})")
    parser.add_argument("--configs", type=int, default=10, help="random configurations per robot (default 10)")
    parser.add_argument("--seed", type=int, default=7, help="numpy default_rng seed, per file (default 7)")
    args = parser.parse_args()

    corpus = (args.corpus or default_corpus()).resolve()
    out_dir = args.out.resolve()
    out_dir.mkdir(parents=True, exist_ok=True)
    version = pin.__version__
    gravity = to_list(pin.Model().gravity.linear)

    files = sorted(corpus.rglob("*.urdf"), key=lambda p: p.relative_to(corpus).as_posix())
    if not files:
        sys.exit(f"pinocchio_goldens: no .urdf under {corpus}")

    index = []
    rows = []
    written = set()
    worst = 0.0
    named_checks = {}
    for path in files:
        rel = path.relative_to(corpus).as_posix()
        urdf = read_urdf(path)
        model, err = load_model(path)
        if model is not None:
            try:
                configs, unresolved = make_configurations(urdf["joints"], args.configs, args.seed)
                results, held, dev = evaluate(model, urdf, configs, 1 + LINK_POSITION_RANDOM_CONFIGS)
            except Exception as exc:  # noqa: BLE001
                model, err = None, f"golden generation failed: {exc}"
        index.append({"file": rel, "loaded": model is not None, "error": err})
        if model is None:
            rows.append((rel, "no", "-", "-", len(urdf["joints"]), "-"))
            continue
        worst = max(worst, dev)
        stem = Path(rel).stem
        if stem in SELF_CHECK_ROBOTS:
            named_checks[rel] = dev
        golden = {
            "source": rel,
            "pinocchio_version": version,
            "gravity": gravity,
            "seed": args.seed,
            "root_link": urdf["root_link"],
            "welded_links": urdf["welded"],
            "held_at_neutral": held,
            "unresolved_mimics": unresolved,
            "configurations": results,
        }
        name = rel[: -len(".urdf")].replace("/", "__") + ".json"
        with open(out_dir / name, "w", encoding="utf-8") as fh:
            json.dump(golden, fh, sort_keys=True, indent=1)
            fh.write("\n")
        written.add(name)
        rows.append((rel, "yes", model.nq, model.njoints - 1, len(urdf["joints"]), f"{results[0]['total_mass']:.6g}"))

    with open(out_dir / "index.json", "w", encoding="utf-8") as fh:
        json.dump(index, fh, sort_keys=True, indent=1)
        fh.write("\n")
    written.add("index.json")

    # Prune goldens of URDFs no longer in the corpus (only files this script wrote: they carry our keys).
    for stale in sorted(out_dir.glob("*.json")):
        if stale.name in written:
            continue
        try:
            content = json.loads(stale.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        if isinstance(content, dict) and {"source", "pinocchio_version", "configurations"} <= content.keys():
            stale.unlink()
            print(f"removed stale golden {stale.name}")

    w = max(len(r[0]) for r in rows)
    print(f"{'file':<{w}}  loaded  {'nq':>4}  {'pin joints':>10}  {'urdf joints':>11}  total mass")
    for r in rows:
        print(f"{r[0]:<{w}}  {r[1]:<6}  {r[2]!s:>4}  {r[3]!s:>10}  {r[4]!s:>11}  {r[5]}")
    loaded = sum(1 for e in index if e["loaded"])
    print(f"\npinocchio {version}: {loaded}/{len(index)} loaded; goldens in {out_dir}")
    for e in index:
        if not e["loaded"]:
            print(f"  FAILED {e['file']}: {e['error']}")
    print("self-check (sum over non-welded links vs pinocchio centerOfMass/data.mass[0], welded vs inertias[0]):")
    for rel, dev in sorted(named_checks.items()):
        print(f"  {rel}: max discrepancy {dev:.3e}")
    print(f"  all loaded files: max discrepancy {worst:.3e}")
    if worst > 1e-9:
        print("pinocchio_goldens: self-check discrepancy above 1e-9", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
