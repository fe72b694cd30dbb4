#!/usr/bin/env python3
"""Soak of `urdf_validate server` on PR2: N random edits (inserts, deletes, replacements at random ranges,
some breaking the XML, some restoring the original text) with random pauses of 0-150 ms, so analyses
start and are cancelled by the next edit (one edit in 100, --settle-rate, waits for its physics pass), and hover, completion, code-action and outline requests among
them, some cancelled ($/cancelRequest) as soon as sent. Standard library only (scripts/lsp_client.py).

    python3 scripts/soak-lsp.py [--edits 10000] [--seed 1] [--bin BINARY | --profile release]

Fails (exit 1) when the server exits, a request gets neither a response nor a cancellation error
(-32800) within 60 s, a response is another error, the server's text differs from the client's copy at a
checkpoint (the outline of the edited document against that of a fresh document opened with the client's
text; at the end, after restoring the original, against the outline of the original), a change is
refused (a line on stderr: the edits never reach past the end), the server's stderr has a panic, or its
resident memory (sampled every --sample-every edits) is not flat after the warm-up: max - min above
--rss-spread MiB, or the median of the last quarter of the samples more than --rss-trend MiB above the
first quarter's. Prints edits, elapsed time, RSS per quarter, requests answered and cancelled, CPU time.

Without PR2 (URDF_VALIDATOR_SHARED_ROBOTS, default ../shared/robots) it skips, unless CI=true: then it fails.
"""

import argparse
import json
import os
import pathlib
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from lsp_client import Client, ServerGone, position  # noqa: E402

REQUEST_CANCELLED = -32800

# Inserted text: URDF pieces, XML that breaks the file (an open tag, a stray quote, an unclosed comment,
# a second root), and text outside ASCII (UTF-16 columns).
SNIPPETS = [
    "x", " ", "\n", "  ", "\n  ", "a", "1", "0.5", "-", "e",
    '<link name="soak_link"/>\n',
    '<joint name="soak_joint" type="fixed"><parent link="base_link"/><child link="soak_link"/></joint>\n',
    '<inertial><mass value="-1"/></inertial>',
    '<origin xyz="0 0 1" rpy="0 0 0"/>',
    '<mesh filename="package://pr2_description/meshes/missing.stl"/>',
    '<limit lower="1" upper="-1" effort="0" velocity="0"/>',
    "<", ">", "</", "/>", '"', "'", "=", "&", "&amp;", "<!--", "-->", "<![CDATA[", "]]>",
    "</robot>", "<robot>", "<link", "</link>", 'name="', "<joint name='j' type='bogus'>",
    "é", "名前", "🤖", "𝄞x",
]


def random_snippet(rng):
    if rng.random() < 0.2:
        return "".join(rng.choice("abcxyz_019 <>/=\"'\n.-") for _ in range(rng.randint(1, 40)))
    return rng.choice(SNIPPETS)


class Document:
    """The client's copy of the text, and the changes that keep the server's in step with it."""

    def __init__(self, text):
        self.original = text
        self.text = text

    def ranged(self, start, end, new):
        """The change replacing code points [start, end) with `new`, applied to the copy."""
        change = {"range": {"start": position(self.text, start), "end": position(self.text, end)}, "text": new}
        self.text = self.text[:start] + new + self.text[end:]
        return change

    def whole(self, new):
        self.text = new
        return {"text": new}

    def random_edit(self, rng):
        """One didChange's content changes, and what kind of edit it is."""
        n = len(self.text)
        if n > 1.3 * len(self.original) or n < 0.5 * len(self.original):
            return [self.whole(self.original)], "restore"
        r = rng.random()
        if r < 0.04:
            return [self.whole(self.original)], "restore"
        if r < 0.06:
            # The original again, as one ranged change over the whole text.
            return [self.ranged(0, n, self.original)], "restore"
        if r < 0.36:
            at = rng.randint(0, n)
            return [self.ranged(at, at, random_snippet(rng))], "insert"
        if r < 0.6:
            start = rng.randint(0, max(0, n - 1))
            return [self.ranged(start, min(n, start + rng.randint(1, 120)), "")], "delete"
        if r < 0.9:
            start = rng.randint(0, max(0, n - 1))
            return [self.ranged(start, min(n, start + rng.randint(1, 40)), random_snippet(rng))], "replace"
        # Two changes in one message, applied in order.
        at = rng.randint(0, n)
        first = self.ranged(at, at, random_snippet(rng))
        start = rng.randint(0, max(0, len(self.text) - 1))
        second = self.ranged(start, min(len(self.text), start + rng.randint(1, 30)), "")
        return [first, second], "two"


