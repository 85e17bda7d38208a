#!/usr/bin/env bash
# bench/bhem/run_bench.sh — BHEM validation and paper-scene runs (issue 4).
#
#   bash bench/bhem/run_bench.sh [SHELLBENCH] [quick]
#
# Runs every case once through `shellbench run --summary json --out FILE.h5`
# and keeps, per run, the HDF5 record and the JSON summary under
# results/bhem/runs/.  The report (results/bhem_report.md) is then generated
# from those files by bench/bhem/report.py — never by re-running.
# "quick" skips the 30x30 paper scenes and the RMTR-scene sweep;
# "rmtr-scenes" runs only that sweep (and its pictures); "rmtr-pictures" only
# draws the missing pictures of the RMTR-paper scenes (below).
set -u
BIN=${1:-build/shellbench}
MODE=${2:-full}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/bhem/runs
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
# OpenBLAS's generic x86-64 kernels unless set: the same round-off on every
# x86-64 machine, so counts on the nonconvex scenes reproduce (docs/reproducibility.md)
export OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott}   # not the environment's: some machines preset another set
SC=bench/bhem/scenes

# the profile tool reads /final/x of a record (wrinkle statistics)
LIB=${LIB:-build/libshellbench.a}
if [ -e "$LIB" ]; then
  cc -std=c11 -O2 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE $(for d in core/*/; do printf -- "-I%s " "$d"; done) -I/usr/include/suitesparse \
     $(pkg-config --cflags hdf5-serial jansson gsl) -fopenmp bench/bhem/bhem_profile.c "$LIB" -o "$OUT/../bhem_profile" \
     -lcholmod -lsuitesparseconfig $(pkg-config --libs hdf5-serial jansson gsl) -llapack -lblas -losdCPU -lstdc++ -lm || true
fi

# the reference shell kernel (per point, the arithmetic results/bhem_report.md
# was made with; docs/reproducibility.md); KERNEL=fast for the default one
KERNEL=${KERNEL:-reference}

# run TAG SCENE SOLVER RES [--set ...]: one run, summary to $OUT/TAG.json
run() {
  local tag=$1 scene=$2 solver=$3 res=$4; shift 4
  echo "== $tag: $scene $solver --res $res $*" >&2
  "$BIN" run --scene "$scene" --method bhem --solver "$solver" --res "$res" --out "$OUT/$tag.h5" \
    --summary json --set method.kernel=$KERNEL "$@" > "$OUT/$tag.json" 2> "$OUT/$tag.log"
  echo "   exit $?" >&2
}

# picture TAG SCENE SOLVER RES [--set ...]: the final state of run TAG as a
# small PNG, results/bhem/images/TAG.png (240x180, 8 samples per pixel,
# committed; the report shows it).  Drawn from the run's record when it is
# there, else (the RMTR-scene records are not committed) from the same run
# made again into a temporary record.  A picture that exists is kept.
picture() {
  local tag=$1 scene=$2 solver=$3 res=$4; shift 4
  local png=results/bhem/images/$tag.png rec=$OUT/$tag.h5 tmp=
  [ -s "$png" ] && return 0
  mkdir -p results/bhem/images
  if [ ! -s "$rec" ]; then
    tmp=$(mktemp -d)
    rec=$tmp/$tag.h5
    echo "== $tag (rerun for its picture)" >&2
    "$BIN" run --scene "$scene" --method bhem --solver "$solver" --res "$res" --out "$rec" --quiet \
      --set method.kernel=$KERNEL "$@" > /dev/null 2>&1
  fi
  "$BIN" render "$rec" --size 240x180 --spp 8 --out "$png" --quiet || echo "$tag: not drawn" >&2
  [ -n "$tmp" ] && rm -rf "$tmp"
  return 0
}

# one picture per RMTR-paper scene: its finest converged lsnewton run (the
# re-entrant corner converges at none: its smallest run, stopped at step 1)
rmtr_pictures() {
  picture rmtr_trampoline_lsnewton_r16 trampoline lsnewton 16 --set run.max_iter=300
  picture rmtr_drooping_lsnewton_r8 drooping lsnewton 8 --set run.max_iter=300
  picture rmtr_drape_lsnewton_r8 drape lsnewton 8 --set run.max_iter=300
  picture rmtr_reentrant_corner_lsnewton_r10 reentrant_corner lsnewton 10 --set run.max_iter=300
}
if [ "$MODE" = rmtr-pictures ]; then rmtr_pictures; exit 0; fi

# MODE rmtr-scenes: only the four RMTR-paper scenes (last section)
if [ "$MODE" != rmtr-scenes ]; then
# ---- validation ----------------------------------------------------------
for r in 2 4 8 16; do
  run plate_clamped_r$r $SC/plate_clamped.json lsnewton $r
  run plate_ss_r$r $SC/plate_simply_supported.json lsnewton $r
  run scordelis_r$r $SC/scordelis_lo_linear.json lsnewton $r --set run.gtol=1e-5
done
run scordelis_full_r16 $SC/scordelis_lo.json lsnewton 16
for g in 1 5 20 100; do
  for r in 8 16 32; do
    run cantilever_G${g}_r$r $SC/cantilever_G$g.json lsnewton $r --set method.cells_t=1
  done
done
for r in 8 16; do
  run rollup_quarter_r$r $SC/rollup_quarter.json lsnewton $r --set method.cells_t=1
  run rollup_full_r$r $SC/rollup_full.json lsnewton $r --set method.cells_t=1
done
run rollup_quarter_tr_r16 $SC/rollup_quarter.json tr 16 --set method.cells_t=1

[ "$MODE" = quick ] && exit 0

# ---- paper scenes ----------------------------------------------------------
for r in 10 15 20 30; do
  run wrinkled_r$r $SC/wrinkled_sheet.json lsnewton $r --set method.imperfection=1e-6
done
run wrinkled_tr_r15 $SC/wrinkled_sheet.json tr 15 --set method.imperfection=1e-6
run wrinkled_pseudo_r15 $SC/wrinkled_sheet.json lsnewton 15 --set method.imperfection=1e-6 --set method.hessian=pseudo
run twisting_r30 $SC/twisting_cloth.json lsnewton 30
run draped_r30 $SC/draped_cloth.json lsnewton 30
fi

# ---- the four RMTR-paper scenes (denim, dt = 1 s), capped iterations -------
for s in trampoline drooping drape; do
  for solver in lsnewton tr; do
    for r in 4 8 16 32; do
      run rmtr_${s}_${solver}_r$r $s $solver $r --set run.max_iter=300
    done
  done
done
for solver in lsnewton tr; do            # notch at 0.3: resolutions divisible by 10
  for r in 10 20 30; do
    run rmtr_reentrant_corner_${solver}_r$r reentrant_corner $solver $r --set run.max_iter=300
  done
done
rmtr_pictures
