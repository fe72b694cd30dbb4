#!/usr/bin/env python3
"""Latency of `urdf_validate server` on PR2, as the client sees it (a raw LSP client, standard library only)
and as the server times its passes (URDF_VALIDATOR_LSP_TIMINGS on its stderr), per kind of edit:

- open: the first, full analysis (every arm sampled);
- comment, effort, mass: edits that leave the arms' kinematics and geometry as they were, so their physics
  pass takes the sampled arms from the document's memo;
- left-arm origin: one arm's joint origin moves (that arm is sampled again; the other arm too when the moved
  links are among the pairs it checks for self-collision);
- left tool frame origin: the left arm's tip frame (no geometry) moves: that arm only is sampled again;
- left forearm camera frame origin: a frame without geometry (nothing below it has any) on the left arm: it
  moves with the arm but sampling never places it, so nothing is sampled again;
- torso origin: both arms move (everything sampled again: the full analysis, the baseline of the ratios);
- cancel: kinematic edits typed faster than a physics pass, each cancelling the one under way; how long a
  cancelled pass took to stop after its cancellation;

and the server's resident memory at the end. "Physics published" is the time from the change to the physics
pass's diagnostics as the client sees it; "server pass" the pass's own time (both include the 30 ms typing
pause when an arm is sampled).

    python3 scripts/bench-lsp.py [--bin target/release/urdf_validate] [--robots ../shared/robots] [--edits 20]

Build the release binary first (`cargo build --release -p urdf-validate-cli`). Medians over the edits; the
machine's load shows in them (compare the ratios).
"""

import argparse
import json
import os
import pathlib
import re
import shutil
import statistics
import sys
import tempfile
import time

from lsp_client import Client, position, rss_mib


def publications(client, version, count, timeout=120):
    """The arrival times and diagnostics of the first `count` publications for `version`."""
    found = []
    while len(found) < count:
        message = client.wait_notification(
            lambda m: m.get("method") == "textDocument/publishDiagnostics" and m["params"].get("version") == version,
            timeout)
        found.append((time.perf_counter(), message["params"]["diagnostics"]))
    return found


def value_span(text, element, tag, attribute):
    """Where the value of `attribute` of the first `<tag>` in the first element starting with `element`
    is (`tag` None: of that element itself)."""
    at = text.index(element)
    if tag is not None:
        at = text.index("<" + tag, at)
    match = re.compile(attribute + r'="([^"]*)"').search(text, at)
    return match.start(1), match.end(1)


class Document:
    """PR2 open in the server, edited as an editor would (the client keeps its own copy of the text)."""

    PASS_LINE = re.compile(r"(structure|physics) pass of \S+ \(version Some\((\d+)\)\) in ([\d.]+) ms "
                           r"\(arms kept (\d+), sampled (\d+)\)")
    CANCELLED_LINE = re.compile(r"cancelled physics pass of \S+ stopped ([\d.]+) ms after its cancellation \(in (\w+)\)")

    def __init__(self, client, uri, text):
        self.client, self.uri, self.text, self.version = client, uri, text, 1
        client.notify("textDocument/didOpen",
                      {"textDocument": {"uri": uri, "languageId": "xml", "version": 1, "text": text}})

    def replace(self, start, end, new_text):
        """Replace text[start:end] by `new_text` in the server and here; the version sent."""
        self.version += 1
        change = {"range": {"start": position(self.text, start), "end": position(self.text, end)}, "text": new_text}
        self.text = self.text[:start] + new_text + self.text[end:]
        self.client.notify("textDocument/didChange",
                           {"textDocument": {"uri": self.uri, "version": self.version}, "contentChanges": [change]})
        return self.version

    def server_passes(self):
        """Per (pass, version): (milliseconds, arms kept, arms sampled), from the server's stderr."""
        passes = {}
        for entry in list(self.client.stderr):
            match = self.PASS_LINE.search(entry)
            if match:
                kind, version, ms, kept, sampled = match.groups()
                passes[(kind, int(version))] = (float(ms), int(kept), int(sampled))
        return passes

    def physics_done(self, version, timeout=120):
        """When the client read the server's line saying the physics pass of `version` is done (its
        diagnostics are published right after it)."""
        deadline = time.perf_counter() + timeout
        while time.perf_counter() < deadline:
            for at, entry in list(self.client.stderr_times):
                match = self.PASS_LINE.search(entry)
                if match and match.group(1) == "physics" and int(match.group(2)) == version:
                    return at
            time.sleep(0.001)
        raise TimeoutError(f"no physics pass of version {version}")

    def cancellations(self):
        """How long each cancelled physics pass took to stop, and in which stage it was."""
        return [(float(m.group(1)), m.group(2)) for e in list(self.client.stderr) if (m := self.CANCELLED_LINE.search(e))]


def median(values):
    return statistics.median(values) if values else float("nan")


def scenario(document, name, edits, edit):
    """`edits` edits made by `edit(document, k)`, each waited for (both passes): the figures."""
    client_ms, versions = [], []
    for k in range(edits):
        sent = time.perf_counter()
        version = edit(document, k)
        client_ms.append(1e3 * (document.physics_done(version) - sent))
        versions.append(version)
    passes = document.server_passes()
    server = [passes[("physics", v)] for v in versions if ("physics", v) in passes]
    return {
        "edit": name,
        "edits": edits,
        "client_physics_ms": median(client_ms),
        "server_physics_ms": median([ms for ms, _, _ in server]),
        "arms_kept": median([kept for _, kept, _ in server]),
        "arms_sampled": median([sampled for _, _, sampled in server]),
    }


