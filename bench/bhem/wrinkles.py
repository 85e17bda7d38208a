#!/usr/bin/env python3
"""Wrinkle statistics of a BHEM wrinkled-sheet run from its surface profile
(bhem_profile CSV on stdin, a fine grid over the whole sheet):
  - centre line s = 1/2 (across the width): out-of-plane profile z(y)
  - wrinkles = number of crests+troughs of z(y) whose |z| exceeds 10 % of the
    line's peak (half waves), wavelength = 2 x mean spacing of those extrema
  - peak amplitude = max |z| over the whole sheet and over the centre line.
Prints one JSON object."""
import json, sys

rows = [l.strip().split(',') for l in sys.stdin if l[0].isdigit() or l[0] == '-']
pts = [tuple(map(float, r)) for r in rows]
ss = sorted(set(p[0] for p in pts))
mid = min(ss, key=lambda s: abs(s - 0.5))
line = sorted([p for p in pts if p[0] == mid], key=lambda p: p[1])
zl = [p[4] for p in line]
yl = [p[3] for p in line]
peak_line = max(abs(z) for z in zl) if zl else 0.0
ext = []
for i in range(1, len(zl) - 1):
    if (zl[i] - zl[i-1]) * (zl[i+1] - zl[i]) < 0 and abs(zl[i]) > 0.1 * peak_line:
        ext.append(yl[i])
lam = 2 * (ext[-1] - ext[0]) / (len(ext) - 1) if len(ext) > 1 else float('nan')
print(json.dumps({
    "half_waves": len(ext),
    "crests": sum(1 for i in range(1, len(zl) - 1) if zl[i] > zl[i-1] and zl[i] >= zl[i+1] and zl[i] > 0.1 * peak_line),
    "wavelength_mm": lam * 1000,
    "peak_amplitude_mm": max(abs(p[4]) for p in pts) * 1000,
    "centre_line_peak_mm": peak_line * 1000,
}))
