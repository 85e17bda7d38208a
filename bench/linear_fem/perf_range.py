#!/usr/bin/env python3
"""bench/linear_fem/perf_range.py — results/linear_fem/perf.md from repeated
outputs of build/bench/bench_linear_fem (concatenated in FILE): a table of
the ranges (min-max over the repetitions) of every figure per
discretization, then the repetitions themselves verbatim.

    python3 bench/linear_fem/perf_range.py FILE > results/linear_fem/perf.md
"""
import re, sys

text = open(sys.argv[1]).read()
rows, header, loads = {}, None, []
for line in text.splitlines():
    if line.startswith("| discretization"):
        header = [c.strip() for c in line.strip("|").split("|")]
    elif line.startswith("| ") and header and not line.startswith("|--") and "---" not in line:
        cells = [c.strip() for c in line.strip("|").split("|")]
        rows.setdefault(cells[0], []).append(cells)
    m = re.match(r"load average \(1 min\) before ([\d.]+), after ([\d.]+)", line)
    if m:
        loads += [float(m.group(1)), float(m.group(2))]

n = max((len(v) for v in rows.values()), default=0)
print("linear_fem Newton-iteration cost: ranges over %d repetitions of bench_linear_fem (thread CPU time, one "
      "core; the machine is shared and was loaded: 1-min load average %s on 2 cores during the runs, so the "
      "figures are upper bounds of an idle machine's)\n" % (n, "%.1f-%.1f" % (min(loads), max(loads)) if loads else "?"))
if header:
    print("| " + " | ".join(header) + " |")
    print("|---|" + "--:|" * (len(header) - 1))
    for name, reps in rows.items():
        out = [name]
        for j in range(1, len(header)):
            vals = []
            for r in reps:
                try:
                    vals.append(float(r[j]))
                except (ValueError, IndexError):
                    pass
            if not vals:
                out.append(reps[0][j] if j < len(reps[0]) else "—")
            elif min(vals) == max(vals):
                out.append(reps[0][j])
            else:
                out.append("%.3g–%.3g" % (min(vals), max(vals)))
        print("| " + " | ".join(out) + " |")
print("\n" + text)
