#!/usr/bin/env python3
"""bench/sqrt3/distance.py — per-step series of the runs of bench/sqrt3/run.sh
(the curtain by default; another scene with --full TAG --diag D SHORT=TAG ...), read from their HDF5 records with h5dump (hdf5-tools;
the report scripts use the Python standard library only): time, dofs and
seconds of every step of the adaptive and the full-resolution run, and the
distance between their surfaces on the records' common sample grid (11 x 11
material points), RMS and max, divided by the curtain's diagonal (the
suite's error measure, DESIGN.md "Accuracy"); every 5th step (the
adaptation interval) and the last, to keep the file small.  CSV on stdout.

    python3 bench/sqrt3/distance.py results/sqrt3 > results/sqrt3/series.csv
    python3 bench/sqrt3/distance.py results/sqrt3 --full cs-full --diag 0.848528 \
        adaptive=cs-adaptive loose=cs-adaptive-loose > results/sqrt3/series_cloth_sphere.csv
"""
import math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from h5ddl import h5_text as h5, numbers, samples  # noqa: E402  (bench/h5ddl.py)

DIR = sys.argv[1] if len(sys.argv) > 1 else "results/sqrt3"
DIAG = math.hypot(1.0, 1.5)          # the curtain is 1 m x 1.5 m (bench/scenes/curtain.json)
FULL = "curtain-full-cholmod"
PAIRS = [("curtain-adaptive-cholmod", "adaptive"), ("curtain-adaptive-loose-cholmod", "loose")]
_rest = sys.argv[2:]
# --triangles: also every step's triangle count (/history/steps/triangles;
# the paper's Fig. 8 counts triangles), as tri_full and tri_SHORT columns
TRIANGLES = "--triangles" in _rest
_rest = [a for a in _rest if a != "--triangles"]
if _rest:
    PAIRS = []
    while _rest:
        a = _rest.pop(0)
        if a == "--full":
            FULL = _rest.pop(0)
        elif a == "--diag":
            DIAG = float(_rest.pop(0))
        else:
            short, tag = a.split("=", 1)
            PAIRS.append((tag, short))


def series(path, name):
    return numbers(h5(path, "-d", name))


def main():
    rf = os.path.join(DIR, "records", FULL + ".h5")
    if not os.path.exists(rf) and os.path.exists(rf + ".partial"):
        rf += ".partial"   # a run stopped with a checkpoint (run.sh paper): the steps it has done
    t = series(rf, "/history/steps/t")
    df, sf, pf = series(rf, "/history/steps/dofs"), series(rf, "/history/steps/seconds"), samples(rf)
    tri = {"full": series(rf, "/history/steps/triangles")} if TRIANGLES else {}
    cols, data = [], []
    for tag, short in PAIRS:
        ra = os.path.join(DIR, "records", tag + ".h5")
        if not os.path.exists(ra) and os.path.exists(ra + ".partial"):
            ra += ".partial"   # stopped with a checkpoint: the steps it has done
        if not os.path.exists(ra):
            continue
        cols += ["dofs_" + short, "seconds_" + short, "rms_" + short, "max_" + short]
        data.append((series(ra, "/history/steps/dofs"), series(ra, "/history/steps/seconds"), samples(ra)))
        if TRIANGLES:
            tri[short] = series(ra, "/history/steps/triangles")
    print(",".join(["step", "t", "dofs_full", "seconds_full"] + cols + ["tri_" + k for k in tri]))
    for k in range(len(t)):
        step = k + 1
        if step % 5 and step != len(t) and step != 1:
            continue
        row = ["%d" % step, "%.6g" % t[k], "%d" % df[k], "%.6g" % sf[k]]
        f = pf.get(step)
        for da, sa, pa in data:
            if k >= len(da):   # a run with fewer steps (stopped): nothing to compare
                row += ["", "", "nan", "nan"]
                continue
            a = pa.get(step)
            rms = mx = float("nan")
            if a and f and len(a) == len(f):
                d = [math.dist(a[i:i + 3], f[i:i + 3]) for i in range(0, len(a), 3)]
                rms = math.sqrt(sum(x * x for x in d) / len(d)) / DIAG
                mx = max(d) / DIAG
            row += ["%d" % da[k], "%.6g" % sa[k], "%.6g" % rms, "%.6g" % mx]
        row += ["%d" % v[k] if k < len(v) else "" for v in tri.values()]
        print(",".join(row))


main()
