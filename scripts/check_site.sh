#!/usr/bin/env bash
# check_site.sh BIN OUTDIR — `make check-site` (docs/site.md):
#  1. a small site (tests/site/: part of the committed accuracy study read
#     from its records, a small nightly history, a report, with markup in
#     every string) opened in headless Chromium by scripts/check_site.js:
#     no console error or failed load, every plot drawn with its series,
#     sort and filter change the tables, markup shows as text;
#     screenshots into OUTDIR/shots (docs/img/site-*.png are copies);
#  2. the site of the committed results (make site) checked the same way,
#     with the load times of the accuracy study's pages printed (measured,
#     never asserted).
set -euo pipefail
BIN=${1:-build/shellbench}
OUT=${2:-build/check-site}
CHROMIUM=${SB_CHROMIUM:-/usr/bin/chromium}
if [ ! -x "$CHROMIUM" ]; then
  echo "check-site: $CHROMIUM is not installed (bash scripts/ensure_deps.sh installs Debian's chromium)" >&2
  exit 2
fi
if ! command -v node >/dev/null 2>&1; then
  echo "check-site: node is not installed (bash scripts/ensure_deps.sh installs Debian's nodejs)" >&2
  exit 2
fi
rm -rf "$OUT/small" "$OUT/full"
mkdir -p "$OUT"
echo "check-site: the small site ($OUT/small)"
"$BIN" site --out "$OUT/small" --study tests/site/study.json --history tests/site/history.csv \
  --baseline bench/nightly/baseline.json --report tests/site/report.md
node scripts/check_site.js "$OUT/small" "$OUT/shots" tests/site/spec.json
echo "check-site: the committed results' site ($OUT/full)"
"$BIN" site --out "$OUT/full"
echo "check-site: size of the accuracy study's pages: $(du -sh "$OUT/full/studies/accuracy" | cut -f1) (+ $(du -sh "$OUT/full/static" | cut -f1) of scripts shared by every page); whole site $(du -sh "$OUT/full" | cut -f1)"
echo "check-site: load average before the timed pages: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores (the times below depend on it)"
node scripts/check_site.js "$OUT/full" "$OUT/shots-full" scripts/check_site_full.json
echo "check-site: screenshots in $OUT/shots (committed copies: docs/img/site-*.png)"
