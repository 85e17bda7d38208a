/* sb_render.c — the ray tracer of `shellbench render`: camera, Sobol pixel
 * samples, shading with a key light (soft shadows), a fill light and sky
 * light, a ground plane with a metric grid, colour fields with their scale,
 * and labels (sb_render.h). */
#include "sb_render_world.h"
#include "sb_common.h"
#include "sb_gsl.h"

#include <gsl/gsl_qrng.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

const char *const sb_color_names[] = { "none", "curvature", "strain", "softening", NULL };

void sb_render_options_default(sb_render_options *o)
{
    memset(o, 0, sizeof *o);
    o->width = 640;
    o->height = 480;
    o->spp = 16;
    o->isect = SB_ISECT_NEWTON;
    o->color = SB_COLOR_NONE;
    o->azimuth = -60.0;
    o->elevation = 30.0;
    o->zoom = 1.0;
    o->fov = 30.0;
    o->shadows = 1;
    o->ground = 1;
    o->eps_rel = 1e-6;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void normalize3(double a[3])
{
    const double l = sqrt(dot3(a, a));
    if (l > 0) for (int c = 0; c < 3; c++) a[c] /= l;
}
static double deg(double x) { return x * M_PI / 180.0; }

/* sRGB component -> linear */
static float lin(double s) { return (float)(s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4)); }

/* ---- camera ----------------------------------------------------------- */

typedef struct camera {
    double eye[3], f[3], r[3], u[3];
    double tanh_, aspect;
    double azimuth;           /* of the view direction (degrees), for placing the lights */
} camera;

static void camera_setup(camera *cam, const sb_render_options *o, const sb_world *w)
{
    double at[3], eye[3];
    const double fov = deg(o->fov > 1 && o->fov < 170 ? o->fov : 30.0);
    cam->aspect = (double)o->width / o->height;
    cam->tanh_ = tan(0.5 * fov);
    if (o->use_eye) {
        memcpy(at, o->at, sizeof at);
        memcpy(eye, o->eye, sizeof eye);
    } else {
        const double az = deg(o->azimuth), el = deg(o->elevation);
        const double dir[3] = { cos(el) * cos(az), cos(el) * sin(az), sin(el) };
        /* the bounding sphere fits the narrower of the two fields of view */
        const double half = atan(cam->tanh_ * fmin(1.0, cam->aspect));
        const double dist = w->radius / sin(half) / (o->zoom > 0 ? o->zoom : 1.0);
        for (int c = 0; c < 3; c++) {
            at[c] = w->centre[c];
            eye[c] = at[c] + dist * dir[c];
        }
    }
    memcpy(cam->eye, eye, sizeof eye);
    for (int c = 0; c < 3; c++) cam->f[c] = at[c] - eye[c];
    normalize3(cam->f);
    double up[3] = { 0, 0, 1 };
    cross3(cam->f, up, cam->r);
    if (sqrt(dot3(cam->r, cam->r)) < 1e-6) {   /* looking straight down or up */
        up[1] = 1;
        up[2] = 0;
        cross3(cam->f, up, cam->r);
    }
    normalize3(cam->r);
    cross3(cam->r, cam->f, cam->u);
    cam->azimuth = atan2(-cam->f[1], -cam->f[0]) * 180.0 / M_PI;
}

static void camera_ray(const camera *cam, const sb_render_options *o, double px, double py, sb_ray *ray)
{
    const double x = (2.0 * px / o->width - 1.0) * cam->tanh_ * cam->aspect;
    const double y = (1.0 - 2.0 * py / o->height) * cam->tanh_;
    double d[3];
    for (int c = 0; c < 3; c++) d[c] = cam->f[c] + x * cam->r[c] + y * cam->u[c];
    sb_ray_init(ray, cam->eye, d, 0.0, INFINITY);
}

/* ---- lights and shading --------------------------------------------------- */

typedef struct lights {
    double key[3], fill[3];   /* unit directions towards the lights */
    double e1[3], e2[3];      /* frame normal to key (soft-shadow cone) */
    double cone;              /* tan of the key light's angular radius */
} lights;

