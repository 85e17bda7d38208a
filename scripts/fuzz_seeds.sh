#!/usr/bin/env bash
# Seed corpora of the fuzz targets (`make fuzz`): the bundled, test and bad
# scenes for fuzz_scene; small records, a checkpoint and non-records made by
# the ordinary build for fuzz_record.  Usage: fuzz_seeds.sh BIN DIR
set -euo pipefail
BIN=$1
DIR=$2
mkdir -p "$DIR/scene" "$DIR/record"
cp bench/scenes/*.json tests/scenes/*.json tests/scenes_bad/*.json "$DIR/scene/"
R="$DIR/record"
if [ ! -f "$R/bhem.h5" ]; then
  "$BIN" run --scene trampoline --method bhem --solver tr --res 2 --samples 2 --out "$R/bhem.h5" --quiet \
    --set run.checkpoint=0 || true
  "$BIN" run --scene drooping --method rmtr --solver rmtr --levels 2 --res 2 --samples 3 --out "$R/rmtr.h5" --quiet \
    --set run.checkpoint=0 || true
  "$BIN" run --scene plate_clamped --method bhem --solver lsnewton --res 2 --samples 2 --out "$R/probes.h5" --quiet || true
  "$BIN" run --scene trampoline --method bhem --solver tr --res 2 --samples 2 --out "$R/ckpt.h5" --quiet \
    --stop-after-steps 2 || true
  rm -f "$R"/*.xdmf "$R"/*.lock
  cp bench/scenes/trampoline.json "$R/not_a_record.json"
  : > "$R/empty"
fi
ls "$DIR/scene" | wc -l | xargs echo "fuzz seeds: scenes:"
ls "$R" | wc -l | xargs echo "fuzz seeds: records:"
