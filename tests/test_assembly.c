/* test_assembly.c — the methods' element assembly (issue 30): with
 * method.kernel=reference it computes the bits it computed before the fast
 * kernel existed (stored checksums of f, g and H for StVK scenes, whose
 * arithmetic uses no libm function but sqrt; for denim and end moments,
 * whose libm calls may round differently on another machine, the old
 * serial loop re-run here), for any run.threads; the fast kernel gives the
 * same bits for any run.threads and agrees with the reference to
 * round-off; whole runs are bit-identical for 1, 2 and 3 threads. */
#include "sb_test.h"
#include "run_json.h"
#include "sb_record.h"
#include "sb_method.h"
#include "sb_solver.h"
#include "sb_sparse.h"
#include "sb_assemble.h"
#include "../methods/rmtr/cc_method.h"
#include "../methods/bhem/bhem.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

extern const sb_method_type *sb_method_find(const char *name);

static unsigned long long fnv(unsigned long long h, const void *p, size_t n)
{
    const unsigned char *c = p;
    for (size_t i = 0; i < n; i++) {
        h ^= c[i];
        h *= 1099511628211ULL;
    }
    return h;
}
#define FNV0 1469598103934665603ULL

/* one method on one scene at one level, at a deterministic perturbed state */
typedef struct asm_case {
    sb_scene sc;
    sb_paramset ps;
    const sb_method_type *mt;
    void *S;
    sb_pattern *pat;
    int n;
    double *x;
} asm_case;

static int case_open(asm_case *c, const char *scene, const char *method, int res, double amp,
                     const char *const *sets)
{
    char path[1024], err[1024];
    memset(c, 0, sizeof *c);
    snprintf(path, sizeof path, "%s/%s", sb_test_root(), scene);
    if (sb_scene_load(path, &c->sc, err, sizeof err)) return printf("    %s\n", err), -1;
    c->mt = sb_method_find(method);
    sb_paramset_init(&c->ps);
    sb_paramset_add(&c->ps, "method", c->mt->params);
    sb_paramset_add(&c->ps, "run", sb_solve_params);
    for (int i = 0; sets && sets[i]; i++)
        if (sb_paramset_set(&c->ps, sets[i], err, sizeof err)) return printf("    %s\n", err), -1;
    c->S = calloc(1, c->mt->state_size);
    sb_method_config cfg = { res, 1, &c->ps, NULL, 0 };
    if (c->mt->create(c->S, &c->sc, &cfg)) return -1;
    c->n = c->mt->n_dofs(c->S, 0);
    const int bs = c->mt->block_size(c->S, 0);
    sb_pattern_builder *pb = sb_pattern_builder_new(c->n / bs, bs);
    c->mt->pattern(c->S, 0, pb);
    if (sb_pattern_builder_finish(pb, &c->pat)) return -1;
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = si.n_steps = 1;
    si.t = 1;
    for (int i = 0; i < SB_SCENE_MAX_LOADS; i++) si.load_factor[i] = 1;
    for (int i = 0; i < SB_SCENE_MAX_BCS; i++) si.motion_factor[i] = 1;
    c->mt->set_step(c->S, &si);
    c->x = malloc(sizeof(double) * c->n);
    c->mt->initial(c->S, 0, c->x);
    unsigned long long st = 12345;
    for (int i = 0; i < c->n; i++) {
        st = st * 6364136223846793005ULL + 1442695040888963407ULL;
        c->x[i] += amp * ((double)(st >> 11) * (2.0 / 9007199254740992.0) - 1.0);
    }
    return 0;
}

static void case_close(asm_case *c)
{
    if (c->S) {
        c->mt->destroy(c->S);
        free(c->S);
    }
    sb_pattern_free(c->pat);
    free(c->x);
    sb_scene_free(&c->sc);
}

/* f, g and H of the case into fresh storage */
typedef struct fgh {
    double f;
    double *g;
    sb_matrix H;
    int rc;
} fgh;

static void eval(asm_case *c, fgh *r)
{
    r->g = calloc(c->n, sizeof(double));
    sb_matrix_init(&r->H, c->pat);
    sb_matrix_zero(&r->H);
    r->rc = c->mt->energy(c->S, 0, c->x, &r->f, r->g, &r->H);
}

