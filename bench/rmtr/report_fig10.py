"""bench/rmtr/report_fig10.py — issue 43: the RMTR paper's Fig. 10 (largest
time step at which each solver converges, 1,083 dofs) beside ours, read from
the study reports results/dt_stability_large/report.md (the paper's size,
`shellbench report --study bench/studies/dt_stability_large.json`) and
results/dt_stability/report.md (about 400 dofs), which are made from their
records; never re-runs.  What is not run is said per row."""
import csv
import glob
import io
import os
import re
import subprocess
import sys

SCENES = ["trampoline", "drooping", "reentrant_corner", "drape"]
NAMES = {"trampoline": "Trampoline", "drooping": "Drooping", "reentrant_corner": "Re-entrant corner", "drape": "Drape"}
SOLVERS = ["tr", "rmtr L2", "lsnewton", "damped", "linearized"]
# RMTR paper §7.4.1 and Fig. 10 (1,083 dofs): the text gives no per-solver values, only the statement
PAPER = {"tr": "converges for every dt <= 1 s (all scenes)", "rmtr L2": "converges for every dt <= 1 s (all scenes)",
         "lsnewton": "needs smaller dt; worse on harder scenes", "damped": "needs smaller dt; worse on harder scenes",
         "linearized": "needs smaller dt; drape: about 10 million more steps than TR"}


PROBES = "probes.csv"   # results/dt_stability_large/probes.csv: every probe of every search (all methods)
METHODS = ["rmtr", "bhem", "linear_fem"]


def make_probes(results_root, binary="build/shellbench"):
    """(re)write results/dt_stability_large/probes.csv from the records there (`shellbench report --format
    csv`): one row per probe of every method's searches, so the largest converging dt can be read without every
    probe's digest in git (results/ size limit, issue 43)"""
    d = os.path.join(results_root, "dt_stability_large")
    files = sorted(glob.glob(os.path.join(d, "*", "*-dt*.h5")))
    out = subprocess.run([binary, "report", "--format", "csv"] + files, capture_output=True, text=True).stdout
    rows = []
    for r in csv.DictReader(io.StringIO(out)):
        m = re.search(r"/([a-z_]+)/(rmtr|bhem|linear_fem)-(tr|rmtr-l2|lsnewton|damped|linearized)-r(\d+)-dt([0-9.e+-]+)"
                      r"\.h5$", r["file"])
        if not m:
            continue
        rows.append((m.group(1), m.group(2), m.group(3).replace("rmtr-l2", "rmtr L2"), r["dofs"], m.group(5),
                     r["status_code"], r["reason"], r["steps"], r["iterations"], r["seconds"]))
    rows.sort(key=lambda x: (SCENES.index(x[0]) if x[0] in SCENES else 9, METHODS.index(x[1]), SOLVERS.index(x[2]),
                             float(x[4])))
    # the study's verdict per probe: a linearized probe converges only when every step's one Newton step met the
    # stopping test (sb_study_dt.c), which its record status does not say; the searches are bisections, so
    # its probes up to the report's largest converging dt are the converging ones
    rep = read(os.path.join(d, "report.md"))
    def study_ok(x):
        if x[5] != "0":
            return "0"
        if x[2] != "linearized":
            return "1"
        cell = rep.get((x[0], x[1], x[2]), ("", ""))[1]
        best = 1.0 if cell.startswith("≥ 1") else float(cell.split()[0]) if cell[:1].isdigit() else None
        return "1" if best is not None and float(x[4]) <= best * (1 + 1e-9) else "0"
    with open(os.path.join(d, PROBES), "w") as f:
        f.write("scene,method,solver,dofs,dt,status_code,reason,steps,iterations,seconds,study_converged\n")
        for x in rows:
            f.write(",".join(x + (study_ok(x),)) + "\n")
    return len(rows)


def read_probes(results_root, method="rmtr"):
    """{(scene, solver): (dofs, largest converging dt or None, smallest failing dt above it or None, probes,
    reason at the smallest failing dt)} of one method's searches, from probes.csv"""
    path = os.path.join(results_root, "dt_stability_large", PROBES)
    if not os.path.exists(path):
        return {}
    by = {}
    for r in csv.DictReader(open(path)):
        if r["method"] == method:
            by.setdefault((r["scene"], r["solver"]), []).append(r)
    out = {}
    for k, ps in by.items():
        ok = lambda p: p.get("study_converged", p["status_code"] == "0" and "1") == "1"
        conv = [float(p["dt"]) for p in ps if ok(p)]
        best = max(conv) if conv else None
        fails = [p for p in ps if not ok(p) and (best is None or float(p["dt"]) > best)]
        fmin = min(fails, key=lambda p: float(p["dt"])) if fails else None
        out[k] = (ps[0]["dofs"], best, float(fmin["dt"]) if fmin else None, len(ps), fmin["reason"] if fmin else "")
    return out


