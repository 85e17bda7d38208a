#!/usr/bin/env python3
"""bench/bhem/lateral_curve.py — the master curve of lateral (lateral–torsional)
buckling of a heavy cantilever strip (BHEM paper Fig. 20, Romero et al. 2021),
derived in docs/lateral_buckling.md:

    gamma(kappa) = q_cr L^3 / sqrt(B C),   kappa = C1 / (C L^2),

the smallest eigenvalue of the Vlasov beam's second variation with the
lateral displacement eliminated (Timoshenko & Gere, Theory of Elastic
Stability, 2nd ed. 1961, §6.3: gamma(0) = 12.85 for a narrow strip loaded
at its centroid),

    min over phi  int_0^1 (phi'^2 + kappa phi''^2) dz / int_0^1 z^4 phi^2 dz = gamma^2 / 4,

z = x/L from the free end, phi = phi' = 0 at the clamp z = 1.  For a strip of
width w, thickness h: B = Y w h^3/12, C = G w h^3/3, C1 = Y w^3 h^3/144, so
kappa = (1 + nu) (w/L)^2 / 24 and, with Gamma* = 12 (1 - nu^2) rho g L^3/(Y h^2)
(rho g per unit area over Y h^3: Gamma* = rho_a g L^3 / D),

    Gamma*_cr(w/L) = 12 (1 - nu^2) / sqrt(72 (1 + nu)) * gamma(kappa).

Pure Python (no numpy here): cubic Hermite elements on [0, 1], inverse
iteration with a dense Cholesky factor.

    python3 bench/bhem/lateral_curve.py [NU] > results/bhem/lateral/master_curve.csv
    python3 -c 'import lateral_curve; print(lateral_curve.gamma(0))'
"""
import math
import sys

NE = 40   # elements; gamma(0) to 4 digits (12.85)

# 2-point... 5-point Gauss–Legendre on [0, 1]
_GX = [0.5 - 0.5 * 0.9061798459386640, 0.5 - 0.5 * 0.5384693101056831, 0.5,
       0.5 + 0.5 * 0.5384693101056831, 0.5 + 0.5 * 0.9061798459386640]
_GW = [0.5 * 0.2369268850561891, 0.5 * 0.4786286704993665, 0.5 * 0.5688888888888889,
       0.5 * 0.4786286704993665, 0.5 * 0.2369268850561891]


def _hermite(t, h):
    """cubic Hermite shape functions on an element of length h at t in [0,1]:
    values, first and second derivatives with respect to x"""
    N = [1 - 3 * t * t + 2 * t ** 3, h * (t - 2 * t * t + t ** 3), 3 * t * t - 2 * t ** 3, h * (-t * t + t ** 3)]
    d1 = [(-6 * t + 6 * t * t) / h, 1 - 4 * t + 3 * t * t, (6 * t - 6 * t * t) / h, -2 * t + 3 * t * t]
    d2 = [(-6 + 12 * t) / h ** 2, (-4 + 6 * t) / h, (6 - 12 * t) / h ** 2, (-2 + 6 * t) / h]
    return N, d1, d2


def _matrices(kappa, ne):
    n = 2 * (ne + 1)
    K = [[0.0] * n for _ in range(n)]
    G = [[0.0] * n for _ in range(n)]
    h = 1.0 / ne
    for e in range(ne):
        dofs = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3]
        for gx, gw in zip(_GX, _GW):
            z = (e + gx) * h
            N, d1, d2 = _hermite(gx, h)
            for a in range(4):
                for b in range(4):
                    K[dofs[a]][dofs[b]] += gw * h * (d1[a] * d1[b] + kappa * d2[a] * d2[b])
                    G[dofs[a]][dofs[b]] += gw * h * z ** 4 * N[a] * N[b]
    # clamp at z = 1: phi = 0 and (with warping rigidity) phi' = 0
    keep = [i for i in range(n) if i != n - 2 and not (kappa > 0 and i == n - 1)]
    return [[K[i][j] for j in keep] for i in keep], [[G[i][j] for j in keep] for i in keep]


def _cholesky(A):
    n = len(A)
    L = [[0.0] * n for _ in range(n)]
    for i in range(n):
        for j in range(i + 1):
            s = A[i][j] - sum(L[i][k] * L[j][k] for k in range(j))
            L[i][j] = math.sqrt(s) if i == j else s / L[j][j]
    return L


def _solve(L, b):
    n = len(L)
    y = [0.0] * n
    for i in range(n):
        y[i] = (b[i] - sum(L[i][k] * y[k] for k in range(i))) / L[i][i]
    x = [0.0] * n
    for i in reversed(range(n)):
        x[i] = (y[i] - sum(L[k][i] * x[k] for k in range(i + 1, n))) / L[i][i]
    return x


def gamma(kappa, ne=NE):
    """q_cr L^3 / sqrt(B C) for the warping parameter kappa = C1/(C L^2)"""
    K, G = _matrices(kappa, ne)
    L = _cholesky(K)
    n = len(K)
    v = [1.0] * n
    lam = 0.0
    for _ in range(200):
        Gv = [sum(G[i][j] * v[j] for j in range(n)) for i in range(n)]
        w = _solve(L, Gv)
        # Rayleigh quotient v'Kv / v'Gv with v <- w
        Kw = [sum(K[i][j] * w[j] for j in range(n)) for i in range(n)]
        Gw = [sum(G[i][j] * w[j] for j in range(n)) for i in range(n)]
        new = sum(a * b for a, b in zip(w, Kw)) / sum(a * b for a, b in zip(w, Gw))
        nrm = math.sqrt(sum(a * a for a in w))
        v = [a / nrm for a in w]
        if abs(new - lam) <= 1e-12 * new:
            lam = new
            break
        lam = new
    return 2.0 * math.sqrt(lam)


def gamma_star_cr(w_over_L, nu, ne=NE):
    """Gamma*_cr = 12 (1 - nu^2) rho g L^3 / (Y h^2) at buckling (docs/lateral_buckling.md)"""
    kappa = (1.0 + nu) * w_over_L ** 2 / 24.0
    return 12.0 * (1.0 - nu * nu) / math.sqrt(72.0 * (1.0 + nu)) * gamma(kappa, ne)


if __name__ == "__main__":
    nu = float(sys.argv[1]) if len(sys.argv) > 1 else 0.3
    print("# lateral buckling of a heavy cantilever strip, Vlasov beam with warping (docs/lateral_buckling.md),"
          " nu = %g, %d cubic Hermite elements" % (nu, NE))
    print("w_over_L,Gamma_star_cr,gamma")
    for k in range(0, 41):
        r = 0.02 * k
        kap = (1.0 + nu) * r * r / 24.0
        g = gamma(kap)
        print("%.3f,%.6f,%.6f" % (r, 12.0 * (1.0 - nu * nu) / math.sqrt(72.0 * (1.0 + nu)) * g, g))
