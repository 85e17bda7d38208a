/* sb_scene.c — scene files: reading, top-level parse and validation, name
 * resolution, and the load / motion ramp factors.  The sections are parsed in
 * sb_scene_domain.c, sb_scene_material.c, sb_scene_loads.c and
 * sb_scene_probes.c; the format is documented in docs/scene_format.md. */
#include "sb_scene.h"

#include <errno.h>
#include <fcntl.h>
#include <jansson.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sb_geometry.h"
#include "sb_json_pos.h"
#include "sb_scene_json.h"

#define MAX_FILE_BYTES (16u << 20)
#define DEFAULT_RESOLUTION 8

static int fail_at(const char *file, const char *text, size_t len, size_t off, char *err,
                   size_t errlen, int status, const char *msg)
{
    int line, col;
    sb_json_offset_linecol(text ? text : "", text ? len : 0, off, &line, &col);
    if (err && errlen) snprintf(err, errlen, "%s:%d:%d: at /: %s", file, line, col, msg);
    return status;
}

/* A symmetry edge must lie in a plane normal to its axis (reference geometry). */
static int check_symmetry(sbj_ctx *c, const sb_scene *sc)
{
    static const char axis_name[] = "xyz";
    for (int b = 0; b < sc->n_bcs; b++) {
        const sb_bc *bc = &sc->bcs[b];
        if (bc->kind != SB_BC_SYMMETRY) continue;
        for (int p = 0; p < bc->n_parts; p++) {
            const sb_part *pt = &bc->parts[p];
            double lo = INFINITY, hi = -INFINITY, scale = sb_domain_diameter(&sc->domain);
            for (int k = 0; k <= 8; k++) {
                double f = k / 8.0, s = pt->st0[0] + f * (pt->st1[0] - pt->st0[0]);
                double t = pt->st0[1] + f * (pt->st1[1] - pt->st0[1]);
                sb_jet3 X;
                sb_geometry_eval_st(sc, s, t, &X);
                lo = fmin(lo, X.x[bc->axis]);
                hi = fmax(hi, X.x[bc->axis]);
                for (int q = 0; q < 3; q++) scale = fmax(scale, fabs(X.x[q]));
            }
            if (hi - lo > 1e-9 * scale) {
                size_t mark = sbj_push(c, "boundary");
                sbj_push_index(c, (size_t)b);
                sbj_push(c, "on");
                sbj_push_index(c, (size_t)p);
                int r = sbj_fail(c, NULL, 0, "edge \"%s\" does not lie in a plane normal to %c (%c varies by %g)",
                                 pt->name, axis_name[bc->axis], axis_name[bc->axis], hi - lo);
                sbj_pop(c, mark);
                return r;
            }
        }
    }
    return SB_OK;
}

static int parse_root(sbj_ctx *c, const json_t *root, sb_scene *sc)
{
    static const char *const keys[] = { "name", "description", "domain", "geometry", "material",
                                        "loads", "boundary", "time", "probes", "reference",
                                        "resolution", "methods", "obstacles", "contact", NULL };
    long res = DEFAULT_RESOLUTION;
    int r, constrained = 0;

    if ((r = sbj_check_keys(c, root, keys))) return r;
    if ((r = sbj_get_string(c, root, "name", 1, sc->name, sizeof sc->name, NULL))) return r;
    if (!sbj_valid_name(sc->name))
        return sbj_fail(c, "name", 0, "must be 1..%d characters from [A-Za-z0-9_.-], got \"%s\"",
                        SB_NAME_LEN - 1, sc->name);
    if ((r = sbj_get_string(c, root, "description", 0, sc->description, sizeof sc->description, NULL)))
        return r;
    int res_i = DEFAULT_RESOLUTION, res_t = 0;
    if ((r = sbj_parse_resolution(c, root, "resolution", &res_i, &res_t))) return r;
    res = res_i;
    sc->default_res_t = res_t;
    sc->default_res = (int)res;
    if ((r = sbj_parse_domain(c, root, &sc->domain))) return r;
    if ((r = sbj_parse_geometry(c, root, &sc->domain, &sc->chart))) return r;
    if ((r = sbj_parse_material(c, root, &sc->material))) return r;
    if ((r = sbj_parse_time(c, root, &sc->time))) return r;
    if ((r = sbj_parse_loads(c, root, sc))) return r;
    if ((r = sbj_parse_boundary(c, root, sc))) return r;
    if ((r = sbj_parse_probes(c, root, sc))) return r;
    if ((r = sbj_parse_reference(c, root, sc))) return r;
    if ((r = sbj_parse_methods(c, root, sc))) return r;
    if ((r = check_symmetry(c, sc))) return r;
    if ((r = sbj_parse_obstacles(c, root, sc))) return r;
    for (int b = 0; b < sc->n_bcs; b++) constrained += sc->bcs[b].kind != SB_BC_FREE;
    if (sc->time.mode == SB_TIME_QUASI_STATIC && constrained == 0)
        return sbj_fail(c, json_object_get(root, "boundary") ? "boundary" : NULL, 0,
                        "a quasi-static scene needs at least one fixed, clamped, symmetry or moving "
                        "boundary condition (otherwise the equilibrium is not unique)");
    return SB_OK;
}