def read(path):
    """{(scene, method, solver): (dofs, largest converging dt cell, outcome at dt = 1, why, probes)}"""
    out, scene = {}, None
    if not os.path.exists(path):
        return out
    for ln in open(path):
        if ln.startswith("## "):
            scene = ln[3:].strip()
        elif ln.startswith("| ") and scene and not ln.startswith("| method"):
            c = [x.strip() for x in ln.strip().strip("|").split("|")]
            if len(c) >= 7 and c[0] in ("rmtr", "bhem", "linear_fem"):
                out[(scene, c[0], c[1])] = (c[2], c[3], c[4], c[5], c[6])
    return out


def verdict(cell, solver):
    """our largest dt against the paper's statement"""
    if cell.startswith("unfinished") or cell == "":
        return "not finished"
    at_cap = cell.startswith("≥ 1")
    if solver in ("tr", "rmtr L2"):
        return "agrees" if at_cap else "differs (ours fails below 1 s)"
    return "differs (ours reaches 1 s)" if at_cap else "agrees (needs smaller dt)"


def section(results_root):
    """the Markdown section; results_root is the directory holding results/dt_stability_large"""
    big = read(os.path.join(results_root, "dt_stability_large", "report.md"))
    small = read(os.path.join(results_root, "dt_stability", "report.md"))
    if not big:
        return "\n## Fig. 10 at the paper's size (1,083 dofs)\n\nNot run (no results/dt_stability_large/report.md).\n"
    L = ["\n## Fig. 10 at the paper's size (1,083 dofs): the largest dt at which each solver converges (issue 43)\n",
         "Ours: the subdivision method at the paper's 1,083 dofs (the re-entrant corner: 1,008 on a single-level cage, 1,035 on RMTR's), 5",
         "steps per probe, at most 2,000 iterations per step, dt from 1 s down by factors of 100, then bisections",
         "(bench/studies/dt_stability_large.json; the rmtr part run by dt_stability_large_rmtr.json into the same",
         "records).  \"≥ 1\" = converges at the cap the paper also uses; \"unfinished\" = the search had not reached",
         "its answer when the CPU budget ended (the next probe named).  The 400-dof column is the smaller study",
         "(results/dt_stability: 300 iterations per step).  The paper gives no per-solver values in its text, only",
         "the statement in the \"paper\" column (§7.4.1).\n",
         "| scene | solver | dofs (record) | paper (Fig. 10, §7.4.1) | ours: largest converging dt (s) | steps per TR step (TR's dt / this dt) | outcome at dt = 1 | probes | verdict | ours, ~400 dofs |",
         "|---|---|--:|---|---|--:|---|--:|---|---|"]
    pr = read_probes(results_root)
    counts = {"agrees": 0, "differs": 0, "not finished": 0}
    for sc in SCENES:
        for so in SOLVERS:
            b = big.get((sc, "rmtr", so))
            s = small.get((sc, "rmtr", so))
            if b is None:
                continue
            v = verdict(b[1], so)
            counts[v.split()[0] if not v.startswith("not") else "not finished"] += 1
            lo = lambda cell: 1.0 if cell.startswith("≥ 1") else (float(cell.split()[0]) if cell[:1].isdigit() else None)
            t, m = big.get((sc, "rmtr", "tr")), lo(b[1])
            ratio = "%.3g" % (lo(t[1]) / m) if t and lo(t[1]) and m else "—"
            L.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                NAMES[sc], so, pr[(sc, so)][0] if (sc, so) in pr else b[0], PAPER[so], b[1], ratio, b[2], b[4], v,
                s[1] if s else "—"))
    others = [(k, v) for k, v in big.items() if k[1] != "rmtr" and (v[1].startswith("≥") or v[1][:1].isdigit())]
    pend = sum(1 for k, v in big.items() if k[1] != "rmtr" and v[1].startswith("unfinished"))
    lin = big.get(("drape", "rmtr", "linearized"))
    if lin and lin[1][:1].isdigit():
        L.append("\nDrape, linearized solve: %.3g steps per TR step (paper: the difference in the number of steps is"
                 " \"about 10 million\"; the drape's 5 s ramp at our largest converging dt needs %.3g steps)." % (
                     1.0 / float(lin[1].split()[0]), 5.0 / float(lin[1].split()[0])))
    L.append("\nOf the %d subdivision rows: %d agree with the paper's statement, %d differ, %d not finished." % (
        sum(counts.values()), counts["agrees"], counts["differs"], counts["not finished"]))
    if others:
        L += ["\nThe same searches for the other discretizations (the suite's extension of Fig. 10; same study, same "
              "probes and caps): the largest converging dt (s) per scene and solver, the dofs in brackets.\n",
              "| scene | solver | rmtr (subdivision) | bhem | linear_fem |", "|---|---|---|---|---|"]
        short = lambda c: "≥ 1" if c.startswith("≥ 1") else c.split(" (fails")[0] if c[:1].isdigit() else c
        for sc in SCENES:
            for so in SOLVERS:
                cells = []
                for me in METHODS:
                    b = big.get((sc, me, so))
                    cells.append("%s (%s)" % (short(b[1]), b[0]) if b and b[0] not in ("", "—") else
                                 "refused" if b else "—")
                L.append("| %s | %s | %s |" % (NAMES[sc], so, " | ".join(cells)))
        agree_o = sum(1 for k, v in others if k[1] != "rmtr" and verdict(v[1], k[2]).startswith("agrees"))
        L.append("\nbhem and linear_fem: %d of %d finished searches agree with the paper's statement as the "
                 "subdivision rows are judged above." % (agree_o, len(others)))
    if pend:
        L.append("%d bhem / linear_fem searches are not finished or not run (the study's full plan; CPU budget)." % pend)
    L.append("Full per-probe tables and pictures: results/dt_stability_large/report.md, made by `shellbench report"
             " --study` from all %s probes; every probe's outcome is in results/dt_stability_large/%s (made from the"
             " records by `python3 bench/rmtr/report_fig10.py --probes`).  Committed digests: the largest converging"
             " probe of each search; the other bisection probes' digests are not committed (results/ size limit), so"
             " `shellbench report --study` over the committed records alone would show those searches as unfinished."
             % (sum(sum(v[3] for v in read_probes(results_root, m).values()) for m in METHODS) or "its", PROBES))
    return "\n".join(L) + "\n"


