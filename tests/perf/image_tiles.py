#!/usr/bin/env python3
"""image_tiles.py — fast renders against a reference by region: the whole image and a 3 x 3 grid of tiles
(r0 the top row, c0 the left column), each the ratio of the mean of R, G and B (OpenImageIO's oiiotool
--cut and --printstats; standard library otherwise), and the reference's relative standard error there
from its per-pixel errors (REFERENCE.stderr.exr beside it, as `seasim reference` writes them; pixels taken
as independent).
Usage: tests/perf/image_tiles.py reference.exr fast1.exr [fast2.exr ...] > table.csv
The ratio columns are named after each fast image's folder."""
import os
import re
import subprocess
import sys


def size(path):
    out = subprocess.run(["oiiotool", "--info", path], capture_output=True, text=True, check=True).stdout
    w, h = re.search(r"(\d+)\s*x\s*(\d+)", out).groups()
    return int(w), int(h)


def mean(path, roi=None, squared=False):
    cmd = ["oiiotool", path, "--ch", "R,G,B"] + (["--dup", "--mul"] if squared else []) + \
        (["--cut", roi] if roi else []) + ["--printstats"]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    values = re.search(r"Stats Avg:\s*(\S+)\s+(\S+)\s+(\S+)", out).groups()
    return sum(float(v) for v in values) / 3


def main():
    ref, fasts = sys.argv[1], sys.argv[2:]
    w, h = size(ref)
    regions = [("whole", None)] + [(f"r{r}c{c}", f"{w // 3}x{h // 3}+{c * (w // 3)}+{r * (h // 3)}")
                                   for r in range(3) for c in range(3)]
    stderr = ref[:-len(".exr")] + ".stderr.exr"
    print("region," + ",".join(f.rstrip("/").split("/")[-2] for f in fasts) + ",reference_rel_se")
    for name, roi in regions:
        r = mean(ref, roi)
        # The region mean's error: sqrt(mean of se^2 / pixels), per channel averaged.
        pixels = (w * h) if roi is None else (w // 3) * (h // 3)
        se = (mean(stderr, roi, squared=True) / pixels) ** 0.5 / r if os.path.exists(stderr) else float("nan")
        print(name + "," + ",".join(f"{mean(f, roi) / r:.3f}" for f in fasts) + f",{se:.4f}")


if __name__ == "__main__":
    main()
