#!/usr/bin/env bash
# Closed loop on a real Linux kernel: cross-builds mrd-firmware and the peer
# simulators for aarch64 (preset aarch64-release, static), boots Debian's
# arm64 kernel under qemu-system-aarch64 -M virt with an initramfs holding
# busybox, the CAN modules, the programs, the emulated board's board file and
# the ground-motion record, and runs in the guest:
#   1. for each run of $MRD_EMU_RUNS ("mode:idle_years" …): mrd-drive-sim,
#      mrd-firmware and mrd-plant-sim on vcan0 in lockstep over the record's
#      first $MRD_EMU_DURATION_S seconds, with a snapshot of
#      /sys/kernel/debug/gpio taken while the firmware runs;
#   2. free-running drive and firmware (passive-off, so the drive's 2.5 A
#      safe current is visible), then `kill -9` of the firmware: the drive
#      reports when it fell back, how long after the last valid command, and
#      how long after its own previous tick.
# The serial console goes to $OUT/serial.txt (both boots); lines are tagged [run-N-plant],
# [run-N-firmware], [run-N-drive], [run-N-gpio], [cut-drive], [cut-firmware].
#
# Usage: run.sh RECORD OUT_DIR
# Exit status: 0 the guest finished, 77 skipped (no QEMU, no cross compiler,
# kernel not fetchable), 1 failure.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
record=${1:?usage: run.sh RECORD OUT_DIR}
out=${2:?usage: run.sh RECORD OUT_DIR}
runs=${MRD_EMU_RUNS:-"passive-on:0.25 semi-active:0.5"}
duration_s=${MRD_EMU_DURATION_S:-10}
jobs=${MRD_EMU_JOBS:-$(nproc)}
skip() { echo "emulated-board: SKIP: $*" >&2; exit 77; }

command -v qemu-system-aarch64 >/dev/null || skip "qemu-system-aarch64 not installed (scripts/deps/board.list)"
command -v aarch64-linux-gnu-g++ >/dev/null || skip "aarch64-linux-gnu-g++ not installed (scripts/deps/board.list)"
command -v cpio >/dev/null || skip "cpio not installed"
[[ -r $record ]] || skip "ground-motion record $record not readable"

# 1. Cross build (incremental).
build=$root/build/aarch64-release
if [[ -z ${MRD_EMU_SKIP_BUILD:-} ]]; then
  echo "emulated-board: cross-building for aarch64 in $build"
  (cd "$root" && cmake --preset aarch64-release >/dev/null &&
     cmake --build "$build" -j "$jobs" --target mrd-firmware mrd-plant-sim mrd-drive-sim) >"$out.build.log" 2>&1 ||
    { tail -n 30 "$out.build.log" >&2; echo "emulated-board: cross build failed" >&2; exit 1; }
fi
bins=("$build/firmware/app/mrd-firmware" "$build/host_sim/peers/mrd-plant-sim" "$build/host_sim/peers/mrd-drive-sim")
for b in "${bins[@]}"; do [[ -x $b ]] || { echo "emulated-board: missing $b" >&2; exit 1; }; done

