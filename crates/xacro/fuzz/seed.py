"""Seed a fuzz corpus: `python3 seed.py TARGET CORPUS_DIR CRATE_TESTS_DIR [EXTRA_XACRO_DIR...]`.

expand: every *.xacro under the crate's tests and the extra directories. expression: every case of
tests/golden/expr/cases.tsv and every ${...} found in those files.
"""

import hashlib
import pathlib
import re
import sys


def unescape(s):
    return re.sub(r"\\(.)", lambda m: {"t": "\t", "n": "\n", "r": "\r"}.get(m.group(1), m.group(1)), s)


def main():
    target, out, tests, *extra = sys.argv[1:]
    out = pathlib.Path(out)
    files = sorted(pathlib.Path(tests).rglob("*.xacro"))
    for d in extra:
        if pathlib.Path(d).is_dir():
            files += sorted(pathlib.Path(d).rglob("*.xacro"))
    texts = [f.read_text(errors="replace") for f in files]
    if target == "expand":
        seeds = texts
    else:
        seeds = []
        for line in (pathlib.Path(tests) / "golden/expr/cases.tsv").read_text().splitlines():
            cols = line.split("\t")
            if len(cols) >= 2 and cols[0] in ("case", "prop"):
                seeds.append(unescape(cols[2] if cols[0] == "prop" else cols[1]))
        for t in texts:
            seeds += re.findall(r"\$\{([^}]*)\}", t)
    for s in dict.fromkeys(seeds):
        data = s.encode()
        (out / hashlib.sha1(data).hexdigest()).write_bytes(data)


main()
