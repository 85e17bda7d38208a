"""bench/rmtr/report_fig9.py — issue 43: which energy term sets each end of the
spectrum of H in Fig. 9, how each end grows with the dofs, and what the
paper's h^-4 and its offset would require.  Read by bench/rmtr/report.py
from results/rmtr/cond_split.csv (bash bench/rmtr/cond_split.sh) and
results/rmtr/cond_parts.csv (bash bench/rmtr/cond.sh); never re-runs.

Every number printed here comes from those two files; the sentences around
them are chosen by comparisons of those numbers, not written for them."""
import math
import os

# Table 1 of the RMTR paper, as the scene uses it (docs/rmtr.md, scene audit):
# k_1 in Pa through the thickness tau (core/shell/sb_material.c)
K1, TAU = 4.79e6, 0.66e-3


def fit(pts):
    """p in y ~ h^-p by least squares on log y against log h (pts: (h, y), y > 0); None under 2 points"""
    pts = [(h, y) for h, y in pts if h and y and y > 0]
    if len(pts) < 2:
        return None
    xs = [math.log(h) for h, _ in pts]
    ys = [math.log(y) for _, y in pts]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return -sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else None


def read(path):
    """(rows, split): rows[(setting, dofs)][variant] = CSV row (dense preferred); split[(setting, dofs)][which]"""
    rows, split, key = {}, {}, None
    if not os.path.exists(path):
        return rows, split
    lines = open(path).read().splitlines()
    hdr = lines[0].split(",")
    for ln in lines[1:]:
        if ln.startswith("# split,"):
            f = ln.split(",")[1:]
            if key:
                split.setdefault(key, {})[f[0]] = dict(zip(
                    ("lam", "mass", "mem", "bend", "pen", "bend_check", "relres", "ghost"), [float(x) for x in f[1:]]))
            continue
        if ln.startswith("#"):
            continue
        r = dict(zip(hdr, ln.split(",")))
        key = (r["setting"], int(r["dofs"]))
        d = rows.setdefault(key, {})
        if r["variant"] not in d or r["how"] == "dense":
            d[r["variant"]] = r
    return rows, split


def g(r, k):
    v = r.get(k, "nan") if r else "nan"
    try:
        x = float(v)
    except ValueError:
        return None
    return None if math.isnan(x) else x


def pct(part, lam):
    return "%.0f" % (100.0 * part / lam) if lam else "—"


def shares(s):
    """mass / membrane / bending / penalty shares of one eigenvalue in %, and the ghost share"""
    if not s:
        return "—", "—"
    lam = s["lam"]
    return " / ".join(pct(s[k], lam) for k in ("mass", "mem", "bend", "pen")), "%.0f" % (100 * s["ghost"])


def dominant(s):
    names = {"mass": "the mass", "mem": "the membrane", "bend": "the bending", "pen": "the penalty"}
    k = max(("mass", "mem", "bend", "pen"), key=lambda k: s[k])
    return names[k], 100.0 * s[k] / s["lam"]


def sci(v):
    return "—" if v is None else "%.2g" % v


