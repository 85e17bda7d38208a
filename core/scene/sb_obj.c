/* sb_obj.c — a small Wavefront OBJ reader for obstacle meshes: "v x y z"
 * and "f a b c ..." lines (indices 1-based or negative, "i/t/n" forms
 * accepted, polygons fanned into triangles); every other line is ignored
 * (vt, vn, o, g, s, usemtl, mtllib, comments).  Refused with the line
 * number: a malformed number or index, an index out of range, a face with
 * fewer than three vertices or a repeated vertex, a degenerate (zero-area)
 * triangle, and a non-manifold edge (shared by more than two triangles:
 * the barrier and the continuous collision test treat the mesh as a
 * surface, and such an edge is not one). */
#include "sb_scene_json.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define OBJ_MAX_VERTS 1000000
#define OBJ_MAX_TRIS 2000000
#define OBJ_MAX_POLY 64

typedef struct edge_key { int a, b, line; } edge_key;

static int cmp_edge(const void *x, const void *y)
{
    const edge_key *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return p->line < q->line ? -1 : p->line > q->line;
}

static int grow(void **buf, int *cap, int need, size_t elem)
{
    if (need <= *cap) return 0;
    int nc = *cap ? *cap : 64;
    while (nc < need) nc *= 2;
    void *nb = realloc(*buf, (size_t)nc * elem);
    if (!nb) return -1;
    *buf = nb;
    *cap = nc;
    return 0;
}

