#!/usr/bin/env python3
"""Oracle: the true maximum reach of real robot arms, by numerical optimisation (issue 5).

Used to test the Rust Monte Carlo workspace sampler: its max reach must be within 0.5 % of this
value and never above it. Dev-only tooling (Pinocchio + SciPy); the validator never depends on it,
the Rust tests only read the JSON goldens in `crates/urdf-validator/tests/golden/reach/`.

Regenerate (repo root; venv `.venv-oracle` as in scripts/oracle/README.md, plus SciPy):

    python3 -m venv .venv-oracle
    .venv-oracle/bin/pip install pin==4.1.0 example-robot-data==6.0.0 scipy==1.17.1
    .venv-oracle/bin/python scripts/oracle/max_reach.py          # ur5, panda, z1, kinova (~40 s, 2 cores)
    # options: --robot NAME (repeatable; default all four)  --corpus DIR  --out DIR  --seed S (default 5)
    #          --starts N (200)  --samples N (100000)  --sampled-starts N (20)  --mc N (1000000)
    #          --urdf PATH --root-joint J --name NAME   (any other URDF; PATH relative to --corpus or absolute)

Metric
------
Robot root fixed at the identity (`pinocchio.buildModelFromUrdf(path)`: fixed base, no root joint,
even for robots that also ship a free-flyer). For a root joint J (the arm's first actuated joint:
every joint between the URDF root link and J is `fixed`, so J's frame origin p_J does not move) and
every link L of the subtree below J (J's child link and all its descendants, through fixed and
actuated joints, fingers included):

    max_reach(L) = max_q |p_L(q) - p_J|

p_L = world position of L's frame origin (Pinocchio BODY frame named after the link), q ranges over
the actuated joints on the path J -> L, each within its URDF limits: revolute/prismatic with finite
lower < upper -> [lower, upper]; continuous (and revolute without usable limits) -> [-pi, pi];
prismatic without usable limits -> [-0.1, 0.1]. Joints off the path do not move L. Mimic joints are
respected: a follower is `multiplier * q_leader + offset` (chains resolved), the decision variable is
the leader (even when the leader itself is off the path, e.g. panda_rightfinger follows
panda_finger_joint1), and the leader's interval is intersected with every follower's limits so the
follower stays within its own limits too. The value is frame-independent (distance).

Optimiser
---------
Per link, maximise 0.5*|p_L - p_J|^2 (smooth; same argmax) with the analytic gradient from
Pinocchio's frame Jacobian (LOCAL_WORLD_ALIGNED, linear rows, chain rule through mimics):
  * starts: --starts (200) uniform random points in the box, plus the --sampled-starts (20) best of
    --samples (100,000) uniform random configurations (evaluated with a vectorised numpy forward
    kinematics that is cross-checked against Pinocchio to 1e-12 m);
  * each start: scipy L-BFGS-B with the box bounds, ftol 1e-15, gtol 1e-12, maxiter 5000;
  * polish the best: SLSQP (ftol 1e-16, bounds) then L-BFGS-B again; the best of all is kept;
  * reported: `starts_at_max` = how many starts ended within 1e-6 m of the maximum (a maximum that
    many independent starts reach is a global one), the projected-gradient norm at the maximum,
    and `limits_at_max`: every non-continuous variable at a bound (within 1e-7), with d(reach)/dq and
    `binding` = true when the reach would grow past that bound (|d reach/dq| > 1e-6 pointing
    outwards), i.e. the reach is attained *because of* a joint limit.
Sanity check (fails the run if violated): a Monte Carlo of --mc (1,000,000) uniform configurations
(separate seed stream) never exceeds the optimum by more than 1e-9 m; its max and the margin
optimum - MC max are stored per link (`mc`) and printed with the table.

Output: one JSON per robot, `<out>/<name>.json`: robot, urdf (relative to the example-robot-data
robots dir), root_joint, root_joint_origin_world, variables (joint -> interval, type, followers),
and `links` (subtree order) -> {max_reach_m, q_at_max (every actuated path joint and leader, rad or
m), path_joints, limits_at_max, reach_limited_by_joint_limit, starts_at_max, projected_gradient_norm,
mc {samples, max_reach_m, margin_m, relative_gap}}. Deterministic for a given seed and library set.
"""

from __future__ import annotations

