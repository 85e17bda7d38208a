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
# Each seed is made by an ordinary run that must succeed: a seed that is not
# made fails `make fuzz` (it once went unnoticed behind `|| true`, and
# fuzz_record started from 2 of its 4 record seeds).  The scenes' default
# sample grids are kept: trampoline and drooping have reference records whose
# grid a run must match.
seed() { # NAME EXPECTED_EXITS(a|b) ARGS...
  local name=$1 want=$2; shift 2
  [ -f "$R/$name.h5" ] && return 0
  local rc=0
  "$BIN" run "$@" --out "$R/$name.h5" --quiet || rc=$?
  # a stopped run's checkpoint is OUT.partial: it is the seed
  [ "$rc" = 4 ] && [ -f "$R/$name.h5.partial" ] && mv "$R/$name.h5.partial" "$R/$name.h5"
  if [[ ! "$rc" =~ ^($want)$ ]] || [ ! -f "$R/$name.h5" ]; then
    echo "fuzz seeds: the $name seed was not made (shellbench run exited $rc, expected $want): $*" >&2
    exit 1
  fi
}
seed bhem 0 --scene trampoline --method bhem --solver tr --res 2 --set run.checkpoint=0
# (drooping at res 2 may end unconverged, exit 1: its record is as good a seed)
seed rmtr '0|1' --scene drooping --method rmtr --solver rmtr --levels 2 --res 2 --set run.checkpoint=0
seed probes 0 --scene plate_clamped --method bhem --solver lsnewton --res 2 --samples 2
# a checkpoint: the run stops after 2 steps with a resumable checkpoint (exit 4)
seed ckpt 4 --scene trampoline --method bhem --solver tr --res 2 --stop-after-steps 2
rm -f "$R"/*.xdmf "$R"/*.lock "$R"/*.partial
cp bench/scenes/trampoline.json "$R/not_a_record.json"
: > "$R/empty"
ls "$DIR/scene" | wc -l | xargs echo "fuzz seeds: scenes:"
ls "$R" | wc -l | xargs echo "fuzz seeds: records:"
for name in bhem rmtr probes ckpt; do
  [ -s "$R/$name.h5" ] || { echo "fuzz seeds: $R/$name.h5 is missing" >&2; exit 1; }
done
