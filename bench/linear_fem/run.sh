#!/usr/bin/env bash
# bench/linear_fem/run.sh — linear_fem validation, convergence and comparison
# runs (issue 21), one JSON summary per run (`shellbench run --summary json`,
# written by the run itself) under results/linear_fem/runs/; the report
# (results/linear_fem_report.md) is made from those files by
# bench/linear_fem/report.py, never by re-running.  A record that exists is
# skipped, so an interrupted sweep resumes (delete a record to redo it).
#
#   bash bench/linear_fem/run.sh [SHELLBENCH] [all|conv|cant|roll|cmp|rmtr|perf]
#
# conv  plates (clamped, simply supported) and Scordelis–Lo (linear regime)
#       for the three bending models (midedge with edge or averaged directors,
#       hinge) on alternate, jittered and regular meshes, --res 4 ... 64
# cant  heavy cantilever, Gamma = 1, 5, 20, 100 (master curve), --res 8, 16, 32
# roll  roll-up under an end moment (quarter, full ring; strip_end_moment, a three-quarter
#       ring), alternate and jittered meshes, --res 8, 16, 32 (+ 64 for edge directors)
# cmp   the same plates and Scordelis–Lo through bhem and rmtr (matched dofs; rmtr's roof with
#       method.beta_scale = 1e8)
# rmtr  the four RMTR-paper scenes with every solver (lsnewton, tr, damped,
#       linearized, rmtr on two levels)
# perf  bench_linear_fem (assembly / factorization per dof at ~25k dofs); in
#       `all` only when results/linear_fem/perf.md is missing
set -u
BIN=${1:-build/shellbench}
MODE=${2:-all}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/linear_fem/runs
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
export OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott}
SC=bench/scenes
BSC=bench/bhem/scenes

# run TAG METHOD SCENE SOLVER RES LEVELS [--set ...]
run() {
  local tag=$1 method=$2 scene=$3 solver=$4 res=$5 levels=$6; shift 6
  local f="$OUT/$tag.json"
  [ -s "$f" ] && return 0
  echo "== $tag" >&2
  "$BIN" run --scene "$scene" --method "$method" --solver "$solver" --res "$res" --levels "$levels" \
    --out none --summary json "$@" > "$f.tmp" 2> "$OUT/$tag.log"
  # keep the summary (converged or not); drop the progress lines before it
  if grep -q '^{' "$f.tmp"; then
    sed -n '/^{/,$p' "$f.tmp" > "$f"
    rm -f "$OUT/$tag.log"
  else
    echo "   no summary (see $OUT/$tag.log)" >&2
  fi
  rm -f "$f.tmp"
}

model_sets() {   # model -> --set arguments
  case $1 in
    edge) echo "--set method.bending=midedge --set method.director=edge" ;;
    average) echo "--set method.bending=midedge --set method.director=average" ;;
    hinge) echo "--set method.bending=hinge" ;;
  esac
}

if [ "$MODE" = all ] || [ "$MODE" = conv ]; then
  for scene in plate_clamped plate_simply_supported scordelis; do
    case $scene in
      scordelis) path=$BSC/scordelis_lo_linear.json; extra="--set run.gtol=1e-5" ;;
      *) path=$SC/$scene.json; extra="" ;;
    esac
    for model in edge average hinge; do
      for mesh in alternate jitter regular; do
        for r in 4 8 16 32 64; do
          # shellcheck disable=SC2046
          run "conv_${scene}_${model}_${mesh}_r$r" linear_fem "$path" lsnewton "$r" 1 \
            $(model_sets $model) --set method.mesh=$mesh $extra
        done
      done
    done
  done
fi

if [ "$MODE" = all ] || [ "$MODE" = cant ]; then
  for g in 1 5 20 100; do
    for model in edge average hinge; do
      for mesh in alternate jitter; do
        for r in 8 16 32; do
          ct=$((r / 8)); [ $mesh = jitter ] && [ $ct -lt 2 ] && ct=2   # jitter moves interior vertices only
          # shellcheck disable=SC2046
          run "cant_G${g}_${model}_${mesh}_r$r" linear_fem "$BSC/cantilever_G$g.json" lsnewton "$r" 1 \
            $(model_sets $model) --set method.mesh=$mesh --set method.cells_t=$ct
        done
      done
    done
  done
fi

