#!/usr/bin/env bash
# The whole test suite: installs what is missing for every job (scripts/deps.sh
# all: the test tools and the boards' and firmware's packages too), builds the
# host release and the AddressSanitizer + UndefinedBehaviorSanitizer builds,
# runs every test. Ends with the wall time of each phase (ctest prints the
# time of each test and label above it).
set -euo pipefail
cd "$(dirname "$0")/.."
times=()
t=$SECONDS
./scripts/deps.sh all
times+=("deps $((SECONDS - t)) s")

jobs=$(nproc)
status=0
for preset in host-release host-debug-asan; do
  echo "== $preset: configure and build"
  t=$SECONDS
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j "$jobs"
  times+=("$preset build $((SECONDS - t)) s")
  echo "== $preset: tests"
  t=$SECONDS
  ctest --preset "$preset" -j "$jobs" || status=1
  times+=("$preset tests $((SECONDS - t)) s")
done
printf -v summary '%s, ' "${times[@]}"
echo "== wall time: ${summary}total ${SECONDS} s"
exit $status
