#!/usr/bin/env python3
"""bench/sqrt3/dress_series.py — the per-step series of a full-resolution and
an adaptive run of the dress (bench/sqrt3/dress.sh), read from their HDF5
records with h5dump (hdf5-tools; standard library only): triangles, the
step's seconds and its parts (collide = the impulse response, adapt,
record, checkpoint), and the distance between the two surfaces on the
records' common 11 x 11 material grid, RMS and max, divided by the
domain's diameter (1.2 m: two points of the 330-degree outer arc opposite
each other; the suite's error measure, DESIGN.md "Accuracy").  Every step,
so the report can sum the components.  CSV on stdout.

    python3 bench/sqrt3/dress_series.py FULL.h5 ADAPTIVE.h5 [--contact FILE.json] > results/sqrt3/series_dress.csv

A record may be a checkpoint (OUT.h5.partial) of a run stopped part-way: the
series then ends at its last step.  --contact writes the impulse response's
counts (/final/contact: proximity impulses, CCD tests, hits, passes, impact
zones, unresolved steps) of both records with their step counts, so that the
report has them also for runs without a summary.
"""
import json
import math, re, sys
import os

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from h5ddl import h5_text as h5, numbers, samples  # noqa: E402  (bench/h5ddl.py)

DIAG = 1.2
COLS = ("triangles", "seconds", "seconds_contact", "seconds_adapt", "seconds_record", "seconds_checkpoint")


def contact(path):
    """the attributes of /final/contact (integers) and the steps recorded"""
    text = h5(path, "-A", "-g", "/final/contact")
    out = {}
    for block in text.split('ATTRIBUTE "')[1:]:
        name = block.split('"', 1)[0]
        m = re.search(r"\(0\): ([-0-9]+)\s*\n", block)
        if "H5T_STD_I" in block and m:
            out[name] = int(m.group(1))
    out["steps"] = len(numbers(h5(path, "-d", "/history/steps/t")))
    if "counted_steps" not in out:
        # a record of a build before the counts travelled in checkpoints:
        # a resumed run counted the steps after its last resume point only
        m = re.search(r'"([0-9,]+)"', h5(path, "-a", "/resume_steps")) if "resume_steps" in h5(path, "-A", "-g", "/") else None
        last = int(m.group(1).split(",")[-1]) if m and m.group(1) else 0
        out["counted_steps"] = out["steps"] - last
    out["record"] = path
    return out


def run(path):
    d = {c: numbers(h5(path, "-d", "/history/steps/" + c)) for c in COLS}
    d["t"] = numbers(h5(path, "-d", "/history/steps/t"))
    d["samples"] = samples(path)
    return d


def main():
    if len(sys.argv) > 4 and sys.argv[3] == "--contact":
        with open(sys.argv[4], "w") as fh:
            json.dump({"full": contact(sys.argv[1]), "adaptive": contact(sys.argv[2])}, fh, indent=1)
    f, a = run(sys.argv[1]), run(sys.argv[2])
    n = min(len(f["t"]), len(a["t"]))
    head = ["step", "t"] + ["%s_full" % c for c in COLS] + ["%s_adaptive" % c for c in COLS] + ["rms", "max"]
    print(",".join(head))
    for k in range(n):
        step = k + 1
        row = ["%d" % step, "%.6g" % f["t"][k]]
        for d in (f, a):
            row += ["%.6g" % (d[c][k] if k < len(d[c]) else float("nan")) for c in COLS]
        pf, pa = f["samples"].get(step), a["samples"].get(step)
        rms = mx = float("nan")
        if pf and pa and len(pf) == len(pa):
            dist = [math.dist(pa[i:i + 3], pf[i:i + 3]) for i in range(0, len(pa), 3)]
            rms = math.sqrt(sum(x * x for x in dist) / len(dist)) / DIAG
            mx = max(dist) / DIAG
        row += ["%.6g" % rms, "%.6g" % mx]
        print(",".join(row))


main()
