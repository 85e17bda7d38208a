#!/usr/bin/env python3
"""bench/bhem/report.py — tables of the BHEM validation / paper-scene runs,
generated from the records in results/bhem/runs/ (JSON summaries written by
`shellbench run --summary json`, HDF5 records for the wrinkle profiles).

    python3 bench/bhem/report.py [RUNS_DIR] > tables.md
"""
import glob, json, math, os, subprocess, sys

RUNS = sys.argv[1] if len(sys.argv) > 1 else "results/bhem/runs"
PROFILE = os.path.join(os.path.dirname(RUNS.rstrip("/")), "bhem_profile")
# the shared reference data beside the repository (../shared from /work/main; ../../shared from a worktree)
MASTER = os.path.join(next((d for d in (os.environ.get("SB_SHARED", ""), "../shared", "../../shared")
                            if d and os.path.isdir(os.path.join(d, "reference"))), "../shared"),
                      "reference", "cantilever_master_curve.csv")


def load(tag):
    p = os.path.join(RUNS, tag + ".json")
    try:
        txt = open(p).read()
        return json.loads(txt[txt.index("{"):])
    except (OSError, ValueError):
        return None


def probe(d, name):
    return d["probes"][name]


def fmt(x, f="%.4g"):
    return "—" if x is None or (isinstance(x, float) and not math.isfinite(x)) else f % x


def master_curve(G):
    rows = []
    for line in open(MASTER):
        if line[0].isdigit():
            a, b = line.split(",")
            rows.append((float(a), float(b)))
    for (g0, h0), (g1, h1) in zip(rows, rows[1:]):
        if g0 <= G <= g1:
            w = (math.log(G) - math.log(g0)) / (math.log(g1) - math.log(g0))
            return h0 + w * (h1 - h0)
    return float("nan")


def runline(d):
    return "%s | %s | %d | %.3f" % (d["status"], d["reason"], d["iterations"], d["seconds"]["total"])


out = []
P = out.append

P("### Plates (Kirchhoff, uniform load, linear regime), `lsnewton`\n")
P("| scene | patches | dofs | status | reason | iterations | seconds | w_centre / (q a⁴/D) | reference | rel. error |")
P("|---|---|---|---|---|---|---|---|---|---|")
for tag, coef in (("plate_clamped", 0.00126), ("plate_ss", 0.00406)):
    for r in (2, 4, 8, 16):
        d = load("%s_r%d" % (tag, r))
        if not d:
            continue
        pc = probe(d, "center")
        w = -pc["displacement"][2]
        c = w * coef / -pc["expected"]
        P("| %s | %d×%d | %d | %s | %.5f | %.5f | %.2e |" % (tag, r, r, d["dofs"], runline(d), c, coef, pc["rel_error"]))

P("\n### Scordelis–Lo roof (quarter model), `lsnewton`\n")
P("Load scaled by 1e-3 (linear regime; displacement scaled back by 1e3); reference 0.3006.\n")
P("| patches | dofs | status | reason | iterations | seconds | free-edge midpoint w | rel. error |")
P("|---|---|---|---|---|---|---|---|")
for r in (2, 4, 8, 16):
    d = load("scordelis_r%d" % r)
    if not d:
        continue
    pc = probe(d, "free_edge_mid")
    P("| %d×%d | %d | %s | %.5f | %.2e |" % (r, r, d["dofs"], runline(d), -pc["displacement"][2] * 1e3, pc["rel_error"]))
d = load("scordelis_full_r16")
if d:
    P("\nFull load (geometrically nonlinear), 16×16: w = %.4f (%s, %d iterations) — %.1f %% below the linear 0.3006."
      % (-probe(d, "free_edge_mid")["displacement"][2], d["reason"], d["iterations"],
         100 * (1 + probe(d, "free_edge_mid")["displacement"][2] / 0.3006)))

P("\n### Heavy cantilever, H/W against the master curve (N×1 patches), `lsnewton`\n")
P("| Γ | patches | dofs | status | reason | iterations | seconds | H/W | master curve | rel. error |")
P("|---|---|---|---|---|---|---|---|---|---|")
for g in (1, 5, 20, 100):
    ref = master_curve(g)
    for r in (8, 16, 32):
        d = load("cantilever_G%d_r%d" % (g, r))
        if not d:
            continue
        u = probe(d, "tip")["displacement"]
        hw = -u[2] / (1 + u[0])
        P("| %d | %d×1 | %d | %s | %.5f | %.5f | %+.2f %% |" % (g, r, d["dofs"], runline(d), hw, ref, 100 * (hw / ref - 1)))

