"""seasim.Renderer and Frame: the image is seasim render's image.exr bit for bit, update() reruns only
what it should, arrays are views, the report and timings are the CLI's."""

from __future__ import annotations

import subprocess
import threading
import time

import numpy as np
import pytest

import seasim
from conftest import BINARY, SMALL, scene_path


def test_rgb_is_float32_h_w_3_and_a_view_not_a_copy(flat_sea_frame):
    rgb = flat_sea_frame.rgb
    assert rgb.shape == (36, 64, 3) and rgb.dtype == np.float32
    assert np.all(np.isfinite(rgb)) and rgb.max() > 0
    assert np.shares_memory(rgb, flat_sea_frame.rgb)  # two reads of .rgb: one buffer
    assert flat_sea_frame.spectral is None


def test_render_equals_the_command_lines_image_exr_bit_for_bit(flat_sea_frame, tmp_path):
    out = tmp_path / "cli"
    sets = [arg for key, value in SMALL.items() for arg in ("--set", f"{key}={value}")]
    subprocess.run([str(BINARY), "render", str(scene_path("flat_sea.toml")), *sets, "-o", str(out)], check=True,
                   capture_output=True)
    from_cli = seasim.read_image(out / "image.exr")
    assert from_cli.shape == flat_sea_frame.rgb.shape
    assert np.array_equal(from_cli, flat_sea_frame.rgb)
    # display() is the PNG's tone map: the same 8-bit levels as the command line's image.png.
    png_levels = np.rint(seasim.read_image(out / "image.png") * 255)
    assert np.array_equal(np.rint(seasim.display(flat_sea_frame) * 255), png_levels)


def test_report_and_timings_describe_the_frame(flat_sea, flat_sea_frame):
    report = flat_sea_frame.report
    assert report["name"] == "flat_sea" and report["nonfinite"] == 0
    assert report["settings"]["width"] == 64 and report["settings"]["height"] == 36
    assert [p["name"] for p in report["plan"]] == list(flat_sea_frame.timings)
    assert report["pass_ms"] == pytest.approx(flat_sea_frame.timings)
    assert all(ms >= 0 for ms in flat_sea_frame.timings.values())
    assert report["device"]["label"]


def test_spectral_where_the_scene_asks_for_it():
    scene = seasim.Scene.load(scene_path("flat_sea.toml"),
                              overrides={**SMALL, "spectral.count": 8, "spectral.spectral_exr": True})
    frame = seasim.Renderer(scene).render()
    assert frame.spectral.shape == (36, 64, 8) and frame.spectral.dtype == np.float32
    assert frame.wavelengths_nm.shape == (8,)
    assert np.all(np.diff(frame.wavelengths_nm) > 0)
    assert frame.spectral.max() > 0


def test_update_reruns_only_the_passes_whose_keys_changed():
    scene = seasim.Scene.load(scene_path("wavy_sea.toml"), overrides=SMALL)
    renderer = seasim.Renderer(scene)
    first = renderer.render()
    assert renderer.last_executed == ["ocean_fft", "sea_single", "nonfinite_check"]
    again = renderer.render()  # nothing changed: nothing runs
    assert renderer.last_executed == [] and np.array_equal(again.rgb, first.rgb)
    renderer.update({"quality.sea_lut_size": 17})  # the sea's table: not the waves
    changed = renderer.render()
    assert "ocean_fft" not in renderer.last_executed and "sea_single" in renderer.last_executed
    fresh = seasim.Renderer(scene.with_overrides({"quality.sea_lut_size": 17})).render()
    assert np.array_equal(changed.rgb, fresh.rgb)
    renderer.update(quality__sea_lut_size=17)  # the same value again, by keyword: a no-op
    renderer.render()
    assert renderer.last_executed == []


def test_a_bad_update_raises_and_changes_nothing(flat_sea):
    renderer = seasim.Renderer(flat_sea)
    renderer.render()
    with pytest.raises(seasim.SceneError, match="<overrides>: key 'sun.zenith_deg'"):
        renderer.update({"sun.zenith_deg": "high"})
    renderer.render()
    assert renderer.last_executed == []  # nothing was marked to run again
    renderer.update({"sun.zenith_deg": 50})  # and the next good update applies as if the bad one never came
    frame = renderer.render()
    fresh = seasim.Renderer(flat_sea.with_overrides({"sun.zenith_deg": 50})).render()
    assert np.array_equal(frame.rgb, fresh.rgb)


def test_unknown_device_is_a_device_error(flat_sea):
    with pytest.raises(seasim.DeviceError, match="no-such-device"):
        seasim.Renderer(flat_sea, device="no-such-device")


def test_the_gil_is_released_while_the_kernels_run():
    # A Python thread keeps ticking while another thread renders; were the GIL held through the
    # kernels, it would stop for the whole render.
    renderer = seasim.Renderer(seasim.Scene.load(scene_path("seabed.toml"),
                                                 overrides={"camera.width": 160, "camera.height": 90}))
    renderer.render()  # kernel builds out of the way
    ticks, done = [], threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    ticker = threading.Thread(target=tick)
    ticker.start()
    time.sleep(0.02)
    renderer.rerun_all()
    t0 = time.perf_counter()
    renderer.render()
    t1 = time.perf_counter()
    done.set()
    ticker.join()
    during = [t for t in ticks if t0 < t < t1]
    longest_pause = float(np.max(np.diff([t0, *during, t1])))
    assert t1 - t0 > 0.05, "the render is too short to tell"
    assert longest_pause < 0.5 * (t1 - t0), f"no tick for {longest_pause:.3f} s of a {t1 - t0:.3f} s render"


