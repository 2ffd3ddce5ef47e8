#!/usr/bin/env bash
# Builds one libFuzzer target with clang (-fsanitize=fuzzer,address,undefined)
# and runs it for a bounded time on a copy of its seed corpus.
# Usage: run_fuzz.sh NAME SOURCE_DIR WORK_DIR SECONDS
#   NAME: codec | ground_motion | measured_csv | mat | board_toml | state_record
# Exit status: 0 no finding; 1 a finding, a build failure, or clang/libFuzzer
# missing (they are in scripts/deps/test.list, so a run without them is a
# broken set-up, not a reason to skip).
set -euo pipefail
name=$1 src=$2 work=$3 secs=$4
cxx=${MRD_FUZZ_CXX:-clang++}

libs=()
defines=()
case $name in
  codec)         sources=(fuzz/codec_fuzz.cpp common/protocol/src/codec.cpp) ;;
  ground_motion) sources=(fuzz/ground_motion_fuzz.cpp host_sim/excitation/ground_motion.cpp host_sim/io/text.cpp firmware/platform/linux/regular_file.cpp) ;;
  measured_csv)  sources=(fuzz/measured_csv_fuzz.cpp host_sim/discrepancy/measured_data.cpp host_sim/io/text.cpp firmware/platform/linux/regular_file.cpp)
                 libs=(-lmatio -lz) ;;
  mat)           sources=(fuzz/mat_fuzz.cpp host_sim/discrepancy/measured_data.cpp host_sim/io/text.cpp firmware/platform/linux/regular_file.cpp)
                 libs=(-lmatio -lz) ;;
  # toml++'s internal assertions off, as in the release build (GCC compiles its
  # TOML_ASSERT_ASSUME to nothing); its unreachable points stay checked by UBSan.
  board_toml)    sources=(fuzz/board_toml_fuzz.cpp firmware/app/board_config.cpp)
                 defines=("-DTOML_ASSERT(expr)=((void)0)") ;;
  state_record)  sources=(fuzz/state_record_fuzz.cpp) ;;
  *) echo "fuzz: unknown target '$name'" >&2; exit 1 ;;
esac

command -v "$cxx" >/dev/null || {
  echo "fuzz: FAIL: $cxx not installed (clang and libclang-rt-14-dev are in scripts/deps/test.list; run scripts/deps.sh)"
  exit 1
}
mkdir -p "$work/corpus"
bin=$work/${name}_fuzz
# Rebuild when a source, or a header of the folders they come from, is newer than the binary.
stale=0
if [[ ! -x $bin ]]; then
  stale=1
else
  dirs=("$src/common/include" "$src/fuzz/run_fuzz.sh")
  for s in "${sources[@]}"; do dirs+=("$src/$(dirname "$s")"); done
  [[ -n $(find "${dirs[@]}" -newer "$bin" \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.sh' \) -print -quit) ]] && stale=1
fi
if ((stale)); then
  paths=()
  for s in "${sources[@]}"; do paths+=("$src/$s"); done
  if ! "$cxx" -std=c++20 -O1 -gline-tables-only -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
      "${defines[@]}" -I"$src" -I"$src/common/include" "${paths[@]}" "${libs[@]}" -o "$bin" 2>"$work/build.log"; then
    if grep -q -i "fuzzer" "$work/build.log" && grep -q -i -E "cannot find|not found|No such file" "$work/build.log"; then
      echo "fuzz: FAIL: libFuzzer runtime missing (libclang-rt-14-dev, scripts/deps/test.list)"
    fi
    cat "$work/build.log"; exit 1
  fi
fi
cp -n "$src/fuzz/corpus/$name"/* "$work/corpus/" 2>/dev/null || true
echo "fuzz: running $bin for ${secs} s"
"$bin" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$work/" \
  "$work/corpus" 2>&1 | tail -n 25
