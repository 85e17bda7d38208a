#!/usr/bin/env bash
# bench/bhem/needles.sh — why needles_impulse stops at 16x16 patches (issue 39):
# the run itself (record kept as a digest, results/bhem/needles/r16.h5, with
# its final dof vector), the largest Gauss-point strains of its final state
# with the nearest needle (bench/bhem/needles_diag.c -> r16_strain.csv), and
# three experiments that change one thing each: 12x12 patches, dt = 5 ms,
# and the paper's dt = 2 ms (bench/bhem/scenes/needles_impulse_2ms.json).
# The report section is made by bench/bhem/report_issue39.py from these
# files, never by re-running.  A file that exists is skipped.
#
#   bash bench/bhem/needles.sh [SHELLBENCH]
set -u
BIN=${1:-build/shellbench}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
OUT=results/bhem/needles
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
SC=bench/bhem/scenes/needles_impulse.json
LIB=${LIB:-build/libshellbench.a}
DIAG=$OUT/../needles_diag
cc -std=c11 -O2 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE $(for d in core/*/; do printf -- "-I%s " "$d"; done) \
   -I/usr/include/suitesparse $(pkg-config --cflags hdf5-serial jansson gsl) -fopenmp bench/bhem/needles_diag.c "$LIB" \
   -o "$DIAG" -lcholmod -lsuitesparseconfig $(pkg-config --libs hdf5-serial jansson gsl) -llapack -lblas -losdCPU -lstdc++ -lm
run() {   # run NAME SCENE RES [--set ...]
  local name=$1 scene=$2 res=$3; shift 3
  [ -s "$OUT/$name.json" ] && return 0
  echo "== $name" >&2
  /usr/bin/time -f '{"cpu_user": %U, "cpu_sys": %S, "wall": %e}' -o "$OUT/$name.time.json" \
    nice -n 10 "$BIN" run --scene "$scene" --method bhem --solver lsnewton --res "$res" --out "$OUT/$name.h5" \
    --summary json --quiet "$@" > "$OUT/$name.json.tmp" 2> "$OUT/$name.log"
  mv "$OUT/$name.json.tmp" "$OUT/$name.json"
}
run r16 $SC 16
[ -s "$OUT/r16.h5" ] && "$BIN" digest "$OUT/r16.h5" >&2
"$DIAG" $SC "$OUT/r16.h5" 16 20 > "$OUT/r16_strain.csv"
tmp=$(mktemp -d)
python3 - "$SC" "$tmp/dt5.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["time"]["dt"], s["time"]["steps"], s["name"] = 0.005, 50, "needles_impulse_dt5ms"
json.dump(s, open(sys.argv[2], "w"))
PY
run exp_res_12 $SC 12
run exp_dt_5ms "$tmp/dt5.json" 16
run exp_dt_2ms_paper bench/bhem/scenes/needles_impulse_2ms.json 16
rm -rf "$tmp" "$OUT"/exp_*.h5 "$OUT"/*.xdmf
