"""A CPU OpenCL runtime from PyPI (``pip install seasim[cpu]``), found without environment variables.

The ``cpu`` extra installs Intel's OpenCL CPU runtime as three wheels (intel-opencl-rt, its maths
libraries intel-cmplr-lib-rt, and oneTBB); pip puts their shared libraries into the environment's
``lib/`` folder. The system's OpenCL loader (ocl-icd) does not look there, so on import, before the
core is loaded, this module:

- loads the wheels' oneTBB first. One process holds one ``libtbb.so.12``: the core links it too, and
  whichever is loaded first serves both. The Intel driver needs symbols that Debian 12's oneTBB
  (2021.8) lacks, while the newer oneTBB keeps the older one's ABI, so the newer one must come first;
- writes an ICD folder (in the user's cache) listing the Intel driver beside the ICD files the loader
  would have read anyway (``$OCL_ICD_VENDORS`` if set, else /etc/OpenCL/vendors), and points
  ``OCL_ICD_VENDORS`` at it. The loader reads the variable on the first OpenCL call, after import.

Nothing happens when the runtime is not installed. tests/runtimes/install_intel_opencl.sh does the
same for the command line from the same wheels.
"""

from __future__ import annotations

import ctypes
import hashlib
import os
import site
import sys
import sysconfig
import tempfile
from pathlib import Path
from typing import Optional

DRIVER = "libintelocl.so"
SYSTEM_VENDORS = Path("/etc/OpenCL/vendors")


def _library_folders() -> list[Path]:
    """Where pip puts a wheel's ``<name>.data/data/lib`` files: the scheme's data path + lib."""
    folders = [Path(sysconfig.get_path("data")) / "lib", Path(sys.prefix) / "lib"]
    if site.ENABLE_USER_SITE and site.USER_BASE:
        folders.append(Path(site.USER_BASE) / "lib")
    unique = []
    for folder in folders:
        if folder not in unique:
            unique.append(folder)
    return unique


def find_driver() -> Optional[Path]:
    """The pip-installed Intel OpenCL CPU driver, or None."""
    for folder in _library_folders():
        if (folder / DRIVER).is_file():
            return folder / DRIVER
    return None


def _cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "seasim" / "opencl-vendors"


def _vendor_files(vendors: Path) -> list[Path]:
    if vendors.is_file():  # ocl-icd also takes a single .icd file
        return [vendors]
    if not vendors.is_dir():
        return []
    return sorted(p for p in vendors.iterdir() if p.suffix == ".icd" and p.is_file())


def write_vendor_folder(driver: Path, vendors: Path, cache: Path) -> Path:
    """A folder of ICD files: the driver's own beside copies of those in ``vendors``.

    Its name hashes its content, so each distinct set is written once, completely (a temporary
    folder renamed into place), and never changed afterwards; processes may share it.
    """
    files = {f"seasim-pip-{driver.stem}.icd": f"{driver}\n"}
    for icd in _vendor_files(vendors):
        try:
            files[icd.name] = icd.read_text()
        except OSError:
            continue  # an unreadable ICD file: the loader would have skipped it as well
    digest = hashlib.sha256(repr(sorted(files.items())).encode()).hexdigest()[:16]
    folder = cache / digest
    if folder.is_dir():
        return folder
    cache.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=".tmp-", dir=cache))
    for name, text in files.items():
        (tmp / name).write_text(text)
    try:
        tmp.rename(folder)
    except OSError:  # another process wrote the same folder first
        for p in tmp.iterdir():
            p.unlink()
        tmp.rmdir()
    return folder


def register() -> Optional[Path]:
    """Makes a pip-installed Intel OpenCL CPU runtime visible to the OpenCL loader; its driver or None."""
    driver = find_driver()
    if driver is None:
        return None
    tbb = driver.parent / "libtbb.so.12"
    if tbb.is_file():
        ctypes.CDLL(str(tbb), mode=ctypes.RTLD_GLOBAL)
    vendors = Path(os.environ.get("OCL_ICD_VENDORS") or SYSTEM_VENDORS)
    try:
        folder = write_vendor_folder(driver, vendors, _cache_dir())
    except OSError as e:
        print(f"seasim: cannot register the Intel OpenCL CPU runtime ({e}); set OCL_ICD_VENDORS to a folder "
              f"holding an .icd file that names {driver}", file=sys.stderr)
        return None
    os.environ["OCL_ICD_VENDORS"] = str(folder)
    return driver
