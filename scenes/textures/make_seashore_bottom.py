#!/usr/bin/env python3
"""make_seashore_bottom.py — writes seashore_bottom.exr, the height-field sea floor of scenes/seashore.toml.

128 x 128 grey texels, linear float, grey = (40 - depth) / 39: 1 -> 1 m deep, 0 -> 40 m deep
(scenes/README.md [bottom] with min_depth = 1, max_depth = 40). Pixel column i runs along +x, row j
along +z, the top row at z = -extent/2 (the far side for the camera of seashore.toml, which looks
along -z from the shallow edge). The floor (extent 200 m):
  - a shelf sloping away from the camera, 1 m at the near edge (z = +100 m) to 40 m at the far edge,
    steepening offshore (depth ~ s^1.6 of the distance s from the near edge);
  - relief: sand ripples (0.25 m, 9 m crests), three reef mounds rising 3–8 m, and a gully
    running out to sea, all smooth so that the bilinear floor has no cliffs;
  - clamped to [1, 40] m.
Pure Python (no numpy): writes a PFM (bottom row first, as the format says), converted by
OpenImageIO's oiiotool:
    python3 scenes/textures/make_seashore_bottom.py && \
    oiiotool scenes/textures/seashore_bottom.pfm -d float -o scenes/textures/seashore_bottom.exr
(run from the repository root); the .pfm can be deleted afterwards.
"""
import math
import os
import struct

N = 128
EXTENT = 200.0
MIN_DEPTH, MAX_DEPTH = 1.0, 40.0


def depth(x, z):
    s = (EXTENT / 2 - z) / EXTENT                   # 0 at the near (shallow) edge, 1 at the far edge
    d = MIN_DEPTH + (MAX_DEPTH - MIN_DEPTH) * s ** 1.6
    d += 0.25 * math.sin(2 * math.pi * (z + 0.3 * x) / 9.0) * min(1.0, 4 * s)   # ripples offshore of the beach
    for cx, cz, r, h in ((-35.0, 40.0, 14.0, 3.0), (30.0, 5.0, 18.0, 6.0), (-10.0, -45.0, 22.0, 8.0)):
        d -= h * math.exp(-((x - cx) ** 2 + (z - cz) ** 2) / (2 * r * r))      # reef mounds
    gully = math.exp(-((x - 12.0 - 0.15 * z) ** 2) / (2 * 6.0 ** 2))           # a channel out to sea
    d += 2.5 * gully * min(1.0, 3 * s)
    return min(MAX_DEPTH, max(MIN_DEPTH, d))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    rows = []
    for j in range(N):
        z = -EXTENT / 2 + j * EXTENT / (N - 1)
        rows.append([(MAX_DEPTH - depth(-EXTENT / 2 + i * EXTENT / (N - 1), z)) / (MAX_DEPTH - MIN_DEPTH)
                     for i in range(N)])
    with open(os.path.join(here, "seashore_bottom.pfm"), "wb") as f:
        f.write(b"Pf\n%d %d\n-1.0\n" % (N, N))     # grey, little-endian
        for row in reversed(rows):                 # PFM stores the bottom row first
            f.write(struct.pack("<%df" % N, *row))


if __name__ == "__main__":
    main()
