#!/usr/bin/env python3
"""MuJoCo Menagerie: MuJoCo against urdf_validate on the same files (issue #30).

`--full DIR`: every model file of a whole Menagerie tree with its meshes (not committed; `--extract GIT_DIR
--commit C` writes DIR from a fetched snapshot first), run on a stand-in tree where a file naming a mesh the
snapshot lacks is rewritten without it: MuJoCo compiles?, our report (exit code, verdicts; a hang or crash is
a failure), and mass, COM and gravity torques against MuJoCo at the statics pose and two seeded random
configurations (`--pose custom`). One Markdown row per file (docs/menagerie.md); exit 1 on any failure.

The rest of this text is the committed mesh-free corpus (`--write`, `--check`):

Menagerie's meshes cannot be brought here (its snapshot is over the fetch limit); its XML files can, one by
one. For each robot model listed in MODELS, whose original XML and LICENSE were copied by hand into
`--source` (default target/menagerie-src/<dir>/), `--write` makes a mesh-free variant that MuJoCo compiles
without any asset file:

- `<mesh>`, `<hfield>` and `<skin>` assets with a file are dropped, and so is every geom that uses a mesh
  or a height field (its own attributes or its default class's: `mesh=`, `type="mesh"`/`"hfield"`/`"sdf"`),
  with the `<contact>` pairs and sensors naming a dropped geom;
- `<texture>`s with a file are dropped, and the `texture=` of materials that used them;
- everything else is kept as it is, explicit `<inertial>`s included (the XML is re-serialised: indentation,
  and an XML declaration or comments outside the root element are dropped).

A body whose mass came from a dropped geom (no `<inertial>` and `inertiafromgeom` not false, or
`inertiafromgeom="true"`; the geom's group in `inertiagrouprange`, its mass or density not 0) loses it: the
script lists those bodies per model. The variant, the LICENSE and SOURCES.md go to
crates/urdf-validator/tests/data/menagerie/<dir>/.

Then, for every committed variant (`--check`, and after `--write`): MuJoCo compiles it (the test venv's
`mujoco`), `mj_forward` with zero velocity (gravity on even where the model turns it off) at the statics
pose of our report (`qpos0`, where a joint's `qpos0` is outside its range clamped into it, as the report's
`statics.configuration` and notes say; q = qpos - qpos0), and the validator (`--binary`, default
$URDF_VALIDATE or target/release/urdf_validate) runs on the SAME file with `--format json`. Compared, to
1e-9 relative with floors of 1e-12 kg, 1e-12 m and 1e-10 N·m: the total mass (sum of `body_mass`) with the
report's `statics.total_mass`, the centre of mass (`subtree_com` of the world body) with
`statics.full_body_com`, and each hinge/slide dof's `qfrc_bias` with the report's
`statics.joints[].required_torque_gravity` (ball joints: dofs `NAME_x`, `NAME_y`, `NAME_z`; a joint that
another follows through an `<equality><joint>` adds the follower's times the coupling's `a1`, as the
report folds a mimic follower into its leader). It prints one
Markdown table row per model (the table of docs/menagerie.md) and exits 1 when a variant does not compile
(unless MODELS marks it `refused`), does not agree, or (`--check`) is no longer what `--write` would make
from the sources when they are here; 2 when the binary or (`--write`) the sources are missing.

    .venv/bin/python scripts/oracle/menagerie.py --write    # make the variants from target/menagerie-src
    .venv/bin/python scripts/oracle/menagerie.py --check    # compare the committed variants (CI)
"""

from __future__ import annotations

import argparse
import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import mujoco

REPO = Path(__file__).resolve().parents[2]
DATA = REPO / "crates/urdf-validator/tests/data/menagerie"
UPSTREAM = "https://github.com/google-deepmind/mujoco_menagerie"

RELATIVE = 1e-9
MASS_FLOOR = 1e-12
POSITION_FLOOR = 1e-12
TORQUE_FLOOR = 1e-10


@dataclass(frozen=True)
class Model:
    """One Menagerie robot model: its folder, its robot file, and the commits read_file gave for them."""

    kind: str
    folder: str
    file: str
    commit: str
    license_commit: str
    refused: bool = False
    """MuJoCo refuses the variant (a moving body left without mass): the row says so, --check expects it."""


