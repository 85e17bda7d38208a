#!/usr/bin/env bash
# bench/scaling/supernode_profile.sh — issue 42's factorization-rate goal:
# for the plate and trampoline Hessians of the large study's rate runs, the
# supernode profile and the dense-kernel ceiling of CHOLMOD's rate
# (build/bench/bench_supernodes: the rate CHOLMOD could reach if every
# supernode ran at the dense kernels' speed for its shape) beside the rate
# achieved, one CSV per configuration under OUTDIR.
#
#   bash bench/scaling/supernode_profile.sh [OUTDIR] [small|large]
#
# OUTDIR defaults to results/scaling_large/supernodes; "small" (the default)
# does the 2e5-3e5-dof sizes (a minute each), "large" adds the 1e6-dof ones
# (up to 10 GB and a few minutes each).  A CSV that exists is kept.  The
# report is bench/scaling/report.py's section "What bounds the rate".
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=${1:-results/scaling_large/supernodes}
MODE=${2:-small}
BIN=build/bench/bench_supernodes
make -s "$BIN" >/dev/null
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=1
# "SCENE METHOD RES [KEY=VALUE]": the wide variant is run.supernodes=wide (sb_linsolve.c)
specs=("plate_simply_supported bhem 128" "plate_simply_supported linear_fem 192" "plate_simply_supported rmtr 320"
       "bench/scaling/scenes/trampoline_s2.json bhem 128" "bench/scaling/scenes/trampoline_s2.json linear_fem 192"
       "plate_simply_supported linear_fem 192 run.supernodes=wide" "plate_simply_supported bhem 128 run.supernodes=wide")
[ "$MODE" = large ] && specs+=("plate_simply_supported linear_fem 384" "plate_simply_supported bhem 320"
                              "plate_simply_supported rmtr 576")
for s in "${specs[@]}"; do
  set -- $s
  name=$(basename "$1" .json)-$2-r$3
  [ -n "${4:-}" ] && name=$name-${4##*=}
  [ -s "$OUT/$name.csv" ] && continue
  echo "supernode profile: $name" >&2
  "$BIN" "$@" > "$OUT/$name.csv.tmp" && mv "$OUT/$name.csv.tmp" "$OUT/$name.csv"
done
