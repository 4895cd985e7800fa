"""Opt-in validation (make validate): a spotlight under water — seasim's all-orders path tracer
(`seasim reference`, lamps by equiangular sampling in the cone combined with next-event estimation) and
the fast lamp pass (`seasim render`, each quality.lamps_model by name: paper 001's planes in the water
delta-M scaled, with the orders of multiple scattering (the default), and plain) against Mitsuba 3's
volpathmis. Writes lamps_vs_mitsuba.md.

Mapping (water_scenes.py's docstring for the water, bottom, camera and pixel filter): one grey band at
560 nm, sensor "identity"; no sun (irradiance 0) and no sky (radiance 0), so the image is the lamp's
light alone. The lamp is a point with a hard-edged cone (falloff_deg = 0): Mitsuba's `spot` with
cutoff_angle = beam_width = the cone's half angle and intensity I (W/sr: seasim's intensity is per nm
at 560 nm, and the band is 1 nm wide there). Both renderers see the lamp only by next-event estimation
(a point light). Neither draws the lamp's light mirrored by the surface before it scatters: Mitsuba
cannot reach a point light through a smooth dielectric, seasim leaves it out.

Regions by each pixel centre's ray: the bottom inside the lamp's cone (lit bottom), water whose ray
crosses the cone before it ends (water in the beam), and everything else (water and bottom outside it).
  python mitsuba_lamps.py SEASIM OUT_DIR [mitsuba seeds] [mitsuba spp] [seasim paths per pixel]
"""
import math
import os
import sys
import tempfile
import time

import numpy as np

import water_scenes as ws

LAMP = {"position": (0.4, -4.0, -0.3), "direction": (-0.05, -0.5, -1.0), "cone_deg": 20.0, "intensity": 10.0}
SCENE = {"name": "uw_lamp", "camera": (0.0, -4.0, 0.0), "look_at": (0.0, -6.0, -4.0), "fov": 60.0,
         "width": 48, "height": 27, "a": 0.1, "b": 0.3, "g": 0.5, "ior": 1.333, "bottom_depth": 7.0,
         "bottom_albedo": 0.5, "sun_zenith": 30.0, "sun_azimuth": 60.0, "sun_irradiance": 0.0,
         "sky_radiance": 0.0}


def unit(v):
    v = np.array(v, float)
    return v / np.linalg.norm(v)


def lamp_toml(lamp):
    return [f"[[spotlights]]", f"position = {list(lamp['position'])}", f"direction = {list(lamp['direction'])}",
            f"cone_deg = {lamp['cone_deg']}", "falloff_deg = 0.0", f"intensity = {lamp['intensity']}",
            "[underwater]", 'caustics = "none"']


def mitsuba_lamp_scene(s, lamp, seed, spp):
    """water_scenes' sky scene (plain dielectric surface, the water, the bottom) with the spot in it."""
    import mitsuba as mi
    T = mi.ScalarTransform4f
    c = s["a"] + s["b"]
    pos = np.array(lamp["position"], float)
    axis = unit(lamp["direction"])
    up = [0, 1, 0] if abs(axis[1]) < 0.9 else [1, 0, 0]
    scene = {"type": "scene", "integrator": {"type": "volpathmis", "max_depth": 1000},
             "water": {"type": "homogeneous", "sigma_t": c, "albedo": s["b"] / c,
                       "phase": {"type": "hg", "g": s["g"]} if s["g"] != 0 else {"type": "isotropic"}},
             "sensor": {"type": "perspective", "fov": s["fov"], "fov_axis": "y",
                        "to_world": T().look_at(origin=list(s["camera"]), target=list(s["look_at"]), up=[0, 1, 0]),
                        "film": {"type": "hdrfilm", "width": s["width"], "height": s["height"],
                                 "rfilter": {"type": "box"}, "pixel_format": "rgb"},
                        "sampler": {"type": "independent", "sample_count": spp, "seed": seed},
                        "medium": {"type": "ref", "id": "water"}},
             "surface": {"type": "rectangle", "to_world": T().rotate([1, 0, 0], -90).scale([1000, 1000, 1]),
                         "bsdf": {"type": "dielectric", "int_ior": s["ior"], "ext_ior": 1.0},
                         "interior": {"type": "ref", "id": "water"}},
             "bottom": {"type": "rectangle",
                        "to_world": T().translate([0, -s["bottom_depth"], 0]).rotate([1, 0, 0], -90).scale([1000, 1000, 1]),
                        "bsdf": {"type": "diffuse", "reflectance": s["bottom_albedo"]},
                        "exterior": {"type": "ref", "id": "water"}},
             "lamp": {"type": "spot", "intensity": lamp["intensity"], "cutoff_angle": lamp["cone_deg"],
                      "beam_width": lamp["cone_deg"], "medium": {"type": "ref", "id": "water"},
                      "to_world": T().look_at(origin=list(pos), target=list(pos + axis), up=up)}}
    return mi.load_dict(scene)


