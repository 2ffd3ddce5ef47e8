#!/usr/bin/env bash
# The main job: installs what is missing for it (scripts/deps.sh main), builds
# the mrd program and the Python module mrd (preset host-main: Release, without
# the tests and benchmarks, in build/host-main), and runs the chapter-6 study (records x
# control modes, fully mixed against 2.5 years idle, idle-time sweep) with its
# Markdown report into ${1:-out/study}.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/deps.sh main

out=${1:-out/study}
cmake --preset host-main >/dev/null
cmake --build --preset host-main -j "$(nproc)"
build/host-main/host_sim/mrd study --out "$out"
echo "main: report in $out/report.md (mrd: build/host-main/host_sim/mrd;" \
  "Python: PYTHONPATH=build/host-main/python python3 -c 'import mrd')"
