"""A quality knob swept against the brute-force reference: error (RMSE in 8-bit levels, the metric
of `seasim sweep`) against kernel time, in a Matplotlib plot.

The README's sweep: the flat sea's wavelength count against its quadrature reference at 64 bands
and 512 steps (the knob with the largest error-time trade on this scene: the others converge below
0.01 levels at their smallest settings). Run from the repository root:
python docs/python/quality_sweep.py [out.png]
"""

import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import seasim

KNOB, VALUES = "spectral.count", [3, 4, 8, 16, 32]
out = sys.argv[1] if len(sys.argv) > 1 else "quality_sweep.png"

scene = seasim.Scene.load("scenes/flat_sea.toml", overrides={"camera.width": 160, "camera.height": 90})
reference = seasim.reference(scene.with_overrides({"spectral.count": 64}), steps=512)
print(f"reference: {reference.method}, {reference.steps} steps, {reference.ms:.0f} ms")

renderer = seasim.Renderer(scene)
times, errors = [], []
for value in VALUES:
    renderer.update({KNOB: value})
    renderer.render()  # set-up of what changed (and PoCL's lazy compile) out of the timing
    runs = []
    for _ in range(3):
        renderer.rerun_all()
        frame = renderer.render()
        runs.append(sum(frame.timings.values()))
    ms = statistics.median(runs)
    error = seasim.compare(frame, reference, exposure_ev=frame.report["settings"]["exposure_ev"])
    times.append(ms)
    errors.append(error["rmse_8bit"])
    print(f"{KNOB} = {value:3d}: {ms:7.3f} ms kernels, RMSE {error['rmse_8bit']:.4f} levels, "
          f"max {error['max_abs_8bit']:.3f}")

fig, ax = plt.subplots(figsize=(5, 3.5))
ax.plot(times, errors, "o-")
for t, e, v in zip(times, errors, VALUES):
    ax.annotate(str(v), (t, e), textcoords="offset points", xytext=(4, 4), fontsize=8)
ax.set_xlabel("kernel time (ms)")
ax.set_ylabel("RMSE vs reference (8-bit levels)")
ax.set_yscale("log")
ax.set_title(f"flat_sea 160x90: {KNOB}")
fig.tight_layout()
fig.savefig(out, dpi=100)
print("wrote", out)
