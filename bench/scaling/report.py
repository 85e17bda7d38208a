#!/usr/bin/env python3
"""bench/scaling/report.py — results/scaling/report.md (issue 42): how each
method's and solver's cost and memory grow with dofs, from records only.

    python3 bench/scaling/report.py [DIR]          # DIR default results/scaling

Reads every record or digest DIR/SCENE/*.h5 (h5dump, hdf5-tools; .partial
checkpoints and refused runs are left out) into DIR/records.csv, one row per
record with the figures the report uses; when DIR holds no records (a clean
clone where only the extract is committed) it reads DIR/records.csv instead.
Then writes DIR/report.md and one PNG per scene (gnuplot, log-log panels).
Never re-runs anything.

Figures (docs/recorded_figures.md, format 3):
  * component seconds: the exclusive seconds /stats/events_self_seconds summed
    over levels; assembly = energy + gradient + hessian; the others are the
    events of the same name (cg_iter = the Krylov solves with their
    preconditioner set-up, collide = contact, record = writing records,
    samples = probes, sample grid and the step's physical-state judgement,
    setup = from process start to the first step);
  * peak memory: /stats peak_rss (VmHWM of the run's process at its end);
  * CHOLMOD's achieved rate: chol_flops_sum over the process CPU seconds
    inside the factorizations (/stats/chol_factorize_cpu, format 4), or for
    older records over the inclusive factorize wall seconds
    (/stats/events_seconds), summed over levels, against the DGEMM rate of
    build/bench/bench_dgemm in DIR/dgemm.txt;
  * fitted exponents: y = c n^p by least squares in log-log over the largest
    (up to four) sizes of a configuration, with the 95 % interval
    p +- t_{0.975, m-2} * s / sqrt(Sxx), s^2 = RSS / (m - 2), Sxx = sum (ln n_i -
    mean)^2 (the slope's Student-t interval, e.g. Montgomery & Runger,
    Applied Statistics, 11-3; the same formula as core/report/sb_fit.c).
"""
import csv, glob, math, os, re, subprocess, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from h5ddl import h5dump, parse_ddl  # noqa: E402  (bench/h5ddl.py)

DIR = sys.argv[1] if len(sys.argv) > 1 else "results/scaling"
TARGETS = (1000, 4000, 16000, 64000, 256000, 1000000)
LARGE = "large" in os.path.basename(os.path.normpath(DIR))
STUDY = "scaling_large.json" if LARGE else "scaling.json"
STUDY_TARGETS = TARGETS if LARGE else TARGETS[:-1]
CAP = 30 if LARGE else 100                 # run.max_iter of the study (rmtr 4x)
# the default study's drape: 1,000 (rmtr 2,000), its nonconvex first step needs hundreds (bench/studies/scaling.json)
DRAPE_CAP = "" if LARGE else "; the drape 1,000 (rmtr 2,000)"
# the harness's own parts (issue 42's overhead goal: records, sample grids,
# checkpoints, progress); set-up is not among them: it builds the method
HARNESS = ("record", "samples", "checkpoint", "progress", "error")
EVENTS = ("energy", "gradient", "hessian", "analyze", "factorize", "solve", "cg_iter", "qp", "transfer", "adapt",
          "collide", "record", "galerkin", "checkpoint", "setup", "samples", "error", "progress", "solver")
COMPONENTS = ("assembly", "analyze", "factorize", "solve", "cg_iter", "collide", "record", "samples", "setup")
# what each component's fitted exponent is per: the solver's parts per
# outer iteration (Newton iteration, TR iteration, V-cycle), the per-step
# harness parts per step, set-up per run
NORM = {"assembly": "iteration", "analyze": "run", "factorize": "iteration", "solve": "iteration",
        "cg_iter": "iteration", "collide": "iteration", "record": "step", "samples": "step", "setup": "run"}
ACCURACY_TARGET = {"plate_simply_supported": 1e-3}
# t_{0.975, df}, df = 1..10
T975 = (12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228)

ROOT_ATTRS = ("scene_name", "method", "solver", "levels", "res", "n_dofs", "status", "reason", "steps_planned",
              "steps_done", "build_id", "blas_core", "openblas_num_threads", "started", "cpu_model")
STATS_ATTRS = ("seconds_total", "seconds_unattributed", "peak_rss", "peak_rss_start", "peak_rss_setup", "peak_rss_analyzed",
               "memory_estimate", "work_assembly", "not_posdef")
DATASETS = ("/stats/events_self_seconds", "/stats/events_seconds", "/stats/events_count", "/stats/chol_factor_entries",
            "/stats/chol_nnz_l", "/stats/chol_flops_sum", "/stats/chol_factorize_cpu", "/stats/n_dofs",
            "/stats/chol_first_factorize_cpu", "/stats/chol_first_flops",
            "/history/steps/iterations", "/history/iterations/linear_iters", "/history/iterations/level",
            "/history/iterations/iter")



def read_record(path):
    args = []
    for a in ROOT_ATTRS:
        args += ["-a", "/" + a]
    for a in STATS_ATTRS:
        args += ["-a", "/stats/" + a]
    for a in ("probe", "rms"):
        args += ["-a", "/error/" + a]
    for d in DATASETS:
        args += ["-d", d]
    v = parse_ddl(h5dump(path, args))
    if "n_dofs" not in v or "/stats/events_self_seconds" not in v:
        return None
    row = {k: (v[k][0] if k in v and v[k] else "") for k in ROOT_ATTRS}
    row["scene"] = row.pop("scene_name")
    for k in STATS_ATTRS:
        row[k] = v.get(k, [float("nan")])[0]
    row["error_probe"] = v.get("probe", [float("nan")])[0]
    row["error_rms"] = v.get("rms", [float("nan")])[0]
    ne = len(EVENTS)
    for key, pre in (("/stats/events_self_seconds", "self_"), ("/stats/events_seconds", "incl_")):
        a = v.get(key, [])
        for j, e in enumerate(EVENTS):
            row[pre + e] = sum(a[i] for i in range(j, len(a), ne)) if len(a) % ne == 0 else float("nan")
    cn = v.get("/stats/events_count", [])
    ja = EVENTS.index("analyze")
    row["analyze_calls"] = sum(cn[i] for i in range(ja, len(cn), ne)) if cn and len(cn) % ne == 0 else float("nan")
    fl = v.get("/stats/chol_flops_sum", [])
    row["chol_flops_sum"] = sum(fl)
    row["chol_entries"] = sum(v.get("/stats/chol_factor_entries", []))
    row["chol_nnz_l"] = sum(v.get("/stats/chol_nnz_l", []))
    row["chol_flops_finest"] = fl[-1] if fl else 0.0
    # format 4: process CPU seconds inside the factorizations (NaN before)
    fc = v.get("/stats/chol_factorize_cpu")
    row["cpu_factorize"] = sum(fc) if fc else float("nan")
    # format 5: the first factorization after each analysis apart (NaN before)
    f1c, f1f = v.get("/stats/chol_first_factorize_cpu"), v.get("/stats/chol_first_flops")
    row["cpu_first"] = sum(f1c) if f1c else float("nan")
    row["flops_first"] = sum(f1f) if f1f else float("nan")
    row["iterations"] = sum(v.get("/history/steps/iterations", []))
    lv, li = v.get("/history/iterations/level", []), v.get("/history/iterations/linear_iters", [])
    row["linear_iters"] = sum(li)
    top = max(lv) if lv else 0
    # outer iterations whose top was the finest level (rmtr's nested start
    # records V-cycles with a coarser top under their level; each step's
    # iteration-0 record is not an iteration)
    it = v.get("/history/iterations/iter", [])
    row["iters_finest"] = sum(1 for k, l in enumerate(lv) if l == top and (k >= len(it) or it[k] > 0))
    row["file"] = os.path.relpath(path, DIR)
    return row