MODELS = [
    Model("arm", "universal_robots_ur5e", "ur5e.xml",
          "1b428b08bb26ca6024e7b21e8ff21a59f847eb87", "1b93125c79bb95e4e55a1d6471adb2cd92c71feb"),
    Model("quadruped", "unitree_go2", "go2.xml",
          "2ffe3e33bbf5785a4c5a2290dd909b7a051845bf", "2ffe3e33bbf5785a4c5a2290dd909b7a051845bf"),
    Model("arm", "kuka_iiwa_14", "iiwa14.xml",
          "28ffb48b5c1d409a37fbfbb01c023c12e61cdefd", "dccf05b152d550b4a6d85addd584e373e119e764"),
    Model("humanoid", "unitree_h1", "h1.xml",
          "4035abd3637b5a3cdf038bc1b128852d96a1d19f", "56c951b6e8ba8cd6a330ee42403874dbc2d546c9"),
    Model("hand", "wonik_allegro", "right_hand.xml",
          "28ffb48b5c1d409a37fbfbb01c023c12e61cdefd", "dccf05b152d550b4a6d85addd584e373e119e764",
          refused=True),
    Model("arm", "unitree_z1", "z1.xml",
          "19b9576c9b7b982cd4863bc0c2aa7fde86771fc7", "19b9576c9b7b982cd4863bc0c2aa7fde86771fc7"),
    Model("humanoid (biped)", "agility_cassie", "cassie.xml",
          "1b428b08bb26ca6024e7b21e8ff21a59f847eb87", "1b93125c79bb95e4e55a1d6471adb2cd92c71feb"),
    Model("arm", "kinova_gen3", "gen3.xml",
          "39664247032283fc5cda18cf6ce2b28cdc84eb61", "af493511dbdfce2e046858a4d2f2955e063e17fd"),
    Model("arm with gripper", "ufactory_xarm7", "xarm7.xml",
          "4f04d622db52a300ef4986b5554bb98b2951898c", "dccf05b152d550b4a6d85addd584e373e119e764"),
    Model("humanoid (legs)", "berkeley_humanoid", "berkeley_humanoid.xml",
          "483d231bae9796dff9d25ef23039e5cbb0d55351", "d4da3fd332c491aa684bcca4f634592402c734f6"),
    Model("quadrotor", "skydio_x2", "x2.xml",
          "388eb4f8fb9ea5b38506da806416b5d798dfca4d", "388eb4f8fb9ea5b38506da806416b5d798dfca4d"),
    Model("mobile manipulator", "stanford_tidybot", "tidybot.xml",
          "1aa4a8bb5c519aaabb27fbbde1d1452f63ceb778", "5d4b4c8b5b310be5cbf4fbc0ed14a1dd01ea60a8"),
    Model("quadrotor", "bitcraze_crazyflie_2", "cf2.xml",
          "24d7b69f71d0a93bb9f24f4c2245a12c49366f97", "64285db495f0a4195a00cc3936b2eff370b9745c"),
    Model("arm with gripper", "arx_l5", "arx_l5.xml",
          "0b56166037fc10bd4252879c3c3d3d8d2a74e064", "254b66e14a2145481a7276dc8ee1ca5d109cdd0c"),
    Model("arm", "rethink_robotics_sawyer", "sawyer.xml",
          "28ffb48b5c1d409a37fbfbb01c023c12e61cdefd", "dccf05b152d550b4a6d85addd584e373e119e764"),
    Model("arm", "franka_fr3_v2", "fr3v2.xml",
          "0059d4335f8156206f63a35662313385f7ad6d74", "f90a6fc75691c11fefaa8e7206f1260041a3b5eb"),
    Model("arm", "doosan_robotics_m1013", "m1013.xml",
          "4e5ae99f027b02d323e09e8a72a59af5966bf276", "166f33013bccb872781737b7d1dc303706b00370"),
    Model("wheeled mobile base", "clearpath_jackal", "jackal.xml",
          "e4fad8df9589f3f657503c821610b874bfa0bdfc", "e4fad8df9589f3f657503c821610b874bfa0bdfc"),
    Model("gripper (6 joints in one body)", "umi_gripper", "umi_gripper.xml",
          "17c0268a48eea003f000a8ace844646a7f467e40", "32121e3808b991c27062a1e3e72b2c794126579e"),
    Model("arm with gripper", "trossen_wxai", "wxai_follower.xml",
          "191a7ba5e6d5ca0af05303bf725a644bcceffb0c", "5d5ed51fad1fb965613a70b1c6488aa5156c2dcf"),
    Model("hand", "leap_hand", "right_hand.xml",
          "4035abd3637b5a3cdf038bc1b128852d96a1d19f", "f59b989dea80a523b0e0b0fbe550c664939c6376"),
    Model("humanoid", "pndbotics_adam_lite", "adam_lite.xml",
          "4f04d622db52a300ef4986b5554bb98b2951898c", "2a3595df363b0b4eb20bc8af5c014636f1e0a65b"),
    Model("arm (2 joints)", "dynamixel_2r", "dynamixel_2r.xml",
          "18608e5872945ba51171a49cf5283dd13f1466ca", "ef0e2acef896ce38ec3ea179c64dae27460899b3"),
    Model("humanoid (with a floor plane)", "bxi_elf2", "elf2_dof25.xml",
          "bfe26f8168a757f460514ae10d0f1e888799aa70", "9f1725115564402a93b9fd2e2fa8eb17355de392"),
    Model("mobile manipulator", "hello_robot_stretch", "stretch.xml",
          "163a7e30f34ac1595161180dd7ed450e22145538", "dccf05b152d550b4a6d85addd584e373e119e764",
          refused=True),
]

LOST = "Bodies that lose mass (their mass came from a dropped geom): "
"""The line of SOURCES.md that records the bodies a variant lost mass of (the table's last column)."""

MESH_TYPES = {"mesh", "hfield", "sdf"}
FILE_ASSETS = {"mesh", "hfield", "skin"}


# ---------------------------------------------------------------------------------------------- variants


def parse(text: str) -> ET.Element:
    """The XML tree, comments kept."""
    parser = ET.XMLParser(target=ET.TreeBuilder(insert_comments=True))
    parser.feed(text)
    return parser.close()


