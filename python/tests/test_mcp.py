"""`urdf_validate mcp` through the official `mcp` Python client, as an agent's MCP client uses it.

The server is the command named by URDF_VALIDATE_BIN, else `urdf_validate` on PATH (the native binary
or the wheel's console command); without one the tests skip, or fail under CI. Works with the `mcp`
client 1.x (camelCase result fields) and 2.x (snake_case).
"""

from __future__ import annotations

import asyncio
import os
import shutil
from pathlib import Path
from typing import Any, Awaitable, Callable, TypeVar

import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "robots" / "mobile_manipulator.urdf"
TOOLS = {
    "validate_urdf",
    "validate_urdf_string",
    "check_pick_task",
    "run_pick_task",
    "run_pick_sweep",
    "fix_urdf",
    "list_rules",
    "explain_rule",
}
# Few workspace samples: fast, and enough for the example robot's verdicts.
SAMPLES = 300

T = TypeVar("T")


def _needed(what: str) -> None:
    """Skip for lack of `what`, or fail under CI, where everything must be there."""
    if os.environ.get("CI"):
        pytest.fail(f"{what} (CI is set: every test must run)")
    pytest.skip(what)


def _server_command() -> str:
    command = os.environ.get("URDF_VALIDATE_BIN") or shutil.which("urdf_validate")
    if not command:
        _needed("no urdf_validate: set URDF_VALIDATE_BIN or put it on PATH")
    return str(command)


def _field(result: Any, snake: str, camel: str) -> Any:
    """A result field: `is_error` in mcp 2.x, `isError` in 1.x."""
    return getattr(result, snake) if hasattr(result, snake) else getattr(result, camel)


def _structured(result: Any) -> Any:
    return _field(result, "structured_content", "structuredContent")


def _is_error(result: Any) -> bool:
    return bool(_field(result, "is_error", "isError"))


def _text(result: Any) -> str:
    return result.content[0].text


def _session(work: Callable[[Any], Awaitable[T]]) -> T:
    """Start the server, initialise a client session, run `work(session)`, close both."""
    try:
        from mcp import ClientSession, StdioServerParameters
        from mcp.client.stdio import stdio_client
    except ImportError:
        _needed("the `mcp` client package is not installed (pip install mcp)")
    env = {
        name: os.environ[name]
        for name in ("URDF_VALIDATOR_CACHE_DIR", "PATH")
        if name in os.environ
    }
    server = StdioServerParameters(command=_server_command(), args=["mcp"], env=env, cwd=str(REPO))

    async def run() -> T:
        async with stdio_client(server) as (read, write):
            async with ClientSession(read, write) as session:
                await session.initialize()
                return await asyncio.wait_for(work(session), timeout=300)

    return asyncio.run(run())


def test_the_tools_are_listed_with_their_arguments() -> None:
    async def work(session: Any) -> Any:
        return await session.list_tools()

    tools = {tool.name: tool for tool in _session(work).tools}
    assert TOOLS <= set(tools), sorted(tools)
    schema = _field(tools["validate_urdf"], "input_schema", "inputSchema")
    assert {"path", "xml", "base_dir"} <= set(schema["properties"])
    assert "wheeled" in schema["properties"]["robot_type"]["enum"]
    pick = _field(tools["check_pick_task"], "input_schema", "inputSchema")
    assert {"urdf_path", "target_position", "target_orientation", "object_mass_kg"} <= set(
        pick["properties"]
    )


def test_validate_urdf_returns_the_report_of_the_example_robot() -> None:
    async def work(session: Any) -> Any:
        return await session.call_tool(
            "validate_urdf", {"path": str(EXAMPLE), "samples": SAMPLES}
        )

    result = _session(work)
    assert not _is_error(result), _text(result)
    report = _structured(result)
    assert report["overall_status"] == "PASS"
    assert report["robot_name"] == "mobile_manipulator"
    assert report["workspace"]["samples"] == SAMPLES
    # The text is the verdict, then one line per finding.
    assert _text(result).startswith("mobile_manipulator: PASS")


def test_check_pick_task_answers_with_the_five_sub_checks() -> None:
    async def work(session: Any) -> Any:
        return await session.call_tool(
            "check_pick_task",
            {
                "urdf_path": str(EXAMPLE),
                "target_position": [0.5, 0.0, 0.75],
                "target_orientation": "top_down",
                "object_mass_kg": 0.5,
                "samples": SAMPLES,
            },
        )

    result = _session(work)
    assert not _is_error(result), _text(result)
    response = _structured(result)
    assert response["task_type"] == "pick"
    assert [check["name"] for check in response["sub_checks"]] == [
        "reach",
        "reach_orientation",
        "payload_strength",
        "stability_during_reach",
        "self_collision",
    ]
    assert response["overall_status"] in {"PASS", "FAIL", "UNKNOWN"}
    for check in response["sub_checks"]:
        assert check["status"] in {"PASS", "FAIL", "N/A", "UNKNOWN"}
        assert check["reason"]


def test_errors_are_tool_results_and_the_server_goes_on(tmp_path: Path) -> None:
    missing = tmp_path / "no_such_robot.urdf"

    async def work(session: Any) -> Any:
        no_file = await session.call_tool("validate_urdf", {"urdf_path": str(missing)})
        bad_pose = await session.call_tool(
            "validate_urdf", {"urdf_path": str(EXAMPLE), "pose": "sideways"}
        )
        no_rule = await session.call_tool("explain_rule", {"code": "U9999"})
        rule = await session.call_tool("explain_rule", {"code": "U205"})
        return no_file, bad_pose, no_rule, rule

    no_file, bad_pose, no_rule, rule = _session(work)
    assert _is_error(no_file)
    assert str(missing) in _text(no_file)
    assert "expected a URDF or xacro file" in _text(no_file)
    assert _is_error(bad_pose)
    assert "sideways" in _text(bad_pose)
    assert _is_error(no_rule)
    assert "U9999" in _text(no_rule)
    assert not _is_error(rule)
    assert _structured(rule)["name"] == "inertia-not-positive-definite"


def test_a_sweep_answers_every_request_in_order() -> None:
    async def work(session: Any) -> Any:
        return await session.call_tool(
            "run_pick_sweep",
            {
                "requests": [
                    {"urdf_path": str(EXAMPLE), "target_position": [0.4, 0.0, 0.8]},
                    {"urdf_path": str(EXAMPLE), "target_position": [9.0, 0.0, 0.8]},
                ],
                "samples": SAMPLES,
            },
        )

    result = _session(work)
    assert not _is_error(result), _text(result)
    responses = _structured(result)["responses"]
    assert len(responses) == 2
    assert responses[1]["sub_checks"][0]["name"] == "reach"
    assert responses[1]["sub_checks"][0]["status"] == "FAIL"
