#!/usr/bin/env python3
"""seathru_fit.py — fit the underwater image formation model of Akkaynak and Treibitz ("A revised
underwater image formation model", CVPR 2018; "Sea-thru", CVPR 2019), per colour channel c,

    I_c = J_c · exp(−β_D,c · z) + B∞,c · (1 − exp(−β_B,c · z)),

to one seasim image's layers, and compare the constants it finds with the per-pixel effective
coefficients seasim writes (docs/datasets.md). The model's coefficients are constants per image;
seasim's `beta_d` and `beta_b` layers are what each pixel's light really met, so the table by range
shows how far a constant is from the truth at each distance (Sea-thru's point: β_D varies with range).

    python3 docs/examples/seathru_fit.py results/reef_dataset/reef_s0000/image.exr [--bins 6] [--json fit.json]

The image needs the layers (scene key outputs.layers, or `seasim run ... --output`):
    clear direct backscatter veiling beta_d beta_b range
image.exr then holds channels R, G, B (the image I) and <layer>.R/.G/.B (range: one channel).
beta_d and beta_b come with masks (beta_d_mask, beta_b_mask: 1 where defined), used when present.
Needs NumPy, and OpenImageIO's Python module (pip install OpenImageIO) or its oiiotool command to
read the EXR.

The image I is everything the camera saw: direct + forward + backscatter (+ lamps). The formation
model has no forward-scattering term, so the fit of I folds the point spread into its constants;
the fit of the layers separates them.

Three fits per channel, on the pixels whose ray ends on a surface (finite range > 0, J > 0):
  full        β_D, β_B, B∞ from I, J and z alone (what a method that knows J and z could recover):
              least squares by Levenberg-Marquardt from the best points of a log grid (fit_full).
  direct      β_D from the direct layer: least squares of ln(direct/clear) = −β_D z through 0.
  backscatter β_B, B∞ from the backscatter layer: B = B∞ (1 − exp(−β_B z)), searched like `full`.
and the per-pixel layers' medians (beta_d, beta_b where defined; veiling over those pixels).
"""
from __future__ import annotations

import argparse
import json
import sys
from typing import Dict, Optional

import numpy as np

RGB = ("R", "G", "B")
LAYERS = ("clear", "direct", "backscatter", "veiling", "beta_d", "beta_b")
MAX_PIXELS = 4000  # pixels a search uses (an even subsample): enough for three constants


def _read_exr(path: str):
    """(channel names, pixels (H, W, C) float64): through OpenImageIO's Python module, else through
    the oiiotool command (the image rewritten as a float FITS file, which NumPy reads directly)."""
    try:
        import OpenImageIO as oiio
    except ImportError:
        oiio = None
    if oiio is not None:
        inp = oiio.ImageInput.open(path)
        if inp is None:
            sys.exit(f"seathru_fit.py: cannot open {path}: {oiio.geterror()}")
        names = list(inp.spec().channelnames)
        pixels = np.asarray(inp.read_image(format="float"), dtype=np.float64)
        inp.close()
        return names, pixels
    import shutil
    import subprocess
    import tempfile
    if shutil.which("oiiotool") is None:
        sys.exit("seathru_fit.py: reading EXR needs OpenImageIO's Python module (pip install OpenImageIO) "
                 "or its oiiotool command (apt install openimageio-tools)")
    info = subprocess.run(["oiiotool", "--info", "-v", path], capture_output=True, text=True)
    listed = [line.split(":", 1)[1] for line in info.stdout.splitlines() if "channel list:" in line]
    if info.returncode != 0 or not listed:
        sys.exit(f"seathru_fit.py: cannot read {path}: {(info.stdout + info.stderr).strip()}")
    names = [n.strip() for n in listed[0].split(",")]
    with tempfile.TemporaryDirectory() as tmp:
        fits = f"{tmp}/image.fits"
        subprocess.run(["oiiotool", path, "-d", "float", "-o", fits], check=True, capture_output=True)
        data = open(fits, "rb").read()
    # FITS: 80-character header cards in 2880-byte blocks up to END, then big-endian float32 data,
    # NAXIS1 = channels, NAXIS2 = width, NAXIS3 = height, bottom row first. OpenImageIO 2.4 writes
    # its data unpadded at the very end of the file, after a header padded to a length that varies
    # (3264 and 5760 bytes seen), so the data is read as the file's tail.
    cards, offset_end = {}, 0
    while offset_end + 80 <= len(data):
        card = data[offset_end:offset_end + 80].decode("ascii")
        offset_end += 80
        if card.startswith("END"):
            break
        if "=" in card[:10]:
            cards[card[:8].strip()] = card[10:].split("/")[0].strip()
    c, w, h = (int(cards[k]) for k in ("NAXIS1", "NAXIS2", "NAXIS3"))
    size = c * w * h * 4
    offset = len(data) - size
    if offset < offset_end:
        sys.exit(f"seathru_fit.py: oiiotool wrote a FITS file shorter than its image ({path})")
    pixels = np.frombuffer(data, dtype=">f4", count=c * w * h, offset=offset).reshape(h, w, c)
    return names, np.flipud(pixels).astype(np.float64)


