#!/usr/bin/env bash
# Cross-compiles one source of the idle-time estimator, the mixing scheduler
# or the mixing task for a bare-metal Cortex-M4F and checks the object:
# warning-free with -fno-exceptions -fno-rtti -ffreestanding, and no reference
# to the heap (operator new/delete, malloc, free), exception machinery or stdio.
#
# MODE double (the reference build, soft-float on the M4): only the above.
# MODE strict (the float and fixed builds), as strict as the control core's
# check (core_cross_check.sh):
#   - also -Wdouble-promotion;
#   - the per-tick functions (step, predicted_capacity, volume_to_ceiling,
#     note_mixing_confirmed, plan_for) and every function of the object they
#     call, transitively, call no double-precision soft-float routine
#     (__aeabi_d*, __aeabi_*2d) and no double libm function (exp, log, ceil,
#     llround, …): the M4's FPU is single precision. init(), boot() and
#     save() may convert the double configuration and are not part of a tick.
# Usage: idle_cross_check.sh ARM_GXX SOURCE OBJECT SOURCE_ROOT COMMON_INCLUDE_DIR [double|strict]
set -euo pipefail
cxx=$1 src=$2 obj=$3 root=$4 common=$5 mode=${6:-double}

if [[ ! -x $cxx ]]; then
  echo "idle_cross_check: arm-none-eabi-g++ not found ($cxx); install gcc-arm-none-eabi (scripts/deps/firmware.list)" >&2
  exit 1
fi
nm=${cxx%g++}nm
objdump=${cxx%g++}objdump
cxxfilt=${cxx%g++}c++filt
extra=()
[[ $mode == strict ]] && extra=(-Wdouble-promotion)

"$cxx" -std=c++20 -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 \
  -fno-exceptions -fno-rtti -ffreestanding -O2 \
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion "${extra[@]}" -Werror \
  -I"$root" -I"$common" -c "$src" -o "$obj"
echo "compiled $(basename "$src") for cortex-m4 ($(stat -c %s "$obj") bytes, $mode)"

undefined=$("$nm" -u "$obj" | awk '{print $2}')
forbidden='^(_Znw|_Zna|_Zdl|_Zda|malloc$|calloc$|realloc$|free$|__cxa_throw$|__cxa_allocate_exception$|__cxa_begin_catch$|printf$|puts$|fwrite$|fputs$|__gxx_personality|open$|read$|write$)'
bad=$(grep -E "$forbidden" <<<"$undefined" || true)
if [[ -n $bad ]]; then
  echo "idle_cross_check: forbidden references in $(basename "$obj"):" >&2
  echo "$bad" >&2
  exit 1
fi
echo "no heap, no exceptions, no stdio"
[[ $mode == strict ]] || exit 0

# Call graph of the object (mangled names): "F name" for each function,
# "S section name" for its section, "E caller callee" for each call or tail
# call (by relocation or by a direct branch to a label).
graph=$("$objdump" -dr "$obj" | awk '
  /^Disassembly of section / { sec = $4; sub(/:$/, "", sec) }
  /^[0-9a-f]+ <[^>]+>:$/ { fn = $2; gsub(/^<|>:$/, "", fn); print "F", fn; print "S", sec, fn; next }
  fn != "" && /R_ARM_THM_(CALL|JUMP24|JUMP19)/ { print "E", fn, $NF; next }
  fn != "" && /\t(bl|b\.w|b)\t/ && /<[^>+]+(\+0x[0-9a-f]+)?>/ {
    t = $0; sub(/.*</, "", t); sub(/(\+0x[0-9a-f]+)?>.*/, "", t); if (t != fn) print "E", fn, t }')
roots=$(awk '$1 == "F" { print $2 }' <<<"$graph" | while read -r f; do
  if "$cxxfilt" "$f" | grep -qE '::(step|predicted_capacity|volume_to_ceiling|note_mixing_confirmed|plan_for)\('; then
    echo "$f"
  fi
done)
if [[ -z $roots ]]; then
  echo "idle_cross_check: no per-tick function (step, ...) in $(basename "$obj")" >&2
  exit 1
fi
# Reachable set: a callee that names a section stands for every function in it.
reached=$(awk -v roots="$roots" '
  $1 == "E" { edges[$2] = edges[$2] " " $3 }
  $1 == "S" { members[$2] = members[$2] " " $3 }
  END {
    n = split(roots, q, "\n"); for (i = 1; i <= n; ++i) seen[q[i]] = 1
    head = 1
    while (head <= n) {
      f = q[head++]
      m = split(edges[f], cs, " ")
      for (j = 1; j <= m; ++j) {
        c = cs[j]
        if (c in members) { k = split(members[c], ms, " "); for (l = 1; l <= k; ++l) if (!(ms[l] in seen)) { seen[ms[l]] = 1; q[++n] = ms[l] } }
        if (!(c in seen)) { seen[c] = 1; q[++n] = c }
      }
    }
    for (f in seen) print f
  }' <<<"$graph")
double_calls=$(grep -E '^(__aeabi_(d[a-z0-9]*|cd[a-z0-9]*|[a-z0-9]*2d)|exp|log|log2|sqrt|ceil|floor|round|llround|lround|fabs|pow|fmod)$' <<<"$reached" || true)
if [[ -n $double_calls ]]; then
  echo "idle_cross_check: the per-tick functions of $(basename "$obj") reach double arithmetic:" >&2
  echo "$double_calls" >&2
  exit 1
fi
count=$(wc -l <<<"$reached")
echo "per-tick functions and their $count callees: no double-precision soft float, no double libm"