static void dir_from(double az, double el, double d[3])
{
    d[0] = cos(deg(el)) * cos(deg(az));
    d[1] = cos(deg(el)) * sin(deg(az));
    d[2] = sin(deg(el));
}

static void lights_setup(lights *L, const camera *cam)
{
    /* key light above and to the left of the viewer, fill from the other side */
    dir_from(cam->azimuth + 40.0, 55.0, L->key);
    dir_from(cam->azimuth - 110.0, 25.0, L->fill);
    double a[3] = { 0, 0, 1 };
    if (fabs(L->key[2]) > 0.9) { a[0] = 1; a[2] = 0; }
    cross3(L->key, a, L->e1);
    normalize3(L->e1);
    cross3(L->key, L->e1, L->e2);
    L->cone = tan(deg(2.0));
}

static void sky(const double d[3], float c[3])
{
    const float hz[3] = { lin(0.93), lin(0.94), lin(0.96) }, zn[3] = { lin(0.63), lin(0.73), lin(0.87) };
    const float t = (float)fmin(1.0, fmax(0.0, 1.5 * d[2]));
    for (int k = 0; k < 3; k++) c[k] = (1 - t) * hz[k] + t * zn[k];
}

/* diverging blue - grey - red for t in [-1, 1] */
static void diverging(double t, float c[3])
{
    static const double lo[3] = { 0.23, 0.30, 0.75 }, mid[3] = { 0.87, 0.87, 0.87 }, hi[3] = { 0.71, 0.02, 0.15 };
    t = fmax(-1.0, fmin(1.0, t));
    for (int k = 0; k < 3; k++) {
        const double s = t < 0 ? mid[k] + (-t) * (lo[k] - mid[k]) : mid[k] + t * (hi[k] - mid[k]);
        c[k] = lin(s);
    }
}

typedef struct shade_ctx {
    sb_world *w;
    const sb_render_options *o;
    const lights *L;
    double lo, hi;            /* colour scale: values mapped to the ends */
    sb_render_stats *st;
    int err;
} shade_ctx;

/* visibility of the key light from p (offset along n) with jitter (s0, s1) */
static double key_visibility(shade_ctx *S, const double p[3], const double n[3], double s0, double s1)
{
    if (!S->o->shadows) return 1.0;
    const lights *L = S->L;
    const double r = sqrt(s0) * L->cone, ph = 2.0 * M_PI * s1;
    double d[3], o[3];
    for (int c = 0; c < 3; c++) {
        d[c] = L->key[c] + r * (cos(ph) * L->e1[c] + sin(ph) * L->e2[c]);
        o[c] = p[c] + 50.0 * S->w->eps * n[c];
    }
    sb_ray ray;
    if (sb_ray_init(&ray, o, d, 0.0, INFINITY)) return 1.0;
    sb_hit h;
    S->st->shadow_rays++;
    int rc = sb_world_intersect(S->w, &ray, INFINITY, 1, &h);
    if (rc < 0) S->err = 1;
    return rc > 0 ? 0.0 : 1.0;
}

static void albedo_of(shade_ctx *S, const sb_hit *h, int back, float a[3])
{
    if (h->kind == SB_HIT_OBSTACLE) {
        const sb_world *w = S->w;
        const sb_obstacle *ob = &w->obstacles[h->prim];
        if (ob->kind == SB_OBSTACLE_PLANE) {
            /* a plane obstacle: a light green checkerboard of the ground's
             * grid spacing with a dark rim, so that it reads as a bounded
             * patch of an infinite plane, not as the ground */
            double q[3];
            for (int c = 0; c < 3; c++) q[c] = h->p[c] - ob->c[c];
            const double x = dot3(q, w->plane_u[h->prim]), y = dot3(q, w->plane_v[h->prim]);
            const int rim = fabs(x) > 0.97 * ob->extent || fabs(y) > 0.97 * ob->extent;
            const int odd = ((long)floor(x / w->grid) + (long)floor(y / w->grid)) & 1;
            const double g = rim ? 0.35 : odd ? 0.62 : 0.74;
            a[0] = lin(0.85 * g); a[1] = lin(g); a[2] = lin(0.80 * g);
            return;
        }
        a[0] = lin(0.60); a[1] = lin(0.58); a[2] = lin(0.55);
        return;
    }
    const sb_color_kind kind = S->o->color;
    double v;
    if (kind != SB_COLOR_NONE && sb_field_at(S->w, kind, h->kind, h->prim, h->u, h->v, &v) == 0) {
        if (kind == SB_COLOR_SOFTENING) {
            const int soft = v < -1e-9;
            a[0] = lin(soft ? 0.86 : 0.74); a[1] = lin(soft ? 0.20 : 0.77); a[2] = lin(soft ? 0.14 : 0.82);
        } else {
            diverging(2.0 * (v - S->lo) / (S->hi - S->lo) - 1.0, a);
        }
        return;
    }
    if (kind != SB_COLOR_NONE) { a[0] = a[1] = a[2] = lin(0.3); return; }   /* not evaluable: dark grey */
    if (back) { a[0] = lin(0.82); a[1] = lin(0.64); a[2] = lin(0.44); }
    else { a[0] = lin(0.45); a[1] = lin(0.58); a[2] = lin(0.80); }
}

