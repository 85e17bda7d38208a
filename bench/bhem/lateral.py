#!/usr/bin/env python3
"""bench/bhem/lateral.py — lateral buckling of a heavy vertical plate (BHEM
paper Fig. 20, Romero et al. 2021; issue 39): a scene family over a grid of
Gamma* and w/L, the runs, and the buckled/flat verdicts drawn over the master
curve of bench/bhem/lateral_curve.py (docs/lateral_buckling.md).

    python3 bench/bhem/lateral.py scenes                 # writes the grid's scenes (results/bhem/lateral/scenes/)
    python3 bench/bhem/lateral.py run BIN METHOD [--solver S] [--max-runs N] [--grid small|pair|full]
    python3 bench/bhem/lateral.py table                  # markdown rows from the committed summaries
    python3 bench/bhem/lateral.py plot [METHOD_SOLVER]   # results/bhem/lateral/verdicts_METHOD_SOLVER.png (gnuplot)

The plate: length L = 1 m along xi1 (clamped at xi1 = 0), width w along xi2,
h = 2 mm, Y = 1e7 Pa, nu = 0.3 (Romero et al.'s own values are not available
here: assumed), areal density rho_a = Gamma* D / (g L^3) with D = Y h^3 /
(12 (1 - nu^2)).  Gravity acts in the plate's plane, along -xi2 (the plate
hangs "vertically"); a perturbation of 1e-4 g out of the plane (+z) breaks
the symmetry.  Quasi-static, gravity ramped over 10 load steps, solver `tr`
(`lsnewton` stalls at its limiting accuracy in the first load step on a
quarter of the grid: the in-plane weight on a membrane-stiff plate; its runs
are kept in bhem_lsnewton/ as that finding).  Records (JSON summaries, CPU
seconds) in results/bhem/lateral/METHOD_SOLVER/.  Verdict:
buckled when the largest out-of-plane displacement of the three free-end
probes exceeds L/100 (below the curve the perturbation alone gives about
2e-4 L times the amplification 1/(1 - Gamma*/Gamma*_cr)).
"""
import glob
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import lateral_curve  # noqa: E402

OUT = "results/bhem/lateral"
L, H, Y, NU, G = 1.0, 0.002, 1.0e7, 0.3, 9.81
EPS = 1e-4
THRESHOLD = 0.01 * L
D = Y * H ** 3 / (12 * (1 - NU * NU))
GRIDS = {
    "full": ([0.1, 0.2, 0.3, 0.4, 0.5], list(range(12, 25))),
    "small": ([0.2, 0.4], [12, 16, 20, 24]),
    "pair": ([0.2, 0.4], list(range(12, 25))),
}
# patches (or elements) per metre along each side, per method: bhem as the
# paper (20 per metre); the others about the same dofs
PER_M = {"bhem": 20, "linear_fem": 40, "rmtr": 20, "adaptive_sqrt3": 40}


def tag(r, g):
    return "w%03d_G%02d" % (round(100 * r), g)


def scene(r, g):
    rho = g * D / (G * L ** 3)
    return {
        "name": "lateral_" + tag(r, g),
        "description": ("Lateral buckling (BHEM Fig. 20): plate L = 1 m x w = %.2f m, h = 2 mm, Y = 1e7 Pa, nu = 0.3, "
                        "clamped at xi1 = 0, gravity in its plane along -xi2 plus 1e-4 g out of it; Gamma* = %g "
                        "(rho_a = Gamma* D / (g L^3)). bench/bhem/lateral.py, docs/lateral_buckling.md." % (r, g)),
        "domain": {"type": "rectangle", "origin": [0, 0], "size": [L, r * L]},
        "geometry": {"type": "plane"},
        "material": {"model": "stvk", "young": Y, "poisson": NU, "thickness": H, "density": rho},
        "loads": [{"type": "gravity", "acceleration": [0, -G, EPS * G]}],
        "boundary": [{"type": "clamped", "on": ["left"]}],
        "time": {"mode": "quasi_static", "steps": 10},
        "probes": [{"name": "tip_low", "at": [L, 0]}, {"name": "tip_mid", "at": [L, r * L / 2]},
                   {"name": "tip_high", "at": [L, r * L]}],
        "reference": {"type": "none", "note": "verdict against the master curve, bench/bhem/lateral_curve.py"},
        "resolution": 20,
    }


def write_scenes(grid):
    d = os.path.join(OUT, "scenes")
    os.makedirs(d, exist_ok=True)
    rs, gs = GRIDS[grid]
    paths = []
    for r in rs:
        for g in gs:
            p = os.path.join(d, tag(r, g) + ".json")
            with open(p, "w") as f:
                json.dump(scene(r, g), f, indent=1)
            paths.append((r, g, p))
    return paths


