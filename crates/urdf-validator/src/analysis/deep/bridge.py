"""The MuJoCo side of urdf_validate --deep (embedded in the Rust binary, run as `python -c`).

Reads one job as JSON on stdin and writes one reply as JSON on the original stdout. It never lets a
traceback out: every failure becomes {"ok": false, "kind": ..., "message": ...}. Anything MuJoCo (or
Python) prints goes to stderr, so stdout carries the reply alone.

The job (built by crates/urdf-validator/src/analysis/deep/job.rs):
  urdf            the URDF text, mesh filenames rewritten to the names in `assets`; or
  mjcf            the path of an MJCF file MuJoCo loads itself (includes, meshdir, defaults its own): its
                  own floor, contacts and joints kept, its actuators silenced for the drop test's servos
  assets          [{name, path}] a file MuJoCo reads as it is, or [{name, hull: {vertices, triangles}}]
                  a convex hull written here as binary STL
  fallbacks       [{when, kind, ...}]: what to change when MuJoCo's compile error contains `when`
  mimic           [{follower, leader, multiplier, offset}]: <mimic> as joint equality constraints
  root, fixed_base, payload {link, mass} | null
  configurations  [{label, q: {joint: value}}]: gravity forces and COM at each
  drop            {duration, timestep, height, omega_dt, saturation, integral_rate, q,
                  servos: [{joint, effort}], trace_points} | null

The reply: ok, mujoco_version, attempts [{error, applied}], model {bodies, joints}, crosscheck
[{label, qfrc_bias, com, body_pos}], drop {...} or drop_error. The drop names links, not MuJoCo bodies
(fused links have none): `start_clearance_m` {link: height of its lowest point above the robot's at the
release}, `ground_links_end` [links touching the floor at the last step], `tilt_trace` [[t, degrees]].

Names: an unnamed MuJoCo body is `body#ID`, an unnamed joint `joint#ID` (as the MJCF reader names them);
a ball joint NAME is the validator's three hinges NAME_x, NAME_y, NAME_z (rotations about the body's x,
then y, then z axes): their values make its quaternion, their gravity forces are its three dofs' read
along those hinges' axes.
"""

import json
import math
import os
import struct
import sys
import time

_REPLY = None


def reply(obj):
    _REPLY.write(json.dumps(obj, allow_nan=False, default=float))
    _REPLY.flush()


def finite(x):
    x = float(x)
    return x if math.isfinite(x) else None


def vec(a):
    return [finite(v) for v in a]


def stl_bytes(hull):
    """A binary STL of a hull's triangles."""
    vertices = hull["vertices"]
    triangles = hull["triangles"]
    out = [b"urdf_validate hull".ljust(80, b" "), struct.pack("<I", len(triangles))]
    for tri in triangles:
        a, b, c = (vertices[i] for i in tri)
        out.append(struct.pack("<3f", 0.0, 0.0, 0.0))
        for p in (a, b, c):
            out.append(struct.pack("<3f", *p))
        out.append(b"\0\0")
    return b"".join(out)


def find_body(spec, name):
    """A body by name, or an unnamed one by its `body#ID`."""
    finder = getattr(spec, "body", None) or getattr(spec, "find_body")
    body = finder(name)
    if body is None and name.startswith("body#") and name[5:].isdigit():
        bodies = list(spec.bodies)  # the world first, then depth first: MuJoCo's body ids
        if int(name[5:]) < len(bodies):
            body = bodies[int(name[5:])]
    return body


def load_spec(mujoco, job):
    assets = {}
    for asset in job["assets"]:
        if "path" in asset:
            with open(asset["path"], "rb") as f:
                assets[asset["name"]] = f.read()
        else:
            assets[asset["name"]] = stl_bytes(asset["hull"])
    if "mjcf" in job:
        return mujoco.MjSpec.from_file(job["mjcf"])
    return mujoco.MjSpec.from_string(job["urdf"], assets=assets)


