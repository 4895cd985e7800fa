#!/bin/sh
# spectral_layers_time.sh — the cost of spectral.exr's layers per band on an underwater frame (seabed,
# 640x360, 16 bands, the discrete-ordinates model, froxels on), from report.json's pass_ms: kd_multiple,
# the froxels' term per band (froxel_spectral_bands: one integration per band, one resolve per band and
# target) and the frame's summed kernel time, for spectral.exr without layers, with the split per band
# and with the veiling too; one or more binaries, rounds interleaved (binary, variant) so that a shared
# machine's load falls on every one alike. Prints a CSV row per round, then the medians per binary and
# variant.
# Usage: tests/perf/spectral_layers_time.sh NAME=BINARY[=DATA_DIR] ...   (ROUNDS=3, SCENE=scenes/seabed.toml;
# DATA_DIR: the binary's SEASIM_DATA_DIR, for an older binary with the data folder of its own tree)
SCENE=${SCENE:-scenes/seabed.toml}
ROUNDS=${ROUNDS:-3}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
frame_ms() {  # $1 binary[=data dir], $2 outputs.layers (TOML array); prints "kernel_ms,kd_ms,froxel_bands_ms"
  bin=${1%%=*}
  if [ "$bin" != "$1" ]; then export SEASIM_DATA_DIR="${1#*=}"; else unset SEASIM_DATA_DIR; fi
  "$bin" render "$SCENE" -o "$OUT/r" --output exr,spectral_exr --set camera.width=640 --set camera.height=360 \
    --set spectral.count=16 --set spectral.spectral_exr=true --set "outputs.layers=$2" >/dev/null 2>&1 ||
    { echo nan,nan,nan; return; }
  python3 -c 'import json,sys
r = json.load(open(sys.argv[1])); p = r["pass_ms"]
print("%.1f,%.1f,%.1f" % (r["kernel_ms_total"], p["kd_multiple"], p.get("froxel_spectral_bands", 0)))' "$OUT/r/report.json"
}
{
echo "round,binary,variant,kernel_ms,kd_multiple_ms,froxel_bands_ms"
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for v in none split veiling; do
    case $v in
    none) l='[]' ;;
    split) l='["clear","direct","backscatter","forward","lamps","transmission"]' ;;
    veiling) l='["clear","direct","backscatter","forward","lamps","transmission","veiling"]' ;;
    esac
    for b in "$@"; do
      echo "$r,${b%%=*},$v,$(frame_ms "${b#*=}" "$l")"
    done
  done
  r=$((r + 1))
done
} | tee "$OUT/rows.csv"
python3 - "$OUT/rows.csv" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
by = {}
for r in rows:
    by.setdefault((r["binary"], r["variant"]), []).append(r)
print("binary,variant,median_kernel_ms,median_kd_multiple_ms,median_froxel_bands_ms")
for (b, v), rs in by.items():
    med = lambda k: statistics.median(float(r[k]) for r in rs)
    print(f"{b},{v},{med('kernel_ms'):.0f},{med('kd_multiple_ms'):.0f},{med('froxel_bands_ms'):.0f}")
PY
