#!/bin/sh
# pocl_work_group_specialisation.sh — PoCL's work-group specialisation against the generic work-group
# function seasim asks for (POCL_WORK_GROUP_SPECIALIZATION=0, host/device/kernel_cache.h
# usePoclGenericWorkGroups): every shipped scene's kernel ms per frame (`seasim bench`, the median of
# REPEAT frames after a warm-up), both ways in turn, ROUNDS rounds, warm caches. Prints a Markdown table.
# Usage: tests/perf/pocl_work_group_specialisation.sh [scene.toml ...]   (default: scenes/*.toml; B=build/seasim,
#        SIZE=320x180, ROUNDS=2, REPEAT=5)
B=${B:-build/seasim}
SIZE=${SIZE:-320x180}
ROUNDS=${ROUNDS:-2}
REPEAT=${REPEAT:-5}
W=${SIZE%x*}
H=${SIZE#*x}
[ $# -gt 0 ] || set -- scenes/*.toml
total() {
  POCL_WORK_GROUP_SPECIALIZATION=$1 $B bench --scene "$2" --devices pocl --repeat "$REPEAT" \
    --set camera.width="$W" --set camera.height="$H" 2>/dev/null | awk '$1 == "total" { print $2 }'
}
echo "| scene | specialised ms, rounds 1..$ROUNDS | generic ms | generic / specialised (medians) |"
echo "|---|---|---|---:|"
for S in "$@"; do
  spec="" gen=""
  for r in $(seq "$ROUNDS"); do
    spec="$spec $(total 1 "$S")"
    gen="$gen $(total 0 "$S")"
  done
  ratio=$(echo "$spec|$gen" | awk -F'|' '
    function median(s,   a, n, i, j, t) { n = split(s, a, " "); for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++)
      if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }; return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2 }
    { printf "%.2f", median($2) / median($1) }')
  echo "| $(basename "$S" .toml) |$(echo $spec | sed 's/ /, /g; s/^/ /') |$(echo $gen | sed 's/ /, /g; s/^/ /') | $ratio |"
done
