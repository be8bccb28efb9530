#!/usr/bin/env bash
# Runs the README's two commands on a freshly made Debian 12 root: what a new
# user's machine has (git and nothing else), not what this machine has
# collected. Not part of CI: it downloads ~1 GB of packages and builds, and
# takes 15-30 minutes.
#
#   scripts/fresh-check.sh [--worktree] [--keep] [--root DIR]
#
# The project goes in as a fresh `git clone` of this checkout's HEAD (what is
# committed); --worktree adds the uncommitted changes and untracked files
# (for a check before committing). Then, inside `chroot`, as root:
#   scripts/demo.sh     (sets up, builds and runs the default scene)
#   scripts/test.sh     (sets up and runs the tests)
# each timed; at the end each command's exit code and wall time, and the exit
# status is non-zero if either failed. The root (a new folder under /tmp, or
# DIR, which must be absent or empty) is removed at the end unless --keep.
# Needs root and mmdebstrap (apt-get install mmdebstrap). docs/development.md.
set -euo pipefail
cd "$(dirname "$0")/.."
source_dir=$(pwd)

worktree=0 keep=0 root=""
while (($#)); do
  case "$1" in
    --worktree) worktree=1 ;;
    --keep) keep=1 ;;
    --root) [ $# -ge 2 ] || { echo "fresh-check: --root needs a folder (see --help)" >&2; exit 2; }
            root="$2"; shift ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "fresh-check: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
[ "$(id -u)" -eq 0 ] || { echo "fresh-check: needs root (mmdebstrap, chroot, mounts)" >&2; exit 2; }
command -v mmdebstrap >/dev/null || { echo "fresh-check: apt-get install mmdebstrap" >&2; exit 2; }
if [ -n "$root" ]; then
  # Never remove (at the end) what was there before.
  if [ -e "$root" ] && [ -n "$(ls -A "$root" 2>/dev/null)" ]; then
    echo "fresh-check: $root is not empty; give an absent or empty folder" >&2; exit 2
  fi
  mkdir -p "$root"
  root=$(cd "$root" && pwd)
else
  root=$(mktemp -d /tmp/pushout-fresh.XXXXXX)
fi

mounted=()
cleanup() {
  local pid i
  # Processes left in the root (a virtual X server, an MPI daemon) were
  # started by this check: end them, then unmount and remove.
  for pid in $(ls /proc | grep -E '^[0-9]+$'); do
    [ "$(readlink "/proc/$pid/root" 2>/dev/null)" = "$root" ] && kill -9 "$pid" 2>/dev/null
  done
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount "${mounted[i]}" 2>/dev/null || umount -l "${mounted[i]}" 2>/dev/null || true
  done
  if ((keep)); then
    echo "fresh-check: root kept in $root"
  else
    rm -rf --one-file-system "$root"
  fi
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
trap 'exit 129' HUP

echo "fresh-check: making a Debian 12 root in $root"
# mmdebstrap wants an empty or absent target.
rmdir "$root" 2>/dev/null || true
mmdebstrap --quiet --variant=apt --include=git,ca-certificates bookworm "$root"

echo "fresh-check: cloning $(git rev-parse --short HEAD)$( ((worktree)) && echo ' with the working tree')"
((worktree)) && git status --short | sed 's/^/  /'
git clone --quiet "$source_dir" "$root/work/pushout"
if ((worktree)); then
  # Uncommitted changes and untracked (not ignored) files, as they are here.
  git diff HEAD --binary | git -C "$root/work/pushout" apply --whitespace=nowarn --allow-empty
  git ls-files --others --exclude-standard -z | xargs -0 -r cp --parents -t "$root/work/pushout"
fi

for fs in proc sys dev dev/pts; do
  mount --bind "/$fs" "$root/$fs"
  mounted+=("$root/$fs")
done
cp /etc/resolv.conf "$root/etc/resolv.conf"
# An installed Debian system has /etc/hosts; mmdebstrap's root has none. Without
# it every MPI start (Open MPI's hwloc probes for X displays) asks the DNS
# server for "localhost", and a query left unanswered costs the resolver's 5 s:
# e2e_bad_input_fails_cleanly took 78 s in such a root against 6 s with this file.
printf '127.0.0.1\tlocalhost\n::1\t\tlocalhost ip6-localhost ip6-loopback\n' >"$root/etc/hosts"

# Runs a command in the root as a new user's shell would (root, no sudo).
in_root() {
  chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 TERM=dumb bash -c "cd /work/pushout && $1"
}

declare -A rc seconds
start=$(date +%s)
for cmd in scripts/demo.sh scripts/test.sh; do
  echo "fresh-check: $cmd"
  t0=$(date +%s)
  set +e
  in_root "$cmd" 2>&1 | sed 's/^/  | /'
  rc[$cmd]=${PIPESTATUS[0]}
  set -e
  seconds[$cmd]=$(($(date +%s) - t0))
done

echo
echo "fresh-check: results on a fresh Debian 12 root"
status=0
for cmd in scripts/demo.sh scripts/test.sh; do
  printf '  %-16s exit %d  %4d s\n' "$cmd" "${rc[$cmd]}" "${seconds[$cmd]}"
  [ "${rc[$cmd]}" -eq 0 ] || status=1
done
printf '  %-16s %s  %4d s\n' "total" "      " "$(($(date +%s) - start))"
exit $status