def outline(symbols):
    """Names, kinds and ranges of a documentSymbol answer, nested."""
    return [
        (s["name"], s["kind"], json.dumps(s["range"], sort_keys=True), outline(s.get("children") or []))
        for s in symbols or []
    ]


LOAD_ERRORS = {"xml-syntax", "xacro", "not-validated"}


def unvalidated(message, uri, version):
    """Whether `message` publishes, for `uri` at `version`, that its text could not be validated."""
    params = message.get("params") or {}
    return (message.get("method") == "textDocument/publishDiagnostics" and params.get("uri") == uri
            and params.get("version") == version
            and any(d.get("code") in LOAD_ERRORS for d in params.get("diagnostics", [])))


def quarters(values):
    """`values` cut into four runs in order (the last ones longer when it does not divide)."""
    n = len(values)
    return [values[n * i // 4:n * (i + 1) // 4] for i in range(4)]


def binary_of(args, repo):
    if args.bin:
        return args.bin
    if os.environ.get("URDF_VALIDATE_BIN"):
        return os.environ["URDF_VALIDATE_BIN"]
    profile = ["--release"] if args.profile == "release" else []
    print(f"soak-lsp: building urdf_validate ({args.profile})", file=sys.stderr)
    subprocess.run(["cargo", "build", "--quiet", "-p", "urdf-validate-cli", "--bin", "urdf_validate", *profile],
                   cwd=repo, check=True)
    metadata = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"], cwd=repo, check=True,
                              capture_output=True, text=True).stdout
    return str(pathlib.Path(json.loads(metadata)["target_directory"]) / args.profile / "urdf_validate")


def main():
    repo = pathlib.Path(__file__).resolve().parent.parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bin", help="the binary (default: URDF_VALIDATE_BIN, else built with --profile)")
    parser.add_argument("--profile", choices=["release", "debug"], default="release")
    parser.add_argument("--robots", default=os.environ.get("URDF_VALIDATOR_SHARED_ROBOTS", str(repo / "../shared/robots")))
    parser.add_argument("--edits", type=int, default=10000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--max-pause-ms", type=float, default=150.0)
    parser.add_argument("--request-rate", type=float, default=0.3, help="chance of a request after an edit")
    parser.add_argument("--cancel-rate", type=float, default=0.3, help="chance a request is cancelled at once")
    parser.add_argument("--settle-rate", type=float, default=0.01,
                        help="chance that typing pauses after an edit until its physics pass is published")
    parser.add_argument("--checkpoint-every", type=int, default=500)
    parser.add_argument("--sample-every", type=int, help="edits between RSS samples (default: 100, fewer for short runs)")
    parser.add_argument("--warmup", type=float, default=0.1, help="share of the edits before RSS counts")
    parser.add_argument("--rss-spread", type=float, default=30.0, help="MiB allowed between min and max RSS")
    parser.add_argument("--rss-trend", type=float, default=10.0, help="MiB allowed from the first to the last quarter's median")
    args = parser.parse_args()
    sample_every = args.sample_every or max(1, min(100, args.edits // 40))

    pr2_source = pathlib.Path(args.robots) / "pr2/pr2_description/robots/pr2.urdf"
    if not pr2_source.is_file():
        if os.environ.get("CI") == "true":
            sys.exit(f"soak-lsp: FAIL: {pr2_source} not found (CI=true; set URDF_VALIDATOR_SHARED_ROBOTS)")
        print(f"soak-lsp: skipped: {pr2_source} not found (pass --robots)", file=sys.stderr)
        return 0
    binary = binary_of(args, repo)
    rng = random.Random(args.seed)
    work = pathlib.Path(tempfile.mkdtemp(prefix="soak-lsp-"))
    try:
        return soak(args, binary, pr2_source, work, rng, sample_every)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def soak(args, binary, pr2_source, work, rng, sample_every):
    pr2 = work / "pr2.urdf"
    shutil.copy(pr2_source, pr2)
    document = Document(pr2.read_text())
    uri, twin_uri = pr2.as_uri(), (work / "pr2_twin.urdf").as_uri()
    # The server logs each pass it publishes (URDF_VALIDATOR_LSP_TIMINGS): how many physics passes ran to
    # the end, the others cancelled by the next edit.
    env = dict(os.environ, URDF_VALIDATOR_CACHE_DIR=str(work / "cache"), URDF_VALIDATOR_LSP_TIMINGS="1")
    package_path = pathlib.Path(args.robots) / "pr2"
    client = Client([binary, "server", "--package-path", str(package_path)], env)
    failures = []

    def fail(message):
        failures.append(message)
        print(f"soak-lsp: FAIL: {message}", file=sys.stderr)

    answered = cancelled = errors = 0
    pending = []  # request ids not yet checked

    def settle():
        """Every request sent so far has its response (or a cancellation error)."""
        nonlocal answered, cancelled, errors
        for request_id in pending:
            response = client.response(request_id)
            code = (response.get("error") or {}).get("code")
            if code is None:
                answered += 1
            elif code == REQUEST_CANCELLED:
                cancelled += 1
            else:
                errors += 1
                fail(f"request {request_id}: {response['error']}")
        pending.clear()

    def symbols(of_uri):
        return outline(client.request("textDocument/documentSymbol", {"textDocument": {"uri": of_uri}})["result"])

    started = time.perf_counter()
    client.request("initialize", {"processId": os.getpid(), "capabilities": {}, "rootUri": work.as_uri()})
    client.notify("initialized", {})
    client.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "xml", "version": 1,
                                                            "text": document.text}})
    client.wait_notification(lambda m: m.get("method") == "textDocument/publishDiagnostics"
                             and m["params"].get("version") == 1, timeout=120)
    original_outline = symbols(uri)
    samples = [(0, client.rss_mib())]
    kinds = {}
    checkpoints = settled = settled_broken = 0
    version = 1
    try:
        for edit in range(1, args.edits + 1):
            changes, kind = document.random_edit(rng)
            kinds[kind] = kinds.get(kind, 0) + 1
            version += 1
            client.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": version},
                                                     "contentChanges": changes})
            if rng.random() < args.request_rate:
                at = position(document.text, rng.randint(0, len(document.text)))
                method, params = rng.choice([
                    ("textDocument/hover", {"textDocument": {"uri": uri}, "position": at}),
                    ("textDocument/completion", {"textDocument": {"uri": uri}, "position": at}),
                    ("textDocument/codeAction", {"textDocument": {"uri": uri}, "range": {"start": at, "end": at},
                                                 "context": {"diagnostics": []}}),
                    ("textDocument/documentSymbol", {"textDocument": {"uri": uri}}),
                ])
                request_id = client.send_request(method, params)
                pending.append(request_id)
                if rng.random() < args.cancel_rate:
                    client.cancel(request_id)
            if rng.random() < args.settle_rate:
                # A longer pause: this text's physics pass runs to the end and is published (unless the
                # text cannot be validated: then its structure pass publishes the error, and that is all).
                wanted = f"physics pass of {uri} (version Some({version}))"
                deadline = time.perf_counter() + 120
                while True:
                    if any(wanted in line for line in client.stderr[-20:]):
                        settled += 1
                        break
                    if any(unvalidated(m, uri, version) for m in client.drain_notifications()):
                        settled_broken += 1
                        break
                    if time.perf_counter() > deadline or client.process.poll() is not None:
                        fail(f"edit {edit}: no physics pass published for version {version} within 120 s")
                        break
                    time.sleep(0.01)
            else:
                time.sleep(rng.uniform(0, args.max_pause_ms) / 1000)
            client.drain_notifications()
            if client.process.poll() is not None:
                fail(f"the server exited (status {client.process.returncode}) after edit {edit}")
                break
            if edit % sample_every == 0:
                samples.append((edit, client.rss_mib()))
            if edit % args.checkpoint_every == 0 or edit == args.edits:
                settle()
                # The server's text against the client's: a fresh document opened with the client's copy
                # has the same outline, ranges included.
                client.notify("textDocument/didOpen", {"textDocument": {"uri": twin_uri, "languageId": "xml",
                                                                        "version": 1, "text": document.text}})
                edited, fresh = symbols(uri), symbols(twin_uri)
                client.notify("textDocument/didClose", {"textDocument": {"uri": twin_uri}})
                checkpoints += 1
                if edited != fresh:
                    fail(f"edit {edit}: the server's text is not the client's (outlines differ)")
                    break
        settle()
        # Back to the original, as a ranged change: the outline of the original.
        version += 1
        restore = document.ranged(0, len(document.text), document.original)
        client.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": version},
                                                 "contentChanges": [restore]})
        if symbols(uri) != original_outline:
            fail("after restoring the original text, the outline is not the original's")
        client.wait_notification(lambda m: m.get("method") == "textDocument/publishDiagnostics"
                                 and m["params"].get("uri") == uri and m["params"].get("version") == version,
                                 timeout=120)
        samples.append((args.edits, client.rss_mib()))
        cpu = client.cpu_seconds()
        status = client.shutdown()
        if status != 0:
            fail(f"the server exited with status {status} after shutdown and exit")
    except (ServerGone, TimeoutError, BrokenPipeError) as error:
        fail(f"{type(error).__name__}: {error}")
        cpu = float("nan")
    finally:
        if client.process.poll() is None:
            client.process.kill()
    elapsed = time.perf_counter() - started

    time.sleep(0.2)  # the stderr thread's last lines
    panics = [line for line in client.stderr if "panicked" in line]
    refused = [line for line in client.stderr if "none applied" in line or "which is not open" in line]
    if panics:
        fail(f"the server's stderr has a panic: {panics[0]}")
    if refused:
        fail(f"the server refused {len(refused)} change(s): {refused[0]}")

    passes = {kind: sum(1 for line in client.stderr if f"{kind} pass of {uri}" in line)
              for kind in ("structure", "physics")}
    warm = [rss for edit, rss in samples if edit >= args.warmup * args.edits]
    print(f"soak-lsp: {args.edits} edits of PR2 (seed {args.seed}; {', '.join(f'{k} {v}' for k, v in sorted(kinds.items()))}) "
          f"in {elapsed:.0f} s; {checkpoints} checkpoints; requests: {answered} answered, {cancelled} cancelled "
          f"(-32800), {errors} errors; server CPU {cpu:.1f} s; passes published: {passes['structure']} structure, "
          f"{passes['physics']} physics (the others cancelled by a newer edit; {settled} pauses waited for one, {settled_broken} more on a text that does not parse)")
    print(f"soak-lsp: RSS {samples[0][1]:.1f} MiB after opening; {len(samples)} samples, every {sample_every} edits")
    for number, quarter in enumerate(quarters(samples), 1):
        if quarter:
            values = [rss for _, rss in quarter]
            print(f"soak-lsp:   quarter {number} (edits {quarter[0][0]}-{quarter[-1][0]}): RSS min {min(values):.1f}, "
                  f"median {statistics.median(values):.1f}, max {max(values):.1f} MiB")
    if len(warm) >= 4:
        spread = max(warm) - min(warm)
        first, last = quarters(warm)[0], quarters(warm)[-1]
        trend = statistics.median(last) - statistics.median(first)
        print(f"soak-lsp: after the warm-up ({len(warm)} samples): max - min {spread:.1f} MiB (bound {args.rss_spread}), "
              f"last quarter's median - first's {trend:+.1f} MiB (bound {args.rss_trend})")
        if spread > args.rss_spread:
            fail(f"RSS is not flat: max - min {spread:.1f} MiB > {args.rss_spread} MiB")
        if trend > args.rss_trend:
            fail(f"RSS grows: the last quarter's median is {trend:.1f} MiB above the first's (> {args.rss_trend} MiB)")
    elif not failures:
        fail(f"too few RSS samples after the warm-up ({len(warm)}): more edits or a smaller --sample-every")
    if failures:
        print(f"soak-lsp: FAIL ({len(failures)} problem(s))", file=sys.stderr)
        return 1
    print("soak-lsp: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
