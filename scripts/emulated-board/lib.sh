# Library of the emulated-board scripts (sourced, not run): checks, the
# aarch64 cross build, the fetched kernel/busybox/iproute2, kernel modules in
# load order, the initramfs and the QEMU boot.
#
# A missing tool, package or kernel is a failure (exit 1 with the reason):
# these scripts never report success by skipping.
#
# Environment: MRD_EMU_CACHE (fetch cache), MRD_EMU_SKIP_BUILD (use the binaries
# in build/aarch64-release as they are), MRD_EMU_JOBS (cross build jobs),
# MRD_EMU_TIMEOUT_S (wall-time limit of one boot, default 900).
# Closed-loop scenarios (run.sh, kvaser.sh) also read MRD_EMU_BOARD (the board
# file the guest's programs run, default boards/emulated-arm64/board.toml),
# MRD_EMU_BUILDING (a building file for mrd-plant-sim, default none: the
# thesis building) and MRD_EMU_PGA_G (the record's PGA for mrd-plant-sim, g,
# default none: the program's default, Table 6.3's 0.1127 g).

emu_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
emu_build=$emu_root/build/aarch64-release
emu_cache=${MRD_EMU_CACHE:-$emu_root/.cache/emulated-board}

# Prints "emulated-board: FAIL: MSG" and exits 1.
emu_fail() {
  echo "emulated-board: FAIL: $*" >&2
  exit 1
}

# Fails unless the host has QEMU, the cross compiler, cpio and gzip, and
# every extra program named (e.g. mke2fs).
emu_require_tools() {
  command -v qemu-system-aarch64 >/dev/null || emu_fail "qemu-system-aarch64 not installed (qemu-system-arm, scripts/deps/board.list)"
  command -v aarch64-linux-gnu-g++ >/dev/null || emu_fail "aarch64-linux-gnu-g++ not installed (scripts/deps/board.list)"
  command -v aarch64-linux-gnu-readelf >/dev/null || emu_fail "aarch64-linux-gnu-readelf not installed (binutils-aarch64-linux-gnu)"
  local t
  for t in cpio gzip flock "$@"; do
    command -v "$t" >/dev/null || emu_fail "$t not installed (scripts/deps/board.list)"
  done
}

# Cross-builds the named targets (preset aarch64-release, static) unless
# MRD_EMU_SKIP_BUILD is set; incremental, and serialized with a lock so that
# tests running in parallel share one build tree. Log: $1.
emu_cross_build() {
  local log=$1
  shift
  if [[ -z ${MRD_EMU_SKIP_BUILD:-} ]]; then
    mkdir -p "$emu_build"
    echo "emulated-board: cross-building $* in $emu_build"
    (
      flock 9
      cd "$emu_root" && cmake --preset aarch64-release >/dev/null &&
        cmake --build "$emu_build" -j "${MRD_EMU_JOBS:-$(nproc)}" --target "$@"
    ) 9>"$emu_build/.emulated-board.lock" >"$log" 2>&1 ||
      { tail -n 30 "$log" >&2; emu_fail "cross build failed (log $log)"; }
  fi
}

# Path of a cross-built program by its target name.
emu_bin() {
  local p
  case $1 in
    mrd-firmware) p=$emu_build/firmware/app/mrd-firmware ;;
    *) p=$emu_build/host_sim/peers/$1 ;;
  esac
  [[ -x $p ]] || emu_fail "missing $p (cross build)"
  echo "$p"
}