def world_planes(mujoco, spec):
    """The planes of the world body (not of a moving body): an MJCF model's own ground."""
    return [g for g in spec.worldbody.geoms if g.type == mujoco.mjtGeom.mjGEOM_PLANE]


def add_extras(mujoco, spec, job, drop):
    """Mimic equalities, the payload, the root's free joint, the COM sensor, and for the drop test a
    floor and one servo per actuated joint (of an MJCF model, per joint its own actuators drive). The
    servos, and the index of the first (the model's own actuators come before it)."""
    for m in job["mimic"]:
        eq = spec.add_equality()
        eq.type = mujoco.mjtEq.mjEQ_JOINT
        eq.objtype = mujoco.mjtObj.mjOBJ_JOINT
        eq.name1 = m["follower"]
        eq.name2 = m["leader"]
        data = list(eq.data)
        data[0:5] = [m["offset"], m["multiplier"], 0.0, 0.0, 0.0]
        eq.data = data
    payload = job.get("payload")
    if payload:
        holder = find_body(spec, payload["link"])
        body = holder.add_body()
        body.name = "urdf_validate_payload"
        body.mass = payload["mass"]
        tiny = max(payload["mass"], 1e-9) * 1e-8
        body.inertia = [tiny, tiny, tiny]
        body.explicitinertial = True
    mjcf = "mjcf" in job
    if not job["fixed_base"] and not mjcf:
        find_body(spec, job["root"]).add_freejoint()
    if not mjcf:
        # Naming the root in a sensor keeps it out of fusestatic (on for URDF, which would drop a fixed
        # root's mass).
        sensor = spec.add_sensor()
        sensor.type = mujoco.mjtSensor.mjSENS_SUBTREECOM
        sensor.objtype = mujoco.mjtObj.mjOBJ_BODY
        sensor.objname = job["root"]
    if drop and not mjcf:
        for geom in spec.geoms:
            # Only the floor collides with the robot: links in contact at the start would explode.
            geom.contype = 1
            geom.conaffinity = 0
        # Each geom named after its link, which survives `fusestatic` (the body does not).
        for body in spec.bodies:
            for index, geom in enumerate(body.geoms):
                geom.name = "%s%s/%d" % (GEOM_PREFIX, body.name, index)
    if drop and not job["fixed_base"] and not (mjcf and world_planes(mujoco, spec)):
        floor = spec.worldbody.add_geom()
        floor.name = "urdf_validate_floor"
        floor.type = mujoco.mjtGeom.mjGEOM_PLANE
        floor.size = [0.0, 0.0, 1.0]
        floor.contype = 0
        floor.conaffinity = 1
    servos = []
    first = len(spec.actuators)
    if drop:
        servos = drop["servos"]
        if mjcf:
            driven = {
                a.target for a in spec.actuators
                if a.trntype in (mujoco.mjtTrn.mjTRN_JOINT, mujoco.mjtTrn.mjTRN_JOINTINPARENT)
            }
            servos = [s for s in servos if s["joint"] in driven]
        for servo in servos:
            act = spec.add_actuator()
            act.name = "urdf_validate_servo_" + servo["joint"]
            act.trntype = mujoco.mjtTrn.mjTRN_JOINT
            act.target = servo["joint"]
            # Every setting explicit: an MJCF model's default class (ctrlrange, gear, dynamics) is not ours.
            act.gear = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]
            act.dyntype = mujoco.mjtDyn.mjDYN_NONE
            act.ctrllimited = mujoco.mjtLimited.mjLIMITED_FALSE
            act.actlimited = mujoco.mjtLimited.mjLIMITED_FALSE
            act.forcelimited = mujoco.mjtLimited.mjLIMITED_FALSE
            act.gaintype = mujoco.mjtGain.mjGAIN_FIXED
            act.biastype = mujoco.mjtBias.mjBIAS_AFFINE
            gain = list(act.gainprm)
            gain[0] = 1.0
            act.gainprm = gain
            bias = list(act.biasprm)
            bias[0:3] = [0.0, -1.0, 0.0]
            act.biasprm = bias
            if servo["effort"] is not None:
                act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
                act.forcerange = [-servo["effort"], servo["effort"]]
    return servos, first


