#!/usr/bin/env bash
# slurm_localhost.sh — a private single-node Slurm cluster on localhost for the farm tests.
#
#   tests/farm/slurm_localhost.sh start STATE_DIR   munged + slurmctld + slurmd, all under STATE_DIR
#   tests/farm/slurm_localhost.sh stop  STATE_DIR   stops exactly the daemons start recorded, by PID
#   tests/farm/slurm_localhost.sh env   STATE_DIR   prints `export SLURM_CONF=...` for the clients
#
# Everything is private to STATE_DIR (its own munge socket and key, slurm.conf, spool, state, logs,
# PID files) and the ports are derived from STATE_DIR's path, so it neither touches nor needs the
# machine's /etc/slurm, /etc/munge or a running munged/slurmctld, and two build folders can run
# their tests at the same time. Needs root (slurmd starts jobs as their users) and the Debian
# packages slurmctld, slurmd, slurm-client and munge (the Makefile's `test` target installs them).
# Exit codes of start: 0 up, 1 failed, 77 cannot run here (not root / no binaries): the caller skips.
# Based on ../shared research notes (Slurm 22.05 on Debian 12; no cgroups, no slurmdbd, no systemd).
set -euo pipefail

cmd=${1:-}
STATE=${2:-}
[ -n "$cmd" ] && [ -n "$STATE" ] || { echo "usage: $0 start|stop|env STATE_DIR" >&2; exit 2; }
STATE=$(realpath -m "$STATE")
NODE=$(hostname -s)
# Two ports from the folder's path (10000..59998), so parallel build folders do not collide.
SUM=$(printf '%s' "$STATE" | cksum | cut -d' ' -f1)
CTLD_PORT=$((10000 + (SUM % 25000) * 2))
SLURMD_PORT=$((CTLD_PORT + 1))

log() { printf '[slurm_localhost %(%H:%M:%S)T] %s\n' -1 "$*" >&2; }

# alive NAME: the PID we recorded for NAME runs and is that program (not a reused PID), not a zombie.
alive() {
  local f=$STATE/pids/$1.pid pid
  [ -s "$f" ] || return 1
  pid=$(cat "$f")
  [ -d "/proc/$pid" ] || return 1
  [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$1" ] || return 1
  ! grep -q '^State:[[:space:]]*Z' "/proc/$pid/status" 2>/dev/null
}

write_conf() {
  cat >"$STATE/slurm.conf" <<CONF
# Written by tests/farm/slurm_localhost.sh: a private single-node cluster for the farm tests.
ClusterName=seasimtest
SlurmctldHost=${NODE}(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$STATE/munge/munge.socket
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$STATE/log/jobcomp.log
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1,bf_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
StateSaveLocation=$STATE/ctld
SlurmdSpoolDir=$STATE/slurmd
SlurmctldPidFile=$STATE/run/slurmctld.pid
SlurmdPidFile=$STATE/run/slurmd.pid
SlurmctldLogFile=$STATE/log/slurmctld.log
SlurmdLogFile=$STATE/log/slurmd.log
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmctldTimeout=30
SlurmdTimeout=30
MinJobAge=600
KillWait=2
NodeName=${NODE} NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=1024 State=UNKNOWN
PartitionName=debug Nodes=${NODE} Default=YES MaxTime=INFINITE State=UP
CONF
}

# wait_pidfile FILE NAME: up to 10 s for a daemon to write its PID file; records it as ours.
wait_pidfile() {
  local f=$1 name=$2
  for _ in $(seq 100); do [ -s "$f" ] && break; sleep 0.1; done
  if [ ! -s "$f" ]; then
    log "$name did not start; its log: $STATE/log/$name.log"
    tail -5 "$STATE/log/$name.log" >&2 || true
    if grep -q "No filesystem mounted on /sys/fs/cgroup" "$STATE/log/$name.log" 2>/dev/null; then
      log "$name needs the cgroup file system at /sys/fs/cgroup (in a chroot: mount --rbind /sys)"
    fi
    return 1
  fi
  cp "$f" "$STATE/pids/$name.pid"
  alive "$name" || { log "$name exited right after starting"; tail -5 "$STATE/log/$name.log" >&2 || true; return 1; }
}

do_start() {
  if [ "$(id -u)" != 0 ]; then log "not root: cannot run slurmd/munged here"; exit 77; fi
  for b in munged munge slurmctld slurmd sbatch squeue scontrol; do
    command -v "$b" >/dev/null || { log "$b is not installed (make test installs slurm-wlm and munge)"; exit 77; }
  done
  mkdir -p "$STATE"/{munge,ctld,slurmd,log,run,pids}
  chmod 755 "$STATE"; chmod 700 "$STATE/munge"
  export SLURM_CONF=$STATE/slurm.conf
  write_conf

  if ! alive munged; then
    [ -s "$STATE/munge/munge.key" ] || { dd if=/dev/urandom of="$STATE/munge/munge.key" bs=1024 count=1 status=none; chmod 400 "$STATE/munge/munge.key"; }
    rm -f "$STATE/munge/munged.pid"
    # --force: munged refuses to run as root without it; the socket and key are private to STATE.
    munged --force --socket="$STATE/munge/munge.socket" --key-file="$STATE/munge/munge.key" \
      --pid-file="$STATE/munge/munged.pid" --log-file="$STATE/log/munged.log" --seed-file="$STATE/munge/munged.seed"
    wait_pidfile "$STATE/munge/munged.pid" munged
  fi
  munge -S "$STATE/munge/munge.socket" -n | unmunge -S "$STATE/munge/munge.socket" >/dev/null \
    || { log "munge self-test failed"; return 1; }

  if ! alive slurmctld; then
    rm -f "$STATE/run/slurmctld.pid"
    slurmctld -f "$SLURM_CONF"
    wait_pidfile "$STATE/run/slurmctld.pid" slurmctld
  fi
  if ! alive slurmd; then
    rm -f "$STATE/run/slurmd.pid"
    slurmd -f "$SLURM_CONF" -N "$NODE"
    wait_pidfile "$STATE/run/slurmd.pid" slurmd
  fi
  local st=""
  for i in $(seq 60); do
    st=$(sinfo -h -n "$NODE" -o '%T' 2>/dev/null || true)
    case "$st" in
      idle*|mixed*|allocated*) log "node $NODE is $st (controller port $CTLD_PORT)"; return 0;;
      down*|drain*) scontrol update NodeName="$NODE" State=RESUME >/dev/null 2>&1 || true;;
    esac
    sleep 0.5
  done
  log "node $NODE not idle after 30 s (state: ${st:-none}); logs in $STATE/log"
  return 1
}

do_stop() {
  local name pid
  for name in slurmd slurmctld munged; do
    if alive "$name"; then
      pid=$(cat "$STATE/pids/$name.pid")
      log "stopping $name (pid $pid)"
      kill -TERM "$pid" 2>/dev/null || true
      for _ in $(seq 100); do alive "$name" || break; sleep 0.1; done
      if alive "$name"; then log "$name still running: SIGKILL"; kill -KILL "$pid" 2>/dev/null || true; fi
    fi
    rm -f "$STATE/pids/$name.pid"
  done
}

case "$cmd" in
  start) do_start ;;
  stop) do_stop ;;
  env) echo "export SLURM_CONF=$STATE/slurm.conf" ;;
  *) echo "usage: $0 start|stop|env STATE_DIR" >&2; exit 2 ;;
esac
