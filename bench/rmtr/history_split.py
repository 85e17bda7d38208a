"""How an RMTR record's iterations split, read through h5dump (bench/rmtr/report.py and nowells_csv.py)."""
import os
import subprocess


def dataset(path, dset):
    """one dataset of a record as a list of floats; None when the file or the dataset is absent (older
    records lack /history/iterations/krylov_rtol)"""
    if not os.path.exists(path):
        return None
    out = subprocess.run(["h5dump", "-d", dset, "-y", "-w", "0", path], capture_output=True, text=True).stdout
    if "DATA {" not in out:
        return None
    body = out[out.find("DATA {") + 6:]
    return [float(v) for v in body[:body.find("}")].split(",") if v.strip()]


def iteration_split(path):
    """(V-cycles on the finest level, V-cycles on coarser tops (nested start), Krylov steps, their CG
    iterations) of the record at path; None without its history.  A Krylov step has krylov_rtol > 0."""
    it, lev, kr, li = (dataset(path, "/history/iterations/" + d) for d in ("iter", "level", "krylov_rtol",
                                                                          "linear_iters"))
    if not it:
        return None
    kr = kr or [0.0] * len(it)
    top = max(lev)
    v = sum(1 for i, l, k in zip(it, lev, kr) if i > 0 and l == top and k == 0)
    c = sum(1 for i, l in zip(it, lev) if i > 0 and l < top)
    k = sum(1 for i, q in zip(it, kr) if i > 0 and q > 0)
    cg = int(sum(n for i, q, n in zip(it, kr, li) if i > 0 and q > 0))
    return v, c, k, cg
