#!/usr/bin/env bash
# bench/rmtr/cond_split.sh — issue 43, Fig. 9: which energy term sets each
# extreme eigenvalue of H = M/dt^2 + K_mem + K_bend + K_pen, and how each
# grows with the dofs (bench_cond parts ... split: K_el split into membrane
# and bending by its thickness dependence at the same x, the Rayleigh
# quotients of H's extreme eigenvectors per term; bench/bench_cond.c).
#
#   bash bench/rmtr/cond_split.sh [BENCH_COND] [MAX_RES]   -> results/rmtr/cond_split.csv
#
# Two states of the trampoline's first step (dt = 1 s, the scene as stated):
#   converged  H at the converged first step (what cond.sh measures)
#   initial    H at the step's initial iterate, the flat unstretched cloth:
#              the paper does not say at which x Fig. 9 takes H
# Dense (LAPACK, every eigenvector; also the lowest mode of the cloth itself,
# "smooth") to 1,083 dofs, Lanczos Ritz vectors above.
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
COND=${1:-build/bench/bench_cond}
MAX=${2:-128}
export OPENBLAS_NUM_THREADS=1 OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott} SB_ROOT=$ROOT
OUT=results/rmtr/cond_split.csv
TMP=$OUT.tmp
: > "$TMP"
hdr=header
one() { "$COND" parts "$@" $hdr >> "$TMP" || echo "failed: $*" >&2; hdr=; }
for r in 4 8 16 32 64 128; do [ "$r" -le "$MAX" ] || continue
  one trampoline "$r" tag=converged split only=H
  [ "$r" -le 64 ] && one trampoline "$r" tag=initial split only=H state=initial
done
mv "$TMP" "$OUT" && echo "wrote $OUT"
