"""bench/rmtr/report_fig10.py — issue 43: the RMTR paper's Fig. 10 (largest
time step at which each solver converges, 1,083 dofs) beside ours, read from
the study reports results/dt_stability_large/report.md (the paper's size,
`shellbench report --study bench/studies/dt_stability_large.json`) and
results/dt_stability/report.md (about 400 dofs), which are made from their
records; never re-runs.  What is not run is said per row."""
import os

SCENES = ["trampoline", "drooping", "reentrant_corner", "drape"]
NAMES = {"trampoline": "Trampoline", "drooping": "Drooping", "reentrant_corner": "Re-entrant corner", "drape": "Drape"}
SOLVERS = ["tr", "rmtr L2", "lsnewton", "damped", "linearized"]
# RMTR paper §7.4.1 and Fig. 10 (1,083 dofs): the text gives no per-solver values, only the statement
PAPER = {"tr": "converges for every dt <= 1 s (all scenes)", "rmtr L2": "converges for every dt <= 1 s (all scenes)",
         "lsnewton": "needs smaller dt; worse on harder scenes", "damped": "needs smaller dt; worse on harder scenes",
         "linearized": "needs smaller dt; drape: about 10 million more steps than TR"}


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
         "Ours: the subdivision method at the paper's 1,083 dofs (1,035 on the re-entrant corner's graded cage), 5",
         "steps per probe, at most 2,000 iterations per step, dt from 1 s down by factors of 100, then bisections",
         "(bench/studies/dt_stability_large.json; the rmtr part run by dt_stability_large_rmtr.json into the same",
         "records).  \"≥ 1\" = converges at the cap the paper also uses; \"unfinished\" = the search had not reached",
         "its answer when the CPU budget ended (the next probe named).  The 400-dof column is the smaller study",
         "(results/dt_stability: 300 iterations per step).  The paper gives no per-solver values in its text, only",
         "the statement in the \"paper\" column (§7.4.1).\n",
         "| scene | solver | paper (Fig. 10, §7.4.1) | ours, 1,083 dofs: largest converging dt (s) | outcome at dt = 1 | probes | verdict | ours, ~400 dofs |",
         "|---|---|---|---|---|--:|---|---|"]
    counts = {"agrees": 0, "differs": 0, "not finished": 0}
    for sc in SCENES:
        for so in SOLVERS:
            b = big.get((sc, "rmtr", so))
            s = small.get((sc, "rmtr", so))
            if b is None:
                continue
            v = verdict(b[1], so)
            counts[v.split()[0] if not v.startswith("not") else "not finished"] += 1
            L.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
                NAMES[sc], so, PAPER[so], b[1], b[2], b[4], v, s[1] if s else "—"))
    others = [(k, v) for k, v in big.items() if k[1] != "rmtr" and not v[1].startswith("unfinished")]
    pend = sum(1 for k, v in big.items() if k[1] != "rmtr" and v[1].startswith("unfinished"))
    L.append("\nOf the %d subdivision rows: %d agree with the paper's statement, %d differ, %d not finished." % (
        sum(counts.values()), counts["agrees"], counts["differs"], counts["not finished"]))
    if others:
        L.append("The other methods at about 1,000 dofs (bhem 972, linear_fem 963 dofs), where finished: " + "; ".join(
            "%s %s/%s %s" % (NAMES.get(k[0], k[0]), k[1], k[2], v[1]) for k, v in sorted(others)) + ".")
    if pend:
        L.append("%d bhem / linear_fem searches are not finished or not run (the study's full plan; CPU budget)." % pend)
    L.append("Full per-probe tables and pictures: results/dt_stability_large/report.md.")
    return "\n".join(L) + "\n"


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