def default_classes(root: ET.Element) -> dict[str, dict[str, dict[str, str]]]:
    """Class name -> element tag -> attributes, each class with its parents' attributes merged in."""
    classes: dict[str, dict[str, dict[str, str]]] = {}

    def visit(node: ET.Element, inherited: dict[str, dict[str, str]]) -> None:
        own = {tag: dict(attrs) for tag, attrs in inherited.items()}
        for child in node:
            if child.tag != "default" and isinstance(child.tag, str):
                own.setdefault(child.tag, {}).update(child.attrib)
        classes[node.get("class", "main")] = own
        for child in node:
            if child.tag == "default":
                visit(child, own)

    for top in root.findall("default"):
        visit(top, {})
    return classes


@dataclass
class Geom:
    """A geom with its attributes resolved through its default class."""

    element: ET.Element
    parent: ET.Element
    body: str
    attrs: dict[str, str]


def geoms(root: ET.Element, classes: dict) -> list[Geom]:
    """Every geom under <worldbody>, in document order, with its resolved attributes."""
    found: list[Geom] = []

    def visit(node: ET.Element, body: str, childclass: str) -> None:
        for child in node:
            if child.tag == "geom":
                cls = child.get("class", childclass)
                attrs = dict(classes.get(cls, {}).get("geom", {}))
                attrs.update(child.attrib)
                found.append(Geom(child, node, body, attrs))
            elif child.tag in ("body", "frame"):
                name = child.get("name", "(unnamed)") if child.tag == "body" else body
                visit(child, name, child.get("childclass", childclass))

    for world in root.findall("worldbody"):
        visit(world, "world", "main")
    return found


def uses_mesh(geom: Geom) -> bool:
    return "mesh" in geom.attrs or "hfield" in geom.attrs or geom.attrs.get("type") in MESH_TYPES


def counts_for_mass(geom: Geom, group_range: tuple[int, int]) -> bool:
    """Whether MuJoCo adds this geom's mass to its body when the mass comes from geoms."""
    group = int(geom.attrs.get("group", "0"))
    if not group_range[0] <= group <= group_range[1]:
        return False
    if "mass" in geom.attrs:
        return float(geom.attrs["mass"]) != 0.0
    return float(geom.attrs.get("density", "1000")) != 0.0


def bodies_with_inertial(root: ET.Element) -> set[str]:
    return {
        body.get("name", "(unnamed)")
        for body in root.iter("body")
        if body.find("inertial") is not None
    }


def drop_geoms(root: ET.Element, drop) -> tuple[list[str], int]:
    """Removes every geom `drop(geom)` says, with the `<contact>` pairs and sensors naming one; returns the
    bodies that lose mass by it (their mass came from a dropped geom) and how many geoms were dropped."""
    classes = default_classes(root)
    compiler = root.find("compiler")
    from_geom = compiler.get("inertiafromgeom", "auto") if compiler is not None else "auto"
    group_range = (0, 5)
    if compiler is not None and "inertiagrouprange" in compiler.attrib:
        lo, hi = compiler.get("inertiagrouprange", "0 5").split()
        group_range = (int(lo), int(hi))
    explicit = bodies_with_inertial(root)
    dropped_names: set[str] = set()
    losing: list[str] = []
    dropped = 0
    for geom in geoms(root, classes):
        if not drop(geom):
            continue
        geom.parent.remove(geom.element)
        dropped += 1
        if "name" in geom.element.attrib:
            dropped_names.add(geom.element.get("name", ""))
        mass_from_geoms = from_geom == "true" or (from_geom == "auto" and geom.body not in explicit)
        if geom.body != "world" and mass_from_geoms and counts_for_mass(geom, group_range):
            if geom.body not in losing:
                losing.append(geom.body)
    for section in ("contact", "sensor"):
        for node in root.findall(section):
            for child in list(node):
                named = {child.get(k) for k in ("geom", "geom1", "geom2")} - {None}
                if named & dropped_names:
                    node.remove(child)
    return losing, dropped


def serialise(root: ET.Element) -> str:
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode") + "\n"


def mesh_free(text: str) -> tuple[str, list[str], int]:
    """The variant's text, the bodies that lose mass, and how many geoms were dropped."""
    root = parse(text)
    losing, dropped = drop_geoms(root, uses_mesh)
    dropped_textures: set[str] = set()
    for asset in root.findall("asset"):
        for child in list(asset):
            if child.tag in FILE_ASSETS and "file" in child.attrib:
                asset.remove(child)
            elif child.tag == "texture" and "file" in child.attrib:
                dropped_textures.add(child.get("name", Path(child.get("file", "")).stem))
                asset.remove(child)
        for material in asset.findall("material"):
            if material.get("texture") in dropped_textures:
                del material.attrib["texture"]
    return serialise(root), losing, dropped