GEOM_PREFIX = "urdf_validate_link/"


def link_of_geom(mujoco, m, g, mjcf):
    """The link a robot geom belongs to: an MJCF geom's body, a URDF geom's link (its name, given in
    add_extras); None for what is not the robot's."""
    if mjcf:
        body = int(m.geom_bodyid[g])
        return name_of(mujoco, m, mujoco.mjtObj.mjOBJ_BODY, body) if m.body_weldid[body] else None
    name = name_of(mujoco, m, mujoco.mjtObj.mjOBJ_GEOM, g)
    if not name.startswith(GEOM_PREFIX):
        return None
    return name[len(GEOM_PREFIX):].rsplit("/", 1)[0]


def apply_fallback(mujoco, spec, fallback):
    kind = fallback["kind"]
    if kind == "inertia":
        for fix in fallback["links"]:
            find_body(spec, fix["link"]).fullinertia = fix["fullinertia"]
    elif kind == "bound":
        spec.compiler.boundmass = fallback["mass"]
        spec.compiler.boundinertia = fallback["inertia"]


def compile_model(mujoco, job, drop):
    """Compile, applying each fallback once when MuJoCo's error names its case."""
    attempts = []
    applied = set()
    while True:
        spec = load_spec(mujoco, job)
        for index in sorted(applied):
            apply_fallback(mujoco, spec, job["fallbacks"][index])
        servos, first = add_extras(mujoco, spec, job, drop)
        try:
            return spec.compile(), attempts, (servos, first)
        except Exception as error:  # MuJoCo raises ValueError with its own message
            message = str(error)
            for index, fallback in enumerate(job["fallbacks"]):
                if index not in applied and fallback["when"] in message:
                    applied.add(index)
                    attempts.append({"error": message, "applied": fallback["kind"]})
                    break
            else:
                attempts.append({"error": message, "applied": None})
                return None, attempts, ([], 0)


def name_of(mujoco, m, objtype, index):
    """The element's name; an unnamed body or joint as the MJCF reader names it (`body#ID`, `joint#ID`)."""
    name = mujoco.mj_id2name(m, objtype, index)
    if name:
        return name
    if objtype == mujoco.mjtObj.mjOBJ_BODY:
        return "body#%d" % index if index else "world"
    if objtype == mujoco.mjtObj.mjOBJ_JOINT:
        return "joint#%d" % index
    return ""


def body_id(mujoco, m, name):
    """A body's id by its name, or an unnamed body's `body#ID`."""
    found = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, name)
    if found < 0 and name.startswith("body#") and name[5:].isdigit() and int(name[5:]) < m.nbody:
        found = int(name[5:])
    return found


def describe(mujoco, m):
    bodies = []
    for b in range(m.nbody):  # body 0 is the world (a URDF link named 'world' becomes it)
        bodies.append({
            "name": name_of(mujoco, m, mujoco.mjtObj.mjOBJ_BODY, b),
            "parent": name_of(mujoco, m, mujoco.mjtObj.mjOBJ_BODY, int(m.body_parentid[b])),
            "mass": finite(m.body_mass[b]),
            "inertia": vec(m.body_inertia[b]),
            "geoms": int(m.body_geomnum[b]),
        })
    joints = []
    for j in range(m.njnt):
        joints.append({
            "name": name_of(mujoco, m, mujoco.mjtObj.mjOBJ_JOINT, j),
            "type": int(m.jnt_type[j]),
            "limited": bool(m.jnt_limited[j]),
            "range": vec(m.jnt_range[j]),
            "force_limited": bool(m.jnt_actfrclimited[j]),
            "force_range": vec(m.jnt_actfrcrange[j]),
        })
    return {"bodies": bodies, "joints": joints, "nq": int(m.nq), "nv": int(m.nv)}


