#!/usr/bin/env bash
# Checks what may include what (README, "Architecture"):
#
#   common/          includes only common's own headers ("mrd/...") and a short
#                    list of freestanding standard headers: it runs on the board
#                    and on a bare-metal microcontroller, with no OS and no heap.
#   firmware/core/   the same, plus "firmware/core/...": the pure control core.
#   firmware/app/    common, firmware/core and firmware/app; any standard header;
#                    never a platform adapter, host code or a host library.
#   firmware/platform/<p>/
#                    common, firmware/core, its own folder and the system headers
#                    it adapts; never firmware/app or host code.
#   host_sim/, bench/, fuzz/, tests/
#                    anything above; host_sim never includes tests/.
#   tests/independent_synth/
#                    only its own headers, the standard library and GoogleTest
#                    (an implementation independent of the project's), except
#                    the two programs that run the workflow and the calibration
#                    on its records (discrepancy_independent_study.cpp,
#                    calibrate_coil_test.cpp).
#   tests/independent_building/
#                    only its own headers, the damper laws of
#                    tests/independent_synth/damper_physics.hpp, the standard
#                    library, toml++ and GoogleTest (the second integration
#                    `mrd sim` is judged against).
#
# Usage: check-layering.sh [SOURCE_ROOT]   (default: the repository holding this script)
# Prints one line per violation (file:line: what, and the rule) and exits 1 if
# there is any; exits 0 with a one-line count otherwise.
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root"

# Standard headers that need no operating system and allocate nothing by
# themselves (C++20 freestanding plus the header-only numeric ones).
freestanding='algorithm|array|bit|cfloat|chrono|climits|cmath|concepts|cstddef|cstdint|cstring|functional|initializer_list|limits|numbers|optional|ratio|span|string_view|tuple|type_traits|utility|version'

violations=0
report() {  # file line include rule
  printf '%s:%s: includes %s (%s)\n' "$1" "$2" "$3" "$4"
  violations=$((violations + 1))
}

check_tree() {  # folder-or-file quoted-allowed angle-allowed angle-denied rule [main-quoted-allowed]
  local dir=$1 quoted=$2 angle=$3 denied=$4 rule=$5 main_quoted=${6:-$2}
  [[ -e $dir ]] || return 0
  while IFS=: read -r file line text; do
    local inc=$text
    [[ $text =~ include[[:space:]]*([\"<][^\">]*[\">]) ]] && inc=${BASH_REMATCH[1]}
    case $inc in
      \"*\")
        local path=${inc:1:${#inc}-2}
        # A header beside the including file needs no prefix.
        [[ $path != */* && -f $(dirname "$file")/$path ]] && continue
        local allowed=$quoted
        [[ $file == *_main.cpp ]] && allowed=$main_quoted
        [[ $path =~ ^($allowed) ]] || report "$file" "$line" "$inc" "$rule"
        ;;
      \<*\>)
        local path=${inc:1:${#inc}-2}
        if [[ -n $angle && ! $path =~ ^($angle)$ ]] || [[ -n $denied && $path =~ ^($denied) ]]; then
          report "$file" "$line" "$inc" "$rule"
        fi
        ;;
      *) report "$file" "$line" "$inc" "unreadable include" ;;
    esac
  done < <(grep -rHnE '^[[:space:]]*#[[:space:]]*include' "$dir" --include='*.hpp' --include='*.h' --include='*.cpp' || true)
}

# Libraries only the host tools use.
host_only='Eigen/|unsupported/Eigen|nlohmann/|ceres/|matio|benchmark/|gtest/|gmock/'

check_tree common 'mrd/' "$freestanding" '' \
  'common: only "mrd/..." and freestanding standard headers'
check_tree firmware/core 'mrd/|firmware/core/' "$freestanding" '' \
  'firmware/core: only common, firmware/core and freestanding standard headers'
check_tree firmware/app 'mrd/|firmware/core/|firmware/app/' '' "$host_only" \
  'firmware/app: common, firmware/core, firmware/app; a program main (*_main.cpp) also the Linux adapters it wires, never simulated I/O; no host code or host library' \
  'mrd/|firmware/core/|firmware/app/|firmware/platform/linux/'
for platform in firmware/platform/*/; do
  platform=${platform%/}
  check_tree "$platform" "mrd/|firmware/core/|${platform}/" '' "$host_only" \
    "${platform}: common, firmware/core and its own folder; no firmware/app or host code"
done
check_tree host_sim 'mrd/|firmware/|host_sim/' '' '' 'host_sim: never tests/'
while IFS= read -r file; do
  [[ $file == */discrepancy_independent_study.cpp || $file == */calibrate_coil_test.cpp ]] && continue
  check_tree "$file" 'tests/independent_synth/' '' 'Eigen/|unsupported/Eigen|nlohmann/|ceres/|matio|benchmark/|mrd/|firmware/|host_sim/|common/|tests/' \
    'tests/independent_synth: its own headers, the standard library and GoogleTest only'
done < <(find tests/independent_synth \( -name '*.hpp' -o -name '*.cpp' \) 2>/dev/null | sort)
check_tree tests/independent_building 'tests/independent_building/|tests/independent_synth/damper_physics\.hpp$' '' \
  'Eigen/|unsupported/Eigen|nlohmann/|ceres/|matio|benchmark/|mrd/|firmware/|host_sim/|common/|tests/' \
  'tests/independent_building: its own headers, tests/independent_synth/damper_physics.hpp, the standard library, toml++ and GoogleTest only'

if ((violations)); then
  echo "layering: $violations violation(s)" >&2
  exit 1
fi
echo "layering: ok (common, firmware/core, firmware/app, firmware/platform, host_sim, tests/independent_synth, tests/independent_building)"
