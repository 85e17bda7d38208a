/* sb_chart.c — reference-surface charts xi -> X in R^3 with exact first and
 * second derivatives, the composite (s,t) -> X used by structured methods
 * (chain rule), and Rodrigues rotations.
 *
 * Conventions (sb_scene.h): the cylinder and the sphere map the domain's
 * bounding box [x0,x1] x [y0,y1] LINEARLY onto their parameter ranges,
 * u = (xi1 - x0)/(x1 - x0), v = (xi2 - y0)/(y1 - y0).  With a domain whose
 * size equals the arc lengths (e.g. xi1 in [0, R*angle]) the chart is an
 * isometry.  Normals a_3 = a_1 x a_2: plane +e_z, cylinder outward radial,
 * sphere INWARD (towards the centre: e_phi x e_theta = -e_r). */
#include "sb_geometry.h"

#include <math.h>
#include <string.h>

void sb_chart_eval(const sb_chart *c, const sb_domain *d, const double xi[2], sb_jet3 *o)
{
    memset(o, 0, sizeof *o);
    if (c->kind == SB_CHART_PLANE) {   /* X = (xi1, xi2, 0) */
        o->x[0] = xi[0];
        o->x[1] = xi[1];
        o->d1[0] = 1;
        o->d2[1] = 1;
        return;
    }
    double lo[2], hi[2];
    sb_domain_bbox(d, lo, hi);
    double w = hi[0] - lo[0], h = hi[1] - lo[1];
    double u = (xi[0] - lo[0]) / w, v = (xi[1] - lo[1]) / h;
    double R = c->radius;
    if (c->kind == SB_CHART_CYLINDER) {
        /* X = (R sin phi, v L, R cos phi), phi = a0 + u (a1 - a0); axis e_y */
        double a = (c->angle[1] - c->angle[0]) / w;       /* dphi/dxi1 */
        double phi = c->angle[0] + u * (c->angle[1] - c->angle[0]);
        double sp = sin(phi), cp = cos(phi);
        o->x[0] = R * sp;
        o->x[1] = v * c->length;
        o->x[2] = R * cp;
        o->d1[0] = R * a * cp;
        o->d1[2] = -R * a * sp;
        o->d2[1] = c->length / h;
        o->d11[0] = -R * a * a * sp;
        o->d11[2] = -R * a * a * cp;
        return;
    }
    /* sphere: X = R (sin th cos ph, sin th sin ph, cos th),
     * th = p0 + v (p1 - p0) (polar, along xi2), ph = z0 + u (z1 - z0) (azimuth, along xi1) */
    double a = (c->azimuth[1] - c->azimuth[0]) / w;        /* dph/dxi1 */
    double b = (c->polar[1] - c->polar[0]) / h;            /* dth/dxi2 */
    double th = c->polar[0] + v * (c->polar[1] - c->polar[0]);
    double ph = c->azimuth[0] + u * (c->azimuth[1] - c->azimuth[0]);
    double st = sin(th), ct = cos(th), sp = sin(ph), cp = cos(ph);
    o->x[0] = R * st * cp;
    o->x[1] = R * st * sp;
    o->x[2] = R * ct;
    o->d1[0] = -R * a * st * sp;   o->d1[1] = R * a * st * cp;
    o->d2[0] = R * b * ct * cp;    o->d2[1] = R * b * ct * sp;   o->d2[2] = -R * b * st;
    o->d11[0] = -R * a * a * st * cp;  o->d11[1] = -R * a * a * st * sp;
    o->d12[0] = -R * a * b * ct * sp;  o->d12[1] = R * a * b * ct * cp;
    o->d22[0] = -R * b * b * st * cp;  o->d22[1] = -R * b * b * st * sp;  o->d22[2] = -R * b * b * ct;
}

void sb_geometry_eval_st(const sb_scene *sc, double s, double t, sb_jet3 *o)
{
    sb_jet2 m;
    sb_jet3 X;
    sb_domain_map(&sc->domain, s, t, &m);
    sb_chart_eval(&sc->chart, &sc->domain, m.x, &X);
    /* chain rule: X_s = X_a xi^a_s;
     * X_st = X_ab xi^a_s xi^b_t + X_a xi^a_st  (sum over a, b in {1,2}) */
    for (int k = 0; k < 3; k++) {
        double X1 = X.d1[k], X2 = X.d2[k], X11 = X.d11[k], X12 = X.d12[k], X22 = X.d22[k];
        o->x[k] = X.x[k];
        o->d1[k] = X1 * m.d1[0] + X2 * m.d1[1];
        o->d2[k] = X1 * m.d2[0] + X2 * m.d2[1];
        o->d11[k] = X11 * m.d1[0] * m.d1[0] + 2 * X12 * m.d1[0] * m.d1[1] +
                    X22 * m.d1[1] * m.d1[1] + X1 * m.d11[0] + X2 * m.d11[1];
        o->d12[k] = X11 * m.d1[0] * m.d2[0] + X12 * (m.d1[0] * m.d2[1] + m.d1[1] * m.d2[0]) +
                    X22 * m.d1[1] * m.d2[1] + X1 * m.d12[0] + X2 * m.d12[1];
        o->d22[k] = X11 * m.d2[0] * m.d2[0] + 2 * X12 * m.d2[0] * m.d2[1] +
                    X22 * m.d2[1] * m.d2[1] + X1 * m.d22[0] + X2 * m.d22[1];
    }
}

void sb_rotation(const double axis[3], double angle, double R[9])
{
    /* Rodrigues: R = I + sin(a) K + (1 - cos(a)) K^2, K = [n]_x, n = axis/|axis|;
     * a zero axis gives the identity. */
    double n = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (int i = 0; i < 9; i++) R[i] = (i % 4 == 0) ? 1 : 0;
    if (!(n > 0)) return;
    double x = axis[0] / n, y = axis[1] / n, z = axis[2] / n;
    double s = sin(angle), c1 = 1 - cos(angle);
    double K[9] = { 0, -z, y, z, 0, -x, -y, x, 0 };
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double K2 = 0;
            for (int k = 0; k < 3; k++) K2 += K[3 * i + k] * K[3 * k + j];
            R[3 * i + j] += s * K[3 * i + j] + c1 * K2;
        }
}
