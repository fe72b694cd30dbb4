#!/usr/bin/env python3
"""Write the committed seeds of the `lsp_messages` fuzz target (seeds/lsp_messages/), in its input format
(README): byte 0 the mode (3: a raw byte stream; else records), records separated by 0xFF, each a framing
byte and a body (framing 0 or 1: a message generated from `[op, uri, id, a, b, c, d, e, text...]`).

    python3 crates/cli/fuzz/make-seeds.py
"""

import json
import pathlib

SEP = b"\xff"
HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "seeds" / "lsp_messages"

# Generated-message ops (fuzz_targets/lsp_messages.rs, `generated`).
INITIALIZE, INITIALIZED, OPEN, CHANGE, REPLACE, HOVER, COMPLETION, DEFINITION, REFERENCES, SYMBOLS, \
    CODE_ACTION, CANCEL, SAVE_OR_CLOSE = range(13)
SHUTDOWN, EXIT = 0xFD, 0xFE
ROBOT_URI, XACRO_URI, MACROS_URI, SDF_URI, UNTITLED_URI = range(5)

XACRO = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="length" value="0.4"/>
  <xacro:macro name="segment" params="name parent">
    <joint name="${name}_joint" type="revolute"><parent link="${parent}"/><child link="${name}"/>
      <limit lower="-1" upper="1" effort="3" velocity="1"/></joint>
    <link name="${name}"><inertial><mass value="${length * 2}"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  </xacro:macro>
  <link name="base"/>
  <xacro:segment name="upper" parent="base"/>
  <xacro:segment name="lower" parent="upper"/>
</robot>
"""

MACROS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="side"><link name="${side}_wheel"/></xacro:macro>
</robot>
"""

SDF = """<?xml version="1.0"?>
<sdf version="1.9"><model name="cart">
  <link name="base"><inertial><mass>1</mass></inertial></link>
  <link name="pole"><pose relative_to="slider">0 0 0.5 0 0 0</pose><inertial><mass>0.1</mass></inertial></link>
  <joint name="slider" type="prismatic"><parent>base</parent><child>pole</child>
    <axis><xyz>1 0 0</xyz><limit><lower>-1</lower><upper>1</upper></limit></axis></joint>
</model></sdf>
"""


def gen(op, uri=ROBOT_URI, id_=0, a=0, b=0, c=0, d=0, e=0, text=b""):
    """A record generating a message."""
    if isinstance(text, str):
        text = text.encode()
    return bytes([0, op, uri, id_, a, b, c, d, e]) + text


def framed(body, kind=2):
    """A record framing `body` as it is (kind 2: plain; 3: lowercase header and Content-Type; 4: LF)."""
    if not isinstance(body, bytes):
        body = json.dumps(body).encode()
    return bytes([kind]) + body


def structured(*records):
    return b"\x00" + SEP.join(records)


def raw_frame(body):
    if not isinstance(body, bytes):
        body = json.dumps(body).encode()
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


def request(id_, method, params):
    return {"jsonrpc": "2.0", "id": id_, "method": method, "params": params}


def notification(method, params):
    return {"jsonrpc": "2.0", "method": method, "params": params}


ROBOT_PATH = "file:///tmp/urdf-lsp-fuzz/robot.urdf"
SMALL = '<robot name="r">\n  <link name="a"/>\n  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>\n</robot>\n'

