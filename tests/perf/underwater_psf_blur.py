#!/usr/bin/env python3
"""underwater_psf_blur.py — how far a point-spread of the water would move the discrete-ordinates model's regions
(docs/journal/underwater_regions_3_*.md): a measurement on `seasim underwater-regions --dump DIR` files, not a model.

Delta-M counts the light scattered by a few degrees as unscattered: the model sends a hit's light on from
the same point, where the water spreads it over the pixels around (the dump's `forward` column is that
part, 1 - e^{-(c - c') S} of the hit's light). Here `forward` is taken off each pixel and put back blurred
by a Gaussian of sigma pixels, and the region ratios against the path tracer are printed per sigma.

The model does this itself (underwater.point_spread, the water_spread pass, with widths from
the phase and the distances): dump with `--set underwater.point_spread=false` to measure from the unspread
model.

Usage: tests/perf/underwater_psf_blur.py DUMP_DIR [--sigmas 0,1,2,3] [--width 64 --height 36]
Needs numpy. The dump's cases must be 64x36 unless --width/--height say otherwise.
"""
import argparse
import csv
import glob
import math
import os

import numpy as np

REGIONS = ["objects", "bottom_near", "bottom_far", "water_up", "water_down"]


def load(path, width, height):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if len(rows) != width * height:
        raise SystemExit(f"{path}: {len(rows)} pixels, expected {width}x{height} (--width, --height)")
    if "forward" not in rows[0]:
        raise SystemExit(f"{path}: no 'forward' column (not a dump of the discrete-ordinates model)")
    col = lambda k: np.array([float(r[k]) for r in rows]).reshape(height, width)
    region = np.array([r["region"] for r in rows]).reshape(height, width)
    return col("fast_improved"), col("reference"), col("forward"), region


def gaussian_blur(image, sigma):
    """Separable Gaussian of sigma pixels, edges replicated (sigma 0: the image)."""
    if sigma <= 0:
        return image
    r = int(math.ceil(3 * sigma))
    x = np.arange(-r, r + 1)
    k = np.exp(-0.5 * (x / sigma) ** 2)
    k /= k.sum()
    padded = np.pad(image, ((r, r), (r, r)), mode="edge")
    rows = np.apply_along_axis(lambda m: np.convolve(m, k, mode="valid"), 1, padded)
    return np.apply_along_axis(lambda m: np.convolve(m, k, mode="valid"), 0, rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dump_dir")
    ap.add_argument("--sigmas", default="0,1,2,3")
    ap.add_argument("--width", type=int, default=64)
    ap.add_argument("--height", type=int, default=36)
    args = ap.parse_args()
    sigmas = [float(s) for s in args.sigmas.split(",")]
    files = sorted(glob.glob(os.path.join(args.dump_dir, "*.csv")))
    files = [f for f in files if os.path.basename(f).startswith("a")]
    if not files:
        raise SystemExit(f"no dump files (a*.csv) in {args.dump_dir}")
    print("| case | forward share of objects | " + " | ".join(f"sigma {s:g} px" for s in sigmas) + " |")
    print("|---|---:|" + "---|" * len(sigmas))
    print("(each cell: objects / bottom near / bottom far / water up / water down, fast over path tracer;"
          " - where a region has fewer than 40 pixels)")
    for path in files:
        fast, ref, forward, region = load(path, args.width, args.height)
        objects = region == "objects"
        share = forward[objects].sum() / fast[objects].sum() if objects.sum() else float("nan")
        cells = []
        for s in sigmas:
            model = fast - forward + gaussian_blur(forward, s)
            ratios = []
            for name in REGIONS:
                sel = region == name
                ratios.append(f"{model[sel].sum() / ref[sel].sum():.3f}" if sel.sum() >= 40 else "-")
            cells.append("/".join(ratios))
        name = os.path.basename(path)[:-4]
        print(f"| {name} | {share:.2f} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