def without_missing_meshes(text: str, missing) -> tuple[str, list[str], int] | None:
    """The file without the `<mesh>` assets whose file `missing(file, meshdir)` says is absent and the
    geoms using them (None when it has none): what MuJoCo can compile of a model whose largest meshes a
    fetched snapshot lacks."""
    root = parse(text)
    compiler = root.find("compiler")
    meshdir = ""
    if compiler is not None:
        meshdir = compiler.get("meshdir", compiler.get("assetdir", ""))
    gone: set[str] = set()
    for asset in root.findall("asset"):
        for child in list(asset):
            if child.tag == "mesh" and "file" in child.attrib and missing(child.get("file", ""), meshdir):
                gone.add(child.get("name", Path(child.get("file", "")).stem))
                asset.remove(child)
    if not gone:
        return None
    losing, dropped = drop_geoms(root, lambda geom: geom.attrs.get("mesh") in gone)
    return serialise(root), losing, dropped


def write(source: Path) -> None:
    """Writes every model's variant, LICENSE and SOURCES.md from the hand-copied originals."""
    for model in MODELS:
        folder = source / model.folder
        original = (folder / model.file).read_text()
        variant, losing, dropped = mesh_free(original)
        out = DATA / model.folder
        out.mkdir(parents=True, exist_ok=True)
        (out / model.file).write_text(variant)
        (out / "LICENSE").write_text((folder / "LICENSE").read_text())
        (out / "SOURCES.md").write_text(sources_md(model, losing, dropped))


def sources_md(model: Model, losing: list[str], dropped: int) -> str:
    lost = ", ".join(f"`{b}`" for b in losing) if losing else "none (every body keeps its mass)"
    return (
        f"# {model.folder}\n\n"
        f"From MuJoCo Menagerie ({UPSTREAM}), folder `{model.folder}`:\n\n"
        f"- `{model.file}` at commit {model.commit}\n"
        f"- `LICENSE` at commit {model.license_commit} (unchanged)\n\n"
        f"`{model.file}` here is a mesh-free variant made by `scripts/oracle/menagerie.py` (the meshes are "
        f"not in this repository): {dropped} geoms using a mesh dropped with the `<mesh>` assets (and "
        f"texture files, height fields and skins, where any); the XML is re-serialised (indentation; "
        f"an XML declaration or comments outside the root element are dropped), otherwise unchanged. "
        f"{LOST}{lost}.\n"
    )


# ---------------------------------------------------------------------------------------------- compare


def agrees(ours: float, theirs: float, floor: float) -> bool:
    return abs(ours - theirs) <= max(RELATIVE * max(abs(ours), abs(theirs)), floor)


def mujoco_values(path: Path, configuration: dict[str, float]) -> dict:
    """Total mass, centre of mass and gravity forces by joint, gravity on, at `qpos0` moved by the
    report's statics configuration (our q is MuJoCo's qpos - qpos0 for hinge and slide joints; ball and
    free joints stay at qpos0)."""
    return values_at(mujoco.MjModel.from_xml_path(str(path)), configuration)


def values_at(model: mujoco.MjModel, configuration: dict[str, float]) -> dict:
    """`mujoco_values` of a compiled model (its gravity flag turned on)."""
    model.opt.disableflags &= ~int(mujoco.mjtDisableBit.mjDSBL_GRAVITY)
    data = mujoco.MjData(model)
    data.qpos[:] = model.qpos0
    for j in range(model.njnt):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j)
        # int(): a numpy integer is never `in` a tuple of MuJoCo's enum values.
        if int(model.jnt_type[j]) in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE)):
            data.qpos[model.jnt_qposadr[j]] += configuration.get(name or "", 0.0)
    apply_couplings(model, data)
    data.qvel[:] = 0
    mujoco.mj_forward(model, data)
    forces: dict[str, float] = {}
    unnamed = 0
    for j in range(model.njnt):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j)
        kind = int(model.jnt_type[j])
        dof = model.jnt_dofadr[j]
        if kind == int(mujoco.mjtJoint.mjJNT_FREE):
            continue
        if not name:
            unnamed += 1
            continue
        # What the motors hold: qfrc_bias less body gravcomp's passive force (not subtracted where the
        # joint routes it through its actuators, `actuatorgravcomp`).
        passive = 0.0 if model.jnt_actgravcomp[j] else 1.0
        if kind == int(mujoco.mjtJoint.mjJNT_BALL):
            for k, axis in enumerate("xyz"):
                forces[f"{name}_{axis}"] = float(data.qfrc_bias[dof + k] - passive * data.qfrc_gravcomp[dof + k])
        else:
            forces[name] = float(data.qfrc_bias[dof] - passive * data.qfrc_gravcomp[dof])
    fold_couplings(model, forces)
    return {
        "mass": float(sum(model.body_mass)),
        "com": [float(x) for x in data.subtree_com[0]],
        "forces": forces,
        "unnamed": unnamed,
        "gravity": [float(x) for x in model.opt.gravity],
    }


def joint_couplings(model: mujoco.MjModel) -> list[tuple[int, int, float, float]]:
    """The active joint equalities: (joint1, joint2 or -1 when it holds joint1, a0, a1)."""
    return [
        (int(model.eq_obj1id[e]), int(model.eq_obj2id[e]), float(model.eq_data[e][0]), float(model.eq_data[e][1]))
        for e in range(model.neq)
        if int(model.eq_type[e]) == int(mujoco.mjtEq.mjEQ_JOINT) and model.eq_active0[e]
    ]


