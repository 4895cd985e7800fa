#!/bin/sh
# sea_internal_reflection.sh — how much of the sea seen from above is light the surface
# reflects back down from below (mostly total internal reflection), and how sea.model = "multiple"
# follows it, by the backscattering ratio u = b_b/(a + b_b). One grey band (explicit a, b; g 0.9) in the
# view of tests/perf/sea_allorders.sh (scenes/flat_sea.toml at 96x54, camera 5 m up looking 45° down,
# sun 40°, sky 0.05). Per case three images:
#   - the model: `seasim render --set sea.model="multiple"`;
#   - all orders: `seasim reference --all-orders` (the path tracer, kernels/reference.cl);
#   - all orders without internal reflection: the same path tracer from a copy of kernels/ in which a
#     path that the surface reflects from below ends there (SEASIM_KERNEL_DIR), so the surface only
#     lets light out.
#   tests/perf/sea_internal_reflection.sh [build-dir] [paths-per-pixel] [out.csv]
# e.g. tests/perf/sea_internal_reflection.sh build 512 results/sea_allorders/internal_reflection.csv
# Columns: a, b, bottom depth (1000: deep), u (b_b from HG g = 0.9), image-mean luminance of the model,
# of all orders (and its standard error) and of all orders without internal reflection; model / all
# orders, model / all orders without internal reflection, and all orders / without (the share of the
# internally reflected light). Path tracer images are kept in $PT_DIR (default build/sea_ir_pt).
# MAXB: the path tracer's cap on scattering vertices (seasim reference --max-bounces; default 1000, the
# CLI's default), always passed and named in the images (pt_mb<MAXB>_...): images traced before the cap
# was named carry no mb part and were capped at 64. CASES: "a b depth" triples separated by ';' (default
# the eight below), e.g. MAXB=2048 CASES="0.0425 1.0 1000;0.028 1.0 1000;0.02 1.4 1000".
set -eu
B=${1:-build}
SPP=${2:-512}
OUT=${3:-results/sea_allorders/internal_reflection.csv}
PT_DIR=${PT_DIR:-$B/sea_ir_pt}
MAXB=${MAXB:-1000}
CASES=${CASES:-"0.3 1.0 1000;0.065 1.0 1000;0.0425 1.0 1000;0.028 1.0 1000;0.04 1.4 1000;0.02 1.4 1000;0.065 1.0 5;0.3 0.05 2"}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
export POCL_CACHE_DIR="$B/pocl-cache" SEASIM_CACHE_DIR="$B/seasim-cache"
mkdir -p "$PT_DIR" "$(dirname "$OUT")"

# The path tracer without internal reflection: at the surface from below, a reflected path ends.
. tests/perf/sea_kernels_no_ir.sh
kernels_no_ir "$TMP/kernels_no_ir"

lum() {
  oiiotool "$1" --chsum:weight=2126,7152,722 --printstats | awk '/Stats Avg/ { printf "%.6g", $3 / 1e4 }'
}
lum_se() {
  [ -f "$1" ] || return 0  # the bounce-cap study's mb2048 images were kept without their standard-error image
  oiiotool "$1" --chsum:weight=2126,7152,722 --powc 2 --printstats |
    awk '/Stats Avg/ { printf "%.4g", sqrt($3 / (96 * 54)) / 1e4 }'
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.4f", (b > 0 ? a / b : 0) }'; }

echo "a,b,bottom_m,u,model_lum,pt_lum,pt_lum_se,pt_no_ir_lum,model_over_pt,model_over_pt_no_ir,pt_over_pt_no_ir" > "$OUT"
# a b depth: u = 0.07, 0.26, 0.35, 0.45 (twice, at two b), 0.62 in deep water; 0.26 over 5 m; clear-ish over 2 m.
OLD_IFS=$IFS
IFS=';'
# shellcheck disable=SC2086 # split on ';'
set -- $CASES
IFS=$OLD_IFS
for case in "$@"; do
  # shellcheck disable=SC2086 # the case is three words
  set -- $case
  a=$1; b=$2; d=$3
  sed -e 's/^position = .*/position = [0.0, 5.0, 0.0]/' -e 's/^look_at = .*/look_at = [0.0, 0.0, -5.0]/' \
      -e 's/^width = .*/width = 96/' -e 's/^height = .*/height = 54/' \
      -e "s/^jerlov = .*/wavelengths_nm = [400.0, 700.0]\na = [$a, $a]\nb = [$b, $b]/" \
      -e 's/^count = 16/count = 1/' scenes/flat_sea.toml > "$TMP/sea.toml"
  pt="$PT_DIR/pt_mb${MAXB}_${a}_${b}_${d}_${SPP}.exr"
  pt_no="$PT_DIR/pt_no_ir_mb${MAXB}_${a}_${b}_${d}_${SPP}.exr"
  if [ ! -f "$pt" ]; then
    "$B/seasim" reference "$TMP/sea.toml" --set bottom.depth="$d" --all-orders --max-bounces "$MAXB" --steps "$SPP" --seed 1 \
      -o "$TMP/pt.exr" > /dev/null 2>&1
    mv "$TMP/pt.stderr.exr" "${pt%.exr}.stderr.exr"
    mv "$TMP/pt.exr" "$pt"
  fi
  if [ ! -f "$pt_no" ]; then
    SEASIM_KERNEL_DIR="$TMP/kernels_no_ir" "$B/seasim" reference "$TMP/sea.toml" --set bottom.depth="$d" \
      --all-orders --max-bounces "$MAXB" --steps "$SPP" --seed 1 -o "$TMP/pt.exr" > /dev/null 2>&1
    mv "$TMP/pt.exr" "$pt_no"
  fi
  "$B/seasim" render "$TMP/sea.toml" --set bottom.depth="$d" --set 'sea.model="multiple"' -o "$TMP/model" > /dev/null
  u=$(awk -v a="$a" -v b="$b" 'BEGIN { g = 0.9; f = (1 - g) / (2 * g) * ((1 + g) / sqrt(1 + g * g) - 1); printf "%.3f", f * b / (a + f * b) }')
  m=$(lum "$TMP/model/image.exr"); p=$(lum "$pt"); s=$(lum_se "${pt%.exr}.stderr.exr"); q=$(lum "$pt_no")
  echo "$a,$b,$d,$u,$m,$p,$s,$q,$(ratio "$m" "$p"),$(ratio "$m" "$q"),$(ratio "$p" "$q")" >> "$OUT"
done
cat "$OUT"