# Fetches (or finds in the cache) the kernel, busybox and iproute2, and sets
# emu_vmlinuz, emu_kver, emu_kmod (lib/modules/VERSION) and emu_kconfig.
emu_fetch() {
  mkdir -p "$(dirname "$emu_cache")" || emu_fail "cannot create the folder of the cache $emu_cache"
  (flock 9 && "$emu_root/scripts/emulated-board/fetch.sh") 9>"$emu_cache.lock" ||
    emu_fail "kernel, busybox or iproute2 not available (see fetch: above)"
  emu_vmlinuz=$(ls "$emu_cache"/kernel/boot/vmlinuz-* | head -n1)
  emu_kver=${emu_vmlinuz##*/vmlinuz-}
  emu_kmod=$emu_cache/kernel/lib/modules/$emu_kver
  emu_kconfig=$emu_cache/kernel/boot/config-$emu_kver
  [[ -d $emu_kmod/kernel && -r $emu_kconfig ]] || emu_fail "kernel $emu_kver has no modules or config in $emu_cache"
}

# Fails unless CONFIG_$1 of the fetched kernel is y or m; prints y or m.
emu_kconfig_value() {
  local v
  v=$(sed -n "s/^CONFIG_$1=\\([ym]\\)\$/\\1/p" "$emu_kconfig")
  [[ -n $v ]] || emu_fail "kernel $emu_kver lacks CONFIG_$1"
  echo "$v"
}

# The module file named NAME (dashes and underscores alike) in the fetched
# kernel, found through modules.order (the package has no modules.dep).
emu_module_path() {
  local want=${1//-/_} rel base
  while read -r rel; do
    base=${rel##*/}
    base=${base%%.ko*}
    if [[ ${base//-/_} == "$want" ]]; then
      rel=$emu_kmod/$rel
      if [[ -f $rel ]]; then echo "$rel"; elif [[ -f $rel.xz ]]; then echo "$rel.xz"; fi
      return 0
    fi
  done <"$emu_kmod/modules.order"
  return 1
}

# Module fields from the .modinfo section ("depends", "softdep").
emu_modinfo() {
  local f=$1 key=$2
  if [[ $f == *.xz ]]; then xz -dc "$f"; else cat "$f"; fi | tr '\0' '\n' | sed -n "s/^$key=//p" | head -n1
}

# Prints the module files for NAME... in load order: each module's `depends=`
# (and `softdep=pre:` by name or alias) before itself, each once. A built-in
# module (modules.builtin) needs no file.
emu_resolve_modules() {
  local -A seen=()
  local order=()
  _emu_visit() {
    local name=${1//-/_} f dep pre
    [[ -n ${seen[$name]:-} ]] && return 0
    seen[$name]=1
    if grep -q "/${1}\\.ko\$\\|/${name}\\.ko\$" "$emu_kmod/modules.builtin" 2>/dev/null; then return 0; fi
    f=$(emu_module_path "$1") || {
      f=$(grep -rlazxF -Z "alias=$1" "$emu_kmod/kernel" 2>/dev/null | tr '\0' '\n' | sort | head -n1)
      [[ -n $f ]] || emu_fail "kernel module or alias $1 not found in $emu_kmod"
    }
    [[ -n ${seen[$f]:-} ]] && return 0
    seen[$f]=1
    for pre in $(emu_modinfo "$f" softdep | sed -n 's/^pre: *//p'); do _emu_visit "$pre"; done
    for dep in $(emu_modinfo "$f" depends | tr ',' ' '); do _emu_visit "$dep"; done
    order+=("$f")
  }
  local m
  for m in "$@"; do _emu_visit "$m"; done
  printf '%s\n' "${order[@]}"
}

# The closed-loop scenarios' common start (run.sh, kvaser.sh): the ground-
# motion record $1 readable, a fresh output folder $2, mrd-firmware and the
# two peer simulators cross-built (log in $2/build.log), the kernel fetched.
emu_closed_loop_prepare() {
  local record=$1 out=$2
  [[ -r $record ]] || emu_fail "ground-motion record $record not readable"
  [[ -z ${MRD_EMU_BOARD+x} || (-f $MRD_EMU_BOARD && -r $MRD_EMU_BOARD) ]] ||
    emu_fail "MRD_EMU_BOARD: board file '${MRD_EMU_BOARD}' not a readable file"
  [[ -z ${MRD_EMU_BUILDING+x} || (-f $MRD_EMU_BUILDING && -r $MRD_EMU_BUILDING) ]] ||
    emu_fail "MRD_EMU_BUILDING: building file '${MRD_EMU_BUILDING}' not a readable file"
  [[ -z ${MRD_EMU_PGA_G+x} || $MRD_EMU_PGA_G =~ ^[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?$ ]] ||
    emu_fail "MRD_EMU_PGA_G: '${MRD_EMU_PGA_G}' is not a PGA in g (a positive decimal number)"
  rm -rf "$out" && mkdir -p "$out"
  emu_cross_build "$out/build.log" mrd-firmware mrd-plant-sim mrd-drive-sim
  emu_fetch
}

# The closed-loop initramfs tree $1 (emu_rootfs with modules $2 and $4 as its
# third argument) holding the three programs, the board file (MRD_EMU_BOARD,
# else the emulated board's) as /mrd/board.toml, the building file
# (MRD_EMU_BUILDING, when set) as /mrd/building.toml and the record $3 as
# /mrd/record.csv.
emu_closed_loop_rootfs() {
  local rootfs=$1 modules=$2 record=$3 with_ip=${4:-}
  emu_rootfs "$rootfs" "$modules" "$with_ip"
  cp "$(emu_bin mrd-firmware)" "$(emu_bin mrd-plant-sim)" "$(emu_bin mrd-drive-sim)" "$rootfs/mrd/"
  cp "${MRD_EMU_BOARD:-$emu_root/boards/emulated-arm64/board.toml}" "$rootfs/mrd/board.toml"
  if [[ -n ${MRD_EMU_BUILDING:-} ]]; then cp "$MRD_EMU_BUILDING" "$rootfs/mrd/building.toml"; fi
  cp "$record" "$rootfs/mrd/record.csv"
}

# The options the closed-loop scenarios add to mrd-plant-sim in the guest:
# --building building.toml when MRD_EMU_BUILDING is set, --pga-g G when
# MRD_EMU_PGA_G is (nothing by default).
emu_plant_options() {
  local o=""
  if [[ -n ${MRD_EMU_BUILDING:-} ]]; then o+=" --building building.toml"; fi
  if [[ -n ${MRD_EMU_PGA_G:-} ]]; then o+=" --pga-g $MRD_EMU_PGA_G"; fi
  echo "${o# }"
}

# Makes the initramfs tree $1: busybox, the modules named in $2 (space
# separated, loaded in dependency order by /init), and /sbin/ip from iproute2
# when $3 is "ip". /init starts with the prelude (mounts, modules) and then
# runs /mrd/scenario.sh, which the caller writes, then powers off.
emu_rootfs() {
  local rootfs=$1 modules=$2 with_ip=${3:-}
  rm -rf "$rootfs"
  mkdir -p "$rootfs"/{bin,sbin,proc,sys,dev,tmp,modules,mrd,var/lib/mrd}
  cp "$emu_cache/busybox/bin/busybox" "$rootfs/bin/busybox"
  ln -s busybox "$rootfs/bin/sh"
  local f n=0 base list
  : >"$rootfs/modules/order"
  if [[ -n $modules ]]; then
    list=$(emu_resolve_modules $modules) || exit 1
    while read -r f; do
      n=$((n + 1))
      base=$(printf '%02d-%s' "$n" "$(basename "${f%.xz}")")
      if [[ $f == *.xz ]]; then xz -dc "$f" >"$rootfs/modules/$base"; else cp "$f" "$rootfs/modules/$base"; fi
      echo "$base" >>"$rootfs/modules/order"
    done <<<"$list"
  fi
  if [[ $with_ip == ip ]]; then emu_add_iproute2 "$rootfs"; fi
  cat >"$rootfs/init" <<'INIT'
#!/bin/sh
/bin/busybox --install -s /bin
export PATH=/bin:/sbin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
mount -t debugfs none /sys/kernel/debug
while read -r m; do insmod "/modules/$m" || echo "EMU: insmod $m failed"; done </modules/order
echo "EMU: kernel $(uname -r), $(nproc) CPUs, $(date -u +%Y-%m-%dT%H:%M:%SZ)"
cd /mrd
tag() { sed "s/^/[$1] /" "$2"; }
. /mrd/scenario.sh
sync
poweroff -f
INIT
  chmod +x "$rootfs/init"
}

# Adds iproute2's ip as /sbin/ip: a wrapper that runs the real binary through
# the dynamic loader with the libraries it needs (the closure of DT_NEEDED).
# Call it by full path in the guest: busybox's shell prefers its own applets.
emu_add_iproute2() {
  local rootfs=$1 src=$emu_cache/iproute2 lib
  local libdir=$rootfs/lib/aarch64-linux-gnu
  mkdir -p "$libdir"
  cp "$src/bin/ip" "$rootfs/sbin/ip.real"
  cp -L "$src/lib/ld-linux-aarch64.so.1" "$rootfs/lib/ld-linux-aarch64.so.1"
  local -a todo=("$src/bin/ip")
  local -A have=()
  while ((${#todo[@]})); do
    local elf=${todo[0]}
    todo=("${todo[@]:1}")
    for lib in $(aarch64-linux-gnu-readelf -d "$elf" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p'); do
      [[ -n ${have[$lib]:-} ]] && continue
      have[$lib]=1
      local p="" d
      for d in "$src"/{lib,usr/lib}/aarch64-linux-gnu; do [[ -e $d/$lib ]] && { p=$d/$lib; break; }; done
      [[ -n $p ]] || emu_fail "iproute2: $lib not in the fetched packages ($src)"
      cp -L "$p" "$libdir/$lib"
      todo+=("$p")
    done
  done
  cat >"$rootfs/sbin/ip" <<'IP'
#!/bin/sh
exec /lib/ld-linux-aarch64.so.1 --library-path /lib/aarch64-linux-gnu /sbin/ip.real "$@"
IP
  chmod +x "$rootfs/sbin/ip"
}

# Packs the tree $1 into the gzip'd cpio $2.
emu_pack() {
  (cd "$1" && find . | cpio -o -H newc --quiet | gzip -1) >"$2"
}

# The QEMU command line for the initramfs $1 and the kernel command-line
# extra $2, more QEMU arguments after that; -smp from MRD_EMU_SMP (default 1).
emu_qemu_args() {
  local initrd=$1 append=$2
  shift 2
  emu_args=(qemu-system-aarch64 -M virt -cpu cortex-a53 -smp "${MRD_EMU_SMP:-1}" -m 512
    -kernel "$emu_vmlinuz" -initrd "$initrd" -append "console=ttyAMA0 quiet panic=-1 $append"
    -nic none -nographic -no-reboot -monitor none -serial stdio "$@")
}

# Boots the initramfs $1 with the kernel command-line extra $2, serial console
# to $3 (carriage returns removed), more QEMU arguments after that. Returns
# QEMU's exit status (137 after the time limit MRD_EMU_TIMEOUT_S).
emu_boot() {
  local initrd=$1 append=$2 serial=$3
  shift 3
  local rc=0
  emu_qemu_args "$initrd" "$append" "$@"
  timeout -s KILL "${MRD_EMU_TIMEOUT_S:-900}" "${emu_args[@]}" </dev/null >"$serial.raw" 2>&1 || rc=$?
  tr -d '\r' <"$serial.raw" >"$serial" && rm -f "$serial.raw"
  return "$rc"
}

# Makes the ext4 image $1 (size $2, e.g. 64M) holding the files of folder $3
# (may be empty), without root: mke2fs -d.
emu_make_disk() {
  local img=$1 size=$2 dir=$3
  rm -f "$img"
  mke2fs -q -F -t ext4 -d "$dir" "$img" "$size" >"$img.log" 2>&1 || { cat "$img.log" >&2; emu_fail "mke2fs failed"; }
}

# QEMU arguments attaching the raw image $1 as a virtio-blk disk (vda).
emu_disk_args() {
  echo "-drive file=$1,if=none,format=raw,id=d0 -device virtio-blk-device,drive=d0"
}

# The modules a disk on virtio-mmio with ext4 needs, by name (dependencies
# are resolved from the modules themselves).
emu_disk_modules() {
  local m=""
  [[ $(emu_kconfig_value VIRTIO_MMIO) == m ]] && m+=" virtio_mmio"
  [[ $(emu_kconfig_value VIRTIO_BLK) == m ]] && m+=" virtio_blk"
  [[ $(emu_kconfig_value CRYPTO_CRC32C) == m ]] && m+=" crc32c_generic"
  [[ $(emu_kconfig_value EXT4_FS) == m ]] && m+=" ext4"
  echo "$m"
}
