#!/usr/bin/env bash
# bench/contact/run.sh — the contact scenes (issue 25: cloth_sphere,
# drape_box, needles) with every method and the lsnewton and tr solvers, at
# the scenes' resolutions and at twice them, and the self-contact scene
# tube_collapse at half and at its resolution (self-contact at twice it
# takes minutes a run), one JSON summary per run
# (`shellbench run --summary json`) under results/contact/runs/; the report
# (results/contact_report.md: the contact share of the run time) is made
# from those files by bench/contact/report.py, never by re-running.  A
# summary that exists is skipped (delete it to redo the run).
#
#   bash bench/contact/run.sh [SHELLBENCH]
set -u
BIN=${1:-build/shellbench}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/contact/runs
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
for scene in cloth_sphere drape_box needles; do
  for method in bhem rmtr linear_fem; do
    for solver in lsnewton tr; do
      for res in 8 16; do
        tag="$scene-$method-$solver-r$res"
        f="$OUT/$tag.json"
        [ -s "$f" ] && continue
        echo "== $tag" >&2
        "$BIN" run --scene "$scene" --method "$method" --solver "$solver" --res "$res" \
          --out none --summary json --quiet > "$f.tmp" 2> "$OUT/$tag.log"
        mv "$f.tmp" "$f"
      done
    done
  done
done
for method in bhem rmtr linear_fem; do
  for solver in lsnewton tr; do
    for res in 4 8; do
      tag="tube_collapse-$method-$solver-r$res"
      f="$OUT/$tag.json"
      [ -s "$f" ] && continue
      echo "== $tag" >&2
      "$BIN" run --scene tube_collapse --method "$method" --solver "$solver" --res "$res" \
        --out none --summary json --quiet > "$f.tmp" 2> "$OUT/$tag.log"
      mv "$f.tmp" "$f"
    done
  done
done
python3 bench/contact/report.py results/contact > results/contact_report.md
echo "results/contact_report.md"