static void shade(shade_ctx *S, const sb_ray *ray, const sb_hit *h, const double s[4], float out[3])
{
    const lights *L = S->L;
    if (h->kind == SB_HIT_NONE) { sky(ray->d, out); return; }
    if (h->kind == SB_HIT_GROUND) {
        const double g = S->w->grid, lw = 0.02 * g;
        const double fx = h->p[0] / g - floor(h->p[0] / g), fy = h->p[1] / g - floor(h->p[1] / g);
        const int line = fx * g < lw || fx * g > g - lw || fy * g < lw || fy * g > g - lw;
        const float alb = lin(line ? 0.60 : 0.80);
        const double n[3] = { 0, 0, 1 };
        const double vis = L->key[2] > 0 ? key_visibility(S, h->p, n, s[2], s[3]) : 0.0;
        const double light = 0.22 + 0.8 * fmax(0.0, L->key[2]) * vis + 0.25 * fmax(0.0, L->fill[2]);
        float bg[3];
        sky(ray->d, bg);
        /* fade into the sky with the distance from the surface */
        const double dx = h->p[0] - S->w->centre[0], dy = h->p[1] - S->w->centre[1];
        const double dist = sqrt(dx * dx + dy * dy) / S->w->radius;
        const float f = (float)exp(-fmax(0.0, dist - 1.5) / 2.5);
        for (int c = 0; c < 3; c++) out[c] = f * (float)(alb * light) + (1 - f) * bg[c];
        return;
    }
    double n[3];
    memcpy(n, h->n, sizeof n);
    const int back = dot3(n, ray->d) > 0;
    if (back) for (int c = 0; c < 3; c++) n[c] = -n[c];
    float a[3];
    albedo_of(S, h, back, a);
    const double nk = dot3(n, L->key), nf = fmax(0.0, dot3(n, L->fill));
    const double vis = nk > 0 ? key_visibility(S, h->p, n, s[2], s[3]) : 0.0;
    double hv[3];
    for (int c = 0; c < 3; c++) hv[c] = L->key[c] - ray->d[c];
    normalize3(hv);
    const double spec = nk > 0 ? 0.18 * pow(fmax(0.0, dot3(n, hv)), 48.0) * vis : 0.0;
    const double amb = 0.12 + 0.10 * (0.5 + 0.5 * n[2]);
    const double light = amb + 0.85 * fmax(0.0, nk) * vis + 0.30 * nf;
    for (int c = 0; c < 3; c++) out[c] = (float)(a[c] * light + spec);
}

/* ---- colour scale --------------------------------------------------------- */

/* Sample the field on the surface (9x9 points per patch, centroid and
 * corners per triangle): the colour scale runs from the 1st to the 99th
 * percentile of the samples (a corner singularity does not wash out the
 * picture; the extremes are printed with the scale). */
