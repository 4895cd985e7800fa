"""An experiment on the spotlight scenes with a sphere and a floor in mitsuba_shafts.py: they
read 0.8-1.2 % low against Mitsuba with seasim's reference at 4x4 pixel centres per pixel, while the
open-air case agrees (results/validation/README.md). Which term is it? The scene is split into cheap,
low-noise variants, each rendered by Mitsuba (volpath, max_depth = 2) and by seasim's reference at SS x SS
pixel centres per pixel:
  surfaces only   no medium (ρ = 0): the lit sphere and floor are direct light alone. A third evaluation,
                  independent of both renderers, is computed here in numpy (double): the spot's
                  irradiance I cos θ / r² inside the hard cone, the sphere's shadow, albedo/π, averaged
                  over SS x SS pixel centres (box filter) for SS up to 64.
  airlight only   the medium, with the sphere and the floor black (albedo 0): the shaft and the sphere's
                  shadow volume in it, no surface light.
  full scene      sphere_iso of mitsuba_shafts.py.
Regions: the whole image and three bands of 16 rows (top: airlight near the lamp; middle: the sphere,
the shaft and the lit floor's far part; bottom: the rest of the lit floor). Mitsuba's noise is the spread
of independent seeds (k x SEED_STRIDE); ± is 2 standard errors of its mean. Writes shafts_surfaces.md.
  python shafts_surfaces.py SEASIM OUT_DIR [mitsuba seeds] [mitsuba spp]
"""
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import mitsuba_shafts as ms

LUM = np.array([0.2126, 0.7152, 0.0722])
BASE = {"sphere": True, "rho": 0.04, "kappa": 1.25, "g": 0.0, "cone": 24.0}
VARIANTS = [
    ("surfaces only (ρ = 0)", dict(BASE, name="surfaces", rho=0.0)),
    ("airlight only (black sphere and floor)", dict(BASE, name="airlight", sphere_albedo=0.0, floor_albedo=0.0)),
    ("full scene (sphere_iso)", dict(BASE, name="sphere_iso")),
]
ROWS = [("image", slice(0, ms.H)), ("rows 0-15", slice(0, 16)), ("rows 16-31", slice(16, 32)),
        ("rows 32-47", slice(32, 48))]


