#!/usr/bin/env bash
# The main job (`make run`): the default study (bench/studies/default.json)
# over every registered discretization and the main solvers, sized to finish
# in about 5 minutes on 2 cores; records under results/default/, then
# results/default/report.md with the method-selection table first, the
# work-precision diagrams, performance profiles, the scenes with several
# solutions and the convergence plots (docs/study.md).  Resumable: run it
# again after an interruption and only the missing runs are made.
set -uo pipefail
BIN=${1:-build/shellbench}
STUDY=${SB_DEFAULT_STUDY:-bench/studies/default.json}
OUT=${SB_DEFAULT_OUT:-results/default}
JOBS=${SB_JOBS:-2}
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
# OpenBLAS's generic x86-64 kernels unless set: the same round-off on every
# x86-64 machine, so counts on the nonconvex scenes reproduce (docs/reproducibility.md)
export OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott}   # not the environment's: some machines preset another set

echo "default study: $("$BIN" list methods | awk '$0 !~ /TEST FIXTURE/ {printf "%s ", $1}')(every registered method), $JOBS jobs"
start=$(date +%s)
"$BIN" sweep --study "$STUDY" --dir "$OUT" --jobs "$JOBS"
rc=$?
if [ $rc -ne 0 ] && [ $rc -ne 1 ]; then
  echo "default study: sweep exit $rc (records kept; run again to continue)" >&2
fi
"$BIN" report --study "$STUDY" --dir "$OUT" --out "$OUT"
# the same as a static site (docs/site.md): open $OUT/site/index.html in a browser
"$BIN" site --study "$STUDY" --dir "$OUT" --report "$OUT/report.md" --out "$OUT/site" || echo "default study: the site was not written (above)" >&2
echo
echo "records: $OUT/<scene>/*.h5   report: $OUT/report.md   site: $OUT/site/index.html   ($(( $(date +%s) - start )) s)"
exit $rc