def joint_addresses(mujoco, m, kind=None):
    """{name: (qpos address, dof address)} of the hinge and slide joints (or of the `kind` joints)."""
    kinds = (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE) if kind is None else (kind,)
    out = {}
    for j in range(m.njnt):
        if int(m.jnt_type[j]) in [int(k) for k in kinds]:
            out[name_of(mujoco, m, mujoco.mjtObj.mjOBJ_JOINT, j)] = (int(m.jnt_qposadr[j]), int(m.jnt_dofadr[j]))
    return out


def ball_angles(name, q):
    return [float(q.get("%s_%s" % (name, axis), 0.0)) for axis in "xyz"]


def ball_quaternion(angles):
    """The rotation about x, then the turned y, then the turned z (as three chained hinges)."""
    w, x, y, z = 1.0, 0.0, 0.0, 0.0
    for axis, angle in enumerate(angles):
        h = [0.0, 0.0, 0.0]
        h[axis] = math.sin(angle / 2.0)
        c = math.cos(angle / 2.0)
        w, x, y, z = (
            w * c - x * h[0] - y * h[1] - z * h[2],
            w * h[0] + x * c + y * h[2] - z * h[1],
            w * h[1] - x * h[2] + y * c + z * h[0],
            w * h[2] + x * h[1] - y * h[0] + z * c,
        )
    return [w, x, y, z]


def ball_hinge_axes(angles):
    """The three hinges' axes in the child body's frame (MuJoCo's ball dofs are about the body's axes)."""
    import numpy as np

    def rot(axis, angle):
        c, s = math.cos(angle), math.sin(angle)
        i, j = [(1, 2), (2, 0), (0, 1)][axis]
        r = np.eye(3)
        r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
        return r

    _, b, c = angles
    rz, ry = rot(2, c), rot(1, b)
    return [rz.T @ ry.T @ np.array([1.0, 0, 0]), rz.T @ np.array([0, 1.0, 0]), np.array([0, 0, 1.0])]


def set_pose(mujoco, m, d, q):
    """qpos0 moved by the validator's joint values: q is qpos - qpos0 for hinges and slides (MJCF's
    `ref`), three hinge angles for a ball joint."""
    d.qpos[:] = m.qpos0
    for name, (qadr, _) in joint_addresses(mujoco, m).items():
        if name in q:
            d.qpos[qadr] = m.qpos0[qadr] + q[name]
    for name, (qadr, _) in joint_addresses(mujoco, m, mujoco.mjtJoint.mjJNT_BALL).items():
        turn = ball_quaternion(ball_angles(name, q))
        import numpy as np

        moved = np.zeros(4)
        mujoco.mju_mulQuat(moved, m.qpos0[qadr:qadr + 4].copy(), np.array(turn))
        d.qpos[qadr:qadr + 4] = moved
    d.qvel[:] = 0.0


def gravity_forces(mujoco, m, d, q):
    """qfrc_bias by the validator's joint names (a ball's three dofs along its three hinges)."""
    out = {name: finite(d.qfrc_bias[dof]) for name, (_, dof) in joint_addresses(mujoco, m).items()}
    for name, (_, dof) in joint_addresses(mujoco, m, mujoco.mjtJoint.mjJNT_BALL).items():
        torque = d.qfrc_bias[dof:dof + 3]
        for axis, direction in zip("xyz", ball_hinge_axes(ball_angles(name, q))):
            out["%s_%s" % (name, axis)] = finite(float(direction @ torque))
    return out


def crosscheck(mujoco, m, job, root_id):
    d = mujoco.MjData(m)
    results = []
    for configuration in job["configurations"]:
        set_pose(mujoco, m, d, configuration["q"])
        mujoco.mj_forward(m, d)
        results.append({
            "label": configuration["label"],
            "qfrc_bias": gravity_forces(mujoco, m, d, configuration["q"]),
            "com": vec(d.subtree_com[root_id]),
            "body_pos": {
                name_of(mujoco, m, mujoco.mjtObj.mjOBJ_BODY, b): vec(d.xpos[b]) for b in range(1, m.nbody)
            },
        })
    return results


