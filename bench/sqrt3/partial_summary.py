#!/usr/bin/env python3
"""bench/sqrt3/partial_summary.py — a summary of a run stopped with a checkpoint
(`--stop-after-steps`, RUN.h5.partial), or of a finished record, in the
fields of `--summary json` that bench/sqrt3/report.py reads: steps done, the
exclusive seconds and counts of every event, the summed CHOLMOD flops, read
from the file's /stats and /history with h5dump (hdf5-tools).  status
"stopped" for a checkpoint (the run is not finished; it continues with
`--resume`, bench/sqrt3/run.sh paper), else the record's status ("converged"
for status 0) and reason.

    python3 bench/sqrt3/partial_summary.py results/sqrt3/records/TAG.h5.partial > results/sqrt3/runs/TAG.partial.json
"""
import json, re, subprocess, sys


def h5(path, *args):
    return subprocess.run(["h5dump", "-m", "%.17g", "-w", "0"] + list(args) + [path], check=True,
                          capture_output=True, text=True).stdout


def data(text):
    """the values of the first DATA block, numbers or quoted strings"""
    m = re.search(r"DATA \{(.*?)\n\s*\}", text, re.S)
    out = []
    for line in (m.group(1).splitlines() if m else []):
        if ":" not in line:
            continue
        body = line.split(":", 1)[1]
        strs = re.findall(r'"([^"]*)"', body)
        out += strs if strs else [float(v) for v in body.replace(",", " ").split()]
    return out


def main():
    path = sys.argv[1]
    names = data(h5(path, "-a", "/stats/event_names"))
    secs = data(h5(path, "-d", "/stats/events_self_seconds"))
    counts = data(h5(path, "-d", "/stats/events_count"))
    total = data(h5(path, "-a", "/stats/seconds_total"))[0]
    flops = sum(data(h5(path, "-d", "/stats/chol_flops_sum")))
    steps = len(data(h5(path, "-d", "/history/steps/t")))
    dofs = data(h5(path, "-d", "/history/steps/dofs"))
    code = int(data(h5(path, "-a", "/status"))[0])
    reason = data(h5(path, "-a", "/reason"))[0]
    partial = path.endswith(".partial")
    out = {"file": path, "status": "stopped" if partial else ("converged" if code == 0 else "not converged"),
           "reason": "checkpoint" if partial else reason, "steps": steps,
           "dofs": int(dofs[-1]) if dofs else None,
           "seconds": dict(zip(names, secs[:len(names)]), total=total),
           "counts": {k: int(v) for k, v in zip(names, counts[:len(names)])},
           "linear_algebra": {"factor_flops_sum": flops}}
    json.dump(out, sys.stdout, indent=1)
    print()


main()
