#!/usr/bin/env bash
# bench/sqrt3/run.sh — the curtain of the sqrt3 paper (Bender & Deul, Sec. 7;
# bench/scenes/curtain.json) through adaptive_sqrt3, adaptive against full
# resolution (issue 22).  Base mesh 8 x 12 cells (192 triangles), at most 4
# sqrt3 generations (full resolution: 9 x 192 = 1728 triangles; the paper's 6
# generations, 27 x, would make the full run too long for the bench), the
# paper's E_s = 1000 N/m, dt = 5 ms, 20 s; the curtain hangs to 5 s, opens by
# 11 s and closes by 17 s (the scene's schedule, as the paper's Fig. 8); then
# cloth over a sphere (below).  Each run writes a JSON summary
# (small, committed) and an HDF5 record (results/sqrt3/records/, NOT
# committed: tens of MB each, ~76 MB for the adaptive run, with the per-step sample grid); distance.py reads
# the records (h5dump) into results/sqrt3/series.csv, and report.py writes
# results/sqrt3_report.md and results/sqrt3/fig8.png from the summaries and
# that CSV, never by re-running.  A summary that exists is skipped.  The
# last step and the open state (11 s) of three runs are drawn into
# results/sqrt3/images/ (small PNGs, committed; `picture` below).
#
#   bash bench/sqrt3/run.sh [SHELLBENCH] [pictures|paper|convergence]
#
# `pictures`: only the missing pictures and the report (no runs, no series).
# `paper`: the curtain at the paper's setting (issue 40; below): 6
# generations on a 16 x 26 base mesh, full resolution 22,464 triangles
# (the paper's 22,140 = 27 x 820 base triangles is not reachable: the hooks
# every 1/8 m need 8k columns, and 16 x 26 is the nearest), adaptive and
# full resolution, each in pieces of PAPER_PIECE steps (default 1000, about
# 4 CPU-minutes of the full run on this machine) continued with --resume;
# PAPER_MAX_PIECES (default: all) bounds the pieces run by one call, so a
# user runs it in parts.  Then the series and the report.  `convergence`:
# the study bench/studies/accuracy_sqrt3.json (below).
#
# run.single_step_rtol=1e300: the paper takes every linearized step; the
# suite's default judgement (docs/trust.md) would stop a run at the first
# step whose residual after the step exceeds half its initial one.
set -u
BIN=${1:-build/shellbench}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/sqrt3
mkdir -p "$OUT/runs" "$OUT/records"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}

# run TAG [--set ...]
run() {
  local tag=$1; shift
  local f="$OUT/runs/$tag.json"
  [ -s "$f" ] && return 0
  echo "== $tag" >&2
  "$BIN" run --scene curtain --method adaptive_sqrt3 --solver linearized --res 8x12 --samples 11 \
    --set method.Es=1000 --set method.max_generation=4 --set run.single_step_rtol=1e300 \
    --out "$OUT/records/$tag.h5" --summary json --quiet "$@" > "$f.tmp" 2> "$OUT/runs/$tag.log"
  if grep -q '^{' "$f.tmp"; then sed -n '/^{/,$p' "$f.tmp" > "$f"; rm -f "$OUT/runs/$tag.log"; fi
  rm -f "$f.tmp"
}