def load_layers(path: str) -> Dict[str, np.ndarray]:
    """image.exr's channels as float64 arrays: 'image' and each layer (H, W, 3), 'range' (H, W),
    and '<layer>_mask' (H, W) where the image has one (beta_d, beta_b: 1 where defined)."""
    names, pixels = _read_exr(path)
    channel = {n: i for i, n in enumerate(names)}

    def rgb(prefix: str) -> np.ndarray:
        keys = [f"{prefix}{c}" for c in RGB]
        missing = [k for k in keys if k not in channel]
        if missing:
            sys.exit(f"seathru_fit.py: {path} has no channel {missing[0]}; render with outputs.layers = "
                     f"{list(LAYERS) + ['range']} (channels there: {', '.join(names)})")
        return pixels[..., [channel[k] for k in keys]]

    layers = {"image": rgb("")}
    for name in LAYERS:
        layers[name] = rgb(name + ".")
        if f"{name}_mask" in channel:
            layers[f"{name}_mask"] = pixels[..., channel[f"{name}_mask"]]
    if "range" not in channel:
        sys.exit(f"seathru_fit.py: {path} has no 'range' channel; add range to outputs.layers")
    layers["range"] = pixels[..., channel["range"]]
    return layers


def _subsample(mask: np.ndarray) -> np.ndarray:
    idx = np.flatnonzero(mask.ravel())
    if idx.size > MAX_PIXELS:
        idx = idx[np.linspace(0, idx.size - 1, MAX_PIXELS).astype(np.int64)]
    return idx


def _grid_search(residual_sse, lo: float = 1e-4, hi: float = 20.0, dims: int = 2, n: int = 48):
    """Minimises residual_sse(params) over a log grid in `dims` positive parameters, refined four
    times within ±4 steps of the best point (a grid step of 3e-4 relative at the end)."""
    centre = np.full(dims, np.sqrt(lo * hi))
    span = np.log(hi / lo) / 2
    best = None
    for _ in range(5):
        axes = [np.exp(np.linspace(np.log(c) - span, np.log(c) + span, n)) for c in centre]
        mesh = np.meshgrid(*axes, indexing="ij")
        cand = np.stack([m.ravel() for m in mesh], axis=1)
        sse = np.array([residual_sse(p) for p in cand])
        best = cand[int(np.argmin(sse))]
        centre, span = best, span * 8 / n  # ±4 grid steps of this pass
    return best


def _levenberg_marquardt(residual, jacobian, p, iterations: int = 200):
    """Damped Gauss-Newton from p on the residual vector; parameters kept positive."""
    lam = 1e-3
    r = residual(p)
    cost = float(r @ r)
    for _ in range(iterations):
        Jm = jacobian(p)
        A, g = Jm.T @ Jm, Jm.T @ r
        step = np.linalg.solve(A + lam * np.diag(np.diag(A) + 1e-30), -g)
        trial = np.maximum(p + step, 1e-9)
        rt = residual(trial)
        ct = float(rt @ rt)
        if ct < cost:
            p, r, lam = trial, rt, lam / 3
            done = cost - ct <= 1e-15 * cost
            cost = ct
            if done:
                break
        else:
            lam *= 4
            if lam > 1e12:
                break
    return p, cost