def apply_couplings(model: mujoco.MjModel, data: mujoco.MjData) -> None:
    """Put each coupled joint where the validator's mimic puts it: q1 = a0 + a1·q2 in qpos - qpos0 (the
    linear part; a held joint at a0), followed along chains (leaders first, at most one pass per coupling)."""
    couplings = joint_couplings(model)
    for _ in range(len(couplings)):
        for first, second, a0, a1 in couplings:
            at1 = model.jnt_qposadr[first]
            q2 = 0.0 if second < 0 else data.qpos[model.jnt_qposadr[second]] - model.qpos0[model.jnt_qposadr[second]]
            data.qpos[at1] = model.qpos0[at1] + a0 + a1 * q2


def fold_couplings(model: mujoco.MjModel, forces: dict[str, float]) -> None:
    """Each active joint equality `q1 = a0 + a1·q2 + ...` couples joint1 to joint2, as the validator's mimic
    does: what holds the pair is joint2's drive, so the torque it must give is joint2's own plus a1 times
    joint1's (virtual work through the linear part), followed along chains of couplings to their first
    leader. joint1 keeps its
    own torque (the report's `required_torque_gravity` of a mimic follower); a joint equality without
    joint2 holds joint1 fixed, out of the report."""
    leader: dict[str, tuple[str, float]] = {}
    held = []
    for e in range(model.neq):
        if int(model.eq_type[e]) != int(mujoco.mjtEq.mjEQ_JOINT) or not model.eq_active0[e]:
            continue
        first = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, model.eq_obj1id[e]) or ""
        if model.eq_obj2id[e] < 0:
            held.append(first)
            continue
        second = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, model.eq_obj2id[e]) or ""
        leader.setdefault(first, (second, float(model.eq_data[e][1])))
    own = dict(forces)
    for name, force in own.items():
        # To the chain's first leader only: a joint that follows another keeps its own torque, even when a
        # third follows it (as the report resolves mimic chains).
        at, factor, steps = name, 1.0, 0
        while at in leader and factor != 0.0 and steps <= len(leader):
            at, multiplier = leader[at]
            factor *= multiplier
            steps += 1
        if at != name and at in forces:
            forces[at] += factor * force
    for name in held:
        forces.pop(name, None)


def our_report(binary: Path, path: Path) -> tuple[int, dict | None]:
    run = validate(binary, path, [], 600.0)
    return (run.code if run.code is not None else -1), run.report


@dataclass
class Run:
    """One run of the validator on one file."""

    code: int | None
    """Its exit code (negative: killed by that signal); None when it did not finish in time (a hang)."""
    report: dict | None
    seconds: float
    stderr: str

    def crashed(self) -> bool:
        """A crash: killed by a signal, a panic, an exit code the CLI never gives, or no report."""
        return self.code is not None and (
            self.code not in (0, 1, 2) or "panicked" in self.stderr or self.report is None
        )


def validate(binary: Path, path: Path, extra: list[str], timeout: float) -> Run:
    """`urdf_validate --format json` on `path` (the arguments as a list: file names are data, never
    shell words), its report read back from a temporary --output-dir."""
    with tempfile.TemporaryDirectory(prefix="menagerie-") as out:
        start = time.monotonic()
        try:
            run = subprocess.run(
                [str(binary), "--format", "json", "--output-dir", out, *extra, "--", str(path)],
                capture_output=True,
                text=True,
                timeout=timeout,
            )
        except subprocess.TimeoutExpired:
            return Run(None, None, time.monotonic() - start, "")
        seconds = time.monotonic() - start
        reports = list(Path(out).glob("*_validation.json"))
        report = json.loads(reports[0].read_text()) if reports else None
    return Run(run.returncode, report, seconds, run.stderr)


def compare(theirs: dict, report: dict) -> list[str]:
    """What disagrees, as readable lines (empty when everything agrees)."""
    statics = report.get("statics") or {}
    out = []
    mass = statics.get("total_mass")
    if mass is None or not agrees(mass, theirs["mass"], MASS_FLOOR):
        out.append(f"total mass {mass}, MuJoCo {theirs['mass']}")
    com = statics.get("full_body_com")
    massless = theirs["mass"] == 0.0 and mass is not None and mass <= MASS_FLOOR
    # A model without mass (a camera) has no centre of mass to compare.
    if not massless and (com is None or not all(agrees(com[i], theirs["com"][i], POSITION_FLOOR)
                                                for i in range(3))):
        out.append(f"centre of mass {com}, MuJoCo {theirs['com']}")
    ours = {j["name"]: j.get("required_torque_gravity") for j in statics.get("joints") or []}
    for name, force in theirs["forces"].items():
        torque = ours.get(name)
        if torque is None or not agrees(torque, force, TORQUE_FLOOR):
            out.append(f"joint {name}: gravity torque {torque}, MuJoCo {force}")
    return out


SECTIONS = ("schema", "statics", "stability", "workspace", "symmetry")


def verdicts(report: dict | None) -> str:
    if report is None:
        return "no report"
    return f"{report.get('overall_status')}: " + ", ".join(
        f"{s} {(report.get(s) or {}).get('status', '–')}" for s in SECTIONS
    )


