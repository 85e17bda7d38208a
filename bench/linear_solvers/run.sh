#!/bin/bash
# bench/linear_solvers/run.sh [N [FILTER]] — makes up to N (default all) of
# the runs of bench/studies/linear_solvers_large.json (SB_STUDY: another
# study of the same records, e.g. linear_solvers_1e6.json) that have no record
# yet, one at a time, each as its own `shellbench run` process (the study's
# plan, its resolutions and record paths from `sweep --plan`; the same
# parameters the sweep would set: run.max_iter and the varied solver.* keys), and
# appends each run's CPU seconds to results/linear_solvers/cpu_seconds.csv.
# FILTER (a grep -E pattern on the plan line) picks runs, e.g. 'L5.*pcg-mg'.
#
# Why not `sweep` itself: a sweep forks its runs from a process that has
# set every method up to count dofs, and a forked child's peak resident
# size (VmHWM, the records' peak_rss) counts the parent's pages it inherits
# (about 140 MB here: a 13k-dof run recorded 140 MB); the records hold wall
# seconds only, which on a shared machine carry the load, and /usr/bin/time
# around a sweep would count its planning too.  A record made here is the
# record the sweep would make (`sweep --study ... --plan` lists it as
# recorded; `sweep` resumes around it).
set -u
cd "$(dirname "$0")/../.."
STUDY=${SB_STUDY:-bench/studies/linear_solvers_large.json}   # or linear_solvers_1e6.json (the same records directory)
N=${1:-1000}
FILTER=${2:-.}
BIN=${SB_BIN:-build/shellbench}
CSV=results/linear_solvers/cpu_seconds.csv
MAXITER=$(python3 -c "import json; print(json.load(open('$STUDY'))['set']['run.max_iter'])")
mkdir -p results/linear_solvers
[ -s "$CSV" ] || echo "record,user_s,sys_s,maxrss_kb,wall_s,exit,finished_utc" > "$CSV"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$BIN" sweep --study "$STUDY" --plan > "$tmp/plan" || exit 2
declare -A SCENE=([trampoline_s2]=bench/scaling/scenes/trampoline_s2.json [drape_s2]=bench/scaling/scenes/drape_s2.json
                  [plate_clamped]=plate_clamped)
done_n=0
# a plan line: SCENE METHOD/SOLVER Ln VARIANT... res R DOFS dofs start S OUT [(recorded) | skip ...]; each
# VARIANT k=v is the study's "vary" key ending in .k (solver.linear, solver.mg_cycle)
while read -r -a F; do
  i=3
  while [ "$i" -lt "${#F[@]}" ] && [ "${F[$i]}" != res ]; do i=$((i + 1)); done
  [ $((i + 7)) -eq "${#F[@]}" ] || continue               # "(recorded)", a refusal or a skip
  sc=${F[0]}; ms=${F[1]}; lv=${F[2]}; res=${F[$((i + 1))]}; out=${F[$((i + 6))]}
  variants=("${F[@]:3:$((i - 3))}")
  [ -e "$out" ] || [ -e "${out%.h5}.h5.refused" ] && continue
  echo "$sc $ms $lv ${variants[*]} $res" | grep -qE "$FILTER" || continue
  [ "$done_n" -ge "$N" ] && break
  m=${ms%/*}; s=${ms#*/}
  sets=()
  for v in "${variants[@]}"; do sets+=(--set "solver.${v%%=*}=${v#*=}"); done
  echo "run: $sc $m $s ${lv#L} levels ${variants[*]} res $res -> $out"
  /usr/bin/time -f "%U,%S,%M,%e" -o "$tmp/t" nice -n 10 "$BIN" run --scene "${SCENE[$sc]:-$sc}" --method "$m" \
      --solver "$s" --res "$res" --levels "${lv#L}" --set "run.max_iter=$MAXITER" "${sets[@]}" --out "$out" \
      --quiet < /dev/null
  rc=$?
  [ -e "$out" ] && echo "${out#results/linear_solvers/},$(tail -1 "$tmp/t"),$rc,$(date -u +%FT%TZ)" >> "$CSV"
  done_n=$((done_n + 1))
done < "$tmp/plan"
echo "made $done_n runs"
