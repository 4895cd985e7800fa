#!/bin/sh
# lamps_lattice_sweep.sh — the lamps' orders model with its smooth part on a lattice
# (quality.lamps_ms_cell_deg) against every pixel evaluated (cell 0), error and time side by side:
#   1. rov_lights at 320x180 and 640x360 (`seasim sweep`, the every-pixel render as the reference:
#      the lattice's own error, not the model's);
#   2. the lamps study's 29 cases (tests/perf/lamp_orders_sweep.sh's FIT, HELDOUT, NEAR) at 192x108,
#      every region's fast / reference ratio with the lattice over the ratio without (the reference is
#      the same render, 16 paths per pixel, and cancels: only the lattice's change is measured); cells
#      of 1.15, 1.7 and 2.25 degrees are every 2, 3 and 4 pixels there (0.556 degrees per pixel).
# Writes results/underwater/lamps_lattice_{320,640}.{csv,svg} and prints the regions' summary.
# Usage: tests/perf/lamps_lattice_sweep.sh [work folder, default /tmp/lamps_lattice]   (about 5 min)
B=${B:-build/seasim}
W=${1:-/tmp/lamps_lattice}
mkdir -p "$W" results/underwater
for size in 320x180 640x360; do
  w=${size%x*}; h=${size#*x}
  S="--set camera.width=$w --set camera.height=$h"
  $B render scenes/rov_lights.toml $S --set quality.lamps_ms_cell_deg=0 -o "$W/every$w" > /dev/null || exit 1
  $B sweep scenes/rov_lights.toml $S --param quality.lamps_ms_cell_deg=0.34,0.67,1,1.34,2 \
    --reference "$W/every$w/image.exr" --csv results/underwater/lamps_lattice_$w.csv \
    --plot results/underwater/lamps_lattice_$w.svg || exit 1
done
eval "$(sed -n '/^FIT=/,/^0.05:0.5:0.7:15:10/p' tests/perf/lamp_orders_sweep.sh)"
for cell in 0 1.15 1.7 2.25; do
  $B lamp-regions --cases "$FIT,$HELDOUT,$NEAR" --models orders --spp 16 --rounds 1 --set camera.width=192 \
    --set camera.height=108 --model-set quality.lamps_ms_cell_deg=$cell --csv "$W/regions_$cell.csv" > /dev/null || exit 1
done
python3 - "$W" <<'PY'
import csv, sys
w = sys.argv[1]
rows = {c: list(csv.reader(open(f"{w}/regions_{c}.csv")))[1:] for c in ("0", "1.15", "1.7", "2.25")}
print("| cell | regions | median change | 90th percentile | largest |")
print("|---:|---:|---:|---:|---:|")
for c in ("1.15", "1.7", "2.25"):
    d = []
    for a, b in zip(rows["0"], rows[c]):
        for px in (8, 11, 14, 17):  # whole, lit bottom, beam, outside: pixels, then ratio
            if a[px] and a[px + 1] and b[px + 1] and int(float(a[px])) >= 20:
                d.append(abs(float(b[px + 1]) / float(a[px + 1]) - 1))
    d.sort()
    print(f"| {c}° | {len(d)} | {100 * d[len(d) // 2]:.3f} % | {100 * d[int(0.9 * len(d))]:.2f} % | {100 * d[-1]:.2f} % |")
PY
