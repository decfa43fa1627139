#!/bin/sh
# Verifies with objdump that the batched penalty kernel is vectorised: its AVX2 clone must do
# its arithmetic on packed 256-bit registers (ymm, 4 doubles), its AVX-512 clone on zmm and the
# baseline clone on packed SSE2 (xmm, 2 doubles). Usage: check... OBJDUMP LIBRARY
set -eu
objdump=$1
library=$2
symbol=penaltyTriangleDistanceBatch
listing=$("$objdump" -d --no-show-raw-insn -C "$library")

# Instructions of one clone: from its label to the next label.
clone() {
  printf '%s\n' "$listing" | awk -v want="$1" '
    /^[0-9a-f]+ <.*>:$/ { inside = (index($0, "'"$symbol"'") > 0 && index($0, want) > 0) ; next }
    inside { print }'
}
packed() {  # packed double arithmetic (add, sub, mul, div, fma, sqrt) on register class $1
  grep -Ec "v?(v?f[n]?m(add|sub)[0-9]*|add|sub|mul|div|sqrt)pd[[:space:]].*%$1" || true
}

avx2=$(clone "arch_x86_64_v3" | packed ymm)
avx512=$(clone "arch_x86_64_v4" | packed zmm)
sse2=$(clone "[clone .default]" | packed xmm)
echo "packed double arithmetic in $symbol: AVX2 clone $avx2 (ymm), AVX-512 clone $avx512 (zmm), baseline clone $sse2 (xmm)"
status=0
[ "$avx2" -ge 50 ] || { echo "FAIL: AVX2 clone not vectorised"; status=1; }
[ "$avx512" -ge 50 ] || { echo "FAIL: AVX-512 clone not vectorised"; status=1; }
[ "$sse2" -ge 50 ] || { echo "FAIL: baseline clone not vectorised"; status=1; }
exit $status
