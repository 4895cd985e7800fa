"""seasim.devices / device, compare, reference, read_image and run_job against the command line."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import seasim
from conftest import BINARY, SMALL, scene_path

SETS = [arg for key, value in SMALL.items() for arg in ("--set", f"{key}={value}")]


def test_devices_and_selectors():
    listed = seasim.devices()
    assert listed and all(d.label for d in listed)
    chosen = seasim.device("")
    assert any((d.platform_index, d.device_index) == (chosen.platform_index, chosen.device_index) for d in listed)
    pocl = [d for d in listed if d.is_pocl]
    if pocl:  # the CI machine's device: pocl:0 names it as --device does
        assert seasim.device("pocl:0").name == pocl[0].name
    with pytest.raises(seasim.DeviceError, match="no-such-device"):
        seasim.device("no-such-device")


def test_without_an_opencl_platform_the_error_says_how_to_get_one(tmp_path):
    # An empty vendors folder: the OpenCL loader finds no platform at all.
    code = ("import seasim\n"
            "assert seasim.devices() == []\n"
            "try:\n    seasim.device('')\nexcept seasim.DeviceError as e:\n    print(e)\n")
    env = {**os.environ, "OCL_ICD_VENDORS": str(tmp_path)}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    assert "no OpenCL platform found" in out and "pocl-opencl-icd" in out


def test_compare_gives_the_command_lines_numbers(flat_sea, tmp_path):
    renderer = seasim.Renderer(flat_sea)
    a = renderer.render()
    renderer.update({"sun.zenith_deg": 60})
    b = renderer.render()
    np.save(tmp_path / "a.npy", a.rgb)
    np.save(tmp_path / "b.npy", b.rgb)
    cli = subprocess.run([str(BINARY), "compare", str(tmp_path / "a.npy"), str(tmp_path / "b.npy")],
                         capture_output=True, text=True, check=True).stdout
    # The metric lines are "name value"; the lines after them say which exposure was used and how the
    # recorded settings differ.
    expected = {p[0]: float(p[1]) for p in (line.split() for line in cli.splitlines()) if len(p) == 2}
    assert {"rmse_8bit", "max_abs_8bit", "rel_l2", "hue_sat_distance"} <= expected.keys(), cli
    got = seasim.compare(a, b)
    for key, value in expected.items():
        assert got[key] == pytest.approx(value, rel=1e-4, abs=1e-4), key
    assert got["nonfinite"] == 0 and got["rmse_8bit"] > 0
    # Arrays, frames and paths are all images; the same image has no error.
    same = seasim.compare(a.rgb.astype(np.float64), tmp_path / "a.npy")
    assert same["rmse_8bit"] == 0 and same["max_abs_8bit"] == 0 and same["rel_l2"] == 0
    with pytest.raises(seasim.RenderError):
        seasim.compare(a, a.rgb[:10])


def test_reference_equals_seasim_reference(flat_sea, tmp_path):
    ref = seasim.reference(flat_sea, steps=20)
    assert ref.method == "quadrature" and ref.steps == 20 and ref.std_error is None
    assert ref.rgb.shape == (36, 64, 3) and ref.rgb.dtype == np.float32
    out = tmp_path / "ref.exr"
    subprocess.run([str(BINARY), "reference", str(scene_path("flat_sea.toml")), *SETS, "--steps", "20", "-o", str(out)],
                   check=True, capture_output=True)
    assert np.array_equal(seasim.read_image(out), ref.rgb)
    # The fast render is close to its reference (cli_test's bound for this scene is 0.05 levels at
    # full steps; 20 steps leave more quadrature error).
    assert seasim.compare(seasim.Renderer(flat_sea).render(), ref)["rmse_8bit"] < 2.0


def write_job(tmp_path):
    job = tmp_path / "job.toml"
    job.write_text(f"""
[job]
name = "py"
output_dir = "{tmp_path / 'out'}"

[[render]]
name = "noon"
scene = "{scene_path('flat_sea.toml')}"
overrides = {{ "camera.width" = 32, "camera.height" = 18, "sun.zenith_deg" = 30 }}

