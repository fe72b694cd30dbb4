#!/usr/bin/env python3
"""Independent check of the example robot (examples/robots/mobile_manipulator.urdf) with Pinocchio.

Dev-only tooling: Pinocchio is never a runtime dependency of urdf-validator. To run it:

    bash scripts/setup-test-env.sh                 # creates .venv
    .venv/bin/pip install pin==4.1.0               # Pinocchio (PyPI package `pin`)
    .venv/bin/python scripts/oracle/check_example_robot.py [URDF] [--samples N] [--seed S]

It prints the total mass, the centre of mass at the zero pose, the gravity torque of every joint
(`pinocchio.computeGeneralizedGravity`) at the zero pose, on the arm stretched out horizontally in every
direction, and its maximum |torque| over N seeded random configurations within the joint limits, and the
ratio effort / max |torque| per joint. It also checks every declared inertia tensor (positive definite,
triangle inequality A + B >= C on the principal moments) and the static stability of the base: the centre
of mass must stay inside the support polygon of the wheels and casters in every pose above.

Exit code 0 when every check passes, 1 otherwise (2 on bad usage).
"""

from __future__ import annotations

import argparse
import math
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

try:
    import pinocchio as pin
except ImportError:  # pragma: no cover - a message is more useful than a traceback
    sys.exit("check_example_robot: Pinocchio is missing; run `.venv/bin/pip install pin==4.1.0`")

REPO_ROOT = Path(__file__).resolve().parents[2]
DEFAULT_URDF = REPO_ROOT / "examples" / "robots" / "mobile_manipulator.urdf"

MIN_RATIO = 2.0  # declared effort must be at least this multiple of the worst gravity torque
# Links that touch the floor; their collision primitive (sphere, or cylinder with a horizontal axis)
# gives the contact point under the link origin.
CONTACT_LINKS = ["left_wheel_link", "right_wheel_link", "front_caster_link", "rear_caster_link"]
ARM_PAN_JOINT = "shoulder_pan_joint"  # swept through 360 degrees for the "stretched in any direction" poses
FLOOR_TOLERANCE = 1e-3  # m: a contact link's lowest point must be this close to the root frame's z = 0
REL_TOL = 1e-9


