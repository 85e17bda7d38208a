#!/usr/bin/env bash
# scripts/digest_results.sh [BIN] — rewrite the records under results/ that
# reports read as digests (docs/reproducibility.md "Committed records"):
# without per-step surfaces, the final displacement, reference grid,
# triangles and the final dof vector.  Run it after a report has drawn its
# pictures (a study keeps the picture drawn from a record once the record is
# a digest; the bench reports keep their committed pictures), before
# committing.  Reference records (results/references/), Table 1's records
# (rendered by its bench) and checkpoints (*.partial) are left whole.
set -euo pipefail
BIN=${1:-build/shellbench}
shopt -s nullglob
for d in results/accuracy results/dt_stability; do
  files=("$d"/*/*.h5)
  [ ${#files[@]} -gt 0 ] && "$BIN" digest --drop-state "${files[@]}" | tail -n 1
done
for d in results/rmtr/runs results/bhem/runs; do
  files=("$d"/*.h5)
  [ ${#files[@]} -gt 0 ] && "$BIN" digest --drop-state "${files[@]}" | tail -n 1
done
