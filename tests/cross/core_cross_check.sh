#!/usr/bin/env bash
# Cross-compiles one numeric build of the control core for a bare-metal
# Cortex-M4F and checks the object:
#   - it compiles warning-free with -fno-exceptions -fno-rtti -ffreestanding;
#   - it references no heap (operator new/delete, malloc, free), no exception
#     machinery and no stdio;
#   - DamperController<...>::step() and its parts (step_*) call no
#     double-precision soft-float routine (__aeabi_d*): the M4's FPU is
#     single precision.
# Usage: core_cross_check.sh ARM_GXX SOURCE OBJECT SOURCE_ROOT COMMON_INCLUDE_DIR
set -euo pipefail
cxx=$1 src=$2 obj=$3 root=$4 common=$5

if [[ ! -x $cxx ]]; then
  echo "cross_check: arm-none-eabi-g++ not found ($cxx); install gcc-arm-none-eabi (scripts/deps/firmware.list)" >&2
  exit 1
fi
objdump=${cxx%g++}objdump
nm=${cxx%g++}nm

"$cxx" -std=c++20 -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 \
  -fno-exceptions -fno-rtti -ffreestanding -O2 \
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Wdouble-promotion -Werror \
  -I"$root" -I"$common" -c "$src" -o "$obj"
echo "compiled $(basename "$src") for cortex-m4 ($(stat -c %s "$obj") bytes)"

undefined=$("$nm" -u "$obj" | awk '{print $2}')
forbidden='^(_Znw|_Zna|_Zdl|_Zda|malloc$|calloc$|realloc$|free$|__cxa_throw$|__cxa_allocate_exception$|__cxa_begin_catch$|printf$|puts$|fwrite$|fputs$|__gxx_personality)'
bad=$(grep -E "$forbidden" <<<"$undefined" || true)
if [[ -n $bad ]]; then
  echo "cross_check: forbidden references in $(basename "$obj"):" >&2
  echo "$bad" >&2
  exit 1
fi

# The bodies of step() and its parts: from each label to the next function label.
step_body=$("$objdump" -dr -C "$obj" | awk '
  /^[0-9a-f]+ <.*>:$/ { in_step = ($0 ~ /DamperController<.*>::step(_[a-z]+)?\(/) }
  in_step { print }')
if [[ -z $step_body ]]; then
  echo "cross_check: no DamperController<...>::step in $(basename "$obj")" >&2
  exit 1
fi
if grep -q '__aeabi_d' <<<"$step_body"; then
  echo "cross_check: step() or a part of it uses double-precision soft float:" >&2
  grep '__aeabi_d' <<<"$step_body" >&2
  exit 1
fi
step_only=$("$objdump" -d -C "$obj" | awk '
  /^[0-9a-f]+ <.*>:$/ { in_step = ($0 ~ /DamperController<.*>::step\(/) }
  in_step { print }')
echo "step(): $(grep -cE '^\s+[0-9a-f]+:' <<<"$step_only") instructions of Thumb-2, no heap, no exceptions, no double"