static int field_range(sb_world *w, sb_color_kind kind, sb_render_stats *st, double *lo, double *hi)
{
    const sb_surface *s = w->s;
    const long n = 81L * s->n_patches + 4L * s->n_tris;
    double *a = malloc((size_t)(n ? n : 1) * sizeof *a);
    if (!a) return -1;
    long m = 0, soft = 0;
    for (int p = 0; p < s->n_patches; p++)
        for (int j = 0; j < 9; j++)
            for (int i = 0; i < 9; i++) {
                double v;
                if (sb_field_at(w, kind, SB_HIT_PATCH, p, (i + 0.5) / 9.0, (j + 0.5) / 9.0, &v) == 0) a[m++] = v;
            }
    static const double bary[4][2] = { { 1.0 / 3, 1.0 / 3 }, { 0, 0 }, { 1, 0 }, { 0, 1 } };
    for (int t = 0; t < s->n_tris; t++)
        for (int k = 0; k < 4; k++) {
            double v;
            if (sb_field_at(w, kind, SB_HIT_TRIANGLE, t, bary[k][0], bary[k][1], &v) == 0) a[m++] = v;
        }
    for (long i = 0; i < m; i++)
        if (a[i] < -1e-9) soft++;
    /* percentiles by GSL's rule (sb_quantiles: gsl_sort + gsl_stats) */
    static const double pq[4] = { 0.0, 0.01, 0.99, 1.0 };
    double q[4] = { 0, 0, 0, 0 };
    if (m > 0 && sb_quantiles(a, (size_t)m, pq, 4, q) != SB_OK) {
        free(a);
        return -1;
    }
    *lo = q[1];
    *hi = q[2];
    st->field_min = m ? q[0] : NAN;
    st->field_max = m ? q[3] : NAN;
    /* a (nearly) constant field: a symmetric scale about it */
    const double span = fmax(1e-12, 1e-6 * fmax(fabs(*lo), fabs(*hi)));
    if (!(*hi - *lo > span)) {
        const double c = 0.5 * (*lo + *hi);
        *lo = c - span;
        *hi = c + span;
    }
    st->soft_fraction = m ? (double)soft / m : 0.0;
    free(a);
    return 0;
}

/* ---- labels and the colour bar ------------------------------------------- */

static void fill_rect(sb_image *im, int x0, int y0, int x1, int y1, const float c[3], float alpha)
{
    for (int y = y0 < 0 ? 0 : y0; y < y1 && y < im->h; y++)
        for (int x = x0 < 0 ? 0 : x0; x < x1 && x < im->w; x++) {
            float *d = im->rgb + 3 * ((size_t)y * im->w + x);
            for (int k = 0; k < 3; k++) d[k] = (1 - alpha) * d[k] + alpha * c[k];
        }
}

