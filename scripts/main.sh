#!/usr/bin/env bash
# The main job: installs what is missing, builds the release, and runs the
# chapter-6 study (records x control modes, fully mixed against 2.5 years
# idle, idle-time sweep) with its Markdown report into ${1:-out/study}.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/deps.sh

out=${1:-out/study}
cmake --preset host-release >/dev/null
cmake --build --preset host-release -j "$(nproc)"
build/host-release/host_sim/mrd study --out "$out"
echo "main: report in $out/report.md"
