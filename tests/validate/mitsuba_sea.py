"""Opt-in validation (make validate): the sea seen from above — seasim's all-orders path
tracer with the camera above the surface (`seasim reference --all-orders`), paper 000's model
(`sea.model = "paper"`, single scattering eq. 5 and bottom eq. 9, with and without the second order
eq. 6-8) and `sea.model = "multiple"` (kernels/common/sea_multiple.h) against Mitsuba 3's volpathmis. "multiple" is the default.
Writes sea_vs_mitsuba.md. The mapping of conventions is in water_scenes.py's docstring: one band at
560 nm (grey), water a, b -> sigma_t = a + b, albedo = b / (a + b), HG g; a dielectric rectangle at y = 0
with the water inside (Mitsuba's dielectric and seasim both carry radiance/n² across it: the water's
light leaves as (1 - R)/n² times the radiance below, the sky is reflected with R); a diffuse bottom or
none; a `constant` sky; the sun as a `directional` emitter along its refracted beam (irradiance
E⊥ cos θ_z (1 - R) / cos θ_w) seen by shadow rays through a surface transparent to them only; fov
vertical; `render` block-averaged from 4x4 pixel centres.

Scenes: camera 5 m above the flat surface looking 45° down, 60° vertical fov (every pixel sees the
water, 15-75° from the nadir), 64x36; the sun 40° from the zenith behind the camera (no glint in view),
sky 0.05. Three waters: turbid (a = 0.1, b = 0.3, g = 0.9) over a bottom at 5 m (albedo 0.3) and deep,
and clear (a = 0.05, b = 0.05, g = 0.9) deep. Regions: the whole image, the far half (top rows) and the
near half (bottom rows).
  python mitsuba_sea.py SEASIM OUT_DIR [mitsuba seeds] [mitsuba spp] [seasim paths per pixel]
"""
import os
import sys
import tempfile
import time

import numpy as np

import water_scenes as ws

BASE = {"camera": (0.0, 5.0, 0.0), "look_at": (0.0, 0.0, -5.0), "fov": 60.0, "width": 64, "height": 36,
        "g": 0.9, "ior": 1.333, "bottom_albedo": 0.3, "sun_zenith": 40.0, "sun_azimuth": 90.0,
        "sun_irradiance": 1.0, "sky_radiance": 0.05}
CASES = [dict(BASE, name="sea_turbid_bottom5", a=0.1, b=0.3, bottom_depth=5.0),
         dict(BASE, name="sea_turbid_deep", a=0.1, b=0.3, bottom_depth=None),
         dict(BASE, name="sea_clear_deep", a=0.05, b=0.05, bottom_depth=None)]
MODELS = [("multiple (the default)", ["--set", 'sea.model="multiple"']),
          ("paper (eq. 5, 9)", ["--set", 'sea.model="paper"']),
          ("paper + 2nd order", ["--set", 'sea.model="paper"', "--set", "sea.second_order=true"])]


def main():
    binary, out = sys.argv[1], sys.argv[2]
    seeds = int(sys.argv[3]) if len(sys.argv) > 3 else 8
    spp = int(sys.argv[4]) if len(sys.argv) > 4 else 256
    paths = int(sys.argv[5]) if len(sys.argv) > 5 else 4096
    cache = os.path.dirname(os.path.abspath(binary))
    os.makedirs(out, exist_ok=True)
    lines = ["# The sea seen from above: seasim / Mitsuba 3 (volpathmis)", "",
             f"Camera {BASE['camera']} -> {BASE['look_at']}, fov {BASE['fov']}°, {BASE['width']}x{BASE['height']}; "
             f"sun {BASE['sun_zenith']}° (E⊥ {BASE['sun_irradiance']}) behind the camera, sky {BASE['sky_radiance']}, "
             f"g {BASE['g']}, n {BASE['ior']}. Mitsuba {ws.mi.__version__} (scalar_rgb): {seeds} seeds x {spp} spp (sky and sun images); seasim "
             f"path tracer (`reference --all-orders`): {paths} paths per pixel, seed 1. Machine: "
             f"{os.uname().nodename}, {os.cpu_count()} cores.", "",
             "| case | region | Mitsuba mean | path tracer / Mitsuba (± 2 se) | z | "
             + " | ".join(f"{name} / Mitsuba" for name, _ in MODELS) + " |",
             "|---|---|---:|---:|---:|" + "---:|" * len(MODELS)]
    notes = []
    for s in CASES:
        with tempfile.TemporaryDirectory() as tmp:
            toml, toml_ss = os.path.join(tmp, "sea.toml"), os.path.join(tmp, "sea_ss.toml")
            with open(toml, "w") as f:
                f.write(ws.scene_toml(s))
            with open(toml_ss, "w") as f:
                f.write(ws.scene_toml(s, ws.SS))
            t0 = time.time()
            ws.seasim(binary, ["reference", toml, "--all-orders", "-o", os.path.join(tmp, "pt.exr"),
                               "--steps", str(paths), "--seed", "1"], cache)
            t_pt = time.time() - t0
            pt = ws.read_band(os.path.join(tmp, "pt.exr"))
            pt_se = ws.read_band(os.path.join(tmp, "pt.stderr.exr"))
            fast = []
            for _, extra in MODELS:
                ws.seasim(binary, ["render", toml_ss, "-o", os.path.join(tmp, "r"), "--device", "pocl"] + extra, cache)
                fast.append(ws.read_band(os.path.join(tmp, "r", "image.exr"), ws.SS))
        t0 = time.time()
        runs = ws.render_mitsuba(s, seeds, spp)
        t_mts = time.time() - t0
        rows = np.arange(s["height"])[:, None] * np.ones((1, s["width"]))
        half = s["height"] // 2
        water = f"a {s['a']}, b {s['b']}, " + (f"bottom {s['bottom_depth']} m" if s["bottom_depth"] else "deep")
        for label, mask in (("whole image", rows >= 0), ("far half", rows < half), ("near half", rows >= half)):
            lines.append(ws.region_row(f"{water} | {label}", mask, runs, pt, pt_se, fast))
            print(lines[-1], flush=True)
        notes.append(f"- {s['name']}: per-pixel z-score RMS {ws.pixel_z_rms(runs, pt, pt_se):.2f}; Mitsuba "
                     f"{t_mts:.0f} s, seasim path tracer {t_pt:.1f} s (wall, with start-up).")
    lines += ["", "Per-pixel z-score RMS (path tracer - Mitsuba over the combined standard error; about 1 when "
              f"they agree within noise, somewhat above 1 from Mitsuba's {seeds}-seed variance estimate) and times:"]
    text = "\n".join(lines + notes) + "\n"
    print(text, flush=True)
    with open(os.path.join(out, "sea_vs_mitsuba.md"), "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