[[render]]
name = "evening"
scene = "{scene_path('flat_sea.toml')}"
overrides = {{ "camera.width" = 32, "camera.height" = 18, "sun.zenith_deg" = 75 }}
""", encoding="utf-8")
    return job


def test_run_job_renders_resumes_and_reports_progress(tmp_path):
    job = write_job(tmp_path)
    calls = []
    summary = seasim.run_job(job, progress=lambda *a: calls.append(a))
    assert summary["rendered"] == 2 and summary["failed"] == [] and summary["skipped"] == 0
    assert [c[:3] for c in calls] == [(1, 2, "noon"), (2, 2, "evening")]
    for item in ("noon", "evening"):
        report = json.loads((tmp_path / "out" / item / "report.json").read_text(encoding="utf-8"))
        assert report["settings"]["width"] == 32
        assert seasim.read_image(tmp_path / "out" / item / "image.exr").shape == (18, 32, 3)
    again = seasim.run_job(job, resume=True, progress=False)
    assert again["rendered"] == 0 and again["skipped"] == 2
    sharded = seasim.run_job(job, shard="1/2", output_dir=tmp_path / "shard", progress=False)
    assert sharded["rendered"] + sharded["other_shards"] == 2 and sharded["other_shards"] >= 1
    with pytest.raises(ValueError, match="shard is 'i/N'"):
        seasim.run_job(job, shard="half")


def test_run_job_names_a_bad_job_file(tmp_path):
    job = tmp_path / "bad.toml"
    job.write_text('[job]\nname = "x"\noutput_dir = "out"\nspeed = 3\n', encoding="utf-8")
    with pytest.raises(seasim.SceneError) as e:
        seasim.run_job(job, progress=False)
    assert e.value.file == str(job) and e.value.line == 4 and "speed" in str(e.value)


def test_run_job_draws_a_tqdm_bar_else_a_line_per_item(tmp_path, capsys, monkeypatch):
    job = write_job(tmp_path)
    seasim.run_job(job)
    assert "2/2" in capsys.readouterr().err  # tqdm's count (make python-venv installs tqdm)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)  # as without tqdm: import fails
    seasim.run_job(job, output_dir=tmp_path / "plain")
    err = capsys.readouterr().err
    assert "[1/2] noon: done" in err and "[2/2] evening: done" in err


def test_underwater_reference_is_the_path_tracer_of_seasim_reference(tmp_path):
    tiny = {"camera.width": 32, "camera.height": 18}
    scene = seasim.Scene.load(scene_path("seabed.toml"), overrides=tiny)
    calls = []
    ref = seasim.reference(scene, steps=8, seed=3, progress=lambda done, total: calls.append((done, total)))
    assert ref.method == "path tracer" and ref.steps == 8 and ref.info["seed"] == 3
    assert calls[-1] == (8, 8)
    out = tmp_path / "ref.exr"
    sets = [a for k, v in tiny.items() for a in ("--set", f"{k}={v}")]
    subprocess.run([str(BINARY), "reference", str(scene_path("seabed.toml")), *sets, "--steps", "8", "--seed", "3",
                    "-o", str(out)], check=True, capture_output=True)
    assert np.array_equal(seasim.read_image(out), ref.rgb)
    assert np.array_equal(seasim.read_image(tmp_path / "ref.stderr.exr"), ref.std_error)
    # The unscattered part (docs/layers.md), with its standard error, beside it.
    assert ref.direct.shape == ref.rgb.shape and ref.direct.max() > 0
    assert np.array_equal(seasim.read_image(tmp_path / "ref.direct.exr"), ref.direct)
    assert np.array_equal(seasim.read_image(tmp_path / "ref.direct.stderr.exr"), ref.direct_std_error)


def test_sun_single_quadrature_is_the_one_of_seasim_reference(tmp_path):
    # The froxel term's deterministic reference: the same image as the command's, and the froxel render
    # of the term alone within the error the froxel sweep measures (results/BENCHMARKS.md: 1-2.5 %).
    dark = {"camera.width": 48, "camera.height": 27, "underwater.multiple_scattering": False, "sky.radiance": 0,
            "bottom.albedo": 0, "objects[0].albedo": 0, "objects[1].albedo": 0, "objects[2].albedo": 0}
    scene = seasim.Scene.load(scene_path("seabed.toml"), overrides=dark)
    ref = seasim.reference(scene, steps=200, sun_single_quadrature=True, subpixels=2)
    assert ref.method == "quadrature" and ref.steps == 200 and ref.std_error is None
    out = tmp_path / "ss.exr"
    sets = [a for k, v in dark.items() for a in ("--set", f"{k}={str(v).lower()}")]
    subprocess.run([str(BINARY), "reference", str(scene_path("seabed.toml")), *sets, "--sun-single-quadrature",
                    "--subpixels", "2", "--steps", "200", "-o", str(out)], check=True, capture_output=True)
    assert np.array_equal(seasim.read_image(out), ref.rgb)
    frame = seasim.Renderer(scene).render()
    rel = np.sqrt(((frame.rgb - ref.rgb) ** 2).sum() / (ref.rgb ** 2).sum())
    assert ref.rgb.max() > 0 and rel < 0.04, rel


def test_a_progress_callback_that_raises_stops_the_job_and_the_item_stays_done(tmp_path):
    job = write_job(tmp_path)

    def stop(handled, total, item, outcome):
        raise RuntimeError(f"stopped after {item}")

    with pytest.raises(RuntimeError, match="stopped after noon"):
        seasim.run_job(job, progress=stop)
    again = seasim.run_job(job, resume=True, progress=False)
    assert again["skipped"] == 1 and again["rendered"] == 1 and again["failed"] == []