static void draw_labels(sb_image *im, const sb_render_options *o, const sb_render_stats *st, double grid)
{
    const int sc = im->w >= 1200 ? 2 : 1, m = 6 * sc, lh = sb_font_height(sc) + 2 * sc;
    const float ink[3] = { 0.01f, 0.01f, 0.012f }, paper[3] = { 1, 1, 1 };
    int y = m;
    const char *lines[2] = { o->title, o->subtitle };
    const int maxw = im->w - 2 * m;
    for (int i = 0; i < 2; i++) {
        /* wrap at " | " separators (else anywhere) to fit the width */
        const char *p = lines[i];
        while (*p == ' ') p++;
        while (*p && y + lh < im->h / 2) {
            char buf[256];
            size_t n = strlen(p), take = n;
            if (sb_font_width(p, sc) > maxw) {
                const size_t fit = (size_t)(maxw / sb_font_width("M", sc));
                take = fit < n ? fit : n;
                for (size_t k = take; k > 2; k--)
                    if (!strncmp(p + k - 2, " |", 2)) { take = k - 2; break; }
            }
            if (take == 0) take = 1;
            snprintf(buf, sizeof buf, "%.*s", (int)(take < sizeof buf - 1 ? take : sizeof buf - 1), p);
            const int wd = sb_font_width(buf, sc);
            fill_rect(im, m - 3 * sc, y - sc, m + wd + 3 * sc, y + lh - sc, paper, 0.55f);
            sb_font_draw(im, m, y, sc, buf, ink);
            y += lh;
            p += take;
            while (*p == ' ' || *p == '|') p++;
        }
    }
    char buf[160];
    /* bottom line: the colour scale, or the ground grid */
    const int yb = im->h - m - lh;
    if (o->color == SB_COLOR_CURVATURE || o->color == SB_COLOR_STRAIN) {
        const int bw = im->w / 5, bx = m, bh = lh - 4 * sc;
        for (int x = 0; x < bw; x++) {
            float c[3];
            diverging(2.0 * x / (bw - 1) - 1.0, c);
            fill_rect(im, bx + x, yb + 2 * sc, bx + x + 1, yb + 2 * sc + bh, c, 1.0f);
        }
        if (o->color == SB_COLOR_CURVATURE)
            snprintf(buf, sizeof buf, "H %.3g .. %.3g 1/m", st->field_lo, st->field_hi);
        else
            snprintf(buf, sizeof buf, "strain %.3g .. %.3g", st->field_lo, st->field_hi);
        const int wd = sb_font_width(buf, sc);
        fill_rect(im, bx + bw + 2 * sc, yb - sc, bx + bw + 8 * sc + wd, yb + lh - sc, paper, 0.55f);
        sb_font_draw(im, bx + bw + 5 * sc, yb, sc, buf, ink);
    } else {
        if (o->color == SB_COLOR_SOFTENING) {
            const float red[3] = { lin(0.86), lin(0.20), lin(0.14) };
            fill_rect(im, m, yb + 2 * sc, m + 3 * sb_font_height(sc) / 2, yb + lh - 2 * sc, red, 1.0f);
            snprintf(buf, sizeof buf, "soft: %.1f %% of samples", 100.0 * st->soft_fraction);
            const int x = m + 2 * sb_font_height(sc);
            const int wd = sb_font_width(buf, sc);
            fill_rect(im, x - 3 * sc, yb - sc, x + wd + 3 * sc, yb + lh - sc, paper, 0.55f);
            sb_font_draw(im, x, yb, sc, buf, ink);
        } else if (o->ground) {
            snprintf(buf, sizeof buf, "ground grid %.3g m", grid);
            const int wd = sb_font_width(buf, sc);
            fill_rect(im, m - 3 * sc, yb - sc, m + wd + 3 * sc, yb + lh - sc, paper, 0.55f);
            sb_font_draw(im, m, yb, sc, buf, ink);
        }
    }
}

/* ---- the render loop ------------------------------------------------------- */

/* The per-pixel Cranley-Patterson rotation of the Sobol points: SplitMix64
 * (Steele, Lea & Flood 2014) of the pixel index, used as a hash, not as a
 * stream.  Kept instead of a gsl_rng (issue 31): it is a pure function of
 * (px, py), branch-free in the pixel loop and needs no allocation or seeding
 * per pixel, and the committed images (docs/img, results/bhem/table1) are
 * made with it.  Its name is written into every PNG (sb_render_record.c,
 * SB_RENDER_SAMPLES). */