def lowest_point(mujoco, m, d, robot_geoms):
    """The lowest z of the robot's collision geometry at the current pose."""
    return min((geom_lowest(mujoco, m, d, g) for g in robot_geoms), default=math.inf)


def geom_lowest(mujoco, m, d, g):
    """The lowest z of one geom at the current pose."""
    import numpy as np

    pos = d.geom_xpos[g]
    rot = d.geom_xmat[g].reshape(3, 3)
    size = m.geom_size[g]
    kind = mujoco.mjtGeom(int(m.geom_type[g]))
    if kind == mujoco.mjtGeom.mjGEOM_SPHERE:
        z = pos[2] - size[0]
    elif kind == mujoco.mjtGeom.mjGEOM_CAPSULE:
        z = pos[2] - abs(rot[2, 2]) * size[1] - size[0]
    elif kind == mujoco.mjtGeom.mjGEOM_CYLINDER:
        axis_z = abs(rot[2, 2])
        z = pos[2] - axis_z * size[1] - size[0] * math.sqrt(max(0.0, 1.0 - axis_z * axis_z))
    elif kind == mujoco.mjtGeom.mjGEOM_BOX or kind == mujoco.mjtGeom.mjGEOM_ELLIPSOID:
        z = pos[2] - float(np.abs(rot[2, :]) @ size[:3])
    elif kind == mujoco.mjtGeom.mjGEOM_MESH:
        mesh = m.geom_dataid[g]
        start = m.mesh_vertadr[mesh]
        verts = m.mesh_vert[start:start + m.mesh_vertnum[mesh]]
        z = pos[2] + float(np.min(verts @ rot[2, :])) if len(verts) else pos[2]
    else:
        z = pos[2] - m.geom_rbound[g]
    return float(z)


def tilt_deg(d, root_id, up):
    """The angle between the root's z axis and `up` (its z axis at the release)."""
    z = [float(d.xmat[root_id][i]) for i in (2, 5, 8)]
    cos = sum(a * b for a, b in zip(z, up))
    return math.degrees(math.acos(max(-1.0, min(1.0, cos))))


def ground_height(mujoco, m, d, planes, x, y):
    """The height of the highest of `planes` (world geoms) at (x, y); 0 without any."""
    heights = []
    for g in planes:
        p, n = d.geom_xpos[g], d.geom_xmat[g].reshape(3, 3)[:, 2]
        if n[2] > 1e-6:
            heights.append(float(p[2] - (n[0] * (x - p[0]) + n[1] * (y - p[1])) / n[2]))
    return max(heights, default=0.0)


