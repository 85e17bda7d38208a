#!/usr/bin/env python3
"""bench/bhem/scenes/gen_sharp_standin.py — the stand-in for the BHEM paper's
armadillo (Fig. 3, Table 2: 2.8k sample points, the collider's vertices),
whose mesh is not available here.  A procedurally generated closed triangle
mesh with sharp features at about the paper's sampling density:

  a cube surface, each face an N x N grid of squares split into two
  triangles (vertices shared along the cube's edges, so the mesh is closed
  and manifold), mapped by a continuous deformation that keeps the cube's 12
  edges sharp — tapered (the top 0.6 times the base), twisted 30 degrees
  about the vertical over its height — and with a pyramid raised on the top
  face (4 more sharp ridges and an apex).  N = 22 gives 6 N^2 + 2 = 2,906
  vertices and 5,808 triangles.

    python3 bench/bhem/scenes/gen_sharp_standin.py > bench/bhem/scenes/sharp_standin.obj

Deterministic (no random numbers): the committed OBJ is this script's output.
"""
import math
import sys

N = 22                # squares per cube face side
HALF = 0.2            # half width of the base (m)
HEIGHT = 0.4          # height of the box part (m)
TAPER = 0.6           # top width / base width
TWIST = math.radians(30.0)
ROOF = 0.12           # pyramid height above the top face (m)
BASE = -0.52005       # z of the base: the apex 0.05 mm below the cloth at z = 0 (contact from step 3)


def deform(p):
    """cube [-1, 1]^3 -> the stand-in solid (continuous, so the mesh stays closed)"""
    x, y, z = p
    h = (z + 1.0) / 2.0                              # 0 at the base, 1 at the top
    s = HALF * (1.0 + (TAPER - 1.0) * h)
    a = TWIST * h
    X, Y = s * x, s * y
    X, Y = X * math.cos(a) - Y * math.sin(a), X * math.sin(a) + Y * math.cos(a)
    Z = BASE + HEIGHT * h
    if z > 1.0 - 1e-12:                              # top face: a pyramid, apex at the centre
        Z += ROOF * (1.0 - max(abs(x), abs(y)))
    return (X, Y, Z)


def main():
    verts, index, faces = [], {}, []

    def vid(p):
        key = tuple(round(c * N) for c in p)         # exact integer lattice key: shared along edges
        if key not in index:
            index[key] = len(verts) + 1
            verts.append(deform(p))
        return index[key]

    g = [-1.0 + 2.0 * i / N for i in range(N + 1)]
    for axis in range(3):
        for sign in (-1.0, 1.0):
            u_ax, v_ax = [a for a in range(3) if a != axis]
            for i in range(N):
                for j in range(N):
                    quad = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = [0.0, 0.0, 0.0]
                        p[axis] = sign
                        p[u_ax] = g[i + di]
                        p[v_ax] = g[j + dj]
                        quad.append(vid(tuple(p)))
                    # outward orientation: (u, v, axis) right-handed for sign +1
                    right = (u_ax, v_ax, axis) in ((0, 1, 2), (1, 2, 0), (2, 0, 1))
                    if (sign > 0) != right:
                        quad.reverse()
                    faces.append((quad[0], quad[1], quad[2]))
                    faces.append((quad[0], quad[2], quad[3]))
    out = sys.stdout
    out.write("# sharp_standin.obj: stand-in for the BHEM paper's armadillo (gen_sharp_standin.py)\n")
    out.write("# %d vertices, %d triangles\n" % (len(verts), len(faces)))
    for v in verts:
        out.write("v %.5f %.5f %.5f\n" % v)
    for f in faces:
        out.write("f %d %d %d\n" % f)


if __name__ == "__main__":
    main()
