"""`make wheel` gives a wheel that installs into a fresh virtual environment and renders there,
finding its data and its image module inside the package (no variables set, no source tree)."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np

from conftest import BUILD_DIR, SOURCE_DIR

RENDER = """
import json, sys, numpy as np, seasim
scene = seasim.Scene.load(seasim.scenes_dir() + "/flat_sea.toml", overrides={"camera.width": 64, "camera.height": 36})
frame = seasim.Renderer(scene).render()
np.save(sys.argv[1], frame.rgb)
print(json.dumps({"data_dir": seasim.data_dir(), "file": seasim.__file__}))
"""


def test_make_wheel_installs_into_a_fresh_venv_and_renders(tmp_path, flat_sea_frame):
    subprocess.run(["make", "--no-print-directory", "-C", str(SOURCE_DIR), "wheel", f"BUILD={BUILD_DIR}"], check=True,
                   capture_output=True)
    wheels = sorted(BUILD_DIR.glob("seasim-*.whl"), key=os.path.getmtime)
    assert wheels, "make wheel left no wheel in the build folder"
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    subprocess.run([str(venv / "bin" / "pip"), "install", "-q", str(wheels[-1])], check=True)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "SEASIM_DATA_DIR", "SEASIM_LIB_DIR")}
    out = subprocess.run([str(venv / "bin" / "python"), "-c", RENDER, str(tmp_path / "rgb.npy")], cwd=tmp_path, env=env,
                         capture_output=True, text=True, check=True).stdout
    where = json.loads(out.splitlines()[-1])
    assert where["file"].startswith(str(venv)) and where["data_dir"].startswith(str(venv))
    assert np.array_equal(np.load(tmp_path / "rgb.npy"), flat_sea_frame.rgb)