import argparse
import importlib.metadata
import json
import math
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin
import scipy
from scipy.optimize import minimize

REPO_ROOT = Path(__file__).resolve().parents[2]
DEFAULT_OUT = REPO_ROOT / "crates" / "urdf-validator" / "tests" / "golden" / "reach"
CORPUS_SUBDIR = "cmeel.prefix/share/example-robot-data/robots"
ACTUATED = ("revolute", "continuous", "prismatic")

# name -> (URDF relative to the example-robot-data robots dir, root joint J)
ROBOTS = {
    "ur5": ("ur_description/urdf/ur5_robot.urdf", "shoulder_pan_joint"),
    "panda": ("panda_description/urdf/panda.urdf", "panda_joint1"),
    "z1": ("z1_description/urdf/z1.urdf", "joint1"),
    "kinova": ("kinova_description/robots/kinova.urdf", "j2s6s200_joint_1"),
}

AT_MAX_TOL_M = 1e-6  # a start "reaches the maximum" when within this of it
AT_LIMIT_TOL = 1e-7  # a variable is "at a limit" when within this of a bound
BINDING_GRAD = 1e-6  # |d reach / dq| (m per rad or m/m) above which a limit is binding
MC_TOL_M = 1e-9  # Monte Carlo may exceed the optimum by at most this (float noise)
FK_CHECK_TOL_M = 1e-12
MC_CHUNK = 100_000


# --------------------------------------------------------------------------------------------------
# URDF reading
# --------------------------------------------------------------------------------------------------
def default_corpus() -> Path:
    try:
        candidate = Path(importlib.metadata.distribution("example-robot-data").locate_file(CORPUS_SUBDIR))
        if candidate.is_dir():
            return candidate
    except importlib.metadata.PackageNotFoundError:
        pass
    for candidate in sorted((Path(sys.prefix) / "lib").glob(f"python3*/site-packages/{CORPUS_SUBDIR}")):
        if candidate.is_dir():
            return candidate
    sys.exit("max_reach: cannot find the example-robot-data corpus; install example-robot-data==6.0.0 or pass --corpus")


def _vec(text: str | None, default: list[float]) -> np.ndarray:
    return np.array([float(t) for t in text.split()] if text else default, dtype=float)


def _opt_float(text: str | None) -> float | None:
    try:
        return float(text) if text is not None else None
    except ValueError:
        return None


def read_urdf(path: Path) -> dict:
    root = ET.parse(path).getroot()
    links = [link.get("name") for link in root.findall("link")]
    joints: dict[str, dict] = {}
    for el in root.findall("joint"):  # top level only (not <transmission><joint>)
        origin = el.find("origin")
        axis = el.find("axis")
        limit = el.find("limit")
        mimic = el.find("mimic")
        j = {
            "type": el.get("type"),
            "parent": el.find("parent").get("link"),
            "child": el.find("child").get("link"),
            "xyz": _vec(origin.get("xyz") if origin is not None else None, [0.0, 0.0, 0.0]),
            "rpy": _vec(origin.get("rpy") if origin is not None else None, [0.0, 0.0, 0.0]),
            "axis": _vec(axis.get("xyz") if axis is not None else None, [1.0, 0.0, 0.0]),
            "lower": _opt_float(limit.get("lower")) if limit is not None else None,
            "upper": _opt_float(limit.get("upper")) if limit is not None else None,
            "mimic": None,
        }
        if mimic is not None:
            j["mimic"] = {
                "joint": mimic.get("joint"),
                "multiplier": _opt_float(mimic.get("multiplier")) if mimic.get("multiplier") is not None else 1.0,
                "offset": _opt_float(mimic.get("offset")) if mimic.get("offset") is not None else 0.0,
            }
        joints[el.get("name")] = j
    return {"links": links, "joints": joints}


def sample_range(j: dict) -> tuple[float, float]:
    lo, hi = j["lower"], j["upper"]
    if j["type"] == "continuous":
        return (-math.pi, math.pi)
    if lo is not None and hi is not None and math.isfinite(lo) and math.isfinite(hi) and lo < hi:
        return (lo, hi)
    return (-math.pi, math.pi) if j["type"] == "revolute" else (-0.1, 0.1)