P("\n### Roll-up under a conservative end moment (N×1 patches)\n")
P("θ from the tip position on the arc (chord angle: θ = 2 atan2(z, x)); tip error relative to L.\n")
P("| case | solver | patches | status | reason | iterations | seconds | θ / θ_exact | tip error / L |")
P("|---|---|---|---|---|---|---|---|---|")
for tag, solver, frac in (("rollup_quarter_r8", "lsnewton", .25), ("rollup_quarter_r16", "lsnewton", .25),
                          ("rollup_quarter_tr_r16", "tr", .25), ("rollup_full_r8", "lsnewton", 1.0),
                          ("rollup_full_r16", "lsnewton", 1.0)):
    d = load(tag)
    if not d:
        continue
    pc = probe(d, "tip")
    u = pc["displacement"]
    x, z = 1 + u[0], u[2]
    th = 2 * math.atan2(z, x)
    if th < 0 or frac == 1.0 and th < math.pi:
        th += 2 * math.pi
    e = math.sqrt(sum((a - b) ** 2 for a, b in zip(u, pc["expected"])))
    P("| M/M_max = %.2f | %s | %s | %s | %.4f | %.2e |" % (frac, solver, tag.split("_r")[-1], runline(d),
                                                        th / (frac * 2 * math.pi), e))


def wrinkle_stats(tag, res):
    h5 = os.path.join(RUNS, tag + ".h5")
    if not (os.path.exists(PROFILE) and os.path.exists(h5)):
        return None
    prof = subprocess.run([PROFILE, "bench/bhem/scenes/wrinkled_sheet.json", h5, str(res), "0", "101", "401"],
                          capture_output=True, text=True)
    if prof.returncode:
        return None
    st = subprocess.run([sys.executable, "bench/bhem/wrinkles.py"], input=prof.stdout, capture_output=True, text=True)
    return json.loads(st.stdout) if st.returncode == 0 else None


P("\n### Wrinkled sheet (stretch 10 %, imperfection 1 µm)\n")
P("Cerda–Mahadevan wavelength 18.2 mm; paper: peak amplitude 0.34 mm from 30² patches (measured 0.35 mm).\n")
P("| run | patches | dofs | status | reason | iterations | seconds | half-waves (>10 % peak) | crests | wavelength (mm) | peak amplitude (mm) |")
P("|---|---|---|---|---|---|---|---|---|---|---|")
for tag, res in (("wrinkled_r10", 10), ("wrinkled_r15", 15), ("wrinkled_r20", 20), ("wrinkled_r30", 30),
                 ("wrinkled_tr_r15", 15), ("wrinkled_pseudo_r15", 15)):
    d = load(tag)
    if not d:
        continue
    w = wrinkle_stats(tag, res) or {}
    P("| %s | %d² | %d | %s | %s | %s | %s | %s |" % (tag, res, d["dofs"], runline(d), w.get("half_waves", "—"),
                                                  w.get("crests", "—"), fmt(w.get("wavelength_mm"), "%.1f"),
                                                  fmt(w.get("peak_amplitude_mm"), "%.3f")))

P("\n### Twisting and draped cloth (dynamic), 30×30 patches, `lsnewton`\n")
P("| scene | dofs | nnz (full) | paper nnz | steps | iterations | s/step | paper s/step | s per Newton it. | s per factorization | ratio |")
P("|---|---|---|---|---|---|---|---|---|---|---|")
for tag, paper_nnz, paper_s in (("twisting_r30", "1.19e6", "0.20"), ("draped_r30", "—", "6.01")):
    d = load(tag)
    if not d:
        continue
    s, c, la = d["seconds"], d["counts"], d["linear_algebra"]
    nnz = 2 * la["matrix_nnz"] - d["dofs"]
    fac = s["factorize"] / max(c["factorize"], 1)
    per_it = s["total"] / max(d["iterations"], 1)
    P("| %s | %d | %.4g | %s | %d (%s) | %d | %.3f | %s | %.3f | %.3f | %.2f |" % (
        tag, d["dofs"], nnz, paper_nnz, d["steps"], d["reason"], d["iterations"], s["total"] / max(d["steps"], 1),
        paper_s, per_it, fac, per_it / fac))

