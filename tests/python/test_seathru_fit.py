"""The docs' Sea-thru fit (docs/examples/seathru_fit.py) on synthetic layers made here with known
coefficients: the fits recover them, the per-pixel table shows a β_D that varies with range, and
an EXR with the agreed channel names (<layer>.R/.G/.B, <layer>_mask, range) is read back by name and
the right way up, through OpenImageIO's Python module or else oiiotool. Needs NumPy only (not the seasim module): `pytest --noconftest` runs it alone."""
from __future__ import annotations

import importlib.util
import io
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "docs" / "examples" / "seathru_fit.py"
spec = importlib.util.spec_from_file_location("seathru_fit", SCRIPT)
seathru_fit = importlib.util.module_from_spec(spec)
spec.loader.exec_module(seathru_fit)

BETA_D = np.array([0.45, 0.12, 0.08])
BETA_B = np.array([0.30, 0.10, 0.06])
B_INF = np.array([0.02, 0.09, 0.14])


def synthetic_layers(h=60, w=80, beta_d_slope=0.0, seed=1):
    """Layers of the formation model with constant β_B, B∞ and β_D (+ slope · z when asked)."""
    rng = np.random.default_rng(seed)
    z = rng.uniform(0.5, 15.0, size=(h, w))
    z[0, :5] = np.inf  # open water: no surface
    J = rng.uniform(0.05, 0.8, size=(h, w, 3))
    zz = np.where(np.isfinite(z), z, 0.0)[..., None]
    beta_d = BETA_D * (1 + beta_d_slope * zz)
    T = np.exp(-beta_d * zz)
    B = B_INF * (1 - np.exp(-BETA_B * zz))
    direct = J * T
    layers = {
        "image": direct + B, "clear": J, "direct": direct, "backscatter": B,
        "veiling": np.broadcast_to(B_INF, J.shape).copy(), "range": z,
        "beta_d": np.broadcast_to(beta_d, J.shape).copy(), "beta_b": np.broadcast_to(BETA_B, J.shape).copy(),
    }
    for name in ("beta_d", "beta_b"):
        layers[name][~np.isfinite(z)] = 0.0  # undefined: 0 (with a mask channel in seasim's image)
    return layers


def test_fits_recover_known_coefficients():
    result = seathru_fit.analyse(synthetic_layers())
    assert result["pixels"] == 60 * 80 - 5
    for c, name in enumerate("RGB"):
        ch = result["channels"][name]
        for fit in ("full", "layers"):
            assert ch[fit]["beta_d"] == pytest.approx(BETA_D[c], rel=2e-3), (name, fit)
            assert ch[fit]["beta_b"] == pytest.approx(BETA_B[c], rel=2e-3), (name, fit)
            assert ch[fit]["b_inf"] == pytest.approx(B_INF[c], rel=2e-3), (name, fit)
        assert ch["per_pixel_median"]["beta_d"] == pytest.approx(BETA_D[c])
        assert ch["per_pixel_median"]["veiling"] == pytest.approx(B_INF[c])


def test_range_table_shows_a_range_dependent_beta_d():
    # β_D growing with range, as Sea-thru finds in real water: the constant fit sits in the middle
    # and the per-pixel medians rise bin by bin.
    result = seathru_fit.analyse(synthetic_layers(beta_d_slope=0.05), bins=5)
    for name in "RGB":
        ch = result["channels"][name]
        medians = [m for _, _, m, _ in ch["beta_d_by_range"]]
        assert len(medians) == 5
        assert all(b > a for a, b in zip(medians, medians[1:]))
        assert medians[0] < ch["layers"]["beta_d"] < medians[-1]
    out = io.StringIO()
    seathru_fit.print_report(result, file=out)
    assert "per-pixel beta_D and beta_B (median) by range" in out.getvalue()


def test_too_few_surface_pixels_is_an_error():
    layers = synthetic_layers(h=2, w=3)
    layers["range"][:] = np.inf
    with pytest.raises(ValueError, match="fewer than 10 pixels"):
        seathru_fit.analyse(layers)


def _agreed_channels(layers):
    """The channels seasim's image.exr holds for these layers, in its order, and their pixels."""
    names, planes = list("RGB"), [layers["image"]]
    for name in seathru_fit.LAYERS:
        names += [f"{name}.{c}" for c in "RGB"]
        planes.append(layers[name])
        if name in ("beta_d", "beta_b"):
            names.append(f"{name}_mask")
            planes.append((layers[name][..., :1] > 0).astype(np.float64))
    names.append("range")
    planes.append(layers["range"][..., None])
    return names, np.concatenate(planes, axis=-1).astype(np.float32)


def test_reads_the_agreed_channel_names_from_exr(tmp_path):
    oiio = pytest.importorskip("OpenImageIO")
    layers = synthetic_layers(h=20, w=30)
    names, pixels = _agreed_channels(layers)
    path = str(tmp_path / "image.exr")
    out = oiio.ImageOutput.create(path)
    spec = oiio.ImageSpec(30, 20, len(names), "float")
    spec.channelnames = tuple(names)
    assert out.open(path, spec)
    out.write_image(pixels)
    out.close()
    read = seathru_fit.load_layers(path)
    assert np.allclose(read["backscatter"], layers["backscatter"], rtol=1e-6)
    assert read["beta_d_mask"][0, 0] == 0 and read["beta_d_mask"][5, 5] == 1
    result = seathru_fit.analyse(read)
    assert result["channels"]["G"]["layers"]["beta_d"] == pytest.approx(BETA_D[1], rel=2e-3)


def test_reads_exr_channels_by_name_and_the_right_way_up(tmp_path):
    # An EXR made by oiiotool with the agreed channel names, each channel a gradient with its own
    # corner values (channel i: i, 100 + i, 200 + i, 300 + i at top left, top right, bottom left,
    # bottom right). OpenEXR stores channels sorted by name; the reader must map them by name.
    if shutil.which("oiiotool") is None:
        pytest.skip("no oiiotool")
    names, _ = _agreed_channels(synthetic_layers(h=2, w=2))
    corner = lambda k: ",".join(str(k * 100 + i) for i in range(len(names)))
    path = str(tmp_path / "image.exr")
    subprocess.run(["oiiotool", "--pattern",
                    f"fill:topleft={corner(0)}:topright={corner(1)}:bottomleft={corner(2)}:bottomright={corner(3)}",
                    "30x20", str(len(names)), "--chnames", ",".join(names), "-d", "float", "-o", path], check=True)
    read = seathru_fit.load_layers(path)
    # Channel i reads f(x, y) + i, f the same bilinear gradient for all (R is channel 0).
    f = read["image"][..., 0]
    assert f[0, 0] < 50 and 50 < f[0, 29] < 150 and 150 < f[19, 0] < 250 and f[19, 29] > 250  # right way up
    for layer in ("image", "clear", "direct", "backscatter", "veiling", "beta_d", "beta_b"):
        first = names.index("R" if layer == "image" else f"{layer}.R")
        assert np.allclose(read[layer] - f[..., None], [first, first + 1, first + 2], atol=1e-3), layer
    assert np.allclose(read["range"] - f, names.index("range"), atol=1e-3)
    assert np.allclose(read["beta_d_mask"] - f, names.index("beta_d_mask"), atol=1e-3)
