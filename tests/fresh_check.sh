#!/usr/bin/env bash
# `make fresh-check`: the README's two commands on a bare Debian 12, as a new user meets them.
#
# 1. mmdebstrap builds a minimal bookworm root (variant apt, plus make) from the mirror this
#    machine's apt already uses. Downloaded packages are kept in a cache folder so a second run is quick.
# 2. `git archive HEAD` is unpacked into it: what is committed, nothing else.
# 3. Inside it, under chroot with /proc, /dev and /sys bind-mounted: `make demo && make test`.
# 4. `make package`, then the .deb is installed with apt-get and runs the quickstart job from an
#    empty folder outside the source tree.
# The mounts are undone and the root removed whatever happens (KEEP_ROOT=1 keeps the root).
#
# Needs root (mmdebstrap in root mode, chroot, mount). Too slow for every CI run.
set -euo pipefail

if [ "$(id -u)" != 0 ]; then
  echo "fresh-check: needs root (it builds a Debian root with mmdebstrap and runs chroot and mount)." >&2
  echo "             run it as root, e.g. 'sudo make fresh-check'" >&2
  exit 1
fi
for tool in mmdebstrap git chroot mount; do
  if ! command -v "$tool" >/dev/null; then
    echo "fresh-check: '$tool' not found; on Debian: apt-get install mmdebstrap git" >&2
    exit 1
  fi
done

SRC=$(cd "$(dirname "$0")/.." && pwd)
CACHE=${FRESH_CHECK_CACHE:-/var/cache/seasim-fresh-check}
ROOT=$(mktemp -d "${TMPDIR:-/var/tmp}/seasim-fresh-root.XXXXXX")
LOG_DIR=${FRESH_CHECK_LOGS:-$SRC/build/fresh-check}
mkdir -p "$CACHE/archives" "$LOG_DIR"

# The mirror this machine uses: its deb822 sources (or sources.list) are pasted into the root.
SOURCES=""
for f in /etc/apt/sources.list.d/debian.sources /etc/apt/sources.list; do
  if [ -s "$f" ]; then SOURCES=$f; break; fi
done
[ -n "$SOURCES" ] || SOURCES="http://deb.debian.org/debian"

