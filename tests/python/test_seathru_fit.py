"""The docs' Sea-thru fit (docs/examples/seathru_fit.py) on synthetic layers made here with known
coefficients: the fits recover them, the per-pixel table shows a β_D that varies with range, and
an EXR with the agreed channel names (<layer>.R/.G/.B, range) is read back when OpenImageIO's Python
module is there. Needs NumPy only (not the seasim module): `pytest --noconftest` runs it alone."""
from __future__ import annotations

import importlib.util
import io
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


def test_reads_the_agreed_channel_names_from_exr(tmp_path):
    oiio = pytest.importorskip("OpenImageIO")
    layers = synthetic_layers(h=20, w=30)
    names, planes = list("RGB"), [layers["image"]]
    for name in seathru_fit.LAYERS:
        names += [f"{name}.{c}" for c in "RGB"]
        planes.append(layers[name])
    names.append("range")
    planes.append(layers["range"][..., None])
    pixels = np.concatenate(planes, axis=-1).astype(np.float32)
    path = str(tmp_path / "image.exr")
    out = oiio.ImageOutput.create(path)
    spec = oiio.ImageSpec(30, 20, len(names), "float")
    spec.channelnames = tuple(names)
    assert out.open(path, spec)
    out.write_image(pixels)
    out.close()
    read = seathru_fit.load_layers(path)
    assert np.allclose(read["backscatter"], layers["backscatter"], rtol=1e-6)
    result = seathru_fit.analyse(read)
    assert result["channels"]["G"]["layers"]["beta_d"] == pytest.approx(BETA_D[1], rel=2e-3)
