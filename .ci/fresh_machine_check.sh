#!/usr/bin/env bash
# The fresh-machine check: the README's two Quick start commands, exactly as the README writes
# them, in a clean Debian 12 root (mmdebstrap's minbase variant, plus git and ca-certificates to
# get the clone) holding a clone of the repository; prints each command's time and the last lines
# of its output. A used machine hides a missing install step; this starts from nothing. Not a CI
# test: it downloads about 1 GB and takes about 27 minutes on a quiet 2-core machine. Run it before any change to
# setup.sh, the CMake files or the packages the project uses (README "Quick start").
#
#   sudo .ci/fresh_machine_check.sh [--keep] [REPOSITORY [BRANCH]]
#
# REPOSITORY (a path or URL git clones) defaults to this checkout, BRANCH to its current branch:
# only committed work is checked. --keep leaves the root for a look (its path is printed; each
# command's whole log is in its /root). FRESH_ROOT_PARENT=DIR makes the root there (default
# /var/tmp; about 8 GB). Exit status: 0 when both commands pass, 1 when one fails, 2 bad input.
set -euo pipefail
script=$(realpath "${BASH_SOURCE[0]}")
usage() { sed -n '9p' "$script" | sed 's/^#   //'; }

keep=0
positional=()
for arg in "$@"; do
  case "$arg" in
    --keep) keep=1 ;;
    -h|--help) sed -n '2,14p' "$script" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "fresh_machine_check: unknown option '$arg' (usage: $(usage))" >&2; exit 2 ;;
    *) positional+=("$arg") ;;
  esac