static void fgh_free(fgh *r)
{
    free(r->g);
    sb_matrix_free(&r->H);
}

static int fgh_same(const asm_case *c, const fgh *a, const fgh *b)
{
    return memcmp(&a->f, &b->f, sizeof a->f) == 0 && memcmp(a->g, b->g, sizeof(double) * c->n) == 0 &&
           memcmp(a->H.val, b->H.val, sizeof(double) * c->pat->nnz) == 0;
}

/* the old serial loops (cc_energy and bhem_energy before issue 30), verbatim
 * but for their scratch */
static double old_rmtr(cc_state *S, const double *x, double *g, sb_matrix *H)
{
    const sb_scene *sc = S->scene;
    cc_level *L = &S->lv[0];
    const cc_quad *Q = &L->quad;
    if (cc_level_ref(S, 0)) return NAN;
    double gvec[3] = { 0, 0, 0 };
    int has_g = 0, has_p = 0;
    for (int i = 0; i < sc->n_loads; i++) {
        const sb_load *ld = &sc->loads[i];
        if (ld->kind == SB_LOAD_GRAVITY) {
            for (int c = 0; c < 3; c++) gvec[c] += S->load_factor[i] * ld->vec[c];
            has_g = 1;
        }
        has_p |= ld->kind == SB_LOAD_PRESSURE;
    }
    sb_hess_kind hk = S->hess == SB_HESS_PSD ? SB_HESS_EXACT : S->hess;
    sb_shell_work *w = sb_shell_work_new();
    double *qe = malloc(sizeof(double) * 192), *ge = malloc(sizeof(double) * 192), *Ke = malloc(sizeof(double) * 192 * 192);
    double *psd = malloc(sizeof(double) * sb_psd_work_size(192));
    double E = 0;
    for (int el = 0; el < Q->ne; el++) {
        const int *nd = Q->enode + Q->eoff[el];
        int k = Q->eoff[el + 1] - Q->eoff[el], n = 3 * k;
        for (int a = 0; a < k; a++) memcpy(qe + 3 * a, x + 3 * nd[a], 3 * sizeof(double));
        memset(ge, 0, (size_t)n * sizeof *ge);
        memset(Ke, 0, (size_t)n * n * sizeof *Ke);
        for (int q = 0; q < Q->nq; q++) {
            sb_shell_basis b = cc_quad_basis(Q, el, q);
            const sb_shell_ref *r = &L->ref[(size_t)el * Q->nq + q];
            E += sb_shell_energy(&S->mat, r, &b, qe, ge, Ke, hk, w);
            if (has_g) E += sb_shell_external(&S->mat, r, &b, qe, gvec, 0.0, 0, ge, NULL);
            if (has_p)
                for (int i = 0; i < sc->n_loads; i++)
                    if (sc->loads[i].kind == SB_LOAD_PRESSURE)
                        E += sb_shell_external(&S->mat, r, &b, qe, NULL, S->load_factor[i] * sc->loads[i].value,
                                               sc->loads[i].follower, ge, Ke);
        }
        E += cc_points_energy(S, L, el, qe, ge, Ke);
        for (int a = 0; a < k; a++)
            for (int c = 0; c < 3; c++) g[3 * nd[a] + c] += ge[3 * a + c];
        if (S->hess == SB_HESS_PSD) sb_psd_project(n, Ke, psd);
        sb_matrix_add_element(H, el, Ke);
    }
    sb_shell_work_free(w);
    free(qe);
    free(ge);
    free(Ke);
    free(psd);
    return E;
}

