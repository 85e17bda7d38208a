"""bench/h5ddl.py — read a record's attributes and datasets through h5dump
(hdf5-tools), for the bench report scripts (bench/scaling/report.py,
bench/linear_solvers/report.py, bench/sqrt3/distance.py, dress_series.py): no
h5py needed."""
import re
import subprocess

NUM = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-?(inf|nan)$", re.I)


def h5dump(path, args):
    """h5dump's DDL of the objects named by args (-a ATTR, -d DATASET), full precision"""
    r = subprocess.run(["h5dump", "-y", "-w", "0", "-m", "%.17g"] + args + [path], capture_output=True, text=True)
    return r.stdout


def parse_ddl(txt):
    """{name: [values]} of every ATTRIBUTE / DATASET block in h5dump's output"""
    out, name, data, vals = {}, None, False, []
    for line in txt.splitlines():
        s = line.strip()
        m = re.match(r'^(ATTRIBUTE|DATASET) "([^"]+)" \{$', s)
        if m:
            name, data, vals = m.group(2), False, []
            continue
        if s == "DATA {":
            data = True
            continue
        if data:
            if s == "}":
                out[name] = vals
                data = False
                continue
            for tok in re.findall(r'"[^"]*"|[^,\s]+', s):
                if tok.startswith('"'):
                    vals.append(tok[1:-1])
                elif NUM.match(tok):
                    vals.append(float(tok))
    return out


def h5_text(path, *args):
    """h5dump's text of the objects named by args (-d, -g, -A ...); fails loudly"""
    return subprocess.run(["h5dump", "-m", "%.17g", "-w", "0"] + list(args) + [path], check=True,
                          capture_output=True, text=True).stdout


def numbers(text):
    """the numbers of the first DATA block (the dataset's; attributes follow it)"""
    out = []
    m = re.search(r"DATA \{(.*?)\}", text, re.S)
    for line in (m.group(1).splitlines() if m else []):
        if ":" in line:
            out += [float(v) for v in line.split(":", 1)[1].replace(",", " ").split()]
    return out


def samples(path):
    """{step: [x0, y0, z0, x1, ...]} from /steps/sample_pos"""
    text = h5_text(path, "-g", "/steps/sample_pos")
    out = {}
    for m in re.finditer(r'DATASET "(\d+)" \{(.*?)\n      \}\n   \}', text, re.S):
        out[int(m.group(1))] = numbers(m.group(2) + "}")
    return out
