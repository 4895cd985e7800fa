"""What Python adds over the C++ call: flat_sea at 64x36 rendered from Python and timed by the C++
core itself (FrameResult.wall_ms: set-up + kernels + read-back inside Renderer::render), next to
`seasim bench` on the same scene in the same run; then update() + render() for a sun change.

Run from the repository root:  python docs/python/overhead.py [path/to/seasim] [repeats]
"""

import statistics
import subprocess
import sys
import time

import seasim

binary = sys.argv[1] if len(sys.argv) > 1 else "build/seasim"
repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 50
small = {"camera.width": 64, "camera.height": 36}
scene = seasim.Scene.load("scenes/flat_sea.toml", overrides=small)
renderer = seasim.Renderer(scene)
renderer.render()  # kernel builds (or cache loads) out of the timing


def timed(step):
    py, cpp, kernels = [], [], []
    for i in range(repeats):
        t0 = time.perf_counter()
        frame = step(i)
        py.append(1e3 * (time.perf_counter() - t0))
        cpp.append(frame.wall_ms)
        # as bench counts them: without the NaN/Inf check's pass
        kernels.append(sum(ms for name, ms in frame.timings.items() if name != "nonfinite_check"))
    return statistics.median(py), statistics.median(cpp), statistics.median(kernels)


def whole_frame(i):
    renderer.rerun_all()
    return renderer.render()


def sun_change(i):
    renderer.update({"sun.zenith_deg": 40.0 + (i % 2)})
    return renderer.render()


print(f"device: {renderer.device.label}")
for label, step in (("render() of the whole frame", whole_frame), ("update(sun) + render()", sun_change)):
    py, cpp, kernels = timed(step)
    print(f"{label:30s} Python {py:7.3f} ms | C++ Renderer::render {cpp:7.3f} ms | kernels* {kernels:6.3f} ms | "
          f"Python over C++ {py - cpp:6.3f} ms (median of {repeats})")

sets = [a for k, v in small.items() for a in ("--set", f"{k}={v}")]
bench = subprocess.run([binary, "bench", "--scene", "scenes/flat_sea.toml", *sets, "--wavelengths", "16",
                        "--repeat", str(repeats)], capture_output=True, text=True, check=True).stdout
print("* without nonfinite_check, as bench counts")
print("seasim bench, same scene:", [line for line in bench.splitlines() if line.startswith("n =")][0].strip())
