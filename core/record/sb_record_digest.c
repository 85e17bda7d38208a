/* sb_record_digest.c — `shellbench digest`: a finished record rewritten as
 * the part of it that reports read (docs/reproducibility.md "Committed
 * records").
 *
 * A record keeps, beside its figures, data for looking at the run: the
 * sample grid of every step (/steps, with the method's own triangles), and at
 * the end the displacement, the reference grid and its triangulation (the
 * XDMF views), and the dof vector /final/x (what `render` and `inspect`
 * rebuild the surface from).  Reports need none of these: tables, diagrams
 * and errors come from the attributes, /params, /stats, /history, /probes,
 * /error and the final sample grid /final/sample_st and /final/sample_pos
 * (errors against reference records).  A digest copies every object except
 * those (and /final/x only with drop_state), marks the root with the
 * attribute "digest" naming what it dropped, and is sealed like any record
 * (sb_checksum.c): it reads as the same run everywhere except where the
 * dropped data is asked for, which then fails with a sentence naming the
 * digest (sb_record_dropped).  The file is written beside the record and
 * renamed onto it, so an interrupted digest leaves the record intact.
 *
 * Datasets of DIGEST_MIN_BYTES or more are stored chunked with the
 * shuffle and deflate filters (HDF5's own, read back transparently by every
 * reader), in the HDF5 1.10 file format: iteration histories of doubles
 * shrink 2-4x and their integer columns 10x or more, small records by about
 * a fifth, which is what keeps results/ small.  The values are
 * copied bit for bit.  The root attribute "digest_storage" names the filters;
 * a digest written before it (uncompressed) is rewritten once, compressed,
 * when digested again. */
#include "sb_record.h"
#include "sb_record_io.h"
#include "sb_output.h"

#include <errno.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* what a digest leaves out; /final/x last (kept unless drop_state) */
static const char *const dropped[] = { "/steps", "/final/displacement", "/final/sample_ref", "/final/triangles",
                                       "/final/x", NULL };
enum { N_ALWAYS = 4 };

enum { DIGEST_MIN_BYTES = 256, DIGEST_CHUNK_BYTES = 1 << 20, DIGEST_DEFLATE_LEVEL = 6 };
static const char digest_storage[] = "HDF5 1.10 file format; datasets of 256 bytes or more chunked, shuffle + deflate level 6";

typedef struct digest_ctx {
    hid_t dst;
    int drop_state;
    int bad;
    char path[256];          /* the object being copied */
} digest_ctx;

static int is_dropped(const digest_ctx *c, const char *path)
{
    for (int i = 0; dropped[i]; i++)
        if (!strcmp(path, dropped[i])) return i < N_ALWAYS || c->drop_state;
    return 0;
}

/* a group below `path` holds something dropped: it is rebuilt, not copied whole */
static int holds_dropped(const digest_ctx *c, const char *path)
{
    const size_t n = strlen(path);
    for (int i = 0; dropped[i]; i++)
        if ((i < N_ALWAYS || c->drop_state) && !strncmp(dropped[i], path, n) && dropped[i][n] == '/') return 1;
    return !strcmp(path, "");
}

/* attribute `name` of src copied onto dst (records hold fixed-size types only) */
static herr_t copy_attr(hid_t src, const char *name, const H5A_info_t *info, void *data)
{
    (void)info;
    hid_t *dst = data;
    hid_t a = H5Aopen(src, name, H5P_DEFAULT);
    hid_t t = a < 0 ? -1 : H5Aget_type(a), s = a < 0 ? -1 : H5Aget_space(a);
    int bad = a < 0 || t < 0 || s < 0 || H5Tdetect_class(t, H5T_VLEN) != 0 || H5Tis_variable_str(t) != 0;
    hssize_t np = bad ? 0 : H5Sget_simple_extent_npoints(s);
    size_t sz = bad ? 0 : H5Tget_size(t) * (size_t)(np > 0 ? np : 1);
    void *buf = bad ? NULL : malloc(sz ? sz : 1);
    if (!buf || H5Aread(a, t, buf) < 0) bad = 1;
    if (!bad) {
        hid_t b = H5Acreate2(*dst, name, t, s, H5P_DEFAULT, H5P_DEFAULT);
        if (b < 0 || H5Awrite(b, t, buf) < 0) bad = 1;
        if (b >= 0) H5Aclose(b);
    }
    free(buf);
    if (s >= 0) H5Sclose(s);
    if (t >= 0) H5Tclose(t);
    if (a >= 0) H5Aclose(a);
    return bad ? -1 : 0;
}

