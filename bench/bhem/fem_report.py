#!/usr/bin/env python3
"""bench/bhem/fem_report.py — the BHEM report's sections on the paper's
comparisons with triangle FEM (Figs. 14-17, issue 39), made only from the
committed summaries of bench/bhem/fem_compare.sh in results/bhem/fem/
(TAG.json: `shellbench run --summary json`; TAG.stats.json: bench/bhem/
fem_stats.py; TAG.png: `shellbench render`).  Never re-runs anything.

    python3 bench/bhem/fem_report.py [FEM_DIR]            # the sections, to stdout
    python3 bench/bhem/fem_report.py --splice REPORT.md   # replace them in REPORT.md

bench/bhem/report.py appends fem_sections() to results/bhem_report.md;
--splice rewrites only the block between the markers below (so the rest of
a report made from records that are not committed stays as it was).
"""
import glob, json, math, os, subprocess, sys

BEGIN, END = "<!-- fem-beside-bhem: begin (bench/bhem/fem_report.py) -->", "<!-- fem-beside-bhem: end -->"
CREST_MM = 2.0      # a crest along a cut stands this far above the cut's local (16 cm) mean height
HALF = 4            # half-width (grid points, 2 cm each) of that moving mean
MATCH = 2           # ... and lies within this many grid points (4 cm) of a reference crest to be real


def load(d, tag):
    out = {}
    try:
        t = open(os.path.join(d, tag + ".json")).read()
        out["run"] = json.loads(t[t.index("{"):])
    except (OSError, ValueError):
        return None
    try:   # a run counts once fem_compare.sh has reduced it (a .json alone may be a run in progress)
        out["stats"] = json.load(open(os.path.join(d, tag + ".stats.json")))
    except (OSError, ValueError):
        return None
    return out


def verts(info):
    """vertex count from a linear_fem method description ("...: 697 vertices, ...")"""
    for part in info.split(","):
        w = part.split()
        if len(w) >= 2 and w[-1] == "vertices":
            return int(w[-2])
    return None


def f(x, fmt="%.3g"):
    return "—" if x is None or (isinstance(x, float) and not math.isfinite(x)) else fmt % x


def label(r):
    m = r["run"]
    if m["method"] == "bhem":
        return "BHEM(%s) %d²" % ("p" if "pseudo" in m["method_info"] else "e", m["res"])
    return "FEM %d vertices" % verts(m["method_info"])


