#!/bin/sh
# layers_time.sh — what each group of ground-truth layers (docs/layers.md) adds to an underwater frame
# at 640x360, from report.json's pass_ms: kd_multiple's time (the split and veiling are written by it),
# the layer passes' own (geometry_layers, effective_coefficients, water_spread's second expansion) and
# the frame's summed kernel time, against the same frame without layers, rounds interleaved (none,
# geometry, ..., none, geometry, ...) so that a shared machine's load falls on every variant alike.
# Prints one CSV row per round and variant, then per variant the medians over rounds and kd_multiple's
# ratio to "none" in the same round (the ratio is the figure to quote on a loaded machine).
# Usage: tests/perf/layers_time.sh [SCENE]   (ROUNDS=5, SEASIM=build/seasim, MODEL=thesis|discrete_ordinates)
SCENE=${1:-scenes/seabed.toml}
ROUNDS=${ROUNDS:-5}
SEASIM=${SEASIM:-build/seasim}
MODEL=${MODEL:-thesis}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
kernel_ms() {  # $1: outputs.layers (TOML array); prints "total_ms,kd_ms,layer_passes_ms"
  "$SEASIM" render "$SCENE" -o "$OUT/r" --output exr --set camera.width=640 --set camera.height=360 \
    --set underwater.model=\""$MODEL"\" --set "outputs.layers=$1" >/dev/null 2>&1 || { echo nan,nan,nan; return; }
  python3 -c 'import json,sys
r = json.load(open(sys.argv[1])); p = r["pass_ms"]
own = sum(p.get(k, 0) for k in ("geometry_layers", "effective_coefficients", "water_spread_forward_layer"))
print("%.2f,%.2f,%.2f" % (r["kernel_ms_total"], p["kd_multiple"], own))' "$OUT/r/report.json"
}
{
echo "round,variant,kernel_ms,kd_multiple_ms,layer_passes_ms"
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for v in none geometry split veiling beta; do
    case $v in
    none) l='[]' ;;
    geometry) l='["range","depth","normal","object_id","albedo"]' ;;
    split) l='["clear","direct","backscatter","forward","lamps","transmission"]' ;;
    veiling) l='["veiling"]' ;;
    beta) l='["beta_d","beta_b"]' ;;  # needs the split and veiling too
    esac
    echo "$r,$v,$(kernel_ms "$l")"
  done
  r=$((r + 1))
done
} | tee "$OUT/rows.csv"
python3 - "$OUT/rows.csv" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
base = {r["round"]: float(r["kd_multiple_ms"]) for r in rows if r["variant"] == "none"}
by = {}
for r in rows:
    by.setdefault(r["variant"], []).append(r)
print("variant,median_kernel_ms,median_kd_ms,kd_ratio_to_none(min..max),median_layer_passes_ms")
for v, rs in by.items():
    med = lambda k: statistics.median(float(r[k]) for r in rs)
    ratios = [float(r["kd_multiple_ms"]) / base[r["round"]] for r in rs]
    print(f"{v},{med('kernel_ms'):.1f},{med('kd_multiple_ms'):.1f},{statistics.median(ratios):.2f}({min(ratios):.2f}..{max(ratios):.2f}),{med('layer_passes_ms'):.2f}")
PY
