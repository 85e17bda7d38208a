#!/usr/bin/env python3
"""results/rmtr/nowells.csv from the records of bench/rmtr/nowells.sh (the hard scenes with mu_21 = 0.5).

    python3 bench/rmtr/nowells_csv.py SHELLBENCH DIR > results/rmtr/nowells.csv

One row per record DIR/rmtrd[K]-SCENE-lL.h5: the record summary (`shellbench report --format csv`), the
energy of its last step (J), the iteration split of its history (finest V-cycles, V-cycles on coarser tops in the nested start, Krylov steps
and their CG iterations: history_split.py, as bench/rmtr/report.py's Krylov section), and where the final state lies
in the material law (`shellbench inspect --format csv`: the softening share and the share below the flat
sheet's energy)."""
import csv
import glob
import io
import os
import re
import subprocess
import sys

from history_split import dataset, iteration_split


def one_row(binary, path):
    rep = subprocess.run([binary, "report", "--format", "csv", path], capture_output=True, text=True)
    ins = subprocess.run([binary, "inspect", "--format", "csv", path], capture_output=True, text=True)
    if rep.returncode != 0 or ins.returncode != 0:
        sys.stderr.write("nowells_csv: %s: %s%s" % (path, rep.stderr, ins.stderr))
        return None
    r = next(csv.DictReader(io.StringIO(rep.stdout)))
    m = next(csv.DictReader(io.StringIO(ins.stdout)))
    v, c, k, cg = iteration_split(path)
    name = os.path.basename(path)[:-3]
    g = re.match(r"(rmtrdK?)-(.+)-l(\d)$", name)
    return {
        "record": name, "krylov": "auto" if g.group(1) == "rmtrdK" else "off", "scene": g.group(2),
        "levels": g.group(3), "dofs": r["dofs"], "status": r["status"],
        "finest_vcycles": v, "coarser_tops": c, "krylov_steps": k, "cg_iterations": cg,
        "f_final": "%.6g" % dataset(path, "/history/steps/f")[-1], "seconds": r["seconds"],
        "soft_area_fraction": m["soft_area_fraction"], "below_reference_area_fraction": m["below_reference_area_fraction"],
        "max_strain": max(float(m["max_E11"]), float(m["max_E22"]), float(m["max_E12"])),
    }


def main():
    binary, d = sys.argv[1], sys.argv[2]
    rows = [x for x in (one_row(binary, p) for p in sorted(glob.glob(os.path.join(d, "rmtrd*-l?.h5")))) if x]
    keys = ["record", "krylov", "scene", "levels", "dofs", "status", "finest_vcycles", "coarser_tops", "krylov_steps",
            "cg_iterations", "f_final", "seconds", "soft_area_fraction", "below_reference_area_fraction", "max_strain"]
    w = csv.DictWriter(sys.stdout, fieldnames=keys, extrasaction="ignore", lineterminator="\n")
    w.writeheader()
    for x in rows:
        w.writerow(x)


if __name__ == "__main__":
    main()