int sb_obj_read(const char *path, double **verts_out, int *nv_out, int **tris_out, int *nt_out, char *msg,
                size_t msglen)
{
    *verts_out = NULL; *tris_out = NULL; *nv_out = *nt_out = 0;
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {   /* a FIFO or a device would block or never end */
        snprintf(msg, msglen, "%s: not a regular file (obstacle meshes are read from OBJ files)", path);
        return SB_ERR_INPUT;
    }
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(msg, msglen, "%s: cannot open the mesh file (%s)", path, strerror(errno));
        return SB_ERR_INPUT;
    }
    double *V = NULL;
    int *T = NULL, *tline = NULL, nv = 0, nt = 0, capv = 0, capt = 0, capl = 0, lineno = 0, rc = SB_OK;
    char line[4096];
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (!strchr(line, '\n') && !feof(f)) {
            snprintf(msg, msglen, "%s:%d: line too long (more than %zu bytes)", path, lineno, sizeof line - 2);
            rc = SB_ERR_INPUT;
            break;
        }
        char *p = line;
        while (*p == ' ' || *p == '\t') p++;
        if (p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) {
            double x[3];
            char *q = p + 1, *end;
            for (int k = 0; k < 3; k++) {
                errno = 0;
                x[k] = strtod(q, &end);
                if (end == q || !isfinite(x[k])) {
                    snprintf(msg, msglen, "%s:%d: vertex needs three finite coordinates", path, lineno);
                    rc = SB_ERR_INPUT;
                    goto done;
                }
                q = end;
            }
            if (nv >= OBJ_MAX_VERTS || grow((void **)&V, &capv, 3 * (nv + 1), sizeof *V)) {
                snprintf(msg, msglen, "%s:%d: too many vertices or out of memory", path, lineno);
                rc = SB_ERR_INPUT;
                goto done;
            }
            memcpy(V + 3 * nv++, x, sizeof x);
        } else if (p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) {
            int idx[OBJ_MAX_POLY], k = 0;
            char *q = p + 1;
            for (;;) {
                while (*q == ' ' || *q == '\t' || *q == '\r' || *q == '\n') q++;
                if (!*q) break;
                char *end;
                long v = strtol(q, &end, 10);
                if (end == q || v == 0 || (*end && *end != '/' && *end != ' ' && *end != '\t' && *end != '\r' &&
                                           *end != '\n')) {
                    snprintf(msg, msglen, "%s:%d: malformed face index", path, lineno);
                    rc = SB_ERR_INPUT;
                    goto done;
                }
                long i0 = v > 0 ? v - 1 : nv + v;
                if (i0 < 0 || i0 >= nv) {
                    snprintf(msg, msglen, "%s:%d: face index %ld out of range (%d vertices so far)", path, lineno, v,
                             nv);
                    rc = SB_ERR_INPUT;
                    goto done;
                }
                if (k == OBJ_MAX_POLY) {
                    snprintf(msg, msglen, "%s:%d: face with more than %d vertices", path, lineno, OBJ_MAX_POLY);
                    rc = SB_ERR_INPUT;
                    goto done;
                }
                for (int j = 0; j < k; j++)
                    if (idx[j] == (int)i0) {
                        snprintf(msg, msglen, "%s:%d: face repeats vertex %ld", path, lineno, v);
                        rc = SB_ERR_INPUT;
                        goto done;
                    }
                idx[k++] = (int)i0;
                q = end;
                while (*q && *q != ' ' && *q != '\t' && *q != '\r' && *q != '\n') q++;   /* skip /t/n */
            }
            if (k < 3) {
                snprintf(msg, msglen, "%s:%d: face with fewer than three vertices", path, lineno);
                rc = SB_ERR_INPUT;
                goto done;
            }
            for (int j = 1; j + 1 < k; j++) {   /* fan */
                if (nt >= OBJ_MAX_TRIS || grow((void **)&T, &capt, 3 * (nt + 1), sizeof *T) ||
                    grow((void **)&tline, &capl, nt + 1, sizeof *tline)) {
                    snprintf(msg, msglen, "%s:%d: too many faces or out of memory", path, lineno);
                    rc = SB_ERR_INPUT;
                    goto done;
                }
                int *t = T + 3 * nt;
                t[0] = idx[0]; t[1] = idx[j]; t[2] = idx[j + 1];
                const double *a = V + 3 * t[0], *b = V + 3 * t[1], *c = V + 3 * t[2];
                double u[3], w[3], n[3];
                for (int m = 0; m < 3; m++) { u[m] = b[m] - a[m]; w[m] = c[m] - a[m]; }
                n[0] = u[1] * w[2] - u[2] * w[1];
                n[1] = u[2] * w[0] - u[0] * w[2];
                n[2] = u[0] * w[1] - u[1] * w[0];
                double area2 = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                double scale = fmax(sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]), sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]));
                if (!(area2 > 1e-12 * scale * scale)) {
                    snprintf(msg, msglen, "%s:%d: degenerate (zero-area) triangle", path, lineno);
                    rc = SB_ERR_INPUT;
                    goto done;
                }
                tline[nt++] = lineno;
            }
        }
    }
    if (ferror(f)) {
        snprintf(msg, msglen, "%s: read error", path);
        rc = SB_ERR_INPUT;
    } else if (nt == 0) {
        snprintf(msg, msglen, "%s:%d: no faces (an obstacle mesh needs at least one triangle)", path, lineno);
        rc = SB_ERR_INPUT;
    }
done:
    fclose(f);
    if (rc == SB_OK) {
        /* manifold edges: no edge in more than two triangles */
        edge_key *E = malloc((size_t)3 * nt * sizeof *E);
        if (!E) {
            snprintf(msg, msglen, "%s: out of memory", path);
            rc = SB_ERR_INPUT;
        } else {
            for (int t = 0; t < nt; t++)
                for (int k = 0; k < 3; k++) {
                    int a = T[3 * t + k], b = T[3 * t + (k + 1) % 3];
                    E[3 * t + k] = (edge_key){ a < b ? a : b, a < b ? b : a, tline[t] };
                }
            qsort(E, (size_t)3 * nt, sizeof *E, cmp_edge);
            for (int i = 0; i + 2 < 3 * nt; i++)
                if (E[i].a == E[i + 2].a && E[i].b == E[i + 2].b) {
                    snprintf(msg, msglen, "%s:%d: non-manifold edge (vertices %d and %d are shared by more than two faces)",
                             path, E[i + 2].line, E[i].a + 1, E[i].b + 1);
                    rc = SB_ERR_INPUT;
                    break;
                }
            free(E);
        }
    }
    free(tline);
    if (rc) { free(V); free(T); return rc; }
    *verts_out = V; *tris_out = T; *nv_out = nv; *nt_out = nt;
    return SB_OK;
}
