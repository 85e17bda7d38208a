#!/usr/bin/env python3
"""bench/linear_solvers/report.py — results/linear_solvers/report.md (issue 38,
the measured part): solver.linear = cholmod | pcg-mg | pcg-amg with lsnewton,
as size grows, from records only.

    python3 bench/linear_solvers/report.py [DIR]     # DIR default results/linear_solvers

Reads every record or digest DIR/SCENE/*.h5 (h5dump, hdf5-tools; .partial
checkpoints and refused runs are left out) and DIR/cpu_seconds.csv (the
user + system CPU seconds and the wall seconds of each run's process, logged
by /usr/bin/time around `shellbench sweep --max-runs 1` when the run was
made: the records hold wall time only, and the machine was shared).  Never
re-runs anything.

Figures per record (docs/recorded_figures.md, format 3):
  * Newton iterations: rows of /history/iterations with iter > 0 (each
    step's iter-0 row is its start, not an iteration);
  * CG iterations per Newton step: /history/iterations/linear_iters of those
    rows (a direct solve records 1); capped solves: krylov_status & 3 == 1;
  * seconds per Newton iteration: /history/iterations/seconds of those rows
    (the solver's iterate: assembly, linear solve, line search), mean;
  * wall seconds of the run: /stats seconds_total; peak memory: /stats
    peak_rss (VmHWM of the run's process at its end).

Goals (issue 38): at >= 2.5e5 dofs pcg-mg converges >= 2x faster than
cholmod on the plate and the trampoline with <= 1/3 of its peak memory;
pcg-mg's CG iterations per Newton step grow at most logarithmically with the
dofs.  With three sizes n1 < n2 < n3, "at most logarithmically" is judged on
the mean CG iterations per Newton step c(n): the growth per unit of ln n
from n2 to n3, (c3 - c2) / ln(n3/n2), must not exceed that from n1 to n2,
(c2 - c1) / ln(n2/n1) (a logarithm grows by the same amount per factor of
n, a power by more and more), or the increase c3 - c2 is at most one
iteration (the granularity of the count).
"""
import csv, glob, math, os, re, subprocess, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from h5ddl import h5dump, parse_ddl  # noqa: E402  (bench/h5ddl.py)

DIR = sys.argv[1] if len(sys.argv) > 1 else "results/linear_solvers"
LINEAR = ("cholmod", "pcg-mg", "pcg-mg (W-cycle)", "pcg-amg")
GOAL_SCENES = ("plate_clamped", "trampoline_s2")
GOAL_DOFS = 2.5e5
ROOT = ("scene_name", "method", "solver", "levels", "res", "n_dofs", "status", "reason", "steps_planned",
        "steps_done", "build_id")
STATS = ("seconds_total", "peak_rss", "peak_rss_setup")
HIST = ("iter", "linear_iters", "krylov_status", "seconds", "seconds_assembly", "shift", "krylov_rtol")


def read_record(path):
    args = []
    for a in ROOT:
        args += ["-a", "/" + a]
    for a in STATS:
        args += ["-a", "/stats/" + a]
    args += ["-a", "/params/solver.linear", "-a", "/params/solver.mg_cycle", "-d", "/stats/chol_factor_entries"]
    for d in HIST:
        args += ["-d", "/history/iterations/" + d]
    v = parse_ddl(h5dump(path, args))
    for d in HIST:
        if "/history/iterations/" + d in v:
            v[d] = v.pop("/history/iterations/" + d)
    if "n_dofs" not in v or "iter" not in v:
        return None
    r = {k: (v[k][0] if v.get(k) else "") for k in ROOT + STATS}
    r["linear"] = v.get("solver.linear", ["cholmod"])[0]
    if r["linear"] == "pcg-mg" and v.get("solver.mg_cycle", ["v"])[0] == "w":   # records before it have V-cycles
        r["linear"] = "pcg-mg (W-cycle)"
    # the Cholesky factors' values, 8 bytes per stored entry, summed over levels
    # (cholmod: the finest level's; pcg-mg: the coarsest level's)
    r["factor_bytes"] = 8.0 * sum(v.get("/stats/chol_factor_entries", []))
    st = r["status"]
    r["status"] = {0: "converged", 1: "not converged", 2: "unfinished"}.get(int(st), "failed") if st != "" else "?"
    rows = [k for k, it in enumerate(v["iter"]) if it > 0]
    li = [v["linear_iters"][k] for k in rows]
    ks = [int(v["krylov_status"][k]) for k in rows] if "krylov_status" in v else []
    r["newton"] = len(rows)
    r["cg"] = li
    r["cg_mean"] = sum(li) / len(li) if li else float("nan")
    r["cg_max"] = max(li) if li else float("nan")
    # per digit of the tolerance each Newton step asked for: sum CG / sum log10(1/eta) (the forcing terms'
    # mix, which differs from run to run, taken out of the count)
    eta = [v["krylov_rtol"][k] for k in rows] if "krylov_rtol" in v else []
    dig = sum(math.log10(1.0 / e) for e in eta if 0.0 < e < 1.0)
    r["cg_digit"] = sum(li) / dig if dig > 0 and li else float("nan")
    r["capped"] = sum(1 for s in ks if s & 3 == 1)
    r["shifted"] = sum(1 for k in rows if v["shift"][k] > 0) if "shift" in v else 0
    sec = [v["seconds"][k] for k in rows]
    r["s_iter"] = sum(sec) / len(sec) if sec else float("nan")
    r["file"] = os.path.relpath(path, DIR)
    return r


