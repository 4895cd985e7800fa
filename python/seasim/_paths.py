"""Where an installed wheel keeps seasim's data and its OpenImageIO module.

The C++ core looks for them through SEASIM_DATA_DIR and SEASIM_LIB_DIR (host/util/paths.h,
host/util/module_loader.h) before its build-time folders. A wheel carries them inside the package,
so they are set here, on import, unless the user has set them: nobody has to set a variable.
"""

from __future__ import annotations

import os
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent


def point_core_at_package() -> None:
    data = PACKAGE_DIR / "data"
    if (data / "cie1931_2deg_cmf.csv").is_file():
        os.environ.setdefault("SEASIM_DATA_DIR", str(data))
    lib = PACKAGE_DIR / "lib"
    if lib.is_dir():
        os.environ.setdefault("SEASIM_LIB_DIR", str(lib))


def scenes_dir() -> Path | None:
    """The example scenes shipped in a wheel (None in a build tree: use the checkout's scenes/)."""
    scenes = PACKAGE_DIR / "scenes"
    return scenes if scenes.is_dir() else None
