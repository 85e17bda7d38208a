#!/usr/bin/env bash
# bench/bhem/table1.sh — the BHEM paper's Table 1 (§5.1, §6.3): rendering
# time of three ray–patch intersection algorithms on its three test scenes
# (Fig. 11: Plane, 1 patch; Cylinder and Drape, 10 x 10 patches; 16 samples
# per pixel, the same lights).
#
#   bash bench/bhem/table1.sh [SHELLBENCH] [REPEATS] [ALGORITHMS]
#
# 1. the three records (results/bhem/table1/{plane,cylinder,drape}.h5), run
#    only when missing: bhem at rest on bench/bhem/scenes/render_plane.json
#    (1 patch) and render_cylinder.json (10 x 10), and the draped cloth of
#    the paper's Fig. 15 (bench/bhem/scenes/draped_cloth.json) at 10 x 10;
# 2. every record rendered with --intersect subdivision | newton | clipping |
#    clipping-dfs (ALGORITHMS, comma-separated, default all four) at 480x360,
#    16 spp, REPEATS times (default 3); each render appends its `--stats`
#    JSON line (CPU seconds and work counts) to timings.jsonl and writes its
#    picture;
# 3. per ray class (bench/bhem/isect_classes.c: steep hits, grazing hits and
#    misses, misses through the patch box) every algorithm timed on the
#    patches of each record, one JSON line per class and algorithm in
#    classes.jsonl (rewritten; REPEATS passes over 2000 tests per class).
# The table is then made from timings.jsonl by bench/bhem/table1.py, never
# by re-running.  Needs about 10 minutes of one core.
set -u
BIN=${1:-build/shellbench}
REPEATS=${2:-3}
ALGS=$(echo "${3:-subdivision,newton,clipping,clipping-dfs}" | tr , ' ')
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/bhem/table1
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=1
export OPENBLAS_CORETYPE=${SB_BLAS_CORE:-Prescott}
SC=bench/bhem/scenes

record() {   # NAME SCENE RES
  [ -e "$OUT/$1.h5" ] && return 0
  echo "== record $1: $2 --res $3" >&2
  "$BIN" run --scene "$2" --method bhem --solver lsnewton --res "$3" --out "$OUT/$1.h5" --quiet || exit 1
}
record plane $SC/render_plane.json 1
record cylinder $SC/render_cylinder.json 10
record drape $SC/draped_cloth.json 10

machine=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')
batch=$(date -u +%Y-%m-%dT%H:%MZ)   # one call: table1.py compares algorithms within it (the same load)
for rep in $(seq 1 "$REPEATS"); do
  for scene in plane cylinder drape; do
    for alg in $ALGS; do
      echo "== $scene $alg (repeat $rep of $REPEATS)" >&2
      line=$("$BIN" render "$OUT/$scene.h5" --size 480x360 --spp 16 --intersect "$alg" \
               --out "$OUT/${scene}_$alg.png" --stats --quiet) || exit 1
      echo "{\"batch\": \"$batch\", \"scene\": \"$scene\", \"repeat\": $rep, \"machine\": \"$machine\", \"load\": \"$(cut -d' ' -f1 /proc/loadavg)\", \"stats\": $line}" \
        >> "$OUT/timings.jsonl"
    done
  done
done
make -s build/bench/bhem/isect_classes >/dev/null || exit 1
: > "$OUT/classes.jsonl.tmp"
for spec in "plane $SC/render_plane.json 1" "cylinder $SC/render_cylinder.json 10" "drape $SC/draped_cloth.json 10"; do
  set -- $spec
  echo "== ray classes: $1" >&2
  build/bench/bhem/isect_classes "$2" "$OUT/$1.h5" "$3" 2000 "$REPEATS" | sed "s/^{/{\"scene\": \"$1\", /" >> "$OUT/classes.jsonl.tmp" || exit 1
done
mv "$OUT/classes.jsonl.tmp" "$OUT/classes.jsonl"
echo "timings in $OUT/timings.jsonl and $OUT/classes.jsonl; table: python3 bench/bhem/table1.py > results/bhem_table1.md" >&2