MOUNTED=()
cleanup() {
  local rc=$?
  for ((i = ${#MOUNTED[@]} - 1; i >= 0; i--)); do umount -l "${MOUNTED[$i]}" 2>/dev/null || true; done
  # Keep what the root downloaded, so the next run installs from the cache.
  if [ -d "$ROOT/var/cache/apt/archives" ]; then
    find "$ROOT/var/cache/apt/archives" -maxdepth 1 -name '*.deb' -exec cp -n {} "$CACHE/archives/" \; 2>/dev/null || true
  fi
  if [ "${KEEP_ROOT:-0}" = 1 ]; then
    echo "fresh-check: root kept at $ROOT"
  else
    # Never follow a mount that failed to come off.
    if ! grep -q " $ROOT/" /proc/mounts; then rm -rf --one-file-system "$ROOT"; fi
  fi
  exit $rc
}
trap cleanup EXIT INT TERM

declare -a STEP_NAMES STEP_SECONDS
step() {  # step NAME COMMAND...: runs it, logs to $LOG_DIR/NAME.log, records its time
  local name=$1; shift
  local t0=$SECONDS
  echo "== $name"
  if "$@" >"$LOG_DIR/$name.log" 2>&1; then
    STEP_NAMES+=("$name"); STEP_SECONDS+=($((SECONDS - t0)))
    echo "   ok in $((SECONDS - t0)) s"
  else
    local rc=$?
    STEP_NAMES+=("$name (FAILED)"); STEP_SECONDS+=($((SECONDS - t0)))
    echo "   FAILED (exit $rc) after $((SECONDS - t0)) s; last lines of $LOG_DIR/$name.log:" >&2
    tail -n 40 "$LOG_DIR/$name.log" >&2
    summary
    exit $rc
  fi
}
summary() {
  echo "== step times"
  for i in "${!STEP_NAMES[@]}"; do printf '   %-28s %5d s\n' "${STEP_NAMES[$i]}" "${STEP_SECONDS[$i]}"; done
}

in_root() {  # in_root COMMAND: runs a shell command inside the root with a clean environment
  chroot "$ROOT" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin /bin/bash -c "$1"
}

make_root() {
  mmdebstrap --variant=apt --include=make --skip=essential/unlink \
    --setup-hook='mkdir -p "$1"/var/cache/apt/archives/' \
    --setup-hook="sync-in $CACHE/archives /var/cache/apt/archives/" \
    --customize-hook="sync-out /var/cache/apt/archives $CACHE/archives" \
    bookworm "$ROOT" "$SOURCES"
  # apt inside the root keeps what it downloads (the cache is copied out on exit).
  rm -f "$ROOT/etc/apt/apt.conf.d/docker-clean"
  cp /etc/resolv.conf "$ROOT/etc/resolv.conf"
  # The machine's network as the root sees it: besides its resolver, the extra certificate
  # authorities it trusts (an intercepting egress proxy's; a machine behind none has none), which
  # the root's ca-certificates adds when apt installs it, so pip reaches PyPI from the root too.
  if compgen -G "/usr/local/share/ca-certificates/*.crt" >/dev/null; then
    mkdir -p "$ROOT/usr/local/share/ca-certificates"
    cp /usr/local/share/ca-certificates/*.crt "$ROOT/usr/local/share/ca-certificates/"
    if [ -x "$ROOT/usr/sbin/update-ca-certificates" ]; then in_root update-ca-certificates >/dev/null; fi
  fi
}

copy_source() {
  mkdir -p "$ROOT/src/seasim"
  git -C "$SRC" archive --format=tar HEAD | tar -x -C "$ROOT/src/seasim"
  # The cached package downloads go in before apt runs inside the root.
  find "$CACHE/archives" -maxdepth 1 -name '*.deb' -exec cp -n {} "$ROOT/var/cache/apt/archives/" \;
}

mount_all() {
  for d in proc dev sys; do
    mkdir -p "$ROOT/$d"
    # /sys with its submounts: slurmd (the farm test's real Slurm node) stops at start-up without
    # the cgroup file system at /sys/fs/cgroup, which every booted machine has.
    if [ "$d" = sys ]; then mount --rbind "/$d" "$ROOT/$d"; else mount --bind "/$d" "$ROOT/$d"; fi
    MOUNTED+=("$ROOT/$d")
  done
  # PoCL and the tests need a shared-memory folder and a writable /tmp.
  mount -t tmpfs tmpfs "$ROOT/dev/shm" && MOUNTED+=("$ROOT/dev/shm") || true
}

echo "fresh-check: source $SRC (HEAD $(git -C "$SRC" rev-parse --short HEAD)), root $ROOT, cache $CACHE"
echo "fresh-check: logs in $LOG_DIR"
step make-root make_root
in_root "dpkg-query -W -f '\${Package}\n' | sort" >"$LOG_DIR/packages-bare.txt"
step copy-source copy_source
mount_all
step make-demo in_root "cd /src/seasim && make demo"
step make-test in_root "cd /src/seasim && make test"
in_root "dpkg-query -W -f '\${Package}\n' | sort" >"$LOG_DIR/packages-after-make.txt"
step make-package in_root "cd /src/seasim && make package"
step install-deb in_root "cd /src/seasim/build && apt-get install -y --no-install-recommends ./seasim_*.deb"
step installed-run in_root "rm -rf /tmp/empty && mkdir /tmp/empty && cd /tmp/empty && seasim --version && \
  seasim run jobs/quickstart.toml && test -s results/quickstart/manifest.json && \
  test -s results/quickstart/flat_sea_noon/report.json && ls results/quickstart"
# What `make` installed on the bare root (named packages and their dependencies).
comm -13 "$LOG_DIR/packages-bare.txt" "$LOG_DIR/packages-after-make.txt" >"$LOG_DIR/installed-by-make.txt"
echo "fresh-check: make installed $(wc -l <"$LOG_DIR/installed-by-make.txt") packages on the bare root (list: $LOG_DIR/installed-by-make.txt)"
summary
echo "fresh-check: passed"
