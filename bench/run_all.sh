#!/usr/bin/env bash
# `make bench`: every benchmark program under build/bench, then the paper
# reproductions that exist (bench/*/run.sh).  Figures are ratios and counts.
set -uo pipefail
BUILD=${1:-build}
for b in "$BUILD"/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  "$b"
  echo
done
for s in bench/*/run.sh; do
  [ -f "$s" ] || continue
  echo "== $s"
  bash "$s" "$BUILD/shellbench"
  echo
done