# runp TAG [--set ...]: the curtain at the paper's setting in pieces
# (--stop-after-steps, exit 4, then --resume from TAG.h5.partial); the
# summary is kept when the run finishes.  Issue 40.  run.checkpoint=3000:
# with the default 300 a step's end writes a checkpoint whenever the last is
# 30 s old, and each rewrites the record so far (every step's sample grid and
# mesh): measured on the committed pieces under load, 26 % of the adaptive
# run's wall time (57 checkpoints, 11.6 s each) and 11 % of the full run's;
# run.checkpoint may differ between pieces (docs/running.md), so the pieces
# already run continue with it.
runp() {
  local tag=$1; shift
  local f="$OUT/runs/$tag.json" piece=${PAPER_PIECE:-1000} max=${PAPER_MAX_PIECES:-1000000} n=0 k rc resume
  [ -s "$f" ] && return 0
  k=$piece
  if [ -e "$OUT/records/$tag.h5.partial" ]; then   # the step it stopped after, from the checkpoint's history
    local done_steps
    done_steps=$(h5dump -H "$OUT/records/$tag.h5.partial" 2> /dev/null |
                 awk '/DATASET "t"/{f=1} f&&/DATASPACE/{gsub(/[(),]/," "); print $4; exit}')
    [ -n "$done_steps" ] && k=$(( (done_steps / piece + 1) * piece ))
  fi
  while [ "$n" -lt "$max" ]; do
    resume=""
    [ -e "$OUT/records/$tag.h5.partial" ] && resume=--resume
    echo "== $tag (to step $k)" >&2
    "$BIN" run --scene curtain --method adaptive_sqrt3 --solver linearized --res 16x26 --samples 11 \
      --set method.Es=1000 --set method.max_generation=6 --set run.single_step_rtol=1e300 --set run.checkpoint=3000 \
      --out "$OUT/records/$tag.h5" --summary json --quiet --stop-after-steps "$k" $resume "$@" > "$f.tmp" \
      2> "$OUT/runs/$tag.log"
    rc=$?
    n=$((n + 1))
    if [ "$rc" != 4 ]; then
      if grep -q '^{' "$f.tmp"; then sed -n '/^{/,$p' "$f.tmp" > "$f"; rm -f "$OUT/runs/$tag.log"; fi
      break
    fi
    k=$((k + piece))
  done
  rm -f "$f.tmp"
}
# Convergence under refinement (issue 40): bench/studies/accuracy_sqrt3.json
# (its own study: sweep, report --study, digests committed); its records' errors
# extracted to a small CSV for the sqrt3 report's order fit.
if [ "${2:-}" = convergence ]; then
  "$BIN" sweep --study bench/studies/accuracy_sqrt3.json --jobs 1 &&
    "$BIN" report --study bench/studies/accuracy_sqrt3.json &&
    "$BIN" report --format csv results/accuracy_sqrt3/*/*.h5 > "$OUT/convergence.csv"
  python3 bench/sqrt3/report.py "$OUT" > results/sqrt3_report.md
  exit 0
fi
if [ "${2:-}" = paper ]; then
  runp curtain-paper-adaptive --set method.adaptive=1
  runp curtain-paper-full --set method.adaptive=0
  # a full run not finished (PAPER_MAX_PIECES): its checkpoint's summary
  # (committed, small) and the series over the steps it has done
  for t in curtain-paper-full curtain-paper-adaptive; do
    rm -f "$OUT/runs/$t.partial.json"
    if [ ! -s "$OUT/runs/$t.json" ] && [ -e "$OUT/records/$t.h5.partial" ]; then
      python3 bench/sqrt3/partial_summary.py "$OUT/records/$t.h5.partial" > "$OUT/runs/$t.partial.json"
    fi
  done
  if [ -e "$OUT/records/curtain-paper-adaptive.h5" ] || [ -e "$OUT/records/curtain-paper-adaptive.h5.partial" ]; then
    python3 bench/sqrt3/distance.py "$OUT" --full curtain-paper-adaptive --diag 1.802775638 --triangles \
      > "$OUT/series_curtain_paper_adaptive.csv"   # the adaptive run alone: its whole run (columns *_full)
  fi
  if [ -e "$OUT/records/curtain-paper-adaptive.h5" -o -e "$OUT/records/curtain-paper-adaptive.h5.partial" ] &&
     [ -e "$OUT/records/curtain-paper-full.h5" -o -e "$OUT/records/curtain-paper-full.h5.partial" ]; then
    python3 bench/sqrt3/distance.py "$OUT" --full curtain-paper-full --diag 1.802775638 --triangles \
      adaptive=curtain-paper-adaptive > "$OUT/series_curtain_paper.csv"
  fi
  python3 bench/sqrt3/report.py "$OUT" > results/sqrt3_report.md
  exit 0
fi

# The runs and their series; not in `pictures` mode (which must not touch
# them: without the records, distance.py would empty the committed series).
if [ "${2:-}" != pictures ]; then
run curtain-adaptive-cholmod --set method.adaptive=1
run curtain-full-cholmod --set method.adaptive=0
# a looser criterion (Eq. 23 limits 5 and 50 /m instead of 2 and 20): the speed / accuracy trade-off
run curtain-adaptive-loose-cholmod --set method.adaptive=1 --set method.curv_base=5 --set method.curv_max=50
run curtain-adaptive-pcg --set method.adaptive=1 --set solver.linear=pcg
# the full resolution with the paper's PCG too: CG iterations per step on the
# full against the adaptive mesh (issue 40, "where the factor 2 goes")
run curtain-full-pcg --set method.adaptive=0 --set solver.linear=pcg
# the paper's 6 generations on a coarser base mesh, 8 x 6 cells (96 triangles;
# full resolution 27 x 96 = 2592 triangles): later options override the
# earlier ones (--res, method.max_generation)
run curtain-g6-adaptive-cholmod --res 8x6 --set method.max_generation=6 --set method.adaptive=1
run curtain-g6-full-cholmod --res 8x6 --set method.max_generation=6 --set method.adaptive=0

# Cloth over a sphere (sqrt3 paper Sec. 7, Fig. 9; issue 25): the bundled
# cloth_sphere (res 8 base mesh, 128 triangles) run for 2 s instead of 0.3 s
# so that the cloth drapes and wrinkles, the paper's 6 generations (full
# resolution 27 x 128 = 3456 triangles), contact by the barrier with the
# linearized solver (docs/contact.md "The linearized solver": one Newton step
# per time step with the barrier's and the lagged friction's derivatives,
# shortened by the step filter; every step taken, as above).  Three
# criteria: the default limits (2, 20 /m) and two looser ones.
CS="$OUT/cloth_sphere_2s.json"
[ -s "$CS" ] || python3 - "$CS" <<'PY'
import json, sys
d = json.load(open("bench/scenes/cloth_sphere.json"))
d["name"] = "cloth_sphere_2s"
d["time"]["steps"] = 200
d["description"] = ("bench/sqrt3: bench/scenes/cloth_sphere.json run for 2 s (200 steps) instead of 0.3 s, so that "
                    "the cloth drapes over the sphere and wrinkles (sqrt3 paper Fig. 9); written by bench/sqrt3/run.sh.")
json.dump(d, open(sys.argv[1], "w"), indent=1)
PY
# runcs TAG REPEAT [--set ...]: repeat 1 writes the record, repeats 2 and 3
# (TAG.r2, TAG.r3, no record) only time the run again: the report takes the
# fastest of the three, the machine being shared and loaded
runcs() {
  local tag=$1 rep=$2; shift 2
  local name=$tag out="$OUT/records/$tag.h5"
  [ "$rep" -gt 1 ] && name=$tag.r$rep && out=none
  local f="$OUT/runs/$name.json"
  [ -s "$f" ] && return 0
  echo "== $name" >&2
  "$BIN" run --scene "$CS" --method adaptive_sqrt3 --solver linearized --samples 11 \
    --set run.single_step_rtol=1e300 \
    --out "$out" --summary json --quiet "$@" > "$f.tmp" 2> "$OUT/runs/$name.log"
  if grep -q '^{' "$f.tmp"; then sed -n '/^{/,$p' "$f.tmp" > "$f"; rm -f "$OUT/runs/$name.log"; fi
  rm -f "$f.tmp"
}
for rep in 1 2 3; do
  runcs cs-full $rep --set method.adaptive=0
  runcs cs-adaptive $rep --set method.adaptive=1
  runcs cs-adaptive-loose $rep --set method.adaptive=1 --set method.curv_base=5 --set method.curv_max=50
  runcs cs-adaptive-looser $rep --set method.adaptive=1 --set method.curv_base=10 --set method.curv_max=100
  # issue 40: l_base above the sphere's own |c| = 2/r = 13.3 /m (Eq. 22 is
  # 2H), so that the smooth wrapped cap alone refines nothing; l_gmax 10 x
  # l_base as in the default
  runcs cs-adaptive-above $rep --set method.adaptive=1 --set method.curv_base=14 --set method.curv_max=140
done

python3 bench/sqrt3/distance.py "$OUT" > "$OUT/series.csv"
python3 bench/sqrt3/distance.py "$OUT" --full curtain-g6-full-cholmod --diag 1.802775638 \
  adaptive=curtain-g6-adaptive-cholmod > "$OUT/series_curtain_g6.csv"
python3 bench/sqrt3/distance.py "$OUT" --full cs-full --diag 0.848528137 adaptive=cs-adaptive loose=cs-adaptive-loose \
  looser=cs-adaptive-looser above=cs-adaptive-above > "$OUT/series_cloth_sphere.csv"
fi   # runs and series
# picture TAG [--set ...]: run TAG as two small PNGs (240x180 at 8 samples
# per pixel, committed; the report shows them): results/sqrt3/images/TAG.png,
# its last step (20 s, the curtain closed again), and TAG-open.png, step
# OPEN_STEP (11 s, the hooks fully gathered by the scene's schedule).  Drawn
# with `render --step K`, the recorded surface of step K: an adaptive
# record's final state does not rebuild from the base mesh (its /final/x has
# the adapted mesh's dofs).  From the run's record; when the record is gone
# (records are not committed) the same command is run again into a
# temporary record first, its summary discarded.  A picture that exists is
# kept (delete it to redraw).
#
# The curtain hangs in the x-y plane along -y, so it is seen from the front:
# from +z straight down the z axis (for which the renderer takes +y as up),
# 3.6 m away (the vertical field of view of 30 degrees then spans 1.93 m),
# the target at x = -0.1 so that the curtain (x in [0, 1], y in [0, 1.5])
# lies right of the labels.  The picture's ground plane, under the lowest z,
# is a wall behind it.
OPEN_STEP=2200   # 11 s / dt 5 ms
CAMERA="-0.1,0.68,3.6,-0.1,0.68,0"
picture() {
  local tag=$1; shift
  local png="$OUT/images/$tag.png" open="$OUT/images/$tag-open.png"
  local rec="$OUT/records/$tag.h5" log="$OUT/images/$tag.log"
  [ -s "$png" ] && [ -s "$open" ] && return 0
  mkdir -p "$OUT/images"
  local last
  last=$(python3 -c 'import json, sys; t = open(sys.argv[1]).read(); print(json.loads(t[t.index("{"):])["steps"])' \
         "$OUT/runs/$tag.json" 2> /dev/null) || { echo "$tag: no summary, no picture" >&2; return 0; }
  if [ ! -s "$rec" ]; then
    echo "== $tag (rerun for its pictures)" >&2
    rec="$OUT/records/$tag.picture.h5"
    "$BIN" run --scene curtain --method adaptive_sqrt3 --solver linearized --res 8x12 --samples 11 \
      --set method.Es=1000 --set method.max_generation=4 --set run.single_step_rtol=1e300 \
      --out "$rec" --quiet "$@" > /dev/null 2> "$log"
  fi
  local ok=1
  [ -s "$png" ] || "$BIN" render "$rec" --step "$last" --camera "$CAMERA" --size 240x180 --spp 8 --out "$png" \
    --quiet 2>> "$log" || ok=0
  if [ "$last" -ge "$OPEN_STEP" ] && [ ! -s "$open" ]; then
    "$BIN" render "$rec" --step "$OPEN_STEP" --camera "$CAMERA" --size 240x180 --spp 8 --out "$open" \
      --quiet 2>> "$log" || ok=0
  fi
  [ "$ok" = 1 ] && rm -f "$log"
  case "$rec" in *.picture.h5) rm -f "${rec%.h5}".*;; esac
  return 0
}

ADAPTIVE="--set method.adaptive=1"
FULL="--set method.adaptive=0"
PCG="--set method.adaptive=1 --set solver.linear=pcg"
# a looser criterion (Eq. 23 limits 5 and 50 /m instead of 2 and 20): the speed / accuracy trade-off
LOOSE="--set method.adaptive=1 --set method.curv_base=5 --set method.curv_max=50"
if [ "${2:-}" != pictures ]; then
  run curtain-adaptive-cholmod $ADAPTIVE
  run curtain-full-cholmod $FULL
  run curtain-adaptive-pcg $PCG
  run curtain-adaptive-loose-cholmod $LOOSE
fi
# pictures (the PCG run solves the same steps as the CHOLMOD one: not drawn)
picture curtain-adaptive-cholmod $ADAPTIVE
picture curtain-full-cholmod $FULL
picture curtain-adaptive-loose-cholmod $LOOSE
[ "${2:-}" != pictures ] && python3 bench/sqrt3/distance.py "$OUT" > "$OUT/series.csv"
python3 bench/sqrt3/report.py "$OUT" > results/sqrt3_report.md