static int copy_attrs(hid_t src, hid_t dst)
{
    hsize_t idx = 0;
    return H5Aiterate2(src, H5_INDEX_NAME, H5_ITER_INC, &idx, copy_attr, &dst) < 0 ? -1 : 0;
}

static int copy_group(digest_ctx *c, hid_t src, hid_t dst, const char *path);

/* Dataset `name` of src into dst, chunked and compressed when it has
 * DIGEST_MIN_BYTES or more (below it deflate saves nothing; else, and for
 * types the filters do not
 * suit, copied as it is).  Chunks cover whole rows, at most about
 * DIGEST_CHUNK_BYTES each.  Returns 0 or -1. */
static int copy_dataset(hid_t src, const char *name, hid_t dst)
{
    hid_t d = H5Dopen2(src, name, H5P_DEFAULT);
    hid_t t = d < 0 ? -1 : H5Dget_type(d), sp = d < 0 ? -1 : H5Dget_space(d);
    int rank = sp < 0 ? -1 : H5Sget_simple_extent_ndims(sp);
    hsize_t dims[H5S_MAX_RANK], chunk[H5S_MAX_RANK];
    hssize_t np = sp < 0 ? -1 : H5Sget_simple_extent_npoints(sp);
    int plain = d < 0 || t < 0 || rank < 1 || rank > H5S_MAX_RANK || (size_t)np * H5Tget_size(t) < DIGEST_MIN_BYTES ||
                H5Tdetect_class(t, H5T_VLEN) != 0 || H5Tis_variable_str(t) != 0 ||
                H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0 || H5Zfilter_avail(H5Z_FILTER_SHUFFLE) <= 0;
    int bad = 0;
    if (!plain) {
        H5Sget_simple_extent_dims(sp, dims, NULL);
        size_t tsz = H5Tget_size(t), row = tsz;
        for (int i = 1; i < rank; i++) { chunk[i] = dims[i]; row *= (size_t)dims[i]; }
        hsize_t rows = row ? (hsize_t)(DIGEST_CHUNK_BYTES / row) : 1;
        chunk[0] = rows < 1 ? 1 : rows > dims[0] ? dims[0] : rows;
        void *buf = malloc(tsz * (size_t)np);
        hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE), o = -1;
        bad = !buf || dcpl < 0 || H5Pset_chunk(dcpl, rank, chunk) < 0 || H5Pset_shuffle(dcpl) < 0 ||
              H5Pset_deflate(dcpl, DIGEST_DEFLATE_LEVEL) < 0 || H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0;
        if (!bad) o = H5Dcreate2(dst, name, t, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT);
        bad = bad || o < 0 || H5Dwrite(o, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0 || copy_attrs(d, o);
        if (o >= 0) H5Dclose(o);
        if (dcpl >= 0) H5Pclose(dcpl);
        free(buf);
    }
    if (sp >= 0) H5Sclose(sp);
    if (t >= 0) H5Tclose(t);
    if (d >= 0) H5Dclose(d);
    if (plain) bad = H5Ocopy(src, name, dst, name, H5P_DEFAULT, H5P_DEFAULT) < 0;
    return bad ? -1 : 0;
}

