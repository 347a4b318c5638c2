#!/usr/bin/env bash
# Runs the README's two quick-start commands on a fresh, minimal Debian 12 (debootstrap minbase chroot), from a
# clean clone of this repository's HEAD: proof that the set-up scripts install everything they need.
# Needs root and a Debian 12 package mirror: the one this machine's apt sources use for bookworm main
# (scripts/debian-mirror.sh), so a local mirror or proxy is followed. Usage: sudo bash scripts/check-fresh-debian.sh [WORKDIR]
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
root=${1:-/tmp/emcv-fresh-debian}
source "$repo/scripts/debian-mirror.sh"
mirror=$(debian_mirror_uri bookworm) || {
  echo "check-fresh-debian: no apt source on this machine serves bookworm main; add one (any Debian 12 mirror)" >&2
  exit 1
}
command -v debootstrap >/dev/null || { apt-get update -qq && apt-get install -y -qq debootstrap >/dev/null; }
[ -x "$root/bin/bash" ] || debootstrap --variant=minbase bookworm "$root" "$mirror"
rm -rf "$root/root/emcv"
git clone -q "$repo" "$root/root/emcv"
cp /etc/resolv.conf "$root/etc/resolv.conf"
mount -t proc proc "$root/proc"
mount --bind /dev "$root/dev"
trap 'umount "$root/proc" "$root/dev"' EXIT
in_chroot() {
  chroot "$root" /usr/bin/env -i HOME=/root CI=true PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    bash -c "cd /root/emcv && $1"
}
readme_commands=$(awk '/^## Quick start/{q=1;next} q&&/^```/{if(b){exit}b=1;next} q&&b&&NF&&!/^#/' "$repo/README.md")
while IFS= read -r cmd; do
  echo "== fresh Debian 12: $cmd"
  in_chroot "$cmd"
done <<< "$readme_commands"
echo "== both quick-start commands succeeded on a fresh Debian 12"
