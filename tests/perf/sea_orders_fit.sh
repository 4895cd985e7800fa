#!/bin/sh
# sea_orders_fit.sh — the higher orders' factor of sea.model = "multiple"
# (kernels/common/sea_multiple.h, sea_higher_orders) against what the path tracer needs, by the
# backscattering ratio u = b_b/(a + b_b). Deep water, one grey band (explicit a, b; g 0.9), the view of
# tests/perf/sea_allorders.sh (scenes/flat_sea.toml at 96x54, camera 5 m up looking 45° down, sun 40°,
# sky 0.05). Per case three images:
#   - all orders without internal reflection: `seasim reference --all-orders` from a copy of kernels/ in
#     which a path that the surface reflects from below ends there (as tests/perf/sea_internal_reflection.sh);
#   - the model's first order: `seasim render --set sea.model="multiple"` from a copy of kernels/ with
#     orders = 1 and no surface return;
#   - the sky's reflection alone: the model with sea.single_scattering = false (deep: nothing else).
# needed = (all orders - sky reflection) / (first order - sky reflection): the factor that would make the
# model's water part equal the path tracer's. The script prints it beside the model's factor now
# (sea_higher_orders, computed here by awk from the same formula) and Lee's 1 + 2.02 u (the factor before).
#   [G=g] [U="u u ..."] [MAXB=n] tests/perf/sea_orders_fit.sh [build-dir] [paths-per-pixel] [out.csv]
# e.g. MAXB=64 tests/perf/sea_orders_fit.sh build 512 results/sea_allorders/orders_fit.csv (as it was measured)
#      G=0.5 U="0.05 0.1 0.2 0.35 0.6" tests/perf/sea_orders_fit.sh build 512 build/orders_fit_g0.5.csv
# G: the water's HG g (water.g; default 0.9, the fit's). U: backscattering ratios to measure, each with
# b = 1 and a = f b (1 - u)/u (f the HG backscattered fraction at G); without U, the fit's 14 (a, b).
# Path tracer images are kept in $PT_DIR (default build/sea_ir_pt, shared with sea_internal_reflection.sh);
# for G other than 0.9 their names carry g (pt_no_ir_g<G>_...), so images of different g never collide.
# MAXB: the path tracer's cap on scattering vertices per path (seasim reference --max-bounces; default 1000,
# the CLI's default), always passed and named in the image (_mb<MAXB>_), as sea_internal_reflection.sh does:
# images without it were traced under the old default cap of 64, which ends paths that would come back up
# at g 0.95 and small a, and are never reused. (orders_fit.csv was measured with that cap: MAXB=64.)
set -eu
B=${1:-build}
SPP=${2:-512}
OUT=${3:-results/sea_allorders/orders_fit.csv}
G=${G:-0.9}
U=${U:-}
MAXB=${MAXB:-1000}
PT_DIR=${PT_DIR:-$B/sea_ir_pt}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
export POCL_CACHE_DIR="$B/pocl-cache" SEASIM_CACHE_DIR="$B/seasim-cache"
mkdir -p "$PT_DIR" "$(dirname "$OUT")"

. tests/perf/sea_kernels_no_ir.sh
kernels_no_ir "$TMP/kernels_no_ir"
# The model's first order: orders 1, nothing sent back down by the surface.
cp -R kernels "$TMP/kernels_first"
sed -i -e 's|f.orders = sea_higher_orders(f.u, c_f);|f.orders = R(1.0);|' \
  -e 's|const real e_down = r_below \* e_up|const real e_down = R(0.0) * e_up|' "$TMP/kernels_first/common/sea_multiple.h"
{ grep -q 'f.orders = R(1.0);' "$TMP/kernels_first/common/sea_multiple.h" &&
  grep -q 'e_down = R(0.0) \* e_up' "$TMP/kernels_first/common/sea_multiple.h"; } ||
  { echo "sea_orders_fit.sh: kernels/common/sea_multiple.h changed; update the patch" >&2; exit 1; }

