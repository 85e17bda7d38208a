#!/usr/bin/env bash
# bench/bhem/table2.sh — the BHEM paper's Table 2 rows Ball, Umbrella, Can,
# Cans and Armadillo (issue 39): one bhem run per row at the paper's dofs,
# lsnewton, each as many steps as the scene file says (chosen so that one
# run stays near 20 CPU-minutes or less on a 2-core machine); per run the
# JSON summary (`shellbench run --summary json`) and the digest
# (`shellbench digest`) under results/bhem/table2/, and a 240x180 picture of
# the final state under results/bhem/images/table2_TAG.png.  The HDF5
# records stay in $TMPDIR (not committed).  The report section
# (bench/bhem/table2_report.py, part of results/bhem_report.md) is made from
# those files, never by re-running.  A summary that exists is skipped
# (delete it to redo the run).
#
#   bash bench/bhem/table2.sh [SHELLBENCH] [MODE] [ROW...]
#
# MODE "paper" (default): the runs below.  MODE "large": the whole scene
# scenario (all the scene's steps) in pieces of --max-steps K steps each
# (SB_PIECE, default 20) with a checkpoint in results/bhem/table2/large/,
# continued with --resume on the next call: call it again until it says
# "done".  Rows: ball umbrella can cans_h05 cans_h1 cans_h2 armadillo
# (default all).
set -u
BIN=${1:-build/shellbench}
MODE=${2:-paper}
shift 2 2>/dev/null || shift $#
ROWS=${*:-ball umbrella can cans_h05 cans_h1 cans_h2 armadillo}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/bhem/table2
IMG=results/bhem/images
TMP=${TMPDIR:-/tmp}/sb_table2
mkdir -p "$OUT" "$IMG" "$TMP"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
SC=bench/bhem/scenes

# row -> scene file, resolution (the paper's patches), steps of the large
# mode's run (the whole scenario; the paper mode runs the scene's own steps,
# the first part of it)
row_args() {
  case $1 in
    ball) echo "$SC/ball_drape.json 30 250" ;;
    umbrella) echo "$SC/umbrella_fold.json 5x280 300" ;;
    can) echo "$SC/can_crush.json 20 75" ;;
    cans_h05) echo "$SC/cans_mandrel_h05.json 30 100" ;;
    cans_h1) echo "$SC/cans_mandrel_h1.json 30 100" ;;
    cans_h2) echo "$SC/cans_mandrel_h2.json 30 100" ;;
    armadillo) echo "$SC/armadillo_standin.json 30 250" ;;
    *) echo "unknown row $1" >&2; return 1 ;;
  esac
}

for row in $ROWS; do
  set -- $(row_args "$row") || continue
  scene=$1 res=$2 steps=$3
  if [ "$MODE" = large ]; then
    dir=$OUT/large; mkdir -p "$dir"
    rec=$TMP/large_$row.h5
    [ -s "$dir/$row.json" ] && { echo "$row: done"; continue; }
    resume=; [ -e "$rec.partial" ] && resume="--resume"
    nice -n 10 "$BIN" run --scene "$scene" --method bhem --solver lsnewton --res "$res" --out "$rec" $resume \
      --stop-after-steps ${SB_PIECE:-20} --summary json --quiet > "$TMP/large_$row.json" 2> "$TMP/large_$row.log"
    code=$?
    if [ $code = 4 ]; then echo "$row: stopped at a checkpoint, call again"; continue; fi
    cp "$TMP/large_$row.json" "$dir/$row.json"
    "$BIN" digest "$rec" > "$dir/$row.digest" 2>/dev/null
    "$BIN" render "$rec" --size 240x180 --spp 8 --out "$IMG/table2_large_$row.png" --quiet || true
    echo "$row: done (exit $code)"
    continue
  fi
  f=$OUT/$row.json
  [ -s "$f" ] && continue
  rec=$TMP/$row.h5
  echo "== $row: $scene --res $res" >&2
  rm -f "$rec" "$rec.partial"
  nice -n 10 "$BIN" run --scene "$scene" --method bhem --solver lsnewton --res "$res" --out "$rec" \
    --summary json > "$f.tmp" 2> "$OUT/$row.log"
  echo "   exit $?" >&2
  mv "$f.tmp" "$f"
  "$BIN" render "$rec" --size 240x180 --spp 8 --out "$IMG/table2_$row.png" --quiet || echo "$row: not drawn" >&2
  "$BIN" digest "$rec" > /dev/null && cp "$rec" "$OUT/$row.digest.h5"
done