static double old_bhem(bhem_state *S, const double *x, double *g, sb_matrix *H)
{
    bhem_level *L = &S->lv[0];
    const sb_scene *sc = S->scene;
    if (L->rebranch) {
        if (L->n_mq) bhem_moment_rebranch(S, L, x);
        L->rebranch = 0;
    }
    double p_follow = 0.0;
    for (int k = 0; k < sc->n_loads; k++)
        if (sc->loads[k].kind == SB_LOAD_PRESSURE && sc->loads[k].follower)
            p_follow += S->load_factor[k] * sc->loads[k].value;
    const double gzero[3] = { 0.0, 0.0, 0.0 };
    sb_hess_kind kind = S->hess == SB_HESS_PSD ? SB_HESS_EXACT : S->hess;
    sb_shell_work *w = sb_shell_work_new();
    double qe[BHEM_NED], ge[BHEM_NED], *Ke = malloc(sizeof(double) * BHEM_NED * BHEM_NED);
    double *psd = malloc(sizeof(double) * sb_psd_work_size(BHEM_NED));
    double E = 0.0;
    for (int e = 0; e < L->n_elems; e++) {
        bhem_gather(L, e, x, qe);
        memset(ge, 0, sizeof ge);
        memset(Ke, 0, sizeof(double) * BHEM_NED * BHEM_NED);
        const sb_shell_ref *ref = L->ref + (size_t)e * BHEM_NQP;
        for (int q = 0; q < BHEM_NQP; q++) {
            const bhem_qp_basis *B = &L->qb[q];
            sb_shell_basis b = { BHEM_NB, B->N, B->N1, B->N2, B->N11, B->N12, B->N22 };
            E += sb_shell_energy(&S->mat, &ref[q], &b, qe, ge, Ke, kind, w);
            if (p_follow != 0.0) E += sb_shell_external(&S->mat, &ref[q], &b, qe, gzero, p_follow, 1, ge, Ke);
        }
        if (L->n_mq) E += bhem_moment_element(S, L, e, qe, ge, Ke);
        if (S->hess == SB_HESS_PSD) sb_psd_project(BHEM_NED, Ke, psd);
        const int *d = L->elem_dofs + (size_t)e * BHEM_NED;
        for (int a = 0; a < BHEM_NED; a++) g[d[a]] += ge[a];
        sb_matrix_add_element(H, e, Ke);
    }
    double Eext = 0.0;
    for (int i = 0; i < L->n_dofs; i++) Eext -= L->f_ext[i] * (x[i] - L->x_ref[i]);
    E += Eext;
    sb_axpy(L->n_dofs, -1.0, L->f_ext, g);
    sb_shell_work_free(w);
    free(Ke);
    free(psd);
    return E;
}

typedef struct scase {
    const char *scene, *method;
    int res;
    const char *hess;
    unsigned long long ck[3];   /* f, g, H with the reference kernel (0: compare with the old loop) */
} scase;

/* checksums computed with the code before issue 30 (commit 17e9372) */
static const scase scases[] = {
    { "bench/scenes/plate_clamped.json", "rmtr", 8, "exact",
      { 0x20aaaf90950a1a24ULL, 0x70e2e1aac572877bULL, 0x22794f1c307b6a9fULL } },
    { "bench/bhem/scenes/draped_cloth.json", "bhem", 6, "exact",
      { 0x6993a9b7d78647d3ULL, 0x4773d08e8b83f090ULL, 0x9d7e50ac6e5e28a7ULL } },
    { "bench/bhem/scenes/draped_cloth.json", "bhem", 6, "psd", { 0, 0, 0 } },
    { "bench/scenes/drooping.json", "rmtr", 8, "exact", { 0, 0, 0 } },
    { "bench/scenes/drooping.json", "rmtr", 8, "psd", { 0, 0, 0 } },
    { "bench/scenes/drooping.json", "rmtr", 8, "pseudo", { 0, 0, 0 } },
    { "bench/bhem/scenes/rollup_quarter.json", "bhem", 6, "exact", { 0, 0, 0 } },
    /* several chunks of the threaded assembly (~4 MB of element slots each) */
    { "bench/scenes/drooping.json", "rmtr", 24, "exact", { 0, 0, 0 } },
    { "bench/bhem/scenes/draped_cloth.json", "bhem", 18, "exact", { 0, 0, 0 } },
};

