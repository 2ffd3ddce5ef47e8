#!/usr/bin/env bash
# Months between boots: the board's state on a persistent disk (an ext4 image
# made here with `mke2fs -d`, virtio-blk, mounted at /var/lib/mrd in the guest)
# and the guest's wall clock from QEMU's `-rtc base=` (PL031, set at boot by
# RTC_HCTOSYS). Board file boards/emulated-arm64/maintenance-test.toml (short
# hold-off times, a mixing plan of seconds). Three boots on vcan0:
#   1. clock $MRD_EMU_T1 (default 2027-01-01T00:00:00): no state yet. The
#      firmware, mrd-actuator-sim --daq-at-rest and mrd-drive-sim run free
#      until the firmware's summary counts one more confirmed mixing cycle than
#      the state held at boot, then the firmware gets SIGTERM (it saves at
#      exit) and the guest powers off cleanly;
#   2. clock T1 + half a Julian year (182.625 days, 2027-07-02T15:00:00): the
#      same, from the state boot 1 saved;
#   3. clock boot 2 + 1 min: `mrd-firmware --print-state` only.
# Each boot prints `EMU: clock S` (guest Unix time before the firmware starts)
# and `mrd-firmware --print-state` before and after ([boot-N-state-before],
# [boot-N-state-after]); logs tagged [boot-N-firmware], [boot-N-actuator],
# [boot-N-drive]. Serial consoles: $OUT/serial-boot-N.txt.
#
# Usage: months.sh OUT_DIR
# Exit status: 0 the three boots finished, 1 failure or something missing.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
out=${1:?usage: months.sh OUT_DIR}
t1=${MRD_EMU_T1:-2027-01-01T00:00:00}
half_year_s=15778800 # 0.5 × 365.25 days (the Julian year of common/include/mrd/units.hpp)
cycle_limit_s=${MRD_EMU_CYCLE_LIMIT_S:-240}
board=$emu_root/boards/emulated-arm64/maintenance-test.toml

emu_require_tools mke2fs
[[ -r $board ]] || emu_fail "board file $board missing"
rm -rf "$out" && mkdir -p "$out"
emu_cross_build "$out/build.log" mrd-firmware mrd-actuator-sim mrd-drive-sim
emu_fetch

rootfs=$out/rootfs
emu_rootfs "$rootfs" "can can-raw vcan $(emu_disk_modules)"
cp "$(emu_bin mrd-firmware)" "$(emu_bin mrd-actuator-sim)" "$(emu_bin mrd-drive-sim)" "$rootfs/mrd/"
cp "$board" "$rootfs/mrd/board.toml"
{
  echo "CYCLE_LIMIT_S=$cycle_limit_s"
  cat <<'SCENARIO'
BOOT=$(sed -n 's/.*mrd_boot=\([0-9]*\).*/\1/p' /proc/cmdline)
ip link add dev vcan0 type vcan && ip link set vcan0 up || echo "EMU: vcan0 failed"
mount -t ext4 /dev/vda /var/lib/mrd || echo "EMU: mount /dev/vda failed"
echo "EMU: boot $BOOT: clock $(date +%s) ($(date -u +%Y-%m-%dT%H:%M:%SZ))"
./mrd-firmware --board board.toml --print-state > /tmp/state.txt 2>&1; echo "EMU: print-state exit $?"
tag boot-$BOOT-state-before /tmp/state.txt
if [ "$BOOT" != 3 ]; then
  before=$(sed -n 's/.* cycles=\([0-9]*\).*/\1/p' /tmp/state.txt)
  before=${before:-0}
  ./mrd-actuator-sim --board board.toml --can vcan0 --daq-at-rest > /tmp/act.log 2>&1 &
  act=$!
  ./mrd-drive-sim --board board.toml --can vcan0 > /tmp/drive.log 2>&1 &
  drive=$!
  ./mrd-firmware --board board.toml --can vcan0 --log-saves --report-every-s 1 > /tmp/fw.log 2>&1 &
  fw=$!
  t0=$(date +%s)
  while :; do
    now=$(sed -n 's/.*summary.* cycles=\([0-9]*\).*/\1/p' /tmp/fw.log | tail -n1)
    if [ -n "$now" ] && [ "$now" -gt "$before" ]; then echo "EMU: boot $BOOT: cycles $before -> $now after $(( $(date +%s) - t0 )) s"; break; fi
    if [ $(( $(date +%s) - t0 )) -ge "$CYCLE_LIMIT_S" ]; then echo "EMU: boot $BOOT: no confirmed cycle in $CYCLE_LIMIT_S s"; break; fi
    kill -0 $fw 2>/dev/null || { echo "EMU: boot $BOOT: firmware ended early"; break; }
    sleep 1
  done
  kill -TERM $fw; wait $fw; echo "EMU: boot $BOOT: firmware exit $?"
  kill -TERM $act $drive; wait $act; wait $drive
  tag boot-$BOOT-firmware /tmp/fw.log
  tag boot-$BOOT-actuator /tmp/act.log
  tag boot-$BOOT-drive /tmp/drive.log
  ./mrd-firmware --board board.toml --print-state > /tmp/state.txt 2>&1; echo "EMU: print-state exit $?"
  tag boot-$BOOT-state-after /tmp/state.txt
fi
umount /var/lib/mrd || echo "EMU: umount failed"
echo "EMU: done boot $BOOT"
SCENARIO
} >"$rootfs/mrd/scenario.sh"
emu_pack "$rootfs" "$out/initrd.gz"
mkdir -p "$out/empty"
emu_make_disk "$out/state.img" 64M "$out/empty"

t1_s=$(date -u -d "$t1" +%s) || emu_fail "cannot read the clock $t1"
clock() { date -u -d "@$1" +%Y-%m-%dT%H:%M:%S; }
clocks=("$(clock "$t1_s")" "$(clock $((t1_s + half_year_s)))" "$(clock $((t1_s + half_year_s + 60)))")
# Two CPUs: the firmware (SCHED_FIFO from the board file) on one, the
# actuator-DAQ and the drive, free-running at the control period, on the other.
export MRD_EMU_SMP=${MRD_EMU_SMP:-2}
for boot in 1 2 3; do
  echo "emulated-board: boot $boot, clock ${clocks[boot - 1]}"
  rc=0
  # shellcheck disable=SC2046
  emu_boot "$out/initrd.gz" "mrd_boot=$boot" "$out/serial-boot-$boot.txt" -rtc "base=${clocks[boot - 1]}" \
    $(emu_disk_args "$out/state.img") || rc=$?
  grep -q "^EMU: done boot $boot" "$out/serial-boot-$boot.txt" ||
    { tail -n 40 "$out/serial-boot-$boot.txt" >&2; emu_fail "boot $boot did not finish (qemu exit $rc)"; }
done
cat "$out"/serial-boot-{1,2,3}.txt >"$out/serial.txt"
echo "emulated-board: three boots finished ($out/serial.txt)"
