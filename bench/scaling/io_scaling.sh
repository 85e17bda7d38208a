#!/usr/bin/env bash
# bench/scaling/io_scaling.sh — issue 42: records of up to 1e6 dofs are read
# back by `report`, `inspect`, `render` and `digest` (and, with --paraview,
# opened in ParaView) in time proportional to their size.
#
#   bash bench/scaling/io_scaling.sh [--paraview] OUT.csv RECORD.h5...
#
# For each record (full records, not digests: a digest has no state to
# render or inspect), wall seconds of each command on a private copy (digest
# rewrites its file in place), one line of OUT.csv per record:
#   record,dofs,bytes,report_s,inspect_s,render_s,digest_s,digest_bytes,paraview_s
# paraview_s is scripts/check_paraview.py on the record's XDMF sidecars under
# xvfb-run (every check of make check-paraview; its ParaView start-up, about
# 2-4 s, is part of it) or empty without --paraview.  bench/scaling/report.py
# fits seconds against bytes and dofs over these lines.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BIN=${SHELLBENCH:-$ROOT/build/shellbench}
PV=0
if [ "${1:-}" = --paraview ]; then PV=1; shift; fi
[ $# -ge 2 ] || { echo "usage: $0 [--paraview] OUT.csv RECORD.h5..." >&2; exit 2; }
OUT=$1; shift
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}

secs() { # wall seconds of a command, its output discarded; fails loudly
  local t0 t1
  t0=$(date +%s.%N)
  if ! "$@" > "$TMP/out.txt" 2>&1; then
    echo "io_scaling: failed: $*" >&2; cat "$TMP/out.txt" >&2; return 1
  fi
  t1=$(date +%s.%N)
  python3 -c "print('%.3f' % ($t1 - $t0))"
}

[ -e "$OUT" ] || echo "record,dofs,bytes,report_s,inspect_s,render_s,digest_s,digest_bytes,paraview_s" > "$OUT"
for rec in "$@"; do
  [ -f "$rec" ] || { echo "io_scaling: $rec: no such record" >&2; exit 2; }
  base=$(basename "$rec" .h5)
  cp "$rec" "$TMP/$base.h5"
  for side in xdmf steps.xdmf mesh.xdmf; do
    [ -f "${rec%.h5}.$side" ] && cp "${rec%.h5}.$side" "$TMP/$base.$side"
  done
  dofs=$("$BIN" report --format csv "$TMP/$base.h5" | python3 -c "
import csv, sys
r = next(csv.DictReader(sys.stdin)); print(r['dofs'])")
  bytes=$(stat -c %s "$rec")
  t_report=$(secs "$BIN" report --format csv "$TMP/$base.h5")
  # a method without a material state (adaptive_sqrt3) is refused by
  # inspect with a sentence: no figure, not a failure
  if "$BIN" inspect --format csv "$TMP/$base.h5" > /dev/null 2> "$TMP/inspect.err"; then
    t_inspect=$(secs "$BIN" inspect --format csv "$TMP/$base.h5")
  elif grep -q "cannot report its material state" "$TMP/inspect.err"; then
    t_inspect=""
  else
    cat "$TMP/inspect.err" >&2; exit 1
  fi
  t_render=$(secs "$BIN" render "$TMP/$base.h5" --out "$TMP/$base.png")
  t_pv=""
  if [ $PV = 1 ]; then
    # as scripts/check_paraview.sh: ParaView sometimes cannot connect to a
    # freshly started Xvfb and aborts (a signal); the attempt that ran is timed
    for attempt in 1 2 3; do
      t0=$(date +%s.%N)
      set +e
      xvfb-run -a -s "-screen 0 1024x768x24" pvpython "$ROOT/scripts/check_paraview.py" "$TMP" "$TMP/$base.h5" > "$TMP/pv.txt" 2>&1
      rc=$?
      set -e
      t1=$(date +%s.%N)
      [ $rc -lt 128 ] && break
    done
    if [ $rc -ne 0 ]; then echo "io_scaling: ParaView check failed (exit $rc) on $rec" >&2; cat "$TMP/pv.txt" >&2; exit 1; fi
    t_pv=$(python3 -c "print('%.3f' % ($t1 - $t0))")
  fi
  t_digest=$(secs "$BIN" digest "$TMP/$base.h5")
  dbytes=$(stat -c %s "$TMP/$base.h5")
  echo "$rec,$dofs,$bytes,$t_report,$t_inspect,$t_render,$t_digest,$dbytes,$t_pv" | tee -a "$OUT"
  rm -f "$TMP/$base".*
done
