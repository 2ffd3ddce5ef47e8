#!/usr/bin/env bash
# Closed loop over a real CAN controller driver: QEMU's two emulated Kvaser
# PCI cards (SJA1000) on one emulated CAN bus, Debian's sja1000/kvaser_pci
# modules, both controllers brought up with the command of
# boards/mrd-firmware.service's ExecStartPre
#   ip link set canX type can bitrate 1000000 restart-ms 100; ip link set canX up
# (iproute2 for arm64: busybox's ip cannot do `type can`). mrd-firmware runs on
# can0, mrd-drive-sim and mrd-plant-sim on can1, in lockstep over the record's
# first $MRD_EMU_DURATION_S seconds, for each run of $MRD_EMU_RUNS
# ("mode:idle_years" …). `ip -details -statistics link show` of both
# controllers is taken before and after the runs.
# The board file, building and PGA are lib.sh's MRD_EMU_BOARD,
# MRD_EMU_BUILDING and MRD_EMU_PGA_G.
# Serial console: $OUT/serial.txt; lines tagged [run-N-plant], [run-N-firmware],
# [run-N-drive], [link-before-canX], [link-after-canX].
#
# Usage: kvaser.sh RECORD OUT_DIR
# Exit status: 0 the guest finished, 1 failure or something missing.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
record=${1:?usage: kvaser.sh RECORD OUT_DIR}
out=${2:?usage: kvaser.sh RECORD OUT_DIR}
runs=${MRD_EMU_RUNS:-"semi-active:0.5"}
duration_s=${MRD_EMU_DURATION_S:-10}

emu_require_tools
emu_closed_loop_prepare "$record" "$out"
[[ $(emu_kconfig_value CAN_KVASER_PCI) == m ]] || emu_fail "kernel $emu_kver: kvaser_pci is not a module"

rootfs=$out/rootfs
emu_closed_loop_rootfs "$rootfs" "can can-raw kvaser_pci" "$record" ip
{
  echo "DURATION=$duration_s"
  echo "RUNS=\"$runs\""
  echo "PLANT_OPTIONS=\"$(emu_plant_options)\""
  cat <<'SCENARIO'
for i in 0 1; do
  /sbin/ip link set can$i type can bitrate 1000000 restart-ms 100 && /sbin/ip link set can$i up ||
    echo "EMU: can$i: ip link set failed"
  /sbin/ip -details -statistics link show can$i > /tmp/link.txt 2>&1; tag link-before-can$i /tmp/link.txt
done
n=0
for r in $RUNS; do
  n=$((n + 1))
  mode=${r%%:*}
  idle=${r##*:}
  echo "EMU: run $n: $mode, idle $idle years, ${DURATION} s lockstep, firmware on can0, peers on can1"
  ./mrd-drive-sim --board board.toml --can can1 --lockstep > /tmp/drive.log 2>&1 &
  drive=$!
  ./mrd-firmware --board board.toml --can can0 --lockstep --mode "$mode" > /tmp/fw.log 2>&1 &
  fw=$!
  t0=$(date +%s)
  ./mrd-plant-sim --board board.toml --can can1 --lockstep --record record.csv --duration-s "$DURATION" \
      --idle-years "$idle" --start-delay-s 1 $PLANT_OPTIONS > /tmp/plant.log 2>&1
  echo "EMU: run $n: plant exit $?, $(( $(date +%s) - t0 )) s wall"
  wait $fw; echo "EMU: run $n: firmware exit $?"
  wait $drive; echo "EMU: run $n: drive exit $?"
  tag run-$n-plant /tmp/plant.log
  tag run-$n-firmware /tmp/fw.log
  tag run-$n-drive /tmp/drive.log
done
for i in 0 1; do
  /sbin/ip -details -statistics link show can$i > /tmp/link.txt 2>&1; tag link-after-can$i /tmp/link.txt
done
echo "EMU: done kvaser"
SCENARIO
} >"$rootfs/mrd/scenario.sh"
emu_pack "$rootfs" "$out/initrd.gz"

echo "emulated-board: booting $emu_kver with two Kvaser PCI (SJA1000) controllers on one emulated CAN bus"
rc=0
emu_boot "$out/initrd.gz" "" "$out/serial.txt" -object can-bus,id=canbus0 \
  -device kvaser_pci,canbus=canbus0 -device kvaser_pci,canbus=canbus0 || rc=$?
grep -q "^EMU: done kvaser" "$out/serial.txt" ||
  { tail -n 40 "$out/serial.txt" >&2; emu_fail "the guest did not finish (qemu exit $rc)"; }
echo "emulated-board: guest finished ($out/serial.txt)"
