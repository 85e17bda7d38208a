#!/usr/bin/env python3
"""bench/bhem/locking_probes.py — the probe positions of the locking runs at
steps 250 (t = 0.5 s: hanging from the diagonal pins, before they slide),
500, 750 and 1000, read from their HDF5 records (or the .partial record of a
run still going or stopped: the finer reference runs take hours on the
shared machine and are read where they got to) with h5dump, into
results/bhem/locking/probes.csv, which the report reads (the records, 22 MB
and more each, are not committed).

    python3 bench/bhem/locking_probes.py [TAG...]
"""
import os
import re
import subprocess
import sys

OUT = "results/bhem/locking"
STEPS = (250, 500, 750, 1000)
TAGS = ("bhem_r10", "linear_fem_r15", "bhem_r20", "linear_fem_r31")


def h5(path, args):
    r = subprocess.run(["h5dump"] + args + [path], capture_output=True, text=True)
    return r.stdout if r.returncode == 0 else ""


def record(tag):
    for p in (os.path.join(OUT, tag + ".h5"), os.path.join(OUT, tag + ".h5.partial")):
        if os.path.exists(p):
            return p
    return None


def main(tags):
    rows = {}
    csv = os.path.join(OUT, "probes.csv")
    if os.path.exists(csv):                      # keep what an earlier call extracted
        for line in open(csv).read().splitlines()[1:]:
            t, s, n = line.split(",")[:3]
            rows[(t, int(s), n)] = line
    for tag in tags:
        p = record(tag)
        if not p:
            continue
        names = re.findall(r'"([A-Za-z0-9_]+)"', h5(p, ["-d", "/probes/names"]).split("DATA {")[-1])
        dims = re.search(r"DATASPACE\s+SIMPLE \{ \( (\d+), (\d+), 3 \)", h5(p, ["-H", "-d", "/probes/trajectory"]))
        if not names or not dims:
            continue
        nrec, npr = int(dims.group(1)), int(dims.group(2))
        for s in STEPS:
            if s >= nrec:
                continue
            txt = h5(p, ["-d", "/probes/trajectory", "-s", "%d,0,0" % s, "-c", "1,%d,3" % npr, "-y", "-w", "0",
                         "-m", "%.9g"])
            vals = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?", txt.split("DATA {")[1].split("}")[0])]
            for k, n in enumerate(names[:npr]):
                x, y, z = vals[3 * k:3 * k + 3]
                rows[(tag, s, n)] = "%s,%d,%s,%.9g,%.9g,%.9g,%s" % (tag, s, n, x, y, z, os.path.basename(p))
    with open(csv, "w") as f:
        f.write("run,step,probe,x,y,z,record\n")
        for k in sorted(rows):
            f.write(rows[k] + "\n")
    print(csv)


if __name__ == "__main__":
    main(sys.argv[1:] or TAGS)