def run(binary, method, max_runs, grid, solver="tr"):
    d = os.path.join(OUT, method + "_" + solver)
    os.makedirs(d, exist_ok=True)
    done = 0
    for r, g, p in write_scenes(grid):
        t = tag(r, g)
        f = os.path.join(d, t + ".json")
        if os.path.exists(f) and os.path.getsize(f) > 0:
            continue
        if max_runs is not None and done >= max_runs:
            print("stopped after %d runs (--max-runs)" % done, file=sys.stderr)
            return 4
        n1 = max(1, round(PER_M[method] * L))
        n2 = max(1 if method == "bhem" else 2, round(PER_M[method] * r * L))
        cmd = ["/usr/bin/time", "-f", '{"cpu_user": %U, "cpu_sys": %S, "wall": %e}', "-o",
               os.path.join(d, t + ".time.json"), "nice", "-n", "10", binary, "run", "--scene", p, "--method",
               method, "--solver", solver, "--res", "%dx%d" % (n1, n2), "--out", "none", "--summary", "json",
               "--quiet", "--set", "run.max_iter=400"]
        print("==", method, t, file=sys.stderr)
        with open(f + ".tmp", "w") as o, open(os.path.join(d, t + ".log"), "w") as e:
            subprocess.run(cmd, stdout=o, stderr=e, env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
        if os.path.getsize(f + ".tmp") == 0:      # refused before any work: keep the sentence
            with open(os.path.join(d, t + ".log")) as e, open(f + ".tmp", "w") as o:
                json.dump({"refused": e.read().strip()}, o)
        os.replace(f + ".tmp", f)
        done += 1
    return 0


def load(config, t):
    p = os.path.join(OUT, config, t + ".json")
    try:
        txt = open(p).read()
        return json.loads(txt[txt.index("{"):])
    except (OSError, ValueError):
        return None


def verdict(d):
    """'buckled', 'flat', or None (not converged / refused)"""
    if not d or "refused" in d or d.get("status") != "converged":
        return None
    probes = d["probes"].values() if isinstance(d["probes"], dict) else d["probes"]
    uz = max(abs(p["displacement"][2]) for p in probes)
    return "buckled" if uz > THRESHOLD else "flat"


def results():
    rows = []
    for f in sorted(glob.glob(os.path.join(OUT, "*", "w*_G[0-9][0-9].json"))):
        method = os.path.basename(os.path.dirname(f))      # METHOD_SOLVER
        if method == "scenes":
            continue
        t = os.path.basename(f)[:-5]
        r = int(t[1:4]) / 100.0
        g = int(t.split("_G")[1])
        d = load(method, t)
        rows.append((method, r, g, d))
    return rows


def curve_points():
    """(w/L, Gamma*_cr) of the committed master curve"""
    pts = []
    for line in open(os.path.join(OUT, "master_curve.csv")):
        if line[0].isdigit():
            a, b, _ = line.split(",")
            pts.append((float(a), float(b)))
    return pts


def curve_at(r):
    pts = curve_points()
    for (a0, b0), (a1, b1) in zip(pts, pts[1:]):
        if a0 <= r <= a1:
            return b0 + (b1 - b0) * (r - a0) / (a1 - a0)
    return float("nan")


def plot(config, png, gnuplot="gnuplot"):
    """the verdicts of one METHOD_SOLVER over the master curve (gnuplot PNG)"""
    import tempfile
    rows = [(r, g, verdict(d)) for m, r, g, d in results() if m == config]
    if not rows:
        return False
    with tempfile.TemporaryDirectory() as tmp:
        files = {}
        for v in ("buckled", "flat", None):
            f = os.path.join(tmp, "%s.dat" % v)
            with open(f, "w") as o:
                for r, g, vv in rows:
                    if vv == v:
                        o.write("%g %g\n" % (r, g))
                o.write("\n")
            files[v] = f
        cf = os.path.join(tmp, "curve.dat")
        with open(cf, "w") as o:
            for a, b in curve_points():
                if a <= 0.6:
                    # second column: B = D w (anticlastic curvature prevented), Gamma*_cr / sqrt(1 - nu^2)
                    o.write("%g %g %g\n" % (a, b, b / math.sqrt(1 - NU * NU)))
        script = """set terminal pngcairo size 720,400 font ",10"
set output '%s'
set xlabel 'w/L'
set ylabel 'Gamma*'
set xrange [0:0.6]
set yrange [11:25]
set key outside right
set title 'Lateral buckling, %s: verdicts over the master curve'
plot '%s' u 1:2 w filledcurves y1=11 lc rgb '#fde0c5' t 'flat (theory)', \\
     '%s' u 1:2 w filledcurves y1=25 lc rgb '#c7eae5' t 'buckled (theory)', \\
     '%s' u 1:2 w l lw 2 lc rgb 'black' t 'Gamma*_cr(w/L)', \\
     '%s' u 1:3 w l lw 1 dt 2 lc rgb 'black' t 'with B = D w', \\
     '%s' w p pt 7 ps 1.2 lc rgb '#01665e' t 'run: buckled', \\
     '%s' w p pt 5 ps 1.0 lc rgb '#b35806' t 'run: flat', \\
     '%s' w p pt 2 ps 1.2 lc rgb 'red' t 'run: not converged'
""" % (png, config.replace("_", " "), cf, cf, cf, cf, files["buckled"], files["flat"], files[None])
        sp = os.path.join(tmp, "p.gp")
        with open(sp, "w") as o:
            o.write(script)
        return subprocess.run([gnuplot, sp]).returncode == 0


if __name__ == "__main__":
    cmd = sys.argv[1] if len(sys.argv) > 1 else ""
    if cmd == "scenes":
        for _, _, p in write_scenes(sys.argv[2] if len(sys.argv) > 2 else "full"):
            print(p)
    elif cmd == "run":
        mr = None
        grid = "full"
        a = sys.argv[4:]
        if "--max-runs" in a:
            mr = int(a[a.index("--max-runs") + 1])
        if "--grid" in a:
            grid = a[a.index("--grid") + 1]
        solver = a[a.index("--solver") + 1] if "--solver" in a else "tr"
        sys.exit(run(sys.argv[2], sys.argv[3], mr, grid, solver))
    elif cmd == "plot":
        cfg = sys.argv[2] if len(sys.argv) > 2 else "bhem_tr"
        sys.exit(0 if plot(cfg, os.path.join(OUT, "verdicts_%s.png" % cfg)) else 1)
    else:
        print(__doc__)
        sys.exit(2)
