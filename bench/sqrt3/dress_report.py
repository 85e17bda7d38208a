#!/usr/bin/env python3
"""bench/sqrt3/dress_report.py — the dress section of results/sqrt3_report.md
(issue 40; bench/sqrt3/report.py calls dress_section), from the summaries
results/sqrt3/runs/dress-*.json (+ .cpu, the process CPU seconds), the
per-step series results/sqrt3/series_dress*.csv (bench/sqrt3/dress_series.py)
and the pictures results/sqrt3/images/dress-*.png, all written by
bench/sqrt3/dress.sh.  Never re-runs.

    python3 bench/sqrt3/dress_report.py results/sqrt3     # the section alone
"""
import csv, json, math, os, sys

# the paper's dress (Bender & Deul, Sec. 7, Fig. 10)
PAPER = {"full": 66636, "adaptive": 37392, "cloth": 1.8, "collide": 8.7, "overall": 3.13, "share": 1.7}
MOMENTS = ((80, "the skirt fallen, the walk begun"), (230, "mid-stride"), (400, "the end"))


def load(d, tag):
    try:
        txt = open(os.path.join(d, "runs", tag + ".json")).read()
        return json.loads(txt[txt.index("{"):])
    except (OSError, ValueError):
        return None


def cpu(d, tag):
    try:
        return float(open(os.path.join(d, "runs", tag + ".cpu")).read().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def series(d, name):
    try:
        with open(os.path.join(d, name)) as f:
            return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    except (OSError, ValueError):
        return []


def floor(d, n):
    """the distance between the small full run and the same run with E_s
    perturbed by 2e-8 of itself (series_dress_floor.csv, dress.sh floor)
    over the first n steps: mean and largest RMS, and the series; None when
    not run"""
    rows = series(d, "series_dress_floor.csv")[:n]
    rms = [r["rms"] for r in rows if math.isfinite(r["rms"])]
    if not rms:
        return None
    return {"mean": sum(rms) / len(rms), "largest": max(rms), "rows": rows,
            "max": max(r["max"] for r in rows if math.isfinite(r["max"]))}


def contact_counts(d, csv_name):
    """the impulse counts of both records (dress_series.py --contact), or {}"""
    try:
        return json.load(open(os.path.join(d, csv_name.replace(".csv", "_contact.json"))))
    except (OSError, ValueError):
        return {}


def fmt(x, f="%.3g"):
    return "—" if x is None or (isinstance(x, float) and not math.isfinite(x)) else f % x


def parts(rows, who):
    """sums over the steps: cloth (the step without collision handling,
    adaptation, recording and checkpoints), collide, adapt, step (all but
    recording and checkpoints), and the mean triangles"""
    g = lambda r, c: r["%s_%s" % (c, who)]
    rec = sum(g(r, "seconds_record") + g(r, "seconds_checkpoint") for r in rows)
    step = sum(g(r, "seconds") for r in rows) - rec
    col = sum(g(r, "seconds_contact") for r in rows)
    ad = sum(g(r, "seconds_adapt") for r in rows)
    return {"cloth": step - col - ad, "collide": col, "adapt": ad, "step": step,
            "tri": sum(g(r, "triangles") for r in rows) / len(rows)}


def paper_rows(d, size, full_tag, ad_tag, csv_name, planned, limits, base):
    """the paper's figures beside ours for one size; [] when not run"""
    f, a = load(d, full_tag), load(d, ad_tag)
    rows = series(d, csv_name)
    if not rows:
        return [], None
    pf, pa = parts(rows, "full"), parts(rows, "adaptive")
    cf, ca = cpu(d, full_tag), cpu(d, ad_tag)
    rms = [r["rms"] for r in rows if math.isfinite(r["rms"])]
    mx = [r["max"] for r in rows if math.isfinite(r["max"])]
    n = len(rows)
    bound = "" if n >= planned else " (**bounded**: the first %d of %d steps, to t = %.3g s, from the runs' checkpoints)" % (
        n, planned, rows[-1]["t"])
    sp = lambda k: pf[k] / pa[k] if pa[k] > 0 else float("nan")
    out = []
    row = lambda q, p, o, r, diff: out.append("| %s | %s | %s | %s | %s | %s |" % (size, q, p, o, r, diff))
    row("full-resolution triangles", "66,636", "%.0f" % pf["tri"], "%.3f" % (pf["tri"] / PAPER["full"]),
        "our circle skirt, 6 generations on a %s-triangle base mesh%s" % ("{:,}".format(base), bound))
    row("adaptive triangles (mean over the steps)", "37,392", "%.0f" % pa["tri"], "%.3f" % (pa["tri"] / PAPER["adaptive"]),
        "limits %s (paper: 'low limits', values not given)" % limits)
    red = pf["tri"] / pa["tri"]
    row("mesh reduction (full / adaptive)", "1.78 x", "%.2f x" % red, "%.2f" % (red / 1.78), "")
    row("**cloth speed-up** (step without collision handling)", "1.8 x", "%.2f x" % sp("cloth"),
        "%.2f" % (sp("cloth") / PAPER["cloth"]), "CHOLMOD direct solve (paper: CG); wall clock on a shared machine")
    row("**collision speed-up** (event `collide`)", "8.7 x", "%.2f x" % sp("collide"),
        "%.2f" % (sp("collide") / PAPER["collide"]),
        "same pipeline (Bridson et al.: proximity, at most 5 CCD passes, rigid impact zones); analytic body, "
        "self-contact on")
    row("**overall speed-up** (a step)", "3.13 x", "%.2f x" % sp("step"), "%.2f" % (sp("step") / PAPER["overall"]),
        "process CPU time: %s" % ("%.2f x (%.0f s against %.0f s)" % (cf / ca, cf, ca) if cf and ca else "not recorded"))
    share = 100 * pa["adapt"] / pa["step"] if pa["step"] > 0 else float("nan")
    row("adaptation's share of the adaptive step", "1.7 %", "%.1f %%" % share, "%.2f" % (share / PAPER["share"]),
        "event `adapt` (curvature, sqrt3 operations, model rebuild; the symbolic re-analysis is in the cloth part)")
    row("**accuracy price**: RMS distance to the full run / 1.2 m, mean over time (largest)", "not measured",
        "%s (%s)" % (fmt(sum(rms) / len(rms)) if rms else "—", fmt(max(rms)) if rms else "—"), "—",
        "11 x 11 material grid, every step")
    row("max distance to the full run / 1.2 m, largest over time", "not measured", fmt(max(mx)) if mx else "—", "—",
        "")
    fl = floor(d, n) if "16 x 77" not in size else None
    if fl:
        row("**accuracy floor**: RMS distance between two full runs, E_s 2e-8 apart, mean over time (largest)",
            "not measured", "%s (%s)" % (fmt(fl["mean"]), fmt(fl["largest"])), "—",
            "the price above is %.2f x this floor (mean), %.2f x (largest); `dress.sh floor`" % (
                (sum(rms) / len(rms)) / fl["mean"], max(rms) / fl["largest"]))
    info = {"f": f, "a": a, "pf": pf, "pa": pa, "rows": rows, "bound": bound,
            "counts": contact_counts(d, csv_name)}
    return out, info


SIZES = (("small (base 6 x 28)", "dress-full", "dress-adaptive", "series_dress.csv", "5, 50 /m (the scene's)"),
         ("small, default limits", "dress-full", "dress-adaptive-default", "series_dress_default.csv",
          "2, 20 /m (the method's defaults)"),
         ("paper's size (base 16 x 77)", "dress-large-full", "dress-large-adaptive", "series_dress_large.csv",
          "5, 50 /m (the scene's)"))


def summary_rows(d):
    """the paper table's Fig. 10 rows (bench/sqrt3/report.py): the largest
    size both of whose runs covered the whole 2 s, else the small one"""
    pick = None
    for size, ft, at, csvn, lim in SIZES:
        if "default" in size:
            continue
        rows = series(d, csvn)
        if rows and len(rows) >= 400:
            pick = (size, ft, at, rows)
    if not pick:
        return []
    size, ft, at, rows = pick
    pf, pa = parts(rows, "full"), parts(rows, "adaptive")
    cf, ca = cpu(d, ft), cpu(d, at)
    rms = [r["rms"] for r in rows if math.isfinite(r["rms"])]
    fl = floor(d, len(rows)) if "small" in size else None
    price = "%s (%s)%s" % (fmt(sum(rms) / len(rms)), fmt(max(rms)),
                           "; floor %s (%s)" % (fmt(fl["mean"]), fmt(fl["largest"])) if fl else "")
    diff = ("%s: our circle skirt on a walking body of capsules, %.0f triangles full (paper 66,636), impulses with "
            "self-contact, CHOLMOD; wall clock on a shared machine" % (size, pf["tri"]))
    csv_name = [c for sz, _, _, c, _ in SIZES if sz == size][0]
    cc = contact_counts(d, csv_name)
    un = [(nm, cc[nm]) for nm in ("full", "adaptive") if (cc.get(nm) or {}).get("unresolved_steps")]
    if un:
        diff += "; **not converged: collisions left unresolved** (contact_unresolved) in %s counted steps" % " and ".join(
            "%d of %d (%s)" % (c["unresolved_steps"], c.get("counted_steps") or c["steps"], nm) for nm, c in un)
    sp = lambda k: pf[k] / pa[k] if pa[k] > 0 else float("nan")
    out = ["| Fig. 10 dress | mesh reduction (full / adaptive triangles) | 1.78 x | %.2f x | %.2f | %s | %s |" % (
               pf["tri"] / pa["tri"], pf["tri"] / pa["tri"] / 1.78, diff, price)]
    for key, name, paper in (("cloth", "cloth speed-up", "cloth"), ("collide", "collision speed-up", "collide"),
                             ("step", "overall speed-up", "overall")):
        extra = " (process CPU time %.2f x)" % (cf / ca) if key == "step" and cf and ca else ""
        out.append("| Fig. 10 dress | %s | %s x | %.2f x%s | %.2f | as above | — |" % (
            name, PAPER[paper], sp(key), extra, sp(key) / PAPER[paper]))
    share = 100 * pa["adapt"] / pa["step"] if pa["step"] > 0 else float("nan")
    out.append("| Fig. 10 dress | adaptation share | 1.7 %% | %.1f %% | %.2f | as above | — |" % (
        share, share / PAPER["share"]))
    return out


def collision_detail(size, info):
    """the impulse counts of both runs, from their records (final or
    checkpoint: dress_series.py --contact), else from the summaries"""
    out = []
    for name, key, summ in (("full", "full", info["f"]), ("adaptive", "adaptive", info["a"])):
        c = info["counts"].get(key)
        status = judged_status(summ, c) if summ else "stopped part-way (checkpoint)"
        if not c and summ:
            c = dict(summ.get("contact") or {}, steps=summ["steps"])
        if not c or not c.get("steps"):
            out.append("| %s | %s | %s | | | | | | | | | |" % (size, name, status))
            continue
        s = c.get("counted_steps") or c["steps"]
        steps = "%d" % c["steps"] if s == c["steps"] else "%d (counts: the last %d)" % (c["steps"], s)
        out.append("| %s | %s | %s | %s | %.2f | %s | %s | %s | %s | %s | %s | %s |" % (
            size, name, status, steps, c.get("ccd_iterations", 0) / s, "{:,}".format(c.get("impact_zones", 0)),
            "{:,}".format(c.get("ccd_tests", 0)), "{:,}".format(c.get("ccd_hits", 0)),
            "{:,}".format(c.get("proximity_impulses", 0)), c.get("unresolved_steps", "—"),
            "{:,.0f}".format(c["broad_queries"] / s) if c.get("broad_queries") else "—",
            "%.1f" % (c["broad_candidates"] / c["broad_queries"]) if c.get("broad_queries") else "—"))
    return out


def judged_status(summ, counts):
    """The run's status under today's rule: a run whose impulse response left
    collisions in more than run.contact_unresolved_max (default 0) steps is
    not converged (reason contact_unresolved, since 2026-12-06).  A record
    made before the rule says `converged`; the report judges it by its count."""
    un = (counts or summ.get("contact") or {}).get("unresolved_steps") or 0
    if summ["status"] == "converged" and un > 0:
        return "**not converged** (contact_unresolved: judged here; the record predates the rule and says %s)" % (
            summ["reason"])
    return "%s (%s)" % (summ["status"], summ["reason"])


def others(d):
    out = []
    for tag, what in (("dress-lf-impulse", "linear_fem, impulse, linearized"),
                      ("dress-lf-impulse-lsnewton", "linear_fem, impulse, lsnewton"),
                      ("dress-lf-barrier", "linear_fem, barrier, lsnewton"),
                      ("dress-bhem-barrier", "bhem, barrier, lsnewton"),
                      ("dress-rmtr-barrier", "rmtr, barrier, lsnewton")):
        r = load(d, tag)
        if not r:
            out.append("| %s | not run | | | | |" % what)
            continue
        c = r.get("contact") or {}
        out.append("| %s | %s (%s) | %d of %d | %d | %.1f | %s |" % (
            what, r["status"], r["reason"], r["steps"], r["steps_planned"], r["dofs"], r["seconds"]["total"],
            "inside %s, min distance %s m" % (c.get("inside"), fmt(c.get("min_distance"))) if "inside" in c
            else "unresolved steps %s" % c.get("unresolved_steps", "—")))
    for m in ("bhem", "rmtr"):
        try:
            txt = open(os.path.join(d, "runs", "dress-%s-impulse.refused" % m)).read().strip()
        except OSError:
            txt = ""
        out.append("| %s, impulse (the bundled scene) | refused before any work: %s | | | | |" % (
            m, txt.replace("|", "/").replace("\n", " ") if txt else "not run"))
    return out


def pictures(d):
    imgs = os.path.join(d, "images")
    rel = os.path.join(os.path.basename(os.path.normpath(d)), "images")
    runs = (("dress-full", "full resolution"), ("dress-adaptive", "adaptive (5, 50 /m)"),
            ("dress-large-full", "paper's size, full resolution"),
            ("dress-large-adaptive", "paper's size, adaptive (5, 50 /m)"))
    steps = set()
    for f in os.listdir(imgs) if os.path.isdir(imgs) else []:
        for tag, _ in runs:
            if f.startswith(tag + "-") and f.endswith(".png") and f[len(tag) + 1:-4].isdigit():
                steps.add(int(f[len(tag) + 1:-4]))
    if not steps:
        return []
    what = dict(MOMENTS)
    have = sorted(steps)
    out = ["", "| run | " + " | ".join("step %d (t = %.3g s%s)" % (s, s * 0.005, ": " + what[s] if s in what else "")
                                    for s in have) + " |", "|---|" + "---|" * len(have)]
    for tag, name in runs:
        if not any(os.path.exists(os.path.join(imgs, "%s-%d.png" % (tag, s))) for s in have):
            continue
        cells = []
        for s in have:
            p = os.path.join(imgs, "%s-%d.png" % (tag, s))
            cells.append("![%s, step %d](%s/%s-%d.png)" % (name, s, rel, tag, s) if os.path.exists(p) else "—")
        out.append("| %s | %s |" % (name, " | ".join(cells)))
    return out


def dress_section(d):
    out = ["", "## The dress on a walking body (sqrt3 paper Sec. 7, Fig. 10; issue 40)", "",
           "Generated by `bench/sqrt3/dress_report.py` from `results/sqrt3/runs/dress-*.json` (and `.cpu`: the "
           "runs' process CPU seconds), `results/sqrt3/series_dress*.csv` (every step of both runs, read from the "
           "records by `bench/sqrt3/dress_series.py`; the records are not committed) and the pictures; runs: "
           "`bash bench/sqrt3/dress.sh` (small), `… large` (the paper's size, in pieces), `… others`.  The scene, "
           "the body and every choice: [docs/sqrt3_dress.md](../docs/sqrt3_dress.md).", "",
           "Scene `bench/scenes/dress.json`: a calf-length circle skirt (flat 330° annulus sector, waist radius "
           "0.125 m, length 0.7 m, the open back seam where a zipper would be) held along the waist, falling from "
           "horizontal onto a body of 12 analytic obstacles (capsules and a sphere: torso, shoulders, head, hips, "
           "thighs, shins, upper arms, forearms) that walks in place from 0.3 s to 2 s (legs ±30°, arms ±15° "
           "about hip and shoulder joints, schedules); E = E_s = 5000 N/m (the paper), ν = 0.33, ρ = 0.1 kg/m², "
           "dt = 5 ms, 400 steps; `contact.model` impulse (the paper's Sec. 6 pipeline) with self-contact, "
           "thickness 1 mm, friction 0.3.  adaptive_sqrt3, `linearized` (Eq. 21), 6 generations, adaptation "
           "every 5 steps, refinement limits (Eq. 23) l_base 5, l_gmax 50 /m (the scene's) and the method's defaults "
           "2, 20 /m.  **Cloth** = a step's seconds without `collide`, `adapt`, recording and "
           "checkpoints; **collision** = event `collide` (the impulse response: proximity, CCD passes, impact "
           "zones, spatial hashing); **overall** = the step without recording and checkpoints.  Seconds are wall "
           "clock on a shared 2-core machine (the runs of 2026-12-06: two to four single-threaded jobs at once, "
           "load average 2-4), so wall-clock ratios are indicative; the process CPU-time ratio, which the load "
           "does not inflate, is given beside the overall one.", "",
           "| size | quantity | paper | ours | ours / paper | setting differences |", "|---|---|---|---|---|---|"]
    detail, notrun = [], []
    for size, ft, at, csvn, lim in SIZES:
        base = 2464 if "16 x 77" in size else 336   # 2 triangles per base cell
        rows, info = paper_rows(d, size, ft, at, csvn, 400, lim, base)
        if not rows:
            notrun.append(size)
            continue
        out += rows
        detail.append((size, info))
    if notrun:
        out += ["", "Not run (no summaries or series): %s." % ", ".join(notrun)]
    for size, info in detail:
        rows = info["rows"]
        if info["bound"] and rows[-1]["t"] < 0.3:
            out += ["", "**%s is bounded** to its first %d steps (t <= %.3g s): the skirt is still falling, nearly flat "
                    "(the walk starts at 0.3 s), and the adaptive mesh has hardly left its base mesh (%.0f triangles on "
                    "average against %.0f), so these rows compare a coarse flat sheet with the full one; they are not "
                    "comparable with the paper's averages over a whole walk." % (
                        size, len(rows), rows[-1]["t"], info["pa"]["tri"], info["pf"]["tri"])]
        elif not info["bound"]:
            late = [r for r in rows if r["t"] > 0.3]
            if late:
                fr = sum(r["triangles_adaptive"] / r["triangles_full"] for r in late) / len(late)
                out += ["", "**%s**: during the walk (t > 0.3 s) the adaptive mesh holds %.0f %% of the full "
                        "resolution's triangles on average (the folded skirt's mean curvature is above the limits "
                        "over most of it), and collision handling costs the adaptive run %.2f x the full run's "
                        "time." % (size, 100 * fr, info["pa"]["collide"] / info["pf"]["collide"]
                                   if info["pf"]["collide"] > 0 else float("nan"))]
                cf_, ca_ = info["counts"].get("full") or {}, info["counts"].get("adaptive") or {}
                if cf_.get("broad_queries") and ca_.get("broad_queries"):
                    out[-1] += ("  The broad phase made %s hash queries in the full run and %s in the adaptive one "
                                "(%.2f x), with %.1f and %.1f candidates a query: a query costs the same on both "
                                "meshes, and the adaptive run's %.2f CCD passes a step (full: %.2f) and %s rigid "
                                "impact zones (full: %s), each zone pass a sweep over every primitive, %s its "
                                "smaller mesh." % (
                                    "{:,}".format(cf_["broad_queries"]), "{:,}".format(ca_["broad_queries"]),
                                    ca_["broad_queries"] / cf_["broad_queries"],
                                    cf_["broad_candidates"] / cf_["broad_queries"],
                                    ca_["broad_candidates"] / ca_["broad_queries"],
                                    ca_.get("ccd_iterations", 0) / ca_["steps"], cf_.get("ccd_iterations", 0) / cf_["steps"],
                                    "{:,}".format(ca_.get("impact_zones", 0)), "{:,}".format(cf_.get("impact_zones", 0)),
                                    "more than make up for" if ca_["broad_queries"] > 1.1 * cf_["broad_queries"]
                                    else "make up for"))
                un = [(nm, c) for nm, c in (("full", cf_), ("adaptive", ca_)) if c.get("unresolved_steps")]
                if un:
                    out[-1] += ("  **Collisions left unresolved**: %s of the counted steps ended with a collision "
                                "that the response could not remove (five CCD passes, then up to 100 impact-zone "
                                "passes); the cloth crosses itself or the body there.  Under the rule of 2026-12-06 "
                                "(run.contact_unresolved_max = 0: a run that leaves collisions is not converged) "
                                "these runs are **not converged** (contact_unresolved); their records, made "
                                "before the rule, say `converged`." % " and ".join(
                                    "%d of %d (%s)" % (c["unresolved_steps"], c.get("counted_steps") or c["steps"], nm)
                                    for nm, c in un))
                if info["pa"]["step"] > info["pf"]["step"]:
                    out[-1] += ("  **The adaptive run is slower than the full one** here (%.2f x its time a step): its "
                                "mesh is only %.2f x smaller on average and its collision handling costs %.2f x the "
                                "full run's." % (info["pa"]["step"] / info["pf"]["step"],
                                                 info["pf"]["tri"] / info["pa"]["tri"],
                                                 info["pa"]["collide"] / info["pf"]["collide"]))
    if detail:
        out += ["", "**Collision handling** (the paper explains its 8.7 x by more CCD passes and impact zones at full "
                "resolution): per run, over the steps its record holds (a run stopped part-way: up to its last "
                "checkpoint; a run made in pieces by a build before 2026-12-06 counted the steps after its last "
                "resume only, and the table says how many), CCD passes per step (at most 5, then impact zones), impact zones formed, CCD "
                "tests after culling, collisions resolved by impulses, proximity impulses, steps left with a collision, "
                "and the broad phase's spatial-hash queries per step with the primitives each returned (records of "
                "builds since 2026-12-06).",
                "", "| size | run | status | steps | CCD passes / step | impact zones | CCD tests | CCD hits | "
                "proximity impulses | unresolved steps | hash queries / step | candidates / query |",
                "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for size, info in detail:
            if "default" not in size:
                out += collision_detail(size, info)
        rows = detail[0][1]["rows"]
        fl = floor(d, len(rows))
        if fl:
            rms = [r["rms"] for r in rows if math.isfinite(r["rms"])]
            cur = [r.get("rms_adaptive") for r in series(d, "series_curtain_paper.csv")]
            cur = [x for x in cur if x is not None and math.isfinite(x)]
            curtain = sum(cur) / len(cur) if cur else None   # the curtain's price at the paper's size
            out += ["", "**The accuracy floor** (`bash bench/sqrt3/dress.sh … floor`): the small full-resolution run "
                    "made again with E_s = 5000.0001 instead of 5000 N/m (2e-8 of itself, far below any modelling "
                    "error) drifts from the unperturbed run by an RMS distance of %s of the diameter on average over "
                    "the 2 s (largest %s; max over the grid %s), against the adaptive run's %s (largest %s).  The two "
                    "full runs agree to round-off while the skirt falls and separate within the first stride (t = "
                    "0.3-0.5 s, the column *floor* below): the walking legs' contacts amplify any difference, and "
                    "the same happens to the adaptive run.  So %.0f %% of the accuracy price measured here (mean "
                    "over time) is this scene's sensitivity, which any change of mesh, solver or machine would "
                    "show, and the adaptivity's own price is the excess above it (%.2f x the floor).  The curtain "
                    "(sections above) does not amplify differences this way: its price at the paper's size, "
                    "%s, is %s times smaller; the cloth over the sphere's was not measured against a floor." % (
                        fmt(fl["mean"]), fmt(fl["largest"]), fmt(fl["max"]), fmt(sum(rms) / len(rms)),
                        fmt(max(rms)), 100 * fl["mean"] / (sum(rms) / len(rms)), (sum(rms) / len(rms)) / fl["mean"],
                        fmt(curtain), "%.0f" % ((sum(rms) / len(rms)) / curtain) if curtain else "—")]
        out += ["", "**Over time** (%s): triangles and the accuracy price (distance to the full run / 1.2 m)%s." % (
                    detail[0][0], ", beside the floor (distance between the two full runs)" if fl else ""),
                "", "| t (s) | triangles adaptive | triangles full | RMS distance | max distance |%s" % (
                    " floor: RMS distance |" if fl else ""), "|---|---|---|---|---|%s" % ("---|" if fl else "")]
        for r in rows[49::50] + ([rows[-1]] if len(rows) % 50 else []):
            k = int(r["step"]) - 1
            out.append("| %.2f | %.0f | %.0f | %s | %s |%s" % (
                r["t"], r["triangles_adaptive"], r["triangles_full"], fmt(r["rms"]), fmt(r["max"]),
                " %s |" % fmt(fl["rows"][k]["rms"]) if fl and k < len(fl["rows"]) else ""))
    pics = pictures(d)
    if pics:
        out += ["", "**Pictures** (`shellbench render --step K`, the body at its pose of that step; "
                "drawn from the records, or from the checkpoint of a run stopped part-way (its picture says "
                "CHECKPOINT), by `bench/sqrt3/dress.sh`):"] + pics
    planned = [r["steps_planned"] for r in (load(d, t) for t in ("dress-lf-impulse", "dress-lf-barrier",
                                                                 "dress-bhem-barrier", "dress-rmtr-barrier")) if r]
    n = planned[0] if planned else 0
    out += ["", "**Other methods** on the same scene (`bash bench/sqrt3/dress.sh … others`: the first %d steps, "
            "%.3g s; " % (n, 0.005 * n) +
            "the barrier variant differs only in `contact.model`; each method at its bundled resolution, the scene's "
            "`methods` section):", "", "| method, contact, solver | status | steps | dofs | seconds | contact |",
            "|---|---|---|---|---|---|"] + others(d)
    return out


if __name__ == "__main__":
    print("\n".join(dress_section(sys.argv[1] if len(sys.argv) > 1 else "results/sqrt3")))
