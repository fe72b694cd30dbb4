#!/usr/bin/env python3
"""Whether a change leaves every report as it was: two urdf_validate binaries (before and after) on the same
robots, their JSON reports compared byte for byte with the run's clock left out.

For every robot file under the paths given (default: the four corpora a refactoring must keep — example-robot-
data, Menagerie's models in the repository, dm_control's suite and ../shared/robots), both binaries run with
`--format json --no-write --no-config` (and `--timings` off) and the script prints each file whose report
differs, with the first differing line. `timestamp` is the one field left out; everything else counts,
including `error` texts of files a binary refuses and the exit status.

    python3 scripts/report-identity.py --before /tmp/base/urdf_validate --after target/release/urdf_validate

Exit code 0 when every report is identical, 1 when one differs, 2 when a binary or a corpus is missing.
"""

import argparse
import concurrent.futures
import difflib
import json
import os
import pathlib
import sys

from corpus_files import json_report, robot_files

REPO = pathlib.Path(__file__).resolve().parent.parent


def default_corpora():
    """The corpora of the issue that asked for this script, where this machine has them."""
    corpora = []
    erd = os.environ.get("URDF_VALIDATOR_CORPUS")
    if not erd:
        found = sorted(REPO.glob(".venv/lib/python3*/site-packages/cmeel.prefix/share/example-robot-data/robots"))
        erd = str(found[0]) if found else ""
    corpora.append(("example-robot-data", erd))
    corpora.append(("Menagerie", str(REPO / "crates/urdf-validator/tests/data/menagerie")))
    corpora.append(("dm_control", str(REPO / "target/dm-control/dm_control/suite")))
    corpora.append(("shared robots", str(REPO.parent / "shared/robots")))
    return corpora


def report(binary, path):
    """The report's text without its timestamp, and the exit status (stderr when there is no report)."""
    document, run = json_report(binary, path)
    if document is None:
        return f"(no report) exit {run.returncode}\n{run.stderr}"
    document.pop("timestamp", None)
    return f"exit {run.returncode}\n" + json.dumps(document, indent=1, sort_keys=False)


def compare(before, after, path):
    old, new = report(before, path), report(after, path)
    if old == new:
        return None
    diff = difflib.unified_diff(old.splitlines(), new.splitlines(), lineterm="", n=0)
    changed = [line for line in diff if line[:1] in "+-" and line[:3] not in ("+++", "---")]
    return f"{path}:\n    " + "\n    ".join(changed[:6])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", required=True)
    parser.add_argument("--after", required=True)
    parser.add_argument("--jobs", type=int, default=2, help="files compared at once (default 2)")
    parser.add_argument("paths", nargs="*", help="robot files or folders (default: the four corpora)")
    args = parser.parse_args()
    for binary in (args.before, args.after):
        if not pathlib.Path(binary).is_file():
            print(f"report-identity: no binary {binary}", file=sys.stderr)
            sys.exit(2)
    corpora = [(path, path) for path in args.paths] or default_corpora()
    missing = [name for name, path in corpora if not path or not pathlib.Path(path).exists()]
    if missing:
        print(f"report-identity: missing corpus: {', '.join(missing)}", file=sys.stderr)
        sys.exit(2)
    differing = 0
    for name, path in corpora:
        files = list(robot_files([path]))
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            results = list(pool.map(lambda f: compare(args.before, args.after, f), files))
        for result in filter(None, results):
            print(result)
        changed = sum(1 for r in results if r)
        differing += changed
        print(f"{name}: {len(files)} files, {changed} with another report", flush=True)
    sys.exit(1 if differing else 0)


if __name__ == "__main__":
    main()