def drop_test(mujoco, m, job, root_id, servos):
    """The drop: an MJCF model on its own ground (its world planes, else the floor added), its root's free
    joint at qpos0 raised or lowered to `height` above it; a URDF robot upright above the floor added."""
    import numpy as np

    drop = job["drop"]
    mjcf = "mjcf" in job
    servos, first = servos
    d = mujoco.MjData(m)
    addresses = joint_addresses(mujoco, m)
    m.opt.timestep = drop["timestep"]
    m.opt.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    # The model's own actuators do nothing: the servos hold the joints.
    m.actuator_gainprm[:first] = 0.0
    m.actuator_biasprm[:first] = 0.0
    collides = [g for g in range(m.ngeom) if m.geom_contype[g] or m.geom_conaffinity[g]]
    if mjcf:  # the ground is what is welded to the world
        ground = {g for g in collides if not m.body_weldid[m.geom_bodyid[g]]}
    else:  # -1: fixed base
        ground = {mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "urdf_validate_floor")}
    robot_geoms = [g for g in collides if g not in ground]
    planes = [g for g in ground if g >= 0 and m.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE]

    set_pose(mujoco, m, d, drop["q"])
    mujoco.mj_forward(m, d)
    low = lowest_point(mujoco, m, d, robot_geoms) if robot_geoms else 0.0
    if not job["fixed_base"] and mjcf:
        free = [j for j in range(m.njnt)
                if m.jnt_bodyid[j] == root_id and m.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE]
        if free:
            qadr = int(m.jnt_qposadr[free[0]])
            floor_z = ground_height(mujoco, m, d, planes, d.qpos[qadr], d.qpos[qadr + 1])
            d.qpos[qadr + 2] += floor_z + drop["height"] - low
    elif not job["fixed_base"]:
        d.qpos[0:3] = [0.0, 0.0, drop["height"] - low]
        d.qpos[3:7] = [1.0, 0.0, 0.0, 0.0]
    mujoco.mj_forward(m, d)
    up = [float(d.xmat[root_id][i]) for i in (2, 5, 8)]
    # How far above the robot's lowest point each link starts: the links at 0 are what it stands on.
    start_low = lowest_point(mujoco, m, d, robot_geoms) if robot_geoms else 0.0
    start_clearance = {}
    for g in robot_geoms:
        link = link_of_geom(mujoco, m, g, mjcf)
        if link is not None:
            z = geom_lowest(mujoco, m, d, g) - start_low
            start_clearance[link] = min(start_clearance.get(link, math.inf), z)

    # Servos: a PID whose proportional gain reaches the joint's effort at `saturation` rad (or m) of
    # error, capped so the joint's own inertia does not oscillate faster than the time step allows,
    # critically damped, with an integral term: a joint strong enough ends on its target, one too weak
    # saturates at its effort and sags.
    unit, column = np.zeros(m.nv), np.zeros(m.nv)
    omega_max = drop["omega_dt"] / drop["timestep"]
    saturation = drop["saturation"]
    servo_joint, servo_q, servo_dof, servo_ref, servo_limit = [], [], [], [], []
    for a, servo in enumerate(servos, start=first):
        qadr, dof = addresses[servo["joint"]]
        unit[:] = 0.0
        unit[dof] = 1.0
        mujoco.mj_mulM(m, d, column, unit)  # (mj_fullM's signature changed between MuJoCo 3 and 4)
        inertia = max(float(column[dof]), 1e-12)
        kp = inertia * omega_max * omega_max
        if servo["effort"] is not None:
            kp = min(kp, servo["effort"] / saturation)
        kv = 2.0 * math.sqrt(kp * inertia)
        m.actuator_gainprm[a, 0] = kp
        m.actuator_biasprm[a, 0:3] = [0.0, -kp, -kv]
        servo_joint.append(servo["joint"])
        servo_q.append(qadr)
        servo_dof.append(dof)
        servo_ref.append(float(d.qpos[qadr]))  # the pose set above: qpos0 moved by drop["q"]
        effort = servo["effort"]
        servo_limit.append(effort / kp if effort is not None else math.inf)
    servo_q = np.array(servo_q, dtype=int)
    ref = np.array(servo_ref)
    limit = np.array(servo_limit)
    integral = np.zeros(len(servo_joint))
    ki = drop["integral_rate"]

    steps = int(round(drop["duration"] / drop["timestep"]))
    last_window = int(round(0.5 / drop["timestep"]))
    com0 = np.array(d.subtree_com[root_id])
    max_tilt = 0.0
    max_dev = np.zeros(len(servo_joint))
    late_dev = np.zeros(len(servo_joint))
    tilts = []
    # The tilt over time for plots: at the start, then every `stride` steps, the last step included.
    stride = max(1, -(-steps // max(1, drop["trace_points"] - 2)))
    trace = [[0.0, finite(tilt_deg(d, root_id, up))]]
    started = time.time()
    for step in range(steps):
        if len(servo_joint):
            error = ref - d.qpos[servo_q]
            integral = np.clip(integral + ki * drop["timestep"] * error, -limit, limit)
            d.ctrl[first:] = ref + integral
        mujoco.mj_step(m, d)
        tilt = tilt_deg(d, root_id, up)
        max_tilt = max(max_tilt, tilt)
        if step % 10 == 0:
            tilts.append(tilt)
        if (step + 1) % stride == 0 or step == steps - 1:
            trace.append([finite((step + 1) * drop["timestep"]), finite(tilt)])
        if len(servo_joint):
            dev = np.abs(d.qpos[servo_q] - ref)
            max_dev = np.maximum(max_dev, dev)
            if step >= steps - last_window:
                late_dev = np.maximum(late_dev, dev)
    unstable = None
    bad = d.warning[int(mujoco.mjtWarning.mjWARN_BADQACC)]
    if bad.number > 0:
        unstable = "MuJoCo found the acceleration not finite (simulation unstable) at step %d" % (bad.lastinfo,)
    com1 = np.array(d.subtree_com[root_id])
    # The links resting on the ground at the end: a contact with the ground at the last step.
    ground_end = set()
    for c in d.contact[:d.ncon]:
        g1, g2 = int(c.geom1), int(c.geom2)
        if (g1 in ground) != (g2 in ground):
            other = g2 if g1 in ground else g1
            link = link_of_geom(mujoco, m, other, mjcf)
            if link is not None:
                ground_end.add(link)
    final_dev = np.abs(d.qpos[servo_q] - ref) if len(servo_joint) else np.zeros(0)
    return {
        "simulated_s": steps * drop["timestep"],
        "timestep_s": drop["timestep"],
        "steps": steps,
        "lowest_point_z": finite(low),
        "max_tilt_deg": finite(max_tilt),
        "final_tilt_deg": finite(tilt_deg(d, root_id, up)),
        "tilt_range_last_s_deg": finite(max(tilts[len(tilts) // 2:]) - min(tilts[len(tilts) // 2:])) if tilts else 0.0,
        "com_start": vec(com0),
        "com_end": vec(com1),
        "com_drift_m": finite(math.hypot(com1[0] - com0[0], com1[1] - com0[1])),
        "joints": [
            {
                "name": name,
                "final_deviation": finite(final_dev[i]),
                "max_deviation": finite(max_dev[i]),
                "max_deviation_last_half_s": finite(late_dev[i]),
            }
            for i, name in enumerate(servo_joint)
        ],
        "start_clearance_m": {link: finite(z) for link, z in sorted(start_clearance.items())},
        "ground_links_end": sorted(ground_end),
        "tilt_trace": trace,
        "unstable": unstable,
        "wall_s": time.time() - started,
    }


def run(job):
    try:
        import mujoco  # noqa: F401 (the point of the bridge)
    except Exception as error:  # ImportError, or a broken install raising anything else
        return {
            "ok": False,
            "kind": "no_mujoco",
            "message": "%s: %s" % (type(error).__name__, error),
            "python": sys.executable,
            "python_version": sys.version.split()[0],
        }
    out = {
        "ok": True,
        "mujoco_version": getattr(mujoco, "__version__", "unknown"),
        "python": sys.executable,
        "python_version": sys.version.split()[0],
    }
    if job.get("probe"):
        return out
    m, attempts, servos = compile_model(mujoco, job, job.get("drop"))
    out["attempts"] = attempts
    if m is None:
        out["ok"] = False
        out["kind"] = "compile"
        out["message"] = attempts[-1]["error"] if attempts else "MuJoCo compiled nothing"
        return out
    root_id = body_id(mujoco, m, job["root"])
    out["model"] = describe(mujoco, m)
    out["crosscheck"] = crosscheck(mujoco, m, job, root_id)
    if job.get("drop"):
        try:
            out["drop"] = drop_test(mujoco, m, job, root_id, servos)
        except Exception as error:
            out["drop_error"] = "%s: %s" % (type(error).__name__, error)
    return out


def main():
    global _REPLY
    _REPLY = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)  # MuJoCo's C code prints to fd 1: send it to stderr
    sys.stdout = sys.stderr
    try:
        job = json.load(sys.stdin)
        reply(run(job))
    except BaseException as error:  # never a traceback: the Rust side turns this into a finding
        reply({"ok": False, "kind": "internal", "message": "%s: %s" % (type(error).__name__, error)})


main()
