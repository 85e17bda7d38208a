#!/usr/bin/env bash
# bench/bhem/fem_compare.sh — the BHEM paper's comparisons with triangle FEM
# (Figs. 14-17, issue 39): bhem (exact and pseudo Hessian) beside linear_fem
# on randomly triangulated (jitter) meshes, on the wrinkled sheet and the
# draped cloth.
#
#   bash bench/bhem/fem_compare.sh [SHELLBENCH] [wrinkle|drape|large|all] [--max-runs N]
#
# Every run: `shellbench run --summary json --out TAG.h5` under
# results/bhem/fem/, its process CPU seconds (TAG.cpu, from /usr/bin/time:
# the 2-core machine is shared, so the records' wall seconds are not a
# measure), then bench/bhem/fem_stats.py reduces the record to TAG.stats.json
# (per-step iterations and seconds, wrinkle statistics or the drape's height
# field on a 41 x 41 grid) and, for the drape, `shellbench render` draws
# TAG.png.  The .h5 records are not committed (large); the .json, .cpu,
# .stats.json and .png are, and bench/bhem/report.py makes its FEM sections
# from them only.  A run whose TAG.stats.json exists is skipped (resume).
#
# linear_fem stands in for libshell (Vouga 2021), which the paper used:
# midedge bending with one director per edge (method.director=edge) is
# libshell's MidedgeAngleTanFormulation (Chen et al. 2018) up to tan against
# the angle itself (docs/linear_fem.md); it converges to Kirchhoff-Love on
# jittered meshes, where the averaged-director and hinge models do not.
#
# "large" is the FEM wrinkle amplitude toward the paper's 130k vertices
# (Fig. 17): 320x128 (41k vertices), 480x192 (93k) and 570x228 (130k);
# each needs more than 20 CPU-minutes on this machine: run them one at a
# time with --max-runs 1 (each call does the next missing one).  A run
# stopped part way goes on from its checkpoint (FILE.h5.partial, written
# every run.checkpoint = 300 s) when the script is called again; the CPU
# seconds of a piece that was killed are not counted.
set -u
BIN=${1:-build/shellbench}
MODE=${2:-all}
MAX_RUNS=1000000
[ "${3:-}" = --max-runs ] && MAX_RUNS=${4:-1}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/bhem/fem
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=1
export OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott}
SC=bench/bhem/scenes
PROFILE=build/bench/bhem/surface_profile
make -s "$PROFILE" >/dev/null 2>&1 || { echo "cannot build $PROFILE" >&2; exit 1; }
done_runs=0

# run TAG KIND SCENE METHOD RES [--set ...]: KIND wrinkle|drape
run() {
  local tag=$1 kind=$2 scene=$3 method=$4 res=$5; shift 5
  [ -s "$OUT/$tag.stats.json" ] && return 0
  if [ -s "$OUT/$tag.cpu" ] && [ -s "$OUT/$tag.h5" ] && grep -q '"status"' "$OUT/$tag.json" 2>/dev/null; then
    echo "== $tag: run finished earlier, reducing it" >&2   # (its script was stopped after the run)
  else
    [ "$done_runs" -ge "$MAX_RUNS" ] && return 0
    done_runs=$((done_runs + 1))
    # a run stopped earlier goes on from its checkpoint (written every
    # run.checkpoint seconds); its CPU seconds add up across the pieces
    local resume=() cpu0="0 0"
    if [ -s "$OUT/$tag.h5.partial" ]; then
      resume=(--resume)
      [ -s "$OUT/$tag.cpu" ] && cpu0=$(tail -n 1 "$OUT/$tag.cpu")
    fi
    echo "== $tag: $method $scene --res $res $* ${resume[*]}" >&2
    /usr/bin/time -f '%U %S' -o "$OUT/$tag.cpu.new" \
      "$BIN" run --scene "$scene" --method "$method" --solver lsnewton --res "$res" --out "$OUT/$tag.h5" \
      --summary json "${resume[@]}" "$@" > "$OUT/$tag.json" 2>> "$OUT/$tag.log"
    echo "   exit $?" >&2
    # user and system seconds of every piece so far, one line
    echo "$cpu0 $(tail -n 1 "$OUT/$tag.cpu.new")" | awk '{ printf "%.2f %.2f\n", $1 + $3, $2 + $4 }' > "$OUT/$tag.cpu"
    rm -f "$OUT/$tag.cpu.new"
  fi
  # the profile tool takes the run's method options (not the solver's)
  local sets=() a prev=
  for a in "$@"; do
    [ "$prev" = --set ] && case $a in method.*|run.seed=*) sets+=("$a");; esac
    prev=$a
  done
  local n=${res%%x*} nt=101 ns=101
  [ "$kind" = wrinkle ] && nt=401
  case $res in *x*) sets+=("method.cells_t=${res##*x}");; esac
  "$PROFILE" "$method" "$scene" "$OUT/$tag.h5" "$n" "$ns" "$nt" "${sets[@]}" > "$OUT/$tag.profile.csv" 2>> "$OUT/$tag.log"
  python3 bench/bhem/fem_stats.py "$kind" "$OUT/$tag.h5" "$OUT/$tag.profile.csv" "$OUT/$tag.cpu" > "$OUT/$tag.stats.json.tmp" &&
    mv "$OUT/$tag.stats.json.tmp" "$OUT/$tag.stats.json"
  rm -f "$OUT/$tag.profile.csv"
  if [ "$kind" = drape ]; then
    "$BIN" render "$OUT/$tag.h5" --size 200x150 --spp 4 --out "$OUT/$tag.png" --quiet 2>> "$OUT/$tag.log" ||
      echo "$tag: not drawn" >&2
  fi
}