SB_TEST(reference_kernel_is_the_old_arithmetic)
{
    for (size_t i = 0; i < sizeof scases / sizeof scases[0]; i++) {
        const scase *s = &scases[i];
        char hess[64];
        snprintf(hess, sizeof hess, "method.hessian=%s", s->hess);
        fgh first;
        memset(&first, 0, sizeof first);
        for (int threads = 1; threads <= (sb_assemble_have_threads() ? 3 : 1); threads++) {
            char th[32];
            snprintf(th, sizeof th, "run.threads=%d", threads);
            /* rmtr: the paper's penalty beta, which the stored checksums were taken with (the scaled
             * default differs on the stvk plate; docs/trust.md) */
            const char *sets[] = { "method.kernel=reference", hess, th,
                                   strcmp(s->method, "rmtr") ? NULL : "method.beta_rule=paper", NULL };
            asm_case c;
            if (case_open(&c, s->scene, s->method, s->res, 1e-3, sets)) {
                CHECK_MSG(0, "%s: cannot set up", s->scene);
                case_close(&c);
                continue;
            }
            fgh r;
            eval(&c, &r);
            CHECK_EQ_INT(r.rc, SB_OK);
            if (threads == 1) {
                if (s->ck[0]) {
                    CHECK_MSG(fnv(FNV0, &r.f, sizeof r.f) == s->ck[0] && fnv(FNV0, r.g, sizeof(double) * c.n) == s->ck[1] &&
                                  fnv(FNV0, r.H.val, sizeof(double) * c.pat->nnz) == s->ck[2],
                              "%s %s: reference kernel checksums differ from the stored ones", s->scene, s->method);
                } else {
                    fgh o;
                    o.g = calloc(c.n, sizeof(double));
                    sb_matrix_init(&o.H, c.pat);
                    sb_matrix_zero(&o.H);
                    o.f = strcmp(s->method, "rmtr") == 0 ? old_rmtr(c.S, c.x, o.g, &o.H) : old_bhem(c.S, c.x, o.g, &o.H);
                    CHECK_MSG(fgh_same(&c, &r, &o), "%s %s %s: reference kernel differs from the old loop", s->scene,
                              s->method, s->hess);
                    fgh_free(&o);
                }
                first = r;
            } else {
                CHECK_MSG(fgh_same(&c, &r, &first), "%s %s %s: %d threads differ from 1", s->scene, s->method, s->hess,
                          threads);
                fgh_free(&r);
            }
            case_close(&c);
        }
        fgh_free(&first);
    }
}

/* the fast kernel: the same bits for 1, 2, 3 threads; the reference's values to round-off */
SB_TEST(fast_kernel_threads_and_agreement)
{
    for (size_t i = 0; i < sizeof scases / sizeof scases[0]; i++) {
        const scase *s = &scases[i];
        char hess[64];
        snprintf(hess, sizeof hess, "method.hessian=%s", s->hess);
        fgh first;
        memset(&first, 0, sizeof first);
        asm_case c0;
        for (int threads = 1; threads <= (sb_assemble_have_threads() ? 3 : 1); threads++) {
            char th[32];
            snprintf(th, sizeof th, "run.threads=%d", threads);
            const char *sets[] = { "method.kernel=fast", hess, th, NULL };
            asm_case c;
            if (case_open(&c, s->scene, s->method, s->res, 1e-3, sets)) {
                CHECK_MSG(0, "%s: cannot set up", s->scene);
                case_close(&c);
                continue;
            }
            fgh r;
            eval(&c, &r);
            CHECK_EQ_INT(r.rc, SB_OK);
            if (threads > 1) {
                CHECK_MSG(fgh_same(&c, &r, &first), "%s %s %s: fast kernel, %d threads differ from 1", s->scene,
                          s->method, s->hess, threads);
                fgh_free(&r);
                case_close(&c);
                continue;
            }
            first = r;
            c0 = c;
        }
        /* against the reference kernel (kind PSD: the projections differ by design) */
        if (strcmp(s->hess, "psd") != 0) {
            const char *sets[] = { "method.kernel=reference", hess, NULL };
            asm_case c;
            case_open(&c, s->scene, s->method, s->res, 1e-3, sets);
            fgh r;
            eval(&c, &r);
            double dg = 0, gm = 0, dh = 0, hm = 0;
            for (int j = 0; j < c.n; j++) {
                dg = fmax(dg, fabs(r.g[j] - first.g[j]));
                gm = fmax(gm, fabs(r.g[j]));
            }
            for (long j = 0; j < c.pat->nnz; j++) {
                dh = fmax(dh, fabs(r.H.val[j] - first.H.val[j]));
                hm = fmax(hm, fabs(r.H.val[j]));
            }
            CHECK_MSG(fabs(r.f - first.f) <= 1e-11 * fabs(r.f) && dg <= 1e-10 * gm && dh <= 1e-10 * hm,
                      "%s %s %s: fast vs reference f %.3g g %.3g H %.3g", s->scene, s->method, s->hess,
                      fabs(r.f - first.f) / fabs(r.f), dg / gm, dh / hm);
            fgh_free(&r);
            case_close(&c);
        }
        fgh_free(&first);
        case_close(&c0);
    }
}

