#!/usr/bin/env bash
# Power cuts while the firmware saves its state: every trial is one boot of
# the emulated board with the state disk (ext4 image, virtio-blk, mounted at
# /var/lib/mrd). The guest first reads the state the previous trial left
# (`mrd-firmware --print-state`), then runs mrd-firmware saving every 10 ms
# (`--save-every-s 0.01 --log-saves`, board file
# boards/emulated-arm64/maintenance-test.toml); the host kills QEMU with SIGKILL
# at a random moment (uniform in [0, $MRD_EMU_CUT_WINDOW_S) s, default 1)
# after the first `state saved` line of the serial console. A last boot reads
# the state of the last trial.
#   corrupt: print-state says anything but ok or missing (corrupt,
#            wrong-size, io-error …);
#   lost:    missing although a save was seen, or a seq lower than the last
#            `state saved seq=N` the console showed before the kill
#            (N or N+1 are both fine: the old or the new record).
# The randomness is seeded (--seed, default the clock) and the seed printed.
# A boot that prints no read-back line within $MRD_EMU_READBACK_LIMIT_S s
# (default 60; a boot takes about 3 s here) hung before it read the state
# and wrote nothing: it is killed and booted again on the same disk, once
# per trial and twice per run at most, and the script says so. A hang the
# state itself causes (the kernel's ext4 or --print-state on what the cut
# left) comes back on the same disk and fails the run; one of the emulator
# alone (seen once in 1,233 trials) does not. MRD_EMU_HANG_TRIAL=K[:N] makes
# the first N boots (default 1) of trial K hang before their read-back, to
# test both paths.
# Serial consoles: OUT/serial-N.txt (a hung boot's: OUT/serial-N-hung-A.txt).
# The last line is exactly
#   power cuts: N trials, L lost, C corrupt
#
# Usage: power-cuts.sh [--trials N] [--seed S] [--out DIR]
# Exit status: 0 no trial lost or corrupt, 1 otherwise or something missing.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
trials=20
seed=$(date +%s)
out=$emu_build/power-cuts
while (($#)); do
  case $1 in
    --trials) trials=${2:?}; shift 2 ;;
    --seed) seed=${2:?}; shift 2 ;;
    --out) out=${2:?}; shift 2 ;;
    *) emu_fail "usage: power-cuts.sh [--trials N] [--seed S] [--out DIR]" ;;
  esac
done
[[ $trials =~ ^[1-9][0-9]*$ ]] || emu_fail "--trials takes a positive integer"
[[ $seed =~ ^[0-9]+$ ]] || emu_fail "--seed takes a non-negative integer"
window_ms=$(awk -v s="${MRD_EMU_CUT_WINDOW_S:-1}" 'BEGIN { printf "%d", s * 1000 }')
first_save_limit_s=${MRD_EMU_FIRST_SAVE_LIMIT_S:-120}
readback_limit_s=${MRD_EMU_READBACK_LIMIT_S:-60}
hang=${MRD_EMU_HANG_TRIAL:-0}
[[ $readback_limit_s =~ ^[1-9][0-9]*$ ]] || emu_fail "MRD_EMU_READBACK_LIMIT_S takes a positive whole number of seconds"
[[ $hang =~ ^[0-9]+(:[0-9]+)?$ ]] || emu_fail "MRD_EMU_HANG_TRIAL takes K or K:N (trial K, its first N boots; 0: none)"
hang_trial=${hang%%:*}
hang_boots=1
[[ $hang == *:* ]] && hang_boots=${hang##*:}
board=$emu_root/boards/emulated-arm64/maintenance-test.toml

emu_require_tools mke2fs awk
[[ -r $board ]] || emu_fail "board file $board missing"
rm -rf "$out" && mkdir -p "$out"
emu_cross_build "$out/build.log" mrd-firmware
emu_fetch

rootfs=$out/rootfs
emu_rootfs "$rootfs" "can can-raw vcan $(emu_disk_modules)"
cp "$(emu_bin mrd-firmware)" "$rootfs/mrd/"
cp "$board" "$rootfs/mrd/board.toml"
cat >"$rootfs/mrd/scenario.sh" <<'SCENARIO'
grep -q mrd_hang /proc/cmdline && { echo "EMU: hanging before the read-back (mrd_hang)"; while :; do sleep 60; done; }
ip link add dev vcan0 type vcan && ip link set vcan0 up || echo "EMU: vcan0 failed"
echo "EMU: vcan0 up, mounting the state disk"
mount -t ext4 /dev/vda /var/lib/mrd && echo "EMU: state disk mounted" || echo "EMU: mount /dev/vda failed"
echo "EMU: read-back: $(./mrd-firmware --board board.toml --print-state 2>&1 | tail -n1)"
grep -q mrd_read_only /proc/cmdline || ./mrd-firmware --board board.toml --can vcan0 --save-every-s 0.01 --log-saves 2>&1
umount /var/lib/mrd
echo "EMU: done"
SCENARIO
emu_pack "$rootfs" "$out/initrd.gz"
mkdir -p "$out/empty"
emu_make_disk "$out/state.img" 64M "$out/empty"

echo "power cuts: seed $seed, $trials trials, cut within ${window_ms} ms after the first save"
RANDOM=$seed
lost=0 corrupt=0 hung=0 last_seq=-1 t_start=$(date +%s.%N)

# Judges the read-back line of serial log $1 against the last seq seen: sets
# verdict (ok, lost, corrupt) and readback, counts lost and corrupt.
judge() {
  local line seq
  line=$(tr -d '\r' <"$1" | sed -n 's/^EMU: read-back: //p' | tail -n1)
  readback=$line
  [[ -n $line ]] || emu_fail "no read-back line in $1 (the boot failed)"
  if [[ $line =~ :\ ok\ .*seq=([0-9]+) ]]; then
    seq=${BASH_REMATCH[1]}
    if ((seq < last_seq)); then verdict=lost; else verdict=ok; fi
  elif [[ $line == *": missing" ]]; then
    if ((last_seq >= 0)); then verdict=lost; else verdict=ok; fi
  else
    verdict=corrupt
  fi
  case $verdict in lost) lost=$((lost + 1)) ;; corrupt) corrupt=$((corrupt + 1)) ;; esac
}

