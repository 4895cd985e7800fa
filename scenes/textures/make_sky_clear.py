#!/usr/bin/env python3
"""make_sky_clear.py — writes sky_clear.exr, the small latitude-longitude sky of scenes/wavy_sky_image.toml.

64 x 32 texels, linear RGB: a blue zenith fading to a pale horizon, a warm glow around azimuth 270 deg
(towards -z, where the example scenes put the sun), a few soft clouds from a fixed sum of sines, and a
dark lower half (the image's ground, never seen by the sea pass). Layout as scenes/README.md [sky]:
column u -> azimuth 360 u from +x towards +z, row v -> zenith angle 180 v, top row = zenith.

Pure Python (no numpy): writes a PFM, then converts it with OpenImageIO's oiiotool:
    python3 scenes/textures/make_sky_clear.py && oiiotool sky_clear.pfm -d half -o sky_clear.exr
(run in scenes/textures/).
"""
import math
import struct

W, H = 64, 32


def texel(x, y):
    phi = 2 * math.pi * (x + 0.5) / W          # azimuth from +x towards +z
    theta = math.pi * (y + 0.5) / H            # zenith angle
    if theta > math.pi / 2:                    # below the horizon: dark ground
        return (0.03, 0.035, 0.04)
    up = math.cos(theta)
    t = up ** 0.5                              # 0 at the horizon, 1 at the zenith
    zenith, horizon = (0.10, 0.25, 0.75), (0.75, 0.85, 0.95)
    rgb = [h + (z - h) * t for z, h in zip(zenith, horizon)]
    # Warm glow towards azimuth 270 deg, 40 deg up.
    sun = (math.sin(math.radians(50)) * math.cos(math.radians(270)), math.cos(math.radians(50)),
           math.sin(math.radians(50)) * math.sin(math.radians(270)))
    d = (math.sin(theta) * math.cos(phi), up, math.sin(theta) * math.sin(phi))
    cos_chi = sum(a * b for a, b in zip(d, sun))
    glow = 0.8 * math.exp(-3 * math.acos(max(-1.0, min(1.0, cos_chi))))
    rgb = [c + glow * w for c, w in zip(rgb, (1.0, 0.85, 0.6))]
    # Soft clouds: a fixed, periodic sum of sines (seamless in azimuth), only between 10 and 60 deg up.
    n = (math.sin(3 * phi + 1.3) * math.sin(5 * theta + 0.4) + 0.6 * math.sin(7 * phi - 0.7 + 9 * theta)
         + 0.4 * math.sin(11 * phi + 2.1) * math.cos(13 * theta))
    band = max(0.0, math.sin(math.pi * (math.pi / 2 - theta - math.radians(10)) / math.radians(50)))
    cloud = max(0.0, n - 0.5) * band
    return tuple(c * (1 - cloud) + 0.9 * cloud for c in rgb)


with open("sky_clear.pfm", "wb") as f:
    f.write(b"PF\n%d %d\n-1.0\n" % (W, H))
    for y in reversed(range(H)):               # PFM rows run bottom to top
        for x in range(W):
            f.write(struct.pack("<3f", *texel(x, y)))
