#!/usr/bin/env bash
# bench/sqrt3/dress.sh — the dress of the sqrt3 paper (Bender & Deul, Sec. 7,
# Fig. 10; issue 40): bench/scenes/dress.json (a circle skirt on a walking
# body of capsules, docs/sqrt3_dress.md) through adaptive_sqrt3, adaptive
# against full resolution, measured as the paper did: the cloth's speed-up
# (the step without collision handling and adaptation), the collision
# handling's (event collide: Bridson's impulses, at most 5 CCD passes, then
# rigid impact zones), the overall one, the adaptation's share, and the
# accuracy price (distance of the adaptive surface to the full one on an
# 11 x 11 material grid, bench/sqrt3/dress_series.py).
#
#   bash bench/sqrt3/dress.sh [SHELLBENCH] [small|large|small-series|large-series|others|floor|pictures]
#
#   small    (default) base mesh 6 x 28 cells (336 triangles), 6 generations
#            (full resolution 27 x: about 9,000 triangles), the whole 2 s; the
#            adaptive run with the scene's limits (5, 50 /m) and with the
#            method's defaults (2, 20 /m)
#   large    the paper's size: base 16 x 77 (2,464 triangles; full resolution
#            66,440 triangles against the paper's 66,636), 6 generations; in
#            pieces of PIECE steps (default 25) with checkpoints and --resume,
#            up to LARGE_STEPS steps (default 400 = the whole 2 s; a smaller
#            LARGE_STEPS bounds the run: the report says how many).  ONE_PIECE=1
#            stops after one piece; rerun the same command to continue; a
#            finished run is skipped.  ONLY=TAG runs one of the two
#            (dress-large-adaptive, dress-large-full), e.g. both side by side.
#   others   the scene with the other methods (linear_fem with both contact
#            models, bhem and rmtr with the barrier; the impulse model is
#            refused by bhem (self-contact) and rmtr (no response), recorded
#            as such), OTHER_STEPS steps (default 100)
#   floor    the accuracy floor: the small full-resolution run again with
#            E_s perturbed by 2e-8 of itself (method.Es=5000.0001), and its
#            distance to the unperturbed run (series_dress_floor.csv): how far
#            two runs of the same mesh drift apart on this scene by round-off-
#            sized causes alone (the walking skirt's contacts amplify them),
#            the floor under the adaptive run's accuracy price; needs the
#            small mode's dress-full record
#   small-series, large-series  the series (and the small runs' pictures)
#            from the records or, for runs stopped part-way, from their
#            checkpoints, as far as they got (run them while none of those
#            runs is running)
#   pictures only the missing pictures (from the records)
#
# Each run writes a JSON summary (results/sqrt3/runs/dress-*.json, committed)
# and its process CPU time (TAG.cpu, committed: the machine is shared, wall
# times are inflated by the load; the report gives both); records go to
# results/sqrt3/records/ (NOT committed: hundreds of MB at the paper's size).
# run.single_step_rtol=1e300: every linearized step is taken (the paper's
# linear implicit Euler; bench/sqrt3/run.sh does the same).
set -u
BIN=${1:-build/shellbench}
MODE=${2:-small}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/sqrt3
mkdir -p "$OUT/runs" "$OUT/records" "$OUT/images"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
PIECE=${PIECE:-25}
LARGE_STEPS=${LARGE_STEPS:-400}
OTHER_STEPS=${OTHER_STEPS:-100}

# a copy of the bundled scene with fewer steps and/or another contact model
# variant FILE NAME STEPS MODEL
variant() {
  python3 - "$@" <<'PY'
import json, sys
f, name, steps, model = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
d = json.load(open("bench/scenes/dress.json"))
d["name"] = name
d["time"]["steps"] = steps
d["contact"]["model"] = model
d["description"] = ("bench/sqrt3/dress.sh: bench/scenes/dress.json with %d steps and contact.model %s" % (steps, model))
json.dump(d, open(f, "w"), indent=1)
PY
}