def render_mitsuba(s, lamp, seeds, spp):
    import mitsuba as mi
    return [np.array(mi.render(mitsuba_lamp_scene(s, lamp, (k + 1) * ws.SEED_STRIDE, spp)), dtype=np.float64)[:, :, 0]
            for k in range(seeds)]


def regions(s, lamp):
    d = ws.pixel_rays(s)
    eye = np.array(s["camera"], float)
    pos, axis = np.array(lamp["position"], float), unit(lamp["direction"])
    cos_cone = math.cos(math.radians(lamp["cone_deg"]))
    dy = d[:, :, 1]
    t_hit = np.where(dy < 0, (s["bottom_depth"] + eye[1]) / np.maximum(-dy, 1e-9), 50.0)
    bottom = dy < 0

    def inside(p):
        q = p - pos
        n = np.linalg.norm(q, axis=-1)
        return (q @ axis) > cos_cone * n

    lit = bottom & inside(eye + t_hit[:, :, None] * d)
    beam = np.zeros(dy.shape, bool)
    for f in np.linspace(0.0, 1.0, 400, endpoint=False) + 0.5 / 400:
        beam |= inside(eye + (f * np.minimum(t_hit, 50.0))[:, :, None] * d)
    beam &= ~lit
    return [("whole image", np.ones(dy.shape, bool)), ("lit bottom", lit), ("water in the beam", beam),
            ("outside the beam", ~lit & ~beam)]


def compare(binary, s, lamp, seeds, spp, paths):
    cache = os.path.dirname(os.path.abspath(binary))
    s = dict(s, toml_extra=lamp_toml(lamp))
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
        # Each lamps model pinned by name (orders, the default, adds the glow outside the cone).
        models = [("fast, delta-M", ["--set", 'quality.lamps_model="delta_m"']),
                  ("fast, orders", ["--set", 'quality.lamps_model="orders"']),
                  ("fast, plain 001", ["--set", 'quality.lamps_model="single"'])]
        fast = []
        for _, extra in models:
            ws.seasim(binary, ["render", toml_ss, "-o", os.path.join(tmp, "r"), "--device", "pocl"] + extra, cache)
            fast.append(ws.read_band(os.path.join(tmp, "r", "image.exr"), ws.SS))
    t0 = time.time()
    runs = render_mitsuba(s, lamp, seeds, spp)
    t_mts = time.time() - t0
    import mitsuba as mi
    lines = [f"## a = {s['a']}, b = {s['b']}, g = {s['g']}",
             "",
             f"Scene: {s['width']}x{s['height']}, bottom {s['bottom_depth']} m (albedo {s['bottom_albedo']}), lamp at "
             f"{lamp['position']} towards {lamp['direction']}, hard {lamp['cone_deg']}° cone, I = {lamp['intensity']}; "
             f"camera {s['camera']} -> {s['look_at']}, fov {s['fov']}°. Mitsuba {mi.__version__} (scalar_rgb, volpathmis): "
             f"{seeds} seeds x {spp} spp, {t_mts:.0f} s; seasim path tracer: {paths} paths per pixel, {t_pt:.1f} s "
             f"(wall). Machine: {os.uname().nodename}, {os.cpu_count()} cores.",
             "",
             "| region | Mitsuba mean | path tracer / Mitsuba (± 2 se) | z | "
             + " | ".join(f"{name} / Mitsuba" for name, _ in models) + " |",
             "|---|---:|---:|---:|" + "---:|" * len(models)]
    for label, mask in regions(s, lamp):
        lines.append(ws.region_row(label, mask, runs, pt, pt_se, fast))
    lines += ["", f"Per-pixel z-score RMS: {ws.pixel_z_rms(runs, pt, pt_se):.2f}", ""]
    print("\n".join(lines), flush=True)
    return lines


def main():
    binary, out = sys.argv[1], sys.argv[2]
    seeds = int(sys.argv[3]) if len(sys.argv) > 3 else 8
    spp = int(sys.argv[4]) if len(sys.argv) > 4 else 256
    paths = int(sys.argv[5]) if len(sys.argv) > 5 else 2048
    os.makedirs(out, exist_ok=True)
    lines = ["# A spotlight under water: seasim / Mitsuba 3 (volpathmis), all orders", ""]
    for water in ({"a": 0.1, "b": 0.3, "g": 0.5}, {"a": 0.1, "b": 0.3, "g": 0.9}, {"a": 0.1, "b": 0.8, "g": 0.9}):
        lines += compare(binary, dict(SCENE, **water), LAMP, seeds, spp, paths)
    with open(os.path.join(out, "lamps_vs_mitsuba.md"), "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
