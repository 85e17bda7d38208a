#!/usr/bin/env bash
# bench/bhem/ccd.sh — BHEM's needle scene (paper Fig. 4) with bhem under its
# own collision pipeline (contact.model = "impulse": §5.2 dynamic ray–patch
# CCD, §6.2 impulse response; bench/bhem/scenes/needles_impulse.json) and,
# for comparison, under the barrier model (bench/scenes/needles.json), at
# the scene's resolution and at twice it, lsnewton; one JSON summary per run
# (`shellbench run --summary json`) under results/bhem/ccd/.  The report
# results/bhem_ccd.md (the share of the run time spent in the event
# `collide`, beside the paper's Table 2) is made from those files by
# bench/bhem/ccd_report.py, never by re-running.  A summary that exists is
# skipped (delete it to redo the run).
#
#   bash bench/bhem/ccd.sh [SHELLBENCH]
set -u
BIN=${1:-build/shellbench}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/bhem/ccd
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
for model in impulse barrier; do
  if [ "$model" = impulse ]; then scene=bench/bhem/scenes/needles_impulse.json; else scene=needles; fi
  for res in 8 16; do
    tag="needles-bhem-lsnewton-$model-r$res"
    f="$OUT/$tag.json"
    [ -s "$f" ] && continue
    echo "== $tag" >&2
    "$BIN" run --scene "$scene" --method bhem --solver lsnewton --res "$res" \
      --out none --summary json --quiet > "$f.tmp" 2> "$OUT/$tag.log"
    mv "$f.tmp" "$f"
  done
done
python3 bench/bhem/ccd_report.py "$OUT" > results/bhem_ccd.md
echo "results/bhem_ccd.md"