def load():
    cpu = {}
    try:
        with open(os.path.join(DIR, "cpu_seconds.csv")) as fh:
            for row in csv.DictReader(fh):
                cpu[row["record"]] = row
    except OSError:
        pass
    recs = []
    for p in sorted(glob.glob(os.path.join(DIR, "*", "*.h5"))):
        r = read_record(p)
        if not r:
            continue
        c = cpu.get(r["file"])
        r["cpu"] = float(c["user_s"]) + float(c["sys_s"]) if c else float("nan")
        recs.append(r)
    return recs


def f0(x):
    return "—" if not isinstance(x, float) or not math.isfinite(x) else "{:,.0f}".format(x)


def f1(x):
    return "—" if not isinstance(x, float) or not math.isfinite(x) else "%.1f" % x


def f2(x):
    return "—" if not isinstance(x, float) or not math.isfinite(x) else "%.2f" % x


def mb(b):
    return b / 2 ** 20 if isinstance(b, float) else float("nan")


def main():
    recs = load()
    out = []
    w = out.append
    w("# Linear solvers against the direct solve (issue 38)")
    w("")
    w("Generated by `python3 bench/linear_solvers/report.py` from the %d records (digests) in `%s/` of the studies "
      "`bench/studies/linear_solvers_large.json` (1.3e4-2.6e5 dofs), `linear_solvers_1e6.json` (1e6 dofs), `linear_solvers_drape_1e6.json` (the drape at 1e6 dofs), `linear_solvers_rmtr.json` (the rmtr method, 1.3e4-2.5e5 dofs, since pcg-mg solves its penalty band exactly), `linear_solvers_rmtr_amg.json` (pcg-amg on it, 1.3e4 dofs) and `linear_solvers_wcycle.json` (linear_fem's pcg-mg with the W-cycle, `solver.mg_cycle=w`, on the same meshes: rows *pcg-mg (W-cycle)*; every other pcg-mg row is a V-cycle) and "
      "the CPU seconds logged beside them (`cpu_seconds.csv`); every record was made on one machine, one run at a "
      "time, by the build aaf6a18 (committed as 3d1a57a, the same sources: the Krylov paths' correction test, "
      "`solver.cg_xstop`), except the cholmod records at 1e6 dofs, which are the ninth session's (064c9c2-dirty; "
      "bhem, linear_fem) and the eighth's (b23a8de; rmtr), on other machines: the direct path has not changed "
      "since but the machines differ, so the 1e6 ratios pair records of two machines.  Do not edit by hand."
      % (len(recs), DIR))
    w("")
    w("lsnewton (line-search Newton, Eisenstat–Walker forcing terms on the Krylov paths) with `solver.linear` = "
      "cholmod, pcg-mg (CG + one V-cycle of the method's own hierarchy, coarsest level ~1,000 dofs), pcg-amg "
      "(CG + hypre BoomerAMG); the trampoline and drape bounded to their first 2 steps (the drape at 1e6 dofs to its first 5 Newton "
      "iterations: these rows measure the cost per Newton iteration, not the time to convergence), the clamped "
      "plate's one load step.  *Newton* counts the iterations of all steps; *CG/Newton* the CG iterations per Newton iteration "
      "(mean and max; a direct solve counts 1); *s/Newton* the mean wall seconds of one Newton iteration (assembly, "
      "linear solve, line search); *wall s* the record's whole run (set-up and sample grids included); *CPU s* "
      "user + system seconds of the run's process (2 cores; the rows at 2.5e5 and 1e6 dofs but the drape's pcg-mg "
      "ones ran with nothing else on the machine, some 1.3e4-7.9e4-dof rows and the drape's 2.5e5-dof pcg-mg rows "
      "beside a compilation or a profiling run on the other core; ratios below use CPU seconds where logged); *peak MB* the "
      "process's peak resident memory (VmHWM) at the end of the run, *set-up MB* the same at the end of set-up "
      "(mesh, patterns, the matrices of every level, quadrature data, the linear solver's allocations; no "
      "factorization yet): the memory every path holds before it solves anything; *factor MB* the values of the "
      "Cholesky factors (`chol_factor_entries` x 8 B: cholmod's of the finest level, pcg-mg's of its coarsest).")
    w("")
    scenes = []
    for r in recs:
        if r["scene_name"] not in scenes:
            scenes.append(r["scene_name"])
    key = {}
    for r in recs:
        key[(r["scene_name"], r["method"], r["n_dofs"], r["linear"])] = r
    for sc in scenes:
        w("## %s" % sc)
        w("")
        w("| method | dofs | levels | linear | status | Newton | CG/Newton mean | max | capped | s/Newton | wall s "
          "| CPU s | peak MB | set-up MB | factor MB |")
        w("|---|--:|--:|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
        rows = sorted((r for r in recs if r["scene_name"] == sc),
                      key=lambda r: (r["method"], r["n_dofs"], LINEAR.index(r["linear"]) if r["linear"] in LINEAR
                                     else 9))
        for r in rows:
            direct = r["linear"] == "cholmod"
            st = "%s (%s)" % (r["status"], r["reason"])
            w("| %s | %s | %d | %s | %s | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                r["method"], f0(r["n_dofs"]), int(r["levels"]), r["linear"], st, r["newton"],
                "—" if direct else f1(r["cg_mean"]), "—" if direct else f0(r["cg_max"]),
                "—" if direct else "%d" % r["capped"], f2(r["s_iter"]), f1(r["seconds_total"]), f1(r["cpu"]),
                f0(mb(r["peak_rss"])), f0(mb(r["peak_rss_setup"])), f0(mb(r["factor_bytes"]))))
        w("")
    # goals
    w("## The issue's goals")
    w("")
    w("Speed and memory at >= 2.5e5 dofs, pcg-mg (and pcg-amg beside it) against cholmod on the same scene, method "
      "and mesh: *speed-up* = cholmod's seconds / the path's seconds (CPU; wall in brackets), goal >= 2 to convergence; "
      "per Newton iteration: the same with each run's CPU seconds divided by its Newton iterations (the Krylov paths "
      "take more of them: Eisenstat–Walker asks little of the first); *memory* = the path's peak / cholmod's peak, "
      "goal <= 0.33 (missed by k: k times the allowed third).")
    w("")
    w("| scene | method | dofs | path | converged (path / cholmod) | CPU s (path / cholmod) | speed-up to convergence, CPU (wall) "
      "| speed-up per Newton iteration, CPU | goal 2x | peak MB (path / cholmod) | memory ratio | goal 1/3 |")
    w("|---|---|--:|---|---|--:|--:|--:|---|--:|--:|---|")
    for sc in scenes:
        for (s, m, n, lin), r in sorted(key.items()):
            if s != sc or n < GOAL_DOFS or lin == "cholmod":
                continue
            c = key.get((s, m, n, "cholmod"))
            if not c:
                continue
            su = c["cpu"] / r["cpu"] if r["cpu"] > 0 else float("nan")
            suw = c["seconds_total"] / r["seconds_total"]
            # per Newton iteration: the run's CPU seconds (set-up included) over its Newton iterations
            spi = (c["cpu"] / c["newton"]) / (r["cpu"] / r["newton"]) if r["cpu"] > 0 and r["newton"] else float("nan")
            mr = r["peak_rss"] / c["peak_rss"]
            both = r["status"] == "converged" and c["status"] == "converged"
            sp = su if math.isfinite(su) else suw
            gs = ("met" if sp >= 2 else "missed by %.2fx" % (2 / sp)) if both else "not judged (not converged)"
            gm = "met" if mr <= 1 / 3 else "missed by %.2fx" % (mr * 3)
            tag = "" if s in GOAL_SCENES else " (not a goal scene)"
            w("| %s%s | %s | %s | %s | %s / %s | %s / %s | %s (%s) | %s | %s | %s / %s | %.2f | %s |" % (
                s, tag, m, f0(n), lin, r["status"], c["status"], f1(r["cpu"]), f1(c["cpu"]), f2(su), f2(suw), f2(spi),
                gs, f0(mb(r["peak_rss"])), f0(mb(c["peak_rss"])), mr, gm))
    w("")
    w("CG iterations per Newton iteration against dofs (mean over the run's Newton iterations; slope = growth per "
      "unit of ln n between consecutive sizes; *at most logarithmic* when the last slope is not above the first, "
      "or the last increase is at most one iteration; see the script's docstring).  *Per digit*: the run's CG "
      "iterations over the digits its Newton steps asked for, sum log10(1/eta) of the recorded forcing terms, "
      "judged by the same rule: the count per Newton step mixes the solver's cost with how much each step asked "
      "of it, which the forcing terms decide and which differs from one run to the next:")
    w("")
    w("| scene | method | path | dofs | CG/Newton mean | slopes per ln n | verdict | CG per digit of eta | "
      "slopes per ln n | verdict per digit |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    for sc in scenes:
        for m in sorted({r["method"] for r in recs if r["scene_name"] == sc}):
            for lin in LINEAR[1:]:
                runs = sorted(((n, r) for (s, mm, n, l), r in key.items()
                               if s == sc and mm == m and l == lin and math.isfinite(r["cg_mean"])),
                              key=lambda x: x[0])
                pts = [(n, r["cg_mean"]) for n, r in runs]
                if len(pts) < 2:
                    continue
                bad = [n for n, r in runs if r["status"] != "converged"]

                def judge(p):
                    s = [(p[i + 1][1] - p[i][1]) / math.log(p[i + 1][0] / p[i][0]) for i in range(len(p) - 1)]
                    if bad:
                        v = "not judged: the %s-dof run%s did not converge" % (
                            ", ".join(f0(float(n)) for n in bad), "s" if len(bad) > 1 else "")
                    elif len(p) >= 3:
                        ok = s[-1] <= s[0] or p[-1][1] - p[-2][1] <= 1.0
                        v = "at most logarithmic" if ok else "faster than logarithmic"
                    else:
                        v = "two sizes only: not judged"
                    return s, v
                sl, verdict = judge(pts)
                pd = [(n, r["cg_digit"]) for n, r in runs]
                if all(math.isfinite(c) for _, c in pd):
                    sld, vd = judge(pd)
                    dcols = (", ".join(f1(c) for _, c in pd), ", ".join("%.2f" % x for x in sld), vd)
                else:
                    dcols = ("—", "—", "—")
                w("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                    sc, m, lin, ", ".join(f0(float(n)) for n, _ in pts), ", ".join(f1(c) for _, c in pts),
                    ", ".join("%.2f" % x for x in sl), verdict, *dcols))
    w("")
    # the study's plan (`shellbench sweep --study ... --plan`, saved as DIR/plan.txt when the records were
    # committed): every planned run without a record or digest here was not made
    missing = []
    try:
        with open(os.path.join(DIR, "plan.txt")) as fh:
            for line in fh:
                f = [x for x in line.split() if x.startswith(DIR + "/") and x.endswith(".h5")]
                if f and not os.path.exists(f[0]):
                    missing.append(line.split()[:4] + [f[0]])
    except OSError:
        missing = None
    w("## Runs of the study not made")
    w("")
    if missing is None:
        w("(no `%s/plan.txt`: the plans of the studies above, `shellbench sweep --study FILE --plan`, to compare)"
          % DIR)
    elif not missing:
        w("None: every planned run has its record.")
    else:
        w("%d of the planned runs (`%s/plan.txt`) have no record here:" % (len(missing), DIR))
        w("")
        for m in missing:
            w("- %s %s %s %s (`%s`)" % tuple(m))
    w("")
    with open(os.path.join(DIR, "report.md"), "w") as fh:
        fh.write("\n".join(out))
    print("wrote %s (%d records)" % (os.path.join(DIR, "report.md"), len(recs)))


if __name__ == "__main__":
    main()
