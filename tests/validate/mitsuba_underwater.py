"""Opt-in validation (make validate): the underwater flat-bottom scene with a dielectric
surface, a uniform sky and the sun — seasim's all-orders path tracer (`seasim reference`) and the fast
models (`seasim render`: K_d multiple scattering, froxel single scattering; the thesis's eq. 4.7 and
underwater.model = "discrete_ordinates", the default) against Mitsuba 3's volpathmis.
Writes underwater_vs_mitsuba.md. The mapping of conventions is in water_scenes.py's docstring:
one band at 560 nm (grey), water a, b -> sigma_t = a + b, albedo = b / (a + b), HG g; a dielectric
rectangle at y = 0 with the water inside; a diffuse bottom; a `constant` sky; the sun as a
`directional` emitter along its refracted beam (irradiance E⊥ cos θ_z (1 - R) / cos θ_w) seen by shadow
rays through a surface that is transparent to them only; fov vertical; radiance/n² across the surface
(Mitsuba's dielectric and seasim both); `render` block-averaged from 4x4 pixel centres.

Scene: the issue's one-band case, a = 0.1, b = 0.3, g = 0.9 (1/m), flat bottom at 5 m of albedo 0.35,
sun 30° from the zenith, sky 0.05; camera 2 m above the bottom looking 2.9° down, 60° vertical fov,
64x36. Regions by each pixel centre's ray: the bottom nearer than 6 m, the bottom 6-15 m away, water
looking down (the bottom beyond 15 m, unseen through 6 attenuation lengths), water looking up.
A second view of the same scene (SNELL) looks 45° up through Snell's window; its regions are the
window's middle, its rim and the surface outside it (total reflection).
  python mitsuba_underwater.py SEASIM OUT_DIR [mitsuba seeds] [mitsuba spp] [seasim paths per pixel]
"""
import math
import os
import sys
import tempfile
import time

import numpy as np

import water_scenes as ws

SCENE = {"name": "uw_flat_bottom", "camera": (0.0, -3.0, 0.0), "look_at": (0.0, -3.5, -10.0), "fov": 60.0,
         "width": 64, "height": 36, "a": 0.1, "b": 0.3, "g": 0.9, "ior": 1.333, "bottom_depth": 5.0,
         "bottom_albedo": 0.35, "sun_zenith": 30.0, "sun_azimuth": 60.0, "sun_irradiance": 1.0,
         "sky_radiance": 0.05}


# The same water and light seen through Snell's window: the camera 3 m under the flat surface, looking up
# 45° (away from the sun's azimuth), so the window's edge (48.6° from the zenith at n = 1.333) crosses the
# frame. Inside the window the sky comes through the surface (n² (1 - R) L); outside it the surface
# reflects the water below totally.
SNELL = dict(SCENE, name="uw_snell_window", look_at=(0.0, -3.0 + 10.0 * math.sin(math.radians(45.0)),
                                                     -10.0 * math.cos(math.radians(45.0))))


def regions(s):
    d = ws.pixel_rays(s)
    dy = d[:, :, 1]
    depth_below = s["camera"][1] + s["bottom_depth"]  # camera height above the bottom
    t = np.where(dy < 0, depth_below / np.maximum(-dy, 1e-9), np.inf)
    return [("whole image", np.ones(dy.shape, bool)),
            ("bottom < 6 m", t < 6.0),
            ("bottom 6-15 m", (t >= 6.0) & (t < 15.0)),
            ("water looking down", (dy < 0) & (t >= 15.0)),
            ("water looking up", dy >= 0)]


def snell_regions(s):
    """By the pixel centre's ray: inside Snell's window (the refracted ray leaves the water) or outside it
    (total internal reflection), and the window's centre and rim by the angle from the zenith."""
    dy = ws.pixel_rays(s)[:, :, 1]
    edge = math.sqrt(1.0 - 1.0 / s["ior"] ** 2)  # cos of the critical angle from the zenith
    zenith = np.degrees(np.arccos(np.clip(dy, -1.0, 1.0)))
    critical = math.degrees(math.acos(edge))
    return [("whole image", np.ones(dy.shape, bool)),
            (f"window, < {critical - 10:.1f}° from the zenith", zenith < critical - 10),
            (f"window rim, {critical - 10:.1f}-{critical:.1f}°", (zenith >= critical - 10) & (zenith < critical)),
            ("outside the window (total reflection)", zenith >= critical)]


