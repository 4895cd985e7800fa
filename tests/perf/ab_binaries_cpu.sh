#!/bin/sh
# ab_binaries_cpu.sh — the seabed frame in process CPU seconds (user + system, PoCL's threads included)
# for several seasim binaries (e.g. a copy of main's and this tree's), interleaved round by round, at
# several band counts: per variant, round and n,
#   frame_cpu_s = [CPU of `seasim run` on a job of 3 seabed renders - CPU of a job of 1] / 2
# (start-up, program builds and image writes cancel in the difference; the renders differ by
# 1/100 degree of sun azimuth, since a job renders identical items once). The machine's other jobs
# disturb CPU seconds far less than wall or profiling time.
# Usage: tests/perf/ab_binaries_cpu.sh NAME=BINARY[=KERNEL_DIR] ...   (ROUNDS=2, BANDS="16 256")
ROUNDS=${ROUNDS:-2}
BANDS=${BANDS:-16 256}
SCENE=${SCENE:-$PWD/scenes/seabed.toml}
T=${T:-/tmp/seasim_ab_binaries}
mkdir -p "$T"
job() {  # job file of $1 renders at $2 bands
  f="$T/job_$1_$2.toml"
  printf '[job]\nname = "ab"\noutput_dir = "out"\n' > "$f"
  i=0
  while [ $i -lt "$1" ]; do
    # the sun moved by i/100 degree: renders of one scene must differ, or the job renders it once
    printf '[[render]]\nname = "r%d"\nscene = "%s"\noutputs = ["exr"]\noverrides = { "spectral.count" = %s, "sun.azimuth_deg" = 60.0%d }\n' \
      $i "$SCENE" "$2" $i >> "$f"
    i=$((i + 1))
  done
  echo "$f"
}
cpu() { /usr/bin/time -f "%U %S" "$@" 2>&1 >/dev/null | tail -1 | awk '{print $1 + $2}'; }
r=1
while [ $r -le "$ROUNDS" ]; do
  for n in $BANDS; do
    for v in "$@"; do
      name=${v%%=*}; rest=${v#*=}; bin=${rest%%=*}; dir=${rest#"$bin"}; dir=${dir#=}
      if [ -n "$dir" ]; then export SEASIM_KERNEL_DIR=$dir; else unset SEASIM_KERNEL_DIR; fi
      j1=$(job 1 "$n"); j3=$(job 3 "$n")
      rm -rf "$T/out"; $bin run "$j1" > /dev/null 2>&1  # warm-up: fills the kernel caches
      rm -rf "$T/out"; a1=$(cpu $bin run "$j1")
      rm -rf "$T/out"; a3=$(cpu $bin run "$j3")
      echo "$r $name $n" | awk -v a1="$a1" -v a3="$a3" \
        '{printf "round %s  %-8s n = %4s  frame_cpu_s %.3f\n", $1, $2, $3, (a3 - a1) / 2}'
    done
  done
  r=$((r + 1))
done