done
if ((${#positional[@]} > 2)); then
  echo "fresh_machine_check: at most a repository and a branch (usage: $(usage))" >&2; exit 2
fi
checkout=$(dirname "$(dirname "$script")")
repository=${positional[0]:-$checkout}
branch=${positional[1]:-$(git -C "$checkout" symbolic-ref --short HEAD 2>/dev/null || true)}
if [ -z "$branch" ]; then
  echo "fresh_machine_check: $checkout is on no branch; name one (usage: $(usage))" >&2; exit 2
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "fresh_machine_check: needs root (mmdebstrap's root mode, chroot and mount): sudo $0 $*" >&2; exit 2
fi
parent=${FRESH_ROOT_PARENT:-/var/tmp}
if [ ! -d "$parent" ]; then
  echo "fresh_machine_check: FRESH_ROOT_PARENT '$parent' is no directory" >&2; exit 2
fi

# Everything from here on runs in a mount namespace of its own: the root's mounts never show on
# this machine (nor do mounts made under its /dev reach the machine's /dev through a shared bind),
# and they go with the namespace however the script ends. The trap below unmounts them anyway, so
# that the root can be removed.
if [ -z "${FRESH_CHECK_NAMESPACE:-}" ]; then
  FRESH_CHECK_NAMESPACE=1 exec unshare --mount --propagation private "$script" "$@"
fi

minutes() { printf '%d min %02d s' $(($1 / 60)) $(($1 % 60)); }

if ! command -v mmdebstrap >/dev/null; then
  echo "fresh_machine_check: installing mmdebstrap (Debian's package)"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends mmdebstrap >/dev/null ||
    { apt-get update -q >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends mmdebstrap >/dev/null; }
fi

root=$(realpath "$(mktemp -d "$parent/hybridlab-fresh.XXXXXX")")
mounted=()
cleanup() {
  local status=$? pid p m
  trap - EXIT INT TERM
  set +e  # every step of the clean-up is tried
  # A command cut short leaves its processes running in the root: stopped by their ids.
  for signal in TERM KILL; do
    for p in /proc/[0-9]*; do
      pid=${p#/proc/}
      [ "$(readlink "$p/root" 2>/dev/null)" = "$root" ] && kill "-$signal" "$pid" 2>/dev/null
    done
    sleep 1
  done
  for ((m = ${#mounted[@]} - 1; m >= 0; m--)); do
    umount "${mounted[m]}" 2>/dev/null || umount -l "${mounted[m]}" || echo "fresh_machine_check: cannot unmount ${mounted[m]}" >&2
  done
  if ((keep)); then
    echo "fresh_machine_check: the root is kept in $root"
  elif findmnt -rn -o TARGET | grep -qF "$root/"; then
    echo "fresh_machine_check: something is still mounted under $root; left it there" >&2
  else
    rm -rf --one-file-system "$root"
  fi
  exit "$status"
}
trap cleanup EXIT
trap 'echo "fresh_machine_check: interrupted; stopping what runs in the root, unmounting, removing it" >&2; exit 130' INT
trap 'echo "fresh_machine_check: terminated; stopping what runs in the root, unmounting, removing it" >&2; exit 143' TERM

# The package mirror apt uses on this machine, and its security archive: a fresh install takes both.
uris=$(cat /etc/apt/sources.list.d/*.sources /etc/apt/sources.list 2>/dev/null |
         awk '/^(URIs:|deb )/ { for (i = 2; i <= NF; i++) if ($i ~ /^https?:/) print $i }' || true)
mirror=$(grep -v security <<<"$uris" | head -1 || true)
security=$(grep security <<<"$uris" | head -1 || true)
mirror=${mirror:-http://deb.debian.org/debian}
security=${security:-http://deb.debian.org/debian-security}

echo "fresh_machine_check: $repository ($branch) in a clean bookworm root at $root, from $mirror"
start=$SECONDS
mmdebstrap --quiet --variant=minbase --include=git,ca-certificates bookworm "$root" \
  "deb $mirror bookworm main" "deb $mirror bookworm-updates main" "deb $security bookworm-security main"
echo "fresh_machine_check: root made in $(minutes $((SECONDS - start)))"

mount_in() {  # mount_in PATH_IN_ROOT MOUNT_ARGUMENTS...
  local target="$root/$1"
  shift
  mkdir -p "$target"
  mount "$@" "$target"
  mounted+=("$target")
}
# What a booted machine has and the tests use: processes (everything), sysfs (Vulkan's lavapipe
# and Chromium look at devices there), /dev with its pseudo-terminals and shared memory (Chromium).
# No cgroup file system: slurmd wants one, and the machine's own is no root's to take over, so the
# Slurm test skips here, saying so.
mount_in proc -t proc proc
mount_in sys -t sysfs sysfs
mount_in dev --bind /dev
mount_in dev/pts --bind /dev/pts
mount_in dev/shm -t tmpfs -o mode=1777 tmpfs

# apt's mirror is plain HTTP, but npm's registry is reached over TLS through this machine's chain,
# which Debian's bundle in the root may not hold (npm ci then fails with SELF_SIGNED_CERT_IN_CHAIN
# and the check tests the root, not the project): the machine's bundle goes in beside Debian's, for
# Node.js (npm) alone. The machine's proxy settings, where it has any, go along for the same reason.
environment=(HOME=/root USER=root LOGNAME=root SHELL=/bin/bash TERM=dumb
             PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin)
if [ -f /etc/ssl/certs/ca-certificates.crt ]; then
  install -m 644 /etc/ssl/certs/ca-certificates.crt "$root/etc/ssl/this-machine-ca-certificates.crt"
  environment+=(NODE_EXTRA_CA_CERTS=/etc/ssl/this-machine-ca-certificates.crt)
fi
for v in http_proxy https_proxy no_proxy HTTP_PROXY HTTPS_PROXY NO_PROXY; do
  if [ -n "${!v:-}" ]; then environment+=("$v=${!v}"); fi
done

# The clone, made by the root's own git from a bare copy of the branch (the root sees nothing of
# this machine's file system).
git clone --quiet --bare --single-branch --branch "$branch" "$repository" "$root/srv/hybridlab.git"
chroot "$root" git clone --quiet /srv/hybridlab.git /root/hybridlab
echo "fresh_machine_check: cloned $(chroot "$root" git -C /root/hybridlab log -1 --format='%h %s')"

# The README's commands: the lines of its Quick start block that are no comments.
mapfile -t commands < <(awk '/^## Quick start/ { q = 1 } q && /^```sh/ { b = 1; next } b && /^```/ { exit }
                             b && NF && !/^#/' "$root/root/hybridlab/README.md")
if ((${#commands[@]} != 2)); then
  echo "fresh_machine_check: README.md's Quick start holds ${#commands[@]} commands, not the 2 this check runs" >&2
  exit 2
fi

failed=0
for i in 0 1; do
  log=/root/command-$((i + 1)).log
  echo
  echo "=== command $((i + 1)): ${commands[i]}"
  start=$SECONDS
  status=0
  # In the background, so that an interrupt reaches the trap at once, not after the command.
  chroot "$root" /usr/bin/env -i "${environment[@]}" /bin/bash -c "cd /root/hybridlab && ${commands[i]}" \
    >"$root$log" 2>&1 </dev/null &
  wait $! || status=$?
  echo "=== command $((i + 1)): exit status $status after $(minutes $((SECONDS - start))); its last lines ($log in the root):"
  tail -n 30 "$root$log"
  ((status == 0)) || failed=1
done
echo
if ((failed)); then
  echo "fresh_machine_check: FAILED (a README command failed in a clean bookworm root)"
  exit 1
fi
echo "fresh_machine_check: both README commands pass in a clean bookworm root"
