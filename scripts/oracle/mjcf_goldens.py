#!/usr/bin/env python3
"""MuJoCo's own numbers for MJCF models: the oracle of the MJCF reader (issue #30).

For every model (an `.xml` file with a `<mujoco>` root that MuJoCo compiles) writes `<stem>.json` with each
body's mass and principal moments of inertia (`body_mass`, `body_inertia`) and, at
`qpos0`, at two seeded random configurations and at each keyframe (`key:NAME`: the key's qpos, free joints
left at qpos0 as `--pose key:NAME` leaves the base): per-body mass and world centre of mass (`body_mass`,
`xipos`), the total mass and centre of mass (`subtree_com` of the world body), and the generalized gravity
forces (`qfrc_bias` at zero velocity less body `gravcomp`'s passive `qfrc_gravcomp`: what the actuators must apply to hold the pose) by joint, under
standard gravity (0, 0, -9.81) whatever the model says: on even where the model turns it off
(`<flag gravity="disable"/>`, recorded as `gravity_disabled`), and standard where `<option gravity>` is
another (gymnasium's pusher has none, its inverted double pendulum a tilt of 1e-5; recorded as
`model_gravity`): the validator's statics are about the robot under standard gravity; and per
actuator the fields that bound its force (`gear`, `ctrlrange`, `forcerange`, `gainprm`, `biasprm`, the
joint's `actfrcrange`).

    python scripts/oracle/mjcf_goldens.py [--models DIR] [--out DIR] [--check]

The committed goldens: `tests/golden/mujoco` (dm_control's suite, the default) and `tests/golden/gymnasium`
(`--models target/gymnasium/gymnasium/envs/mujoco/assets --out crates/urdf-validator/tests/golden/gymnasium`,
the `gymnasium==1.2.2` wheel's models, unpacked by scripts/setup-test-env.sh).

Without --models, the dm_control suite models are read from the `dm-control==1.0.50` wheel (downloaded
with `pip download --no-deps` into target/dm-control and unzipped: the wheel's `dm_control/suite/` folder,
its includes and meshes; nothing of dm_control is imported). Needs `mujoco` (the test venv's). --check
compares with the committed files and exits 1 on a difference.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

import mujoco
import numpy as np

REPO = Path(__file__).resolve().parents[2]
DM_CONTROL = "dm-control==1.0.50"
SEED = 7
RANDOM_CONFIGURATIONS = 2
STANDARD_GRAVITY = (0.0, 0.0, -9.81)


def held_force(model, data, joint, dof):
    """What the motors hold at dof `dof` of joint `joint`: qfrc_bias, less the force body `gravcomp`
    applies passively (`qfrc_gravcomp`; routed through the actuators instead when the joint has
    `actuatorgravcomp`, then the motors hold it too)."""
    force = data.qfrc_bias[dof].item()
    if not model.jnt_actgravcomp[joint]:
        force -= data.qfrc_gravcomp[dof].item()
    return force


def dm_control_suite() -> Path:
    """The dm_control suite folder, unzipped from the wheel (downloaded once)."""
    root = REPO / "target" / "dm-control"
    suite = root / "dm_control" / "suite"
    if suite.is_dir():
        return suite
    root.mkdir(parents=True, exist_ok=True)
    subprocess.run(
        [sys.executable, "-m", "pip", "download", "-q", "--no-deps", DM_CONTROL, "-d", str(root)],
        check=True,
    )
    wheel = next(root.glob("dm_control-*.whl"))
    with zipfile.ZipFile(wheel) as z:
        for name in z.namelist():
            if name.startswith("dm_control/suite/") and not name.endswith(".py"):
                z.extract(name, root)
    return suite


def is_mjcf(path: Path) -> bool:
    head = path.read_text(errors="replace")[:4096]
    return "<mujoco" in head


def name_of(model: mujoco.MjModel, kind: mujoco.mjtObj, index: int) -> str:
    return mujoco.mj_id2name(model, kind, index) or f"#{index}"


def configurations(model: mujoco.MjModel) -> list[tuple[str, np.ndarray]]:
    """qpos0, then random configurations: hinge/slide joints uniform in their range when limited, else in
    [-π, π] (hinge) or [-0.1, 0.1] m (slide); ball and free joints held at qpos0; then each keyframe
    (`key:NAME`, an unnamed one `key:INDEX`) with its free joints at qpos0."""
    rng = np.random.default_rng(SEED)
    found = [("qpos0", model.qpos0.copy())]
    for k in range(RANDOM_CONFIGURATIONS):
        q = model.qpos0.copy()
        for j in range(model.njnt):
            kind = int(model.jnt_type[j])  # a numpy integer is never `in` a tuple of mjtJoint members
            if kind not in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE):
                continue
            lo, hi = model.jnt_range[j]
            if not (model.jnt_limited[j] and lo < hi):
                lo, hi = (-math.pi, math.pi) if kind == mujoco.mjtJoint.mjJNT_HINGE else (-0.1, 0.1)
            q[model.jnt_qposadr[j]] = rng.uniform(lo, hi)
        found.append((f"random_{k}", q))
    for k in range(model.nkey):
        # A keyframe as `--pose key:NAME` analyses it: free joints stay at qpos0 (the base is not moved).
        q = model.key_qpos[k].copy()
        for j in range(model.njnt):
            if int(model.jnt_type[j]) == mujoco.mjtJoint.mjJNT_FREE:
                a = model.jnt_qposadr[j]
                q[a : a + 7] = model.qpos0[a : a + 7]
        found.append((f"key:{mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_KEY, k) or k}", q))
    return found


def golden(path: Path, root: Path) -> dict:
    model = mujoco.MjModel.from_xml_path(str(path))
    gravity_bit = int(mujoco.mjtDisableBit.mjDSBL_GRAVITY)
    gravity_disabled = bool(model.opt.disableflags & gravity_bit)
    model.opt.disableflags &= ~gravity_bit
    model_gravity = model.opt.gravity.tolist()
    model.opt.gravity[:] = STANDARD_GRAVITY
    data = mujoco.MjData(model)
    bodies = [name_of(model, mujoco.mjtObj.mjOBJ_BODY, b) for b in range(model.nbody)]
    joints = []
    for j in range(model.njnt):
        joints.append(
            {
                "name": name_of(model, mujoco.mjtObj.mjOBJ_JOINT, j),
                "type": int(model.jnt_type[j]),
                "body": bodies[model.jnt_bodyid[j]],
                "dof": int(model.jnt_dofadr[j]),
                "limited": bool(model.jnt_limited[j]),
                "range": model.jnt_range[j].tolist(),
                "actfrcrange": model.jnt_actfrcrange[j].tolist()
                if model.jnt_actfrclimited[j]
                else None,
            }
        )
    actuators = []
    for a in range(model.nu):
        actuators.append(
            {
                "name": name_of(model, mujoco.mjtObj.mjOBJ_ACTUATOR, a),
                "trntype": int(model.actuator_trntype[a]),
                "target": int(model.actuator_trnid[a][0]),
                "gear": float(model.actuator_gear[a][0]),
                "ctrlrange": model.actuator_ctrlrange[a].tolist()
                if model.actuator_ctrllimited[a]
                else None,
                "forcerange": model.actuator_forcerange[a].tolist()
                if model.actuator_forcelimited[a]
                else None,
                "gainprm": model.actuator_gainprm[a][:3].tolist(),
                "biasprm": model.actuator_biasprm[a][:3].tolist(),
            }
        )
    configs = []
    for label, q in configurations(model):
        data.qpos[:] = q
        data.qvel[:] = 0
        mujoco.mj_forward(model, data)
        configs.append(
            {
                "label": label,
                "qpos": q.tolist(),
                "body_com": {bodies[b]: data.xipos[b].tolist() for b in range(1, model.nbody)},
                "total_com": data.subtree_com[0].tolist(),
                "gravity_force": {
                    j["name"]: held_force(model, data, index, j["dof"])
                    for index, j in enumerate(joints)
                    if j["type"] in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE)
                },
            }
        )
    return {
        "source": path.relative_to(root).as_posix(),
        "mujoco_version": mujoco.__version__,
        "gravity": model.opt.gravity.tolist(),
        "gravity_disabled": gravity_disabled,
        "model_gravity": model_gravity,
        "total_mass": float(sum(model.body_mass)),
        "bodies": [
            {
                "name": bodies[b],
                "parent": bodies[model.body_parentid[b]],
                "mass": float(model.body_mass[b]),
                "inertia": model.body_inertia[b].tolist(),
            }
            for b in range(1, model.nbody)
        ],
        "joints": joints,
        "actuators": actuators,
        "configurations": configs,
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--models", type=Path, help="folder of MJCF models (default: dm_control's suite)")
    parser.add_argument("--out", type=Path, default=REPO / "crates/urdf-validator/tests/golden/mujoco")
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    root = (args.models or dm_control_suite()).resolve()
    args.out = args.out.resolve()
    # MuJoCo writes its warnings to MUJOCO_LOG.TXT in the working directory: not into the repository.
    os.chdir(tempfile.mkdtemp(prefix="mjcf-goldens-"))
    stale = 0
    rows = []
    for path in sorted(root.glob("*.xml")):
        if not is_mjcf(path):
            continue
        try:
            value = golden(path, root)
        except (ValueError, mujoco.FatalError) as error:
            rows.append((path.name, f"not compiled: {str(error).splitlines()[0]}"))
            continue
        text = json.dumps(value, indent=1, sort_keys=True) + "\n"
        out = args.out / f"{path.stem}.json"
        if args.check:
            if not out.is_file() or out.read_text() != text:
                stale += 1
                rows.append((path.name, "STALE"))
                continue
        else:
            args.out.mkdir(parents=True, exist_ok=True)
            out.write_text(text)
        rows.append(
            (path.name, f"{value['total_mass']:.6g} kg, {len(value['bodies'])} bodies, "
             f"{len(value['joints'])} joints, {len(value['actuators'])} actuators")
        )
    for name, what in rows:
        print(f"{name:28} {what}")
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
