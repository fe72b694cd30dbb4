#!/usr/bin/env python3
"""Golden inertia-from-geometry values from Drake, for the inertia fix (crates/urdf-validator/src/analysis/
geometry_inertia.rs).

Each URDF in FILES (example-robot-data, whose folder is found through `--robots` or the repo's .venv, and
the reference robots in ../shared/robots or $URDF_VALIDATOR_SHARED_ROBOTS) gets, per link, what
`pydrake.multibody.fix_inertia` (`_inertia_fixer.InertiaProcessor._maybe_fix_inertia`) computes for a body:
the geometries of the first role that has any (proximity = <collision>, then illustration = <visual>), each
`CalcSpatialInertia(shape, density=1)` re-expressed and shifted into the body frame by its <origin>
(`RigidTransform(RollPitchYaw(rpy), xyz)`, as Drake's URDF parser reads it) and summed. The shapes are built
here from the URDF's XML rather than by Drake's `Parser`, because the parser refuses a whole file as soon as
one collision mesh is an .stl or .dae (`MakeConvexHull only applies to .obj, .vtk, and .gltf meshes`), which
would leave out every primitive link of most real robots. Per link the
golden keeps the role, the volume (the density-1 mass), the centre of mass and the rotational inertia per
unit mass about the centre of mass in the body frame's axes (Drake's `M_BBo_B_one.get_unit_inertia()`
shifted to the COM): the tensor the fix writes divided by the declared mass. Full precision (`repr`), not
fix_inertia's 5 significant digits.

A link is excluded, with the reason, when Drake cannot compute it: CalcSpatialInertia reads only .obj (and
tetrahedral .vtk) meshes, so a link with an .stl or .dae mesh in the role used is listed in `excluded`.
(Drake integrates an .obj surface as it is, closed or not; the Rust test compares only links whose meshes
are closed, where both integrate the same solid.)

    python scripts/oracle/inertia_golden.py            # regenerate
    python scripts/oracle/inertia_golden.py --check    # regenerate in memory, compare with the files

Dev-only tooling: needs `drake` (PyPI, 1.51.1 used), never a runtime dependency.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from importlib.metadata import version
from pathlib import Path

import numpy as np
import xml.etree.ElementTree as ET

from pydrake.geometry import Box, Capsule, Cylinder, Mesh, Sphere
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.parsing import PackageMap
from pydrake.multibody.tree import CalcSpatialInertia, SpatialInertia, UnitInertia

REPO_ROOT = Path(__file__).resolve().parents[2]
OUT = REPO_ROOT / "crates" / "urdf-validator" / "tests" / "golden" / "inertia"
ROBOTS = REPO_ROOT / ".venv/lib/python3.11/site-packages/cmeel.prefix/share/example-robot-data/robots"
SHARED = Path(os.environ.get("URDF_VALIDATOR_SHARED_ROBOTS", REPO_ROOT.parent / "shared" / "robots"))
# (golden name, root, path under it). Chosen for their .obj meshes (laikago, quadruped, alexander, solo,
# spot) and primitives (talos *_box, pr2's primitive links, quadruped).
FILES = [
    ("laikago", "robots", "laikago_description/urdf/laikago.urdf"),
    ("quadruped", "robots", "quadruped_description/urdf/quadruped.urdf"),
    ("alexander", "robots", "alexander_description/urdf/alexander_v1.lowerBodyOnly.urdf"),
    ("talos_reduced_box", "robots", "talos_data/robots/talos_reduced_box.urdf"),
    ("pr2", "robots", "pr2_description/urdf/pr2.urdf"),
    ("spot", "shared", "spot/spot_description/model.urdf"),
]


def pose(element) -> RigidTransform:
    """The <origin> child of `element` as Drake's URDF parser reads it (xyz, then fixed-axis rpy)."""
    origin = element.find("origin")
    if origin is None:
        return RigidTransform()
    xyz = [float(v) for v in origin.get("xyz", "0 0 0").split()]
    rpy = [float(v) for v in origin.get("rpy", "0 0 0").split()]
    return RigidTransform(RollPitchYaw(rpy), xyz)


