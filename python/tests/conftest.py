"""Shared paths for the tests of the installed wheel (run by scripts/test-python.sh)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "robots" / "mobile_manipulator.urdf"


@pytest.fixture
def example() -> Path:
    """The example robot that ships with the repository (a wheeled base with an arm: PASS)."""
    assert EXAMPLE.is_file(), EXAMPLE
    return EXAMPLE


def shared_robot(relative: str) -> Path:
    """A robot of ``../shared/robots`` (``URDF_VALIDATOR_SHARED_ROBOTS``); absent: a failure under CI, else a
    skip saying so."""
    root = Path(os.environ.get("URDF_VALIDATOR_SHARED_ROBOTS", REPO.parent / "shared" / "robots"))
    path = root / relative
    if not path.is_file():
        message = f"{path} is absent (../shared/robots; set URDF_VALIDATOR_SHARED_ROBOTS)"
        if os.environ.get("CI"):
            pytest.fail(message)
        pytest.skip(message)
    return path