def section(results, fig9):
    """the Markdown section, or '' when cond_split.csv is missing"""
    rows, split = read(os.path.join(results, "cond_split.csv"))
    if not rows:
        return ""
    parts, _ = read(os.path.join(results, "cond_parts.csv"))
    out = []
    p = out.append
    p("\n### Fig. 9: which energy term sets lambda_min and lambda_max, and how each grows (issue 43)\n")
    p("For a unit eigenvector v of H its eigenvalue is the sum of the terms' Rayleigh quotients, lambda =")
    p("v'(M/dt^2)v + v'K_mem v + v'K_bend v + v'K_pen v; the table gives each term's share in %.  K_el is split")
    p("into membrane and bending by its thickness dependence at the same x (K_el(tau) = tau K_1 + tau^3 K_3 +")
    p("O(tau^5), the section energy integrated through the thickness; K_bend from tau and tau/2, checked against")
    p("tau and tau/4: `bench_cond parts ... split`, bench/bench_cond.c).  Eigenvectors: LAPACK to 1,083 dofs,")
    p("Lanczos Ritz vectors above (relative residual in the last column).  \"ghost\": share of |v|^2 on the")
    p("control points outside the cloth.  \"lowest cloth mode\": the smallest eigenvalue whose eigenvector has")
    p("less than half of |v|^2 on ghost points (dense sizes only).  Two states of the first step (dt = 1 s):")
    p("**converged** (what Fig. 9 (left) above measures) and **initial** (the flat, unstretched cloth the step")
    p("starts from: the paper does not say at which x it takes H).  `bash bench/rmtr/cond_split.sh`, records in")
    p("`results/rmtr/cond_split.csv`.\n")
    p("| state | dofs | lambda_min | its shares: mass / membrane / bending / penalty | ghost | lambda_max | its shares | lowest cloth mode (index): lambda, shares | cond_2(H) | rel. residual min / max |")
    p("|---|--:|--:|---|--:|--:|---|---|--:|---|")
    worst_check = 0.0
    for st in ("converged", "initial"):
        for d in sorted(dofs for s, dofs in split if s == st):
            sp = split[(st, d)]
            H = rows.get((st, d), {}).get("H")
            mn, mx = sp.get("min"), sp.get("max")
            sm = [(k, v) for k, v in sp.items() if k.startswith("smooth_")]
            for s in (mn, mx):
                if s and abs(s["bend"]) > 1e-3 * abs(s["lam"]):
                    worst_check = max(worst_check, abs(s["bend"] - s["bend_check"]) / abs(s["bend"]))
            smc = "%s (%s): %.3g, %s" % ("lowest", sm[0][0].split("_")[1], sm[0][1]["lam"], shares(sm[0][1])[0]) if sm else "—"
            rr = "%s / %s" % (H["relres_min"], H["relres_max"]) if H and H["how"] == "lanczos" else "dense"
            p("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                st, "{:,}".format(d), sci(mn["lam"]) if mn else "—", shares(mn)[0], shares(mn)[1],
                "%.4g" % mx["lam"] if mx else "—", shares(mx)[0], smc, sci(g(H, "cond2")), rr))
    p("\nThe two bending estimates (tau/2 and tau/4) of the extreme eigenvalues' bending parts agree to %.1g"
      " (relative): the O(tau^5) rest is negligible and the split is exact to that." % worst_check)

    # growth of each end and of each term's largest eigenvalue
    sizes = sorted(d for s, d in rows if s == "converged")
    h = {d: float(rows[("converged", d)]["H"]["h"]) for d in sizes}
    col = lambda st, d, v, k: g(rows.get((st, d), {}).get(v), k)
    lmin = {d: col("converged", d, "H", "lambda_min") for d in sizes}
    lmax = {d: col("converged", d, "H", "lambda_max") for d in sizes}
    kmem = {d: col("converged", d, "K_mem", "lambda_max") for d in sizes}
    kbend = {d: col("converged", d, "K_bend", "lambda_max") for d in sizes}
    pdofs = sorted(d for s, d in parts if s == "paper")
    hp = {d: float(parts[("paper", d)]["H"]["h"]) for d in pdofs if "H" in parts[("paper", d)]}
    kpen = {d: g(parts[("paper", d)].get("K_pen"), "lambda_max") for d in pdofs}
    condp = {d: g(parts[("paper", d)].get("H"), "cond2") for d in pdofs}
    lminp = {d: g(parts[("paper", d)].get("H"), "lambda_min") for d in pdofs}
    lmaxp = {d: g(parts[("paper", d)].get("H"), "lambda_max") for d in pdofs}
    allh = dict(hp)
    allh.update(h)
    p("\nHow each end grows (converged state).  p: the exponent of y ~ h^-p fitted by least squares over the")
    p("sizes given (h halves per row).  lambda_max(K_pen) and the 51,483-dof H are from cond_parts.csv.\n")
    p("| dofs | h | lambda_max(H) | lambda_min(H) | cond_2(H) | lambda_max(K_mem) | lambda_max(K_bend) | lambda_max(K_pen) | bending / membrane (largest eigenvalues) |")
    p("|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
    for d in sorted(set(pdofs) | set(sizes)):
        a, b = kbend.get(d), kmem.get(d)
        p("| %s | 1/%d | %s | %s | %s | %s | %s | %s | %s |" % (
            "{:,}".format(d), round(1 / allh[d]), sci(lmaxp.get(d) or lmax.get(d)), sci(lminp.get(d) or lmin.get(d)),
            sci(condp.get(d)), sci(b), sci(a), sci(kpen.get(d)), sci(a / b) if a and b else "—"))
    fits = {}
    def pfit(name, ys, lo=0):
        fits[name] = (fit([(allh[d], y) for d, y in ys.items() if d >= lo]),
                      min([d for d in ys if d >= lo and ys[d]] or [0]), max([d for d in ys if ys[d]] or [0]))
    pfit("cond(H)", condp)
    pfit("cond(H), from 1,083 dofs", condp, 1083)
    pfit("lambda_max(H)", lmaxp)
    pfit("lambda_max(H), from 1,083 dofs", lmaxp, 1083)
    pfit("lambda_min(H)", lminp)
    pfit("lambda_max(K_mem)", kmem)
    pfit("lambda_max(K_bend)", kbend)
    pfit("lambda_max(K_pen)", kpen)
    pfit("paper's Fig. 9", {d: v for d, v in fig9.items() if d in allh})
    p("\n| quantity | fitted p (y ~ h^-p) | over dofs |\n|---|--:|---|")
    for k, (v, a, b) in fits.items():
        p("| %s | %s | %s-%s |" % (k, "%.2f" % v if v is not None else "—", "{:,}".format(a), "{:,}".format(b)))

    # what the paper's numbers would need
    p("\nWhat the paper's numbers would require.  Its Fig. 9 gives cond only.  If its lambda_max were ours (the same")
    p("penalty beta = h^-5 and Table 1 material), its lambda_min would be lambda_max(ours) / cond(paper):\n")
    p("| dofs | paper cond | implied paper lambda_min | ours, converged: lambda_min | ours, initial (flat) state: lambda_min | paper / ours (converged) |")
    p("|--:|--:|--:|--:|--:|--:|")
    for d in pdofs:
        if d not in fig9 or not lmaxp.get(d):
            continue
        ini = col("initial", d, "H", "lambda_min")
        p("| %s | %s | %s | %s | %s | %.0f |" % ("{:,}".format(d), sci(fig9[d]), sci(lmaxp[d] / fig9[d]),
                                                sci(lminp.get(d)), sci(ini), fig9[d] / condp[d] if condp.get(d) else 0))
    # the verdict, from the numbers
    mn147, mnbig = split.get(("converged", min(sizes)), {}).get("min"), None
    big = max(d for s, d in split if s == "converged" and "min" in split[(s, d)])
    mnbig = split[("converged", big)]["min"]
    mxs = [(d, split[("converged", d)].get("max")) for d in sizes if split.get(("converged", d), {}).get("max")]
    pen_from = min((d for d, s in mxs if dominant(s)[0] == "the penalty"), default=None)
    ratio_bm = {d: kbend[d] / kmem[d] for d in sizes if kbend.get(d) and kmem.get(d)}
    q = fit([(h[d], r) for d, r in ratio_bm.items()])
    dlast = max(ratio_bm) if ratio_bm else None
    p("\n**Reading.**")
    if pen_from:
        dn, sh = dominant(dict(mxs)[pen_from])
        p("* lambda_max is the penalty from %s dofs on (%.1f %% of the Rayleigh quotient there) and grows with p = %.2f"
          " (from 1,083 dofs), the h^-(sigma-1) = h^-4 of beta = h^-5 times a boundary mass matrix of size h: the" %
          ("{:,}".format(pen_from), sh, fits["lambda_max(H), from 1,083 dofs"][0]))
        p("  paper's \"h^-4\" is there, from the penalty, not from the fourth-order shell.  Below, the membrane sets it.")
    if dlast and q is not None:
        hx = allh[dlast] * (ratio_bm[dlast]) ** (1.0 / q) if q > 0 else None
        p("* The bending stiffness's largest eigenvalue grows with p = %.2f (the h^-2 of a fourth-order operator in"
          " unscaled control-point coordinates), the membrane's with p = %.2f; at %s dofs bending is %.2g of the"
          " membrane.  With k_1 = %.3g Pa and tau = %.2g mm (Table 1, as the paper states them) D / (k_1 tau) = tau^2/12"
          " = %.2g m^2: bending would reach the membrane's largest eigenvalue only near h = %s m, i.e. about %s"
          " elements per side.  A bending-dominated lambda_max ~ h^-4 (relative to a fixed lambda_min) cannot occur"
          " at the paper's sizes with this material." % (
              fits["lambda_max(K_bend)"][0], fits["lambda_max(K_mem)"][0], "{:,}".format(dlast), ratio_bm[dlast],
              K1, TAU * 1e3, TAU ** 2 / 12, "%.1g" % hx if hx else "—", "{:,.0f}".format(1 / hx) if hx else "—"))
    if mn147 and mnbig:
        a, sa = dominant(mn147)
        b, sb = dominant(mnbig)
        sm = [(d, [v for k, v in split[("converged", d)].items() if k.startswith("smooth_")]) for d in sizes]
        rs = [v[0]["lam"] / split[("converged", d)]["min"]["lam"] for d, v in sm if v and "min" in split[("converged", d)]]
        p("* lambda_min is a mode of the ghost control points (%.0f-%.0f %% of |v|^2 on them) set by %s (%.0f %%) at"
          " %s dofs and by %s (%.0f %%) at %s dofs; its bending share rises from %.0f %% to %.0f %% and lambda_min"
          " rises with refinement (p = %.2f over all sizes): the bending stiffness of that local mode grows as the"
          " elements shrink.%s  So cond grows like lambda_max / lambda_min: p = %.2f over all sizes and %.2f"
          " from 1,083 dofs, against the paper's %.2f." % (
              100 * min(mn147["ghost"], mnbig["ghost"]), 100 * max(mn147["ghost"], mnbig["ghost"]), a, sa,
              "{:,}".format(min(sizes)), b, sb, "{:,}".format(big), 100 * mn147["bend"] / mn147["lam"],
              100 * mnbig["bend"] / mnbig["lam"], fits["lambda_min(H)"][0],
              ("  The lowest mode of the cloth itself lies %.0f-%.0fx higher (dense sizes)." % (min(rs), max(rs)))
              if rs else "", fits["cond(H)"][0], fits["cond(H), from 1,083 dofs"][0], fits["paper's Fig. 9"][0]))
    ini = [(d, split[("initial", d)].get("min")) for d in sizes if split.get(("initial", d), {}).get("min")]
    if ini:
        c = [(d, col("initial", d, "H", "cond2")) for d, _ in ini]
        pi = fit([(h[d], v) for d, v in c])
        pi2 = fit([(h[d], v) for d, v in c if d >= 1083])
        smooth = [d for d, s in ini if s["ghost"] < 0.5]
        p("* At the flat initial state (no tension yet) the out-of-plane stiffness is bending and mass only:"
          " lambda_min is %s (%s dofs), a bending mode of the ghost points at the coarse sizes%s; cond is %s at %s"
          " dofs (paper / ours: %s), fitted p = %.2f over all sizes and %.2f from 1,083 dofs against the paper's"
          " %.2f.  Neither state gives the paper's offset and growth together." % (
              ", ".join(sci(s_["lam"]) for _, s_ in ini), ", ".join("{:,}".format(d) for d, _ in ini),
              (" and from %s dofs on a mass-dominated mode of the cloth (%.0f %% mass), which falls like the"
               " mass matrix" % ("{:,}".format(min(smooth)), 100 * split[("initial", min(smooth))]["min"]["mass"] /
                                 split[("initial", min(smooth))]["min"]["lam"])) if smooth else "",
              ", ".join(sci(v) for _, v in c), ", ".join("{:,}".format(d) for d, _ in c),
              ", ".join("%.2g" % (fig9[d] / v) if d in fig9 and v else "—" for d, v in c), pi or 0, pi2 or 0,
              fits["paper's Fig. 9"][0]))
    fac = [fig9[d] / condp[d] for d in pdofs if d in fig9 and condp.get(d)]
    if fac:
        p("* So the factor %.0f-%.0f is in lambda_min: with our lambda_max, the paper's lambda_min would have to be"
          " that much smaller than our smallest eigenvalue at the converged state (table above).  Which mode sets"
          " the paper's lambda_min is not determined by its text (the state at which H is taken, the treatment of"
          " its boundary control points and its penalty quadrature are not stated); the growth of its cond is not"
          " the shell's fourth order in ours, but the penalty's h^-4 over a rising lambda_min." % (min(fac), max(fac)))
    return "\n".join(out) + "\n"


def summary_cell(results, fig9):
    """for the summary row: (p of cond over all sizes, p from 1,083 dofs, p of the paper, the largest bending /
    membrane ratio of the largest eigenvalues), or None"""
    rows, _ = read(os.path.join(results, "cond_parts.csv"))
    pd = sorted(d for s, d in rows if s == "paper" and "H" in rows[(s, d)])
    if not pd:
        return None
    hh = {d: float(rows[("paper", d)]["H"]["h"]) for d in pd}
    c = {d: g(rows[("paper", d)]["H"], "cond2") for d in pd}
    sp, _ = read(os.path.join(results, "cond_split.csv"))
    bm = [g(v.get("K_bend"), "lambda_max") / g(v.get("K_mem"), "lambda_max") for (st, d), v in sp.items()
          if st == "converged" and g(v.get("K_bend"), "lambda_max") and g(v.get("K_mem"), "lambda_max")]
    return (fit([(hh[d], c[d]) for d in pd]), fit([(hh[d], c[d]) for d in pd if d >= 1083]),
            fit([(hh[d], fig9[d]) for d in pd if d in fig9]), max(bm) if bm else None)


def initial_summary(results, fig9):
    """one phrase on H at the flat initial state for the summary row, '' without those rows"""
    rows, _ = read(os.path.join(results, "cond_split.csv"))
    d = sorted(dofs for st, dofs in rows if st == "initial" and g(rows[(st, dofs)].get("H"), "cond2"))
    if not d:
        return ""
    c = {k: g(rows[("initial", k)]["H"], "cond2") for k in d}
    hh = {k: float(rows[("initial", k)]["H"]["h"]) for k in d}
    r = [fig9[k] / c[k] for k in d if k in fig9]
    return ("H at the flat initial state of the step (the paper does not say where it takes H) gives %s at %s dofs "
            "(paper %s) and %.2g-%.2gx below the paper above, growing with p = %.2f from 1,083 dofs" % (
                sci(c[d[0]]), "{:,}".format(d[0]), sci(fig9.get(d[0])), min(r[1:] or r), max(r[1:] or r),
                fit([(hh[k], c[k]) for k in d if k >= 1083]) or 0))
