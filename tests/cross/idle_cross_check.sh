#!/usr/bin/env bash
# Cross-compiles one source of the idle-time estimator, the mixing scheduler
# or the mixing task for a bare-metal Cortex-M4F and checks the object:
# warning-free with -fno-exceptions -fno-rtti -ffreestanding, and no reference
# to the heap (operator new/delete, malloc, free), exception machinery or stdio.
# These blocks compute in double (soft-float on the M4; they may run
# decimated), so unlike the control core no single-precision check applies.
# Usage: idle_cross_check.sh ARM_GXX SOURCE OBJECT SOURCE_ROOT COMMON_INCLUDE_DIR
set -euo pipefail
cxx=$1 src=$2 obj=$3 root=$4 common=$5

if [[ ! -x $cxx ]]; then
  echo "idle_cross_check: arm-none-eabi-g++ not found ($cxx); install gcc-arm-none-eabi (scripts/deps/firmware.list)" >&2
  exit 1
fi
nm=${cxx%g++}nm

"$cxx" -std=c++20 -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 \
  -fno-exceptions -fno-rtti -ffreestanding -O2 \
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Werror \
  -I"$root" -I"$common" -c "$src" -o "$obj"
echo "compiled $(basename "$src") for cortex-m4 ($(stat -c %s "$obj") bytes)"

undefined=$("$nm" -u "$obj" | awk '{print $2}')
forbidden='^(_Znw|_Zna|_Zdl|_Zda|malloc$|calloc$|realloc$|free$|__cxa_throw$|__cxa_allocate_exception$|__cxa_begin_catch$|printf$|puts$|fwrite$|fputs$|__gxx_personality|open$|read$|write$)'
bad=$(grep -E "$forbidden" <<<"$undefined" || true)
if [[ -n $bad ]]; then
  echo "idle_cross_check: forbidden references in $(basename "$obj"):" >&2
  echo "$bad" >&2
  exit 1
fi
echo "no heap, no exceptions, no stdio; external symbols: $(tr '\n' ' ' <<<"$undefined")"
