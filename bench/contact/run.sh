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
#   bash bench/contact/run.sh [SHELLBENCH] [pictures]
#
# `pictures`: only the missing pictures (no summaries, no report).
set -u
BIN=${1:-build/shellbench}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/contact/runs
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
for scene in cloth_sphere drape_box needles; do
  [ "${2:-}" = pictures ] && break
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
  [ "${2:-}" = pictures ] && break
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
# The papers' impulse pipeline (contact.model = "impulse", Bridson et al.
# 2002 / Bender & Deul §6) against the barrier on the triangle methods: the
# same scenes with contact.model switched (scene copies in a temporary
# directory), lsnewton for linear_fem, and the linearized solver (the
# paper's linear implicit Euler, every single step accepted:
# run.single_step_rtol=1e300, docs/contact.md) for both triangle methods
# under both models.  A run that is refused (a method without contact sample
# points for the barrier) leaves its log and no summary.
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
for scene in cloth_sphere drape_box; do
  [ "${2:-}" = pictures ] && break
  python3 - "$scene" "$TMP" <<'PY'
import json, sys
scene, tmp = sys.argv[1], sys.argv[2]
d = json.load(open("bench/scenes/%s.json" % scene))
d["contact"]["model"] = "impulse"
json.dump(d, open("%s/%s.json" % (tmp, scene), "w"), indent=1)
PY
  for model in barrier impulse; do
    src=$scene; [ "$model" = impulse ] && src="$TMP/$scene.json"
    for ms in linear_fem:lsnewton linear_fem:linearized adaptive_sqrt3:linearized; do
      method=${ms%%:*}; solver=${ms##*:}
      [ "$model:$solver" = barrier:lsnewton ] && continue   # measured above
      sets=(); [ "$solver" = linearized ] && sets=(--set run.single_step_rtol=1e300)
      for res in 8 16; do
        tag="$scene-$method-$solver-r$res"; [ "$model" = impulse ] && tag="$tag-impulse"
        f="$OUT/$tag.json"
        [ -s "$f" ] && continue
        [ -s "$OUT/$tag.log" ] && [ ! -s "$f" ] && grep -q "shellbench:" "$OUT/$tag.log" && continue   # refused before
        echo "== $tag" >&2
        "$BIN" run --scene "$src" --method "$method" --solver "$solver" --res "$res" "${sets[@]}" \
          --out none --summary json --quiet > "$f.tmp" 2> "$OUT/$tag.log"
        if [ -s "$f.tmp" ]; then mv "$f.tmp" "$f"; else rm -f "$f.tmp"; fi
      done
    done
  done
done
# pictures: the final state of each scene with each method (lsnewton, the
# scene's resolution 8) as a small PNG, results/contact/images/TAG.png
# (240x180 at 8 samples per pixel, committed; the report shows them).  The
# summaries above keep no record (--out none), so the same run is made again
# into a temporary record and drawn; a picture that exists is kept.
mkdir -p results/contact/images
for scene in cloth_sphere drape_box needles; do
  for method in bhem rmtr linear_fem; do
    tag="$scene-$method-lsnewton-r8"
    png="results/contact/images/$tag.png"
    [ -s "$png" ] && continue
    rec=$(mktemp -d)/"$tag.h5"
    echo "== $tag (picture)" >&2
    if "$BIN" run --scene "$scene" --method "$method" --solver lsnewton --res 8 --out "$rec" --quiet \
         > /dev/null 2> "results/contact/images/$tag.log" &&
       "$BIN" render "$rec" --size 240x180 --spp 8 --out "$png" --quiet 2>> "results/contact/images/$tag.log"; then
      rm -f "results/contact/images/$tag.log"
    fi
    rm -rf "$(dirname "$rec")"
  done
done
[ "${2:-}" = pictures ] && exit 0
python3 bench/contact/report.py results/contact > results/contact_report.md
echo "results/contact_report.md"
