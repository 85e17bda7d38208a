#!/usr/bin/env bash
# bench/scaling/supernodes.sh — issue 42's factorization-rate goal: CHOLMOD's
# numeric factorization at >= 1e5 dofs against the one-core DGEMM rate, with
# CHOLMOD's default supernodes and with run.supernodes=wide (both on huge
# pages, sb_cholmod_alloc.c).  The simply supported plate with lsnewton (one
# load step, three factorizations of one pattern), one BLAS thread.
#
#   bash bench/scaling/supernodes.sh [OUTDIR]     # default results/scaling_supernodes
#
# A record that exists is kept (delete it to run again).  The report is
# bench/scaling/report.py's section "run.supernodes" of results/scaling_large.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BIN=${SHELLBENCH:-$ROOT/build/shellbench}
OUT=${1:-$ROOT/results/scaling_supernodes}
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=1
for mr in "bhem 128" "linear_fem 192" "rmtr 320" "bhem 320" "linear_fem 384"; do
  set -- $mr
  for sn in cholmod wide; do
    rec="$OUT/$1-$sn-r$2.h5"
    [ -f "$rec" ] && continue
    echo "supernodes: $1 --res $2 run.supernodes=$sn" >&2
    "$BIN" run --scene plate_simply_supported --method "$1" --solver lsnewton --res "$2" \
      --set run.supernodes=$sn --out "$rec" --quiet
  done
done
