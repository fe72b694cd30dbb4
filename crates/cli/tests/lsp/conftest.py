"""End-to-end tests of `urdf_validate server` with a real LSP client (pytest-lsp): shared set-up.

Run by scripts/test-lsp.sh, which builds the binary and sets URDF_VALIDATE_BIN. PR2 comes from
URDF_VALIDATOR_SHARED_ROBOTS (../shared/robots); without it the tests needing it skip, or fail under
CI=true.
"""

import asyncio
import os
import pathlib
import shutil

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig
from pytest_lsp.client import (
    DEFAULT_CLIENT_FEATURES,
    LanguageClient,
    register_lsp_features,
)
from pygls.protocol import default_converter

BIN = os.environ.get("URDF_VALIDATE_BIN", "urdf_validate")
ROBOTS = os.environ.get("URDF_VALIDATOR_SHARED_ROBOTS")
PR2_PACKAGES = pathlib.Path(ROBOTS, "pr2") if ROBOTS else None


def need_shared_robots() -> pathlib.Path:
    """The shared robots folder; skip without it (fail under CI=true)."""
    if ROBOTS and pathlib.Path(ROBOTS).is_dir():
        return pathlib.Path(ROBOTS)
    message = "URDF_VALIDATOR_SHARED_ROBOTS is not set to the shared robots folder"
    if os.environ.get("CI") == "true":
        pytest.fail(message)
    pytest.skip(message)


def make_client() -> LanguageClient:
    """pytest-lsp's client, also keeping every publishDiagnostics in order (`client.published`)."""
    client = LanguageClient(converter_factory=default_converter)
    client.published = []

    def publish(client: LanguageClient, params: types.PublishDiagnosticsParams):
        client.diagnostics[params.uri] = params.diagnostics
        client.published.append(params)

    features = dict(DEFAULT_CLIENT_FEATURES)
    features[types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS] = publish
    register_lsp_features(client, features)
    return client


def server_command() -> list[str]:
    command = [BIN, "server"]
    if PR2_PACKAGES is not None:
        command += ["--package-path", str(PR2_PACKAGES)]
    return command


@pytest_lsp.fixture(
    config=ClientServerConfig(server_command=server_command(), client_factory=make_client)
)
async def client(lsp_client: LanguageClient):
    params = types.InitializeParams(capabilities=types.ClientCapabilities())
    await lsp_client.initialize_session(params)
    yield
    await lsp_client.shutdown_session()


async def wait_for(what, predicate, timeout=60.0):
    """The first truthy `predicate()`, polled; fails naming `what` after `timeout` seconds."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + timeout
    while True:
        value = predicate()
        if value:
            return value
        if loop.time() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        await asyncio.sleep(0.02)


def codes(client: LanguageClient, uri: str) -> list[str]:
    return sorted(d.code for d in client.diagnostics.get(uri, []) if d.code)


def open_file(client: LanguageClient, path: pathlib.Path, version: int = 1) -> str:
    uri = path.as_uri()
    client.text_document_did_open(
        types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(
                uri=uri, language_id="xml", version=version, text=path.read_text()
            )
        )
    )
    return uri


def change(client: LanguageClient, uri: str, version: int, text: str) -> None:
    """Replace the whole text of `uri`."""
    client.text_document_did_change(
        types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=text)],
        )
    )


def position_of(text: str, needle: str, delta: int = 1) -> types.Position:
    """The LSP position `delta` characters into the first `needle` of `text` (ASCII text)."""
    offset = text.index(needle) + delta
    line = text.count("\n", 0, offset)
    column = offset - (text.rfind("\n", 0, offset) + 1)
    return types.Position(line=line, character=column)


def copy_pr2(tmp_path: pathlib.Path) -> pathlib.Path:
    robots = need_shared_robots()
    source = robots / "pr2/pr2_description/robots/pr2.urdf"
    target = tmp_path / "pr2.urdf"
    shutil.copy(source, target)
    return target
