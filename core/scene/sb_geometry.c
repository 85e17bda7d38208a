/* sb_geometry.c — domains in material coordinates: the grid-parameter map
 * (s,t) in [0,1]^2 -> xi with exact first and second derivatives, its inverse,
 * the L-shape notch, named boundary parts, and the error-metric sample grid.
 * Charts (xi -> R^3) are in sb_chart.c. */
#include "sb_geometry.h"

#include <math.h>
#include <string.h>
#include <stdio.h>

#define PI 3.14159265358979323846
/* Points within this relative distance of the boundary count as inside
 * (closed domain; absorbs round-off in coordinates written in decimal). */
#define REL_TOL 1e-10

static double clamp01(double x) { return x < 0 ? 0 : (x > 1 ? 1 : x); }

void sb_domain_map(const sb_domain *d, double s, double t, sb_jet2 *o)
{
    memset(o, 0, sizeof *o);
    if (d->kind == SB_DOMAIN_ANNULUS_SECTOR) {
        /* polar map: r = r_in + s (r_out - r_in), th = th0 + t (th1 - th0),
         * xi = c + r (cos th, sin th); derivatives by differentiation. */
        double dr = d->r_out - d->r_in, dth = d->theta[1] - d->theta[0];
        double r = d->r_in + s * dr, th = d->theta[0] + t * dth;
        double c = cos(th), sn = sin(th);
        o->x[0] = d->center[0] + r * c;
        o->x[1] = d->center[1] + r * sn;
        o->d1[0] = dr * c;              o->d1[1] = dr * sn;
        o->d2[0] = -r * dth * sn;       o->d2[1] = r * dth * c;
        o->d12[0] = -dr * dth * sn;     o->d12[1] = dr * dth * c;
        o->d22[0] = -r * dth * dth * c; o->d22[1] = -r * dth * dth * sn;
        return;
    }
    /* rectangle and L-shape: the bounding box, affine */
    o->x[0] = d->origin[0] + s * d->size[0];
    o->x[1] = d->origin[1] + t * d->size[1];
    o->d1[0] = d->size[0];
    o->d2[1] = d->size[1];
}

int sb_domain_notch_st(const sb_domain *d, double s01[2], double t01[2])
{
    if (d->kind != SB_DOMAIN_L_SHAPE) return 0;
    double ns = d->notch[0] / d->size[0], nt = d->notch[1] / d->size[1];
    int hi_s = d->notch_corner == SB_CORNER_10 || d->notch_corner == SB_CORNER_11;
    int hi_t = d->notch_corner == SB_CORNER_11 || d->notch_corner == SB_CORNER_01;
    s01[0] = hi_s ? 1 - ns : 0;  s01[1] = hi_s ? 1 : ns;
    t01[0] = hi_t ? 1 - nt : 0;  t01[1] = hi_t ? 1 : nt;
    return 1;
}

int sb_domain_contains_st(const sb_domain *d, double s, double t)
{
    double s01[2], t01[2], e = REL_TOL;
    if (!(s >= -e && s <= 1 + e && t >= -e && t <= 1 + e)) return 0;
    if (sb_domain_notch_st(d, s01, t01)) {
        /* The removed set is the notch minus its two inner edges (notch_s,
         * notch_t): those belong to the domain, the notch's sides on the
         * bounding box (e.g. the notched corner itself) do not. */
        int hi_s = s01[1] == 1, hi_t = t01[1] == 1;
        int in_s = hi_s ? s > s01[0] + e : s < s01[1] - e;
        int in_t = hi_t ? t > t01[0] + e : t < t01[1] - e;
        if (in_s && in_t) return 0;
    }
    return 1;
}

int sb_domain_unmap(const sb_domain *d, const double xi[2], double st[2])
{
    if (d->kind == SB_DOMAIN_ANNULUS_SECTOR) {
        double dx = xi[0] - d->center[0], dy = xi[1] - d->center[1];
        double r = hypot(dx, dy), dr = d->r_out - d->r_in, dth = d->theta[1] - d->theta[0];
        double a = r > 0 ? atan2(dy, dx) - d->theta[0] : 0;
        a = fmod(a, 2 * PI);
        if (a < 0) a += 2 * PI;                       /* a in [0, 2 pi) */
        if (a > dth && 2 * PI - a <= REL_TOL * dth) a -= 2 * PI;  /* just below theta0 */
        st[0] = (r - d->r_in) / dr;
        st[1] = a / dth;
        if (!(st[0] >= -REL_TOL && st[0] <= 1 + REL_TOL && st[1] >= -REL_TOL &&
              st[1] <= 1 + REL_TOL))
            return 1;
        st[0] = clamp01(st[0]);
        st[1] = clamp01(st[1]);
        return 0;
    }
    st[0] = (xi[0] - d->origin[0]) / d->size[0];
    st[1] = (xi[1] - d->origin[1]) / d->size[1];
    if (!sb_domain_contains_st(d, st[0], st[1])) return 1;
    st[0] = clamp01(st[0]);
    st[1] = clamp01(st[1]);
    return 0;
}

