"""An experiment on the open-air spotlight case of mitsuba_shafts.py: is seasim's 1.7 % deficit
against Mitsuba there (results/validation/README.md), largest in the top rows whose rays pass 0.2-0.4 m
below the lamp, an effect of the pixel filter? Mitsuba averages radiance over each pixel's area (box
filter); seasim samples pixel centres, and mitsuba_shafts.py averages 4x4 of them per pixel. Near the
lamp's apex the airlight grows like the inverse distance to the apex and is convex across a pixel, so a
midpoint rule falls short of the pixel's mean. If that is the cause, seasim / Mitsuba moves towards 1
as the supersampling SS grows (same scene, same Mitsuba images).
Writes shafts_pixel_filter.md: seasim reference (SS x SS pixel centres per pixel) / Mitsuba, whole
image and the top rows, for SS = 1, 2, 4, 8, 16.
  python shafts_pixel_filter.py SEASIM OUT_DIR [mitsuba seeds] [mitsuba spp]
"""
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import mitsuba_shafts as ms

CASE = {"name": "open_iso", "sphere": False, "rho": 0.04, "kappa": 1.0, "g": 0.0, "cone": 30.0}
LUM = np.array([0.2126, 0.7152, 0.0722])


def main():
    binary, out = sys.argv[1], sys.argv[2]
    seeds = int(sys.argv[3]) if len(sys.argv) > 3 else 8
    spp = int(sys.argv[4]) if len(sys.argv) > 4 else 1024
    os.makedirs(out, exist_ok=True)
    t0 = time.time()
    runs = [np.array(ms.mi.render(ms.mitsuba_scene(CASE, (seed + 1) * ms.SEED_STRIDE, spp)), dtype=np.float64)[:, :, :3] @ LUM
            for seed in range(seeds)]
    t_mts = time.time() - t0
    rows = [0, 1, 2, 3, 4, 8]
    per_run_rows = np.array([r.mean(axis=1) for r in runs])  # seeds x H
    per_run_all = np.array([r.mean() for r in runs])
    m_rows, se_rows = per_run_rows.mean(axis=0), per_run_rows.std(axis=0, ddof=1) / np.sqrt(seeds)
    m_all, se_all = per_run_all.mean(), per_run_all.std(ddof=1) / np.sqrt(seeds)
    lines = ["# Open-air spotlight: seasim reference / Mitsuba against seasim's supersampling", "",
             f"Case open_iso of mitsuba_shafts.py ({ms.W}x{ms.H}, lamp at y = 5.2 m just above the frame, 30° hard "
             f"cone, ρ = 0.04, κ = 1). Mitsuba {ms.mi.__version__}: {seeds} seeds x {spp} spp, {t_mts:.0f} s; seasim "
             f"`reference --steps 1000` at SS x SS pixel centres per pixel, block-averaged. Luminance ratios, "
             f"± 2 standard errors of Mitsuba's mean. Machine: {os.uname().nodename}, {os.cpu_count()} cores.", "",
             "| SS | whole image | " + " | ".join(f"row {r}" for r in rows) + " | seasim s |",
             "|---:|---:|" + "---:|" * len(rows) + "---:|",
             f"| Mitsuba ± 2 se | {2 * se_all / m_all:.4f} | "
             + " | ".join(f"{2 * se_rows[r] / m_rows[r]:.4f}" for r in rows) + " | |"]
    with tempfile.TemporaryDirectory() as tmp:
        for ss in (1, 2, 4, 8, 16):
            toml = os.path.join(tmp, "open.toml")
            with open(toml, "w") as f:
                f.write(ms.scene_toml(CASE, ss))
            t0 = time.time()
            subprocess.run([binary, "reference", toml, "-o", os.path.join(tmp, "ref.exr"), "--steps", "1000"],
                           check=True, stdout=subprocess.DEVNULL)
            t_ref = time.time() - t0
            ref = ms.read_exr(os.path.join(tmp, "ref.exr"), ss) @ LUM
            ref_rows = ref.mean(axis=1)
            lines.append(f"| {ss} | {ref.mean() / m_all:.4f} | "
                         + " | ".join(f"{ref_rows[r] / m_rows[r]:.4f}" for r in rows) + f" | {t_ref:.1f} |")
            print(lines[-1], flush=True)
    text = "\n".join(lines) + "\n"
    print(text, flush=True)
    with open(os.path.join(out, "shafts_pixel_filter.md"), "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
