#!/bin/sh
# ab_cpu.sh — like ab_kernels.sh, but in process CPU seconds (user + system of the whole process,
# PoCL's threads included), which the other jobs on a shared machine disturb far less than wall or
# profiling time. Per variant and round:
#   seabed frame      = [CPU of `seasim run` on a job of 3 seabed renders - CPU of a job of 1] / 2
#   seashore 2nd order = [CPU of `bench --sea-maps 64 --repeat 5` - CPU of `--repeat 1`] / 4
# (start-up, kernel cache loads, depth tables and image writes cancel in the differences). Each render
# of a job has its own surface.time (the caustics' time: same work, another image): a job's renderer
# skips a render whose settings equal the one before, which would make the frame cost nothing.
# Usage: tests/perf/ab_cpu.sh NAME=KERNEL_DIR=FAST_MATH ...   (ROUNDS=3; KERNEL_DIR "-": the binary's own)
B=${B:-build/seasim}
ROUNDS=${ROUNDS:-3}
T=${T:-/tmp/seasim_ab_cpu}
mkdir -p "$T"
job() {  # job file of $1 seabed renders with fast_math=$2
  f="$T/job_$1_$2.toml"
  printf '[job]\nname = "ab"\noutput_dir = "out"\n' > "$f"
  i=0
  while [ $i -lt "$1" ]; do
    printf '[[render]]\nname = "r%d"\nscene = "%s/scenes/seabed.toml"\noutputs = ["exr"]\noverrides = { "quality.fast_math" = %s, "surface.time" = %d.5 }\n' \
      $i "$PWD" "$2" $i >> "$f"
    i=$((i + 1))
  done
  echo "$f"
}
cpu() { /usr/bin/time -f "%U %S" "$@" 2>&1 >/dev/null | tail -1 | awk '{print $1 + $2}'; }
r=1
while [ $r -le "$ROUNDS" ]; do
  for v in "$@"; do
    name=${v%%=*}; rest=${v#*=}; dir=${rest%=*}; fm=${rest##*=}
    if [ "$dir" = "-" ]; then unset SEASIM_KERNEL_DIR; else export SEASIM_KERNEL_DIR=$dir; fi  # -: embedded
    j1=$(job 1 "$fm"); j3=$(job 3 "$fm")
    rm -rf "$T/out"; $B run "$j1" > /dev/null 2>&1  # warm-up: fills the kernel caches for this variant
    rm -rf "$T/out"; a1=$(cpu $B run "$j1")
    rm -rf "$T/out"; a3=$(cpu $B run "$j3")
    s1=$(cpu $B bench --scene scenes/seashore.toml --sea-maps 64 --repeat 1 --set quality.fast_math=$fm)
    s5=$(cpu $B bench --scene scenes/seashore.toml --sea-maps 64 --repeat 5 --set quality.fast_math=$fm)
    echo "$r $name $fm" | awk -v a1="$a1" -v a3="$a3" -v s1="$s1" -v s5="$s5" \
      '{printf "round %s  %-10s fast_math=%-5s  seabed_frame_cpu_s %.3f  seashore_second_cpu_s %.3f\n", $1, $2, $3, (a3 - a1) / 2, (s5 - s1) / 4}'
  done
  r=$((r + 1))
done
