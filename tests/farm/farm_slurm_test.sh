#!/usr/bin/env bash
# farm_slurm_test.sh — `seasim farm` on a real Slurm scheduler (ctest `farm.slurm`).
#
#   tests/farm/farm_slurm_test.sh SEASIM_BINARY WORK_DIR
#
# Starts a private single-node Slurm (tests/farm/slurm_localhost.sh, state under WORK_DIR), then:
#  A. submits a real 4-task array of a small 8-item job plus its merge, with one task SIGKILLed in
#     the middle of a frame (SEASIM_TEST_KILL_MID_ITEM) and one item held until released
#     (SEASIM_TEST_HOLD_ITEM, so a sample sees it running however fast the items render); samples
#     `seasim farm status` while the array runs; checks the task retried, the merge passed, and
#     every output equals a single-machine `seasim run` of the same job (PNG and NPY byte for byte, EXR pixels and
#     channels by idiff: its header's DateTime differs), and that nothing half-written was recorded;
#  B. submits a job with an item that fails for good: the afterok merge is cancelled, the afternotok
#     merge runs and fails naming the missing item.
# Stops every daemon it started, by PID, on any exit. Exit 77 (ctest: skipped) only when the
# daemons cannot be started here (not root); a missing package is a failure (make test installs it).
set -uo pipefail

