#!/bin/sh
# layers_time.sh — what each ground-truth layer (docs/layers.md) adds to an underwater frame at
# 640x360: the summed kernel time of report.json's pass_ms with one group of layers asked, against the
# same frame without layers, rounds interleaved (none, range, ..., none, range, ...) so that a shared
# machine's load falls on every variant alike. Prints one CSV row per round and variant, then the
# median over rounds of each variant's kernel ms and its difference from "none".
# Usage: tests/perf/layers_time.sh [SCENE]   (ROUNDS=5, SEASIM=build/seasim, MODEL=thesis|improved)
SCENE=${1:-scenes/seabed.toml}
ROUNDS=${ROUNDS:-5}
SEASIM=${SEASIM:-build/seasim}
MODEL=${MODEL:-thesis}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
kernel_ms() {  # $1: outputs.layers (TOML array); prints the frame's summed kernel ms
  "$SEASIM" render "$SCENE" -o "$OUT/r" --output exr --set camera.width=640 --set camera.height=360 \
    --set underwater.model=\""$MODEL"\" --set "outputs.layers=$1" >/dev/null 2>&1 || { echo nan; return; }
  python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["kernel_ms_total"])' "$OUT/r/report.json"
}
{
echo "round,variant,kernel_ms"
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for v in none range geometry split veiling beta all; do
    case $v in
    none) l='[]' ;;
    range) l='["range"]' ;;
    geometry) l='["range","depth","normal","object_id","albedo"]' ;;
    split) l='["clear","direct","backscatter","forward","lamps","transmission"]' ;;
    veiling) l='["veiling"]' ;;
    beta) l='["beta_d","beta_b"]' ;;
    all) l='["range","depth","normal","object_id","albedo","clear","direct","backscatter","forward","lamps","transmission","veiling","beta_d","beta_b"]' ;;
    esac
    echo "$r,$v,$(kernel_ms "$l")"
  done
  r=$((r + 1))
done
} | tee "$OUT/rows.csv"
python3 - "$OUT/rows.csv" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
by = {}
for r in rows:
    by.setdefault(r["variant"], []).append(float(r["kernel_ms"]))
base = statistics.median(by["none"])
print("variant,median_kernel_ms,added_ms,min,max")
for v, ms in by.items():
    m = statistics.median(ms)
    print(f"{v},{m:.2f},{m - base:+.2f},{min(ms):.2f},{max(ms):.2f}")
PY