def summary_verdict(results_root):
    """the verdict cell of the summary row: per solver, whether all four scenes agree with the paper's statement"""
    big = read(os.path.join(results_root, "dt_stability_large", "report.md"))
    if not big:
        return None
    agree, differ, unf = [], [], []
    for so in SOLVERS:
        vs = [verdict(big[(sc, "rmtr", so)][1], so) for sc in SCENES if (sc, "rmtr", so) in big]
        (unf if any(v.startswith("not") for v in vs) or not vs else
         agree if all(v.startswith("agrees") for v in vs) else differ).append(so)
    out = "reproduced at 1,083 dofs for %s" % ", ".join(agree) if agree else "not reproduced"
    if differ:
        out += "; not for %s (converges at dt = 1 s where the paper needs smaller dt)" % ", ".join(differ)
    if unf:
        out += "; unfinished: %s" % ", ".join(unf)
    return out


def summary_cell(results_root):
    """one sentence for the report's summary table"""
    big = read(os.path.join(results_root, "dt_stability_large", "report.md"))
    if not big:
        return None
    parts = []
    for sc in SCENES:
        cap = [so for so in SOLVERS if big.get((sc, "rmtr", so), ("", ""))[1].startswith("≥ 1")]
        fin = [so for so in SOLVERS if (sc, "rmtr", so) in big and not big[(sc, "rmtr", so)][1].startswith("unfinished")]
        below = [so for so in fin if so not in cap]
        unf = [so for so in SOLVERS if (sc, "rmtr", so) in big and so not in fin]
        parts.append("%s: dt = 1 s with %s%s%s" % (
            NAMES[sc], ", ".join(cap) or "none", "; smaller dt: " + ", ".join(
                "%s %s" % (so, big[(sc, "rmtr", so)][1].split(" (")[0]) for so in below) if below else "",
            "; unfinished: " + ", ".join(unf) if unf else ""))
    return "; ".join(parts)


if __name__ == "__main__":
    # python3 bench/rmtr/report_fig10.py --probes: rewrite probes.csv from the records present (run it
    # while every probe's record is there: it lists only what it finds)
    if sys.argv[1:] == ["--probes"]:
        print("%d probes" % make_probes("results", os.environ.get("SB_BIN", "build/shellbench")))
    else:
        print(section("results"))