def fit_full(I: np.ndarray, J: np.ndarray, z: np.ndarray):
    """β_D, β_B, B∞ of one channel from I, J and z (1-D arrays of the same pixels).

    The model has a degenerate valley (β_B → 0, B∞ → ∞ with their product fixed: a backscatter
    linear in z), so a coarse log grid over (β_D, β_B), with B∞ in closed form for each, gives
    starting points, and Levenberg-Marquardt polishes the best few; the lowest residual wins."""
    def b_inf(bd, bb):
        g = 1 - np.exp(-bb * z)
        r = I - J * np.exp(-bd * z)
        return max(float(g @ r) / max(float(g @ g), 1e-300), 0.0)

    def residual(p):
        bd, bb, binf = p
        return I - J * np.exp(-bd * z) - binf * (1 - np.exp(-bb * z))

    def jacobian(p):
        bd, bb, binf = p
        return np.stack([J * z * np.exp(-bd * z), -binf * z * np.exp(-bb * z), -(1 - np.exp(-bb * z))], axis=1)

    axis = np.exp(np.linspace(np.log(1e-3), np.log(10.0), 32))
    starts = []
    for bd in axis:
        for bb in axis:
            binf = b_inf(bd, bb)
            r = residual((bd, bb, binf))
            starts.append((float(r @ r), bd, bb, binf))
    starts.sort()
    best = None
    for _, bd, bb, binf in starts[:6]:
        p, cost = _levenberg_marquardt(residual, jacobian, np.array([bd, bb, binf]))
        if best is None or cost < best[1]:
            best = (p, cost)
    bd, bb, binf = best[0]
    return float(bd), float(bb), float(binf)


def fit_direct(direct: np.ndarray, clear: np.ndarray, z: np.ndarray) -> float:
    """β_D of one channel: least squares of ln(direct / clear) = −β_D z through the origin."""
    ok = (direct > 0) & (clear > 0)
    t = np.log(direct[ok] / clear[ok])
    return float(-(z[ok] @ t) / (z[ok] @ z[ok]))


def fit_backscatter(B: np.ndarray, z: np.ndarray):
    """β_B, B∞ of one channel: B = B∞ (1 − exp(−β_B z))."""
    def b_inf(bb):
        g = 1 - np.exp(-bb * z)
        return float(g @ B) / max(float(g @ g), 1e-300)

    def sse(p):
        g = 1 - np.exp(-p[0] * z)
        return float(np.sum((B - b_inf(p[0]) * g) ** 2))

    (bb,) = _grid_search(sse, dims=1, n=400)
    return float(bb), b_inf(bb)


def range_profile(z: np.ndarray, values: np.ndarray, edges: np.ndarray):
    """Median of `values` in the range bins between `edges`: [(z_lo, z_hi, median, count)]."""
    rows = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        sel = (z >= lo) & (z <= hi)
        if sel.any():
            rows.append((float(lo), float(hi), float(np.median(values[sel])), int(sel.sum())))
    return rows


