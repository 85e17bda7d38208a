#!/usr/bin/env bash
# bench/rmtr/mgstrip.sh — issue 38, docs/krylov.md "Why: the penalty defeats
# the V-cycle": two-grid CG counts on the trampoline's first Newton system
# (rmtr method), plain, with an exact solve on the penalty's support (the
# "strip") inside the cycle, with the energy-minimizing coarse space
# P' = (I - Z H_SS^-1 Z^T H) P, and with both; and the plain cycle with the
# penalty scaled by 1e-6 (build/bench/bench_mgstrip, dense: minutes at 3,675
# dofs).
#
#   bash bench/rmtr/mgstrip.sh [BENCH_MGSTRIP]      -> results/rmtr/mgstrip.csv
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
B=${1:-build/bench/bench_mgstrip}
export OPENBLAS_NUM_THREADS=1 OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott} SB_ROOT=$ROOT
OUT=results/rmtr/mgstrip.csv
TMP=$OUT.tmp
hdr=header
for a in "8 2 0" "16 3 1" "16 3 0" "32 4 2"; do
  set -- $a
  "$B" trampoline "$1" "$2" "$3" strip=pen tag=scene $hdr >> "$TMP" || echo "failed: $a" >&2
  hdr=
  "$B" trampoline "$1" "$2" "$3" method.beta_scale=1e-6 tag=beta_x1e-6 >> "$TMP" || echo "failed: $a beta" >&2
done
mv "$TMP" "$OUT" && echo "wrote $OUT"
