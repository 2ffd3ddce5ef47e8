#!/usr/bin/env bash
# Fetches what the emulated arm64 board boots, all from Debian's archive with
# `apt-get download` (no install), unpacked with `dpkg -x` into
#   $CACHE/kernel/    boot/vmlinuz-*, boot/config-*, lib/modules/*/
#                     (the version the linux-image-arm64 metapackage points at)
#   $CACHE/busybox/   bin/busybox (busybox-static)
#   $CACHE/iproute2/  bin/ip and the libraries it loads (libbpf1, libelf1,
#                     zlib1g, libmnl0, libbsd0, libmd0, libcap2, libc6): busybox's
#                     `ip` cannot configure a CAN controller (`type can`)
# $CACHE defaults to .cache/emulated-board (git-ignored). A cache that is
# already complete is used as is, without network. As root, a machine without
# the arm64 package lists gets them (dpkg --add-architecture, apt-get update).
# Exit status: 0 ready, 1 not ready (the reason is printed).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cache=${MRD_EMU_CACHE:-$root/.cache/emulated-board}
mkdir -p "$cache"

ip_libs=(libbpf1 libelf1 zlib1g libmnl0 libbsd0 libmd0 libcap2 libc6)
ready() {
  compgen -G "$cache/kernel/boot/vmlinuz-*" >/dev/null && compgen -G "$cache/kernel/boot/config-*" >/dev/null &&
    [[ -x $cache/busybox/bin/busybox && -x $cache/iproute2/bin/ip && -e $cache/iproute2/lib/ld-linux-aarch64.so.1 ]]
}
if ready; then
  echo "fetch: using the cached kernel, busybox and iproute2 in $cache"
  exit 0
fi

fail() { echo "fetch: FAIL: $*" >&2; exit 1; }
command -v apt-get >/dev/null || fail "no apt-get on this machine (Debian 12 is assumed)"
command -v dpkg >/dev/null || fail "no dpkg on this machine"

resolve_kernel() {
  apt-cache depends linux-image-arm64:arm64 2>/dev/null |
    sed -n 's/^ *Depends: \(linux-image-[^ ]*-arm64\).*/\1/p' | head -n1
}
if ! dpkg --print-foreign-architectures | grep -qx arm64 || [[ -z $(resolve_kernel) ]]; then
  [[ $(id -u) -eq 0 ]] ||
    fail "no arm64 package lists here; as root: dpkg --add-architecture arm64 && apt-get update (or ./scripts/deps.sh)"
  dpkg --print-foreign-architectures | grep -qx arm64 || dpkg --add-architecture arm64
  apt-get update -qq >/dev/null 2>&1 || fail "apt-get update failed"
fi
# The kernel version is not written anywhere in the code: ask the metapackage.
kpkg=$(resolve_kernel)
[[ -n $kpkg ]] || fail "cannot resolve linux-image-arm64:arm64 (no arm64 package lists?)"
kpkg=${kpkg%:arm64}

dl=$cache/downloads
mkdir -p "$dl"
deb() { compgen -G "$dl/${1}_*_arm64.deb" | head -n1; }
for p in "$kpkg" busybox-static iproute2 "${ip_libs[@]}"; do
  [[ -n $(deb "$p") ]] && continue
  (cd "$dl" && apt-get download "$p:arm64" >"$dl/$p.log" 2>&1) ||
    { cat "$dl/$p.log" >&2; fail "apt-get download $p:arm64 failed"; }
done

rm -rf "$cache/kernel" "$cache/busybox" "$cache/iproute2"
dpkg -x "$(deb "$kpkg")" "$cache/kernel"
dpkg -x "$(deb busybox-static)" "$cache/busybox"
for p in iproute2 "${ip_libs[@]}"; do dpkg -x "$(deb "$p")" "$cache/iproute2"; done
ready || fail "the packages did not contain boot/vmlinuz-*, boot/config-*, bin/busybox, bin/ip and ld-linux-aarch64.so.1"
echo "fetch: $kpkg, busybox-static and iproute2 (with ${ip_libs[*]}) unpacked in $cache"
