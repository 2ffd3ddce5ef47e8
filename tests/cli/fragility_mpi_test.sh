#!/usr/bin/env bash
# `mrd fragility` under MPI: mpirun -n 1, mpirun -n 2 and the threaded
# single-process run of one small study write the same runs.csv and
# fragility.csv, byte for byte. Fails (never skips) when mpirun is missing.
# Usage: fragility_mpi_test.sh MRD_BINARY
set -euo pipefail
mrd=$1
if ! command -v mpirun >/dev/null; then
  echo "mpirun not found: install openmpi-bin (scripts/deps.sh, scripts/deps/risk.list)" >&2
  exit 1
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Root in containers and CI; two ranks on a machine with fewer free cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpi=(mpirun --oversubscribe)
# OpenMPI's own allocations are not freed at MPI_Finalize: no leak report for them.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"

study=(fragility --synthetic 4 --duration-s 8 --pga-g 0.2,0.6,1.2 --idle-years 0,1
       --control passive-off,passive-on --bootstrap 20 --seed 3)
"$mrd" "${study[@]}" --threads 2 --out "$tmp/threads" >"$tmp/threads.log" 2>&1
"${mpi[@]}" -n 1 "$mrd" "${study[@]}" --threads 1 --out "$tmp/n1" >"$tmp/n1.log" 2>&1
"${mpi[@]}" -n 2 "$mrd" "${study[@]}" --threads 1 --out "$tmp/n2" >"$tmp/n2.log" 2>&1

status=0
for f in runs.csv fragility.csv fragility_curves.csv; do
  for run in n1 n2; do
    if ! cmp -s "$tmp/threads/$f" "$tmp/$run/$f"; then
      echo "FAIL: $run/$f differs from the threaded run's" >&2
      diff "$tmp/threads/$f" "$tmp/$run/$f" | head -5 >&2
      status=1
    fi
  done
done
# 4 records x 3 PGAs x 2 idle times x 2 modes = 48 runs and the header.
lines=$(wc -l <"$tmp/n2/runs.csv")
[[ $lines -eq 49 ]] || { echo "FAIL: runs.csv has $lines lines, expected 49" >&2; status=1; }
grep -q '"ranks": 2' "$tmp/n2/summary.json" || { echo "FAIL: the -n 2 summary does not say 2 ranks" >&2; status=1; }
grep -q '"ranks": 1' "$tmp/n1/summary.json" || { echo "FAIL: the -n 1 summary does not say 1 rank" >&2; status=1; }
[[ $status -eq 0 ]] && echo "runs.csv, fragility.csv and fragility_curves.csv identical for threads, -n 1 and -n 2"
exit $status
