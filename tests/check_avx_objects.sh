#!/usr/bin/env bash
# Fails when an object built from a file that holds AVX2 code defines a weak (link-time shared) function whose code
# uses AVX: the linker keeps one copy of a weak function for the whole program, and if it keeps that one, a CPU
# without AVX2 crashes in code that never chose the AVX2 path. Arguments: ';'-separated lists of object files (CMake's
# $<TARGET_OBJECTS:...>); only the objects of files named *avx* are read.
set -euo pipefail
checked=0 failed=0
for list in "$@"; do
  IFS=';' read -r -a objects <<<"$list"
  for object in "${objects[@]}"; do
    case "$(basename "$object")" in *avx*) ;; *) continue ;; esac
    checked=$((checked + 1))
    # Weak definitions: W, V (weak) and u (unique global) in nm's letters.
    mapfile -t weak < <(nm --defined-only "$object" | awk '$2 ~ /^[WVu]$/ { print $3 }')
    [ ${#weak[@]} -eq 0 ] && continue
    for symbol in "${weak[@]}"; do
      # VEX-encoded instructions (every AVX instruction, and SSE ones when AVX is on) start with 'v'; ymm registers.
      if objdump -d --no-show-raw-insn --disassemble="$symbol" "$object" |
        awk 'NR > 7 && NF >= 2 { print $2 }' | grep -qE '^v|ymm'; then
        echo "$object: weak $(c++filt "$symbol") holds AVX code" >&2
        failed=$((failed + 1))
      fi
    done
  done
done
echo "checked $checked objects built from AVX2 files"
[ "$checked" -ge 2 ] || { echo "too few objects of AVX2 files found: is the list right?" >&2; exit 1; }
[ "$failed" -eq 0 ]
