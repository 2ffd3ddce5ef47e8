#!/usr/bin/env bash
# The main job: installs what is missing, builds the release, and runs the
# headline study into ${1:-out/}.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/deps.sh

out=${1:-out}
cmake --preset host-release >/dev/null
cmake --build --preset host-release -j "$(nproc)"
mrd=build/host-release/host_sim/mrd

for years in 0 0.25 0.5 2.5; do
  "$mrd" settle --idle-years "$years" --out "$out/settle-${years}y"
  echo
done
echo "main: results in $out/"
