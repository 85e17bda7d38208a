#!/usr/bin/env python3
"""bench/bhem/ccd_report.py DIR — results/bhem_ccd.md from the JSON summaries
that bench/bhem/ccd.sh wrote into DIR (nothing is re-run): the needle scene
(BHEM paper Fig. 4) with bhem under its own collision pipeline
(contact.model = "impulse") and under the barrier model, the time of the
event `collide` per step and its share of the run, beside the paper's
Table 2 (Needles: t_int = 5.05 s per integration step, t_obj = 26.66 s per
CCD step)."""
import glob
import json
import math
import os
import sys

PAPER = {"dofs": 1.15e4, "sps": 3600, "dt_ms": 2, "t_int": 5.05, "t_obj": 26.66}


def capsule_points(o):
    """the capsule sampling of methods/bhem/bhem_impulse.c: 2 poles, 2 rings of 8
    on each cap, rings of 8 along the shaft at most 2 radii apart"""
    ln = math.dist(o["from"], o["to"])
    rings = 1 + math.ceil(ln / (2 * o["radius"]))
    return 2 * (1 + 2 * 8) + 8 * (rings + 1)


def main():
    d = sys.argv[1]
    rows = []
    for f in sorted(glob.glob(os.path.join(d, "*.json"))):
        with open(f) as fh:
            s = json.load(fh)
        model = "impulse" if "impulse" in os.path.basename(f) else "barrier"
        rows.append((model, s, os.path.basename(f)))
    rows.sort(key=lambda r: (r[0] != "impulse", r[1]["res"]))
    scene = json.load(open("bench/scenes/needles.json"))
    n_obst = sum(capsule_points(o) for o in scene["obstacles"] if o["type"] == "capsule")
    P = print
    P("# bhem: CCD share of the step time on the needle scene (BHEM Table 2)")
    P()
    P("Made by `bench/bhem/ccd.sh` (runs) and `bench/bhem/ccd_report.py` (this file, from the")
    P("JSON summaries in `results/bhem/ccd/`; nothing is re-run).  Scene: `needles` (BHEM Fig. 4, a")
    P("free 0.6 m cloth on 4 x 4 needles, dt = 10 ms, 25 steps) with bhem and `lsnewton`; `impulse` =")
    P("`bench/bhem/scenes/needles_impulse.json` (contact.model = \"impulse\": the §5.2 dynamic")
    P("ray–patch CCD and the §6.2 impulse response after each step, no barrier), `barrier` =")
    P("`bench/scenes/needles.json` (the IPC barrier in the potential and the step filter).")
    P("`collide` is the time of the event of that name: under `impulse` the whole response (detection")
    P("passes and the impulse solves) after each step; under `barrier` the contact term inside every")
    P("evaluation plus the step filter.  share = collide / total run seconds; per step = over the steps")
    P("run.  Sample points under `impulse`: %d on the needles (capsule sampling of bhem_impulse.c) plus" % n_obst)
    P("the cloth's (3 res + 1)^2 midsurface points against the needles' exact shape.  Machine: 2 cores")
    P("shared with other jobs, single-threaded BLAS; times are indicative.")
    P()
    P("| model | res | dofs | steps | status | run s | collide s | share | collide s/step | other s/step | "
      "CCD tests | CCD hits | impulses | passes | unresolved | max strain |")
    P("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for model, s, _ in rows:
        sec = s["seconds"]
        tot, col = sec["total"], sec["collide"]
        st = s["steps"]
        im = s.get("impulse") or s.get("contact") or {}   # summaries before 2026-12-05 had a separate "impulse" object
        ms = max(s["material"]["max_strain"]) if s.get("material") else float("nan")
        P("| %s | %d | %d | %d | %s | %.2f | %.2f | %.1f%% | %.3f | %.3f | %s | %s | %s | %s | %s | %.3g |" % (
            model, s["res"], s["dofs"], st, s["status"], tot, col, 100 * col / tot if tot else float("nan"),
            col / st if st else float("nan"), (tot - col) / st if st else float("nan"),
            im.get("ccd_tests", "–"), im.get("ccd_hits", "–"), im.get("proximity_impulses", "–"),
            im.get("ccd_iterations", "–"), im.get("unresolved_steps", "–"), ms))
    share = PAPER["t_obj"] / (PAPER["t_int"] + PAPER["t_obj"])
    P()
    P("BHEM paper, Table 2, Needles (30 x 30 patches, %.3g dofs, %d sample points on the collider, dt = %d ms,"
      % (PAPER["dofs"], PAPER["sps"], PAPER["dt_ms"]))
    P("with self-collision): t_int = %.2f s per integration step, t_obj = %.2f s per CCD step, a CCD share of"
      % (PAPER["t_int"], PAPER["t_obj"]))
    P("%.1f%% of t_int + t_obj.  Not comparable in absolute terms (their machine, resolution, time step and"
      % (100 * share))
    P("self-collision; ours has none) — the comparison is of the share.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