P("\n### RMTR-paper scenes (denim, dt = 1 s), iterations capped at 300 per step\n")
P("| scene | solver | patches | dofs | steps done | status | reason | iterations | assembly WU | seconds | probe displacements (m) |")
P("|---|---|---|---|---|---|---|---|---|---|---|")
rmtr = [load(os.path.basename(f)[:-5]) for f in glob.glob(os.path.join(RUNS, "rmtr_*.json"))]
for d in sorted((d for d in rmtr if d), key=lambda d: (d["scene"], d["solver"], d["res"])):
    pr = "; ".join("%s (%s)" % (k, ", ".join("%.3g" % v for v in p["displacement"])) for k, p in d["probes"].items())
    P("| %s | %s | %d² | %d | %d/%d | %s | %s | %d | %.1f | %.2f | %s |" % (
        d["scene"], d["solver"], d["res"], d["dofs"], d["steps"], d["steps_planned"], d["status"], d["reason"],
        d["iterations"], d["work_units"]["assembly"], d["seconds"]["total"], pr))

# ---- pictures of final states (bench/render_thumbs.py, `shellbench render`) ----
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from render_thumbs import thumbnails  # noqa: E402

RMTR_PICS = (("trampoline", "lsnewton", 16, "final state"), ("drooping", "lsnewton", 8, "final state"),
             ("drape", "lsnewton", 8, "final state"),
             ("reentrant_corner", "lsnewton", 10, "where it stopped (step 1, not converged)"))


def rmtr_pictures(images, reldir):
    """Markdown showing the committed pictures of the RMTR-paper scenes
    (results/bhem/images/rmtr_SCENE_SOLVER_rRES.png, drawn by
    `bash bench/bhem/run_bench.sh BIN rmtr-pictures` from a rerun of that
    run, since these records are not committed); none when no picture exists."""
    items = [("%s, %s %d²: %s (run rmtr_%s_%s_r%d, rerun by run_bench.sh)" % (sc, so, r, what, sc, so, r),
              os.path.join(images, "rmtr_%s_%s_r%d.h5" % (sc, so, r)), (), "rmtr_%s_%s_r%d" % (sc, so, r))
             for sc, so, r, what in RMTR_PICS]
    rows = thumbnails(None, items, images, reldir)   # no records here: links the pictures that exist
    if not rows:
        return []
    return ["", "The final state of one run per scene (its finest converged `lsnewton` run; the re-entrant "
            "corner converges at none, so its smallest run, stopped at step 1), drawn by `shellbench render` "
            "(240x180, 8 samples per pixel) from the same run made again by `bench/bhem/run_bench.sh BIN "
            "rmtr-pictures`; the labels say how each run ended.", ""] + rows


out.extend(rmtr_pictures(os.path.join(os.path.dirname(RUNS.rstrip("/")), "images"), "bhem/images"))

# Table 2 rows Ball, Umbrella, Can, Cans, Armadillo (issue 39): bench/bhem/table2_report.py
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from table2_report import table2_section  # noqa: E402
_res = os.path.dirname(RUNS.rstrip("/"))
out.extend(table2_section(os.path.join(_res, "table2"), "bhem/images", os.path.join(_res, "images")))

BIN = os.environ.get("SB_BIN", "build/shellbench")
PICS = [("clamped plate, 16×16", "plate_clamped_r16"), ("Scordelis–Lo roof, full load, 16×16", "scordelis_full_r16"),
        ("heavy cantilever Γ = 5, 32×1", "cantilever_G5_r32"), ("full roll-up, 16×1", "rollup_full_r16"),
        ("wrinkled sheet, 15×15, mean curvature", "wrinkled_r15", ("--color", "curvature")),
        ("twisting cloth, 30×30, mean curvature", "twisting_r30", ("--color", "curvature")),
        ("draped cloth, 30×30", "draped_r30")]
# (wrinkles of 0.35 mm and the twist's dimple do not show in plain shading: their curvature does)
rows = thumbnails(BIN, [(p[0], os.path.join(RUNS, p[1] + ".h5")) + tuple(p[2:]) for p in PICS],
                  os.path.join(os.path.dirname(RUNS.rstrip("/")), "images"), "bhem/images")
if rows:
    P("\n### Final states\n")
    P("Drawn from the records' final states by `shellbench render` (the Hermite patches traced directly, BHEM §5; "
      "docs/render.md).  Ray tracing the patches, the paper's Table 1: results/bhem_table1.md.\n")
    out.extend(rows)

# ---- issue 39: lateral buckling (Fig. 20), locking (Fig. 21), needles at 16² ----
from report_issue39 import sections as issue39_sections  # noqa: E402
out.extend(issue39_sections())

# ---- linear FEM beside BHEM (paper Figs. 14-17, issue 39): its own module ----
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fem_report import fem_sections  # noqa: E402

out.extend([""] + fem_sections(os.path.join(os.path.dirname(RUNS.rstrip("/")), "fem"), "bhem/fem"))

print("\n".join(out))
