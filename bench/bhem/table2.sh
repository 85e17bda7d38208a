#!/usr/bin/env bash
# bench/bhem/table2.sh — the BHEM paper's Table 2 rows Ball, Umbrella, Can,
# Cans and Armadillo (issue 39; docs/bhem_table2.md): one bhem run per row at
# the paper's patches (its dofs), lsnewton, over the scene file's steps (the
# first part of each scenario, chosen so that one run stays well under 20
# CPU-minutes); per run the JSON summary (`shellbench run --summary json`),
# the record made a digest after its picture is drawn (`shellbench digest
# --drop-state`, ROW.digest.h5: statistics, histories and probes, as every
# committed digest, docs/reproducibility.md), the load
# average at its start (ROW.load) under results/bhem/table2/, and a 240x180
# picture of the final state, results/bhem/images/table2_ROW.png.  The
# report section (bench/bhem/table2_report.py, in results/bhem_report.md)
# is made from those files, never by re-running.  A summary that exists is
# skipped (delete it to redo the run).
#
#   bash bench/bhem/table2.sh [SHELLBENCH] [MODE] [ROW...]
#
# MODE "paper" (default): the runs above.
# MODE "large": the whole scenario of each row (the steps in row_args, at the
#   same resolution; RES_ROW=NxM overrides it, e.g. RES_umbrella=5x56) from a
#   copy of the scene with that many steps, in pieces of SB_PIECE steps
#   (default 25) per call with a checkpoint under $TMPDIR/sb_table2/large/;
#   call again to continue (--resume); SB_SET="key=value" adds one --set
#   (e.g. method.imperfection=2e-5); when a row finishes, its summary,
#   digest and picture go to results/bhem/table2/large/ and
#   results/bhem/images/table2_large_ROW.png.
# Rows: ball umbrella can cans_h05 cans_h1 cans_h2 armadillo (default all),
# and the can's two diagnostics can_dt1ms and can_slow (why the can stalls:
# the rim moving 0.2 mm a step instead of 0.4 mm, by a halved dt or a
# halved rim speed; docs/bhem_table2.md).
set -u
BIN=${1:-build/shellbench}
MODE=${2:-paper}
shift 2 2>/dev/null || shift $#
ROWS=${*:-ball umbrella can cans_h05 cans_h1 cans_h2 armadillo can_dt1ms can_slow}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/bhem/table2
IMG=results/bhem/images
TMP=${TMPDIR:-/tmp}/sb_table2
mkdir -p "$OUT" "$IMG" "$TMP"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
SC=bench/bhem/scenes

# row -> scene file, resolution (the paper's patches), steps of the whole
# scenario (large mode; the paper mode runs the scene file's own steps)
row_args() {
  case $1 in
    ball) echo "$SC/ball_drape.json 30 250" ;;
    umbrella) echo "$SC/umbrella_fold.json 5x280 300" ;;
    can) echo "$SC/can_crush.json 20 75" ;;
    can_dt1ms) echo "$SC/can_crush_dt1ms.json 20 150" ;;
    can_slow) echo "$SC/can_crush_slow.json 20 150" ;;
    cans_h05) echo "$SC/cans_mandrel_h05.json 30 100" ;;
    cans_h1) echo "$SC/cans_mandrel_h1.json 30 100" ;;
    cans_h2) echo "$SC/cans_mandrel_h2.json 30 100" ;;
    armadillo) echo "$SC/armadillo_standin.json 30 250" ;;
    *) echo "unknown row $1" >&2; return 1 ;;
  esac
}

# the picture's camera per row (the can stands along e_y beside its ground plane)
view() { case $1 in can*) echo "--camera 0.22,0.2,0.3,0,0.05,0 --no-ground" ;; esac; }

# large ROW SCENE RES STEPS: one piece of the whole scenario
large() {
  local row=$1 scene=$2 res=$3 steps=$4
  local v=RES_$row; res=${!v:-$res}
  local dir=$OUT/large ldir=$TMP/large tag=${row}_r${res}
  mkdir -p "$dir" "$ldir"
  [ -s "$dir/$tag.json" ] && { echo "$tag: done"; return 0; }
  local sc=$ldir/$(basename "$scene") rec=$ldir/$tag.h5 at=0 resume=
  # the scene with all the scenario's steps, beside a copy of its meshes
  python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); j["time"]["steps"]=int(sys.argv[2]); print(json.dumps(j, indent=1))' \
    "$scene" "$steps" > "$sc" || return 1
  cp "$SC"/*.obj "$ldir"/ 2>/dev/null
  [ -s "$ldir/$tag.step" ] && at=$(cat "$ldir/$tag.step")
  [ -e "$rec.partial" ] && resume=--resume
  local stop=$((at + ${SB_PIECE:-25}))
  [ $stop -ge "$steps" ] && stop=$steps
  [ -z "$resume" ] && cat /proc/loadavg > "$dir/$tag.load"
  nice -n 10 "$BIN" run --scene "$sc" --method bhem --solver lsnewton --res "$res" --out "$rec" $resume \
    ${SB_SET:+--set "$SB_SET"} --stop-after-steps "$stop" --summary json --quiet > "$ldir/$tag.json" 2> "$ldir/$tag.log"
  local code=$?
  if [ $code = 4 ]; then echo "$stop" > "$ldir/$tag.step"; echo "$tag: at step $stop of $steps, call again"; return 0; fi
  cp "$ldir/$tag.json" "$dir/$tag.json"
  "$BIN" render "$rec" --size 240x180 --spp 8 $(view "$row") --out "$IMG/table2_large_$tag.png" --quiet ||
    echo "$tag: not drawn" >&2
  "$BIN" digest --drop-state "$rec" > /dev/null && cp "$rec" "$dir/$tag.digest.h5"
  echo "$tag: done (exit $code)"
}

for row in $ROWS; do
  set -- $(row_args "$row") || continue
  scene=$1 res=$2 steps=$3
  if [ "$MODE" = large ]; then large "$row" "$scene" "$res" "$steps"; continue; fi
  f=$OUT/$row.json
  [ -s "$f" ] && continue
  rec=$TMP/$row.h5
  echo "== $row: $scene --res $res" >&2
  rm -f "$rec" "$rec.partial"
  cat /proc/loadavg > "$OUT/$row.load"
  nice -n 10 "$BIN" run --scene "$scene" --method bhem --solver lsnewton --res "$res" --out "$rec" \
    --summary json > "$f.tmp" 2> "$OUT/$row.log"
  echo "   exit $?" >&2
  mv "$f.tmp" "$f"
  "$BIN" render "$rec" --size 240x180 --spp 8 $(view "$row") --out "$IMG/table2_$row.png" --quiet ||
    echo "$row: not drawn" >&2
  "$BIN" digest --drop-state "$rec" > /dev/null && cp "$rec" "$OUT/$row.digest.h5"
done