def set_value(element, tag, attribute, value):
    """An edit that sets `attribute` (of `tag` in `element`) to `value(k)`, a new value at every edit (a
    value seen before would be in the memo)."""
    def edit(document, k):
        start, end = value_span(document.text, element, tag, attribute)
        return document.replace(start, end, value(k))
    return edit


def torso(first):
    """Edits of the torso's height: both arms move (nothing is kept)."""
    return set_value('<joint name="torso_lift_joint"', "origin", "xyz",
                     lambda k: f"-0.05 0 {0.739675 + 1e-6 * (first + k + 1):.6f}")


def type_in_comment(document, k):
    at = document.text.index("<!--") + 4
    return document.replace(at, at, "x")


def main():
    repo = pathlib.Path(__file__).resolve().parent.parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bin", default=str(repo / "target/release/urdf_validate"))
    parser.add_argument("--robots", default=os.environ.get("URDF_VALIDATOR_SHARED_ROBOTS", str(repo / "../shared/robots")))
    parser.add_argument("--edits", type=int, default=20, help="edits per kind (default 20)")
    parser.add_argument("--json", help="also write the figures to this file")
    args = parser.parse_args()
    robots = pathlib.Path(args.robots)
    pr2_source = robots / "pr2/pr2_description/robots/pr2.urdf"
    if not pr2_source.is_file():
        sys.exit(f"bench-lsp: {pr2_source} not found (pass --robots)")
    work = pathlib.Path(tempfile.mkdtemp(prefix="bench-lsp-"))
    pr2 = work / "pr2.urdf"
    shutil.copy(pr2_source, pr2)
    env = dict(os.environ, URDF_VALIDATOR_LSP_TIMINGS="1")
    client = Client([args.bin, "server", "--package-path", str(robots / "pr2")], env)
    client.request("initialize", {"processId": os.getpid(), "capabilities": {}, "rootUri": work.as_uri()})
    client.notify("initialized", {})
    start = time.perf_counter()
    document = Document(client, pr2.as_uri(), pr2.read_text())
    [(structure, _), (physics, findings)] = publications(client, 1, 2)
    print(f"open: structure {1e3 * (structure - start):.1f} ms, physics {1e3 * (physics - start):.1f} ms "
          f"({len(findings)} diagnostics)")
    results = [
        scenario(document, "torso origin (full analysis)", args.edits, torso(0)),
        scenario(document, "comment", args.edits, type_in_comment),
        scenario(document, "effort", args.edits,
                 set_value('<joint name="r_shoulder_pan_joint"', "limit", "effort", lambda k: f"{30 + k}")),
        scenario(document, "mass", args.edits,
                 set_value('<link name="r_shoulder_pan_link"', "mass", "value", lambda k: f"{25.8 + 0.01 * k:.2f}")),
        scenario(document, "left-arm origin", args.edits,
                 set_value('<joint name="l_wrist_roll_joint"', "origin", "xyz", lambda k: f"0 0 {1e-4 * (k + 1):.4f}")),
        scenario(document, "left tool frame origin", args.edits,
                 set_value('<joint name="l_gripper_tool_joint"', "origin", "xyz", lambda k: f"{0.18 + 1e-4 * (k + 1):.4f} 0 0")),
        scenario(document, "left forearm camera frame origin", args.edits,
                 set_value('<joint name="l_forearm_cam_frame_joint"', "origin", "xyz",
                           lambda k: f".135 0 {0.044 + 1e-4 * (k + 1):.4f}")),
    ]
    full_client, full_server = results[0]["client_physics_ms"], results[0]["server_physics_ms"]
    print(f"{'edit':<30} {'physics published':>18} {'of full':>8} {'server pass':>12} {'of full':>8} "
          f"{'arms kept':>10} {'sampled':>8}")
    for r in results:
        r["client_fraction_of_full"] = r["client_physics_ms"] / full_client
        r["server_fraction_of_full"] = r["server_physics_ms"] / full_server
        print(f"{r['edit']:<30} {r['client_physics_ms']:>15.1f} ms {100 * r['client_fraction_of_full']:>7.1f}% "
              f"{r['server_physics_ms']:>9.1f} ms {100 * r['server_fraction_of_full']:>7.1f}% "
              f"{r['arms_kept']:>10g} {r['arms_sampled']:>8g}")
    # Kinematic edits every 60 ms: the physics pass starts 30 ms after each and the next edit cancels it.
    edit = torso(args.edits)
    for k in range(args.edits):
        edit(document, k)
        time.sleep(0.06)
    publications(client, document.version, 2)
    cancelled = document.cancellations()
    stops = [ms for ms, _ in cancelled]
    stages = sorted({stage for _, stage in cancelled})
    print(f"cancel: {len(stops)} physics passes cancelled (in {', '.join(stages)}); stopped after median "
          f"{median(stops):.2f} ms, max {max(stops, default=float('nan')):.2f} ms")
    rss = client.rss_mib()
    print(f"RSS at the end: {rss:.1f} MiB")
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps({
            "results": results,
            "cancel_stop_ms": {"count": len(stops), "median": median(stops), "max": max(stops, default=None)},
            "rss_mib": rss,
        }, indent=2) + "\n")
    client.shutdown()
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
