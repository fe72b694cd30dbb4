#!/usr/bin/env python3
"""Golden statics values from Drake for the SDFormat reader (crates/urdf-validator/src/sdf).

Every SDF file named in MODELS (under crates/urdf-validator/tests/data/sdf) is loaded with
`pydrake.multibody.parsing.Parser` (its package map holding every package.xml under that folder, for
`package://` includes) into a `MultibodyPlant` (time step 0, Drake's default gravity
(0, 0, -9.81) m/s^2 in the world frame, as our statics uses), finalised, and evaluated at the zero
configuration and at N seeded random configurations. One JSON per model is written to
crates/urdf-validator/tests/data/sdf/golden/<stem>.json with, per configuration:

  q               joint name (scoped like ours: `inner::joint` for a joint of nested model inner) -> position
  gravity_torque  joint name -> -CalcGravityGeneralizedForces at that joint's velocity index: the
                  effort a motor must apply to hold the pose (Pinocchio's g(q), our convention)
  total_mass      CalcTotalMass
  com             CalcCenterOfMassPositionInWorld

Free (floating) bodies stay at the pose the SDF gives them; their generalized forces are not stored.
The Rust side (tests/sdf_golden.rs) compares to 1e-9.

    python scripts/oracle/sdf_golden.py            # regenerate
    python scripts/oracle/sdf_golden.py --check    # regenerate in memory, compare with the files

Dev-only tooling: needs `drake` (PyPI, 1.51.1 used), never a runtime dependency.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import xml.etree.ElementTree as ET
from importlib.metadata import version
from pathlib import Path

import numpy as np
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import JointIndex, PrismaticJoint, RevoluteJoint

REPO_ROOT = Path(__file__).resolve().parents[2]
DATA = REPO_ROOT / "crates" / "urdf-validator" / "tests" / "data" / "sdf"
OUT = DATA / "golden"
MODELS = [
    "drake_acrobot.sdf",
    "drake_cart_pole.sdf",
    "drake_double_pendulum.sdf",
    "sdformat_double_pendulum.sdf",
    "sdformat_joint_axis_in_rotated_frame.sdf",
    "sdformat_model_joint_axis_expressed_in.sdf",
    "frames_and_poses.sdf",
    "legacy_1_5_axis.sdf",
    "legacy_1_4_axis.sdf",
    "nested_arm.sdf",
    "bullet_kuka_iiwa.sdf",
    # Merge-includes package://interface_api_test/gripper.sdf (SDFormat 1.9 merge include).
    "drake_packages/interface_api_test/arm_merge_include.sdf",
]
# Models whose total mass and COM differ by design (the gravity torques are still compared).
MASS_COM_NOT_COMPARED = {
    "bullet_kuka_iiwa.sdf": "lbr_iiwa_link_0 declares <mass>0</mass>: sdformat reports LINK_INERTIA_INVALID "
    "and Drake gives the link 1 kg; the reader keeps the 0 as written (the base link: no torque depends on it)",
}
RANDOM_CONFIGS = 2
SEED = 7
TOLERANCE = 1e-12


def sdf_joint_names(path: Path) -> list[str]:
    """Every joint of the file's (first) model, scoped like ours (`arm::j1` for joint j1 of nested model
    arm), read from the XML itself: Drake files a joint under the model instance of its child body, not
    the model that declares it."""
    root = ET.parse(path).getroot()
    model = root.find("model")
    if model is None:
        model = root.find("world/model")
    names: list[str] = []

    def walk(node, scope: str) -> None:
        for child in node:
            if child.tag == "joint":
                names.append(scope + child.get("name", ""))
            elif child.tag == "model":
                walk(child, scope + child.get("name", "") + "::")

    walk(model, "")
    return names


def scoped_name(joint, names: list[str]) -> str:
    """Our name of a Drake joint: the one joint of the file with that local name."""
    matches = [n for n in names if n.split("::")[-1] == joint.name()]
    if len(matches) != 1:
        raise SystemExit(f"sdf_golden: joint {joint.name()!r} is not named once in the file: {matches}")
    return matches[0]


def golden(name: str) -> dict:
    path = DATA / name
    plant = MultibodyPlant(0.0)
    parser = Parser(plant)
    for package_xml in sorted(DATA.rglob("package.xml")):
        parser.package_map().AddPackageXml(str(package_xml))
    parser.AddModels(str(path))
    plant.Finalize()
    names = sdf_joint_names(path)
    context = plant.CreateDefaultContext()
    joints = []
    for i in range(plant.num_joints()):
        joint = plant.get_joint(JointIndex(i))
        if isinstance(joint, (RevoluteJoint, PrismaticJoint)):
            joints.append(joint)
    rng = np.random.default_rng(SEED)
    configurations = []
    for label in ["zero"] + [f"random_{k}" for k in range(RANDOM_CONFIGS)]:
        q = {}
        for joint in joints:
            if label == "zero":
                value = 0.0
            else:
                lower, upper = joint.position_lower_limits()[0], joint.position_upper_limits()[0]
                span = (-math.pi, math.pi) if isinstance(joint, RevoluteJoint) else (-0.5, 0.5)
                lower, upper = max(lower, span[0]), min(upper, span[1])
                value = float(rng.uniform(lower, upper)) if lower < upper else 0.0
            joint.set_angle(context, value) if isinstance(joint, RevoluteJoint) else joint.set_translation(context, value)
            q[scoped_name(joint, names)] = value
        tau = plant.CalcGravityGeneralizedForces(context)
        configurations.append(
            {
                "label": label,
                "q": q,
                "gravity_torque": {
                    scoped_name(joint, names): -float(tau[joint.velocity_start()]) for joint in joints
                },
                "total_mass": float(plant.CalcTotalMass(context)),
                "com": [float(v) for v in plant.CalcCenterOfMassPositionInWorld(context)],
            }
        )
    extra = {"mass_com_not_compared": MASS_COM_NOT_COMPARED[name]} if name in MASS_COM_NOT_COMPARED else {}
    return {
        **extra,
        "source": name,
        "drake_version": version("drake"),
        "gravity": [float(v) for v in plant.gravity_field().gravity_vector()],
        "seed": SEED,
        "configurations": configurations,
    }


def close(a, b) -> bool:
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(close(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(close(x, y) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return abs(a - b) <= TOLERANCE * max(1.0, abs(a))
    return a == b


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare with the committed JSON, write nothing")
    args = parser.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    stale = 0
    for name in MODELS:
        result = golden(name)
        target = OUT / (Path(name).stem + ".json")
        text = json.dumps(result, indent=1, sort_keys=True) + "\n"
        if args.check:
            committed = json.loads(target.read_text()) if target.is_file() else None
            ok = committed is not None and close(result, committed)
            print(f"{'ok   ' if ok else 'STALE'} {target.relative_to(REPO_ROOT)}")
            stale += 0 if ok else 1
        else:
            target.write_text(text)
            first = result["configurations"][0]
            print(f"{name}: {len(first['q'])} joints, mass {first['total_mass']:.6g} kg")
    if stale:
        print(f"{stale} golden file(s) differ from Drake: regenerate with scripts/oracle/sdf_golden.py", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