def test_layers_are_image_exrs_channels_by_name_and_split_the_image(tmp_path):
    layers = ["range", "object_id", "normal", "clear", "direct", "backscatter", "forward", "lamps", "beta_d"]
    overrides = {**SMALL, "outputs.layers": layers}
    frame = seasim.Renderer(seasim.Scene.load(scene_path("seabed.toml"), overrides=overrides)).render()
    got = frame.layers
    assert set(got) == set(layers) | {"beta_d_mask"}
    assert got["range"].shape == (36, 64) and got["range"].dtype == np.float32
    assert got["object_id"].shape == (36, 64) and got["beta_d_mask"].shape == (36, 64)
    assert got["normal"].shape == (36, 64, 3) and got["direct"].shape == (36, 64, 3)
    ids = got["object_id"]  # 0 water, 1 the bottom, 2... the scene's objects
    assert np.array_equal(ids, np.rint(ids)) and ids.min() >= 0 and np.any(ids == 1) and np.any(ids >= 2)
    # The split sums to the image (docs/layers.md), as in the kernel tests.
    total = got["direct"] + got["backscatter"] + got["forward"] + got["lamps"]
    scale = np.maximum(frame.rgb.max(axis=2, keepdims=True), 1e-30)
    assert np.max(np.abs(total - frame.rgb) / scale) < 1e-5
    # The same numbers as the command line's image.exr channels.
    out = tmp_path / "cli"
    sets = [arg for key, value in SMALL.items() for arg in ("--set", f"{key}={value}")]
    subprocess.run([str(BINARY), "render", str(scene_path("seabed.toml")), *sets, *[f"--output={l}" for l in layers],
                    "-o", str(out)], check=True, capture_output=True)
    exr = seasim.read_image(out / "image.exr")
    assert exr.shape == (36, 64, 3 + 1 + 1 + 3 * 7 + 1)
    assert np.array_equal(exr[:, :, :3], frame.rgb)
    # EXR keeps channels sorted by name, so match each layer channel to a channel of the file.
    columns = [got[name][..., None] if got[name].ndim == 2 else got[name] for name in got]
    for column in np.concatenate(columns, axis=2).transpose(2, 0, 1):
        assert any(np.array_equal(column, exr[:, :, c]) for c in range(3, exr.shape[2]))


def test_no_layers_asked_gives_an_empty_dict(flat_sea_frame):
    assert flat_sea_frame.layers == {}


def test_band_layers_split_the_spectral_image_per_band():
    overrides = {**SMALL, "spectral.count": 4, "spectral.spectral_exr": True,
                 "outputs.layers": ["direct", "backscatter", "forward", "lamps"]}
    frame = seasim.Renderer(seasim.Scene.load(scene_path("seabed.toml"), overrides=overrides)).render()
    bands = frame.band_layers
    assert set(bands) == {"direct", "backscatter", "forward", "lamps"}
    assert all(b.shape == (36, 64, 4) and b.dtype == np.float32 for b in bands.values())
    total = bands["direct"] + bands["backscatter"] + bands["forward"] + bands["lamps"]
    scale = np.maximum(np.abs(frame.spectral).max(axis=2, keepdims=True), 1e-30)
    assert np.max(np.abs(total - frame.spectral) / scale) < 1e-5
    assert frame.layers["direct"].shape == (36, 64, 3)  # the RGB layers as before


def test_spectral_exr_holds_the_layers_per_band_by_name(tmp_path):
    sets = {**SMALL, "spectral.count": 4, "spectral.spectral_exr": "true"}
    args = [a for k, v in sets.items() for a in ("--set", f"{k}={v}")]
    out = tmp_path / "cli"
    subprocess.run([str(BINARY), "render", str(scene_path("seabed.toml")), *args, "--set", 'outputs.layers=["direct"]',
                    "--output", "exr", "--output", "spectral_exr", "-o", str(out)], check=True, capture_output=True)
    info = subprocess.run(["oiiotool", "--info", "-v", str(out / "spectral.exr")], check=True, capture_output=True,
                          text=True).stdout
    # Names hold decimal commas ("S0.437,500000nm"): the list is separated by ", ".
    names = [n.strip() for n in info.split("channel list:")[1].splitlines()[0].split(", ")]
    values = seasim.read_image(out / "spectral.exr")
    assert values.shape == (36, 64, len(names)) and len(names) == 8  # 4 bands, then direct per band
    frame = seasim.Renderer(seasim.Scene.load(scene_path("seabed.toml"), overrides={
        **SMALL, "spectral.count": 4, "spectral.spectral_exr": True, "outputs.layers": ["direct"]})).render()
    nm = frame.wavelengths_nm
    for b in range(4):
        band = f"S0.{nm[b]:.6f}".replace(".", ",").replace("S0,", "S0.") + "nm"
        assert np.array_equal(values[:, :, names.index(band)], frame.spectral[:, :, b])
        assert np.array_equal(values[:, :, names.index("direct." + band)], frame.band_layers["direct"][:, :, b])
