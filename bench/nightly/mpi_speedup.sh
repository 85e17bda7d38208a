#!/usr/bin/env bash
# The speedup of an MPI sweep with 1, 2 and 4 ranks (docs/regression.md
# "Distributed sweeps"): the study bench/nightly/speedup.json swept from
# scratch serially (sweep --jobs 1) and under mpirun -n 1, 2, 4, each into a
# fresh directory; wall time of each, the sum of the runs' own seconds and the
# longest run (the bounds of the makespan), the machine's load before each.
# ROUNDS (default 3) interleaved rounds of the four sweeps; the table has the
# minimum and the median wall time of each (a shared machine's noise only
# ever adds time: the minimum is the least disturbed).
# Writes results/nightly/mpi_speedup.md.  Usage: bash bench/nightly/mpi_speedup.sh [build/shellbench]
set -euo pipefail
BIN=${1:-build/shellbench}
STUDY=bench/nightly/speedup.json
OUT=results/nightly/mpi_speedup.md
BASE=results/nightly/speedup
export OPENBLAS_NUM_THREADS=1 OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott}
command -v mpirun >/dev/null || { echo "mpi_speedup: mpirun not found (bash scripts/ensure_deps.sh)"; exit 2; }
[ -x "$(dirname "$BIN")/shellbench-mpi" ] || { echo "mpi_speedup: no $(dirname "$BIN")/shellbench-mpi (built when mpicc is found)"; exit 2; }
MPIRUN="mpirun --allow-run-as-root --oversubscribe"
now() { date +%s.%N; }
ROUNDS=${ROUNDS:-3}
declare -A WALL LOAD TIMES
sweep() {   # name, command...
  local name=$1; shift
  rm -rf "${BASE:?}/$name"
  local l; l=$(cut -d' ' -f1 /proc/loadavg)
  LOAD[$name]="${LOAD[$name]:+${LOAD[$name]} }$l"
  local t0; t0=$(now)
  "$@" --study "$STUDY" --dir "$BASE/$name" --quiet > "$BASE-$name.log" 2>&1
  local w; w=$(echo "$(now) - $t0" | bc -l)
  TIMES[$name]="${TIMES[$name]:+${TIMES[$name]} }$w"
  echo "$name: $w s (load $l)"
}
mkdir -p "$BASE"
for r in $(seq "$ROUNDS"); do
  sweep serial "$BIN" sweep --jobs 1
  sweep n1 $MPIRUN -n 1 "$BIN" sweep
  sweep n2 $MPIRUN -n 2 "$BIN" sweep
  sweep n4 $MPIRUN -n 4 "$BIN" sweep
done
declare -A MED
for n in serial n1 n2 n4; do
  read -r WALL[$n] MED[$n] < <(echo "${TIMES[$n]}" | tr ' ' '\n' | sort -g | awk '{a[NR]=$1} END {print a[1], a[int((NR+1)/2)]}')
done
# the runs' own seconds (seconds_total) from the serial records
read -r SUM LONGEST NRUNS < <("$BIN" report --format csv "$BASE"/serial/*/*.h5 | python3 -c '
import csv, sys
rows = list(csv.DictReader(sys.stdin))
s = [float(r["seconds"]) for r in rows]
print(f"{sum(s):.2f} {max(s):.2f} {len(s)}")')
CORES=$(nproc)
{
  echo "# MPI sweep speedup (bench/nightly/mpi_speedup.sh)"
  echo
  echo "Study \`$STUDY\`: $NRUNS runs; build \`$("$BIN" --version | cut -d' ' -f2)\`, $(date -u +%Y-%m-%dT%H:%MZ), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $CORES cores, shared with other work (load average before each sweep in the table)."
  echo "Sum of the runs' own seconds (serial records): $SUM s; longest run: $LONGEST s; the rest of the serial"
  echo "sweep's wall time is per-run overhead (process start, scene and method set-up, writing and syncing the record)."
  BOUND=$(echo "m = $SUM / $CORES; if ($LONGEST > m) m = $LONGEST; m" | bc -l)
  printf 'Lower bound of the makespan on %d idle cores, max(longest run, sum / cores): %.1f s (best speedup over the fastest serial sweep about %.1f).\n' \
    "$CORES" "$BOUND" "$(echo "${WALL[serial]} / $BOUND" | bc -l)"
  echo
  echo "$ROUNDS interleaved rounds; speedups from the minimum wall times."
  echo
  echo "| sweep | wall s, min | median | speedup vs serial | vs mpirun -n 1 | load before each round |"
  echo "|---|--:|--:|--:|--:|--:|"
  for n in serial n1 n2 n4; do
    label=$([ $n = serial ] && echo "sweep --jobs 1" || echo "mpirun -n ${n#n}")
    printf '| %s | %.1f | %.1f | %.2f | %.2f | %s |\n' "$label" "${WALL[$n]}" "${MED[$n]}" \
      "$(echo "${WALL[serial]} / ${WALL[$n]}" | bc -l)" "$(echo "${WALL[n1]} / ${WALL[$n]}" | bc -l)" "${LOAD[$n]}"
  done
} > "$OUT"
cat "$OUT"
