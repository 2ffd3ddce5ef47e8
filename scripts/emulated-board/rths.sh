#!/usr/bin/env bash
# Real-time hybrid simulation on the emulated arm64 board: cross-builds
# mrd-rths (the RTHS runtime) and mrd-rths-lab (the emulated laboratory),
# boots Debian's arm64 kernel under qemu-system-aarch64 -M virt with both
# programs, the emulated board's board file and the ground-motion record, and
# runs in the guest, over vcan0, free-running on CLOCK_MONOTONIC with the
# board's SCHED_FIFO and locked memory:
#   1. for each run of $MRD_EMU_RTHS_RUNS ("rate_hz:compensator" …, default
#      "1000:adaptive"): mrd-rths-lab and mrd-rths on the virtual benchmark
#      (case 1, the record × 0.4) over its first $MRD_EMU_RTHS_DURATION_S
#      seconds (default 5); the runtime's status line gives J1–J5, ticks,
#      overruns, worst lateness and the longest tick;
#   2. the laboratory's stop: no compensation and a 0.05 mm tracking limit, so
#      the laboratory stops, holds and reports it; the runtime ends with the
#      stop's status (exit 3) and its folder is listed (stop.json, no summary).
#   3. the thesis's set-up, for each mode of $MRD_EMU_RTHS_DAMPER_MODES
#      (default "passive-on semi-active"; empty: none): mrd-rths-lab
#      --specimen damper (an actuator with a $MRD_EMU_RTHS_DAMPER_DELAY_MS delay,
#      default 10 ms, and a 2 ms lag stroking the MR
#      damper, its drive and DAQ) and mrd-rths --specimen damper (the thesis
#      building, the model-based compensation, the board's firmware control
#      task beside it) at 1 kHz over the record's first
#      $MRD_EMU_RTHS_DAMPER_DURATION_S seconds (default 5) at 0.1127 g.
#   4. the same with the laboratory on its own clock (mrd-rths-lab --own-clock,
#      mrd-rths --lab-own-clock) for each mode of $MRD_EMU_RTHS_OWN_CLOCK_MODES
#      (default none), tagged [rths-own-clock-MODE-runtime], [...-lab].
#   5. CAN FD (--can-fd on both programs), for each run of
#      $MRD_EMU_RTHS_FD_RUNS ("rate_hz:compensator" …, default none): first
#      vcan0 is made classic-only (`ip link set vcan0 mtu 16`; vcan's default
#      is the FD MTU, 72) and mrd-rths-lab --can-fd must refuse it (exit 1,
#      [rths-fd-refused]); then vcan0 is set back to the FD MTU
#      (`ip link set vcan0 mtu 72`, down and up again) and the benchmark runs
#      as in 1 over $MRD_EMU_RTHS_DURATION_S s with mrd-rths --lab-silent-ms
#      $MRD_EMU_RTHS_FD_LAB_SILENT_MS (default 500: under TCG the laboratory,
#      on the same vCPU, can miss the 205 ticks of the default 50 ms at
#      4096 Hz), tagged [rths-fd-N-runtime], [rths-fd-N-lab], [rths-fd-N-summary].
# The serial console goes to $OUT/serial.txt; lines are tagged
# [rths-N-runtime], [rths-N-lab], [rths-N-summary], [rths-stop-runtime],
# [rths-stop-lab], [rths-stop-files], [rths-stop-json], [rths-damper-MODE-runtime],
# [rths-damper-MODE-lab], [rths-damper-MODE-summary].
#
# Usage: rths.sh RECORD OUT_DIR
# Exit status: 0 the guest finished, 1 failure or something missing (the
# reason is printed).
set -euo pipefail
source "$(dirname "$0")/lib.sh"
record=${1:?usage: rths.sh RECORD OUT_DIR}
out=${2:?usage: rths.sh RECORD OUT_DIR}
runs=${MRD_EMU_RTHS_RUNS:-"1000:adaptive"}
duration_s=${MRD_EMU_RTHS_DURATION_S:-5}
damper_modes=${MRD_EMU_RTHS_DAMPER_MODES-"passive-on semi-active"}
damper_duration_s=${MRD_EMU_RTHS_DAMPER_DURATION_S:-5}
# 10 ms: the thesis's shortest delay. Over these 5 s the library's own loop
# gives -0.31 % semi-active at 10 ms and -1.48 % at 15 ms, and the guest's
# stale samples move a run by up to about 0.9 point either way; 10 ms keeps
# the 2 % check about the set-up, not about the emulator's timing (15 ms is
# held within 2 % on the host, tests/cli and tests/rths_board).
damper_delay_ms=${MRD_EMU_RTHS_DAMPER_DELAY_MS:-10}
case "$damper_delay_ms" in
  ''|*[!0-9]*) emu_fail "MRD_EMU_RTHS_DAMPER_DELAY_MS: '$damper_delay_ms' is not a whole number of ms" ;;