# 2. Kernel and busybox.
set +e
"$root/scripts/emulated-board/fetch.sh"
rc=$?
set -e
((rc == 77)) && exit 77
((rc == 0)) || exit 1
cache=${MRD_EMU_CACHE:-$root/.cache/emulated-board}
vmlinuz=$(ls "$cache"/kernel/boot/vmlinuz-* | head -n1)
kver=${vmlinuz##*/vmlinuz-}
kmod=$cache/kernel/lib/modules/$kver/kernel

# 3. Initramfs.
rm -rf "$out" && mkdir -p "$out"
rootfs=$out/rootfs
mkdir -p "$rootfs"/{bin,sbin,proc,sys,dev,tmp,modules,mrd}
cp "$cache/busybox/bin/busybox" "$rootfs/bin/busybox"
ln -s busybox "$rootfs/bin/sh"
for m in net/can/can.ko net/can/can-raw.ko drivers/net/can/dev/can-dev.ko drivers/net/can/vcan.ko; do
  src=$kmod/$m
  if [[ -f $src ]]; then cp "$src" "$rootfs/modules/"; elif [[ -f $src.xz ]]; then xz -dc "$src.xz" >"$rootfs/modules/$(basename "$m")"; else
    echo "emulated-board: kernel module $m not found in $kmod" >&2; exit 1; fi
done
cp "${bins[@]}" "$rootfs/mrd/"
cp "$root/boards/emulated-arm64/board.toml" "$rootfs/mrd/board.toml"
cp "$record" "$rootfs/mrd/record.csv"

{
  cat <<'INIT'
#!/bin/sh
/bin/busybox --install -s /bin
export PATH=/bin:/sbin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
mount -t debugfs none /sys/kernel/debug
for m in can can-raw can-dev vcan; do insmod /modules/$m.ko || echo "EMU: insmod $m failed"; done
ip link add dev vcan0 type vcan && ip link set vcan0 up || echo "EMU: vcan0 failed"
echo "EMU: kernel $(uname -r), $(nproc) CPUs, $(ls /dev/gpiochip* 2>/dev/null)"
cd /mrd
tag() { sed "s/^/[$1] /" "$2"; }
INIT
  echo "DURATION=$duration_s"
  echo "RUNS=\"$runs\""
  cat <<'INIT'
case " $(cat /proc/cmdline) " in *" mrd_phase=cut "*) PHASE=cut ;; *) PHASE=lockstep ;; esac
n=0
[ "$PHASE" = lockstep ] && for r in $RUNS; do
  n=$((n + 1))
  mode=${r%%:*}
  idle=${r##*:}
  echo "EMU: run $n: $mode, idle $idle years, ${DURATION} s lockstep"
  ./mrd-drive-sim --board board.toml --lockstep > /tmp/drive.log 2>&1 &
  drive=$!
  ./mrd-firmware --board board.toml --lockstep --mode "$mode" > /tmp/fw.log 2>&1 &
  fw=$!
  (sleep 3; cat /sys/kernel/debug/gpio > /tmp/gpio.txt) &
  snap=$!
  t0=$(date +%s)
  ./mrd-plant-sim --board board.toml --lockstep --record record.csv --duration-s "$DURATION" --idle-years "$idle" \
      --start-delay-s 1 > /tmp/plant.log 2>&1
  echo "EMU: run $n: plant exit $?, $(( $(date +%s) - t0 )) s wall"
  wait $snap
  wait $fw; echo "EMU: run $n: firmware exit $?"
  wait $drive; echo "EMU: run $n: drive exit $?"
  tag run-$n-plant /tmp/plant.log
  tag run-$n-firmware /tmp/fw.log
  tag run-$n-drive /tmp/drive.log
  tag run-$n-gpio /tmp/gpio.txt
done

if [ "$PHASE" = cut ]; then
echo "EMU: cut: free-running drive (SCHED_FIFO 90, as hardware of its own) and firmware; firmware killed after 2 s"
./mrd-drive-sim --board board.toml --duration-s 4 --sched-fifo 90 > /tmp/drive2.log 2>&1 &
drive=$!
./mrd-firmware --board board.toml --mode passive-off > /tmp/fw2.log 2>&1 &
fw=$!
sleep 2
kill -9 $fw
echo "EMU: cut: firmware killed"
wait $drive; echo "EMU: cut: drive exit $?"
tag cut-drive /tmp/drive2.log
tag cut-firmware /tmp/fw2.log
fi
echo "EMU: done $PHASE"
poweroff -f
INIT
} >"$rootfs/init"
chmod +x "$rootfs/init"
(cd "$rootfs" && find . | cpio -o -H newc --quiet | gzip -1) >"$out/initrd.gz"

# 4. Boot twice: the lockstep runs on one CPU (cross-CPU wake-ups are slow
# under TCG), the command cut on two (drive and firmware each get a CPU, as
# they would on separate hardware).
boot() {  # phase smp
  echo "emulated-board: booting $kver under qemu-system-aarch64 -smp $2 for the $1 phase"
  set +e
  timeout "${MRD_EMU_TIMEOUT_S:-900}" qemu-system-aarch64 -M virt -cpu cortex-a53 -smp "$2" -m 512 \
    -kernel "$vmlinuz" -initrd "$out/initrd.gz" -append "console=ttyAMA0 quiet panic=-1 mrd_phase=$1" \
    -nic none -nographic -no-reboot -monitor none -serial stdio </dev/null >"$out/serial-$1.log" 2>&1
  local rc=$?
  set -e
  tr -d '\r' <"$out/serial-$1.log" >>"$out/serial.txt"
  grep -q "^EMU: done $1" "$out/serial-$1.log" ||
    { echo "emulated-board: the $1 phase did not finish (qemu exit $rc)" >&2; tail -n 40 "$out/serial-$1.log" >&2; exit 1; }
}
: >"$out/serial.txt"
boot lockstep 1
boot cut 2
echo "emulated-board: guest finished both phases ($out/serial.txt)"
