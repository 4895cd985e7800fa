"""`make wheel` gives a wheel that installs into a fresh virtual environment and renders there,
finding its data and its image module inside the package (no variables set, no source tree); with
the ``cpu`` extra it also brings an OpenCL runtime, found on import with no system driver at all."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from pathlib import Path

import numpy as np
import pytest

from conftest import BUILD_DIR, SOURCE_DIR

RENDER = """
import json, sys, numpy as np, seasim
scene = seasim.Scene.load(seasim.scenes_dir() + "/flat_sea.toml", overrides={"camera.width": 64, "camera.height": 36})
frame = seasim.Renderer(scene).render()
np.save(sys.argv[1], frame.rgb)
print(json.dumps({"data_dir": seasim.data_dir(), "file": seasim.__file__}))
"""


def cached(name: str) -> str:
    """A setting of the build folder's CMakeCache.txt ('' when absent)."""
    for line in (BUILD_DIR / "CMakeCache.txt").read_text().splitlines():
        if line.startswith(name + ":"):
            return line.split("=", 1)[1]
    return ""


@pytest.fixture(scope="module")
def wheel() -> Path:
    # scikit-build-core wipes a build folder whose record names another interpreter's install; make wheel
    # drops the record, so the folder keeps its cache (its test suites) and its object files.
    tests_before = cached("SEASIM_TESTS")
    (BUILD_DIR / ".skbuild-info.json").write_text(json.dumps({"source_dir": "/elsewhere", "skbuild_path": "/elsewhere"}))
    made = subprocess.run(["make", "--no-print-directory", "-C", str(SOURCE_DIR), "wheel", f"BUILD={BUILD_DIR}"],
                          capture_output=True, text=True)
    if made.returncode != 0:
        pytest.fail(f"make wheel failed ({made.returncode}):\n{made.stdout[-4000:]}\n{made.stderr[-4000:]}")
    assert cached("SEASIM_TESTS") == tests_before, "make wheel reset the build folder's CMake cache"
    wheels = sorted(BUILD_DIR.glob("seasim-*.whl"), key=os.path.getmtime)
    assert wheels, "make wheel left no wheel in the build folder"
    return wheels[-1]


def clean_env() -> dict:
    """The test's environment without what points Python or the core at the build tree or a driver."""
    drop = ("PYTHONPATH", "SEASIM_DATA_DIR", "SEASIM_LIB_DIR", "LD_LIBRARY_PATH", "OCL_ICD_VENDORS")
    return {k: v for k, v in os.environ.items() if k not in drop}


def test_make_wheel_installs_into_a_fresh_venv_and_renders(tmp_path, wheel, flat_sea_frame):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    subprocess.run([str(venv / "bin" / "pip"), "install", "-q", str(wheel)], check=True)
    env = clean_env()
    out = subprocess.run([str(venv / "bin" / "python"), "-c", RENDER, str(tmp_path / "rgb.npy")], cwd=tmp_path, env=env,
                         capture_output=True, text=True, check=True).stdout
    where = json.loads(out.splitlines()[-1])
    assert where["file"].startswith(str(venv)) and where["data_dir"].startswith(str(venv))
    assert np.array_equal(np.load(tmp_path / "rgb.npy"), flat_sea_frame.rgb)


CPU_RENDER = """
import json, sys, numpy as np, seasim
names = [d.platform_name for d in seasim.devices()]
scene = seasim.Scene.load(seasim.scenes_dir() + "/flat_sea.toml", overrides={"camera.width": 64, "camera.height": 36})
frame = seasim.Renderer(scene, device="intel").render()
np.save(sys.argv[1], frame.rgb)
print(json.dumps({"platforms": names}))
"""


def wheel_cache() -> Path:
    """Where tests/runtimes/install_intel_opencl.sh (make intel-opencl) keeps the Intel runtime's wheels."""
    if os.environ.get("SEASIM_WHEEL_CACHE"):
        return Path(os.environ["SEASIM_WHEEL_CACHE"])
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "seasim" / "wheels"


def test_the_cpu_extra_brings_an_opencl_runtime_that_is_found_without_variables(tmp_path, wheel, flat_sea_frame):
    cache = wheel_cache()
    assert list(cache.glob("intel_opencl_rt-*.whl")), f"no Intel runtime wheels in {cache}: run make intel-opencl"
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    # The runtime's pinned wheels from the download cache (the same ones make intel-opencl uses).
    subprocess.run([str(venv / "bin" / "pip"), "install", "-q", "--find-links", str(cache), f"{wheel}[cpu]"],
                   check=True)
    # No system driver at all: the loader's own folder is empty, as on a machine with no OpenCL package.
    no_drivers = tmp_path / "no-drivers"
    no_drivers.mkdir()
    env = {**clean_env(), "OCL_ICD_VENDORS": str(no_drivers), "XDG_CACHE_HOME": str(tmp_path / "cache")}
    run = subprocess.run([str(venv / "bin" / "python"), "-c", CPU_RENDER, str(tmp_path / "rgb.npy")], cwd=tmp_path,
                         env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    platforms = json.loads(run.stdout.splitlines()[-1])["platforms"]
    assert platforms and all("Intel" in p for p in platforms), platforms
    # Intel's runtime against PoCL's image (results/runtimes/: at most 8e-3 relative L2 on any scene).
    rgb = np.load(tmp_path / "rgb.npy")
    assert np.isfinite(rgb).all()
    rel_l2 = np.linalg.norm(rgb - flat_sea_frame.rgb) / np.linalg.norm(flat_sea_frame.rgb)
    assert rel_l2 < 1e-3, rel_l2