/* whole runs: every count, the history of every iteration and the final
 * state are bit-identical for 1, 2 and 3 threads and for every vector width
 * of the fast kernel this CPU runs (run.vectors; records compared) */
SB_TEST(runs_identical_for_any_thread_count)
{
    static const char *const runs[][3] = { { "trampoline_1step.json", "rmtr", "rmtr" },
                                           { "drooping_1step.json", "rmtr", "tr" },
                                           { "drooping_1step.json", "bhem", "lsnewton" } };
    /* (threads, run.vectors): the first is the reference of the others */
    static const struct { int threads; const char *vectors; } cfgs[] = {
        { 1, "auto" }, { 2, "auto" }, { 3, "auto" }, { 1, "sse2" }, { 1, "avx2" }, { 2, "avx512" }
    };
    const int ncfg = (int)(sizeof cfgs / sizeof cfgs[0]);
    char dir[] = "/tmp/sb_test_assembly_XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    for (int k = 0; k < 3; k++) {
        sb_record_summary first;
        sb_record_setup xfirst;
        char msg[1024];
        for (int ic = 0; ic < ncfg; ic++) {
            const int threads = cfgs[ic].threads;
            if (threads > 1 && !sb_assemble_have_threads()) continue;
            sb_shell_isa isa;
            char vset[64];
            snprintf(vset, sizeof vset, "run.vectors=%s", cfgs[ic].vectors);
            sb_paramset vps;
            sb_paramset_init(&vps);
            sb_paramset_add(&vps, "run", sb_solve_params);
            CHECK_EQ_INT(sb_paramset_set(&vps, vset, msg, sizeof msg), SB_OK);
            if (sb_shell_isa_from_params(&vps, &isa, msg, sizeof msg) != SB_OK) {
                printf("# %s: %s (not compared)\n", vset, msg);
                continue;
            }
            char scene[1024], th[32], out[1100];
            snprintf(scene, sizeof scene, "%s/tests/scenes/%s", sb_test_root(), runs[k][0]);
            snprintf(th, sizeof th, "run.threads=%d", threads);
            snprintf(out, sizeof out, "%s/run%d_%d.h5", dir, k, ic);
            const char *sets[] = { th, "run.max_iter=60", vset };
            sb_run_request req;
            memset(&req, 0, sizeof req);
            req.scene = scene;
            req.method = runs[k][1];
            req.solver = runs[k][2];
            req.res = 8;
            req.levels = strcmp(runs[k][2], "rmtr") == 0 ? 2 : 1;
            req.out = out;
            req.quiet = 1;
            req.n_sets = 3;
            req.sets = sets;
            int ec;
            json_t *r = sb_test_run_json(&req, &ec);
            CHECK_MSG(r != NULL && ec <= 1, "%s %s with %d threads, %s: exit %d", runs[k][0], runs[k][1], threads, vset, ec);
            if (r && strcmp(cfgs[ic].vectors, "auto")) {   /* the record says which width ran */
                const char *info = json_string_value(json_object_get(json_object_get(r, "summary"), "method_info"));
                if (!info) info = json_string_value(json_object_get(r, "method_info"));
                CHECK_MSG(info && strstr(info, sb_shell_isa_name(isa)), "%s: method_info %s", vset, info ? info : "?");
            }
            json_decref(r);
            sb_record_summary rs;
            sb_record_setup xs;
            CHECK_EQ_INT(sb_record_read_summary(out, &rs, msg, sizeof msg), SB_OK);
            CHECK_EQ_INT(sb_record_read_setup(out, &xs, msg, sizeof msg), SB_OK);
            remove(out);
            char xdmf[1200];
            sb_record_xdmf_path(out, xdmf, sizeof xdmf);
            remove(xdmf);
            if (ic == 0) {
                first = rs;
                xfirst = xs;
                CHECK(rs.iterations > 5);
                continue;
            }
            CHECK_MSG(rs.iterations == first.iterations && rs.steps == first.steps && rs.reason == first.reason &&
                          rs.work_assembly == first.work_assembly && rs.work_qp == first.work_qp &&
                          rs.n_hist == first.n_hist,
                      "%s %s: %d threads, %s: %d iterations, %g + %g work units against %d, %g + %g", runs[k][0], runs[k][1], threads, vset,
                      rs.iterations, rs.work_assembly, rs.work_qp, first.iterations, first.work_assembly,
                      first.work_qp);
            if (rs.n_hist == first.n_hist)
                CHECK_MSG(memcmp(rs.hist_gnorm, first.hist_gnorm, sizeof(double) * rs.n_hist) == 0 &&
                              memcmp(rs.hist_level, first.hist_level, sizeof(int) * rs.n_hist) == 0,
                          "%s %s: %d threads, %s: another history", runs[k][0], runs[k][1], threads, vset);
            CHECK_MSG(xs.n_x == xfirst.n_x && memcmp(xs.x, xfirst.x, sizeof(double) * xs.n_x) == 0,
                      "%s %s: %d threads, %s: another final state", runs[k][0], runs[k][1], threads, vset);
            sb_record_summary_free(&rs);
            sb_record_setup_free(&xs);
        }
        sb_record_summary_free(&first);
        sb_record_setup_free(&xfirst);
    }
    rmdir(dir);
}

