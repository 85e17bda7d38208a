#!/usr/bin/env python3
"""bench/bhem/scenes/gen_umbrella.py — writes umbrella_fold.json, the BHEM
paper's oriental paper parasol (Fig. 5, Table 2 row Umbrella: 280 x 5
patches, 2.02e4 dofs, Y = 1e6 Pa, nu = 0.5, h = 0.1 mm, rho = 930 kg/m^3,
alpha = 5, dt = 2 ms), folded by its ribs through prescribed nodal positions
and first derivatives (the moving boundary's "derivative" key, bhem only).

    python3 bench/bhem/scenes/gen_umbrella.py > bench/bhem/scenes/umbrella_fold.json

The paper gives neither the canopy's size, nor the ribs' number, nor their
motion.  Assumed: a flat annulus (the open parasol, r_in = 5 cm at the
crown, r_out = 0.5 m), closed in the angle (280 patches around, 5 along the
radius: 6 x 280 nodes x 12 = 20,160 dofs), RIBS = 28 ribs every 10 patches;
each rib is a rigid radial line hinged at the crown ring: its 6 nodes turn
about the horizontal axis e_theta through the rib's inner end by FOLD
degrees (the outer end goes down), their positions and their first
derivative along the rib (d/ds) prescribed, the derivative across (d/dt)
free, so the paper between two ribs folds.  The crown ring is fixed.
"""
import json
import math

RIBS, PER = 28, 10            # ribs, patches between two ribs (RIBS * PER = 280 around)
R_IN, R_OUT, NS = 0.05, 0.5, 5
FOLD = 60.0                   # degrees each rib turns down over RAMP steps
STEPS, RAMP = 15, 300           # the bundled run: the first 15 steps of the 300-step fold (large mode: all)

bcs = [{"type": "fixed", "on": ["inner"]}]
for k in range(RIBS):
    th = 2.0 * math.pi * k / RIBS
    c, s = math.cos(th), math.sin(th)
    pts = [[round((R_IN + (R_OUT - R_IN) * i / NS) * c, 12), round((R_IN + (R_OUT - R_IN) * i / NS) * s, 12)]
           for i in range(NS + 1)]
    bcs.append({"type": "moving", "at": pts,
                "rotation": {"axis": [round(-s, 12), round(c, 12), 0.0],
                             "center": [round(R_IN * c, 12), round(R_IN * s, 12), 0.0], "angle": FOLD},
                "ramp_steps": RAMP, "derivative": "s"})
scene = {
    "name": "umbrella_fold",
    "description": ("BHEM paper Fig. 5 / Table 2 row Umbrella: a paper parasol folded by its ribs, nodal positions and "
                    "first derivatives along the ribs prescribed (moving bcs with \"derivative\": \"s\"; bhem only). "
                    "Table 2: Y 1e6 Pa, nu 0.5, h 0.1 mm, rho 930 kg/m^3, alpha 5, dt 2 ms, 280x5 patches (2.02e4 dofs). "
                    "Assumed: flat annulus r 0.05-0.5 m, 28 ribs hinged at the fixed crown ring, each turning down "
                    "60 deg over 300 steps. From gen_umbrella.py."),
    "domain": {"type": "annulus_sector", "center": [0, 0], "r_in": R_IN, "r_out": R_OUT, "theta": [0, 360]},
    "geometry": {"type": "plane"},
    "material": {"model": "stvk", "young": 1e6, "poisson": 0.5, "thickness": 0.0001, "density": 0.093},
    "loads": [{"type": "gravity", "acceleration": [0, 0, -9.81]}],
    "boundary": bcs,
    "time": {"mode": "dynamic", "dt": 0.002, "steps": STEPS, "rayleigh": {"alpha": 5, "beta": 0}},
    "probes": [{"name": "rib0_tip", "at": [R_OUT, 0.0]},
               {"name": "mid_panel_rim", "at": [round(R_OUT * math.cos(math.pi / RIBS), 12),
                                                 round(R_OUT * math.sin(math.pi / RIBS), 12)]}],
    "resolution": [NS, RIBS * PER],
}
print(json.dumps(scene, indent=1))