esac
[[ $damper_duration_s =~ ^[0-9]+(\.[0-9]+)?$ ]] ||
  emu_fail "MRD_EMU_RTHS_DAMPER_DURATION_S: '$damper_duration_s' is not a duration in s"
own_clock_modes=${MRD_EMU_RTHS_OWN_CLOCK_MODES:-}
fd_runs=${MRD_EMU_RTHS_FD_RUNS:-}
fd_lab_silent_ms=${MRD_EMU_RTHS_FD_LAB_SILENT_MS:-500}
[[ $fd_lab_silent_ms =~ ^[0-9]+$ ]] || emu_fail "MRD_EMU_RTHS_FD_LAB_SILENT_MS: '$fd_lab_silent_ms' is not a whole number of ms"
for m in $damper_modes $own_clock_modes; do
  [[ $m =~ ^(passive-off|passive-on|semi-active)$ ]] ||
    emu_fail "MRD_EMU_RTHS_DAMPER_MODES: '$m' is not passive-off, passive-on or semi-active"
done
[[ $duration_s =~ ^[0-9]+(\.[0-9]+)?$ ]] || emu_fail "MRD_EMU_RTHS_DURATION_S: '$duration_s' is not a duration in s"
for r in $runs $fd_runs; do
  [[ $r =~ ^[0-9]+:(none|sample|polynomial|adaptive|model)$ ]] ||
    emu_fail "MRD_EMU_RTHS_RUNS: '$r' is not rate_hz:compensator (none, sample, polynomial, adaptive, model)"
done

emu_require_tools
[[ -r $record ]] || emu_fail "ground-motion record $record not readable"
rm -rf "$out" && mkdir -p "$out"
emu_cross_build "$out/build.log" mrd-rths mrd-rths-lab
emu_fetch

rootfs=$out/rootfs
emu_rootfs "$rootfs" "can can-raw vcan"
for p in mrd-rths mrd-rths-lab; do
  bin=$emu_build/host_sim/rths_board/$p
  [[ -x $bin ]] || emu_fail "missing $bin (cross build)"
  cp "$bin" "$rootfs/mrd/"
