"""The ``cpu`` extra's registration (python/seasim/_cpu_runtime.py): the ICD folder it writes for
the OpenCL loader, and that nothing happens without the runtime. test_wheel.py installs the extra
into a fresh environment and renders with it."""

from __future__ import annotations

import os
from pathlib import Path

from seasim import _cpu_runtime


def test_the_vendor_folder_lists_the_driver_beside_the_loaders_own_files(tmp_path):
    vendors = tmp_path / "vendors"
    vendors.mkdir()
    (vendors / "pocl.icd").write_text("libpocl.so.2\n")
    (vendors / "README").write_text("not an ICD file\n")
    driver = tmp_path / "lib" / "libintelocl.so"
    folder = _cpu_runtime.write_vendor_folder(driver, vendors, tmp_path / "cache")
    files = {p.name: p.read_text() for p in folder.iterdir()}
    assert files == {"pocl.icd": "libpocl.so.2\n", "seasim-pip-libintelocl.icd": f"{driver}\n"}
    # The same content gives the same folder, written once; different content a different one.
    assert _cpu_runtime.write_vendor_folder(driver, vendors, tmp_path / "cache") == folder
    (vendors / "other.icd").write_text("libother.so\n")
    assert _cpu_runtime.write_vendor_folder(driver, vendors, tmp_path / "cache") != folder
    assert not list((tmp_path / "cache").glob(".tmp-*"))


def test_a_missing_vendors_folder_leaves_only_the_driver(tmp_path):
    driver = Path("/opt/x/libintelocl.so")
    folder = _cpu_runtime.write_vendor_folder(driver, tmp_path / "absent", tmp_path / "cache")
    assert [p.name for p in folder.iterdir()] == ["seasim-pip-libintelocl.icd"]


def test_without_the_runtime_nothing_is_registered(monkeypatch, tmp_path):
    monkeypatch.setattr(_cpu_runtime, "_library_folders", lambda: [tmp_path])
    monkeypatch.setenv("OCL_ICD_VENDORS", "/somewhere")
    assert _cpu_runtime.register() is None
    assert os.environ["OCL_ICD_VENDORS"] == "/somewhere"
