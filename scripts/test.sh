#!/usr/bin/env bash
# The whole test suite: installs what is missing for every job (scripts/deps.sh
# all: the test tools and the boards' and firmware's packages too), builds the
# host release and the AddressSanitizer + UndefinedBehaviorSanitizer builds,
# runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/deps.sh all

jobs=$(nproc)
status=0
for preset in host-release host-debug-asan; do
  echo "== $preset: configure and build"
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j "$jobs"
  echo "== $preset: tests"
  ctest --preset "$preset" -j "$jobs" || status=1
done
exit $status
