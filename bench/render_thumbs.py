"""bench/render_thumbs.py — pictures of records for the reports: each record's
final state rendered by `shellbench render` (docs/render.md) into a PNG
beside the report, and the Markdown that shows them.

    from render_thumbs import thumbnails
    lines = thumbnails(BIN, [(caption, record.h5[, [extra render options][, png name]]), ...],
                       "results/rmtr/images", "rmtr/images")

A picture is made only when its PNG is missing (the committed pictures are
the report's; delete them to redraw).  A record that cannot be drawn gets
its reason as the caption instead."""
import os, subprocess


def render(bin_, record, png, size="320x240", spp=8, extra=()):
    """render one record; returns None or the error line"""
    if os.path.exists(png):
        return None
    os.makedirs(os.path.dirname(png), exist_ok=True)
    p = subprocess.run([bin_, "render", record, "--size", size, "--spp", str(spp), "--out", png, "--quiet"]
                       + list(extra), capture_output=True, text=True)
    return None if p.returncode == 0 else (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]


def thumbnails(bin_, items, outdir, reldir, per_row=3, size="320x240", spp=8):
    """Markdown table rows of pictures (per_row per row), captions below"""
    cells = []
    for item in items:
        caption, record = item[0], item[1]
        extra = item[2] if len(item) > 2 else ()
        name = item[3] if len(item) > 3 else os.path.basename(record)   # the PNG's name (records of several
        if name.endswith(".h5"):                                          # scenes may share a basename)
            name = name[:-3]
        png = os.path.join(outdir, name + ".png")
        if not os.path.exists(record) and not os.path.exists(png):
            continue
        err = render(bin_, record, png, size, spp, extra) if os.path.exists(record) else None
        if err:
            cells.append(("—", "%s: not drawn (%s)" % (caption, err)))
        else:
            cells.append(("![%s](%s/%s.png)" % (caption, reldir, name), caption))
    out = []
    for i in range(0, len(cells), per_row):
        row = cells[i:i + per_row]
        out.append("| " + " | ".join(c[0] for c in row) + " |")
        out.append("|" + "---|" * len(row))
        out.append("| " + " | ".join(c[1] for c in row) + " |")
        out.append("")
    return out