static int parse_buffer(const char *text, size_t len, const char *file, sb_scene *sc, char *err,
                        size_t errlen)
{
    json_error_t jerr;
    sbj_ctx c = { text, len, file, err, errlen, "" };
    size_t i = 0;
    const char *nul = memchr(text, '\0', len);
    int r;

    memset(sc, 0, sizeof *sc);
    /* an HDF5 file, or a shellbench record (its checksum user block first, sb_checksum.c) */
    if ((len >= 8 && memcmp(text, "\x89HDF\r\n\x1a\n", 8) == 0) ||
        (len >= 520 && memcmp(text + 512, "\x89HDF\r\n\x1a\n", 8) == 0 && strncmp(text, "shellbench record", 17) == 0))
        return fail_at(file, text, len, 0, err, errlen, SB_ERR_INPUT,
                       "this is an HDF5 file (a run record?), not a scene: read records with `shellbench report` "
                       "or `shellbench inspect`");
    if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) {   /* a UTF-8 byte-order mark: skipped */
        text += 3;
        len -= 3;
    }
    while (i < len && (text[i] == ' ' || text[i] == '\t' || text[i] == '\n' || text[i] == '\r')) i++;
    if (i == len) return fail_at(file, text, len, len, err, errlen, SB_ERR_INPUT, "empty file (expected a JSON object)");
    if (nul) return fail_at(file, text, len, (size_t)(nul - text), err, errlen, SB_ERR_INPUT,
                            "the file contains a NUL byte");
    json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES | JSON_DECODE_ANY, &jerr);
    if (!root) {
        if (err && errlen)
            snprintf(err, errlen, "%s:%d:%d: at /: invalid JSON: %s", file, jerr.line > 0 ? jerr.line : 1,
                     jerr.column > 0 ? jerr.column : 1, jerr.text);
        return SB_ERR_INPUT;
    }
    if (!json_is_object(root)) {
        r = sbj_fail(&c, NULL, 0, "a scene must be a JSON object, got %s", sbj_type_name(root));
        json_decref(root);
        return r;
    }
    if (strlen(file) >= sizeof sc->path) {
        json_decref(root);
        return fail_at(file, text, len, 0, err, errlen, SB_ERR_INPUT, "file path too long");
    }
    snprintf(sc->path, sizeof sc->path, "%s", file);
    r = parse_root(&c, root, sc);
    json_decref(root);
    if (r == SB_OK) {
        sc->json_text = malloc(len + 1);
        if (!sc->json_text) return fail_at(file, text, len, 0, err, errlen, SB_ERR_NOMEM, "out of memory");
        memcpy(sc->json_text, text, len);
        sc->json_text[len] = '\0';
    } else {
        char path[sizeof sc->path];
        memcpy(path, sc->path, sizeof path);
        sbj_free_obstacles(sc);
        memset(sc, 0, sizeof *sc);   /* nothing half-filled survives an error */
        memcpy(sc->path, path, sizeof path);
    }
    return r;
}

int sb_scene_parse_string(const char *text, const char *path_for_messages, sb_scene *scene,
                          char *err, size_t errlen)
{
    const char *file = path_for_messages ? path_for_messages : "<string>";
    if (!text || !scene) {
        if (scene) memset(scene, 0, sizeof *scene);
        if (err && errlen) snprintf(err, errlen, "%s:1:1: at /: no scene text given", file);
        return SB_ERR_INPUT;
    }
    int r = parse_buffer(text, strlen(text), file, scene, err, errlen);
    if (r && err && errlen) sb_escape_controls(err, errlen);
    return r;
}