def direct_light_only(case, ss):
    """Luminance of the surfaces-only scene (no medium), box-filtered over ss x ss pixel centres, in numpy
    double: L = albedo/π I cos θ / r² for points inside the lamp's hard cone and not shadowed by the
    sphere. Shares no code with seasim or Mitsuba (camera: vertical fov, pinhole, as both)."""
    eye, target = np.array([0.0, 1.6, 9.0]), np.array([0.0, 1.0, 0.0])
    fwd = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(fwd, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    tan_half = np.tan(np.radians(45.0) / 2)
    centre, radius, lamp = np.array([0.0, 2.2, -1.0]), 0.55, np.array([0.0, 5.2, -1.0])
    cos_cone = np.cos(np.radians(case["cone"]))
    out = np.zeros((ms.H, ms.W))
    xs = (np.arange(ms.W * ss) + 0.5) / ss
    for row in range(ms.H):  # one image row at a time keeps the arrays small at ss = 64
        ys = row + (np.arange(ss) + 0.5) / ss
        X, Y = np.meshgrid(xs, ys)
        u = (2 * X / ms.W - 1) * tan_half * ms.W / ms.H
        v = (1 - 2 * Y / ms.H) * tan_half
        d = fwd + u[..., None] * right + v[..., None] * up
        d /= np.linalg.norm(d, axis=-1, keepdims=True)
        oc = eye - centre
        b = d @ oc
        disc = b * b - (oc @ oc - radius * radius)
        t_sphere = np.where(disc > 0, -b - np.sqrt(np.maximum(disc, 0.0)), np.inf)
        down = d[..., 1] < 0
        t_floor = np.where(down, -eye[1] / np.where(down, d[..., 1], -1.0), np.inf)
        on_sphere = t_sphere < t_floor
        t = np.minimum(t_sphere, t_floor)
        hit = np.isfinite(t)
        p = eye + np.where(hit, t, 0.0)[..., None] * d
        normal = np.where(on_sphere[..., None], (p - centre) / radius, np.array([0.0, 1.0, 0.0]))
        albedo = np.where(on_sphere, case.get("sphere_albedo", 0.6), case.get("floor_albedo", 0.35))
        to_lamp = lamp - p
        r = np.linalg.norm(to_lamp, axis=-1)
        wl = to_lamp / r[..., None]
        cos_n = np.sum(normal * wl, axis=-1)
        in_cone = wl[..., 1] > cos_cone  # the axis points down: cos to the axis = -(-wl).y
        pc = p - centre  # the sphere between a floor point and the lamp
        b2 = np.sum(wl * pc, axis=-1)
        disc2 = b2 * b2 - (np.sum(pc * pc, axis=-1) - radius * radius)
        t2 = -b2 - np.sqrt(np.maximum(disc2, 0.0))
        shadowed = ~on_sphere & (disc2 > 0) & (t2 > 0) & (t2 < r)
        lit = hit & in_cone & (cos_n > 0) & ~shadowed
        radiance = np.where(lit, albedo / np.pi * cos_n / (r * r), 0.0)
        out[row] = radiance.reshape(ss, ms.W, ss).mean(axis=(0, 2))
    return out * (np.array([60.0, 57.0, 51.0]) @ LUM)  # the lamp's RGB intensity, as luminance


def seasim_reference(binary, case, ss, tmp):
    toml = os.path.join(tmp, case["name"] + ".toml")
    with open(toml, "w") as f:
        f.write(ms.scene_toml(case, ss))
    exr = os.path.join(tmp, "ref.exr")
    t0 = time.time()
    subprocess.run([binary, "reference", toml, "-o", exr, "--steps", "1000"], check=True, stdout=subprocess.DEVNULL)
    return ms.read_exr(exr, ss) @ LUM, time.time() - t0


def main():
    binary, out = sys.argv[1], sys.argv[2]
    seeds = int(sys.argv[3]) if len(sys.argv) > 3 else 8
    spp = int(sys.argv[4]) if len(sys.argv) > 4 else 1024
    os.makedirs(out, exist_ok=True)
    lines = ["# Spotlight with a sphere and a floor: which term reads low against Mitsuba", "",
             f"Scene of mitsuba_shafts.py ({ms.W}x{ms.H}; lamp 5.2 m above the floor, 24° hard cone; sphere "
             f"r = 0.55 m, albedo 0.6; floor albedo 0.35; ρ = 0.04, κ = 1.25, isotropic). Mitsuba "
             f"{ms.mi.__version__} volpath max_depth = 2: {seeds} independent seeds x {spp} spp. seasim "
             f"`reference --steps 1000` at SS x SS pixel centres per pixel, block-averaged. Luminance ratios "
             f"of region means, ± 2 standard errors of Mitsuba's mean. Machine: {os.uname().nodename}, "
             f"{os.cpu_count()} cores.", ""]
    with tempfile.TemporaryDirectory() as tmp:
        for label, case in VARIANTS:
            t0 = time.time()
            runs = np.array([np.array(ms.mi.render(ms.mitsuba_scene(case, (k + 1) * ms.SEED_STRIDE, spp)),
                                      dtype=np.float64)[:, :, :3] @ LUM for k in range(seeds)])
            t_mts = time.time() - t0
            images = []
            if case["rho"] == 0:
                for ss in (1, 2, 4, 8, 16, 32, 64):
                    images.append((f"numpy direct light, SS = {ss}", direct_light_only(case, ss), None))
            for ss in (4, 16):
                img, sec = seasim_reference(binary, case, ss, tmp)
                images.append((f"seasim reference, SS = {ss}", img, sec))
            lines += [f"## {label}", "", f"Mitsuba: {t_mts:.0f} s.", "",
                      "| | " + " | ".join(name for name, _ in ROWS) + " | s |",
                      "|---|" + "---:|" * (len(ROWS) + 1)]
            means = {name: np.array([r[rows].mean() for r in runs]) for name, rows in ROWS}
            lines.append("| Mitsuba mean (± 2 se, relative) | " + " | ".join(
                f"{m.mean():.4g} (± {2 * m.std(ddof=1) / np.sqrt(seeds) / m.mean():.4f})" for m in means.values())
                + " | |")
            for name, img, sec in images:
                lines.append(f"| {name} / Mitsuba | " + " | ".join(
                    f"{img[rows].mean() / means[rn].mean():.4f}" for rn, rows in ROWS)
                    + f" | {'' if sec is None else f'{sec:.1f}'} |")
            lines.append("")
            print("\n".join(lines[-len(images) - 6:]), flush=True)
    with open(os.path.join(out, "shafts_surfaces.md"), "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