BIN=$(realpath "$1")
WORK=$(realpath -m "$2")
HERE=$(cd "$(dirname "$0")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
STATE=$WORK/slurm
RUN=$WORK/run
T0=$(date +%s)

log() { printf '[farm test %3ds] %s\n' "$(( $(date +%s) - T0 ))" "$*"; }
fail() { log "FAIL: $*"; exit 1; }

SUBMITTED=()
cleanup() {
  local rc=$?
  if [ ${#SUBMITTED[@]} -gt 0 ]; then scancel "${SUBMITTED[@]}" 2>/dev/null || true; fi
  "$HERE/slurm_localhost.sh" stop "$STATE" || true
  log "exit $rc"
  exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT TERM

for b in slurmctld slurmd sbatch munged idiff; do
  command -v "$b" >/dev/null || fail "$b is not installed: 'make test' installs slurm-wlm, munge and openimageio-tools"
done
rm -rf "$RUN"
mkdir -p "$RUN"
start_rc=0
"$HERE/slurm_localhost.sh" start "$STATE" || start_rc=$?
if [ "$start_rc" = 77 ]; then log "SKIPPED: the Slurm daemons cannot be started here (needs root)"; exit 77; fi
[ "$start_rc" = 0 ] || fail "could not start the local Slurm cluster (logs: $STATE/log)"
export SLURM_CONF=$STATE/slurm.conf
log "slurm up"

# 8 tiny renders of the flat sea at different sun angles, widths 32..60 (so costs differ).
JOB=$RUN/job.toml
{
  printf '[job]\nname = "farmtest"\noutput_dir = "out"\n'
  for i in 0 1 2 3 4 5 6 7; do
    printf '[[render]]\nname = "item%d"\nscene = "%s/scenes/flat_sea.toml"\noutputs = ["exr", "png", "npy"]\n' "$i" "$REPO"
    printf 'overrides = { "camera.width" = %d, "camera.height" = 18, "spectral.count" = 4, "sun.zenith_deg" = %d }\n' \
      $((32 + 4 * i)) $((20 + 5 * i))
  done
} >"$JOB"

"$BIN" run "$JOB" -o "$RUN/single" --device pocl >"$RUN/single.log" 2>&1 || { cat "$RUN/single.log"; fail "single-machine run"; }
log "single-machine run done"

# wait_jobs ID...: until squeue lists none of them, at most 60 s. (All bounds together stay under
# ctest's 300 s TIMEOUT, whose SIGKILL would skip the trap that stops the daemons.)
wait_jobs() {
  local ids; ids=$(IFS=,; echo "$*")
  for _ in $(seq 120); do
    [ -z "$(squeue -h -j "$ids" 2>/dev/null)" ] && return 0
    sleep 0.5
  done
  squeue; fail "jobs $ids not finished after 60 s"
}
# job_state ID: COMPLETED, FAILED, CANCELLED... from the controller's completion log.
job_state() { grep -E "^JobId=$1 " "$STATE/log/jobcomp.log" | tail -1 | sed -E 's/.*JobState=([A-Z_]+).*/\1/'; }
submitted_id() { sed -n "s/^$1=//p" "$2"; }

# ---------------------------------------------------------------- A: kill mid-frame, retry, merge
OUT=$RUN/farm
export SEASIM_TEST_KILL_MID_ITEM="item5:$RUN/item5.killed"
RELEASE=$RUN/item1.release
export SEASIM_TEST_HOLD_ITEM="item1:$RELEASE"
"$BIN" farm slurm "$JOB" --tasks 4 --retries 2 --device pocl -o "$OUT" --submit >"$RUN/submit_a.log" 2>&1 \
  || { cat "$RUN/submit_a.log"; fail "farm slurm --submit"; }
unset SEASIM_TEST_KILL_MID_ITEM SEASIM_TEST_HOLD_ITEM
ARRAY=$(submitted_id array_job_id "$RUN/submit_a.log")
MERGE=$(submitted_id merge_job_id "$RUN/submit_a.log")
MERGE_FAIL=$(submitted_id merge_after_failure_job_id "$RUN/submit_a.log")
SUBMITTED+=("$ARRAY" "$MERGE" "$MERGE_FAIL")
log "A: array $ARRAY, merge $MERGE, merge-after-failure $MERGE_FAIL"

# Sample `farm status` while the array runs: every sample accounts for all 8 items, done never
# goes down, and at least one sample catches a shard running with items left. item1 is held until a
# sample has seen that (on a fast machine the whole array otherwise ends between two samples).
samples=0; saw_running=0; last_done=0
while [ -n "$(squeue -h -j "$ARRAY" 2>/dev/null)" ]; do
  read -r d r f l < <("$BIN" farm status "$JOB" -o "$OUT" | awk '$1 == "all" { print $2, $3, $4, $5 }')
  samples=$((samples + 1))
  [ $((d + r + f + l)) = 8 ] || fail "status sample $samples: done $d + running $r + failed $f + left $l != 8"
  [ "$d" -ge "$last_done" ] || fail "status sample $samples: done went down from $last_done to $d"
  last_done=$d
  if [ "$r" -ge 1 ] && [ "$d" -lt 8 ]; then saw_running=1; touch "$RELEASE"; fi
  [ $(( $(date +%s) - T0 )) -lt 120 ] || fail "array still running 120 s after the test started"
  sleep 0.3
done
log "A: array left the queue; $samples status samples, running seen: $saw_running"
[ "$samples" -ge 1 ] && [ "$saw_running" = 1 ] || fail "no status sample caught a running shard"
wait_jobs "$ARRAY" "$MERGE" "$MERGE_FAIL"
"$BIN" farm status "$JOB" -o "$OUT" | tee "$RUN/status_a_final.txt"
read -r d r f l < <(awk '$1 == "all" { print $2, $3, $4, $5 }' "$RUN/status_a_final.txt")
[ "$d $r $f $l" = "8 0 0 0" ] || fail "final status: done $d running $r failed $f left $l, expected 8 0 0 0"

[ -e "$RUN/item5.killed" ] || fail "the kill hook did not fire"
grep -l "holding item 'item1'" "$OUT"/farm/logs/task-*.log >/dev/null || fail "the hold hook did not fire"
grep -l "killing this process in the middle of item 'item5'" "$OUT"/farm/logs/task-*.log >/dev/null \
  || fail "no task log shows the kill"
grep -h "attempt 2 of 3" "$OUT"/farm/logs/task-*.log | grep -q . || fail "the killed task was not retried"
grep -h "removing stale lock" "$OUT"/farm/logs/task-*.log | grep -q . || fail "the retry did not take over the dead run's lock"
# The item killed between its files was not counted done: the retry rendered it again.
KLOG=$(grep -l "killing this process in the middle of item 'item5'" "$OUT"/farm/logs/task-*.log)
grep -q "item5: done" "$KLOG" || fail "the retry did not render item5 again"
! grep -q "item5: finished earlier" "$KLOG" || fail "item5, killed mid-frame, was taken as finished"
[ "$(job_state "$MERGE")" = COMPLETED ] || fail "merge job $MERGE: $(job_state "$MERGE")"
[ "$(job_state "$MERGE_FAIL")" = CANCELLED ] || fail "merge-after-failure job $MERGE_FAIL ran: $(job_state "$MERGE_FAIL")"
grep -q "all 8 items present with intact files" "$OUT"/farm/logs/merge-"$MERGE".log || fail "merge log"
grep -q '"complete": true' "$OUT/farm/report.json" || fail "farm/report.json is not complete"
[ "$(grep -c '<img ' "$OUT/farm/contact_sheet.html")" = 8 ] || fail "contact sheet does not show 8 images"
[ -z "$(find "$OUT" -name '.*.tmp-*')" ] || fail "temporary files left: $(find "$OUT" -name '.*.tmp-*')"
for i in 0 1 2 3 4 5 6 7; do
  a=$RUN/single/item$i b=$OUT/item$i
  cmp -s "$a/image.npy" "$b/image.npy" || fail "item$i: image.npy differs from the single-machine run"
  cmp -s "$a/image.png" "$b/image.png" || fail "item$i: image.png differs from the single-machine run"
  idiff -q -fail 0 -warn 0 "$a/image.exr" "$b/image.exr" >/dev/null || fail "item$i: image.exr pixels differ"
done
log "A: outputs of the farm (with a killed task) equal the single-machine run"

# ------------------------------------------------------------- B: an item that fails for good
JOB_B=$RUN/job_bad.toml
sed 's/^name = "farmtest"/name = "farmbad"/' "$JOB" >"$JOB_B"
printf '[[render]]\nname = "bad_item"\nscene = "%s/scenes/flat_sea.toml"\nreference = "%s"\n' \
  "$REPO" "$RUN/single/item7/image.exr" >>"$JOB_B"   # a 60x18 reference for a 480x270 render: fails each time
printf 'overrides = { "spectral.count" = 4 }\n' >>"$JOB_B"
OUT_B=$RUN/farm_bad
"$BIN" farm slurm "$JOB_B" --tasks 4 --retries 1 --device pocl -o "$OUT_B" --submit >"$RUN/submit_b.log" 2>&1 \
  || { cat "$RUN/submit_b.log"; fail "farm slurm --submit (B)"; }
ARRAY=$(submitted_id array_job_id "$RUN/submit_b.log")
MERGE=$(submitted_id merge_job_id "$RUN/submit_b.log")
MERGE_FAIL=$(submitted_id merge_after_failure_job_id "$RUN/submit_b.log")
SUBMITTED+=("$ARRAY" "$MERGE" "$MERGE_FAIL")
wait_jobs "$ARRAY" "$MERGE" "$MERGE_FAIL"
log "B: array $ARRAY done; merge $(job_state "$MERGE"), merge-after-failure $(job_state "$MERGE_FAIL")"
[ "$(job_state "$MERGE")" = CANCELLED ] || fail "the afterok merge should be cancelled: $(job_state "$MERGE")"
[ "$(job_state "$MERGE_FAIL")" = FAILED ] || fail "the afternotok merge should fail: $(job_state "$MERGE_FAIL")"
MLOG=$OUT_B/farm/logs/merge-$MERGE_FAIL.log
grep -q "1 of 9 items are missing" "$MLOG" || { cat "$MLOG"; fail "merge message"; }
grep -q "bad_item (failed: .*reference" "$MLOG" || { cat "$MLOG"; fail "merge does not name the failed item"; }
grep -h "failed 2 times; giving up" "$OUT_B"/farm/logs/task-*.log | grep -q . || fail "the failing task did not retry once"
grep -q '"complete": false' "$OUT_B/farm/report.json" || fail "farm/report.json claims completeness"
[ ! -e "$OUT_B/bad_item/report.json" ] || fail "the failed item has a report.json"
log "B: a task failing for good: merge fails naming bad_item"
log "PASS"
