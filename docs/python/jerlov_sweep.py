"""The seabed scene under every Jerlov water type, in one Matplotlib figure.

One Renderer for the whole sweep: each water.jerlov update sets up again only the passes that read
the water. Run from the repository root:  python docs/python/jerlov_sweep.py [out.png]
"""

import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import seasim

TYPES = ["I", "IA", "IB", "II", "III", "1C", "3C", "5C", "7C", "9C"]
out = sys.argv[1] if len(sys.argv) > 1 else "jerlov_sweep.png"

scene = seasim.Scene.load("scenes/seabed.toml", overrides={"camera.width": 160, "camera.height": 90})
renderer = seasim.Renderer(scene)
fig, axes = plt.subplots(2, 5, figsize=(12, 3.6))
for ax, water in zip(axes.flat, TYPES):
    renderer.update({"water.jerlov": water})
    t0 = time.perf_counter()
    frame = renderer.render()
    ms = 1e3 * (time.perf_counter() - t0)
    ax.imshow(seasim.display(frame))
    ax.set_title(f"Jerlov {water}  ({ms:.0f} ms)", fontsize=9)
    ax.axis("off")
    print(f"{water:>4}: {ms:7.1f} ms, passes run: {', '.join(renderer.last_executed)}")
fig.suptitle("seabed.toml under the Jerlov water types (160x90, PoCL)")
fig.tight_layout()
fig.savefig(out, dpi=100)
print("wrote", out)