def fact_rate(r):
    """CHOLMOD's achieved GFLOP/s and its basis: per CPU second of the process
    inside the factorizations (format 4, unchanged by other processes taking
    turns on the cores), else per wall second (older records: other work on
    the machine lowers it)"""
    cpu = fnum(r.get("cpu_factorize"))
    if r["chol_flops_sum"] <= 0:
        return float("nan"), "—"
    if math.isfinite(cpu) and cpu > 0:
        return r["chol_flops_sum"] / cpu / 1e9, "CPU"
    if r["incl_factorize"] > 0:
        return r["chol_flops_sum"] / r["incl_factorize"] / 1e9, "wall"
    return float("nan"), "—"


def fact_rate_reuse(r):
    """CHOLMOD's GFLOP/s in the factorizations after the first of each
    analysis (format 5), which reuse the factor's memory: the first also
    takes the factor's pages from the kernel (first touch); NaN for older
    records or a run with one factorization"""
    c1, f1 = fnum(r.get("cpu_first")), fnum(r.get("flops_first"))
    cpu = fnum(r.get("cpu_factorize"))
    if not (math.isfinite(c1) and math.isfinite(f1) and math.isfinite(cpu)):
        return float("nan")
    dc, df = cpu - c1, r["chol_flops_sum"] - f1
    return df / dc / 1e9 if dc > 0 and df > 0 else float("nan")


