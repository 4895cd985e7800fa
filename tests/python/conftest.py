"""Shared set-up of the Python package's tests (ctest's python.pytest runs them; CMake sets the
environment: PYTHONPATH to the build folder's package, SEASIM_BINARY, SEASIM_SOURCE_DIR, SEASIM_BUILD_DIR,
and the PoCL / kernel caches)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import seasim

SOURCE_DIR = Path(os.environ.get("SEASIM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BUILD_DIR = Path(os.environ.get("SEASIM_BUILD_DIR", SOURCE_DIR / "build"))
BINARY = Path(os.environ.get("SEASIM_BINARY", BUILD_DIR / "seasim"))
SMALL = {"camera.width": 64, "camera.height": 36}


def scene_path(name: str) -> Path:
    return SOURCE_DIR / "scenes" / name


@pytest.fixture(scope="session")
def flat_sea() -> seasim.Scene:
    return seasim.Scene.load(scene_path("flat_sea.toml"), overrides=SMALL)


@pytest.fixture(scope="session")
def flat_sea_frame(flat_sea) -> seasim.Frame:
    return seasim.Renderer(flat_sea).render()