def compare(binary, s, region_fn, seeds, spp, paths, title):
    """Markdown lines for one scene: its description, the times, one row per region, the per-pixel z."""
    cache = os.path.dirname(os.path.abspath(binary))
    with tempfile.TemporaryDirectory() as tmp:
        toml, toml_ss = os.path.join(tmp, "uw.toml"), os.path.join(tmp, "uw_ss.toml")
        with open(toml, "w") as f:
            f.write(ws.scene_toml(s))
        with open(toml_ss, "w") as f:
            f.write(ws.scene_toml(s, ws.SS))
        t0 = time.time()
        ws.seasim(binary, ["reference", toml, "-o", os.path.join(tmp, "pt.exr"), "--steps", str(paths), "--seed", "1"],
                  cache)
        t_pt = time.time() - t0
        pt = ws.read_band(os.path.join(tmp, "pt.exr"))
        pt_se = ws.read_band(os.path.join(tmp, "pt.stderr.exr"))
        thesis = ["--set", 'underwater.model="thesis"']
        models = [("discrete ordinates (the default)", ["--set", 'underwater.model="discrete_ordinates"']),
                  ("thesis (K_d + froxels)", thesis),
                  ("thesis, no froxels", thesis + ["--set", "underwater.single_scattering=false"])]
        fast = []
        for _, extra in models:
            ws.seasim(binary, ["render", toml_ss, "-o", os.path.join(tmp, "r"), "--device", "pocl"] + extra, cache)
            fast.append(ws.read_band(os.path.join(tmp, "r", "image.exr"), ws.SS))
    t0 = time.time()
    runs = ws.render_mitsuba(s, seeds, spp)
    t_mts = time.time() - t0
    lines = [title,
             "",
             f"Scene: {s['width']}x{s['height']}, a = {s['a']}, b = {s['b']}, g = {s['g']}, n = {s['ior']}, bottom "
             f"{s['bottom_depth']} m (albedo {s['bottom_albedo']}), sun {s['sun_zenith']}° (E⊥ {s['sun_irradiance']}), "
             f"sky {s['sky_radiance']}; camera {s['camera']} -> "
             f"({', '.join(f'{x:.3g}' for x in s['look_at'])}), fov {s['fov']}°.",
             f"Mitsuba {ws.mi.__version__} (scalar_rgb): {seeds} seeds x {spp} spp (sky and sun images), {t_mts:.0f} s; seasim path tracer: "
             f"{paths} paths per pixel, seed 1, {t_pt:.1f} s (wall, with start-up). Machine: {os.uname().nodename}, "
             f"{os.cpu_count()} cores.",
             "",
             "| region | Mitsuba mean | path tracer / Mitsuba (± 2 se) | z | "
             + " | ".join(f"{name} / Mitsuba" for name, _ in models) + " |",
             "|---|---:|---:|---:|" + "---:|" * len(models)]
    for label, mask in region_fn(s):
        lines.append(ws.region_row(label, mask, runs, pt, pt_se, fast))
    lines += ["", f"Per-pixel z-score RMS (path tracer - Mitsuba over the combined standard error; about 1 "
              f"when they agree within noise, somewhat above 1 from Mitsuba's {seeds}-seed variance "
              f"estimate): {ws.pixel_z_rms(runs, pt, pt_se):.2f}", ""]
    print("\n".join(lines), flush=True)
    return lines


def main():
    binary, out = sys.argv[1], sys.argv[2]
    seeds = int(sys.argv[3]) if len(sys.argv) > 3 else 8
    spp = int(sys.argv[4]) if len(sys.argv) > 4 else 256
    paths = int(sys.argv[5]) if len(sys.argv) > 5 else 4096
    os.makedirs(out, exist_ok=True)
    lines = compare(binary, SCENE, regions, seeds, spp, paths,
                    "# Under water, flat bottom, dielectric surface, sky and sun: seasim / Mitsuba 3 (volpathmis)")
    lines += compare(binary, SNELL, snell_regions, seeds, spp, paths,
                     "## The same water looking up through Snell's window")
    with open(os.path.join(out, "underwater_vs_mitsuba.md"), "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