def row(model: Model, binary: Path) -> tuple[str, bool, list[str]]:
    """The table row, whether it is as expected (agrees, or MuJoCo refuses a variant `refused` says it
    does), and what disagrees."""
    path = DATA / model.folder / model.file
    sources = (DATA / model.folder / "SOURCES.md").read_text()
    lost = sources.split(LOST, 1)[-1].strip()
    lost = lost.removesuffix(".")
    code, report = our_report(binary, path)
    start = f"| {model.folder}/{model.file} | {model.kind} |"
    end = f"| {code} | {verdicts(report)} | {lost} |"
    configuration = ((report or {}).get("statics") or {}).get("configuration") or {}
    try:
        theirs = mujoco_values(path, configuration)
    except (ValueError, mujoco.FatalError) as error:
        message = str(error).splitlines()[0].removeprefix("Error: ")
        problems = [] if model.refused else [f"MuJoCo refuses the variant: {message}"]
        return f"{start} no: {message} | – {end}", not problems, problems
    if model.refused:
        return f"{start} yes | – {end}", False, ["MuJoCo compiles a variant MODELS says it refuses"]
    if report is None:
        return f"{start} yes | no report {end}", False, ["no report"]
    problems = compare(theirs, report)
    if theirs["gravity"] != [0.0, 0.0, -9.81]:
        problems.append(f"gravity {theirs['gravity']} (the validator uses -9.81 along z)")
    moved = sum(1 for q in configuration.values() if q != 0.0)
    figures = f"{theirs['mass']:.6g} kg, {len(theirs['forces'])} joint torques"
    if theirs["unnamed"]:
        figures += f", {theirs['unnamed']} unnamed joints not compared"
    if moved:
        figures += f"; {moved} joints clamped into their limits"
    agreed = "yes" if not problems else f"**no** ({len(problems)} values)"
    return f"{start} yes | {agreed} ({figures}) {end}", not problems, problems


# ---------------------------------------------------------------------------------------------- full corpus

FULL_TIMEOUT = 300.0
"""Seconds a validator run may take in --full before it counts as a hang (its own --timeout is 60 s)."""
RANDOM_CONFIGURATIONS = 2
SEED = 7
UNSAFE_IN_JOINT_ANGLES = set(",= \t\n")
"""Characters a joint name cannot have in `--joint-angles NAME=VALUE,...`: such a joint stays at qpos0."""


def full_models(root: Path) -> list[Path]:
    """Every model of a Menagerie tree: the `*.xml` files directly in a top-level folder whose root
    element is `<mujoco>` (robot files, scenes, `mjx_` variants; not the fragments under `assets/`),
    sorted. File names are data: they are never put into a shell command."""
    found = []
    for folder in sorted(p for p in root.iterdir() if p.is_dir() and not p.name.startswith(".")):
        for path in sorted(folder.glob("*.xml")):
            try:
                tag = next(ET.iterparse(path, events=("start",)))[1].tag
            except (ET.ParseError, StopIteration, OSError):
                continue
            if tag == "mujoco":
                found.append(path)
    return found


def extract(git_dir: Path, commit: str, out: Path) -> list[tuple[str, str]]:
    """Writes the tree of `commit` of a fetched Menagerie snapshot (a bare git directory) into `out`; returns
    the files the snapshot lacks (path, blob id): a fetched snapshot has no file of 4 MiB or more. Paths
    are data: no shell, and none may leave `out`."""
    git = ["git", f"--git-dir={git_dir}"]
    listing = subprocess.run(git + ["ls-tree", "-r", "-z", commit], capture_output=True, check=True).stdout
    missing = []
    for entry in listing.split(b"\0"):
        if not entry:
            continue
        meta, raw = entry.split(b"\t", 1)
        mode, kind, blob = meta.decode().split()
        path = raw.decode()
        if kind != "blob" or mode == "120000":
            continue
        target = (out / path).resolve()
        if out.resolve() not in target.parents:
            raise SystemExit(f"{path!r}: a path outside the tree")
        content = subprocess.run(git + ["cat-file", "blob", blob], capture_output=True)
        if content.returncode != 0:
            missing.append((path, blob))
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(content.stdout)
    return missing


@dataclass
class StandIn:
    """What the stand-in of one file dropped: the geoms whose mesh file the snapshot lacks."""

    meshes: int
    geoms: int
    losing: list[str]


def meshdirs(folder: Path) -> set[str]:
    """The `meshdir`s (or `assetdir`s) the model files directly in `folder` give."""
    found = set()
    for path in folder.glob("*.xml"):
        try:
            compiler = ET.parse(path).getroot().find("compiler")
        except ET.ParseError:
            continue
        if compiler is not None:
            found.add(compiler.get("meshdir", compiler.get("assetdir", "")))
    return found


