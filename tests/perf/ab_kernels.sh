#!/bin/sh
# ab_kernels.sh — one seasim binary with several kernel folders (SEASIM_KERNEL_DIR) and maths
# settings, interleaved round by round so the machine's load hits every variant alike: the seabed
# frame (all passes, its 16 bands, `seasim bench`) and seashore's second order (`bench --sea-maps 64`,
# the scattering maps and the accumulation, OpenCL profiling ms, median of 3 after a warm-up).
# Usage: tests/perf/ab_kernels.sh NAME=KERNEL_DIR=FAST_MATH ...   (FAST_MATH true|false; ROUNDS=2)
B=${B:-build/seasim}
ROUNDS=${ROUNDS:-2}
r=1
while [ $r -le "$ROUNDS" ]; do
  for v in "$@"; do
    name=${v%%=*}
    rest=${v#*=}
    dir=${rest%=*}
    fm=${rest##*=}
    t=$(SEASIM_KERNEL_DIR=$dir $B bench --scene scenes/seabed.toml --wavelengths 16 --repeat 3 \
          --set quality.fast_math=$fm | grep "^n =" | awk '{print $4}')
    s=$(SEASIM_KERNEL_DIR=$dir $B bench --scene scenes/seashore.toml --sea-maps 64 --repeat 3 \
          --set quality.fast_math=$fm | grep "^sea second" |
        sed 's/.*scattering maps \([0-9.]*\) ms, accumulation \([0-9.]*\) ms, total \([0-9.]*\) ms.*/maps \1 accum \2 total \3/')
    echo "round $r  $name  fast_math=$fm  seabed_frame_ms $t  seashore_second_ms $s"
  done
  r=$((r + 1))
done
