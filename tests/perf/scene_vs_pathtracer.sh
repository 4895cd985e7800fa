#!/bin/sh
# scene_vs_pathtracer.sh — a shipped scene as it is (its sky, bottom, objects), each fast model
# (`seasim render`, the model key pinned) against the path tracer (`seasim reference`, all orders, the
# same sky and floor): image-mean luminance ratios over the whole image and its top and bottom halves,
# with the path tracer's standard error of each ratio, and `seasim compare`'s rel. L2.
# Usage: tests/perf/scene_vs_pathtracer.sh SCENE [width height paths] [--set ...]
#   e.g. tests/perf/scene_vs_pathtracer.sh scenes/snells_window.toml 160 90 4096
#        KEY=sea.model MODELS="multiple paper" REFERENCE=--all-orders \
#          tests/perf/scene_vs_pathtracer.sh scenes/seashore.toml 160 90 4096
# KEY, MODELS: the model key and its values (default underwater.model: discrete_ordinates thesis);
# REFERENCE: more `seasim reference` flags (--all-orders for the sea seen from above).
set -eu
SCENE=$1
W=${2:-160}
H=${3:-90}
SPP=${4:-4096}
[ $# -ge 4 ] && shift 4 || shift $#
B=${B:-build/seasim}
KEY=${KEY:-underwater.model}
MODELS=${MODELS:-discrete_ordinates thesis}
REFERENCE=${REFERENCE:-}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
SIZE="--set camera.width=$W --set camera.height=$H"
lum() { oiiotool "$1" --cut "$2" --chsum:weight=2126,7152,722 --printstats | awk '/Stats Avg/ { printf "%.6g", $3 / 1e4 }'; }
lum_se() {
  n=$(echo "$2" | awk -Fx '{ split($2, a, "+"); print $1 * a[1] }')
  oiiotool "$1" --cut "$2" --chsum:weight=2126,7152,722 --powc 2 --printstats |
    awk -v n="$n" '/Stats Avg/ { printf "%.4g", sqrt($3 / n) / 1e4 }'
}
HALF=$((H / 2))
ALL="${W}x${H}+0+0"
TOP="${W}x${HALF}+0+0"
BOT="${W}x$((H - HALF))+0+$HALF"
"$B" reference "$SCENE" $SIZE "$@" $REFERENCE --steps "$SPP" --seed 1 -o "$TMP/pt.exr" > /dev/null 2>&1
echo "model,region,model_lum,pt_lum,ratio,ratio_se,rel_l2"
for model in $MODELS; do
  "$B" render "$SCENE" $SIZE "$@" --set "$KEY=\"$model\"" -o "$TMP/$model" > /dev/null
  rel=$("$B" compare "$TMP/$model/image.exr" "$TMP/pt.exr" 2>/dev/null | awk '$1 == "rel_l2" { print $2 }')
  for region in all:$ALL top:$TOP bottom:$BOT; do
    name=${region%%:*}
    box=${region#*:}
    m=$(lum "$TMP/$model/image.exr" "$box")
    p=$(lum "$TMP/pt.exr" "$box")
    s=$(lum_se "$TMP/pt.stderr.exr" "$box")
    awk -v mo="$model" -v r="$name" -v m="$m" -v p="$p" -v s="$s" -v l="$rel" \
      'BEGIN { printf "%s,%s,%s,%s,%.4f,%.4f,%s\n", mo, r, m, p, m / p, m / p * s / p, l }'
  done
done