IMP="--set method.imperfection=1e-6"
FEM="--set method.mesh=jitter --set method.bending=midedge --set method.director=edge"

# (order: what the report needs first, in case a session ends before the rest)
wrinkle() {
  for r in 10 15 20; do
    run w_bhem_e_r$r wrinkle $SC/wrinkled_sheet.json bhem $r $IMP
    run w_bhem_p_r$r wrinkle $SC/wrinkled_sheet.json bhem $r $IMP --set method.hessian=pseudo
  done
  # cells_t = 0.4 N: near-isotropic triangles on the 0.25 m x 0.1 m sheet
  for r in 40x16 80x32 120x48 160x64; do
    run w_fem_r${r%%x*} wrinkle $SC/wrinkled_sheet.json linear_fem $r $IMP $FEM
  done
  run w_bhem_e_r30 wrinkle $SC/wrinkled_sheet.json bhem 30 $IMP
  run w_bhem_p_r30 wrinkle $SC/wrinkled_sheet.json bhem 30 $IMP --set method.hessian=pseudo
  run w_fem_r240 wrinkle $SC/wrinkled_sheet.json linear_fem 240x96 $IMP $FEM
}
# The pinned corners are point constraints: the membrane strain under them
# is singular (it grows without bound with the resolution), and bhem at 10^2
# passes the default run.strain_max = 1 there at step 30.  The drape runs
# lift the bound (run.strain_max=0, recorded; their summaries give the max
# strain) since the comparison is about the cloth away from the corners.
NOBOUND="--set run.strain_max=0"
drape() {
  for r in 5 10 20; do
    run d_bhem_e_r$r drape $SC/draped_cloth_pinned.json bhem $r $NOBOUND
  done
  # about 500, 1k, 2k and 4k vertices (the paper's Fig. 15 columns)
  for r in 21 31; do
    run d_fem_r$r drape $SC/draped_cloth_pinned.json linear_fem $r $NOBOUND $FEM
  done
  run d_bhem_e_r30 drape $SC/draped_cloth_pinned.json bhem 30 $NOBOUND
  for r in 44 63; do
    run d_fem_r$r drape $SC/draped_cloth_pinned.json linear_fem $r $NOBOUND $FEM
  done
  run d_bhem_p_r30 drape $SC/draped_cloth_pinned.json bhem 30 $NOBOUND --set method.hessian=pseudo
}
large() {
  for r in 320x128 480x192 570x228; do
    run w_fem_r${r%%x*} wrinkle $SC/wrinkled_sheet.json linear_fem $r $IMP $FEM
  done
}
case $MODE in
  wrinkle) wrinkle ;;
  drape) drape ;;
  large) large ;;
  all) wrinkle; drape ;;
  *) echo "mode: wrinkle, drape, large or all" >&2; exit 2 ;;
esac
