#!/usr/bin/env python3
"""bench/bhem/fem_stats.py — reduce one run of bench/bhem/fem_compare.sh to
the small JSON the report is made from (the .h5 record is not committed).

    python3 bench/bhem/fem_stats.py wrinkle|drape RECORD.h5 PROFILE.csv CPUFILE > TAG.stats.json

  steps        per load/time step: [iterations, seconds (wall, from the record)]
  cpu_seconds  user + system CPU seconds of the run (/usr/bin/time; the
               machine is shared, so wall seconds are not a measure)
  wrinkle      bench/bhem/wrinkles.py on the profile (half-waves, crests,
               wavelength, peak amplitude in mm) — the statistics of the
               BHEM report's wrinkled-sheet table
  drape        z (mm, 0.1 mm) of the final surface on the 51 x 51 grid
               s, t = 0, 0.02, ..., 1 (every second point of the 101 x 101
               profile); report.py finds crests and compares runs on it
"""
import json, os, subprocess, sys

kind, h5, prof, cpuf = sys.argv[1:5]


def dset(path):
    out = subprocess.run(["h5dump", "-y", "-w", "0", "-d", path, h5], capture_output=True, text=True).stdout
    if "DATA {" not in out:
        return []
    body = out.split("DATA {", 1)[1].split("}", 1)[0]
    return [float(v) for v in body.replace("\n", " ").split(",") if v.strip()]


it, sec = dset("/history/steps/iterations"), dset("/history/steps/seconds")
res = {"steps": [[int(a), round(b, 4)] for a, b in zip(it, sec)]}
try:
    # /usr/bin/time -f '%U %S' writes "Command exited with non-zero status N" first for a failed run
    u, s = open(cpuf).read().strip().splitlines()[-1].split()[:2]
    res["cpu_seconds"] = round(float(u) + float(s), 2)
except (OSError, ValueError):
    res["cpu_seconds"] = None
txt = open(prof).read()
if kind == "wrinkle":
    here = os.path.dirname(os.path.abspath(__file__))
    st = subprocess.run([sys.executable, os.path.join(here, "wrinkles.py")], input=txt, capture_output=True, text=True)
    res["wrinkle"] = json.loads(st.stdout) if st.returncode == 0 else None
else:
    rows = [l.split(",") for l in txt.splitlines()[1:] if l]
    z = {}
    for r in rows:
        i, j = round(float(r[0]) * 100), round(float(r[1]) * 100)
        if i % 2 == 0 and j % 2 == 0:
            z[(i // 2, j // 2)] = round(float(r[4]) * 1000, 1)
    res["drape"] = {"n": 51, "z_mm": [[z.get((i, j)) for i in range(51)] for j in range(51)]}
print(json.dumps(res, separators=(",", ":")))