static uint64_t splitmix(uint64_t *x)
{
    uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

int sb_render_surface(const sb_surface *s, const sb_material *mat, const sb_render_options *o, sb_image *img,
                      sb_render_stats *st, char *err, size_t errlen)
{
    sb_render_stats local;
    if (!st) st = &local;
    memset(st, 0, sizeof *st);
    st->field_lo = st->field_hi = NAN;
    if (o->width < 8 || o->height < 8 || o->width > 8192 || o->height > 8192 || o->spp < 1 || o->spp > 4096) {
        snprintf(err, errlen, "image size %dx%d or %d samples per pixel out of range (8..8192 pixels, 1..4096 samples)",
                 o->width, o->height, o->spp);
        return SB_ERR_INPUT;
    }
    if (sb_field_check(s, mat, o->color, err, errlen)) return SB_ERR_INPUT;
    const double t0 = now();
    sb_world w;
    int rc = sb_world_build(&w, s, mat, o, err, errlen);
    if (rc) return rc;
    if (sb_image_alloc(img, o->width, o->height)) {
        sb_world_free(&w);
        snprintf(err, errlen, "out of memory for a %dx%d image", o->width, o->height);
        return SB_ERR_NOMEM;
    }
    double lo = -1.0, hi = 1.0;
    if (o->color != SB_COLOR_NONE && field_range(&w, o->color, st, &lo, &hi)) {
        sb_world_free(&w);
        sb_image_free(img);
        snprintf(err, errlen, "out of memory sampling the colour field");
        return SB_ERR_NOMEM;
    }
    if (o->color == SB_COLOR_CURVATURE || o->color == SB_COLOR_STRAIN) {
        st->field_lo = lo;
        st->field_hi = hi;
    }
    /* pixel samples: the first spp points of the 4-D Sobol sequence (pixel x,
     * y, key-light disc), shifted per pixel by a hashed Cranley–Patterson
     * rotation; one sample = the pixel centre */
    const int spp = o->spp;
    double *pts = malloc((size_t)spp * 4 * sizeof *pts);
    sb_gsl_errors_off();   /* the suite's GSL policy (sb_gsl.h): a failure returns NULL */
    gsl_qrng *q = spp > 1 ? gsl_qrng_alloc(gsl_qrng_sobol, 4) : NULL;
    if (!pts || (spp > 1 && !q)) {
        free(pts);
        if (q) gsl_qrng_free(q);
        sb_world_free(&w);
        sb_image_free(img);
        snprintf(err, errlen, "out of memory for the sample pattern");
        return SB_ERR_NOMEM;
    }
    int qbad = 0;
    for (int k = 0; k < spp; k++) {
        if (q) qbad |= gsl_qrng_get(q, pts + 4 * k) != GSL_SUCCESS;
        else pts[0] = pts[1] = pts[2] = pts[3] = 0.5;
    }
    if (q) gsl_qrng_free(q);
    if (qbad) {   /* more points than the Sobol generator gives: cannot happen below 2^30 */
        free(pts);
        sb_world_free(&w);
        sb_image_free(img);
        snprintf(err, errlen, "the Sobol sequence cannot give %d points", spp);
        return SB_ERR_INTERNAL;
    }
    camera cam;
    camera_setup(&cam, o, &w);
    lights L;
    lights_setup(&L, &cam);
    shade_ctx S = { &w, o, &L, lo, hi, st, 0 };
    st->build_seconds = now() - t0;
    const double t1 = now(), c1 = cpu_now();
    for (int py = 0; py < o->height && !S.err; py++)
        for (int px = 0; px < o->width && !S.err; px++) {
            uint64_t seed = (uint64_t)py * 0x10000ULL + (uint64_t)px;
            double rot[4];
            for (int k = 0; k < 4; k++) rot[k] = spp > 1 ? (splitmix(&seed) >> 11) * 0x1.0p-53 : 0.0;
            float acc[3] = { 0, 0, 0 };
            for (int k = 0; k < spp; k++) {
                double smp[4];
                for (int c = 0; c < 4; c++) {
                    smp[c] = pts[4 * k + c] + rot[c];
                    if (smp[c] >= 1.0) smp[c] -= 1.0;
                }
                sb_ray ray;
                camera_ray(&cam, o, px + smp[0], py + smp[1], &ray);
                sb_hit h;
                st->primary_rays++;
                if (sb_world_intersect(&w, &ray, INFINITY, 0, &h) < 0) { S.err = 1; break; }
                float c[3];
                shade(&S, &ray, &h, smp, c);
                for (int j = 0; j < 3; j++) acc[j] += c[j];
            }
            float *d = img->rgb + 3 * ((size_t)py * o->width + px);
            for (int j = 0; j < 3; j++) d[j] = acc[j] / spp;
        }
    st->seconds = now() - t1;
    st->cpu_seconds = cpu_now() - c1;
    st->isect = *sb_bezier_ws_counts(w.ws);
    st->tri_tests = w.tri_tests;
    free(pts);
    if (S.err) {
        sb_world_free(&w);
        sb_image_free(img);
        snprintf(err, errlen, "out of memory in the ray–patch search");
        return SB_ERR_NOMEM;
    }
    draw_labels(img, o, st, w.grid);
    sb_world_free(&w);
    return SB_OK;
}