# Boot `trial` on the state disk in the background (kernel command-line
# extra $1) with its console in $serial; sets qemu and t0.
start_boot() {
  emu_qemu_args "$out/initrd.gz" "$1" $(emu_disk_args "$out/state.img")
  "${emu_args[@]}" </dev/null >"$serial" 2>&1 &
  qemu=$!
  t0=$(date +%s)
}

# Called while the boot of `trial` has printed no read-back line: after
# readback_limit_s it has hung; it is killed, its console kept, and true is
# returned so that the caller boots again (fails on a second hang of the
# same trial or a third in the run).
hung_before_readback() {
  grep -aq "EMU: read-back: " "$serial" && return 1
  (($(date +%s) - t0 > readback_limit_s)) || return 1
  kill -KILL $qemu 2>/dev/null || true
  wait $qemu 2>/dev/null || true
  hung=$((hung + 1))
  local kept=${serial%.txt}-hung-$attempt.txt
  mv "$serial" "$kept"
  ((attempt == 1 && hung <= 2)) ||
    emu_fail "trial $trial: the boot hung before its read-back again (no line in $readback_limit_s s, console $kept;" \
      "$hung hung boots in this run)"
  echo "power cuts: boot of trial $trial hung before its read-back (no line in $readback_limit_s s," \
    "console $kept); booting again on the same disk"
  return 0
}

for ((trial = 1; trial <= trials + 1; trial++)); do
  serial=$out/serial-$trial.txt
  for ((attempt = 1; ; attempt++)); do
    extra=""
    ((trial > trials)) && extra="mrd_read_only"
    ((trial == hang_trial && attempt <= hang_boots)) && extra+=" mrd_hang"
    start_boot "$extra"
    if ((trial > trials)); then
      # The last boot reads the state back and powers off.
      again=0
      while kill -0 $qemu 2>/dev/null; do
        if hung_before_readback; then again=1; break; fi
        if (($(date +%s) - t0 > ${MRD_EMU_TIMEOUT_S:-900})); then kill -KILL $qemu 2>/dev/null || true; fi
        sleep 0.05
      done
      ((again)) && continue
      wait $qemu 2>/dev/null || true
      break
    fi
    again=0
    until grep -aq "state saved seq=" "$serial"; do
      kill -0 $qemu 2>/dev/null || { tail -n 30 "$serial" >&2; emu_fail "trial $trial: QEMU ended before the first save"; }
      if hung_before_readback; then again=1; break; fi
      if (($(date +%s) - t0 > first_save_limit_s)); then
        kill -KILL $qemu; tail -n 30 "$serial" >&2; emu_fail "trial $trial: no save in $first_save_limit_s s"
      fi
      sleep 0.05
    done
    ((again)) || break
  done
  if ((trial > trials)); then
    tr -d '\r' <"$serial" >"$serial.tmp" && mv "$serial.tmp" "$serial"
    judge "$serial"
    echo "power cuts: trial $trials: $verdict (last saved seq $last_seq): $readback"
    break
  fi
  delay_ms=$(((RANDOM * 32768 + RANDOM) % window_ms))
  sleep "$(awk -v ms="$delay_ms" 'BEGIN { printf "%.3f", ms / 1000 }')"
  kill -KILL $qemu
  wait $qemu 2>/dev/null || true
  # What the previous trial's cut left, read back at this boot's start.
  if ((trial > 1)); then
    judge "$serial"
    echo "power cuts: trial $((trial - 1)): $verdict (last saved seq $last_seq): $readback"
  fi
  seen=$(tr -d '\r' <"$serial" | sed -n 's/.*state saved seq=\([0-9]*\).*/\1/p' | tail -n1)
  last_seq=${seen:-$last_seq}
  echo "power cuts: trial $trial: killed ${delay_ms} ms after the first save, last seq on the console $last_seq"
done
elapsed=$(awk -v a="$t_start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
echo "power cuts: $(awk -v e="$elapsed" -v n="$trials" 'BEGIN { printf "%.2f", e / (n + 1) }') s per trial ($elapsed s for $trials trials and the final read-back)"
((hung == 0)) || echo "power cuts: $hung boot(s) hung before their read-back and were booted again"
echo "power cuts: $trials trials, $lost lost, $corrupt corrupt"
((lost == 0 && corrupt == 0))
