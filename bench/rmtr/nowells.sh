#!/usr/bin/env bash
# bench/rmtr/nowells.sh — a diagnostic for issue 38's Table 4 goal: the RMTR
# paper's three hard scenes (drooping, re-entrant corner, drape) with the
# denim coupling halved, mu_21 = 0.5 instead of our reading of Table 1
# (mu_21 = 1), which leaves the law without energy below the flat sheet's
# (docs/denim.md "Energy below the reference state": with mu_21 = 1 the
# converged states lie 87-98 % in those wells; with mu_21 <= 0.5 the law has
# none, tests/test_stability.c).  Not the paper's material: it asks whether
# the wells are what makes the counts grow with the levels.
#
#   bash bench/rmtr/nowells.sh [SHELLBENCH] [LEVELS]      (default "2 3 4 5"; 6: run.gtol 1e-6)
#
# Runs, with run.sh's "ours" settings (stopping rule, kernel, BLAS) and with
# krylov.sh's solver.krylov=auto beside them, records rmtrd-SCENE-lL and
# rmtrdK-SCENE-lL in results/rmtr/nowells/ (not committed; an interrupted
# sweep resumes: finished records are kept), then writes
# results/rmtr/nowells.csv (committed; bench/rmtr/nowells_csv.py) and the
# RMTR report, whose section "Table 4 without the law's wells" reads it.
# Levels 2-4 take about 3 minutes of one core, 5 levels 5-20 minutes a run.
set -u
BIN=${1:-build/shellbench}
LEVELS=${2:-"2 3 4 5"}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/rmtr/nowells
mkdir -p "$OUT/scenes"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
export OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott}   # as run.sh: reproducible counts on the nonconvex scenes
KERNEL=${KERNEL:-reference}
SCENES="drooping reentrant_corner drape"

# the variant scenes: the paper's scene file with material.mu {"21": 0.5}
# and without its reference (a reference of the other law would not apply)
for s in $SCENES; do
  python3 - "bench/scenes/$s.json" "$OUT/scenes/${s}_mu21half.json" "$s" <<'EOF' || exit 2
import json, sys
src, dst, name = sys.argv[1:]
with open(src) as fh:
    d = json.load(fh)
d["name"] = name + "_mu21half"
d["description"] = ("diagnostic (bench/rmtr/nowells.sh): %s with the denim coupling halved, mu_21 = 0.5, "
                    "so that the law has no energy below the flat sheet's (docs/denim.md)" % name)
d["material"]["mu"] = {"21": 0.5}
d.pop("reference", None)
with open(dst + ".tmp", "w") as fh:
    json.dump(d, fh, indent=1)
EOF
  mv "$OUT/scenes/${s}_mu21half.json.tmp" "$OUT/scenes/${s}_mu21half.json"
done

run() {   # run FILE SCENE LEVELS [--set ...]
  local f=$1 s=$2 l=$3; shift 3
  [ -f "$OUT/$f.h5" ] && { echo "kept  $f"; return; }
  "$BIN" run --scene "$OUT/scenes/${s}_mu21half.json" --method rmtr --solver rmtr --res $((4 << (l - 1))) \
    --levels "$l" --out "$OUT/$f.h5" --quiet --set run.max_iter=40000 --set method.kernel=$KERNEL \
    --set run.stop=paper --set run.penalty_tol=0 "$@"
  echo "exit $?  $f"
}

for l in $LEVELS; do
  g=(); [ "$l" = 6 ] && g=(--set run.gtol=1e-6)   # the 6-level rows stop at run.gtol 1e-6, as run.sh's
  for s in $SCENES; do
    run "rmtrd-$s-l$l" "$s" "$l" "${g[@]}"
    run "rmtrdK-$s-l$l" "$s" "$l" --set solver.krylov=auto "${g[@]}"
  done
done
python3 bench/rmtr/nowells_csv.py "$BIN" "$OUT" > results/rmtr/nowells.csv.tmp &&
  mv results/rmtr/nowells.csv.tmp results/rmtr/nowells.csv && echo "table: results/rmtr/nowells.csv"
python3 bench/rmtr/report.py > results/rmtr_report.md && echo "report: results/rmtr_report.md"
