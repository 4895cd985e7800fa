"""The FFT ocean animated into frames: surface.time advances, and only the passes that read the
time run again (the wave spectrum's set-up is kept). Writes frames/frame_NNN.png and a contact sheet.

Run from the repository root:  python docs/python/ocean_frames.py [out_dir] [frames]
"""

import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import seasim

out = Path(sys.argv[1] if len(sys.argv) > 1 else "ocean_frames")
count = int(sys.argv[2]) if len(sys.argv) > 2 else 8
out.mkdir(parents=True, exist_ok=True)

scene = seasim.Scene.load("scenes/wavy_sea.toml", overrides={"camera.width": 240, "camera.height": 135})
renderer = seasim.Renderer(scene)
images = []
for i in range(count):
    renderer.update({"surface.time": 0.25 * i})  # seconds
    t0 = time.perf_counter()
    frame = renderer.render()
    ms = 1e3 * (time.perf_counter() - t0)
    image = seasim.display(frame)
    plt.imsave(out / f"frame_{i:03d}.png", image)
    images.append(image)
    print(f"t = {0.25 * i:4.2f} s: {ms:6.1f} ms, passes run: {', '.join(renderer.last_executed)}")

cols = 4
rows = (count + cols - 1) // cols
fig, axes = plt.subplots(rows, cols, figsize=(3 * cols, 1.8 * rows))
for i, ax in enumerate(axes.flat):
    ax.axis("off")
    if i < count:
        ax.imshow(images[i])
        ax.set_title(f"t = {0.25 * i:.2f} s", fontsize=9)
fig.tight_layout()
fig.savefig(out / "contact_sheet.png", dpi=100)
print("wrote", out)