def check_inertias(root: ET.Element) -> list[str]:
    """Declared inertia tensors: positive definite and triangle inequality on principal moments."""
    problems = []
    print("Declared inertias (principal moments, kg m^2):")
    for link in root.findall("link"):
        inertia = link.find("inertial/inertia")
        if inertia is None:
            continue
        g = {k: float(inertia.get(k, "0")) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
        tensor = np.array(
            [
                [g["ixx"], g["ixy"], g["ixz"]],
                [g["ixy"], g["iyy"], g["iyz"]],
                [g["ixz"], g["iyz"], g["izz"]],
            ]
        )
        moments = np.sort(np.linalg.eigvalsh(tensor))
        a, b, c = moments
        status = "ok"
        if a <= 0:
            status = "NOT POSITIVE DEFINITE"
            problems.append(f"{link.get('name')}: inertia not positive definite (min eigenvalue {a:.3g})")
        elif a + b < c * (1 - REL_TOL):
            status = f"TRIANGLE INEQUALITY VIOLATED (A + B - C = {a + b - c:.3g})"
            problems.append(f"{link.get('name')}: principal moments {a:.6g} + {b:.6g} < {c:.6g}")
        print(f"  {link.get('name'):<20} {a:11.6g} {b:11.6g} {c:11.6g}   {status}")
    return problems


def contact_radius(root: ET.Element, name: str) -> float:
    link = root.find(f"link[@name='{name}']")
    if link is None:
        raise SystemExit(f"check_example_robot: contact link {name!r} not in the URDF")
    for tag in ("sphere", "cylinder"):
        geometry = link.find(f"collision/geometry/{tag}")
        if geometry is not None:
            return float(geometry.get("radius"))
    raise SystemExit(f"check_example_robot: contact link {name!r} has no sphere or cylinder collision")


def polygon_margin(points: np.ndarray, p: np.ndarray) -> float:
    """Signed distance from p to the boundary of the convex polygon `points` (counter-clockwise):
    positive inside, negative outside."""
    margin = math.inf
    n = len(points)
    for i in range(n):
        a, b = points[i], points[(i + 1) % n]
        edge = b - a
        normal = np.array([-edge[1], edge[0]]) / np.linalg.norm(edge)  # inward for a CCW polygon
        margin = min(margin, float(np.dot(p - a, normal)))
    return margin


def convex_hull(points: np.ndarray) -> np.ndarray:
    """Andrew's monotone chain, counter-clockwise."""
    pts = sorted(map(tuple, points))

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def set_joint(model, q: np.ndarray, joint_id: int, angle: float) -> None:
    joint = model.joints[joint_id]
    if joint.nq == 1:
        q[joint.idx_q] = angle
    elif joint.nq == 2 and joint.nv == 1:  # continuous joint: (cos, sin)
        q[joint.idx_q] = math.cos(angle)
        q[joint.idx_q + 1] = math.sin(angle)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("urdf", nargs="?", type=Path, default=DEFAULT_URDF)
    parser.add_argument("--samples", type=int, default=20_000, help="random configurations (default 20000)")
    parser.add_argument("--seed", type=int, default=20240611, help="random seed (default 20240611)")
    args = parser.parse_args()

    root = ET.parse(args.urdf).getroot()
    # A free-flyer root puts the root link's mass on a body (Pinocchio leaves bodies welded to the fixed
    # universe out of the total mass and the COM). At the neutral base pose and zero base acceleration the
    # joint gravity torques are the same as with a fixed base; the base's own 6 DOF are not reported.
    model = pin.buildModelFromUrdf(str(args.urdf), pin.JointModelFreeFlyer())
    data = model.createData()
    problems: list[str] = []

    print(f"URDF: {args.urdf}")
    print(f"Pinocchio {pin.__version__}; gravity {model.gravity.linear}")
    print()
    problems += check_inertias(root)

    # Joints with one degree of freedom (revolute, continuous, prismatic), in model order.
    joints = [j for j in range(1, model.njoints) if model.joints[j].nv == 1]
    names = {j: model.names[j] for j in joints}

    q0 = pin.neutral(model)
    total_mass = pin.computeTotalMass(model)
    com0 = pin.centerOfMass(model, data, q0)
    tau0 = pin.computeGeneralizedGravity(model, data, q0)
    print()
    print(f"Total mass: {total_mass:.3f} kg")
    print(f"COM at the zero pose (root frame): x={com0[0]:.4f} y={com0[1]:.4f} z={com0[2]:.4f} m")

    # Named poses: the arm stretched out horizontally, swept through every direction (the zero pose of this
    # robot has the arm horizontal; other joints stay at zero).
    named = {"zero": q0}
    pan = model.getJointId(ARM_PAN_JOINT) if model.existJointName(ARM_PAN_JOINT) else None
    if pan is not None:
        lo, hi = model.lowerPositionLimit[model.joints[pan].idx_q], model.upperPositionLimit[model.joints[pan].idx_q]
        for deg in range(0, 360, 5):
            angle = math.remainder(math.radians(deg), 2 * math.pi)
            q = q0.copy()
            set_joint(model, q, pan, float(np.clip(angle, lo, hi)))
            named[f"stretched pan={deg}deg"] = q

    # Random configurations within the limits (continuous joints: any angle).
    rng = np.random.default_rng(args.seed)
    configs = list(named.values())
    for _ in range(args.samples):
        q = q0.copy()
        for j in joints:
            joint = model.joints[j]
            if joint.nq == 1:
                lo, hi = model.lowerPositionLimit[joint.idx_q], model.upperPositionLimit[joint.idx_q]
                set_joint(model, q, j, rng.uniform(lo, hi))
            else:
                set_joint(model, q, j, rng.uniform(-math.pi, math.pi))
        configs.append(q)

    max_tau = np.zeros(model.nv)
    worst_q = [q0] * model.nv
    stretched_max = np.zeros(model.nv)
    for k, q in enumerate(configs):
        tau = np.abs(pin.computeGeneralizedGravity(model, data, q))
        better = tau > max_tau
        for v in np.nonzero(better)[0]:
            worst_q[v] = q
        max_tau = np.maximum(max_tau, tau)
        if k < len(named):
            stretched_max = np.maximum(stretched_max, tau)

    print()
    print("Gravity torques (N m): zero pose; max |tau| with the arm stretched horizontally (any direction);")
    print(f"max |tau| over zero + stretched + {args.samples} random configurations (seed {args.seed}); ratio effort / max")
    print(f"  {'joint':<22} {'type':<10} {'effort':>8} {'tau(zero)':>10} {'stretched':>10} {'max|tau|':>10} {'ratio':>8}")
    for j in joints:
        joint = model.joints[j]
        v = joint.idx_v
        effort = float(model.effortLimit[v])
        kind = "bounded" if joint.nq == 1 else "continuous"
        ratio = effort / max_tau[v] if max_tau[v] > 1e-9 else math.inf
        flag = ""
        if effort <= 0 or not math.isfinite(effort):
            flag = "  NO EFFORT"
            problems.append(f"{names[j]}: no positive effort limit")
        elif ratio < MIN_RATIO:
            flag = f"  < {MIN_RATIO}"
            problems.append(f"{names[j]}: effort {effort:g} N m < {MIN_RATIO} x max gravity torque {max_tau[v]:.3f} N m")
        ratio_text = "inf" if math.isinf(ratio) else f"{ratio:.2f}"
        print(
            f"  {names[j]:<22} {kind:<10} {effort:8.2f} {tau0[v]:10.4f} {stretched_max[v]:10.4f} "
            f"{max_tau[v]:10.4f} {ratio_text:>8}{flag}"
        )

    # Static stability: the COM's ground projection inside the support polygon of the contacts.
    print()
    pin.forwardKinematics(model, data, q0)
    pin.updateFramePlacements(model, data)
    contacts = []
    for name in CONTACT_LINKS:
        if not model.existFrame(name):
            raise SystemExit(f"check_example_robot: contact link {name!r} not in the model")
        position = data.oMf[model.getFrameId(name)].translation
        lowest = position[2] - contact_radius(root, name)
        if abs(lowest) > FLOOR_TOLERANCE:
            problems.append(f"{name}: lowest point at z={lowest:.4f} m, not on the floor (z=0)")
        contacts.append(position[:2].copy())
        print(f"Contact {name:<20} x={position[0]:+.3f} y={position[1]:+.3f}  lowest point z={lowest:+.4f} m")
    polygon = convex_hull(np.array(contacts))
    worst_margin, worst_name = math.inf, ""
    for k, q in enumerate(configs):
        com = pin.centerOfMass(model, data, q)
        margin = polygon_margin(polygon, com[:2])
        if margin < worst_margin:
            worst_margin = margin
            worst_name = list(named)[k] if k < len(named) else f"random #{k - len(named)}"
    stretched_margin = min(polygon_margin(polygon, pin.centerOfMass(model, data, q)[:2]) for q in named.values())
    print(f"Support polygon: {len(polygon)} vertices; zero-pose stability margin {polygon_margin(polygon, com0[:2]):.4f} m")
    print(f"Smallest margin, arm stretched horizontally in any direction: {stretched_margin:.4f} m")
    print(f"Smallest margin over all {len(configs)} configurations: {worst_margin:.4f} m ({worst_name})")
    if worst_margin <= 0:
        problems.append(f"COM leaves the support polygon ({worst_name}: margin {worst_margin:.4f} m)")

    print()
    if problems:
        print("FAIL:")
        for problem in problems:
            print(f"  - {problem}")
        return 1
    print(f"PASS: inertias valid, every effort >= {MIN_RATIO} x max gravity torque, statically stable")
    return 0


if __name__ == "__main__":
    sys.exit(main())