def fnum(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return float("nan")


def load_rows():
    """the records and digests present, and the rows of DIR/records.csv whose
    record is not present (a clean clone holds digests of the largest size
    only, the extract holds every run); the union is written back"""
    paths = sorted(p for p in glob.glob(os.path.join(DIR, "*", "*.h5")))
    fresh = [r for r in (read_record(p) for p in paths) if r]
    csvp = os.path.join(DIR, "records.csv")
    old = []
    try:
        with open(csvp) as fh:
            old = list(csv.DictReader(fh))
    except OSError:
        pass
    have = {r["file"] for r in fresh}
    kept = [r for r in old if r["file"] not in have]
    rows = sorted([{k: ("%.6g" % v if isinstance(v, float) else str(v)) for k, v in r.items()} for r in fresh] + kept,
                  key=lambda r: r["file"])
    if rows:
        keys = []
        for r in rows:   # the union: older extracts lack the newer figures (peak_rss_start)
            keys += [k for k in r if k not in keys]
        with open(csvp + ".tmp", "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=keys, restval="")
            w.writeheader()
            for r in rows:
                w.writerow(r)
        os.replace(csvp + ".tmp", csvp)
    src = ("%d runs: %d records or digests in `%s`, %d from the extract `%s` whose records are not in this checkout"
           % (len(rows), len(fresh), DIR, len(kept), csvp))
    for r in rows:
        for k in list(r.keys()):
            if k not in ("scene", "method", "solver", "reason", "build_id", "blas_core", "openblas_num_threads",
                         "started", "cpu_model", "file"):
                r[k] = fnum(r[k])
        r["assembly"] = r["self_energy"] + r["self_gradient"] + r["self_hessian"]
        for c in COMPONENTS[1:]:
            r[c] = r["self_" + c]
        r["config"] = "%s/%s" % (r["method"], r["solver"])
        r["harness"] = sum(r["self_" + h] for h in HARNESS)
        # the peak is the run's own: recorded with peak_rss_start (the sweep
        # resets a child's peak since 12f1ba9; before, a forked run's peak
        # included the sweep's plan, up to 1.2 GB)
        r["own_peak"] = math.isfinite(r.get("peak_rss_start", float("nan"))) and r["peak_rss_start"] > 0
        r["per_iter"] = r["seconds_total"] / r["iterations"] if r["iterations"] > 0 else float("nan")
        # normalized for the fits: per iteration, per step, per run (NORM)
        for c in COMPONENTS:
            d = {"iteration": r["iterations"], "step": r["steps_done"], "run": 1}[NORM[c]]
            r["n_" + c] = r[c] / d if d > 0 else float("nan")
        r["target"] = min(TARGETS, key=lambda t: abs(math.log(r["n_dofs"] / t)))
    return rows, src


def fit(ns, ys):
    """exponent p, half-width of its 95 % interval (nan with 2 points), points used"""
    pts = [(math.log(n), math.log(y)) for n, y in zip(ns, ys) if n > 0 and y > 0 and math.isfinite(y)]
    pts = sorted(pts)[-4:]
    m = len(pts)
    if m < 2:
        return float("nan"), float("nan"), m
    mu = sum(p[0] for p in pts) / m
    mv = sum(p[1] for p in pts) / m
    sxx = sum((p[0] - mu) ** 2 for p in pts)
    if sxx <= 0:
        return float("nan"), float("nan"), m
    p = sum((a - mu) * (b - mv) for a, b in pts) / sxx
    if m < 3:
        return p, float("nan"), m
    rss = sum((b - mv - p * (a - mu)) ** 2 for a, b in pts)
    se = math.sqrt(rss / (m - 2) / sxx)
    return p, T975[m - 3] * se, m


def fmt_fit(p, hw, m):
    if not math.isfinite(p):
        return "—"
    if not math.isfinite(hw):
        return "%.2f (%d pts)" % (p, m)
    return "%.2f ± %.2f" % (p, hw)


def series(rows, scene, config, key):
    pts = sorted((r["n_dofs"], r[key]) for r in rows if r["scene"] == scene and r["config"] == config)
    return [p[0] for p in pts], [p[1] for p in pts]


def crossing(ns, a, b):
    """dofs at which b first overtakes a (log-log interpolation), a sentence"""
    pts = [(n, x, y) for n, x, y in zip(ns, a, b) if x > 0 and y > 0]
    if len(pts) < 1:
        return "—"
    if pts[0][2] >= pts[0][1]:
        return "already at the smallest, %d" % pts[0][0]
    for (n0, x0, y0), (n1, x1, y1) in zip(pts, pts[1:]):
        d0, d1 = math.log(y0 / x0), math.log(y1 / x1)
        if d0 < 0 <= d1:
            t = d0 / (d0 - d1)
            return "%.0f" % math.exp(math.log(n0) + t * (math.log(n1) - math.log(n0)))
    return "not up to %d (%.2g of it there)" % (pts[-1][0], pts[-1][2] / pts[-1][1])


def dgemm():
    try:
        txt = open(os.path.join(DIR, "dgemm.txt")).read()
    except OSError:
        return None, ""
    m = re.search(r"dgemm_1core_gflops ([\d.]+)", txt)
    return (float(m.group(1)) if m else None), txt


COLORS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22",
          "#17becf", "#000000", "#aec7e8")


def plot(rows, scene, configs, png):
    panels = list(COMPONENTS) + ["peak_rss"]
    gp = ["set terminal pngcairo size 1000,740 font ',7' noenhanced", "set output '%s.tmp'" % png,
          "set multiplot layout 3,4 title '%s: exclusive seconds per component and peak memory against dofs "
          "(log-log, one curve per method/solver)'" % scene, "set logscale xy", "set xrange [5e2:%g]" % (2e6 if LARGE else 3e4),
          "set format x '%.0e'", "set format y '%g'", "set grid", "set key off"]
    data = {}
    for c in configs:
        for comp in panels:
            ns, ys = series(rows, scene, c, comp)
            data[(c, comp)] = [(n, y / (1e6 if comp == "peak_rss" else 1)) for n, y in zip(ns, ys) if y > 0]
    for comp in panels:
        plots = []
        for i, c in enumerate(configs):
            pts = data[(c, comp)]
            if pts:
                plots.append(("'-' using 1:2 with linespoints lw 1.5 pt %d lc rgb '%s' title '%s'" % (
                    i % 13 + 1, COLORS[i % len(COLORS)], c),
                              pts))
        gp.append("set title '%s'" % (comp + (" (MB)" if comp == "peak_rss" else " (s)")))
        if not plots:
            gp += ["unset logscale y", "set label 1 'none recorded' at graph 0.5, 0.5 center",
                   "plot 0 notitle with lines lc rgb 'white'", "unset label 1", "set logscale xy"]
            continue
        gp.append("plot " + ", ".join(p[0] for p in plots))
        for _, pts in plots:
            gp += ["%g %g" % xy for xy in pts] + ["e"]
    # the key as a panel of its own
    gp += ["set key center center", "unset border", "unset tics", "unset grid", "unset title", "unset logscale",
           "set yrange [0:1]", "plot " + ", ".join("2 with linespoints lw 1.5 pt %d lc rgb '%s' title '%s'" %
                                                   (i % 13 + 1, COLORS[i % len(COLORS)], c)
                                                   for i, c in enumerate(configs)),
           "unset multiplot"]
    try:
        subprocess.run(["gnuplot"], input="\n".join(gp) + "\n", text=True, check=True, capture_output=True)
        os.replace(png + ".tmp", png)
        return True
    except (OSError, subprocess.CalledProcessError) as e:
        sys.stderr.write("report.py: gnuplot failed for %s: %s\n" % (png, getattr(e, "stderr", e)))
        return False


def picture(rows, scene):
    """thumb-SCENE.png of the largest converged run (shellbench render, from
    its record); kept as it is when that record is a digest without its state
    or absent (a clean clone); the caption names the run"""
    ok = [r for r in rows if r["scene"] == scene and r["status"] == 0]
    if not ok:
        return "No run of %s converged: no picture." % scene
    r = max(ok, key=lambda r: (r["n_dofs"], -r["seconds_total"]))
    png = os.path.join(DIR, "thumb-%s.png" % scene)
    rec = os.path.join(DIR, r["file"])
    shellbench = os.environ.get("SB_BIN", "build/shellbench")
    if os.path.exists(rec):
        try:
            subprocess.run([shellbench, "render", rec, "--out", png, "--size", "240x180", "--spp", "4", "--quiet",
                            "--color", "curvature"], capture_output=True)
        except OSError:
            pass                          # no shellbench built: the committed picture stays
    if not os.path.exists(png):
        return "No picture (the record of %s is not in this checkout)." % r["file"]
    return "![%s](thumb-%s.png)  \nThe largest converged run: %s, %d dofs, %.1f s (`shellbench render`, " \
           "curvature colours)." % (scene, scene, r["config"], r["n_dofs"], r["seconds_total"])


def mb(x):
    return "%.0f MB" % (x / 1e6) if math.isfinite(x) else "—"


def own_ratio(r):
    return r["memory_estimate"] / r["peak_rss"] if r["peak_rss"] > 0 and r["memory_estimate"] > 0 else float("nan")


def goals(rows, g1):
    """the issue's goals judged on the runs of >= 1e5 dofs (the sizes it names)"""
    big = [r for r in rows if r["n_dofs"] >= 1e5]
    out = ["## The issue's goals at ≥ 1e5 dofs", ""]
    if not big:
        return out + ["No run of ≥ 1e5 dofs in `%s`: the goals are judged in the large study's report." % DIR, ""]
    out += ["Judged on the %d runs of ≥ 1e5 dofs (%s dofs).  *met* / *missed* per run; the sections below "
            "give every size." % (len(big), ", ".join("%d" % n for n in sorted({r["n_dofs"] for r in big}))), "",
            "| goal | runs | met | missed | worst (run) |", "|---|--:|--:|--:|---|"]

    def line(name, items, ok, fmt, far=lambda v: abs(math.log(max(v, 1e-300)))):
        """items: (value, label); ok(value) -> bool; far(value): how far from the goal (the worst run is the
        farthest of the missed ones, else of all)"""
        items = [(v, l) for v, l in items if math.isfinite(v)]
        if not items:
            out.append("| %s | 0 | — | — | — |" % name)
            return
        bad = [(v, l) for v, l in items if not ok(v)]
        worst = max(bad or items, key=lambda x: far(x[0]))
        out.append("| %s | %d | %d | %d | %s (%s) |" % (name, len(items), len(items) - len(bad), len(bad),
                                                       fmt(worst[0]), worst[1]))
    lab = lambda r: "%s %s %d" % (r["scene"], r["config"], r["n_dofs"])
    # factorization rate: runs without indefinite factorizations, of the solvers that factorize the finest level
    fr = [(fact_rate(r)[0] / g1 if g1 else float("nan"), lab(r) + " " + fact_rate(r)[1]) for r in big
          if r["incl_factorize"] > 1.0 and r["chol_flops_sum"] > 0 and not (r.get("not_posdef", 0) > 0)
          and r["solver"] in ("lsnewton", "tr")]
    line("CHOLMOD's numeric factorization ≥ 1/2 the one-core DGEMM rate (lsnewton, tr; no indefinite "
         "factorization; per CPU second, or per wall second for records before format 4)", fr, lambda v: v >= 0.5, lambda v: "%.0f %%" % (100 * v))
    # the same runs, the factorizations that reuse the factor's memory (format 5; DGEMM is measured warm, best of 5)
    fr2 = [(fact_rate_reuse(r) / g1 if g1 else float("nan"), lab(r)) for r in big
           if r["incl_factorize"] > 1.0 and r["chol_flops_sum"] > 0 and not (r.get("not_posdef", 0) > 0)
           and r["solver"] in ("lsnewton", "tr")]
    line("the same, the factorizations after the first of each analysis (records of format 5: the first also "
         "takes the factor's memory from the kernel; DGEMM's rate is of warm repeats too)", fr2,
         lambda v: v >= 0.5, lambda v: "%.0f %%" % (100 * v))
    # a run that never iterated on its finest level (rmtr whose cap went to the nested start's coarser
    # tops) neither holds nor works on the finest level's structures: its peak and its harness share are
    # not those of a run of its size, so the two goals below leave it out and say so
    fine = [r for r in big if r.get("iters_finest", 1) > 0]
    hs = [(r["harness"] / r["seconds_total"], lab(r)) for r in fine if r["seconds_total"] > 0]
    line("harness overhead (record, samples, checkpoint, progress, error) ≤ 3 % of the run (runs that "
         "iterated on their finest level)", hs, lambda v: v <= 0.03, lambda v: "%.1f %%" % (100 * v), lambda v: v)
    me = [(own_ratio(r), lab(r)) for r in fine if r["own_peak"]]
    line("memory estimate within 30 % of the measured peak (runs with their own peak that iterated on their "
         "finest level)", me, lambda v: abs(v - 1) <= 0.3, lambda v: "estimate/peak %.2f" % v)
    coarse = [r for r in big if r.get("iters_finest", 1) == 0]
    if coarse:
        out += ["", "Left out of these two goals: %s — each spent its whole iteration cap in the nested start's "
                "V-cycles on coarser tops and never iterated on its finest level (harness share %s, estimate/peak "
                "%s: the estimate is for the whole run, which holds the finest level's smoother and "
                "Galerkin structures, never set up here)." % (
                    "; ".join(lab(r) for r in coarse),
                    ", ".join("%.1f %%" % (100 * r["harness"] / r["seconds_total"]) for r in coarse),
                    ", ".join("%.2f" % own_ratio(r) for r in coarse))]
    inh = sum(1 for r in big if not r["own_peak"])
    if inh:
        out += ["", "%d runs of ≥ 1e5 dofs were recorded before a sweep reset its runs' peak memory: their "
                "peak includes the sweep's plan and is left out of the memory goal." % inh]
    an = [r for r in big if r["solver"] in ("lsnewton", "tr") and math.isfinite(r.get("analyze_calls", float("nan")))]
    once = [r for r in an if r["analyze_calls"] == 1]
    more = sorted({"%s %s %d: %d" % (r["scene"], r["config"], r["n_dofs"], r["analyze_calls"]) for r in an
                   if r["analyze_calls"] != 1})
    out += ["", "Symbolic analysis (`analyze` calls per run, `/stats/events_count`), lsnewton and tr at ≥ 1e5 dofs: "
            "once in %d of %d runs%s.  It is redone only when the matrix pattern changes: contact pairs that "
            "join the pattern, an adaptive method's new mesh (docs/performance.md)." % (
                len(once), len(an), ("; more often: " + "; ".join(more)) if more else ""), ""]
    return out


def large_summary():
    """the default study's report carries the large study's answer and goals
    (its report, generated by this script from its own records, is the source)"""
    if LARGE:
        return []
    lp = os.path.join(os.path.dirname(os.path.normpath(DIR)), "scaling_large", "report.md")
    try:
        txt = open(lp).read().splitlines()
    except OSError:
        return []
    rel = os.path.relpath(lp, DIR)
    out = ["## Larger sizes: the large study (to 1e6 dofs)", "",
           "From [%s](%s) (`bench/studies/scaling_large.json`: the trampoline and drape bounded to 2 steps, cloth "
           "over a sphere to 8, at most 30 iterations per step), the sizes above this study's: the fastest "
           "configuration at each size, then the issue's goals." % (rel, rel), ""]
    head = [l for l in txt if l.startswith("| scene | dofs target |")][:1]
    rows = [l for l in txt if re.match(r"\| [a-z_0-9]+ \| (64000|256000|1000000) \| ", l)]
    if head and rows:
        out += head + ["|---|--:|---|--:|--:|---|--:|"] + rows + [""]
    k = next((i for i, l in enumerate(txt) if l.startswith("## The issue's goals")), None)
    if k is not None:
        j = k + 1
        while j < len(txt) and not txt[j].startswith("## "):
            j += 1
        out += [l for l in txt[k + 1:j] if not l.startswith("Judged on")]
    return out


def ceiling_section(g1):
    """DIR/supernodes/*.csv (bench/scaling/supernode_profile.sh, build/bench/bench_supernodes): the supernode
    profile of each configuration's Hessian and the dense kernels' rate at its supernodes' shapes"""
    d = os.path.join(DIR, "supernodes")
    paths = sorted(glob.glob(os.path.join(d, "*.csv")))
    if not paths:
        return []
    rows = []
    for path in paths:
        summ, bins = {}, []
        with open(path) as fh:
            for ln in fh:
                c = ln.strip().split(",")
                if c[0] == "summary" and len(c) >= 3:
                    summ[c[1]] = c[2]
                elif c[0] and c[0][0].isdigit() and len(c) >= 8:
                    bins.append([float(x) for x in c])
        if "achieved_gflops" in summ:
            rows.append((summ, bins))
    if not rows:
        return []
    out = ["## What bounds the factorization rate: the supernodes' shapes", "",
           "`bash bench/scaling/supernode_profile.sh` (`build/bench/bench_supernodes`, CSVs in `%s`): each "
           "configuration's Hessian at the scene's first step, analysed and factorized by the suite's own path; its "
           "supernodes binned by column count k; per bin the rate of the same dense work (DPOTRF k, DTRSM, DSYRK of "
           "the (m−k) × k block) on a panel of the bin's flop-weighted mean shape, measured in the same process; the "
           "**ceiling** = all flops / Σ (a bin's flops / its dense rate), the rate CHOLMOD would reach if every "
           "supernode ran at the dense kernels' speed for its shape (an upper bound: CHOLMOD splits each update over "
           "the ancestors it reaches and scatter-adds it).  **Achieved** = CHOLMOD's flops / the process CPU seconds "
           "of one numeric factorization (best of 2).  Both per CPU second, one BLAS thread; the one-core DGEMM "
           "rate is %s GFLOP/s." % (os.path.relpath(d), "%.1f" % g1 if g1 else "—"), "",
           "| scene | method | dofs | supernodes (setting) | flops in supernodes k < 32 | flop-weighted mean k | "
           "flops / nnz(L) | dense rate at k ≈ 16 / 64 / 256 (GFLOP/s) | ceiling GFLOP/s (of DGEMM) | achieved "
           "GFLOP/s (of DGEMM) | achieved / ceiling | first factorization GFLOP/s |",
           "|---|---|--:|--:|--:|--:|--:|---|--:|--:|--:|--:|"]
    def rate_at(bins, k):
        b = [x for x in bins if x[0] <= k <= (x[1] if x[1] > 0 else 1e9)]
        return "%.0f" % b[0][7] if b and math.isfinite(b[0][7]) else "—"
    key = lambda r: (r[0]["method"], r[0]["scene"], int(r[0]["dofs"]), r[0].get("supernodes_setting", ""))
    for summ, bins in sorted(rows, key=key):
        fl = sum(b[4] for b in bins)
        mk = sum(b[4] * b[5] for b in bins) / fl if fl > 0 else float("nan")
        ce, ac = float(summ["ceiling_gflops"]), float(summ["achieved_gflops"])
        sh = lambda v: " (%.0f %%)" % (100 * v / g1) if g1 else ""
        out.append("| %s | %s | %s | %s (%s) | %.0f %% | %.0f | %.0f | %s / %s / %s | %.1f%s | %.1f%s | %.2f | %s |" % (
            summ["scene"].split("/")[-1].replace(".json", ""), summ["method"], summ["dofs"], summ["supernodes"],
            summ.get("supernodes_setting", "cholmod"), 100 * float(summ["flops_share_k_below_32"]), mk,
            float(summ["cholmod_flops"]) / float(summ["nnz_l"]), rate_at(bins, 16), rate_at(bins, 64),
            rate_at(bins, 256), ce, sh(ce), ac, sh(ac), float(summ["achieved_over_ceiling"]),
            "%.1f" % float(summ["first_gflops"]) if "first_gflops" in summ else "—"))
    # what the rows show, from the rows
    by_m = {}
    for summ, _ in rows:
        if summ.get("supernodes_setting", "cholmod") == "cholmod":
            by_m.setdefault(summ["method"], []).append(
                (float(summ["cholmod_flops"]) / float(summ["nnz_l"]), float(summ["achieved_over_ceiling"]),
                 float(summ["achieved_gflops"]), float(summ["ceiling_gflops"])))
    if by_m and g1:
        out += ["", "Per method (CHOLMOD's default supernodes): " + "; ".join(
            "%s %.0f flops per factor entry, achieved %.0f–%.0f %% of the ceiling, %.0f–%.0f %% of DGEMM" % (
                m, sum(v[0] for v in vs) / len(vs), 100 * min(v[1] for v in vs), 100 * max(v[1] for v in vs),
                100 * min(v[2] for v in vs) / g1, 100 * max(v[2] for v in vs) / g1) for m, vs in sorted(by_m.items())) +
                ".  The ceilings are alike (the supernodes' shapes cost every method 20–30 % of the dense rate); "
                "what differs is the share of the ceiling reached, and it follows the flops per factor entry: "
                "CHOLMOD's supernodal method adds each update block into its ancestor by a scatter through an index "
                "map, memory-bound work proportional to the entries updated, not to the flops, so a pattern with "
                "fewer flops per entry of L spends more of its time there (docs/scaling.md \"What bounds the "
                "factorization rate\")."]
    out.append("")
    return out


def supernodes_section(g1):
    """results/scaling_supernodes (bench/scaling/supernodes.sh): the factorization rate with
    CHOLMOD's default supernodes and with run.supernodes=wide, both on huge pages"""
    d = os.path.join(os.path.dirname(os.path.normpath(DIR)), "scaling_supernodes")
    if not LARGE or not os.path.isdir(d):
        return []
    rows = [r for r in (read_record(p) for p in sorted(glob.glob(os.path.join(d, "*.h5")))) if r]
    if not rows:
        return []
    for r in rows:
        r["sn"] = "wide" if "-wide-" in os.path.basename(r["file"]) else "cholmod"
    out = ["## Factorization rate: CHOLMOD's supernodes, huge pages", "",
           "`bash bench/scaling/supernodes.sh` (records in `%s`): lsnewton on the plate (three numeric "
           "factorizations of one pattern), built with CHOLMOD's memory on transparent huge pages "
           "(`core/linalg/sb_cholmod_alloc.c`, since e19d431; the study's records above from before it use 4 kB "
           "pages), with CHOLMOD's default relaxed amalgamation and with `run.supernodes=wide`.  Rate = "
           "`chol_flops_sum` / the factorizations' process CPU seconds (format 4; basis *wall*: inclusive "
           "`factorize` wall seconds, older records); goal: half the one-core DGEMM rate (%s GFLOP/s)."
           % (os.path.relpath(d), "%.1f" % g1 if g1 else "—"), "",
           "| method | dofs | supernodes | factorize s (wall) | GFLOP/s | basis | share of DGEMM | stored entries / nnz(L) "
           "| peak | estimate / peak | build |",
           "|---|--:|---|--:|--:|---|--:|--:|--:|--:|---|"]
    for r in sorted(rows, key=lambda r: (r["method"], r["n_dofs"], r["sn"])):
        g, basis = fact_rate(r)
        out.append("| %s | %d | %s | %.1f | %.1f | %s | %s | %.2f | %s | %.2f | %s |" % (
            r["method"], r["n_dofs"], r["sn"], r["incl_factorize"], g, basis,
            "%.0f %%" % (100 * g / g1) if g1 else "—",
            r["chol_entries"] / r["chol_nnz_l"] if r["chol_nnz_l"] > 0 else float("nan"), mb(r["peak_rss"]),
            r["memory_estimate"] / r["peak_rss"] if r["peak_rss"] > 0 else float("nan"), r["build_id"]))
    out.append("")
    return out


def io_section():
    """DIR/io.csv of bench/scaling/io_scaling.sh: reading records back"""
    path = os.path.join(DIR, "io.csv")
    try:
        with open(path) as fh:
            rs = list(csv.DictReader(fh))
    except OSError:
        return []
    out = ["## Records read back: report, inspect, render, digest, ParaView", "",
           "`bash bench/scaling/io_scaling.sh --paraview %s RECORD...` (wall seconds of each command on a copy of "
           "the record; ParaView = `scripts/check_paraview.py`, every check of `make check-paraview` on the record's "
           "XDMF sidecars under xvfb-run, with ParaView's start-up of a few seconds).  The issue asks for time "
           "proportional to size: the fitted exponent of seconds against dofs over the largest four records of a "
           "method is at most about 1." % path, "",
           "| record | dofs | MB | report s | inspect s | render s | digest s (digest MB) | ParaView s |",
           "|---|--:|--:|--:|--:|--:|--:|--:|"]
    for r in sorted(rs, key=lambda r: (os.path.basename(r["record"]).split("-")[0], int(r["dofs"]))):
        out.append("| %s | %s | %.1f | %s | %s | %s | %s (%.1f) | %s |" % (
            os.path.relpath(r["record"], DIR), r["dofs"], int(r["bytes"]) / 1e6, r["report_s"],
            r["inspect_s"] or "— (no material state)", r["render_s"], r["digest_s"], int(r["digest_bytes"]) / 1e6,
            r["paraview_s"] or "—"))
    out += ["", "| scene, method | sizes | " + " | ".join(k for k in ("report", "inspect", "render", "digest", "ParaView"))
            + " |", "|---|---|--:|--:|--:|--:|--:|"]
    key = lambda r: "%s %s" % (os.path.basename(os.path.dirname(r["record"])),
                               os.path.basename(r["record"]).split("-")[0])
    for m in sorted({key(r) for r in rs}):
        q = sorted((r for r in rs if key(r) == m), key=lambda r: int(r["dofs"]))
        ns = [int(r["dofs"]) for r in q]
        cells = []
        for k in ("report_s", "inspect_s", "render_s", "digest_s", "paraview_s"):
            ys = [fnum(r[k]) for r in q]
            cells.append(fmt_fit(*fit(ns, ys)) if all(math.isfinite(y) and y > 0 for y in ys) else "—")
        out.append("| %s | %s | %s |" % (m, ", ".join(str(n) for n in ns), " | ".join(cells)))
    out += ["", "Exponents below 1 mean a fixed start-up (process, HDF5, ParaView) dominates at these sizes; "
            "nothing grows faster than the record.", ""]
    return out


def main():
    rows, src = load_rows()
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    g1, dg_txt = dgemm()
    out = ["# Scaling: cost and memory against dofs (issue 42)", "",
           "Made by `python3 bench/scaling/report.py %s` from %s; nothing re-run.  Studies: "
           "`bench/studies/scaling.json` (1e3–2.56e5 dofs), `scaling_large.json` (to 1e6; "
           "`scaling_large_static.json` is its plate and trampoline part), `scaling_small.json` (the three "
           "smallest sizes of scaling.json)." % (DIR, src), ""]
    # --- the answer first
    out += ["## Which method/solver, at each size", "",
            "Per scene and dof target: the configuration that converged (on the plate: reached the probe error "
            "target 1e-3) in the fewest seconds, its peak memory, and the runner-up.  Wall seconds of one run on a "
            "shared 2-core machine (other work beside it, `nice`, one BLAS thread): compare as ratios.", "",
            "| scene | dofs target | fastest (dofs) | seconds | peak memory | runner-up (seconds, memory) | converged / run |",
            "|---|--:|---|--:|--:|---|--:|"]
    for s in scenes:
        for t in TARGETS:
            rs = [r for r in rows if r["scene"] == s and r["target"] == t]
            if not rs:
                continue
            tgt = ACCURACY_TARGET.get(s)
            ok = [r for r in rs if r["status"] == 0 and (tgt is None or (math.isfinite(r["error_probe"])
                                                                          and r["error_probe"] <= tgt))]
            ok.sort(key=lambda r: r["seconds_total"])
            conv = sum(1 for r in rs if r["status"] == 0)
            if ok:
                a = ok[0]
                ru = ("%s (%.2f s, %s)" % (ok[1]["config"], ok[1]["seconds_total"], mb(ok[1]["peak_rss"]))
                      if len(ok) > 1 else "—")
                out.append("| %s | %d | **%s** (%d) | %.2f | %s | %s | %d / %d |" % (
                    s, t, a["config"], a["n_dofs"], a["seconds_total"], mb(a["peak_rss"]), ru, conv, len(rs)))
            else:
                why = "none reached %g" % tgt if tgt else "none converged"
                if tgt:
                    best = min((r for r in rs if math.isfinite(r["error_probe"])), key=lambda r: r["error_probe"],
                               default=None)
                    if best:
                        why += " (best error %.2g: %s)" % (best["error_probe"], best["config"])
                out.append("| %s | %d | %s | — | — | — | %d / %d |" % (s, t, why, conv, len(rs)))
    for s in scenes:
        rs = [r for r in rows if r["scene"] == s and r["status"] != 0]
        if not rs:
            continue
        why = {}
        for r in rs:
            why[r["reason"]] = why.get(r["reason"], 0) + 1
        coarse = [r for r in rs if r["solver"] == "rmtr" and r.get("iters_finest", 1) == 0]
        out.append("")
        out.append("*%s*, not converged: %s%s." % (s, ", ".join("%d %s" % (n, k) for k, n in sorted(why.items())),
                   ("; %d rmtr runs spent the whole cap in the nested start's coarser-top V-cycles (no finest-level "
                    "V-cycle: their per-iteration cost is not the finest level's; the study files now give rmtr 4× "
                    "the cap)" % len(coarse)) if coarse else ""))
    out += ["", "`max_iter`: the cap of %d iterations per step (rmtr %d%s); `single_step_residual`: the linearized "
            "solve's one Newton step per time step left too large a residual (dt = 1 s on the trampoline and drape, "
            "0.01 s on the sphere; its dt limit is far below, results/dt_stability/report.md)." % (CAP, 4 * CAP,
                                                                                                  DRAPE_CAP)]
    ran = sorted({r["target"] for r in rows})
    unrun = []
    for s in scenes:
        for c in sorted({r["config"] for r in rows if r["scene"] == s}):
            have = {r["target"] for r in rows if r["scene"] == s and r["config"] == c}
            miss = [t for t in STUDY_TARGETS if t not in have]
            if miss:
                unrun.append("%s %s: %s" % (s, c, ", ".join("%.3g" % t for t in miss)))
    out += ["", "**Sizes run**: dof targets %s (%d records).  **Not run** of `%s` (scene, configuration: dof "
            "targets): %s.  To run them, in pieces and resumably "
            "(a finished record is never redone; a killed run continues from its checkpoint):" %
            (", ".join("%.3g" % t for t in ran), len(rows), STUDY, "; ".join(unrun) if unrun else "none"), "",
            "    build/shellbench sweep --study bench/studies/%s --plan      # the runs, nothing run" % STUDY,
            "    OPENBLAS_NUM_THREADS=1 nice build/shellbench sweep --study bench/studies/%s --jobs 1 --max-runs %d"
            % (STUDY, 5 if LARGE else 10),
            "    # ... the same command again until it exits 0 (4 = stopped by --max-runs, more to do)",
            "    python3 bench/scaling/report.py %s" % DIR, "",
            "Bounds (stated in the study files): at most %d iterations per step (rmtr %d: its nested start's "
            "coarser-top V-cycles count%s; `run.max_iter`; a run that hits "
            "it is *not converged* and still counts per iteration and per step); %s  rmtr's levels grow with size, "
            "L = 1 + ceil(log4(n/500)) (coarsest level ≤ 500 dofs, about 250): 2 levels at 1e3, 3 at 4e3, 4 at "
            "1.6e4, 5 at 6.4e4, 6 at 2.56e5, 7 at 1e6; its curves join these.  Cost per Newton iteration / V-cycle is "
            "the run's seconds over its iterations (`/history/steps/iterations`), per step over its steps; the "
            "records also hold both per iteration and per step by part (`/history`)." % (CAP, 4 * CAP, DRAPE_CAP, (
                "cloth over a sphere is its first 8 of 30 steps (`bench/scaling/scenes/cloth_sphere_s8.json`, "
                "contact from about step 7), the trampoline and drape their first 2 steps (`trampoline_s2.json`, "
                "`drape_s2.json`), the plate its 1 load step." if LARGE else
                "cloth over a sphere is its first 12 of 30 steps (`bench/scaling/scenes/cloth_sphere_s12.json`, "
                "contact from about step 7); the trampoline and drape keep their 5 steps, the plate its 1 load "
                "step.")), ""]
    out += goals(rows, g1)
    out += large_summary()
    # --- DGEMM and CHOLMOD
    out += ["## Factorization rate against the machine's dense rate", ""]
    if g1:
        first = dg_txt.splitlines()
        out += ["DGEMM (`build/bench/bench_dgemm`, OpenBLAS, n × n, best of 5), measured on this machine:", "",
                "```"] + [l for l in first if l.strip()] + ["```", ""]
    else:
        out += ["DGEMM: not measured (no %s/dgemm.txt; `build/bench/bench_dgemm > %s/dgemm.txt`)." % (DIR, DIR), ""]
    out += ["CHOLMOD's achieved rate = `chol_flops_sum` / the process's CPU seconds inside the numeric "
            "factorizations (`chol_factorize_cpu`, records of format 4: other processes taking turns on the cores "
            "do not lower it), or / their inclusive wall seconds `factorize` for older records (basis *wall*); all "
            "levels, the largest runs of each method (lsnewton; its factorizations dominate):", "",
            "| scene | method/solver | dofs | factorizations' flops | factorize s (wall) | CPU s | indefinite "
            "factorizations | GFLOP/s | basis | share of DGEMM (1 core) | first factorization CPU s | GFLOP/s after "
            "the first (share) | build |",
            "|---|---|--:|--:|--:|--:|--:|--:|---|--:|--:|--:|---|"]
    clean = []
    for s in scenes:
        for r in sorted((r for r in rows if r["scene"] == s and r["solver"] == "lsnewton"),
                        key=lambda r: (r["method"], r["n_dofs"])):
            if r["incl_factorize"] <= 0 or r["chol_flops_sum"] <= 0 or r["n_dofs"] < max(
                    q["n_dofs"] for q in rows if q["scene"] == s and q["config"] == r["config"]):
                continue
            g, basis = fact_rate(r)
            npd = r.get("not_posdef", 0)
            npd = npd if math.isfinite(npd) else 0
            if npd == 0:
                clean.append(g)
            le = "≤ " if npd > 0 else ""
            cpu = fnum(r.get("cpu_factorize"))
            c1, gr = fnum(r.get("cpu_first")), fact_rate_reuse(r)
            out.append("| %s | %s | %d | %.3g | %.2f | %s | %d | %s%.2f | %s | %s | %s | %s | %s |" % (
                s, r["config"], r["n_dofs"], r["chol_flops_sum"], r["incl_factorize"],
                "%.2f" % cpu if math.isfinite(cpu) else "—", npd, le, g, basis,
                (le + "%.0f %%" % (100 * g / g1)) if g1 else "—", "%.2f" % c1 if math.isfinite(c1) else "—",
                ("%s%.2f (%.0f %%)" % (le, gr, 100 * gr / g1) if g1 else "%.2f" % gr) if math.isfinite(gr) else "—",
                r["build_id"]))
    out += ["", "A factorization that meets an indefinite matrix (lsnewton's shifted retries on the nonconvex "
            "drape, contact) stops early but `chol_flops_sum` counts the analysis's full flops for it, so rates "
            "of runs with indefinite factorizations are upper bounds (≤).  The others: %s GFLOP/s, %s of the "
            "one-core DGEMM rate.  %s  Wall seconds "
            "under load 5–7 understate the rates (basis *wall*).  Records of builds before 1900898 ran CHOLMOD's supernodal loops "
            "with its compiled-in 4 OpenMP threads on the 2-core machine (about half of their factorize seconds "
            "were thread waits: docs/scaling.md); later builds run CHOLMOD on one thread." % (
                ("%.1f–%.1f" % (min(clean), max(clean))) if clean else "—",
                ("%.0f–%.0f %%" % (100 * min(clean) / g1, 100 * max(clean) / g1)) if clean and g1 else "—",
                "The issue's goal (half the dense rate at ≥ 1e5 dofs) is judged per run in \"The issue's goals at "
                "≥ 1e5 dofs\" above." if LARGE else
                "At ≤ 1.7e4 dofs a 2-D mesh's supernodes are small (the top separator has ~√n nodes), so CHOLMOD "
                "spends much of its time in small dense blocks and sparse bookkeeping; the issue's goal (half the "
                "dense rate at ≥ 1e5 dofs) is judged at the sizes of results/scaling_large/report.md."), ""]
    # --- exponents
    out += ["## Fitted exponents", "",
            "y = c n^p by least squares in log-log over the largest (up to four) sizes of each configuration, y "
            "the run's total seconds, its seconds per outer iteration, each component's exclusive seconds per "
            "outer iteration (/iter), per step (/step) or per run (/run), and the peak memory; "
            "± is the 95 % Student-t half-width, t_{0.975,m−2} s/√Sxx (m points; with m = 3, t = 12.7, so the "
            "intervals are wide: three sizes a factor 4 apart are what ran).  Components below 1 ms at every size "
            "are left out (—) as timer noise.", ""]
    for s in scenes:
        configs = sorted({r["config"] for r in rows if r["scene"] == s})
        out += ["### %s" % s, "", picture(rows, s), "", "![%s](scaling-%s.png)" % (s, s), "",
                "| method/solver | sizes (dofs) | total | per iteration | " + " | ".join(
                    "%s /%s" % (c, NORM[c][:4] if NORM[c] != "iteration" else "iter") for c in COMPONENTS) + " | peak memory |",
                "|---|---|" + "--:|" * (len(COMPONENTS) + 3)]
        for c in configs:
            ns, _ = series(rows, s, c, "seconds_total")
            cells = []
            for comp in ("seconds_total", "per_iter") + tuple("n_" + c for c in COMPONENTS) + ("peak_rss",):
                n2, ys = series(rows, s, c, comp)
                if comp.startswith("n_") and max(series(rows, s, c, comp[2:])[1] + [0]) < 1e-3:
                    cells.append("—")
                else:
                    cells.append(fmt_fit(*fit(n2, ys)))
            out.append("| %s | %s | %s |" % (c, ", ".join("%d" % n for n in ns), " | ".join(cells)))
        # per iteration / per step and crossings
        out += ["", "Per iteration (Newton iteration, TR iteration or V-cycle) and per step, and where components "
                "cross (dofs at which the second overtakes the first, log-log interpolation between sizes):", "",
                "| method/solver | dofs | status | iterations (finest top) | s / iteration | s / step | factorize overtakes assembly "
                "| collide overtakes assembly | samples+record+setup share |", "|---|--:|---|--:|--:|--:|---|---|--:|"]
        for c in configs:
            rs = sorted((r for r in rows if r["scene"] == s and r["config"] == c), key=lambda r: r["n_dofs"])
            ns = [r["n_dofs"] for r in rs]
            fx = crossing(ns, [r["assembly"] for r in rs], [r["factorize"] for r in rs])
            cx = crossing(ns, [r["assembly"] for r in rs], [r["collide"] for r in rs]) if any(
                r["collide"] > 0 for r in rs) else "no contact"
            if not any(r["factorize"] > 0 for r in rs):
                fx = "no factorization"
            for k, r in enumerate(rs):
                it = r["iterations"]
                harness = (r["samples"] + r["record"] + r["setup"]) / r["seconds_total"] if r["seconds_total"] else 0
                out.append("| %s | %d | %s | %d (%d) | %s | %.3g | %s | %s | %.1f %% |" % (
                    c if k == 0 else "", r["n_dofs"], "converged" if r["status"] == 0 else r["reason"], it,
                    r.get("iters_finest", it),
                    "%.3g" % (r["seconds_total"] / it) if it else "—",
                    r["seconds_total"] / max(r["steps_done"], 1), fx if k == 0 else "", cx if k == 0 else "",
                    100 * harness))
        out.append("")
        plot(rows, s, configs, os.path.join(DIR, "scaling-%s.png" % s))
    # --- the O(n^1.1) goal for the harness parts
    out += ["## Harness parts against the O(n^1.1) goal", "",
            "The issue asks that nothing but factorization and the solve grow faster than n^1.1.  Fitted "
            "exponents of the harness parts (samples and record per step, setup per run) and of assembly (per "
            "iteration) and the symbolic analysis (per run), per configuration, over the sizes run; "
            "*above* = the whole 95 % interval above 1.1, *below* = the whole interval at or below 1.1, "
            "else undecided at these sizes.", "",
            "| scene | part | above 1.1 | below | undecided | largest exponent (configuration) |",
            "|---|---|--:|--:|--:|---|"]
    for s in scenes:
        configs = sorted({r["config"] for r in rows if r["scene"] == s})
        for comp in ("samples", "record", "setup", "assembly", "analyze"):
            up = lo = und = 0
            best = None
            for c in configs:
                ns, ys = series(rows, s, c, "n_" + comp)
                if max(series(rows, s, c, comp)[1] + [0]) < 1e-3:
                    continue
                p_, hw, m = fit(ns, ys)
                if not math.isfinite(p_):
                    continue
                if math.isfinite(hw) and p_ - hw > 1.1:
                    up += 1
                elif math.isfinite(hw) and p_ + hw <= 1.1:
                    lo += 1
                else:
                    und += 1
                if best is None or p_ > best[0]:
                    best = (p_, c, hw, m)
            if best:
                out.append("| %s | %s | %d | %d | %d | %s (%s) |" % (s, comp, up, lo, und, fmt_fit(best[0], best[2], best[3]),
                                                                    best[1]))
    out += ["", "With two or three sizes a factor 4 apart most exponents are undecided; fixed per-run costs "
            "(process start, HDF5, sample grids of 21 × 21 points) make small-size exponents of the harness parts "
            "low, not high.  The 6.4e4–1e6 sizes decide the goal.", ""]
    # --- memory estimate
    out += ["## Memory: estimate against measured peak", "",
            "`memory_estimate` (what `run.max_memory` is checked against) over `peak_rss`, per run.  Only runs "
            "whose peak is their own count (records with `peak_rss_start`, from 12f1ba9 on): before, a sweep's "
            "forked run started with the sweep's resident pages and peak, its plan's set-ups at every size (up to "
            "1.2 GB at 1e6 dofs), so its peak was the sweep's, not its own.  The issue's goal (within 30 %) is "
            "for ≥ 1e5 dofs; below, the fixed 16 MB of the process model and the libraries' own footprint "
            "dominate.", "",
            "| scene | dofs | runs with their own peak | ratio estimate/peak: min | median | max | runs with an inherited peak |",
            "|---|---|--:|--:|--:|--:|--:|"]
    for s in scenes:
        for lo, hi, lab in ((0, 1e5, "< 1e5"), (1e5, 1e99, "≥ 1e5")):
            rs = [r for r in rows if r["scene"] == s and lo <= r["n_dofs"] < hi]
            q = sorted(own_ratio(r) for r in rs if r["own_peak"] and math.isfinite(own_ratio(r)))
            inh = sum(1 for r in rs if not r["own_peak"])
            if not rs:
                continue
            if q:
                out.append("| %s | %s | %d | %.2f | %.2f | %.2f | %d |" % (s, lab, len(q), q[0], q[len(q) // 2], q[-1], inh))
            else:
                out.append("| %s | %s | 0 | — | — | — | %d |" % (s, lab, inh))
    out += ceiling_section(g1)
    out += supernodes_section(g1)
    out += io_section()
    builds = sorted({r["build_id"] for r in rows})
    cores = sorted({r["blas_core"] for r in rows})
    thr = sorted({r["openblas_num_threads"] for r in rows})
    out += ["", "## Records", "",
            "Builds %s; BLAS kernels %s; OPENBLAS_NUM_THREADS %s; every run one process, `--jobs 1`, `nice`.  "
            "Per-record figures: `%s/records.csv`." % (", ".join(builds), ", ".join(cores), ", ".join(thr), DIR), ""]
    with open(os.path.join(DIR, "report.md"), "w") as fh:
        fh.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
