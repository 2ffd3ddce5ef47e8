#!/usr/bin/env bash
# Instructions per tick of the idle-time estimator's step, its two per-tick
# queries (forecast and volume to the ceiling) and the mixing scheduler's
# step (host x86-64, the build's optimization level), in the double, float
# and fixed-point builds, counted by callgrind over the out-of-line
# *_step_once functions of mrd_bench_idle_steps over 240 s of 1 ms ticks
# (two 30 s bursts of motion, each followed by 90 s still; see
# bench/idle_step_count.cpp).
# Usage: bench/idle_callgrind.sh [BUILD_DIR]   (default build/host-release)
set -euo pipefail
build=${1:-build/host-release}
exe=$build/bench/mrd_bench_idle_steps
ticks=240000
[[ -x $exe ]] || { echo "idle_callgrind: $exe not built" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "idle_callgrind: valgrind not installed (scripts/deps/firmware.list)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for numeric in double float fixed; do
  for part in estimator queries scheduler; do
    valgrind --tool=callgrind --toggle-collect="*${part}_step_once*" --callgrind-out-file="$tmp/cg" \
      "$exe" "$numeric" "$ticks" >"$tmp/out" 2>"$tmp/err"
    ir=$(sed -n 's/^==[0-9]*== Collected : \([0-9]*\).*/\1/p' "$tmp/err")
    [[ -n $ir ]] || { echo "idle_callgrind: no count from callgrind" >&2; cat "$tmp/err" >&2; exit 1; }
    awk -v n="$numeric" -v p="$part" -v ir="$ir" -v s="$ticks" \
      'BEGIN { printf "%-6s %-9s %8.1f instructions per tick (%d Ir over %d ticks)\n", n, p, ir / s, ir, s }'
  done
done