# one_run TAG SCENE RECORD [options...]: the run (resumed when a checkpoint
# exists), its summary and its CPU seconds; skipped when the summary exists
one_run() {
  local tag=$1 scene=$2 rec=$3; shift 3
  local f="$OUT/runs/$tag.json"
  [ -s "$f" ] && return 0
  echo "== $tag" >&2
  local resume=()
  [ -e "$rec.partial" ] && resume=(--resume)
  /usr/bin/time -f "%U %S" -o "$OUT/runs/$tag.cpu.tmp" "$BIN" run --scene "$scene" "$@" "${resume[@]}" \
    --out "$rec" --summary json --quiet > "$f.tmp" 2> "$OUT/runs/$tag.log"
  local rc=$?
  # CPU seconds of every piece are summed (user + system)
  awk '{s += $1 + $2} END {printf "%.2f\n", s}' "$OUT/runs/$tag.cpu.tmp" >> "$OUT/runs/$tag.cpu.pieces"
  rm -f "$OUT/runs/$tag.cpu.tmp"
  if [ "$rc" = 4 ]; then rm -f "$f.tmp"; return 4; fi   # a piece ended with a checkpoint
  if grep -q '^{' "$f.tmp"; then
    sed -n '/^{/,$p' "$f.tmp" > "$f"
    awk '{s += $1} END {printf "%.2f\n", s}' "$OUT/runs/$tag.cpu.pieces" > "$OUT/runs/$tag.cpu"
    rm -f "$OUT/runs/$tag.log" "$OUT/runs/$tag.cpu.pieces"
  fi
  rm -f "$f.tmp"
  return 0
}

A3="--method adaptive_sqrt3 --solver linearized --samples 11 --set run.single_step_rtol=1e300"

# series TAG_FULL TAG_ADAPTIVE CSV: from the records, or from the checkpoints
# (.h5.partial) of runs stopped part-way (the large mode: the series then
# covers the steps both have done, and the report says so)
series() {
  local f="$OUT/records/$1.h5" a="$OUT/records/$2.h5"
  [ -s "$f" ] || f="$f.partial"
  [ -s "$a" ] || a="$a.partial"
  [ -s "$f" ] && [ -s "$a" ] || return 0
  python3 bench/sqrt3/dress_series.py "$f" "$a" --contact "${3%.csv}_contact.json" > "$3.tmp" && mv "$3.tmp" "$3"
}

# picture TAG SCENE STEP [run options]: a small PNG of the recorded surface at
# STEP (results/sqrt3/images/TAG-STEP.png), the body drawn at its pose
CAMERA="2.2,1.5,0.25,0,0,-0.35"
picture() {
  local tag=$1 scene=$2 step=$3; shift 3
  local png="$OUT/images/$tag-$step.png" rec="$OUT/records/$tag.h5"
  [ -s "$png" ] && return 0
  [ -s "$rec" ] || rec="$rec.partial"   # a run stopped part-way: its checkpoint
  if [ ! -s "$rec" ]; then
    echo "$tag: no record (results/sqrt3/records/$tag.h5); run the mode first" >&2
    return 0
  fi
  "$BIN" render "$rec" --step "$step" --camera "$CAMERA" --size 200x200 --spp 6 --out "$png" --quiet \
    || echo "$tag: render of step $step failed" >&2
}

# both small runs at 0.4 s (step 80), 1.15 s (230) and the last step both
# recorded (400, or less for runs stopped part-way: the series' last row)
pictures() {
  local last
  last=$(tail -n 1 "$OUT/series_dress.csv" 2> /dev/null | cut -d, -f1)
  for s in 80 230 ${last:-400}; do
    [ "$s" -gt 0 ] 2> /dev/null || continue
    picture dress-full dress $s
    picture dress-adaptive dress $s
  done
}

case "$MODE" in
small)
  # the scene's limits (methods.adaptive_sqrt3: l_base 5, l_gmax 50 /m) and
  # the method's defaults (2, 20 /m); ONLY=TAG runs one of the three
  for tag in ${ONLY:-dress-full dress-adaptive dress-adaptive-default}; do
    case $tag in
      dress-full) one_run $tag dress "$OUT/records/$tag.h5" $A3 --res 6x28 --set method.adaptive=0;;
      dress-adaptive) one_run $tag dress "$OUT/records/$tag.h5" $A3 --res 6x28 --set method.adaptive=1;;
      dress-adaptive-default) one_run $tag dress "$OUT/records/$tag.h5" $A3 --res 6x28 --set method.adaptive=1 \
        --set method.curv_base=2 --set method.curv_max=20;;
    esac
  done
  series dress-full dress-adaptive "$OUT/series_dress.csv"
  series dress-full dress-adaptive-default "$OUT/series_dress_default.csv"
  pictures
  ;;