def has_usable_limits(j: dict) -> bool:
    lo, hi = j["lower"], j["upper"]
    return (j["type"] != "continuous" and lo is not None and hi is not None
            and math.isfinite(lo) and math.isfinite(hi) and lo < hi)


def resolve_leader(joints: dict, name: str) -> tuple[str, float, float]:
    """(independent leader, a, b) with q_name = a * q_leader + b; (name, 1, 0) if independent.

    A mimic whose leader is missing / not actuated / on a cycle is treated as independent."""
    a, b, cur, seen = 1.0, 0.0, name, {name}
    while True:
        m = joints[cur]["mimic"]
        if m is None or m["joint"] not in joints or joints[m["joint"]]["type"] not in ACTUATED:
            return cur, a, b
        nxt = m["joint"]
        if nxt in seen:  # cycle: give up, the original joint is independent
            return name, 1.0, 0.0
        seen.add(nxt)
        # q_cur = mult * q_nxt + off ; q_name = a * q_cur + b
        a, b = a * m["multiplier"], a * m["offset"] + b
        cur = nxt


def rpy_matrix(rpy: np.ndarray) -> np.ndarray:
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


# --------------------------------------------------------------------------------------------------
# Problem set-up
# --------------------------------------------------------------------------------------------------
class Arm:
    def __init__(self, urdf_path: Path, root_joint: str):
        self.urdf = read_urdf(urdf_path)
        joints = self.urdf["joints"]
        if root_joint not in joints or joints[root_joint]["type"] not in ACTUATED:
            sys.exit(f"max_reach: {root_joint!r} is not an actuated joint of {urdf_path}")
        self.root_joint = root_joint
        parent_joint = {j["child"]: name for name, j in joints.items()}
        # J must be the first actuated joint from the root: only fixed joints above it.
        link = joints[root_joint]["parent"]
        while link in parent_joint:
            pj = parent_joint[link]
            if joints[pj]["type"] in ACTUATED:
                sys.exit(f"max_reach: {root_joint!r} has actuated ancestor {pj!r}; its origin would move")
            link = joints[pj]["parent"]
        self.parent_joint = parent_joint

        # Subtree below J in URDF document order of joints (parents before children: BFS).
        children: dict[str, list[str]] = {}
        for name, j in joints.items():
            children.setdefault(j["parent"], []).append(name)
        self.tree_joints: list[str] = []  # every joint of the subtree, parents first
        frontier = [root_joint]
        while frontier:
            nxt = []
            for jn in frontier:
                self.tree_joints.append(jn)
                nxt.extend(children.get(joints[jn]["child"], []))
            frontier = nxt
        self.links = [joints[jn]["child"] for jn in self.tree_joints]

        # Decision variables: independent leaders of the actuated joints of the subtree.
        self.follow: dict[str, tuple[str, float, float]] = {}
        for jn in self.tree_joints:
            if joints[jn]["type"] in ACTUATED:
                self.follow[jn] = resolve_leader(joints, jn)
        leaders = []
        for jn in self.follow.values():
            if jn[0] not in leaders:
                leaders.append(jn[0])
        self.vars = leaders
        self.bounds: dict[str, tuple[float, float]] = {}
        for v in self.vars:
            lo, hi = sample_range(joints[v])
            # Followers within their own limits: a*q + b in [flo, fhi] -> interval on q.
            for fj, (leader, a, b) in self.follow.items():
                if leader != v or fj == v or not has_usable_limits(joints[fj]) or a == 0.0:
                    continue
                flo, fhi = (joints[fj]["lower"] - b) / a, (joints[fj]["upper"] - b) / a
                lo, hi = max(lo, min(flo, fhi)), min(hi, max(flo, fhi))
            if not lo < hi:
                sys.exit(f"max_reach: empty interval for {v} after intersecting with its mimic followers")
            self.bounds[v] = (lo, hi)

        # Path J -> L (actuated joints) and the variables that move L.
        self.path: dict[str, list[str]] = {}
        for link in self.links:
            path, cur = [], link
            while True:
                jn = parent_joint[cur]
                path.append(jn)
                if jn == root_joint:
                    break
                cur = joints[jn]["parent"]
            self.path[link] = [jn for jn in reversed(path) if joints[jn]["type"] in ACTUATED]

        # Pinocchio model: fixed base.
        self.model = pin.buildModelFromUrdf(str(urdf_path))
        self.data = self.model.createData()
        self.q0 = pin.neutral(self.model)
        self.jid = {jn: self.model.getJointId(jn) for jn in self.follow}
        for jn, i in self.jid.items():
            if i >= self.model.njoints:
                sys.exit(f"max_reach: Pinocchio has no joint {jn}")
            if self.model.joints[i].nv != 1:
                sys.exit(f"max_reach: joint {jn} has nv != 1")
        self.fid = {}
        for link in self.links:
            fid = self.model.getFrameId(link, pin.BODY)
            if fid >= len(self.model.frames):
                sys.exit(f"max_reach: Pinocchio has no BODY frame {link}")
            self.fid[link] = fid
        pin.forwardKinematics(self.model, self.data, self.q0)
        self.pJ = self.data.oMi[self.jid[root_joint]].translation.copy()
        pin.updateFramePlacements(self.model, self.data)
        parent_fid = self.model.getFrameId(joints[root_joint]["parent"], pin.BODY)
        self.parent_world = self.data.oMf[parent_fid].copy()  # J's parent link frame (constant)

        # numpy FK constants
        self.origin_R = {jn: rpy_matrix(joints[jn]["rpy"]) for jn in self.tree_joints}
        self.axis = {}
        for jn in self.tree_joints:
            ax = joints[jn]["axis"]
            n = np.linalg.norm(ax)
            self.axis[jn] = ax / n if n > 0 else np.array([1.0, 0.0, 0.0])

    # ---------------------------------------------------------------- joint values from variables
    def joint_values(self, x: dict[str, np.ndarray | float]) -> dict:
        return {jn: a * x[leader] + b for jn, (leader, a, b) in self.follow.items()}

    # ---------------------------------------------------------------- vectorised numpy FK
    def batch_positions(self, x: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Positions (N, 3) of every subtree link in J's parent link frame."""
        joints = self.urdf["joints"]
        n = len(next(iter(x.values())))
        qv = self.joint_values(x)
        parent_link = joints[self.root_joint]["parent"]
        R = {parent_link: np.broadcast_to(np.eye(3), (n, 3, 3))}
        p = {parent_link: np.zeros((n, 3))}
        for jn in self.tree_joints:
            j = joints[jn]
            Rp, pp = R[j["parent"]], p[j["parent"]]
            Ro = Rp @ self.origin_R[jn]  # (n,3,3)
            pc = pp + Rp @ j["xyz"]
            if j["type"] in ("revolute", "continuous"):
                k = self.axis[jn]
                th = qv[jn]
                K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
                Rq = (np.eye(3)[None] + np.sin(th)[:, None, None] * K[None]
                      + (1 - np.cos(th))[:, None, None] * (K @ K)[None])
                Rc = Ro @ Rq
            elif j["type"] == "prismatic":
                Rc = Ro
                pc = pc + (Ro @ self.axis[jn]) * qv[jn][:, None]
            else:
                Rc = Ro
            R[j["child"]], p[j["child"]] = Rc, pc
        return {link: p[link] for link in self.links}

    def batch_reach(self, x: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        pJ_local = self.urdf["joints"][self.root_joint]["xyz"]
        return {link: np.linalg.norm(pos - pJ_local, axis=1) for link, pos in self.batch_positions(x).items()}

    def sample(self, rng: np.random.Generator, n: int) -> dict[str, np.ndarray]:
        return {v: rng.uniform(*self.bounds[v], size=n) for v in self.vars}  # fixed order: self.vars

    # ---------------------------------------------------------------- Pinocchio objective
    def full_q(self, values: dict[str, float]) -> np.ndarray:
        q = self.q0.copy()
        for jn, val in values.items():
            jm = self.model.joints[self.jid[jn]]
            if jm.nq == 2:  # continuous: (cos, sin)
                q[jm.idx_q], q[jm.idx_q + 1] = math.cos(val), math.sin(val)
            else:
                q[jm.idx_q] = val
        return q

    def link_problem(self, link: str):
        """(variables, bounds, f(x) -> (-0.5 d^2, grad), reach(x))."""
        path = self.path[link]
        lvars = [v for v in self.vars if any(self.follow[jn][0] == v for jn in path)]
        fid = self.fid[link]
        model, data = self.model, self.data
        # d v_j / d x_k
        cols = []
        for jn in path:
            leader, a, _ = self.follow[jn]
            cols.append((self.model.joints[self.jid[jn]].idx_v, lvars.index(leader), a))

        def values(x):
            xd = dict(zip(lvars, x))
            return {jn: a * xd[leader] + b for jn, (leader, a, b) in self.follow.items() if jn in path}

        def fun(x):
            q = self.full_q(values(x))
            pin.computeJointJacobians(model, data, q)
            pin.updateFramePlacement(model, data, fid)
            d = data.oMf[fid].translation - self.pJ
            Jl = pin.getFrameJacobian(model, data, fid, pin.LOCAL_WORLD_ALIGNED)[:3]
            g = np.zeros(len(lvars))
            for iv, k, a in cols:
                g[k] += a * (d @ Jl[:, iv])
            return -0.5 * float(d @ d), -g

        def reach(x):
            q = self.full_q(values(x))
            pin.forwardKinematics(model, data, q)
            pin.updateFramePlacement(model, data, fid)
            return float(np.linalg.norm(data.oMf[fid].translation - self.pJ))

        return lvars, [self.bounds[v] for v in lvars], fun, reach, values


# --------------------------------------------------------------------------------------------------
# Optimisation
# --------------------------------------------------------------------------------------------------
def optimise_link(arm: Arm, link: str, rng, samples: dict, sample_reach: np.ndarray, n_starts: int, n_sampled: int):
    lvars, bounds, fun, reach, values = arm.link_problem(link)
    if not lvars:  # cannot happen for a link below an actuated J, kept for safety
        r = reach(np.zeros(0))
        return {"max_reach_m": r, "q_at_max": {}, "lvars": [], "starts_at_max": "0/0", "pg": 0.0, "limits": []}
    lo = np.array([b[0] for b in bounds])
    hi = np.array([b[1] for b in bounds])
    starts = [lo + (hi - lo) * rng.random(len(lvars)) for _ in range(n_starts)]
    order = np.argsort(-sample_reach, kind="stable")
    for i in order[:n_sampled]:
        starts.append(np.array([samples[v][i] for v in lvars]))
    opts = {"ftol": 1e-15, "gtol": 1e-12, "maxiter": 5000, "maxfun": 50000}
    results = []
    for x0 in starts:
        res = minimize(fun, x0, jac=True, method="L-BFGS-B", bounds=bounds, options=opts)
        x = np.clip(res.x, lo, hi)
        results.append((reach(x), x))
    best_r, best_x = max(results, key=lambda t: t[0])
    # polish
    cand = [(best_r, best_x)]
    res = minimize(fun, best_x, jac=True, method="SLSQP", bounds=bounds, options={"ftol": 1e-16, "maxiter": 1000})
    x = np.clip(res.x, lo, hi)
    cand.append((reach(x), x))
    res = minimize(fun, x, jac=True, method="L-BFGS-B", bounds=bounds, options=opts)
    x = np.clip(res.x, lo, hi)
    cand.append((reach(x), x))
    best_r, best_x = max(cand, key=lambda t: t[0])
    hits = sum(1 for r, _ in results if r >= best_r - AT_MAX_TOL_M)

    # gradient of the reach (not squared) at the maximum; projected gradient for maximisation
    _, g = fun(best_x)
    g_reach = -g / best_r if best_r > 0 else -g  # d reach / dx
    pg = g_reach.copy()
    limits = []
    for k, v in enumerate(lvars):
        at_lo, at_hi = best_x[k] - lo[k] <= AT_LIMIT_TOL, hi[k] - best_x[k] <= AT_LIMIT_TOL
        if arm.urdf["joints"][v]["type"] == "continuous":
            at_lo = at_hi = False  # +-pi is no limit for a full turn (the reach is 2*pi-periodic there)
        if at_hi and pg[k] > 0 or at_lo and pg[k] < 0:
            pg[k] = 0.0  # pushing outwards against an active bound
        if at_lo or at_hi:
            outward = g_reach[k] if at_hi else -g_reach[k]
            limits.append({
                "joint": v,
                "bound": "upper" if at_hi else "lower",
                "value": float(best_x[k]),
                "d_reach_dq": float(g_reach[k]),
                "binding": bool(outward > BINDING_GRAD),
            })
    q_at_max = {jn: float(val) for jn, val in values(best_x).items()}
    for k, v in enumerate(lvars):
        q_at_max.setdefault(v, float(best_x[k]))  # an off-path mimic leader
    return {
        "max_reach_m": best_r,
        "q_at_max": q_at_max,
        "lvars": lvars,
        "starts_at_max": f"{hits}/{len(starts)}",
        "pg": float(np.linalg.norm(pg)),
        "limits": limits,
    }


def run_robot(name: str, urdf_rel: str, urdf_path: Path, root_joint: str, args) -> tuple[dict, list, list]:
    t0 = time.time()
    arm = Arm(urdf_path, root_joint)
    seed_seq = np.random.SeedSequence(args.seed)
    rng_samples, rng_starts, rng_mc, rng_check = (np.random.default_rng(s) for s in seed_seq.spawn(4))

    # Cross-check numpy FK against Pinocchio (world positions) and the gradient against finite differences.
    chk = arm.sample(rng_check, 20)
    pos = arm.batch_positions(chk)
    R0, t0w = arm.parent_world.rotation, arm.parent_world.translation
    worst = 0.0
    for i in range(20):
        vals = arm.joint_values({v: chk[v][i] for v in arm.vars})
        pin.framesForwardKinematics(arm.model, arm.data, arm.full_q(vals))
        for link in arm.links:
            w = R0 @ pos[link][i] + t0w
            worst = max(worst, float(np.linalg.norm(w - arm.data.oMf[arm.fid[link]].translation)))
    if worst > FK_CHECK_TOL_M:
        sys.exit(f"max_reach: {name}: numpy FK disagrees with Pinocchio by {worst:.3e} m")
    grad_err = 0.0
    for link in arm.links:
        lvars, bounds, fun, _, _ = arm.link_problem(link)
        if not lvars:
            continue
        x = np.array([chk[v][0] for v in lvars])
        f0, g = fun(x)
        for k in range(len(lvars)):
            e = np.zeros(len(lvars))
            e[k] = 1e-6
            fd = (fun(x + e)[0] - fun(x - e)[0]) / 2e-6
            grad_err = max(grad_err, abs(fd - g[k]))
    if grad_err > 1e-7:
        sys.exit(f"max_reach: {name}: analytic gradient disagrees with finite differences by {grad_err:.3e}")

    samples = arm.sample(rng_samples, args.samples)
    sample_reach = arm.batch_reach(samples)

    per_link = {}
    for link in arm.links:
        per_link[link] = optimise_link(arm, link, rng_starts, samples, sample_reach[link],
                                       args.starts, args.sampled_starts)

    # Monte Carlo sanity check
    mc_max = {link: 0.0 for link in arm.links}
    done = 0
    while done < args.mc:
        n = min(MC_CHUNK, args.mc - done)
        r = arm.batch_reach(arm.sample(rng_mc, n))
        for link in arm.links:
            mc_max[link] = max(mc_max[link], float(r[link].max()))
        done += n

    joints = arm.urdf["joints"]
    out_links = {}
    rows = []
    failures = []
    for link in arm.links:
        res = per_link[link]
        opt = res["max_reach_m"]
        margin = opt - mc_max[link]
        if margin < -MC_TOL_M:
            failures.append(f"{name}/{link}: Monte Carlo {mc_max[link]!r} > optimum {opt!r}")
        rel = margin / opt if opt > 0 else 0.0
        out_links[link] = {
            "max_reach_m": opt,
            "q_at_max": res["q_at_max"],
            "path_joints": arm.path[link],
            "variables": res["lvars"],
            "limits_at_max": res["limits"],
            "reach_limited_by_joint_limit": any(l["binding"] for l in res["limits"]),
            "starts_at_max": res["starts_at_max"],
            "projected_gradient_norm": res["pg"],
            "mc": {"samples": args.mc, "max_reach_m": mc_max[link], "margin_m": margin, "relative_gap": rel},
        }
        rows.append((name, root_joint, link, opt, mc_max[link], margin, rel, res["starts_at_max"],
                     ",".join(f"{l['joint']}@{l['bound']}" for l in res["limits"] if l["binding"]) or "-"))

    doc = {
        "robot": name,
        "urdf": urdf_rel,
        "root_joint": root_joint,
        "root_joint_origin_world": [float(v) for v in arm.pJ],
        "metric": "max over q (path joints within limits, continuous in [-pi, pi], mimics respected) of "
                  "|p_L(q) - p_J|, p = world position of the link / joint frame origin, fixed base at identity",
        "generator": {
            "script": "scripts/oracle/max_reach.py",
            "pin": pin.__version__,
            "scipy": scipy.__version__,
            "numpy": np.__version__,
            "example_robot_data": _version("example-robot-data"),
            "seed": args.seed,
            "random_starts": args.starts,
            "sampled_starts": args.sampled_starts,
            "samples_for_starts": args.samples,
            "optimiser": "L-BFGS-B (ftol 1e-15, gtol 1e-12) per start; polish SLSQP (ftol 1e-16) + L-BFGS-B",
            "fk_check_max_error_m": worst,
            "gradient_check_max_error": grad_err,
        },
        "variables": {
            v: {
                "type": joints[v]["type"],
                "interval": list(arm.bounds[v]),
                "followers": {fj: {"multiplier": a, "offset": b}
                              for fj, (leader, a, b) in arm.follow.items() if leader == v and fj != v},
            }
            for v in arm.vars
        },
        "links": out_links,
    }
    print(f"# {name}: {len(arm.links)} links, {time.time() - t0:.1f} s, FK check {worst:.1e} m, "
          f"gradient check {grad_err:.1e}", file=sys.stderr)
    return doc, rows, failures


def _version(dist: str) -> str | None:
    try:
        return importlib.metadata.version(dist)
    except importlib.metadata.PackageNotFoundError:
        return None


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--robot", action="append", choices=sorted(ROBOTS), help="robot(s) to run (default: all)")
    parser.add_argument("--urdf", help="other URDF (relative to --corpus, or absolute); needs --root-joint, --name")
    parser.add_argument("--root-joint")
    parser.add_argument("--name")
    parser.add_argument("--corpus", type=Path, default=None, help="example-robot-data robots dir")
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT)
    parser.add_argument("--seed", type=int, default=5)
    parser.add_argument("--starts", type=int, default=200, help="uniform random starts per link (default 200)")
    parser.add_argument("--samples", type=int, default=100_000, help="random samples to pick starts from")
    parser.add_argument("--sampled-starts", type=int, default=20, help="best samples used as starts (default 20)")
    parser.add_argument("--mc", type=int, default=1_000_000, help="Monte Carlo check samples (default 1e6)")
    args = parser.parse_args()
    corpus = args.corpus or default_corpus()

    jobs = []
    if args.urdf:
        if not (args.root_joint and args.name):
            parser.error("--urdf needs --root-joint and --name")
        p = Path(args.urdf)
        path = p if p.is_absolute() else corpus / p
        rel = str(path.relative_to(corpus)) if path.is_relative_to(corpus) else str(path)
        jobs.append((args.name, rel, path, args.root_joint))
    else:
        for name in args.robot or list(ROBOTS):
            rel, j = ROBOTS[name]
            jobs.append((name, rel, corpus / rel, j))

    args.out.mkdir(parents=True, exist_ok=True)
    all_rows, all_failures = [], []
    for name, rel, path, j in jobs:
        doc, rows, failures = run_robot(name, rel, path, j, args)
        (args.out / f"{name}.json").write_text(json.dumps(doc, indent=2) + "\n")
        all_rows += rows
        all_failures += failures

    hdr = ("robot", "root joint", "link", "max reach [m]", "MC max [m]", "margin [m]", "gap %", "starts@max", "binding limits")
    print("| " + " | ".join(hdr) + " |")
    print("|" + "---|" * len(hdr))
    for r in all_rows:
        print(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:.9f} | {r[4]:.9f} | {r[5]:.3e} | {100 * r[6]:.4f} | {r[7]} | {r[8]} |")
    if all_failures:
        print("\nMONTE CARLO EXCEEDS OPTIMUM:\n" + "\n".join(all_failures), file=sys.stderr)
        return 1
    min_margin = min(r[5] for r in all_rows)
    print(f"\nMonte Carlo check passed: min margin (optimum - MC max) = {min_margin:.3e} m over {len(all_rows)} links")
    return 0


if __name__ == "__main__":
    sys.exit(main())
