#!/usr/bin/env bash
# Runs each fuzz target for a bounded time (`make fuzz-short`, CI): fuzz_scene
# with the scene dictionary, fuzz_record with HDF5's own leak suppressed
# (LSAN_OPTIONS from the Makefile, tests/lsan.supp) and checked at the end.  The corpora grow in BUILD/corpus; a crash, leak or
# abort is written to BUILD/crashes/ and fails the run.  Usage:
# fuzz_run.sh BUILD SECONDS
set -uo pipefail
BUILD=$1
SECONDS_EACH=${2:-60}
mkdir -p "$BUILD/crashes"
status=0
for t in scene record; do
  mkdir -p "$BUILD/corpus/$t"
  extra=()
  [ "$t" = scene ] && extra=(-dict=fuzz/scene.dict -max_len=65536)
  # record: leaks are checked once at the end, not after every input (HDF5
  # leaks on most malformed files, suppressed, and the scans halve the speed)
  [ "$t" = record ] && extra=(-max_len=262144 -detect_leaks=0)
  echo "== fuzz_$t: ${SECONDS_EACH} s"
  log="$BUILD/fuzz_$t.log"
  ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1} \
  "$BUILD/fuzz/fuzz_$t" -max_total_time="$SECONDS_EACH" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$BUILD/crashes/$t-" "${extra[@]}" "$BUILD/corpus/$t" "$BUILD/seeds/$t" > "$log" 2>&1
  rc=$?
  grep -E '^(#[0-9]+.*DONE|stat::number_of_executed_units|stat::peak_rss_mb|==[0-9]+==ERROR|SUMMARY|fuzz_|.*runtime error|ParseDictionary|INFO: (Loaded|seed corpus))' "$log"
  # coverage: the counters reached (libFuzzer's "cov:" of the last status
  # line) against the instrumented counters of the binary ("Loaded N modules
  # (M inline 8-bit counters)")
  total=$(grep -oE '\([0-9]+ inline 8-bit counters\)' "$log" | head -n 1 | grep -oE '^\([0-9]+' | tr -d '(')
  cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -n 1 | grep -oE '[0-9]+')
  seeds=$(grep -oE 'INFO: seed corpus: files: [0-9]+' "$log" | grep -oE '[0-9]+$')
  echo "fuzz_$t: coverage ${cov:-?} of ${total:-?} counters, from ${seeds:-?} corpus and seed files"
  if [ "$rc" -ne 0 ]; then
    echo "fuzz_$t FAILED (exit $rc): see $BUILD/crashes/ and $log"
    status=1
  elif [ -z "$cov" ]; then
    echo "fuzz_$t FAILED: no coverage reported (see $log)"
    status=1
  fi
done
exit $status
