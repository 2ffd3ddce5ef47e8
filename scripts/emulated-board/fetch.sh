#!/usr/bin/env bash
# Fetches what the emulated arm64 board boots: Debian's arm64 kernel (the
# version the linux-image-arm64 metapackage points at) and busybox-static,
# with `apt-get download` (no install), unpacked with `dpkg -x` into
#   $CACHE/kernel/   boot/vmlinuz-*, lib/modules/*/
#   $CACHE/busybox/  bin/busybox
# $CACHE defaults to .cache/emulated-board (git-ignored). A cache that is
# already complete is used as is, without network.
# Exit status: 0 ready, 77 cannot fetch (the caller skips), 1 other error.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cache=${MRD_EMU_CACHE:-$root/.cache/emulated-board}
mkdir -p "$cache"

ready() { compgen -G "$cache/kernel/boot/vmlinuz-*" >/dev/null && [[ -x $cache/busybox/bin/busybox ]]; }
if ready; then
  echo "fetch: using the cached kernel and busybox in $cache"
  exit 0
fi

skip() { echo "fetch: SKIP: $*" >&2; exit 77; }
command -v apt-get >/dev/null || skip "no apt-get on this machine"
dpkg --print-foreign-architectures | grep -qx arm64 || skip "arm64 is not a dpkg architecture here (run ./scripts/deps.sh)"

# The kernel version is not written anywhere in the code: ask the metapackage.
kpkg=$(apt-cache depends linux-image-arm64:arm64 2>/dev/null | sed -n 's/^ *Depends: \(linux-image-[^ ]*-arm64\).*/\1/p' | head -n1)
if [[ -z $kpkg ]]; then
  if [[ $(id -u) -eq 0 ]]; then apt-get update -qq >/dev/null 2>&1 || true; fi
  kpkg=$(apt-cache depends linux-image-arm64:arm64 2>/dev/null | sed -n 's/^ *Depends: \(linux-image-[^ ]*-arm64\).*/\1/p' | head -n1)
fi
[[ -n $kpkg ]] || skip "cannot resolve linux-image-arm64:arm64 (no arm64 package lists?)"
kpkg=${kpkg%:arm64}

dl=$cache/downloads
mkdir -p "$dl"
(
  cd "$dl"
  compgen -G "${kpkg}_*_arm64.deb" >/dev/null || apt-get download "${kpkg}:arm64" >/dev/null 2>&1 ||
    { echo "fetch: SKIP: apt-get download ${kpkg}:arm64 failed" >&2; exit 77; }
  compgen -G "busybox-static_*_arm64.deb" >/dev/null || apt-get download busybox-static:arm64 >/dev/null 2>&1 ||
    { echo "fetch: SKIP: apt-get download busybox-static:arm64 failed" >&2; exit 77; }
)
rm -rf "$cache/kernel" "$cache/busybox"
dpkg -x "$(ls "$dl"/${kpkg}_*_arm64.deb | head -n1)" "$cache/kernel"
dpkg -x "$(ls "$dl"/busybox-static_*_arm64.deb | head -n1)" "$cache/busybox"
ready || { echo "fetch: the packages did not contain boot/vmlinuz-* and bin/busybox" >&2; exit 1; }
echo "fetch: $kpkg and busybox-static unpacked in $cache"
