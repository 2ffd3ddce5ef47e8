#!/usr/bin/env bash
# The layering check must pass on this tree and must fail, naming each one, on
# a tree with one planted violation of every rule.
set -euo pipefail
src=$1
check=$src/scripts/check-layering.sh
fail() { echo "layering_test: $*" >&2; exit 1; }

"$check" "$src" || fail "the source tree breaks the layering rules (lines above)"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mk() { mkdir -p "$(dirname "$tmp/$1")"; printf '%s\n' "${@:2}" >"$tmp/$1"; }
# A clean tree passes.
mk common/include/mrd/a.hpp '#include <cstdint>' '#include "mrd/b.hpp"'
mk firmware/core/c.hpp '#include "mrd/a.hpp"' '#include "firmware/core/d.hpp"' '#include <array>'
mk firmware/app/e.cpp '#include "firmware/core/c.hpp"' '#include <vector>' '#include <toml++/toml.hpp>'
mk firmware/app/firmware_main.cpp '#include "firmware/platform/linux/socketcan_bus.hpp"'
mk firmware/platform/linux/f.cpp '#include <linux/can.h>' '#include "firmware/platform/linux/f.hpp"'
mk host_sim/run/g.cpp '#include "firmware/app/e.hpp"' '#include <Eigen/Dense>'
mk tests/independent_building/h.cpp '#include "tests/independent_synth/damper_physics.hpp"' '#include <toml++/toml.h>'
"$check" "$tmp" >/dev/null || fail "a clean tree was refused"

# One violation of each rule.
mk common/include/mrd/bad.hpp '#include "firmware/core/c.hpp"' '#include <vector>'
mk firmware/core/bad.hpp '#include "host_sim/run/g.hpp"' '#include <cstdio>' '#include "firmware/platform/linux/f.hpp"'
mk firmware/app/bad.cpp '#include "firmware/platform/linux/f.hpp"' '#include <Eigen/Dense>'
mk firmware/app/other_main.cpp '#include "firmware/platform/sim/memory_io.hpp"'
mk firmware/platform/linux/bad.cpp '#include "firmware/app/e.hpp"'
mk host_sim/run/bad.cpp '#include "tests/unit/x.hpp"'
mk tests/independent_building/bad.cpp '#include "host_sim/structure/building_params.hpp"' '#include <nlohmann/json.hpp>'
set +e
out=$("$check" "$tmp" 2>&1)
status=$?
set -e
((status == 1)) || fail "planted violations: expected exit 1, got $status"$'\n'"$out"
for expect in \
  'common/include/mrd/bad.hpp:1: includes "firmware/core/c.hpp"' \
  'common/include/mrd/bad.hpp:2: includes <vector>' \
  'firmware/core/bad.hpp:1: includes "host_sim/run/g.hpp"' \
  'firmware/core/bad.hpp:2: includes <cstdio>' \
  'firmware/core/bad.hpp:3: includes "firmware/platform/linux/f.hpp"' \
  'firmware/app/bad.cpp:1: includes "firmware/platform/linux/f.hpp"' \
  'firmware/app/bad.cpp:2: includes <Eigen/Dense>' \
  'firmware/app/other_main.cpp:1: includes "firmware/platform/sim/memory_io.hpp"' \
  'firmware/platform/linux/bad.cpp:1: includes "firmware/app/e.hpp"' \
  'host_sim/run/bad.cpp:1: includes "tests/unit/x.hpp"' \
  'tests/independent_building/bad.cpp:1: includes "host_sim/structure/building_params.hpp"' \
  'tests/independent_building/bad.cpp:2: includes <nlohmann/json.hpp>' \
  'layering: 12 violation(s)'; do
  grep -qF "$expect" <<<"$out" || fail "missing in the report: $expect"$'\n'"$out"
done
echo "layering_test: the tree passes; 12 planted violations found, each named"
