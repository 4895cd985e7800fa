#!/bin/sh
# shallow_vs_pathtracer.sh — issue 17: the four-flow model (paper 003, exact spectral path) against the
# spectral Monte Carlo path tracer (`seasim reference --all-orders`, all orders of scattering) for the
# mountain lake's water over a flat, uniform bottom at several depths (the depth bands), seen from 3 m
# up and looking down so that every pixel is water. Writes results/shallow/fourflow_vs_pathtracer.csv.
#   tests/perf/shallow_vs_pathtracer.sh [build-dir] [paths-per-pixel]     (from the repository root)
set -eu
B=${1:-build}
SPP=${2:-256}
OUT=results/shallow/fourflow_vs_pathtracer.csv
TMP=$(mktemp -d)
export POCL_CACHE_DIR="$B/pocl-cache" SEASIM_CACHE_DIR="$B/seasim-cache"
# The lake without the slope and the texture: a flat sand bottom (the dark material made the same).
sed -e '/^slope_/d' -e 's/^dark_albedo = .*/dark_albedo = 0.35/' -e 's/^albedo = 0.35 .*/type = "flat"\ndepth = 1.0\nalbedo = 0.35/' \
    -e 's/^position = .*/position = [0.0, 3.0, 0.0]/' -e 's/^look_at = .*/look_at = [0.0, 0.0, -4.0]/' \
    -e 's/^fov_deg = .*/fov_deg = 40.0/' -e 's/^width = .*/width = 64/' -e 's/^height = .*/height = 36/' \
    scenes/mountain_lake.toml > "$TMP/lake_flat.toml"
echo "depth_m,fourflow_ms,pathtracer_ms,rmse_8bit,max_abs_8bit,rel_l2,hue_sat_distance,pathtracer_noise_rel,fourflow_mean_rgb,pathtracer_mean_rgb" > "$OUT"
for d in 0.5 1 2 4 8 15 30; do
  t0=$(date +%s%N)
  "$B/seasim" render "$TMP/lake_flat.toml" --set bottom.depth=$d --set 'shallow.path="exact"' --out "$TMP/ff$d" >/dev/null
  t1=$(date +%s%N)
  ref=$("$B/seasim" reference "$TMP/lake_flat.toml" --set bottom.depth=$d --all-orders --steps "$SPP" -o "$TMP/pt$d.exr" 2>&1)
  # "noise: mean standard error S (image mean M +- ...)": the path tracer's own per-pixel noise, S / M.
  noise=$(echo "$ref" | sed -n 's/.*mean standard error \([0-9.e+-]*\) (image mean \([0-9.e+-]*\)[ )].*/\1 \2/p' | awk '{ if ($2 > 0) printf "%.4f", $1 / $2 }')
  t2=$(date +%s%N)
  cmp=$("$B/seasim" compare "$TMP/ff$d/image.exr" "$TMP/pt$d.exr")
  v() { echo "$cmp" | awk -v k="$1" '$1 == k { print $2 }'; }
  # Image means (linear RGB) by OpenImageIO's oiiotool, as "r g b" (empty without oiiotool).
  mean() { oiiotool "$1" --printstats 2>/dev/null | awk '/Stats Avg/ { print $3, $4, $5 }'; }
  echo "$d,$(( (t1 - t0) / 1000000 )),$(( (t2 - t1) / 1000000 )),$(v rmse_8bit),$(v max_abs_8bit),$(v rel_l2),$(v hue_sat_distance),$noise,$(mean "$TMP/ff$d/image.exr"),$(mean "$TMP/pt$d.exr")" >> "$OUT"
done
rm -rf "$TMP"
cat "$OUT"
