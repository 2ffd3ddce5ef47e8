#!/usr/bin/env bash
# Closed loop on a real Linux kernel over vcan (the quick path): cross-builds
# mrd-firmware and the peer simulators for aarch64, boots Debian's arm64
# kernel under qemu-system-aarch64 -M virt with an initramfs holding busybox,
# the CAN modules, the programs, the emulated board's board file and the
# ground-motion record, and runs in the guest:
#   1. for each run of $MRD_EMU_RUNS ("mode:idle_years" …): mrd-drive-sim,
#      mrd-firmware and mrd-plant-sim on vcan0 in lockstep over the record's
#      first $MRD_EMU_DURATION_S seconds, with a snapshot of
#      /sys/kernel/debug/gpio taken while the firmware runs;
#   2. free-running drive and firmware (passive-off, so the drive's 2.5 A
#      safe current is visible), then `kill -9` of the firmware: the drive
#      reports when it fell back, how long after the last valid command, and
#      how long after its own previous tick.
# Each phase is a boot of its own; MRD_EMU_PHASES names the phases to run
# (default "lockstep cut"). The board file, building and PGA are lib.sh's
# MRD_EMU_BOARD, MRD_EMU_BUILDING and MRD_EMU_PGA_G (defaults: the emulated
# board, the thesis building, mrd-plant-sim's 0.1127 g).
# The serial console goes to $OUT/serial.txt (every boot); lines are tagged [run-N-plant],
# [run-N-firmware], [run-N-drive], [run-N-gpio], [cut-drive], [cut-firmware].
#
# Usage: run.sh RECORD OUT_DIR
# Exit status: 0 the guest finished, 1 failure or something missing (the
# reason is printed).
set -euo pipefail
source "$(dirname "$0")/lib.sh"
record=${1:?usage: run.sh RECORD OUT_DIR}
out=${2:?usage: run.sh RECORD OUT_DIR}
runs=${MRD_EMU_RUNS:-"passive-on:0.25 semi-active:0.5"}
duration_s=${MRD_EMU_DURATION_S:-10}
phases=${MRD_EMU_PHASES-"lockstep cut"}
[[ -n ${phases// /} ]] || emu_fail "MRD_EMU_PHASES is empty (give lockstep, cut or both)"
for phase in $phases; do
  [[ $phase == lockstep || $phase == cut ]] || emu_fail "MRD_EMU_PHASES: unknown phase '$phase' (lockstep or cut)"
done

emu_require_tools
emu_closed_loop_prepare "$record" "$out"

rootfs=$out/rootfs
emu_closed_loop_rootfs "$rootfs" "can can-raw vcan" "$record"
{
  echo "DURATION=$duration_s"
  echo "RUNS=\"$runs\""
  echo "PLANT_OPTIONS=\"$(emu_plant_options)\""
  cat <<'SCENARIO'
ip link add dev vcan0 type vcan && ip link set vcan0 up || echo "EMU: vcan0 failed"
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
      --start-delay-s 1 $PLANT_OPTIONS > /tmp/plant.log 2>&1
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
SCENARIO
} >"$rootfs/mrd/scenario.sh"
emu_pack "$rootfs" "$out/initrd.gz"

# One boot per phase: the lockstep runs on one CPU (cross-CPU wake-ups are
# slow under TCG), the command cut on two (drive and firmware each get a CPU,
# as they would on separate hardware).
: >"$out/serial.txt"
for name in $phases; do
  smp=1
  if [[ $name == cut ]]; then smp=2; fi
  echo "emulated-board: booting $emu_kver under qemu-system-aarch64 -smp $smp for the $name phase"
  rc=0
  MRD_EMU_SMP=$smp emu_boot "$out/initrd.gz" "mrd_phase=$name" "$out/serial-$name.log" || rc=$?
  cat "$out/serial-$name.log" >>"$out/serial.txt"
  grep -q "^EMU: done $name" "$out/serial-$name.log" ||
    { tail -n 40 "$out/serial-$name.log" >&2; emu_fail "the $name phase did not finish (qemu exit $rc)"; }
done
echo "emulated-board: guest finished ($phases; $out/serial.txt)"