def analyse(layers: Dict[str, np.ndarray], bins: int = 6, min_transmission: float = 1e-4) -> dict:
    """The three fits and the per-pixel medians for each channel, and β_D, β_B by range, over the
    pixels that see a surface through measurable water: finite range > 0, J > 0, and direct / J of
    at least min_transmission in every channel (far surfaces, e.g. the sea surface at grazing
    angles hundreds of metres off, would otherwise dominate the least squares with a signal that
    single precision no longer holds)."""
    z = layers["range"]
    J = layers["clear"]
    with np.errstate(divide="ignore", invalid="ignore"):
        seen = np.all(layers["direct"] >= min_transmission * J, axis=-1)
    surface = np.isfinite(z) & (z > 0) & np.all(J > 0, axis=-1) & seen
    if surface.sum() < 10:
        raise ValueError("fewer than 10 pixels see a surface (finite range, clear > 0, direct/clear >= "
                         f"{min_transmission:g}): nothing to fit")
    idx = _subsample(surface)
    flat = {k: v.reshape(-1, 3) if v.ndim == 3 else v.reshape(-1) for k, v in layers.items()}
    zs = flat["range"][idx]
    z_all = flat["range"][surface.ravel()]
    edges = np.quantile(z_all, np.linspace(0, 1, bins + 1))  # bins of equal pixel count
    out = {"pixels": int(surface.sum()), "min_transmission": min_transmission, "channels": {}}
    for c, name in enumerate(RGB):
        I, Jc = flat["image"][idx, c], flat["clear"][idx, c]
        bd, bb, binf = fit_full(I, Jc, zs)
        bd_direct = fit_direct(flat["direct"][idx, c], Jc, zs)
        bb_back, binf_back = fit_backscatter(flat["backscatter"][idx, c], zs)
        pix_bd = flat["beta_d"][surface.ravel(), c]
        pix_bb = flat["beta_b"][surface.ravel(), c]
        # Undefined pixels are written as 0 with mask 0 (<layer>_mask); without masks, 0 means undefined.
        d_ok = flat["beta_d_mask"][surface.ravel()] > 0.5 if "beta_d_mask" in flat else pix_bd > 0
        b_ok = flat["beta_b_mask"][surface.ravel()] > 0.5 if "beta_b_mask" in flat else pix_bb > 0
        out["channels"][name] = {
            "full": {"beta_d": bd, "beta_b": bb, "b_inf": binf},
            "layers": {"beta_d": bd_direct, "beta_b": bb_back, "b_inf": binf_back},
            "per_pixel_median": {
                "beta_d": float(np.median(pix_bd[d_ok])) if d_ok.any() else None,
                "beta_b": float(np.median(pix_bb[b_ok])) if b_ok.any() else None,
                "veiling": float(np.median(flat["veiling"][surface.ravel(), c])),
            },
            "beta_d_by_range": range_profile(z_all[d_ok], pix_bd[d_ok], edges) if d_ok.any() else [],
            "beta_b_by_range": range_profile(z_all[b_ok], pix_bb[b_ok], edges) if b_ok.any() else [],
        }
    return out


def _fmt(v: Optional[float]) -> str:
    return "     -" if v is None else f"{v:8.4f}"


def print_report(result: dict, file=sys.stdout) -> None:
    print(f"{result['pixels']} pixels see a surface with direct/clear >= {result['min_transmission']:g}\n", file=file)
    print("channel  what                   beta_D    beta_B      B_inf", file=file)
    for name, ch in result["channels"].items():
        rows = [("fit of I to J, z", ch["full"]["beta_d"], ch["full"]["beta_b"], ch["full"]["b_inf"]),
                ("fit of the layers", ch["layers"]["beta_d"], ch["layers"]["beta_b"], ch["layers"]["b_inf"]),
                ("per-pixel median", ch["per_pixel_median"]["beta_d"], ch["per_pixel_median"]["beta_b"],
                 ch["per_pixel_median"]["veiling"])]
        for what, a, b, c in rows:
            print(f"{name:7}  {what:20} {_fmt(a)}  {_fmt(b)}  {_fmt(c)}", file=file)
    print("\nper-pixel beta_D and beta_B (median) by range, against the constant fitted to I:", file=file)
    for name, ch in result["channels"].items():
        print(f"{name}: range m        beta_D  (fit {ch['full']['beta_d']:.4f})    beta_B  (fit {ch['full']['beta_b']:.4f})",
              file=file)
        by_b = {(lo, hi): m for lo, hi, m, _ in ch["beta_b_by_range"]}
        for lo, hi, m, n in ch["beta_d_by_range"]:
            print(f"   {lo:6.2f} - {hi:6.2f}  {m:8.4f}                 {_fmt(by_b.get((lo, hi)))}   ({n} px)", file=file)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("image", help="image.exr with the layers clear, direct, backscatter, veiling, beta_d, beta_b, range")
    ap.add_argument("--bins", type=int, default=6, help="range bins of the per-pixel table (default 6)")
    ap.add_argument("--min-transmission", type=float, default=1e-4,
                    help="leave out pixels whose direct/clear is below this in any channel (default 1e-4)")
    ap.add_argument("--json", help="also write the numbers to this JSON file")
    args = ap.parse_args(argv)
    result = analyse(load_layers(args.image), args.bins, args.min_transmission)
    print_report(result)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
