"""Shared fixtures: a fast reduced scene, the CLI binary when there is one."""

from __future__ import annotations

import os
import pathlib
import shutil

import pytest

#: The repository (python/tests/ → ../..).
REPOSITORY = pathlib.Path(__file__).resolve().parents[2]

#: A reduced example 1 that runs in well under a second: a coarse mesh, the path to a/h = 1,
#: no plots.
FAST = {
    "mesh": {"nx": 16, "ny": 8},
    "solver": {"max_amplitude_over_h": 1.0},
    "output": {"plots": False},
}


@pytest.fixture
def fast_scene() -> dict:
    """A fresh copy of :data:`FAST`."""
    return {section: dict(keys) for section, keys in FAST.items()}


def cli_binary() -> pathlib.Path | None:
    """The ``wrinkle`` CLI to compare with: ``WRINKLE_CLI``, else the repository's release or
    debug build, else one on ``PATH``."""
    named = os.environ.get("WRINKLE_CLI")
    if named:
        return pathlib.Path(named)
    for profile in ("release", "debug"):
        candidate = REPOSITORY / "target" / profile / "wrinkle"
        if candidate.is_file():
            return candidate
    found = shutil.which("wrinkle")
    return pathlib.Path(found) if found else None


@pytest.fixture
def cli() -> pathlib.Path:
    """The CLI binary, or the test is skipped."""
    binary = cli_binary()
    if binary is None:
        pytest.skip("no wrinkle CLI binary (build it, or set WRINKLE_CLI)")
    return binary