def shape(geometry, package_map: PackageMap, urdf_dir: Path):
    """The Drake shape of a URDF <geometry>; a str (why) when Drake cannot compute its inertia."""
    box, cylinder, sphere = geometry.find("box"), geometry.find("cylinder"), geometry.find("sphere")
    capsule, mesh = geometry.find("capsule"), geometry.find("mesh")
    if box is not None:
        return Box(*[float(v) for v in box.get("size").split()])
    if cylinder is not None:
        return Cylinder(float(cylinder.get("radius")), float(cylinder.get("length")))
    if sphere is not None:
        return Sphere(float(sphere.get("radius")))
    if capsule is not None:
        return Capsule(float(capsule.get("radius")), float(capsule.get("length")))
    uri = mesh.get("filename")
    if uri.startswith("package://"):
        package, _, rest = uri[len("package://"):].partition("/")
        path = Path(package_map.GetPath(package)) / rest
    else:
        path = urdf_dir / uri.removeprefix("file://")
    if path.suffix.lower() != ".obj":
        return f"mesh {uri}: CalcSpatialInertia reads only .obj (and tetrahedral .vtk) meshes"
    scale = [float(v) for v in mesh.get("scale", "1 1 1").split()]
    return Mesh(str(path), np.array(scale))


def golden_of(path: Path, package_roots: list[Path]) -> dict:
    package_map = PackageMap()
    for root in package_roots:
        package_map.PopulateFromFolder(str(root))
        # example-robot-data's URIs name the package by its share folder: package://example-robot-data/robots/….
        if root.name == "robots" and not package_map.Contains("example-robot-data"):
            package_map.Add("example-robot-data", str(root.parent))
    links, excluded = {}, {}
    for link in ET.parse(path).getroot().iter("link"):
        name = link.get("name")
        for role in ("collision", "visual"):
            elements = [e for e in link.findall(role) if e.find("geometry") is not None]
            if elements:
                break
        if not elements:
            continue
        total = SpatialInertia(0, np.zeros(3), UnitInertia(0, 0, 0))
        why = None
        for element in elements:
            drake_shape = shape(element.find("geometry"), package_map, path.parent)
            if isinstance(drake_shape, str):
                why = drake_shape
                break
            one = CalcSpatialInertia(drake_shape, 1.0)
            X_BG = pose(element)
            total += one.ReExpress(X_BG.rotation()).Shift(-X_BG.translation())
        if why is not None:
            excluded[name] = why
            continue
        com = total.get_com()
        central = total.Shift(com).CalcRotationalInertia().CopyToFullMatrix3() / total.get_mass()
        links[name] = {
            "role": role,
            "volume": total.get_mass(),
            "com": [float(c) for c in com],
            "unit_inertia": [[float(v) for v in row] for row in central],
        }
    return {"drake": version("drake"), "links": links, "excluded": excluded}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="compare with the committed goldens")
    parser.add_argument("--robots", type=Path, default=ROBOTS, help="example-robot-data's robots folder")
    args = parser.parse_args()
    roots = {"robots": args.robots, "shared": SHARED}
    stale = []
    for name, root, rel in FILES:
        path = roots[root] / rel
        if not path.is_file():
            print(f"inertia_golden: {path} is missing", file=sys.stderr)
            return 2
        golden = golden_of(path, [roots[root]])
        text = json.dumps(golden, indent=1, sort_keys=True) + "\n"
        out = OUT / f"{name}.json"
        if args.check:
            if not out.is_file() or out.read_text() != text:
                stale.append(str(out))
        else:
            OUT.mkdir(parents=True, exist_ok=True)
            out.write_text(text)
            print(f"{out}: {len(golden['links'])} links, {len(golden['excluded'])} excluded")
    if stale:
        print("inertia_golden: stale goldens (regenerate with scripts/oracle/inertia_golden.py):", *stale, sep="\n  ")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
