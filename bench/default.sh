#!/usr/bin/env bash
# The main job (`make run`): the RMTR paper's four scenes and the plate
# validation through every registered discretization and the main solvers, at
# a resolution that finishes in a few minutes on 2 cores; one HDF5 record per
# run under results/default/, then a Markdown report and a convergence plot.
set -uo pipefail
BIN=${1:-build/shellbench}
OUT=${SB_DEFAULT_OUT:-results/default}
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
# OpenBLAS's generic x86-64 kernels unless set: the same round-off on every
# x86-64 machine, so counts on the nonconvex scenes reproduce (docs/reproducibility.md)
export OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott}   # not the environment's: some machines preset another set

methods=$("$BIN" list methods | awk '$0 !~ /TEST FIXTURE/ {print $1}')
if [ -z "$methods" ]; then
  echo "default benchmark: no discretization registered yet; running the test fixture instead" >&2
  methods=fixture_membrane
fi
scenes="trampoline drooping reentrant_corner drape plate_clamped"
files=()
for m in $methods; do
  hier=$("$BIN" list methods | awk -v m="$m" '$1 == m && /\[hierarchy\]/ {print 1}')
  for s in $scenes; do
    case "$m:$s" in
      rmtr:*) res=8 ;;                 # 363 dofs on the 1 m square (paper level 2)
      bhem:reentrant_corner) res=10 ;; # the 0.3 m notch needs a multiple of 10 patches
      bhem:*) res=8 ;;                 # 8 x 8 Hermite patches
      *) res=16 ;;
    esac
    for solver in lsnewton tr rmtr; do
      levels=1
      if [ "$solver" = rmtr ]; then
        [ -n "$hier" ] || continue
        [ "$m:$s" = bhem:reentrant_corner ] && continue   # 10 patches do not halve onto the notch
        levels=2
      fi
      f="$OUT/$s-$m-$solver-r$res-l$levels.h5"
      "$BIN" run --scene "$s" --method "$m" --solver "$solver" --res "$res" --levels "$levels" \
        --out "$f" --quiet --set run.max_iter=500
      rc=$?
      printf '%-60s exit %d\n' "$f" "$rc"
      [ -f "$f" ] && files+=("$f")
    done
  done
done
echo
"$BIN" report --plot "$OUT/convergence.png" "${files[@]}" | tee "$OUT/report.md"
# one readable plot per scene as well
for s in $scenes; do
  sf=()
  for f in "${files[@]}"; do case "$(basename "$f")" in "$s"-*) sf+=("$f") ;; esac; done
  [ ${#sf[@]} -gt 0 ] && "$BIN" report --plot "$OUT/convergence-$s.png" "${sf[@]}" > /dev/null
done
echo
echo "records: $OUT/*.h5   report: $OUT/report.md   plots: $OUT/convergence.png, $OUT/convergence-SCENE.png"