void sb_domain_bbox(const sb_domain *d, double lo[2], double hi[2])
{
    if (d->kind != SB_DOMAIN_ANNULUS_SECTOR) {
        for (int k = 0; k < 2; k++) {
            lo[k] = d->origin[k];
            hi[k] = d->origin[k] + d->size[k];
        }
        return;
    }
    /* x = r cos th is monotone in r, so extremes lie at r_in or r_out and at
     * the end angles or the axis crossings (multiples of pi/2) in between. */
    double ang[12];
    int na = 0;
    ang[na++] = d->theta[0];
    ang[na++] = d->theta[1];
    for (int k = (int)ceil(d->theta[0] / (PI / 2)); k * (PI / 2) < d->theta[1] && na < 12; k++)
        ang[na++] = k * (PI / 2);
    lo[0] = lo[1] = INFINITY;
    hi[0] = hi[1] = -INFINITY;
    for (int i = 0; i < na; i++) {
        for (int j = 0; j < 2; j++) {
            double r = j ? d->r_out : d->r_in;
            double p[2] = { d->center[0] + r * cos(ang[i]), d->center[1] + r * sin(ang[i]) };
            for (int k = 0; k < 2; k++) {
                if (p[k] < lo[k]) lo[k] = p[k];
                if (p[k] > hi[k]) hi[k] = p[k];
            }
        }
    }
}

double sb_domain_diameter(const sb_domain *d)
{
    if (d->kind != SB_DOMAIN_ANNULUS_SECTOR)
        return hypot(d->size[0], d->size[1]);   /* L-shape keeps two opposite corners */
    /* The diameter is attained between extreme points: two points of the outer
     * arc (chord 2R sin(D/2)), or an end point of the inner arc and the outer
     * arc (law of cosines), with the angle difference D = min(span, pi). */
    double D = fmin(d->theta[1] - d->theta[0], PI), R = d->r_out, r = d->r_in;
    double chord = 2 * R * sin(D / 2);
    double cross = sqrt(fmax(0, R * R + r * r - 2 * R * r * cos(D)));
    return fmax(chord, cross);
}

/* ---- named boundary parts -------------------------------------------- */

static void set_edge(sb_part *p, const char *name, double s0, double t0, double s1, double t1)
{
    memset(p, 0, sizeof *p);
    p->kind = SB_PART_EDGE;
    snprintf(p->name, sizeof p->name, "%s", name);
    p->st0[0] = s0; p->st0[1] = t0;
    p->st1[0] = s1; p->st1[1] = t1;
}

const char *const *sb_domain_part_names(sb_domain_kind kind)
{
    static const char *const rect[] = { "left", "right", "bottom", "top", NULL };
    static const char *const lshape[] = { "left", "right", "bottom", "top", "notch_s", "notch_t", NULL };
    static const char *const annulus[] = { "inner", "outer", "start", "end", NULL };
    return kind == SB_DOMAIN_L_SHAPE ? lshape : kind == SB_DOMAIN_ANNULUS_SECTOR ? annulus : rect;
}

int sb_domain_edge_part(const sb_domain *d, const char *name, sb_part *part)
{
    /* edges at s = 0, s = 1, t = 0, t = 1 under both naming schemes */
    static const char *const rect[4] = { "left", "right", "bottom", "top" };
    static const char *const ann[4] = { "inner", "outer", "start", "end" };
    const char *const *names = d->kind == SB_DOMAIN_ANNULUS_SECTOR ? ann : rect;
    double s01[2] = { 0, 1 }, t01[2] = { 0, 1 };
    double ns[2] = { 0, 1 }, nt[2] = { 0, 1 };   /* notch ranges */
    int notch = sb_domain_notch_st(d, ns, nt);
    int hi_s = notch && ns[1] == 1, hi_t = notch && nt[1] == 1;

    if (notch && strcmp(name, "notch_s") == 0) {
        set_edge(part, name, hi_s ? ns[0] : ns[1], nt[0], hi_s ? ns[0] : ns[1], nt[1]);
        return SB_OK;
    }
    if (notch && strcmp(name, "notch_t") == 0) {
        set_edge(part, name, ns[0], hi_t ? nt[0] : nt[1], ns[1], hi_t ? nt[0] : nt[1]);
        return SB_OK;
    }
    for (int e = 0; e < 4; e++) {
        if (strcmp(name, names[e]) != 0) continue;
        double lo = 0, hi = 1;
        if (e < 2) {                 /* s = const edge: clip its t-range by the notch */
            if (notch && (e == 1) == hi_s) {
                if (hi_t) hi = nt[0]; else lo = nt[1];
            }
            set_edge(part, name, s01[e], lo, s01[e], hi);
        } else {                     /* t = const edge: clip its s-range */
            if (notch && (e == 3) == hi_t) {
                if (hi_s) hi = ns[0]; else lo = ns[1];
            }
            set_edge(part, name, lo, t01[e - 2], hi, t01[e - 2]);
        }
        return SB_OK;
    }
    return SB_ERR_INPUT;
}

int sb_part_contains_st(const sb_part *p, double s, double t, double tol)
{
    if (p->kind == SB_PART_POINT) return fabs(s - p->st[0]) <= tol && fabs(t - p->st[1]) <= tol;
    if (p->st0[0] == p->st1[0])     /* s = const */
        return fabs(s - p->st0[0]) <= tol && t >= p->st0[1] - tol && t <= p->st1[1] + tol;
    return fabs(t - p->st0[1]) <= tol && s >= p->st0[0] - tol && s <= p->st1[0] + tol;
}

int sb_domain_sample_grid(const sb_domain *d, int n, double *st, int max)
{
    int count = 0;
    if (n < 1) return 0;
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < n; i++) {
            /* n >= 2: nodes i/(n-1) including the boundary; n = 1: the centre */
            double s = n > 1 ? (double)i / (n - 1) : 0.5, t = n > 1 ? (double)j / (n - 1) : 0.5;
            if (!sb_domain_contains_st(d, s, t)) continue;
            if (count < max && st) {
                st[2 * count] = s;
                st[2 * count + 1] = t;
            }
            count++;
        }
    }
    return count;
}
