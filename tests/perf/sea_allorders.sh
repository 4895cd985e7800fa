#!/bin/sh
# sea_allorders.sh — the sea seen from above, a fast model (`seasim render`) against all
# orders of scattering (`seasim reference --all-orders`, the spectral path tracer with the camera above
# the surface refracting in), for Jerlov I, IB, II, III, 3C over a flat bottom at 2, 5, 10, 20 m and
# deep water (1000 m). The scene is scenes/flat_sea.toml at 96x54 with the camera 5 m up looking 45°
# down (every pixel sees water, 25–65° from the nadir; sun 40°, g 0.9, 16 bands, CIE 1931), as
# results/sea_allorders/README.md describes.
#   tests/perf/sea_allorders.sh [build-dir] [paths-per-pixel] [out.csv] [render --set ...]
# e.g. (from the repository root)
#   MAXB=64 tests/perf/sea_allorders.sh build 2048 results/sea_allorders/table.csv --set 'sea.model="paper"' --set sea.second_order=true
#   tests/perf/sea_allorders.sh build 2048 results/sea_allorders/table_multiple.csv --set 'sea.model="multiple"'
# The path tracer's images are kept in $PT_DIR (default build/sea_allorders_pt, one per case, cap and
# paths-per-pixel count; seed 1, so a kept image is the one a rerun would make) and reused, so a second
# model costs only its own renders. MAXB: the path tracer's cap on scattering vertices (--max-bounces;
# default 1000, the CLI's), always passed and named in the image (pt_mb<MAXB>_...), so images traced under
# the old default cap of 64 (names without it) are never reused; table.csv was traced with MAXB=64.
# JERLOV and DEPTHS (space-separated) pick a subset of the cases, e.g. JERLOV="II III" DEPTHS="5 1000".
# SCENE_SET: --set arguments for both renderers (the scene itself, e.g. SCENE_SET='--set sky.model="preetham"'),
# with SCENE_TAG naming the path tracer's kept images for it (required with SCENE_SET).
# Columns: image-mean luminance (0.2126 R + 0.7152 G + 0.0722 B of linear sensor RGB) of the model and
# of the path tracer, the standard error of the path tracer's mean (from its per-pixel standard-error
# image), their ratio, per-pixel rel. L2 and RMSE (8-bit levels, `seasim compare`), the model's kernel
# ms (report.json's kernel_ms_total) and the path tracer's wall ms; then the same ratio over the far
# half of the image (top 27 rows: the distant water, 45–65° from the nadir) and the near half (bottom
# 27 rows, 25–45°), each with the path tracer's standard error of that ratio.
set -eu
B=${1:-build}
SPP=${2:-2048}
OUT=${3:-results/sea_allorders/table.csv}
[ $# -ge 3 ] && shift 3 || shift $#
PT_DIR=${PT_DIR:-$B/sea_allorders_pt}
SCENE_SET=${SCENE_SET:-}
SCENE_TAG=${SCENE_TAG:-}
if [ -n "$SCENE_SET" ] && [ -z "$SCENE_TAG" ]; then echo "sea_allorders.sh: SCENE_SET needs a SCENE_TAG" >&2; exit 2; fi
MAXB=${MAXB:-1000}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
export POCL_CACHE_DIR="$B/pocl-cache" SEASIM_CACHE_DIR="$B/seasim-cache"
mkdir -p "$PT_DIR" "$(dirname "$OUT")"
W=96
H=54
HALF=$((H / 2))
sed -e 's/^position = .*/position = [0.0, 5.0, 0.0]/' -e 's/^look_at = .*/look_at = [0.0, 0.0, -5.0]/' \
    -e "s/^width = .*/width = $W/" -e "s/^height = .*/height = $H/" scenes/flat_sea.toml > "$TMP/sea.toml"

# Mean luminance of an image region ("WxH+X+Y"), by oiiotool (weights scaled by 1e4 for its 6 digits).
lum() {
  oiiotool "$1" --cut "$2" --chsum:weight=2126,7152,722 --printstats | awk '/Stats Avg/ { printf "%.6g", $3 / 1e4 }'
}
# Standard error of a region's mean luminance from the per-pixel standard-error image: per pixel the
# channels' errors are added with the luminance weights (as if fully correlated: an upper bound),
# then sqrt(mean(se²) / pixels).
lum_se() {
  n=$(echo "$2" | awk -Fx '{ split($2, a, "+"); print $1 * a[1] }')
  oiiotool "$1" --cut "$2" --chsum:weight=2126,7152,722 --powc 2 --printstats |
    awk -v n="$n" '/Stats Avg/ { printf "%.4g", sqrt($3 / n) / 1e4 }'
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.4f", (b > 0 ? a / b : 0) }'; }
ratio_se() { awk -v a="$1" -v b="$2" -v s="$3" 'BEGIN { printf "%.4f", (b > 0 ? a / b * s / b : 0) }'; }

ALL="${W}x${H}+0+0"
FAR="${W}x${HALF}+0+0"
NEAR="${W}x$((H - HALF))+0+$HALF"
echo "jerlov,bottom_m,model_lum,pt_lum,pt_lum_se,ratio,rel_l2,rmse_8bit,model_ms,pt_ms,ratio_far,ratio_far_se,ratio_near,ratio_near_se" > "$OUT"
for j in ${JERLOV:-I IB II III 3C}; do
  for d in ${DEPTHS:-2 5 10 20 1000}; do
    set_case="--set water.jerlov=\"$j\" --set bottom.depth=$d $SCENE_SET"
    pt="$PT_DIR/pt_mb${MAXB}${SCENE_TAG:+_$SCENE_TAG}_${j}_${d}_${SPP}.exr"
    pt_ms_file="${pt%.exr}.ms"
    if [ ! -f "$pt" ] || [ ! -f "$pt_ms_file" ]; then
      t0=$(date +%s%N)
      eval "\"$B/seasim\" reference \"$TMP/sea.toml\" $set_case --all-orders --max-bounces $MAXB --steps $SPP --seed 1 -o \"$TMP/pt.exr\"" \
        > /dev/null 2>&1
      t1=$(date +%s%N)
      mv "$TMP/pt.exr" "$pt"
      mv "$TMP/pt.stderr.exr" "${pt%.exr}.stderr.exr"
      echo $(( (t1 - t0) / 1000000 )) > "$pt_ms_file"
    fi
    eval "\"$B/seasim\" render \"$TMP/sea.toml\" $set_case \"\$@\" -o \"$TMP/model\"" > /dev/null
    model="$TMP/model/image.exr"
    model_ms=$(awk -F': ' '/"kernel_ms_total"/ { sub(",", "", $2); printf "%.2f", $2 }' "$TMP/model/report.json")
    cmp=$("$B/seasim" compare "$model" "$pt")
    v() { echo "$cmp" | awk -v k="$1" '$1 == k { print $2 }'; }
    se="${pt%.exr}.stderr.exr"
    m_all=$(lum "$model" "$ALL"); p_all=$(lum "$pt" "$ALL"); s_all=$(lum_se "$se" "$ALL")
    m_far=$(lum "$model" "$FAR"); p_far=$(lum "$pt" "$FAR"); s_far=$(lum_se "$se" "$FAR")
    m_near=$(lum "$model" "$NEAR"); p_near=$(lum "$pt" "$NEAR"); s_near=$(lum_se "$se" "$NEAR")
    echo "$j,$d,$m_all,$p_all,$s_all,$(ratio "$m_all" "$p_all"),$(v rel_l2),$(v rmse_8bit),$model_ms,$(cat "$pt_ms_file"),$(ratio "$m_far" "$p_far"),$(ratio_se "$m_far" "$p_far" "$s_far"),$(ratio "$m_near" "$p_near"),$(ratio_se "$m_near" "$p_near" "$s_near")" >> "$OUT"
  done
done
cat "$OUT"
