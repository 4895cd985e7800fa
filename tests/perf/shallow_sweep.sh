#!/bin/sh
# shallow_sweep.sh — shallow water's measured tables (results/shallow/): for each shallow scene, the paper's
# table path (003 eq. 22) and eq. 24's pre-converted blend against the exact spectral path (eq. 20),
# by table resolution and γ, with times; and the lake's time per frame by band count.
#   tests/perf/shallow_sweep.sh [build-dir]     (run from the repository root)
set -eu
B=${1:-build}
OUT=results/shallow
TMP=$(mktemp -d)
mkdir -p "$OUT"
export POCL_CACHE_DIR="$B/pocl-cache" SEASIM_CACHE_DIR="$B/seasim-cache"
for s in mountain_lake tropical_shallows muddy_coast; do
  "$B/seasim" render "scenes/$s.toml" --set 'shallow.path="exact"' --out "$TMP/$s" >/dev/null
  "$B/seasim" sweep "scenes/$s.toml" --param quality.fourflow_table_size=4,8,16,32,64,128 \
    --param shallow.gamma=0.5,1,2,4 --reference "$TMP/$s/image.exr" --csv "$OUT/${s}_table_vs_exact.csv"
  "$B/seasim" sweep "scenes/$s.toml" --set 'shallow.path="table_eq24"' \
    --param quality.fourflow_table_size=8,32,128 --reference "$TMP/$s/image.exr" --csv "$OUT/${s}_eq24_vs_exact.csv"
done
"$B/seasim" bench --scene scenes/mountain_lake.toml --wavelengths 3,8,16,32,64 --repeat 3 \
  --csv "$OUT/bench_wavelengths_table.csv"
"$B/seasim" bench --scene scenes/mountain_lake.toml --set 'shallow.path="exact"' --wavelengths 3,8,16,32,64 --repeat 3 \
  --csv "$OUT/bench_wavelengths_exact.csv"
rm -rf "$TMP"
