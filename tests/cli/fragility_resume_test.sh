#!/usr/bin/env bash
# `mrd fragility` resumes a study killed part-way (SIGKILL): the second run
# takes the journal's completed runs and the final runs.csv equals an
# uninterrupted run's, byte for byte.
# Usage: fragility_resume_test.sh MRD_BINARY [RECORD_SECONDS]
# (shorter records under the sanitizers, which run 10-30x slower)
set -euo pipefail
mrd=$1
seconds=${2:-20}
tmp=$(mktemp -d)
trap 'kill -9 "${pid:-}" 2>/dev/null || true; rm -rf "$tmp"' EXIT

# 8 records x 4 PGAs x 3 idle times x 3 modes = 288 runs, one thread.
study=(fragility --synthetic 8 --duration-s "$seconds" --pga-g 0.1,0.3,0.6,1.0 --idle-years 0,0.5,1
       --bootstrap 10 --seed 5 --threads 1)
total=288
"$mrd" "${study[@]}" --out "$tmp/whole" >/dev/null 2>&1

"$mrd" "${study[@]}" --out "$tmp/killed" >/dev/null 2>&1 &
pid=$!
journal="$tmp/killed.journal"
# Kill once 32 runs (64-byte records) are in the journal.
for _ in $(seq 1 3000); do
  size=$( (cat "$journal"/part-*.journal 2>/dev/null || true) | wc -c)
  ((size >= 32 * 64)) && break
  sleep 0.01
done
kill -9 "$pid"
wait "$pid" && { echo "FAIL: the study finished before it was killed" >&2; exit 1; } || true
kept=$(( $(cat "$journal"/part-*.journal | wc -c) / 64 ))
if ((kept < 32 || kept >= total)); then
  echo "FAIL: $kept runs in the journal at the kill, expected 32 to $((total - 1))" >&2
  exit 1
fi
[[ -e "$tmp/killed/summary.json" ]] && { echo "FAIL: a killed study left outputs" >&2; exit 1; }

"$mrd" "${study[@]}" --out "$tmp/killed" >"$tmp/resume.log" 2>&1
cmp "$tmp/whole/runs.csv" "$tmp/killed/runs.csv" || { echo "FAIL: resumed runs.csv differs" >&2; exit 1; }
cmp "$tmp/whole/fragility.csv" "$tmp/killed/fragility.csv" || { echo "FAIL: resumed fragility.csv differs" >&2; exit 1; }
resumed=$(grep -o '"runs_resumed": [0-9]*' "$tmp/killed/summary.json" | grep -o '[0-9]*$')
((resumed >= kept - 1 && resumed < total)) || { echo "FAIL: runs_resumed $resumed, journal held $kept" >&2; exit 1; }
[[ ! -e $journal ]] || { echo "FAIL: the journal was not removed after the outputs were written" >&2; exit 1; }
echo "killed with $kept of $total runs kept; resumed $resumed; runs.csv identical"