def stand_in_tree(root: Path, out: Path) -> dict[str, StandIn]:
    """Mirrors the Menagerie tree `root` into `out` (symbolic links to its files), every XML file that
    declares a `<mesh>` whose file is not in `root` rewritten without that mesh and the geoms using it
    (`without_missing_meshes`); returns what each rewritten file dropped, by path relative to `root`.
    Mesh files are looked up in the model's folder (the top-level folder), under the file's `meshdir`."""
    if out.exists():
        shutil.rmtree(out)
    changed: dict[str, StandIn] = {}
    for path in sorted(root.rglob("*")):
        relative = path.relative_to(root)
        target = out / relative
        if path.is_dir():
            target.mkdir(parents=True, exist_ok=True)
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        variant = None
        if path.suffix == ".xml" and len(relative.parts) > 1:
            folder = root / relative.parts[0]
            gone: set[str] = set()
            # An included file's meshes resolve against the including model's meshdir: absent only when
            # absent under every meshdir of the folder's models (and under the file's own folder).
            bases = {path.parent, folder} | {folder / d for d in meshdirs(folder)}

            def missing(file: str, meshdir: str, bases: set[Path] = bases, gone: set[str] = gone) -> bool:
                absent = not any((base / meshdir / file).is_file() or (base / file).is_file() for base in bases)
                if absent:
                    gone.add(file)
                return absent

            try:
                variant = without_missing_meshes(path.read_text(), missing)
            except (ET.ParseError, UnicodeDecodeError, ValueError):
                variant = None
            if variant is not None:
                text, losing, dropped = variant
                target.write_text(text)
                changed[str(relative)] = StandIn(len(gone), dropped, losing)
        if variant is None:
            target.symlink_to(path)
    return changed


def random_configuration(model: mujoco.MjModel, rng: random.Random) -> dict[str, float]:
    """q (MuJoCo's qpos - qpos0) for every named hinge and slide joint the command line can name: uniform
    in the joint's range when it is limited, else in [-pi, pi] (hinge) or [-0.1, 0.1] m (slide); not the
    joints a joint equality moves (the validator places them as their coupling says)."""
    q = {}
    coupled = {first for first, _, _, _ in joint_couplings(model)}
    for j in range(model.njnt):
        if j in coupled:
            continue
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j)
        kind = int(model.jnt_type[j])
        if not name or set(name) & UNSAFE_IN_JOINT_ANGLES:
            continue
        if kind not in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE)):
            continue
        if model.jnt_limited[j]:
            low, high = (float(x) for x in model.jnt_range[j])
        elif kind == int(mujoco.mjtJoint.mjJNT_HINGE):
            low, high = -math.pi, math.pi
        else:
            low, high = -0.1, 0.1
        q[name] = rng.uniform(low, high) - float(model.qpos0[model.jnt_qposadr[j]])
    return q


@dataclass
class FullResult:
    """One model of the full corpus: MuJoCo's verdict, ours, and what disagrees."""

    model: str
    compiles: str
    agrees: str
    code: str
    verdicts: str
    seconds: float
    failures: list[str]


def full_row(binary: Path, root: Path, path: Path) -> FullResult:
    """MuJoCo compiles the model?; our report (default options, then `--pose custom` at two seeded random
    configurations); our mass, COM and gravity torques against MuJoCo's at each of the three poses."""
    name = str(path.relative_to(root))
    run = validate(binary, path, [], FULL_TIMEOUT)
    failures = []
    if run.code is None:
        failures.append(f"hang: no report within {FULL_TIMEOUT:.0f} s")
    elif run.crashed():
        failures.append(f"crash: exit code {run.code}: {run.stderr.strip()[-300:]}")
    code = "hang" if run.code is None else str(run.code)
    result = FullResult(name, "", "–", code, verdicts(run.report), run.seconds, failures)
    try:
        model = mujoco.MjModel.from_xml_path(str(path))
    except (ValueError, mujoco.FatalError) as error:
        message = str(error).splitlines()[0].removeprefix("Error: ")
        result.compiles = f"no: {message}"
        return result
    result.compiles = "yes"
    if run.report is None:
        return result
    if (run.report.get("statics") or {}).get("total_mass") is None:
        result.agrees = "– (no statics)"
        return result
    rng = random.Random(f"{SEED}:{name}")
    poses: list[tuple[str, dict[str, float] | None]] = [("qpos0", None)]
    if random_configuration(model, random.Random(0)):
        poses += [(f"random {i + 1}", random_configuration(model, rng)) for i in range(RANDOM_CONFIGURATIONS)]
    compared = 0
    problems: list[str] = []
    for label, wanted in poses:
        report = run.report
        if wanted is not None:
            angles = ",".join(f"{joint}={value!r}" for joint, value in wanted.items())
            extra = ["--pose", "custom", "--samples", "200"] + (["--joint-angles", angles] if angles else [])
            posed = validate(binary, path, extra, FULL_TIMEOUT)
            result.seconds += posed.seconds
            if posed.code is None or posed.crashed() or posed.report is None:
                failures.append(f"{label}: no report (exit code {posed.code}): {posed.stderr.strip()[-300:]}")
                continue
            report = posed.report
        configuration = (report.get("statics") or {}).get("configuration") or {}
        for joint, value in (wanted or {}).items():
            if joint in configuration and configuration[joint] != value:
                problems.append(f"{label}: joint {joint} analysed at {configuration[joint]}, asked {value}")
        theirs = values_at(model, configuration)
        problems += [f"{label}: {p}" for p in compare(theirs, report)]
        compared = len(theirs["forces"])
    failures += problems
    figures = f"{float(sum(model.body_mass)):.6g} kg, {compared} joint torques × {len(poses)} poses"
    result.agrees = ("yes" if not problems else f"**no** ({len(problems)} values)") + f" ({figures})"
    return result