static herr_t copy_link(hid_t src, const char *name, const H5L_info_t *info, void *data)
{
    (void)info;
    digest_ctx *c = data;
    char parent[256], path[256];
    snprintf(parent, sizeof parent, "%s", c->path);
    if ((size_t)snprintf(path, sizeof path, "%s/%s", parent, name) >= sizeof path) return -1;
    if (is_dropped(c, path)) return 0;
    hid_t dst = c->dst;
    H5O_info_t oi;   /* HDF5 1.10 API (Debian 12) */
    if (H5Oget_info_by_name2(src, name, &oi, H5O_INFO_BASIC, H5P_DEFAULT) < 0) return -1;
    int bad = 0;
    if (oi.type == H5O_TYPE_GROUP && holds_dropped(c, path)) {
        hid_t gs = H5Gopen2(src, name, H5P_DEFAULT);
        hid_t gd = gs < 0 ? -1 : H5Gcreate2(dst, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        bad = gs < 0 || gd < 0 || copy_attrs(gs, gd) || copy_group(c, gs, gd, path);
        if (gd >= 0) H5Gclose(gd);
        if (gs >= 0) H5Gclose(gs);
    } else if (oi.type == H5O_TYPE_GROUP) {
        hid_t gs = H5Gopen2(src, name, H5P_DEFAULT);
        hid_t gd = gs < 0 ? -1 : H5Gcreate2(dst, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        bad = gs < 0 || gd < 0 || copy_attrs(gs, gd) || copy_group(c, gs, gd, path);
        if (gd >= 0) H5Gclose(gd);
        if (gs >= 0) H5Gclose(gs);
    } else if (oi.type == H5O_TYPE_DATASET) {
        bad = copy_dataset(src, name, dst);
    } else {
        bad = H5Ocopy(src, name, dst, name, H5P_DEFAULT, H5P_DEFAULT) < 0;
    }
    snprintf(c->path, sizeof c->path, "%s", parent);
    c->dst = dst;
    return bad ? -1 : 0;
}

/* every link of src below path, into dst */
static int copy_group(digest_ctx *c, hid_t src, hid_t dst, const char *path)
{
    snprintf(c->path, sizeof c->path, "%s", path);
    c->dst = dst;
    hsize_t idx = 0;
    return H5Literate(src, H5_INDEX_NAME, H5_ITER_INC, &idx, copy_link, c) < 0 ? -1 : 0;
}

static int write_digest(const char *path, const char *tmp, int drop_state, char *note, size_t notelen)
{
    hid_t src = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (src < 0) return -1;
    hid_t fcpl = H5Pcreate(H5P_FILE_CREATE), fapl = H5Pcreate(H5P_FILE_ACCESS), dst = -1;
    /* as sb_record_write: a user block for the checksum, dense root attributes;
     * unlike a record, the HDF5 1.10 file format (readable by HDF5 1.10 and
     * later, Debian 12's is 1.10.8): its compact object headers and its
     * single-chunk index make a small digest about 20 % smaller than in the
     * 1.8 format records use, where every chunked dataset costs a B-tree
     * (measured on four records: 1.8 format 7 % smaller than the record,
     * 1.10 format 31 %) */
    if (fcpl >= 0 && fapl >= 0 && H5Pset_attr_phase_change(fcpl, 0, 0) >= 0 &&
        H5Pset_userblock(fcpl, SB_RECORD_USERBLOCK) >= 0 &&
        H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110) >= 0)
        dst = H5Fcreate(tmp, H5F_ACC_TRUNC, fcpl, fapl);
    if (fcpl >= 0) H5Pclose(fcpl);
    if (fapl >= 0) H5Pclose(fapl);
    digest_ctx c = { dst, drop_state, 0, "" };
    int bad = dst < 0 || copy_attrs(src, dst) || copy_group(&c, src, dst, "");
    if (!bad) {
        size_t k = (size_t)snprintf(note, notelen, "shellbench digest: dropped");
        for (int i = 0; dropped[i] && k < notelen; i++)
            if (i < N_ALWAYS || drop_state) k += (size_t)snprintf(note + k, notelen - k, " %s", dropped[i]);
        sb_h5w w = { "" };
        /* an older digest keeps its own note of what it dropped, unless this
         * digest drops its state too (then the note above says it all) */
        if (drop_state && H5Aexists(dst, "digest") > 0 && H5Adelete(dst, "digest") < 0) bad = 1;
        bad = bad || (H5Aexists(dst, "digest") <= 0 && sb_h5w_attr_str(&w, dst, "digest", note) != 0) ||
              (H5Aexists(dst, "digest_storage") <= 0 && sb_h5w_attr_str(&w, dst, "digest_storage", digest_storage) != 0);
    }
    if (dst >= 0 && H5Fclose(dst) < 0) bad = 1;
    H5Fclose(src);
    return bad ? -1 : 0;
}

static int digest_locked(const char *path, int drop_state, int *already, char *err, size_t errlen);

/* The record is rewritten under its writer's lock (OUT.lock, sb_output.h):
 * a run that is writing it, or another digest, makes this one refuse. */
static void record_dir(const char *path, char *dir, size_t len)
{
    const char *slash = strrchr(path, '/');
    if (!slash) snprintf(dir, len, ".");
    else if (slash == path) snprintf(dir, len, "/");
    else snprintf(dir, len, "%.*s", (int)(slash - path), path);
}

int sb_record_digest(const char *path, int drop_state, int *already, char *err, size_t errlen)
{
    sb_output_lock lk;
    char dir[4200];
    *already = 0;
    record_dir(path, dir, sizeof dir);
    /* a missing record or an unwritable directory: nothing will be written,
     * so no lock is taken (its file could not be made either); digest_locked
     * says why after reading what it can */
    if (access(path, F_OK) != 0 || access(dir, W_OK | X_OK) != 0)
        return digest_locked(path, drop_state, already, err, errlen);
    if (sb_output_lock_take(&lk, path, err, errlen)) return SB_ERR_INPUT;
    int rc = digest_locked(path, drop_state, already, err, errlen);
    sb_output_lock_release(&lk);
    return rc;
}

static int digest_locked(const char *path, int drop_state, int *already, char *err, size_t errlen)
{
    *already = 0;
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    /* the record must read (checksum, format) and not be a checkpoint */
    int rc = sb_h5r_open(&r, &f);
    /* a digest is left alone; one written before digests were compressed is
     * rewritten once (its "digest" attribute is then replaced, not doubled),
     * and one that still holds its state is rewritten without it when
     * drop_state asks (a committed digest slimmed later) */
    if (!rc && H5Aexists(f, "digest") > 0 && H5Aexists(f, "digest_storage") > 0 &&
        !(drop_state && H5Lexists(f, "/final/x", H5P_DEFAULT) > 0))
        *already = 1;
    if (!rc && H5Lexists(f, "/resume", H5P_DEFAULT) > 0) {
        snprintf(err, errlen, "cannot digest %s: it is a checkpoint of an unfinished run (it holds /resume), not a "
                 "finished record: finish the run with --resume, then digest its record", path);
        rc = SB_ERR_INPUT;
    }
    sb_h5r_close(&r, f);
    if (rc || *already) return rc;
    sb_output_kind kind;
    if (sb_output_check(path, "record", &kind, err, errlen)) return SB_ERR_INPUT;
    /* the digest is written beside the record and renamed onto it: its
     * directory must be writable, which is checked before any copying */
    char dir[4200];
    record_dir(path, dir, sizeof dir);
    if (access(dir, W_OK | X_OK) != 0) {
        snprintf(err, errlen, "cannot digest %s: its directory %s is not writable (%s); the digest is written beside "
                 "the record and renamed onto it: make the directory writable or digest a copy elsewhere", path, dir,
                 strerror(errno));
        return SB_ERR_INPUT;
    }
    char tmp[4200], note[256];
    if ((size_t)snprintf(tmp, sizeof tmp, "%s.digest.tmp", path) >= sizeof tmp) {
        snprintf(err, errlen, "cannot digest %s: path too long", path);
        return SB_ERR_INPUT;
    }
    unlink(tmp);
    H5E_auto2_t old_fn = NULL;
    void *old_data = NULL;
    H5Eget_auto2(H5E_DEFAULT, &old_fn, &old_data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    int bad = write_digest(path, tmp, drop_state, note, sizeof note);
    H5Eset_auto2(H5E_DEFAULT, old_fn, old_data);
    if (bad) {
        unlink(tmp);
        snprintf(err, errlen, "cannot digest %s: HDF5 failed copying it", path);
        return SB_ERR_IO;
    }
    if ((rc = sb_record_seal(tmp, err, errlen)) != SB_OK || sb_record_fsync_path(tmp) != 0 || rename(tmp, path) != 0) {
        if (!rc) snprintf(err, errlen, "cannot digest %s: %s", path, strerror(errno));
        unlink(tmp);
        return rc ? rc : SB_ERR_IO;
    }
    sb_record_fsync_dir(path);
    return SB_OK;
}
