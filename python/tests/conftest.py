"""Shared paths for the tests of the installed wheel (run by scripts/test-python.sh)."""

from __future__ import annotations

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "robots" / "mobile_manipulator.urdf"


@pytest.fixture
def example() -> Path:
    """The example robot that ships with the repository (a wheeled base with an arm: PASS)."""
    assert EXAMPLE.is_file(), EXAMPLE
    return EXAMPLE