large)
  SC="$OUT/dress_large.json"
  variant "$SC" dress_large "$LARGE_STEPS" impulse
  for tag in ${ONLY:-dress-large-adaptive dress-large-full}; do
    mode=1
    [ "$tag" = dress-large-full ] && mode=0
    # the steps done so far are kept in TAG.steps (pieces of PIECE steps)
    while [ ! -s "$OUT/runs/$tag.json" ]; do
      done_steps=$(cat "$OUT/runs/$tag.steps" 2> /dev/null || echo 0)
      stop=()
      [ $((done_steps + PIECE)) -lt "$LARGE_STEPS" ] && stop=(--stop-after-steps $((done_steps + PIECE)))
      one_run "$tag" "$SC" "$OUT/records/$tag.h5" $A3 --res 16x77 --set method.adaptive=$mode "${stop[@]}"
      rc=$?
      [ "$rc" = 4 ] || break
      echo $((done_steps + PIECE)) > "$OUT/runs/$tag.steps"
      [ -n "${ONE_PIECE:-}" ] && break   # ONE_PIECE=1: one piece per invocation
    done
    [ -s "$OUT/runs/$tag.json" ] && rm -f "$OUT/runs/$tag.steps"
  done
  series dress-large-full dress-large-adaptive "$OUT/series_dress_large.csv"
  for s in 80 230 400; do   # the pictures of both finished runs
    [ -s "$OUT/runs/dress-large-full.json" ] && picture dress-large-full dress_large $s
    [ -s "$OUT/runs/dress-large-adaptive.json" ] && picture dress-large-adaptive dress_large $s
  done
  ;;
small-series)   # the small runs' series and pictures as far as they got (stop them first)
  series dress-full dress-adaptive "$OUT/series_dress.csv"
  series dress-full dress-adaptive-default "$OUT/series_dress_default.csv"
  pictures
  ;;
large-series)   # the series of the large runs as far as they got (stop them first)
  series dress-large-full dress-large-adaptive "$OUT/series_dress_large.csv"
  ;;
others)
  SI="$OUT/dress_others_impulse.json" SB="$OUT/dress_others_barrier.json"
  variant "$SI" dress_others_impulse "$OTHER_STEPS" impulse
  variant "$SB" dress_others_barrier "$OTHER_STEPS" barrier
  one_run dress-lf-impulse "$SI" none --method linear_fem --solver linearized
  one_run dress-lf-impulse-lsnewton "$SI" none --method linear_fem --solver lsnewton
  one_run dress-lf-barrier "$SB" none --method linear_fem --solver lsnewton
  one_run dress-bhem-barrier "$SB" none --method bhem --solver lsnewton
  one_run dress-rmtr-barrier "$SB" none --method rmtr --solver lsnewton
  # refusals (the sentence is kept in the .log beside the empty summary)
  for m in bhem rmtr; do
    "$BIN" run --scene "$SI" --method $m --solver lsnewton --out none --quiet > /dev/null \
      2> "$OUT/runs/dress-$m-impulse.refused"
  done
  ;;
floor)
  one_run dress-full-perturbed dress "$OUT/records/dress-full-perturbed.h5" $A3 --res 6x28 --set method.adaptive=0 \
    --set method.Es=5000.0001
  series dress-full dress-full-perturbed "$OUT/series_dress_floor.csv"
  ;;
pictures)
  pictures
  ;;
*) echo "usage: bash bench/sqrt3/dress.sh [SHELLBENCH] [small|large|small-series|large-series|others|floor|pictures]" >&2; exit 2;;
esac
python3 bench/sqrt3/report.py "$OUT" > results/sqrt3_report.md