done
cp "$emu_root/boards/emulated-arm64/board.toml" "$rootfs/mrd/board.toml"
cp "$record" "$rootfs/mrd/record.csv"
{
  echo "DURATION=$duration_s"
  echo "RUNS=\"$runs\""
  echo "DAMPER_MODES=\"$damper_modes\""
  echo "DAMPER_DURATION=$damper_duration_s"
  echo "DAMPER_DELAY_MS=$damper_delay_ms"
  echo "OWN_CLOCK_MODES=\"$own_clock_modes\""
  echo "FD_RUNS=\"$fd_runs\""
  echo "FD_LAB_SILENT_MS=$fd_lab_silent_ms"
  cat <<'SCENARIO'
ip link add dev vcan0 type vcan && ip link set vcan0 up || echo "EMU: vcan0 failed"
n=0
for r in $RUNS; do
  n=$((n + 1))
  rate=${r%%:*}
  comp=${r##*:}
  echo "EMU: rths run $n: $rate Hz, $comp, ${DURATION} s"
  ./mrd-rths-lab --board board.toml --rate-hz "$rate" > /tmp/lab.log 2>&1 &
  lab=$!
  ./mrd-rths --board board.toml --record record.csv --rate-hz "$rate" --compensator "$comp" \
      --duration-s "$DURATION" --out /tmp/rths-$n > /tmp/rths.log 2>&1
  echo "EMU: rths run $n: runtime exit $?"
  wait $lab; echo "EMU: rths run $n: lab exit $?"
  tag rths-$n-runtime /tmp/rths.log
  tag rths-$n-lab /tmp/lab.log
  tag rths-$n-summary /tmp/rths-$n/summary.json
done
echo "EMU: rths stop: no compensation, tracking limit 0.05 mm"
./mrd-rths-lab --board board.toml --rate-hz 1000 --tracking-limit-mm 0.05 > /tmp/lab-stop.log 2>&1 &
lab=$!
./mrd-rths --board board.toml --record record.csv --rate-hz 1000 --compensator none --duration-s "$DURATION" \
    --out /tmp/rths-stop > /tmp/rths-stop.log 2>&1
echo "EMU: rths stop: runtime exit $?"
wait $lab; echo "EMU: rths stop: lab exit $?"
tag rths-stop-runtime /tmp/rths-stop.log
tag rths-stop-lab /tmp/lab-stop.log
ls /tmp/rths-stop > /tmp/rths-stop-files.txt
tag rths-stop-files /tmp/rths-stop-files.txt
tag rths-stop-json /tmp/rths-stop/stop.json
for mode in $DAMPER_MODES; do
  echo "EMU: rths damper $mode: 1000 Hz, ${DAMPER_DURATION} s"
  ./mrd-rths-lab --board board.toml --specimen damper --rate-hz 1000 --delay-ms "$DAMPER_DELAY_MS" --lag-ms 2 \
      > /tmp/lab-damper.log 2>&1 &
  lab=$!
  ./mrd-rths --board board.toml --specimen damper --record record.csv --rate-hz 1000 --mode "$mode" \
      --pga-g 0.1127 --delay-ms "$DAMPER_DELAY_MS" --lag-ms 2 --duration-s "$DAMPER_DURATION" --out /tmp/rths-damper-$mode \
      > /tmp/rths-damper.log 2>&1
  echo "EMU: rths damper $mode: runtime exit $?"
  wait $lab; echo "EMU: rths damper $mode: lab exit $?"
  tag rths-damper-$mode-runtime /tmp/rths-damper.log
  tag rths-damper-$mode-lab /tmp/lab-damper.log
  tag rths-damper-$mode-summary /tmp/rths-damper-$mode/summary.json
done
for mode in $OWN_CLOCK_MODES; do
  echo "EMU: rths own clock $mode: 1000 Hz, ${DAMPER_DURATION} s"
  ./mrd-rths-lab --board board.toml --specimen damper --rate-hz 1000 --delay-ms "$DAMPER_DELAY_MS" --lag-ms 2 --own-clock \
      > /tmp/lab-own.log 2>&1 &
  lab=$!
  ./mrd-rths --board board.toml --specimen damper --record record.csv --rate-hz 1000 --mode "$mode" \
      --pga-g 0.1127 --delay-ms "$DAMPER_DELAY_MS" --lag-ms 2 --duration-s "$DAMPER_DURATION" --lab-own-clock \
      --out /tmp/rths-own-$mode > /tmp/rths-own.log 2>&1
  echo "EMU: rths own clock $mode: runtime exit $?"
  wait $lab; echo "EMU: rths own clock $mode: lab exit $?"
  tag rths-own-clock-$mode-runtime /tmp/rths-own.log
  tag rths-own-clock-$mode-lab /tmp/lab-own.log
done
n=0
for r in $FD_RUNS; do
  n=$((n + 1))
  rate=${r%%:*}
  comp=${r##*:}
  if [ $n -eq 1 ]; then
    echo "EMU: vcan0 mtu before the FD runs $(cat /sys/class/net/vcan0/mtu)"
    ip link set vcan0 down && ip link set vcan0 mtu 16 && ip link set vcan0 up || echo "EMU: vcan0 mtu 16 failed"
    ./mrd-rths-lab --board board.toml --rate-hz "$rate" --can-fd --start-timeout-s 5 > /tmp/lab-fd-refused.log 2>&1
    echo "EMU: rths fd refused on classic vcan0: lab exit $?"
    tag rths-fd-refused /tmp/lab-fd-refused.log
    ip link set vcan0 down && ip link set vcan0 mtu 72 && ip link set vcan0 up || echo "EMU: vcan0 mtu 72 failed"
    echo "EMU: vcan0 mtu $(cat /sys/class/net/vcan0/mtu)"
  fi
  echo "EMU: rths fd run $n: $rate Hz, $comp, ${DURATION} s"
  ./mrd-rths-lab --board board.toml --rate-hz "$rate" --can-fd > /tmp/lab-fd.log 2>&1 &
  lab=$!
  ./mrd-rths --board board.toml --record record.csv --rate-hz "$rate" --compensator "$comp" --can-fd \
      --lab-silent-ms "$FD_LAB_SILENT_MS" --duration-s "$DURATION" --out /tmp/rths-fd-$n > /tmp/rths-fd.log 2>&1
  echo "EMU: rths fd run $n: runtime exit $?"
  wait $lab; echo "EMU: rths fd run $n: lab exit $?"
  tag rths-fd-$n-runtime /tmp/rths-fd.log
  tag rths-fd-$n-lab /tmp/lab-fd.log
  tag rths-fd-$n-summary /tmp/rths-fd-$n/summary.json
done
echo "EMU: done rths"
SCENARIO
} >"$rootfs/mrd/scenario.sh"
emu_pack "$rootfs" "$out/initrd.gz"

echo "emulated-board: booting $emu_kver under qemu-system-aarch64 for the RTHS runs"
rc=0
emu_boot "$out/initrd.gz" "" "$out/serial.txt" || rc=$?
grep -q "^EMU: done rths" "$out/serial.txt" ||
  { tail -n 40 "$out/serial.txt" >&2; emu_fail "the RTHS runs did not finish (qemu exit $rc)"; }
echo "emulated-board: guest finished ($out/serial.txt)"
