#!/usr/bin/env bash
# bench/rmtr/krylov.sh — issue 38: RMTR with Krylov acceleration
# (solver.krylov=auto, docs/krylov.md) on the RMTR paper's Table 4 rows, and
# the penalty diagnostic of pcg-mg on the subdivision hierarchy.
#
#   bash bench/rmtr/krylov.sh [SHELLBENCH] [quick|large]
#   ONLY="rmtrdK-drape-l4 ..." bash bench/rmtr/krylov.sh build/shellbench large
#
# Table 4 rows: the defaults of run.sh's "ours" (records rmtrd-SCENE-lL, made
# by run.sh) with solver.krylov=auto beside them, records rmtrdK-SCENE-lL in
# results/rmtr/runs, same stopping rule, kernel and BLAS settings as run.sh
# (so the two differ only in the Krylov steps).  Each record is digested
# without its state (shellbench digest --drop-state, as
# scripts/digest_results.sh) as soon as it is finished.
#   quick: levels 2-3 on every scene, the trampoline to 5 levels, drooping 4
#          (about 10 min of one core)
#   large: + 4 and 5 levels on the hard scenes, 6 levels (51,483 dofs,
#          run.gtol 1e-6 as run.sh); the plain 5-level runs took 20-50 min,
#          6 levels 40-90 min each.
# Penalty diagnostic (results/rmtr/krylov_penalty.csv): CG iterations of the
# first Newton iteration of the trampoline's first step, lsnewton with
# solver.linear=pcg-mg|pcg-amg at a fixed rtol 1e-6 (cap 3,000), levels 2-5,
# with the scene's penalty beta (method.beta_scale=1) and with it scaled by
# 1e-3 and 1e-6.
set -u
BIN=${1:-build/shellbench}
MODE=${2:-quick}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/rmtr/runs
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
export OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott}   # as run.sh: reproducible counts on the nonconvex scenes
KERNEL=${KERNEL:-reference}
CAP=2000
KEEP="--set run.stop=paper --set run.penalty_tol=0"   # run.sh's stopping rule of the committed records

run() {   # run FILE SCENE RES LEVELS [--set ...]
  local f=$1 scene=$2 res=$3 lev=$4; shift 4
  case " ${ONLY:-$f} " in *" $f "*) ;; *) return ;; esac
  [ -f "$OUT/$f.h5" ] && { echo "kept  $f"; return; }
  local resume=()
  h5ls "$OUT/$f.h5.partial/resume" >/dev/null 2>&1 && resume=(--resume)
  nice -n 10 "$BIN" run --scene "$scene" --method rmtr --solver rmtr --res "$res" --levels "$lev" \
    --out "$OUT/$f.h5" --quiet --set run.max_iter=$CAP --set method.kernel=$KERNEL $KEEP "${resume[@]}" "$@"
  echo "exit $?  $f"
  [ -f "$OUT/$f.h5" ] && "$BIN" digest --drop-state "$OUT/$f.h5" >/dev/null   # as scripts/digest_results.sh
}

K="--set solver.krylov=auto"
for s in trampoline drooping reentrant_corner drape; do
  lv="2 3"
  [ "$s" = trampoline ] && lv="2 3 4 5"
  [ "$s" = drooping ] && lv="2 3 4"
  [ "$MODE" = large ] && lv="2 3 4 5"
  for l in $lv; do
    run "rmtrdK-$s-l$l" "$s" $((4 << (l - 1))) "$l" $K
  done
  [ "$MODE" = large ] && run "rmtrdK-$s-l6-gtol1e-6" "$s" 128 6 $K --set run.gtol=1e-6
done

# the penalty diagnostic (cheap: one Newton iteration per run)
CSV=results/rmtr/krylov_penalty.csv
if [ -z "${ONLY:-}" ] && [ ! -f "$CSV" ]; then
  T=$(mktemp -d)
  echo "linear,beta_scale,levels,dofs,cg_iterations,krylov_status" > "$CSV.tmp"
  for lin in pcg-mg pcg-amg; do
    for bs in 1 1e-3 1e-6; do
      for l in 2 3 4 5; do
        nice -n 10 "$BIN" run --scene tests/scenes/trampoline_1step.json --method rmtr --solver lsnewton \
          --res $((4 << (l - 1))) --levels "$l" --out "$T/p.h5" --quiet --set solver.linear=$lin \
          --set solver.cg_rtol=1e-6 --set solver.cg_max_iter=3000 --set run.max_iter=1 \
          --set method.beta_scale=$bs >/dev/null 2>&1
        python3 - "$T/p.h5" "$lin" "$bs" "$l" "$BIN" >> "$CSV.tmp" <<'EOF'
import csv, io, subprocess, sys
path, lin, bs, l, binary = sys.argv[1:]
def col(d):
    out = subprocess.run(["h5dump", "-d", "/history/iterations/" + d, "-y", "-w", "0", path],
                         capture_output=True, text=True).stdout
    body = out[out.find("DATA {") + 6:]
    return [float(v) for v in body[:body.find("}")].split(",") if v.strip()]
rep = subprocess.run([binary, "report", "--format", "csv", path], capture_output=True, text=True).stdout
dofs = next(csv.DictReader(io.StringIO(rep)))["dofs"]
it, st = col("linear_iters"), col("krylov_status")
print("%s,%s,%s,%s,%d,%d" % (lin, bs, l, dofs, it[1], st[1]))
EOF
      done
    done
  done
  mv "$CSV.tmp" "$CSV"
  rm -rf "$T"
  echo "penalty diagnostic: $CSV"
fi
python3 bench/rmtr/report.py "$OUT" > results/rmtr_report.md && echo "report: results/rmtr_report.md"
