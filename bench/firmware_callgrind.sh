#!/usr/bin/env bash
# Instructions per control step of the firmware core (host x86-64, the build's
# optimization level), float and fixed point, counted by callgrind over the
# out-of-line step_once() of mrd_bench_firmware_steps.
# Usage: bench/firmware_callgrind.sh [BUILD_DIR]   (default build/host-release)
set -euo pipefail
build=${1:-build/host-release}
exe=$build/bench/mrd_bench_firmware_steps
steps=100000
[[ -x $exe ]] || { echo "firmware_callgrind: $exe not built" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "firmware_callgrind: valgrind not installed (scripts/deps/firmware.list)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for numeric in float fixed; do
  valgrind --tool=callgrind --toggle-collect='*step_once*' --callgrind-out-file="$tmp/cg.$numeric" \
    "$exe" "$numeric" "$steps" >"$tmp/out.$numeric" 2>"$tmp/err.$numeric"
  ir=$(sed -n 's/^==[0-9]*== Collected : \([0-9]*\).*/\1/p' "$tmp/err.$numeric")
  [[ -n $ir ]] || { echo "firmware_callgrind: no count from callgrind" >&2; cat "$tmp/err.$numeric" >&2; exit 1; }
  awk -v n="$numeric" -v ir="$ir" -v s="$steps" 'BEGIN { printf "%-6s %10.1f instructions per step (%d Ir over %d steps)\n", n, ir / s, ir, s }'
done
