#!/usr/bin/env bash
# Builds the CAN-decoder fuzzer with clang (-fsanitize=fuzzer,address,undefined)
# and runs it for a bounded time on a copy of the seed corpus.
# Usage: run_fuzz.sh SOURCE_DIR WORK_DIR SECONDS
# Exit status: 0 no finding, 77 clang/libFuzzer unavailable (skip), 1 finding or build failure.
set -euo pipefail
src=$1 work=$2 secs=$3
cxx=${MRD_FUZZ_CXX:-clang++}
command -v "$cxx" >/dev/null || { echo "fuzz: SKIP: $cxx not installed (scripts/deps/board.list)"; exit 77; }
mkdir -p "$work/corpus"
bin=$work/codec_fuzz
if [[ ! -x $bin || $src/fuzz/codec_fuzz.cpp -nt $bin || $src/common/protocol/src/codec.cpp -nt $bin ||
      $src/common/include/mrd/protocol/codec.hpp -nt $bin || $src/common/include/mrd/protocol/messages.hpp -nt $bin ]]; then
  if ! "$cxx" -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
      -I"$src/common/include" "$src/fuzz/codec_fuzz.cpp" "$src/common/protocol/src/codec.cpp" -o "$bin" 2>"$work/build.log"; then
    if grep -q -i "fuzzer" "$work/build.log" && grep -q -i -E "cannot find|not found|No such file" "$work/build.log"; then
      echo "fuzz: SKIP: libFuzzer runtime missing (libclang-rt-14-dev)"; exit 77
    fi
    cat "$work/build.log"; exit 1
  fi
fi
cp -n "$src"/fuzz/corpus/* "$work/corpus/" 2>/dev/null || true
echo "fuzz: running $bin for ${secs} s"
"$bin" -max_total_time="$secs" -timeout=5 -print_final_stats=1 -artifact_prefix="$work/" "$work/corpus" 2>&1 | tail -n 25
