#!/bin/bash
# preview_levels.sh — the live preview's frame times and quality levels (results/BENCHMARKS.md
# "Live preview"). For each example scene at 640x360 under Xvfb, through the real window:
#   level k (Q preset, k = 0..3): median ms of the frames while the camera orbits (every frame moves
#     the view, so the passes that depend on the camera run again), and the RMS error of the window's
#     screenshot against level 3's, in 8-bit levels (oiiotool --diff; levels 0 and 1 are rendered
#     smaller and scaled up by the window, which is part of their error);
#   budget: the same orbit with the automatic choice (--budget-ms, default 40): levels shown, median ms.
# Prints a markdown table. Usage: tests/perf/preview_levels.sh [scene.toml ...]   (default scenes/*.toml)
# Env: B (binary, build/seasim), DEVICE (pocl), SIZE (640x360), MOVES (orbit frames per level, 5),
# BUDGET_MOVES (orbit frames of the budget run, 16: the budget forgets a time after 8 frames), BUDGET (40, the
# preview's default).
set -euo pipefail
B=${B:-build/seasim}
DEVICE=${DEVICE:-pocl}
SIZE=${SIZE:-640x360}
MOVES=${MOVES:-5}
BUDGET_MOVES=${BUDGET_MOVES:-16}
BUDGET=${BUDGET:-40}
T=$(mktemp -d /tmp/seasim_preview_levels.XXXXXX)
trap 'rm -rf "$T"' EXIT
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/*.toml)

# median of the "N ms" of frames [first, last] in a preview log
median_ms() {
  awk -v a="$2" -v b="$3" '/^frame /{ f = $2 + 0; if (f >= a && f <= b) { for (i = 1; i < NF; i++) if ($(i+1) == "ms") print $i } }' "$1" |
    sort -g | awk '{ v[NR] = $1 } END { if (NR) print v[int((NR + 1) / 2)]; else print "-" }'
}
rms8() { { oiiotool "$1" "$2" --diff 2>/dev/null || true; } | awk '/RMS error/ { r = $4 } END { printf "%.2f", r * 255 }'; }
run() {  # log, screenshot, frames, script
  xvfb-run -a -s '-screen 0 1024x768x24 -nolisten tcp' "$B" preview "$SCENE" --device "$DEVICE" --size "$SIZE" \
    --frames "$3" --script "$4" --budget-ms "$BUDGET" --screenshot "$2" > "$1" 2>&1
}

echo "| scene | level 0 ms | level 1 ms | level 2 ms | level 3 (full) ms | budget ${BUDGET} ms: level of moving frames 1..$((BUDGET_MOVES - 1)) | budget: median ms | error of level 0 / 1 / 2 vs 3 (8-bit RMS) |"
echo "|---|---|---|---|---|---|---|---|"
for SCENE in "${scenes[@]}"; do
  name=$(basename "$SCENE" .toml)
  ms=()
  for k in 0 1 2 3; do
    presses=$((k + 1))
    if ! run "$T/$name.$k.log" "$T/$name.$k.png" $((presses + MOVES)) "Q*$presses ORBIT:3,0*$MOVES"; then
      echo "| $name | failed: $(tail -1 "$T/$name.$k.log") |||||||"
      continue 2
    fi
    # the first orbit frame after the preset is left out (it may still set passes up)
    ms+=("$(median_ms "$T/$name.$k.log" $((presses + 1)) $((presses + MOVES - 1)))")
  done
  run "$T/$name.b.log" "$T/$name.b.png" $((BUDGET_MOVES + 1)) "ORBIT:3,0*$BUDGET_MOVES" || true
  levels=$(awk -v n="$BUDGET_MOVES" '/^frame /{ f = $2 + 0; if (f >= 1 && f < n) for (i = 1; i < NF; i++) if ($i == "level") printf "%s", substr($(i+1), 1, 1) }' "$T/$name.b.log")
  budget_ms=$(median_ms "$T/$name.b.log" 1 $((BUDGET_MOVES - 1)))
  err="$(rms8 "$T/$name.0.png" "$T/$name.3.png") / $(rms8 "$T/$name.1.png" "$T/$name.3.png") / $(rms8 "$T/$name.2.png" "$T/$name.3.png")"
  echo "| $name | ${ms[0]} | ${ms[1]} | ${ms[2]} | ${ms[3]} | ${levels% } | $budget_ms | $err |"
done