# ---- crests along cuts of the drape's height field (the fake-wrinkle criterion) ----
def cuts(z):
    n = len(z)
    return {"s=1/2": [z[j][n // 2] for j in range(n)], "t=1/2": [z[n // 2][i] for i in range(n)],
            "diagonal": [z[i][i] for i in range(n)], "antidiagonal": [z[i][n - 1 - i] for i in range(n)]}


def crests(line):
    """wrinkle crests along a cut: local maxima of the high-passed height h = z - (its moving average over
    +-HALF grid points, 2 x HALF + 1 = 9 points = 16 cm) with h > CREST_MM; the sag of the cloth (a trend over
    the whole 1 m) is removed, folds of a few cm remain"""
    n = len(line)
    if any(v is None for v in line):
        return []
    h = []
    for i in range(n):
        w = line[max(0, i - HALF):min(n, i + HALF + 1)]
        h.append(line[i] - sum(w) / len(w))
    return [i for i in range(HALF, n - HALF) if h[i] > CREST_MM and h[i] >= h[i - 1] and h[i] > h[i + 1]]


def drape_metrics(r, ref):
    z = r["stats"].get("drape", {}).get("z_mm")
    zr = ref["stats"].get("drape", {}).get("z_mm") if ref else None
    if not z or not zr:
        return None
    n = fake = missing = 0
    for k, line in cuts(z).items():
        c, cr = crests(line), crests(cuts(zr)[k])
        n += len(c)
        fake += sum(1 for i in c if all(abs(i - j) > MATCH for j in cr))
        missing += sum(1 for j in cr if all(abs(i - j) > MATCH for i in c))
    d2 = [(a - b) ** 2 for row, rowr in zip(z, zr) for a, b in zip(row, rowr) if a is not None and b is not None]
    return {"crests": n, "fake": fake, "missing": missing, "rms_mm": math.sqrt(sum(d2) / len(d2)) if d2 else None}


def curves(runs, png, title, xlabel):
    """gnuplot: cumulative iterations and CPU seconds (the run's CPU total spread over its steps by their
    wall-second shares) against the step, one curve per run"""
    dat = png[:-4] + ".dat"
    blocks = []
    for r in runs:
        st, cpu = r["stats"].get("steps"), r["stats"].get("cpu_seconds")
        if not st or not cpu:
            continue
        tw = sum(s[1] for s in st) or 1.0
        ci = cs = 0.0
        rows = ["# %s" % label(r), "0 0 0"]
        for k, (it, sec) in enumerate(st):
            ci += it
            cs += cpu * sec / tw
            rows.append("%d %d %.4g" % (k + 1, ci, cs))
        blocks.append((label(r), "\n".join(rows)))
    if not blocks:
        return False
    with open(dat, "w") as fh:
        fh.write("\n\n\n".join(b for _, b in blocks) + "\n")
    dash = lambda t: 1 if t.startswith("BHEM(e)") else 2 if t.startswith("BHEM(p)") else 3
    plots = lambda col: ", ".join("'%s' index %d using 1:%d with linespoints lc %d dt %d pt 7 ps 0.4 title '%s'"
                                  % (dat, i, col, i + 1, dash(t), t) for i, (t, _) in enumerate(blocks))
    gp = ("set terminal pngcairo size 1000,340 font ',9'\nset output '%s'\nset multiplot layout 1,2 title '%s'\n"
          "set key outside right top\nset grid\nset xlabel '%s'\nset ylabel 'iterations (cumulative)'\nplot %s\n"
          "set ylabel 'CPU seconds (cumulative)'\nset logscale y\nunset key\nplot %s\nunset multiplot\n"
          % (png, title + " (solid BHEM(e), dashed BHEM(p), dotted FEM)", xlabel, plots(2), plots(3)))
    rc = subprocess.run(["gnuplot"], input=gp, text=True, capture_output=True).returncode
    os.remove(dat)
    return rc == 0 and os.path.exists(png)


def amp(r):
    return ((r["stats"].get("wrinkle") or {}).get("peak_amplitude_mm")) or 0.0


def finest(rows, method, pseudo=False):
    rs = [r for r in rows if r["run"]["method"] == method and ("pseudo" in r["run"]["method_info"]) == pseudo]
    return max(rs, key=lambda r: r["run"]["dofs"]) if rs else None


def nc(r):
    """ " **not converged** (reason)" for a run that did not converge: its iterations and seconds are those to the
    failure, not to a solution, so a comparison row says so"""
    run = r["run"]
    return "" if run.get("status") == "converged" else " **not converged** (%s)" % run.get("reason", "?")


def paper_rows(W, D):
    """one row per claim of the paper: its number, ours, the ratio, the differences of setting"""
    out = ["| paper | claim (paper's number) | ours | ratio ours / paper | differences of setting |",
           "|---|---|---|---|---|"]
    w = list(W.values())
    be, fe = finest(w, "bhem"), finest(w, "linear_fem")
    if be:
        out.append("| Fig. 17 | BHEM peak amplitude 0.34 mm at 30² patches (11.5k dofs) | %.3f mm at %s (%d dofs) | %.2f | "
                   "stretch 10 %% and 1 µm imperfection assumed (not stated) |" % (amp(be), label(be), be["run"]["dofs"],
                                                                                  amp(be) / 0.34))
    if fe:
        out.append("| Fig. 17 | FEM peak amplitude 0.31 mm at 130k vertices (390k dofs) | %.3f mm at %s (%d dofs) | %s | "
                   "our largest FEM run (the 130k-vertex run is in the large mode, not run); linear_fem midedge with "
                   "edge directors for Libshell |" % (amp(fe), label(fe), fe["run"]["dofs"], f(amp(fe) / 0.31, "%.2f")))
    if be and fe:
        cands = [r for r in w if r["run"]["method"] == "linear_fem"]
        near = min(cands, key=lambda r: abs(r["run"]["dofs"] - be["run"]["dofs"]))
        out.append("| Fig. 14 | FEM: fewer iterations, much more time than BHEM | nearest in dofs (of the runs made), %s (%d dofs) against "
                   "%s (%d): %d against %d iterations, %.1f against %.1f CPU s (peak %.3f against %.3f mm) | "
                   "iterations %.2f×, time %.2f× (FEM / BHEM) | CPU seconds on a shared machine; no wall clock |" % (
                       label(near) + nc(near), near["run"]["dofs"], label(be) + nc(be), be["run"]["dofs"], near["run"]["iterations"],
                       be["run"]["iterations"], near["stats"]["cpu_seconds"], be["stats"]["cpu_seconds"], amp(near),
                       amp(be), near["run"]["iterations"] / be["run"]["iterations"],
                       near["stats"]["cpu_seconds"] / be["stats"]["cpu_seconds"]))
    # exact against pseudo at the finest resolution where both converged (a stalled run's counts are to its failure)
    pairs = []
    for q in sorted((r for r in w if r["run"]["method"] == "bhem" and "pseudo" in r["run"]["method_info"]),
                    key=lambda r: -r["run"]["dofs"]):
        ex = [r for r in w if r["run"]["method"] == "bhem" and r["run"]["res"] == q["run"]["res"]
              and "pseudo" not in r["run"]["method_info"]]
        if ex:
            pairs.append((ex[0], q))
    both = [(e, q) for e, q in pairs if not nc(e) and not nc(q)]
    failed = ["%d²: %s %d iterations, %s" % (q["run"]["res"], "pseudo" if nc(q) else "exact", (q if nc(q) else e)["run"]
              ["iterations"], (q if nc(q) else e)["run"].get("reason", "?")) for e, q in pairs if nc(e) or nc(q)]
    bp = (both[0] if both else pairs[0] if pairs else (None, None))[1]
    be2 = [(both[0] if both else pairs[0])[0]] if pairs else []
    if bp and be2:
        e = be2[0]
        out.append("| Figs. 14, 16 | BHEM with the exact Hessian: more time, fewer iterations than with the pseudo "
                   "Hessian | wrinkled sheet %d²: exact %d iterations, %.1f CPU s%s; pseudo %d iterations, %.1f CPU s%s | "
                   "%s | %s |" % (
                       e["run"]["res"], e["run"]["iterations"], e["stats"]["cpu_seconds"], nc(e), bp["run"]["iterations"],
                       bp["stats"]["cpu_seconds"], nc(bp), "iterations %.2f×, time %.2f× (exact / pseudo)" % (
                           e["run"]["iterations"] / bp["run"]["iterations"],
                           e["stats"]["cpu_seconds"] / bp["stats"]["cpu_seconds"]) if not nc(e) and not nc(bp) else
                       "— (a run that did not converge: its counts are to its failure)",
                       "not converged: %s" % "; ".join(failed) if failed else "—"))
    d = list(D.values())
    bd = finest(d, "bhem")
    fems = [r for r in d if r["run"]["method"] == "linear_fem"]
    if bd and fems:
        near = min(fems, key=lambda r: abs(r["run"]["dofs"] - bd["run"]["dofs"]))
        big = [r for r in fems if verts(r["run"]["method_info"]) >= 4000]
        for fd, how in [(near, "nearest in dofs of the runs made")] + ([(big[0], "4k vertices, as the paper")] if big and big[0] is not near else []):
            out.append("| Fig. 16 | BHEM 30² (11.5k dofs) converges in much fewer iterations and less time than FEM at "
                       "4k vertices (12k dofs) | %s (%d dofs): %d iterations, %.1f CPU s; %s (%d dofs, %s): %d "
                       "iterations, %.1f CPU s | %s | corners pinned, not "
                       "clamped (both methods); 1 m square, 0.1 m inward motion assumed; our FEM has 6 dofs per "
                       "vertex |" % (
                           label(bd) + nc(bd), bd["run"]["dofs"], bd["run"]["iterations"], bd["stats"]["cpu_seconds"],
                           label(fd) + nc(fd),
                           fd["run"]["dofs"], how, fd["run"]["iterations"], fd["stats"]["cpu_seconds"],
                           "iterations %.2f×, time %.2f× (FEM / BHEM)" % (
                               fd["run"]["iterations"] / bd["run"]["iterations"],
                               fd["stats"]["cpu_seconds"] / bd["stats"]["cpu_seconds"])
                           if not nc(fd) and not nc(bd) else "— (a run that did not converge: its counts are to its "
                           "failure)"))
        cf = min((r for r in d if r["run"]["method"] == "linear_fem"), key=lambda r: r["run"]["dofs"])
        cb = min((r for r in d if r["run"]["method"] == "bhem"), key=lambda r: r["run"]["dofs"])
        mf, mb = drape_metrics(cf, bd) or {}, drape_metrics(cb, bd) or {}
        out.append("| Fig. 15 | at low resolution FEM (500 vertices) makes fake wrinkles, BHEM (5²) is over-smoothed | "
                   "%s: %s fake, %s missing crests; %s: %s fake, %s missing (against %s) | — | criterion below; "
                   "reference = our finest BHEM(e) run |" % (label(cf), mf.get("fake", "—"), mf.get("missing", "—"),
                                                             label(cb), mb.get("fake", "—"), mb.get("missing", "—"),
                                                             label(bd)))
        mn, mr = drape_metrics(near, bd) or {}, drape_metrics(bd, bd) or {}
        out.append("| Fig. 15 | at comparable dofs BHEM (30², 11.5k) shows more vivid wrinkles than FEM (4k vertices, "
                   "12k dofs) | %s: %s crests; %s (nearest in dofs of the runs made): %s crests, %s of them fake, %s of the reference's "
                   "missing, RMS Δz %s mm | — | crests as below |" % (
                       label(bd), mr.get("crests", "—"), label(near), mn.get("crests", "—"), mn.get("fake", "—"),
                       mn.get("missing", "—"), f(mn.get("rms_mm"), "%.1f")))
    return out if len(out) > 2 else []


# every run bench/bhem/fem_compare.sh plans (mode all, then large), for the "not run" lines
PLANNED = [("w_bhem_e_r30", "BHEM(e) 30²"), ("w_bhem_p_r30", "BHEM(p) 30²"), ("w_fem_r240", "FEM 240×96 (23k vertices)"),
           ("w_fem_r320", "FEM 320×128 (41k vertices, large mode)"), ("w_fem_r480", "FEM 480×192 (93k vertices, large mode)"),
           ("w_fem_r570", "FEM 570×228 (130k vertices, large mode)"), ("d_fem_r44", "FEM 44² (2025 vertices, 12k dofs)"),
           ("d_fem_r63", "FEM 63² (4096 vertices)"), ("d_bhem_p_r30", "BHEM(p) 30²")]


def not_run(d, prefix):
    miss = [what for tag, what in PLANNED if tag.startswith(prefix) and not os.path.exists(os.path.join(d, tag + ".stats.json"))]
    return ("Planned by fem_compare.sh but not run (CPU budget; `bash bench/bhem/fem_compare.sh build/shellbench %s` "
            "resumes%s): %s.\n"
            % ("wrinkle" if prefix == "w_" else "drape",
               ", `large --max-runs 1` does one large run per call" if prefix == "w_" else "", ", ".join(miss))
            if miss else "")


def fem_sections(d="results/bhem/fem", reldir="bhem/fem"):
    out = []
    P = out.append
    W = {t: load(d, t) for t in [os.path.basename(p)[:-5] for p in glob.glob(os.path.join(d, "w_*.json"))
                                  if not p.endswith(".stats.json")]}
    D = {t: load(d, t) for t in [os.path.basename(p)[:-5] for p in glob.glob(os.path.join(d, "d_*.json"))
                                  if not p.endswith(".stats.json")]}
    W = {k: v for k, v in W.items() if v}
    D = {k: v for k, v in D.items() if v}
    if not W and not D:
        return out
    P(BEGIN)
    P("\n## Linear FEM beside BHEM (paper Figs. 14–17)\n")
    P("Made by `bash bench/bhem/fem_compare.sh build/shellbench all` (records in `results/bhem/fem/`, reduced to the "
      "committed `TAG.json` / `TAG.stats.json` / `TAG.png`) and `python3 bench/bhem/fem_report.py --splice "
      "results/bhem_report.md`.  The paper compares with Libshell (Vouga 2021) on randomly triangulated meshes.  "
      "Here `linear_fem` on `jitter` meshes (interior vertices moved by up to 0.3 of the cell size, then Delaunay "
      "flips; seed 1) with **midedge bending and one director per edge**: that is Libshell's "
      "MidedgeAngleTanFormulation (Chen et al. 2018) up to the tangent of the midedge angle against the angle itself "
      "(they agree to third order, docs/linear_fem.md), and it converges to Kirchhoff–Love on jittered meshes, "
      "where the averaged-director and hinge models level off at 10–25 % errors (results/linear_fem_report.md).  "
      "Its dofs are 3 per vertex plus 1 per edge (about 6 per vertex); the paper counts 3 per vertex (390k dofs for "
      "130k vertices), so rows give vertices and our dofs.  Same solver for all (`lsnewton`, direct CHOLMOD), "
      "the default (fast) shell kernel, `OPENBLAS_NUM_THREADS=1`.  **Seconds are process CPU seconds** "
      "(/usr/bin/time; the 2-core machine's load average was 25–43 while these ran, so wall seconds measure "
      "the load, not the method).\n")
    out.extend(paper_rows(W, D))
    P("")

    # ---- wrinkled sheet: Figs. 14 and 17 ----
    if W:
        P("### Wrinkled sheet (Fig. 14 convergence, Fig. 17 amplitude)\n")
        P("bench/bhem/scenes/wrinkled_sheet.json (stretch 10 %, 20 quasi-static load steps) with the same 1 µm "
          "imperfection for both methods (`method.imperfection`, one field of the grid parameter, "
          "core/scene/sb_imperfection.c: bhem adds it at its nodes, linear_fem at its vertices).  FEM meshes "
          "N × 0.4N cells (near-isotropic triangles on the 0.25 m × 0.1 m sheet).  Wrinkle statistics as in the "
          "wrinkled-sheet table above (centre line s = 1/2, half-waves above 10 % of its peak); *flat*: peak below "
          "0.01 mm, ten times the imperfection (the peak is then the imperfection left at the clamped ends).  "
          "BHEM at 30² is in the wrinkled-sheet table above (made by run_bench.sh with the reference "
          "kernel); it was not run again here.\n")
        P("*Indefinite* counts the Newton iterations whose Hessian CHOLMOD found not positive definite: 0 means the "
          "discrete energy was convex at every iterate, i.e. the flat state (or the wrinkled one) was a stable "
          "minimum of that discretization, not a saddle the solver stopped at.\n")
        P("| run | vertices | dofs | status | reason | iterations | indefinite | CPU s | half-waves | wavelength (mm) | peak amplitude (mm) |")
        P("|---|---|---|---|---|---|---|---|---|---|---|")
        rows = sorted(W.values(), key=lambda r: (r["run"]["method"] != "bhem", "pseudo" in r["run"]["method_info"],
                                                 r["run"]["dofs"]))
        for r in rows:
            m, s = r["run"], r["stats"]
            w = dict(s.get("wrinkle") or {})
            if (w.get("peak_amplitude_mm") or 0.0) < 0.01:   # below 10 x the imperfection: flat, no wave to count
                w["half_waves"], w["wavelength_mm"] = "flat", None
            P("| %s | %s | %d | %s | %s | %d | %s | %s | %s | %s | %s |" % (
                label(r), f(verts(m["method_info"]), "%d"), m["dofs"], m["status"], m["reason"], m["iterations"],
                f((m.get("linear_algebra") or {}).get("not_posdef"), "%d"), f(s.get("cpu_seconds"), "%.1f"), w.get("half_waves", "—"), f(w.get("wavelength_mm"), "%.1f"),
                f(w.get("peak_amplitude_mm"), "%.3f")))
        png = os.path.join(d, "fig14.png")
        if curves(rows, png, "wrinkled sheet: BHEM(e), BHEM(p), FEM (jitter)", "load step"):
            P("\n![Fig. 14: cumulative iterations and CPU seconds per load step](%s/fig14.png)\n" % reldir)
        # the paper's claim, checked
        fem = [r for r in rows if r["run"]["method"] == "linear_fem" and r["run"]["status"] == "converged"]
        be = [r for r in rows if r["run"]["method"] == "bhem" and "pseudo" not in r["run"]["method_info"]]
        ref = max(be, key=lambda r: r["run"]["dofs"]) if be else None
        if ref and fem:
            a_ref = amp(ref)
            good = [r for r in fem if amp(r) >= 0.9 * a_ref]
            P("Checking \"FEM takes fewer iterations but much more time\": BHEM(e) at its finest (%s) gives %.3f mm.  "
              % (label(ref), a_ref) + (
                  "The smallest FEM run within 10 %% of that amplitude is %s (%d dofs): %d iterations and %.1f CPU s "
                  "against BHEM(e)'s %d and %.1f at %d dofs — %.2f× the iterations, %.1f× the CPU time.  "
                  % (label(good[0]), good[0]["run"]["dofs"], good[0]["run"]["iterations"],
                     good[0]["stats"]["cpu_seconds"], ref["run"]["iterations"], ref["stats"]["cpu_seconds"],
                     ref["run"]["dofs"], good[0]["run"]["iterations"] / ref["run"]["iterations"],
                     good[0]["stats"]["cpu_seconds"] / ref["stats"]["cpu_seconds"])
                  if good else
                  "No FEM run here reaches 90 %% of it (largest: %s, %.3f mm), so the time to a converged wrinkle "
                  "is beyond every FEM run made; the iterations of the FEM runs are in the table.  " %
                  (label(fem[-1]), amp(fem[-1]))))
        P("\n#### Fig. 17: peak amplitude against resolution\n")
        P("| method | vertices | dofs | peak amplitude (mm) | / BHEM(e) finest |")
        P("|---|---|---|---|---|")
        for r in [r for r in rows if "pseudo" not in r["run"]["method_info"]]:
            P("| %s | %s | %d | %s | %s |" % (label(r), f(verts(r["run"]["method_info"]), "%d"), r["run"]["dofs"],
                                              f(amp(r), "%.3f"), f(amp(r) / amp(ref) if ref and amp(ref) else None, "%.2f")))
        P("\n" + not_run(d, "w_"))

    # ---- draped cloth: Figs. 15 and 16 ----
    if D:
        P("### Draped cloth (Figs. 15–16)\n")
        P("bench/bhem/scenes/draped_cloth_pinned.json: the draped cloth of the table above with the corners prescribed "
          "in **position only** for both methods (a triangle mesh has no rotation at a vertex; linear_fem refuses a "
          "clamped point), 100 steps of 10 ms.  Pinned corners are point constraints whose membrane strain is "
          "singular: bhem 10² passes the default bound (Green–Lagrange strain 1) at step 30, so these runs set "
          "`run.strain_max=0` (no bound); *max strain* below is the largest over the material points.  FEM at "
          "21², 31², 44², 63² cells (about 500, 1k, 2k, 4k vertices: the paper's columns).\n")
        P("**Fake wrinkles, the criterion.**  Along four cuts of the final surface (s = 1/2, t = 1/2 and both "
          "diagonals; height z on a 51 × 51 grid of the material square, 2 cm spacing) a *crest* is a local maximum "
          "of the high-passed height — z minus its mean over the 9 grid points (16 cm) around — above %.0f mm, "
          "away from the cut's ends (the sag of the cloth, a trend over the whole metre, is removed; folds of a "
          "few cm remain).  A crest is *fake* when the converged "
          "solution — the finest BHEM(e) run — has no crest within %d grid points (4 cm) of it on the same "
          "cut; a reference crest with no crest near it is *missing* (over-smoothed).  RMS Δz is the height "
          "difference to that reference over the grid.  All runs compare at the same time, t = 1 s.\n"
          % (CREST_MM, MATCH))
        rows = sorted(D.values(), key=lambda r: (r["run"]["method"] != "bhem", "pseudo" in r["run"]["method_info"],
                                                 r["run"]["dofs"]))
        ref = [r for r in rows if r["run"]["method"] == "bhem" and "pseudo" not in r["run"]["method_info"]]
        ref = max(ref, key=lambda r: r["run"]["dofs"]) if ref else None
        P("| run | vertices | dofs | status | steps | iterations | CPU s | CPU s / step | max strain | crests | fake | missing | RMS Δz (mm) |")
        P("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            m, s = r["run"], r["stats"]
            dm = drape_metrics(r, ref) or {}
            ms = (m.get("material") or {}).get("max_strain")
            P("| %s | %s | %d | %s (%s) | %d/%d | %d | %s | %s | %s | %s | %s | %s | %s |" % (
                label(r), f(verts(m["method_info"]), "%d"), m["dofs"], m["status"], m["reason"], m["steps"],
                m["steps_planned"], m["iterations"], f(s.get("cpu_seconds"), "%.1f"),
                f(s["cpu_seconds"] / max(1, m["steps"]) if s.get("cpu_seconds") else None, "%.3f"),
                f(max(ms) if ms else None, "%.2f"), dm.get("crests", "—"), dm.get("fake", "—"),
                dm.get("missing", "—"), f(dm.get("rms_mm"), "%.1f")))
        png = os.path.join(d, "fig16.png")
        if curves(rows, png, "draped cloth: BHEM(e), BHEM(p), FEM (jitter)", "time step"):
            P("\n![Fig. 16: cumulative iterations and CPU seconds per time step](%s/fig16.png)\n" % reldir)
        fem = [r for r in rows if r["run"]["method"] == "linear_fem"]
        bh = [r for r in rows if r["run"]["method"] == "bhem" and "pseudo" not in r["run"]["method_info"]]
        pics = lambda rs: [(label(r), "%s/%s.png" % (reldir, os.path.basename(r["run"]["file"])[:-3])) for r in rs
                           if os.path.exists(os.path.join(d, os.path.basename(r["run"]["file"])[:-3] + ".png"))]
        fp, bp = pics(fem), pics(bh)
        if fp or bp:
            P("\nFinal states (t = 1 s), as the paper's Fig. 15: FEM above, BHEM below, resolution increasing to the "
              "right (`shellbench render`, 200×150, 4 samples per pixel).\n")
            k = max(len(fp), len(bp))
            P("| " + " | ".join(["   "] * k) + " |")
            P("|" + "---|" * k)
            for ps in (fp, bp):
                cells = ["![%s](%s)<br>%s" % (t, p, t) for t, p in ps] + ["—"] * (k - len(ps))
                P("| " + " | ".join(cells) + " |")
        P("\n" + not_run(d, "d_"))
    P("")
    P(END)
    return out


def splice(path, lines):
    txt = open(path).read() if os.path.exists(path) else ""
    block = "\n".join(lines)
    if BEGIN in txt and END in txt:
        a, b = txt.index(BEGIN), txt.index(END) + len(END)
        txt = txt[:a] + block + txt[b:]
    else:
        txt = txt.rstrip("\n") + "\n\n" + block + "\n"
    open(path, "w").write(txt)


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "--splice":
        splice(sys.argv[2], fem_sections())
    else:
        print("\n".join(fem_sections(sys.argv[1] if len(sys.argv) > 1 else "results/bhem/fem")))
