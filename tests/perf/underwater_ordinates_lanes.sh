#!/bin/sh
# underwater_ordinates_lanes.sh — kd_multiple's time per band for underwater.model = "thesis" and
# "ordinates" (the discrete-ordinates model on the band lanes must cost <= 2x the thesis per band),
# round by round interleaved so that the shared machine's load falls on every variant alike:
#   seasim bench --scene scenes/seabed.toml --wavelengths 16,64 --repeat 3 --set underwater.caustics="none"
# per variant (ordinates_no_spread: the discrete-ordinates model without the water's point-spread, whose forward
# light kd_multiple then does not keep apart; optionally also BEFORE, another binary's discrete-ordinates model, e.g. a copy of main's), and
# per band = (kd at n = 64 - kd at n = 16) / 48, the fixed per-pixel cost cancelling (N1, N2 change the
# two band counts: a wider gap measures the per-band cost above the machine's noise).
# Usage: tests/perf/underwater_ordinates_lanes.sh [BEFORE_BINARY]   (ROUNDS=2, SEASIM=build/seasim, N1=16, N2=64)
ROUNDS=${ROUNDS:-2}
N1=${N1:-16}
N2=${N2:-64}
SEASIM=${SEASIM:-build/seasim}
BEFORE=$1
kd_ms() {  # $1 binary, then --set overrides; prints "kd16 kd64"
  bin=$1
  shift
  "$bin" bench --scene scenes/seabed.toml --wavelengths "$N1,$N2" --repeat 3 --set underwater.caustics=\"none\" "$@" 2>&1 |
    sed -n 's/.*kd \([0-9.]*\) ms.*/\1/p' | tr '\n' ' '
}
echo "round,variant,kd_ms_n$N1,kd_ms_n$N2,ms_per_band"
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for v in thesis ordinates ordinates_no_spread before; do
    case $v in
    thesis) t=$(kd_ms "$SEASIM" --set underwater.model=\"thesis\") ;;
    ordinates) t=$(kd_ms "$SEASIM" --set underwater.model=\"discrete_ordinates\") ;;
    ordinates_no_spread) t=$(kd_ms "$SEASIM" --set underwater.model=\"discrete_ordinates\" --set underwater.point_spread=false) ;;
    before) [ -n "$BEFORE" ] || continue; t=$(kd_ms "$BEFORE" --set underwater.model=\"discrete_ordinates\") ;;
    esac
    echo "$t" | awk -v r="$r" -v v="$v" -v dn=$((N2 - N1)) '{printf "%d,%s,%.2f,%.2f,%.4f\n", r, v, $1, $2, ($2 - $1) / dn}'
  done
  r=$((r + 1))
done
