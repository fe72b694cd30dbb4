"""A small LSP client over a server's stdin and stdout, standard library only, for the scripts that drive
`urdf_validate server` (scripts/soak-lsp.py). It frames messages with Content-Length headers, reads the
server's messages on a thread (responses by id, notifications in a queue), keeps the server's stderr, and
reads the process's memory and CPU time from /proc.

    from lsp_client import Client
    client = Client([binary, "server"])
    client.request("initialize", {"processId": None, "capabilities": {}, "rootUri": None})
"""

import json
import os
import pathlib
import queue
import subprocess
import threading
import time


class ServerGone(Exception):
    """The server's stdout closed (it exited, or crashed)."""


class Client:
    """One server process and its connection."""

    def __init__(self, command, env=None):
        self.process = subprocess.Popen(
            command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env
        )
        self.notifications = queue.Queue()
        self.stderr = []
        # (the time it was read, the line): for latencies measured on the server's log lines.
        self.stderr_times = []
        self._responses = {}
        self._answered = threading.Condition()
        self._closed = False
        self._next_id = 0
        self._write_lock = threading.Lock()
        threading.Thread(target=self._read_stdout, daemon=True).start()
        threading.Thread(target=self._read_stderr, daemon=True).start()

    # Reading.

    def _read_stdout(self):
        stream = self.process.stdout
        try:
            while True:
                length = None
                while True:
                    line = stream.readline()
                    if not line:
                        return
                    line = line.strip()
                    if not line:
                        if length is not None:
                            break
                        continue
                    name, _, value = line.partition(b":")
                    if name.strip().lower() == b"content-length":
                        length = int(value.strip())
                body = stream.read(length)
                if len(body) < length:
                    return
                message = json.loads(body)
                if "id" in message and "method" not in message:
                    with self._answered:
                        self._responses[message["id"]] = (time.perf_counter(), message)
                        self._answered.notify_all()
                else:
                    self.notifications.put((time.perf_counter(), message))
        finally:
            with self._answered:
                self._closed = True
                self._answered.notify_all()

    def _read_stderr(self):
        for line in self.process.stderr:
            text = line.decode(errors="replace").rstrip("\n")
            self.stderr_times.append((time.perf_counter(), text))
            self.stderr.append(text)

    # Writing.

    def send(self, message):
        body = json.dumps(message).encode()
        with self._write_lock:
            self.process.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
            self.process.stdin.flush()

    def notify(self, method, params):
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def send_request(self, method, params):
        """Send a request without waiting; its id."""
        self._next_id += 1
        self.send({"jsonrpc": "2.0", "id": self._next_id, "method": method, "params": params})
        return self._next_id

    def cancel(self, request_id):
        self.notify("$/cancelRequest", {"id": request_id})

    def response(self, request_id, timeout=60.0):
        """The response to `request_id` (kept until taken), waiting up to `timeout` seconds."""
        deadline = time.perf_counter() + timeout
        with self._answered:
            while request_id not in self._responses:
                if self._closed:
                    raise ServerGone(f"the server closed its output before answering request {request_id}")
                left = deadline - time.perf_counter()
                if left <= 0:
                    raise TimeoutError(f"no response to request {request_id} within {timeout} s")
                self._answered.wait(left)
            return self._responses.pop(request_id)[1]

    def request(self, method, params, timeout=60.0):
        return self.response(self.send_request(method, params), timeout)

    def wait_notification(self, wanted, timeout=60.0):
        """The first notification satisfying `wanted` (earlier ones are dropped)."""
        deadline = time.perf_counter() + timeout
        while True:
            left = deadline - time.perf_counter()
            if left <= 0:
                raise TimeoutError(f"no such notification within {timeout} s")
            try:
                _, message = self.notifications.get(timeout=min(left, 1.0))
            except queue.Empty:
                if self.process.poll() is not None:
                    raise ServerGone(f"the server exited with status {self.process.returncode}")
                continue
            if wanted(message):
                return message

    def drain_notifications(self):
        """The notifications received so far, emptied from the queue."""
        drained = []
        while True:
            try:
                drained.append(self.notifications.get_nowait()[1])
            except queue.Empty:
                return drained

    # The process.

    def rss_mib(self):
        return rss_mib(self.process.pid)

    def cpu_seconds(self):
        return cpu_seconds(self.process.pid)

    def shutdown(self, timeout=30.0):
        """shutdown, exit, and the exit status."""
        self.request("shutdown", None, timeout)
        self.notify("exit", None)
        self.process.stdin.close()
        return self.process.wait(timeout=timeout)


def rss_mib(pid):
    """The resident memory of process `pid`, in MiB (/proc/PID/status, VmRSS)."""
    for line in pathlib.Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def cpu_seconds(pid):
    """User plus system CPU time of process `pid` (every thread), in seconds."""
    fields = pathlib.Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def utf16_units(text):
    return sum(2 if ord(c) > 0xFFFF else 1 for c in text)


def position(text, offset):
    """The LSP position (0-based line, UTF-16 column) of code-point `offset` of `text` (lines end at \\n)."""
    line = text.count("\n", 0, offset)
    start = text.rfind("\n", 0, offset) + 1
    return {"line": line, "character": utf16_units(text[start:offset])}