def stand_in_note(path: Path, stand: Path, changed: dict[str, StandIn]) -> str:
    """What the stand-in of the file, or of the files it includes, dropped ("–" when nothing)."""
    notes = []
    relative = path.relative_to(stand)
    files = [relative]
    try:
        for include in ET.parse(path).getroot().iter("include"):
            included = (path.parent / include.get("file", "")).resolve()
            if stand.resolve() in included.parents:
                files.append(included.relative_to(stand.resolve()))
    except ET.ParseError:
        pass
    for file in files:
        dropped = changed.get(str(file))
        if dropped is not None:
            lost = ", ".join(f"`{b}`" for b in dropped.losing) or "none"
            where = "" if file == relative else f" (in `{file.name}`)"
            notes.append(f"{dropped.meshes} missing meshes, {dropped.geoms} geoms dropped{where}; "
                         f"bodies losing mass: {lost}")
    return "; ".join(notes) or "–"


def full(binary: Path, root: Path, only: str | None = None) -> int:
    """The full-corpus table (Markdown, stdout), the failures (stderr); 1 when any. Runs on a stand-in
    tree (target/menagerie-stand-in) where the files naming a mesh the snapshot lacks are rewritten
    without it (the last column says what that dropped), everything else linked to `root`. `only`: just
    the model files whose path under the tree contains it."""
    stand = REPO / "target" / "menagerie-stand-in"
    changed = stand_in_tree(root, stand)
    models = [m for m in full_models(stand) if only is None or only in str(m.relative_to(stand))]
    if not models:
        print(f"{root}: no Menagerie model folders here", file=sys.stderr)
        return 2
    print("| model | MuJoCo compiles | we agree (mass, COM, gravity torques at qpos0 and 2 random poses) "
          "| exit code | verdicts (overall: sections) | time (s) | stand-in for meshes the snapshot lacks |")
    print("|---|---|---|---|---|---|---|")
    failed = []
    start = time.monotonic()
    for path in models:
        r = full_row(binary, stand, path)
        note = stand_in_note(path, stand, changed)
        print(f"| {r.model} | {r.compiles} | {r.agrees} | {r.code} | {r.verdicts} | {r.seconds:.2f} "
              f"| {note} |", flush=True)
        failed += [f"{r.model}: {f}" for f in r.failures]
    print(f"\n{len(models)} models, {time.monotonic() - start:.0f} s in all", file=sys.stderr)
    for line in failed:
        print(line, file=sys.stderr)
    return 1 if failed else 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="make the variants from --source")
    parser.add_argument("--check", action="store_true", help="also check the variants are up to date")
    parser.add_argument("--source", type=Path, default=REPO / "target/menagerie-src")
    parser.add_argument(
        "--full",
        type=Path,
        metavar="DIR",
        help="instead: every model of a whole Menagerie tree with its meshes (not committed; e.g. "
        "target/menagerie-full), one table row each",
    )
    parser.add_argument(
        "--extract",
        type=Path,
        metavar="GIT_DIR",
        help="first write --full DIR from this fetched snapshot (a bare git directory) at --commit",
    )
    parser.add_argument("--commit", default="HEAD", help="the commit --extract writes")
    parser.add_argument("--only", metavar="TEXT", help="with --full: only the model files whose path contains TEXT")
    parser.add_argument(
        "--binary",
        type=Path,
        default=Path(os.environ.get("URDF_VALIDATE", REPO / "target/release/urdf_validate")),
    )
    args = parser.parse_args()
    source = args.source.resolve()
    binary = args.binary.resolve()
    if not binary.is_file():
        print(f"{binary}: no urdf_validate binary here (build it with `cargo build --release`, or give "
              "--binary PATH or $URDF_VALIDATE)", file=sys.stderr)
        return 2
    if args.write and not source.is_dir():
        print(f"{source}: no hand-copied Menagerie originals to make the variants from", file=sys.stderr)
        return 2
    full_root = args.full.resolve() if args.full else None
    # MuJoCo writes its warnings to MUJOCO_LOG.TXT in the working directory: not into the repository.
    os.chdir(tempfile.mkdtemp(prefix="menagerie-"))
    if full_root is not None:
        if args.extract is not None:
            for path, blob in extract(args.extract.resolve(), args.commit, full_root):
                print(f"missing from the snapshot: {path} (blob {blob})")
        return full(binary, full_root, args.only)
    if args.write:
        write(source)
    failed = 0
    if args.check and source.is_dir():
        for model in MODELS:
            original = source / model.folder / model.file
            if original.is_file():
                variant, _, _ = mesh_free(original.read_text())
                if (DATA / model.folder / model.file).read_text() != variant:
                    print(f"{model.folder}/{model.file}: STALE (not what --write makes)")
                    failed += 1
    print("| model | kind | MuJoCo compiles the variant "
          "| we agree (mass, COM, gravity torques at the statics pose) "
          "| exit code | verdicts (overall: sections) | bodies the variant lost mass of |")
    print("|---|---|---|---|---|---|---|")
    details = []
    for model in MODELS:
        line, ok, problems = row(model, binary)
        print(line)
        if not ok:
            failed += 1
            details.extend(f"{model.folder}: {p}" for p in problems)
    for line in details:
        print(line, file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
