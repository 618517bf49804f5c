#!/usr/bin/env bash
# The rule of an AVX-512 region (src/core/network/avx512_region.h), checked on
# the objects the build made: a function whose code uses AVX registers (ymm,
# zmm) and which the linker can see from other files (a global or weak
# symbol) must be one of the region's entry points. Anything else would be a
# symbol the linker may hand to baseline callers, and a CPU without AVX-512
# would stop on it. Usage: region_symbols.sh LIBRARY.a (the core's static
# library; its *_avx512.cpp.o members are read, and there must be some).
set -euo pipefail
library=$(realpath "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
ar x "$library"
set -- ./*_avx512.cpp.o
entry='^neurocloth::(spring_forces_avx512|spring_outputs_avx512|spring_forces_adjoint_avx512)\('
read_any=0
bad=0
for obj in "$@"; do
  [ -f "$obj" ] || continue
  read_any=1
  # Functions with AVX registers in their code (demangled names).
  avx=$(objdump -dC --no-show-raw-insn "$obj" |
    awk '/^[0-9a-f]+ <.*>:$/ { sub(/^[0-9a-f]+ </, ""); sub(/>:$/, ""); name = $0; next }
         /%[yz]mm/ && name != "" { print name; name = "" }' | sort -u)
  # Symbols other objects can bind to.
  visible=$(nm -C --defined-only "$obj" | awk '$2 ~ /^[TWVu]$/ { $1 = ""; $2 = ""; sub(/^  /, ""); print }' | sort -u)
  while IFS= read -r name; do
    [ -n "$name" ] || continue
    if grep -qxF -- "$name" <<<"$visible" && ! grep -qE -- "$entry" <<<"$name"; then
      echo "$obj: '$name' uses AVX registers and is visible to other files" >&2
      bad=1
    fi
  done <<<"$avx"
  entries=$(grep -cE -- "$entry" <<<"$visible" || true)
  if [ "$entries" -lt 1 ]; then
    echo "$obj: no entry point found: the check would read nothing" >&2
    bad=1
  fi
  echo "$obj: $(wc -l <<<"$avx") functions with AVX registers, $entries entry points visible"
done
[ "$read_any" = 1 ] || { echo "no *_avx512.cpp.o in $library" >&2; exit 1; }
exit "$bad"