int sb_scene_parse_buffer(const char *bytes, size_t len, const char *path_for_messages, sb_scene *scene, char *err,
                          size_t errlen)
{
    const char *file = path_for_messages ? path_for_messages : "<buffer>";
    if (!scene) return SB_ERR_INPUT;
    if (len > MAX_FILE_BYTES) {
        memset(scene, 0, sizeof *scene);
        if (err && errlen) snprintf(err, errlen, "%s:1:1: at /: too large (more than %u bytes)", file, MAX_FILE_BYTES);
        return SB_ERR_INPUT;
    }
    int r = parse_buffer(bytes ? bytes : "", bytes ? len : 0, file, scene, err, errlen);
    if (r && err && errlen) sb_escape_controls(err, errlen);
    return r;
}

/* The standard input under the names a shell gives it: scenes may come
 * from a pipe or a terminal there, not from any other non-regular file. */
static int is_stdin_path(const char *p)
{
    return strcmp(p, "/dev/stdin") == 0 || strncmp(p, "/dev/fd/", 8) == 0 || strncmp(p, "/proc/self/fd/", 14) == 0;
}

static const char *file_type(mode_t m)
{
    return S_ISDIR(m) ? "a directory" : S_ISCHR(m) ? "a character device" : S_ISBLK(m) ? "a block device"
         : S_ISFIFO(m) ? "a FIFO (named pipe)" : S_ISSOCK(m) ? "a socket" : "not a regular file";
}

/* Opens without blocking (a FIFO without a writer would block open() and a
 * read forever), then accepts regular files, and the standard input in
 * whatever form (blocking again: a pipe's writer may be slow). */
static int open_scene(const char *path, int *fd_out, char *err, size_t errlen)
{
    struct stat st;
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    *fd_out = -1;
    if (fd < 0) {
        if (err && errlen) snprintf(err, errlen, "%s:1:1: at /: cannot open file (%s)", path, strerror(errno));
        return SB_ERR_IO;
    }
    if (fstat(fd, &st) != 0) {
        if (err && errlen) snprintf(err, errlen, "%s:1:1: at /: cannot open file (%s)", path, strerror(errno));
        close(fd);
        return SB_ERR_IO;
    }
    if (!S_ISREG(st.st_mode) && (S_ISDIR(st.st_mode) || !is_stdin_path(path))) {
        if (err && errlen)
            snprintf(err, errlen, "%s:1:1: at /: is %s, not a scene file (scenes are read from regular files, or "
                     "from the standard input as /dev/stdin)", path, file_type(st.st_mode));
        close(fd);
        return SB_ERR_INPUT;
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags >= 0) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    *fd_out = fd;
    return SB_OK;
}

static int load_file(const char *path, sb_scene *scene, char *err, size_t errlen)
{
    int fd;
    char *buf = NULL;
    size_t len = 0, cap = 0;
    int r;

    memset(scene, 0, sizeof *scene);
    if (!path) {
        if (err && errlen) snprintf(err, errlen, "(null):1:1: at /: cannot open file (no path)");
        return SB_ERR_IO;
    }
    if ((r = open_scene(path, &fd, err, errlen))) return r;
    for (;;) {   /* read the whole file; works for pipes too */
        if (len == cap) {
            size_t ncap = cap ? 2 * cap : 4096;
            char *nb = ncap <= MAX_FILE_BYTES + 1 ? realloc(buf, ncap) : NULL;
            if (!nb) {
                close(fd);
                free(buf);
                if (err && errlen)
                    snprintf(err, errlen, "%s:1:1: at /: file too large (more than %u bytes)", path, MAX_FILE_BYTES);
                return SB_ERR_INPUT;
            }
            buf = nb;
            cap = ncap;
        }
        ssize_t n = read(fd, buf + len, cap - len);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            int e = errno;
            close(fd);
            free(buf);
            if (err && errlen) snprintf(err, errlen, "%s:1:1: at /: read error (%s)", path, strerror(e));
            return SB_ERR_IO;
        }
        if (n == 0) break;
        len += (size_t)n;
    }
    close(fd);
    r = parse_buffer(buf ? buf : "", len, path, scene, err, errlen);
    free(buf);
    return r;
}

int sb_scene_load(const char *path, sb_scene *scene, char *err, size_t errlen)
{
    int r = load_file(path, scene, err, errlen);
    if (r && err && errlen) sb_escape_controls(err, errlen);   /* scene text and paths reach a terminal */
    return r;
}

void sb_scene_free(sb_scene *scene)
{
    if (!scene) return;
    free(scene->json_text);
    scene->json_text = NULL;
    sbj_free_obstacles(scene);
    scene->n_obstacles = 0;
}