seeds = {
    # A whole session of generated messages on the built-in robot: open, edit, every request, shutdown.
    "session_generated": structured(
        gen(INITIALIZE, id_=1),
        gen(INITIALIZED),
        gen(OPEN, a=1),
        gen(CHANGE, a=6, b=20, c=6, d=28, e=2, text="elbow"),
        gen(HOVER, id_=2, a=6, b=23),
        gen(COMPLETION, id_=3, a=7, b=20),
        gen(CODE_ACTION, id_=4, a=0, b=0, c=20, d=0, e=1),
        gen(DEFINITION, id_=5, a=7, b=22),
        gen(REFERENCES, id_=6, a=2, b=16, c=1),
        gen(SYMBOLS, id_=7),
        gen(CANCEL, id_=6),
        gen(REPLACE, e=3),
        gen(SAVE_OR_CLOSE, a=0),
        gen(SHUTDOWN, id_=1),
        gen(EXIT),
    ),
    # xacro, a macro library and SDFormat, edited so that they break and mend.
    "session_formats": structured(
        gen(INITIALIZE, id_=1),
        gen(INITIALIZED),
        gen(OPEN, uri=XACRO_URI, a=1, text=XACRO),
        gen(OPEN, uri=MACROS_URI, a=1, text=MACROS),
        gen(OPEN, uri=SDF_URI, a=1, text=SDF),
        gen(CHANGE, uri=XACRO_URI, a=2, b=30, c=2, d=33, e=2, text="'"),
        gen(HOVER, uri=XACRO_URI, id_=2, a=11, b=20),
        gen(CHANGE, uri=XACRO_URI, a=2, b=30, c=2, d=31, e=3, text="\""),
        gen(COMPLETION, uri=MACROS_URI, id_=3, a=2, b=30),
        gen(SYMBOLS, uri=SDF_URI, id_=4),
        gen(CHANGE, uri=SDF_URI, a=3, b=0, c=60, d=0, e=2, text=""),
        gen(DEFINITION, uri=SDF_URI, id_=5, a=3, b=40),
        gen(SAVE_OR_CLOSE, uri=XACRO_URI, a=1),
        gen(OPEN, uri=UNTITLED_URI, a=1),
        gen(HOVER, uri=UNTITLED_URI, id_=6, a=2, b=16),
    ),
    # The same kind of session as JSON text, framed three ways: the mutations reach the JSON itself.
    "session_json": structured(
        framed(request(1, "initialize", {"processId": None, "capabilities": {}, "rootUri": None})),
        framed(notification("initialized", {}), kind=3),
        framed(notification("textDocument/didOpen", {"textDocument": {
            "uri": ROBOT_PATH, "languageId": "xml", "version": 1, "text": SMALL}})),
        framed(notification("textDocument/didChange", {"textDocument": {"uri": ROBOT_PATH, "version": 2},
            "contentChanges": [{"range": {"start": {"line": 1, "character": 14},
                                          "end": {"line": 1, "character": 15}}, "text": "base"}]}), kind=4),
        framed(request(2, "textDocument/hover", {"textDocument": {"uri": ROBOT_PATH},
                                                 "position": {"line": 2, "character": 50}})),
        framed(request(3, "textDocument/codeAction", {"textDocument": {"uri": ROBOT_PATH},
            "range": {"start": {"line": 0, "character": 0}, "end": {"line": 3, "character": 0}},
            "context": {"diagnostics": [], "only": ["source.fixAll"]}})),
        framed(notification("$/cancelRequest", {"id": 3})),
        framed(request(4, "shutdown", None)),
        framed(notification("exit", None)),
    ),
    # Bad frames among good ones: not JSON, a batch, an object that is no message, an id that is no id, a
    # header without Content-Length, a length that is no number, a message before initialize, a request
    # before `initialized`, a response from the client, a body cut by the end.
    "malformed": structured(
        framed(b"not json"),
        framed(request(9, "textDocument/hover", {})),
        framed(b"[1, 2]"),
        framed({"jsonrpc": "2.0"}),
        framed({"jsonrpc": "2.0", "id": {"an": "object"}}),
        framed({"jsonrpc": "2.0", "id": 1, "result": None}),
        bytes([5]) + b'{"jsonrpc":"2.0","method":"initialized"}',
        bytes([6]) + b'{"jsonrpc":"2.0","id":2,"method":"shutdown"}',
        gen(INITIALIZE, id_=1),
        framed(request(2, "textDocument/hover", {"textDocument": {"uri": ROBOT_PATH}})),
        gen(OPEN, a=1, text="<robot name='x'><link name='a'><inertial><mass value='-1'/></inertial></link>"),
        gen(CHANGE, a=63, b=0, c=63, d=0, e=2, text="lost"),
        gen(HOVER, id_=3, a=0, b=200),
        framed(b'{"jsonrpc":"2.0","id":4,"method":"textDocument/documentSymbol","params":{"textDocument":7}}'),
        bytes([7]) + b'{"jsonrpc":"2.0","method":"initia',
    ),
    # A raw stream: good and bad frames as bytes, blank lines, a body running into the next header.
    "raw_stream": b"\x03" + b"".join([
        raw_frame(request(1, "initialize", {"capabilities": {}})),
        b"\r\n\r\n",
        raw_frame(notification("initialized", {})),
        b"Content-Length: 5\r\nContent-Type: application/json\r\n\r\n{oops",
        b"X-Unknown: 1\r\n\r\nnot framed",
        raw_frame(notification("textDocument/didOpen", {"textDocument": {
            "uri": ROBOT_PATH, "languageId": "xml", "version": 1, "text": SMALL}})),
        b"content-length:  abc\r\n\r\n",
        raw_frame(request(2, "textDocument/documentSymbol", {"textDocument": {"uri": ROBOT_PATH}})),
        b"Content-Length: 999999999999\r\n\r\n",
    ]),
    # Only the lifecycle: exit before initialize, with messages after it that must not be read.
    "exit_first": structured(gen(CANCEL), gen(EXIT), gen(INITIALIZE, id_=1), framed(b"never read")),
}

OUT.mkdir(parents=True, exist_ok=True)
for name, data in seeds.items():
    (OUT / name).write_bytes(data)
    print(f"{OUT / name}: {len(data)} bytes")
