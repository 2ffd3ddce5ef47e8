#!/usr/bin/env bash
# Instructions per run-step of the batch's lanes (host_sim/batch), each mode on
# the thesis building, counted by callgrind over run_closed_loop_batch() in
# BM_Batch<Mode>/8 of mrd_bench_closed_loop: a figure that does not depend on
# the machine's load or clock (for a VM without hardware counters).
# Valgrind has no AVX-512, so the lanes run the x86-64-v3 kernel (AVX2 + FMA,
# two register sets of 4 lanes, the float control core's 8 lanes serving both).
# Usage: bench/batch_callgrind.sh [BUILD_DIR]   (default build/host-release)
set -euo pipefail
build=${1:-build/host-release}
exe=$build/bench/mrd_bench_closed_loop
runs=8               # BM_Batch<Mode>/8
steps_per_run=40000  # the benchmark's 40 s motion at 1 kHz
[[ -x $exe ]] || { echo "batch_callgrind: $exe not built" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "batch_callgrind: valgrind not installed (scripts/deps/firmware.list)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for mode in PassiveOff PassiveOn SemiActive; do
  valgrind --tool=callgrind --toggle-collect='mrd::batch::run_closed_loop_batch*' --callgrind-out-file="$tmp/cg.$mode" \
    "$exe" --benchmark_filter="^BM_Batch$mode/$runs\$" --benchmark_min_time=0 >"$tmp/out.$mode" 2>"$tmp/err.$mode"
  ir=$(sed -n 's/^==[0-9]*== Collected : \([0-9]*\).*/\1/p' "$tmp/err.$mode")
  iterations=$(awk -v b="BM_Batch$mode/$runs" '$1 == b { print $6 }' "$tmp/out.$mode")
  kernel=$(sed -n "s/.*, \(x86-64-v[0-9]\|generic\), .*/\1/p" "$tmp/out.$mode")
  [[ -n $ir && -n $iterations ]] || { echo "batch_callgrind: no count for $mode" >&2; cat "$tmp/err.$mode" "$tmp/out.$mode" >&2; exit 1; }
  awk -v m="$mode" -v ir="$ir" -v it="$iterations" -v n="$runs" -v s="$steps_per_run" -v k="$kernel" \
    'BEGIN { printf "%-10s %8.1f instructions per run-step (%d Ir, %d x %d runs x %d steps, %s kernel)\n", m, ir / (it * n * s), ir, it, n, s, k }'
done