static int is_file(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0 && S_ISREG(st.st_mode);
}

static int try_path(char *out, size_t len, const char *fmt, const char *a, const char *b)
{
    int n = snprintf(out, len, fmt, a, b);
    return n > 0 && (size_t)n < len && is_file(out);
}

int sb_project_file(const char *rel, char *path, size_t len)
{
    /* the places sb_scene_resolve looks for bench/scenes: the working
     * directory, $SB_ROOT, and the directory above the executable's */
    if (!rel || !*rel || rel[0] == '/') return SB_ERR_INPUT;
    if (try_path(path, len, "%s%s", "", rel)) return SB_OK;
    const char *root = getenv("SB_ROOT");
    if (root && *root && try_path(path, len, "%s/%s", root, rel)) return SB_OK;
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            if (try_path(path, len, "%s/../%s", exe, rel)) return SB_OK;
        }
    }
    return SB_ERR_IO;
}

int sb_scene_resolve(const char *name_or_path, char *path, size_t len)
{
    if (!name_or_path || !path || len == 0) return SB_ERR_INPUT;
    struct stat st;
    /* something that is there and is not a directory (a regular file, a FIFO,
     * a device) is the path the user meant: the loader refuses what it cannot
     * read with what it is, instead of "not found" */
    if (is_file(name_or_path) || strchr(name_or_path, '/') ||
        (stat(name_or_path, &st) == 0 && !S_ISDIR(st.st_mode))) {
        /* a path: found when something is there (the loader takes regular
         * files and the standard input, and refuses the rest with a sentence) */
        int n = snprintf(path, len, "%s", name_or_path);
        return (n >= 0 && (size_t)n < len && stat(path, &st) == 0) ? SB_OK : SB_ERR_IO;
    }
    const char *root = getenv("SB_ROOT");
    char exe[PATH_MAX];
    ssize_t n;
    if (try_path(path, len, "%sbench/scenes/%s.json", "", name_or_path)) return SB_OK;
    if (root && *root && try_path(path, len, "%s/bench/scenes/%s.json", root, name_or_path)) return SB_OK;
    n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            if (try_path(path, len, "%s/../bench/scenes/%s.json", exe, name_or_path)) return SB_OK;
        }
    }
    snprintf(path, len, "%s", name_or_path);   /* not found: the loader reports it */
    return SB_ERR_IO;
}

double sb_load_factor(const sb_scene *s, const sb_load *ld, int step)
{
    /* ramp_steps > 0: min(1, step / ramp_steps).  ramp_steps = 0: dynamic
     * scenes apply the full load from step 1; quasi-static scenes ramp
     * linearly over all steps (the load-stepping convention). */
    double f;
    if (step <= 0) return 0;
    if (ld->ramp_steps > 0) f = (double)step / ld->ramp_steps;
    else if (s->time.mode == SB_TIME_DYNAMIC) f = 1;
    else f = (double)step / (s->time.steps > 0 ? s->time.steps : 1);
    return f < 1 ? f : 1;
}

double sb_bc_motion_factor(const sb_scene *s, const sb_bc *bc, int step)
{
    /* min(1, step / ramp_steps); ramp_steps = 0 means over all steps (in
     * dynamic scenes step/ramp_steps = t / (ramp_steps dt)) */
    int ramp = bc->ramp_steps > 0 ? bc->ramp_steps : (s->time.steps > 0 ? s->time.steps : 1);
    if (step <= 0) return 0;
    if (bc->schedule.n > 0)   /* keyframes in seconds (dynamic) or load steps */
        return sb_schedule_factor(&bc->schedule, s->time.mode == SB_TIME_DYNAMIC ? step * s->time.dt : (double)step);
    double f = (double)step / ramp;
    return f < 1 ? f : 1;
}

double sb_obstacle_motion_factor(const sb_scene *s, const sb_obstacle_spec *o, int step)
{
    /* as sb_bc_motion_factor: min(1, step / ramp_steps), 0 = over all steps */
    int ramp = o->ramp_steps > 0 ? o->ramp_steps : (s->time.steps > 0 ? s->time.steps : 1);
    if (step <= 0 || !o->moving) return 0;
    if (o->schedule.n > 0)
        return sb_schedule_factor(&o->schedule, s->time.mode == SB_TIME_DYNAMIC ? step * s->time.dt : (double)step);
    double f = (double)step / ramp;
    return f < 1 ? f : 1;
}