lum() {
  oiiotool "$1" --chsum:weight=2126,7152,722 --printstats | awk '/Stats Avg/ { printf "%.6g", $3 / 1e4 }'
}

echo "a,b,u,pt_no_ir_lum,first_order_lum,sky_reflection_lum,needed,orders,orders_over_needed,lee,lee_over_needed" > "$OUT"
# a/b: u = 0.02, 0.05, 0.07, 0.1, 0.15, 0.2, 0.3, 0.35, 0.4, 0.45, 0.5, 0.6, 0.62 (b = 1.4), 0.7 (g 0.9).
CASES="1.122/1.0 0.435/1.0 0.3/1.0 0.206/1.0 0.1298/1.0 0.0916/1.0 0.0534/1.0 0.0425/1.0 0.0343/1.0
       0.028/1.0 0.0229/1.0 0.01527/1.0 0.02/1.4 0.00981/1.0"
if [ -n "$U" ]; then
  CASES=$(for u in $U; do
    awk -v g="$G" -v u="$u" 'BEGIN {
      f = (g == 0) ? 0.5 : (1 - g) / (2 * g) * ((1 + g) / sqrt(1 + g * g) - 1)
      printf "%.4g/1.0\n", f * (1 - u) / u }'
  done)
fi
GTAG=""
[ "$G" = "0.9" ] || GTAG="g${G}_"
GTAG="${GTAG}mb${MAXB}_"
for case in $CASES; do
  a=${case%/*}
  b=${case#*/}
  d=1000
  sed -e 's/^position = .*/position = [0.0, 5.0, 0.0]/' -e 's/^look_at = .*/look_at = [0.0, 0.0, -5.0]/' \
      -e 's/^width = .*/width = 96/' -e 's/^height = .*/height = 54/' \
      -e "s/^jerlov = .*/wavelengths_nm = [400.0, 700.0]\na = [$a, $a]\nb = [$b, $b]\ng = $G/" \
      -e 's/^count = 16/count = 1/' scenes/flat_sea.toml > "$TMP/sea.toml"
  pt_no="$PT_DIR/pt_no_ir_${GTAG}${a}_${b}_${d}_${SPP}.exr"
  if [ ! -f "$pt_no" ]; then
    SEASIM_KERNEL_DIR="$TMP/kernels_no_ir" "$B/seasim" reference "$TMP/sea.toml" --set bottom.depth="$d" \
      --all-orders --max-bounces "$MAXB" --steps "$SPP" --seed 1 -o "$TMP/pt.exr" > /dev/null 2>&1
    mv "$TMP/pt.exr" "$pt_no"
  fi
  SEASIM_KERNEL_DIR="$TMP/kernels_first" "$B/seasim" render "$TMP/sea.toml" --set bottom.depth="$d" \
    --set 'sea.model="multiple"' -o "$TMP/first" > /dev/null
  "$B/seasim" render "$TMP/sea.toml" --set bottom.depth="$d" --set 'sea.model="multiple"' \
    --set sea.single_scattering=false -o "$TMP/sky" > /dev/null
  p=$(lum "$pt_no"); m=$(lum "$TMP/first/image.exr"); s=$(lum "$TMP/sky/image.exr")
  awk -v a="$a" -v b="$b" -v p="$p" -v m="$m" -v s="$s" -v g="$G" 'BEGIN {
    f = (g == 0) ? 0.5 : (1 - g) / (2 * g) * ((1 + g) / sqrt(1 + g * g) - 1); u = f * b / (a + f * b)
    need = (p - s) / (m - s); h = (g > 0) ? 1 - 2 * f : 0; o = 1 + 0.52 * u * (0.5 + u) + 0.636 * h * u * u / (u * u + 0.0397); lee = 1 + 0.170 / 0.084 * u
    printf "%s,%s,%.3f,%s,%s,%s,%.4f,%.4f,%.4f,%.4f,%.4f\n", a, b, u, p, m, s, need, o, o / need, lee, lee / need
  }' >> "$OUT"
done
cat "$OUT"
