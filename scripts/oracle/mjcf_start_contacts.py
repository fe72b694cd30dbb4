#!/usr/bin/env python3
"""MuJoCo as the oracle of the start-contact findings (U042, U603).

For every MJCF file given (or found under the folders given), MuJoCo loads the model, resets it to
qpos0 and to each keyframe, runs mj_forward and lists its contacts deeper than a threshold: between
two bodies of the robot (U042's pairs) and between a body and a world plane (U603's). The validator's
JSON report is read for the same facts. The script prints every difference and exits 1 when there is
one, so it can gate a corpus run:

    .venv/bin/python scripts/oracle/mjcf_start_contacts.py --validator target/release/urdf_validate \
        crates/urdf-validator/tests/data/menagerie target/dm-control/dm_control/suite

Depths within --band of the 1 mm threshold are not compared (the two narrow phases may round to
different sides of it). Models MuJoCo refuses are skipped (the refusal tests compare those).
"""

import argparse
import json
import pathlib
import re
import subprocess
import sys

import mujoco

THRESHOLD_MM = 1.0


def body_name(model, body):
    """The body's name, or the validator's for an unnamed one (`body#N`, N its index in the tree)."""
    return model.body(body).name or f"body#{body}"


def mujoco_contacts(path, band):
    """{(pose, kind, names)}: pose 'qpos0' or a key name; kind 'pair' or 'floor'; and the same set of
    contacts whose depth is within `band` of the threshold (not compared)."""
    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    found, unsure = set(), set()
    # A key at qpos0 (`<size nkey>` makes them) is qpos0 again: the validator names the contacts once.
    keys = [k for k in range(min(model.nkey, 64)) if (model.key_qpos[k] != model.qpos0).any()]
    poses = [("qpos0", None)] + [(model.key(k).name or str(k), k) for k in keys]
    for name, key in poses:
        if key is None:
            mujoco.mj_resetData(model, data)
        else:
            mujoco.mj_resetDataKeyframe(model, data, key)
        mujoco.mj_forward(model, data)
        for contact in data.contact[: data.ncon]:
            depth = -contact.dist * 1e3
            geoms = (contact.geom1, contact.geom2)
            bodies = [model.geom_bodyid[g] for g in geoms]
            if 0 in bodies:
                world_geom = geoms[bodies.index(0)]
                if model.geom_type[world_geom] != mujoco.mjtGeom.mjGEOM_PLANE:
                    continue
                other = bodies[1 - bodies.index(0)]
                fact = (name, "floor", (body_name(model, other),))
            else:
                fact = (name, "pair", tuple(sorted(body_name(model, b) for b in bodies)))
            if depth > THRESHOLD_MM + band:
                found.add(fact)
            elif depth > THRESHOLD_MM - band:
                unsure.add(fact)
    return found, unsure - found


def pose_names(segment):
    """The poses of a finding's depths ("12.0 mm deep at qpos0 and key 'down', 3.0 mm at key 'b'")."""
    return (["qpos0"] if "qpos0" in segment else []) + re.findall(r"key '([^']*)'", segment)


def validator_contacts(validator, path):
    run = subprocess.run(
        [validator, str(path), "--format", "json", "--no-config", "--no-write"],
        capture_output=True,
        text=True,
    )
    try:
        report = json.loads(run.stdout)
    except json.JSONDecodeError:
        raise RuntimeError(f"no report (exit {run.returncode}): {run.stderr.strip()[:300]}")
    found = set()
    for finding in report["findings"]:
        message = finding["message"]
        if finding["rule"] == "U042":
            names = tuple(sorted(re.match(r"bodies '([^']*)' and '([^']*)'", message).groups()))
            kind = "pair"
            segment = message.split(" overlap ", 1)[1].split(", and MuJoCo", 1)[0]
        elif finding["rule"] == "U603":
            names = (re.match(r"body '([^']*)'", message).group(1),)
            kind = "floor"
            segment = message.split(" starts ", 1)[1].split(" inside ", 1)[0]
        else:
            continue
        for pose in pose_names(segment):
            found.add((pose, kind, names))
    return found


def mjcf_files(arguments):
    for argument in arguments:
        path = pathlib.Path(argument)
        candidates = sorted(path.rglob("*.xml")) if path.is_dir() else [path]
        for candidate in candidates:
            try:
                head = candidate.read_text(errors="replace")[:4000]
            except OSError:
                continue
            if "<mujoco" in head:
                yield candidate


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--validator", default="target/release/urdf_validate")
    parser.add_argument("--band", type=float, default=0.05, help="mm around the threshold not compared")
    parser.add_argument(
        "--facts",
        action="store_true",
        help="print MuJoCo's start contacts as JSON ({file: [[pose, kind, name...]]}, refused: null) and stop",
    )
    parser.add_argument("paths", nargs="+")
    args = parser.parse_args()
    if args.facts:
        facts = {}
        for path in mjcf_files(args.paths):
            try:
                found, _ = mujoco_contacts(path, args.band)
                facts[str(path)] = sorted([pose, kind, *names] for pose, kind, names in found)
            except Exception:
                facts[str(path)] = None
        print(json.dumps(facts))
        return
    compared = differing = 0
    for path in mjcf_files(args.paths):
        try:
            expected, unsure = mujoco_contacts(path, args.band)
        except Exception as error:  # MuJoCo refuses the model, or it includes a missing file
            print(f"skip {path}: MuJoCo: {str(error).splitlines()[0]}")
            continue
        try:
            ours = validator_contacts(args.validator, path)
        except RuntimeError as error:
            differing += 1
            print(f"DIFF {path}: the validator gives {error}")
            continue
        compared += 1
        missed = expected - ours
        extra = ours - expected - unsure
        if missed or extra:
            differing += 1
            print(f"DIFF {path}")
            for fact in sorted(missed):
                print(f"  MuJoCo only: {fact}")
            for fact in sorted(extra):
                print(f"  ours only:   {fact}")
        else:
            print(f"ok   {path}: {len(expected)} start contacts")
    print(f"{compared} models compared, {differing} differ")
    sys.exit(1 if differing else 0)


if __name__ == "__main__":
    main()
