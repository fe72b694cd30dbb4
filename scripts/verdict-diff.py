#!/usr/bin/env python3
"""Which verdicts a change moves: two urdf_validate binaries (before and after) on the same robots.

For every robot file given (or found under the folders given: `.urdf`, `.xacro`, `.sdf`, and `.xml` files
holding `<mujoco` or `<robot`), both binaries run with `--format json --no-write --no-config` and the
script prints, per file whose outcome differs, the overall status before → after and the rule codes whose
finding counts changed (`U042 +2`, `U601 -1`). A closing note lists and judges these lines.

    python3 scripts/verdict-diff.py --before /tmp/base/urdf_validate --after target/release/urdf_validate \
        crates/urdf-validator/tests/data/menagerie target/dm-control/dm_control/suite

Exit code 0 (the differences are for a person to judge); 2 when a binary is missing.
"""

import argparse
import collections
import pathlib
import sys

from corpus_files import json_report, robot_files


def outcome(binary, path):
    """(overall status or 'refused', Counter of rule codes)."""
    report, run = json_report(binary, path)
    if report is None:
        return f"refused (exit {run.returncode})", collections.Counter()
    return report.get("overall_status", "?"), collections.Counter(f["rule"] for f in report["findings"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", required=True)
    parser.add_argument("--after", required=True)
    parser.add_argument("paths", nargs="+")
    args = parser.parse_args()
    for binary in (args.before, args.after):
        if not pathlib.Path(binary).is_file():
            print(f"verdict-diff: no binary {binary}", file=sys.stderr)
            sys.exit(2)
    files = changed = moved = 0
    for path in robot_files(args.paths):
        files += 1
        (status_before, rules_before), (status_after, rules_after) = (
            outcome(args.before, path),
            outcome(args.after, path),
        )
        deltas = {
            rule: rules_after[rule] - rules_before[rule]
            for rule in sorted(set(rules_before) | set(rules_after))
            if rules_after[rule] != rules_before[rule]
        }
        if status_before == status_after and not deltas:
            continue
        changed += 1
        moved += status_before != status_after
        shown = " ".join(f"{rule} {delta:+d}" for rule, delta in deltas.items())
        print(f"{path}: {status_before} -> {status_after}  {shown}")
    print(f"{files} files, {changed} with other findings, {moved} with another overall status")


if __name__ == "__main__":
    main()