/* a build without OpenMP refuses run.threads > 1 before any work; any build
 * refuses an out-of-range count */
SB_TEST(threads_refused_when_unavailable)
{
    /* run.vectors: not a width at all */
    const char *sbad[] = { "run.vectors=avx9", NULL };
    asm_case cb;
    CHECK(case_open(&cb, "bench/scenes/plate_clamped.json", "bhem", 4, 1e-3, sbad) != 0);
    case_close(&cb);
    /* run.vectors: a width this CPU runs is accepted, another refused with a sentence */
    for (int i = 1; sb_vector_choices[i]; i++) {
        char set[64];
        snprintf(set, sizeof set, "run.vectors=%s", sb_vector_choices[i]);
        const char *sv[] = { set, NULL };
        asm_case cv;
        sb_paramset vps;
        sb_paramset_init(&vps);
        sb_paramset_add(&vps, "run", sb_solve_params);
        char msg[256];
        sb_shell_isa isa;
        CHECK_EQ_INT(sb_paramset_set(&vps, set, msg, sizeof msg), SB_OK);
        const int supported = sb_shell_isa_from_params(&vps, &isa, msg, sizeof msg) == SB_OK;
        if (!supported) CHECK_MSG(strstr(msg, "run.vectors") != NULL, "%s", msg);
        CHECK_MSG((case_open(&cv, "bench/scenes/plate_clamped.json", "bhem", 4, 1e-3, sv) == 0) == supported, "%s", set);
        case_close(&cv);
    }
    const char *sets2[] = { "run.threads=2", NULL };
    asm_case c;
    const int rc = case_open(&c, "bench/scenes/plate_clamped.json", "rmtr", 4, 1e-3, sets2);
    CHECK_EQ_INT(rc == 0, sb_assemble_have_threads());
    case_close(&c);
    const char *sets0[] = { "run.threads=0", NULL };
    CHECK(case_open(&c, "bench/scenes/plate_clamped.json", "rmtr", 4, 1e-3, sets0) != 0);
    case_close(&c);
}

static const sb_test_case cases[] = {
    SB_CASE(reference_kernel_is_the_old_arithmetic),
    SB_CASE(fast_kernel_threads_and_agreement),
    SB_CASE(runs_identical_for_any_thread_count),
    SB_CASE(threads_refused_when_unavailable),
    SB_END
};

int main(int argc, char **argv) { return sb_test_main(argc, argv, cases); }
