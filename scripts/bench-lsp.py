#!/usr/bin/env python3
"""Latency of `urdf_validate server` on PR2: time from a change to its first (structural) diagnostics and to
its physics diagnostics, as the client sees them (a raw LSP client, standard library only), and the
server's resident memory after 100 edits.

    python3 scripts/bench-lsp.py [--bin target/release/urdf_validate] [--robots ../shared/robots] [--edits 100]

Build the release binary first (`cargo build --release -p urdf-validate-cli`). The client-side times include
the server's 30 ms typing pause (debounce); the server's own pass times (URDF_VALIDATOR_LSP_TIMINGS on its
stderr) are reported too. Medians over the edits; the machine's load shows in them (compare CPU time).
"""

import argparse
import json
import os
import pathlib
import queue
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time


class Client:
    """A minimal LSP client over the server's stdin/stdout."""

    def __init__(self, command, env):
        self.process = subprocess.Popen(
            command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env
        )
        self.messages = queue.Queue()
        self.stderr = []
        threading.Thread(target=self._read, daemon=True).start()
        threading.Thread(target=self._read_stderr, daemon=True).start()
        self.next_id = 0

    def _read(self):
        stream = self.process.stdout
        while True:
            header = b""
            while not header.endswith(b"\r\n\r\n"):
                byte = stream.read(1)
                if not byte:
                    return
                header += byte
            length = int(header.split(b"Content-Length:")[1].split(b"\r\n")[0])
            self.messages.put((time.perf_counter(), json.loads(stream.read(length))))

    def _read_stderr(self):
        for line in self.process.stderr:
            self.stderr.append(line.decode(errors="replace").rstrip())

    def send(self, message):
        body = json.dumps(message).encode()
        self.process.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.process.stdin.flush()

    def request(self, method, params):
        self.next_id += 1
        self.send({"jsonrpc": "2.0", "id": self.next_id, "method": method, "params": params})
        while True:
            _, message = self.messages.get(timeout=120)
            if message.get("id") == self.next_id:
                return message

    def notify(self, method, params):
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def diagnostics(self, version, count, timeout=120):
        """The arrival times of the first `count` publications for `version`."""
        times = []
        deadline = time.perf_counter() + timeout
        while len(times) < count:
            at, message = self.messages.get(timeout=max(0.0, deadline - time.perf_counter()))
            if message.get("method") == "textDocument/publishDiagnostics":
                if message["params"].get("version") == version:
                    times.append((at, message["params"]["diagnostics"]))
        return times


def rss_mib(pid):
    for line in pathlib.Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def cpu_seconds(pid):
    fields = pathlib.Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main():
    repo = pathlib.Path(__file__).resolve().parent.parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bin", default=str(repo / "target/release/urdf_validate"))
    parser.add_argument("--robots", default=os.environ.get("URDF_VALIDATOR_SHARED_ROBOTS", str(repo / "../shared/robots")))
    parser.add_argument("--edits", type=int, default=100)
    args = parser.parse_args()
    robots = pathlib.Path(args.robots)
    pr2_source = robots / "pr2/pr2_description/robots/pr2.urdf"
    if not pr2_source.is_file():
        sys.exit(f"bench-lsp: {pr2_source} not found (pass --robots)")
    work = pathlib.Path(tempfile.mkdtemp(prefix="bench-lsp-"))
    pr2 = work / "pr2.urdf"
    shutil.copy(pr2_source, pr2)
    text = pr2.read_text()
    uri = pr2.as_uri()
    env = dict(os.environ, URDF_VALIDATOR_LSP_TIMINGS="1")
    client = Client([args.bin, "server", "--package-path", str(robots / "pr2")], env)
    client.request("initialize", {"processId": os.getpid(), "capabilities": {}, "rootUri": work.as_uri()})
    client.notify("initialized", {})
    start = time.perf_counter()
    client.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "xml", "version": 1, "text": text}})
    [(structure, _), (physics, findings)] = client.diagnostics(1, 2)
    print(f"open: structure {1e3 * (structure - start):.1f} ms, physics {1e3 * (physics - start):.1f} ms "
          f"({len(findings)} diagnostics), RSS {rss_mib(client.process.pid):.1f} MiB")
    # Each edit types one character into the first comment and waits for both passes.
    comment = text.index("<!--") + 4
    line = text.count("\n", 0, comment)
    column = comment - (text.rfind("\n", 0, comment) + 1)
    first, second, cpu = [], [], []
    for version in range(2, args.edits + 2):
        cpu_before = cpu_seconds(client.process.pid)
        sent = time.perf_counter()
        position = {"line": line, "character": column}
        client.notify("textDocument/didChange", {
            "textDocument": {"uri": uri, "version": version},
            "contentChanges": [{"range": {"start": position, "end": position}, "text": "x"}],
        })
        [(structure, _), (physics, _)] = client.diagnostics(version, 2)
        first.append(1e3 * (structure - sent))
        second.append(1e3 * (physics - sent))
        cpu.append(1e3 * (cpu_seconds(client.process.pid) - cpu_before))
    print(f"{args.edits} edits: first (structural) diagnostics median {statistics.median(first):.1f} ms "
          f"(min {min(first):.1f}, max {max(first):.1f}); physics median {statistics.median(second):.1f} ms "
          f"(min {min(second):.1f}, max {max(second):.1f}); server CPU per edit median {statistics.median(cpu):.0f} ms")
    passes = {"structure": [], "physics": []}
    for entry in client.stderr:
        if " pass of " in entry:
            kind = entry.split("urdf_validate server: ")[1].split(" ")[0]
            passes[kind].append(float(entry.rsplit(" in ", 1)[1].split(" ms")[0]))
    for kind, times in passes.items():
        if times:
            print(f"server-side {kind} pass: median {statistics.median(times):.1f} ms over {len(times)}")
    print(f"RSS after {args.edits} edits: {rss_mib(client.process.pid):.1f} MiB")
    client.request("shutdown", None)
    client.notify("exit", None)
    client.process.wait(timeout=30)
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