if [ "$MODE" = all ] || [ "$MODE" = roll ]; then
  # quarter roll-up and strip_end_moment (a three-quarter ring since issue 21's review; its records
  # made against the old full-ring scene were deleted) on alternate and jittered meshes; jitter
  # needs interior vertices, so at least 2 cells across; the full ring: alternate, N x 1
  for model in edge average hinge; do
    for r in 8 16 32; do
      # shellcheck disable=SC2046
      run "roll_quarter_${model}_r$r" linear_fem "$BSC/rollup_quarter.json" lsnewton "$r" 1 $(model_sets $model) --set method.cells_t=1
      # shellcheck disable=SC2046
      run "roll_quarter_${model}_jitter_r$r" linear_fem "$BSC/rollup_quarter.json" lsnewton "$r" 1 $(model_sets $model) \
        --set method.mesh=jitter --set method.cells_t=2
      ct=$((r / 8)); [ $ct -lt 1 ] && ct=1
      cj=$ct; [ $cj -lt 2 ] && cj=2
      # shellcheck disable=SC2046
      run "strip_${model}_r$r" linear_fem "$SC/strip_end_moment.json" lsnewton "$r" 1 $(model_sets $model) --set method.cells_t=$ct
      # shellcheck disable=SC2046
      run "strip_${model}_jitter_r$r" linear_fem "$SC/strip_end_moment.json" lsnewton "$r" 1 $(model_sets $model) \
        --set method.mesh=jitter --set method.cells_t=$cj
    done
    for r in 16 32; do
      # shellcheck disable=SC2046
      run "roll_full_${model}_r$r" linear_fem "$BSC/rollup_full.json" lsnewton "$r" 1 $(model_sets $model) --set method.cells_t=1
    done
  done
  # the continuum's own answer: the thin-shell model (finite h/R, shared section law) ends about
  # 4e-4 L from the Euler-Bernoulli arc of the scene's reference; bhem at --res 32 (13k dofs) gives it
  run strip_bhem_r32 bhem "$SC/strip_end_moment.json" lsnewton 32 1
  # a fourth resolution for the converging model (edge directors)
  for mesh in alternate jitter; do
    # shellcheck disable=SC2046
    run "strip_edge$([ $mesh = jitter ] && echo _jitter)_r64" linear_fem "$SC/strip_end_moment.json" lsnewton 64 1 \
      $(model_sets edge) --set method.mesh=$mesh --set method.cells_t=8
  done
fi

if [ "$MODE" = all ] || [ "$MODE" = cmp ]; then
  for scene in plate_clamped plate_simply_supported scordelis; do
    case $scene in
      scordelis) path=$BSC/scordelis_lo_linear.json; extra="--set run.gtol=1e-5" ;;
      *) path=$SC/$scene.json; extra="" ;;
    esac
    for r in 2 4 8 16; do run "cmp_bhem_${scene}_r$r" bhem "$path" lsnewton "$r" 1 $extra; done
    # rmtr's penalty beta: the default (scaled to the paper's 1 m denim cloth) does not hold the
    # roof's boundary (E h = 1e8 N/m; 170 % error, penalty_violated at --res 4): the roof runs take
    # the factor the studies use (bench/studies/accuracy.json: method.beta_scale = 1e8)
    rset=""; [ $scene = scordelis ] && rset="--set method.beta_scale=1e8"
    # shellcheck disable=SC2086
    for r in 4 8 16 32; do run "cmp_rmtr_${scene}_r$r" rmtr "$path" lsnewton "$r" 1 $extra $rset; done
  done
fi

if [ "$MODE" = all ] || [ "$MODE" = rmtr ]; then
  for scene in trampoline drooping reentrant_corner drape; do
    for solver in lsnewton tr damped linearized rmtr; do
      levels=1
      [ "$solver" = rmtr ] && levels=2
      run "rmtr_${scene}_${solver}_r16" linear_fem "$scene" "$solver" 16 "$levels" --set run.max_iter=300
    done
    for model in average hinge; do
      # shellcheck disable=SC2046
      run "rmtr_${scene}_lsnewton_${model}_r16" linear_fem "$scene" lsnewton 16 1 $(model_sets $model) --set run.max_iter=300
    done
    for r in 4 8; do run "rmtr_${scene}_lsnewton_r$r" linear_fem "$scene" lsnewton "$r" 1 --set run.max_iter=300; done
    # the same scene through the other discretizations (bhem --res 8: 972 dofs, or 10 where the
    # notch needs it; rmtr --res 8: 363, --res 16: 1,083)
    rb=8; [ $scene = reentrant_corner ] && rb=10
    run "ref_${scene}_bhem_r$rb" bhem "$scene" lsnewton $rb 1 --set run.max_iter=300
    for r in 8 16; do run "ref_${scene}_rmtr_r$r" rmtr "$scene" lsnewton "$r" 1 --set run.max_iter=300; done
  done
  # denim's strain softening against a convex law: drooping with StVK
  for r in 8 16 32; do run "stvk_drooping_linear_fem_r$r" linear_fem bench/linear_fem/scenes/drooping_stvk.json lsnewton "$r" 1; done
  for r in 8 16; do run "stvk_drooping_bhem_r$r" bhem bench/linear_fem/scenes/drooping_stvk.json lsnewton "$r" 1; done
  for r in 8 16; do run "stvk_drooping_rmtr_r$r" rmtr bench/linear_fem/scenes/drooping_stvk.json lsnewton "$r" 1; done
fi

if [ "$MODE" = perf ] || { [ "$MODE" = all ] && [ ! -s results/linear_fem/perf.md ]; }; then
  B=$(dirname "$BIN")/bench/bench_linear_fem
  if [ -x "$B" ]; then
    # two repetitions on the shared machine; the ranges (min-max of the two) come first
    rm -f results/linear_fem/perf.md.tmp
    for k in 1 2; do
      { echo "### repetition $k of 2"; echo; "$B" 1.0; echo; } >> results/linear_fem/perf.md.tmp || exit 1
    done
    python3 bench/linear_fem/perf_range.py results/linear_fem/perf.md.tmp > results/linear_fem/perf.md \
      && rm -f results/linear_fem/perf.md.tmp
  else
    echo "no $B: run make bench first" >&2
  fi
fi

python3 bench/linear_fem/report.py results/linear_fem > results/linear_fem_report.md && echo "report: results/linear_fem_report.md"
