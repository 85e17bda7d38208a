/* sb_record_h5r.c — HDF5 reading helpers of the recording module
 * (sb_record_io.h): every failure is one sentence naming the file and the
 * object, never a crash or HDF5's own error stack. */
#include "sb_record_io.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int sb_h5r_fail(sb_h5r *r, int status, const char *what, const char *name)
{
    snprintf(r->err, r->errlen, "cannot read record %s: %s %s (file truncated, corrupt or not a shellbench record)",
             r->path, what, name);
    return status;
}

/* Scalar fixed-length string attribute of any length, into a new buffer. */
int sb_h5r_attr_str_alloc(sb_h5r *r, hid_t loc, const char *name, char **out)
{
    *out = NULL;
    hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
    if (a < 0) return sb_h5r_fail(r, SB_ERR_INPUT, "missing attribute", name);
    hid_t t = H5Aget_type(a);
    int rc = SB_OK;
    if (t < 0 || H5Tget_class(t) != H5T_STRING || H5Tis_variable_str(t) != 0) {
        rc = sb_h5r_fail(r, SB_ERR_INPUT, "attribute is not a fixed-length string:", name);
    } else if (!(*out = calloc(H5Tget_size(t) + 1, 1))) {
        rc = SB_ERR_NOMEM;
        snprintf(r->err, r->errlen, "out of memory reading %s", r->path);
    } else if (H5Aread(a, t, *out) < 0) {
        rc = sb_h5r_fail(r, SB_ERR_IO, "cannot read attribute", name);
    }
    if (rc) {
        free(*out);
        *out = NULL;
    }
    if (t >= 0) H5Tclose(t);
    H5Aclose(a);
    return rc;
}

/* Scalar string attribute of fixed length, copied (truncated) into buf. */
int sb_h5r_attr_str(sb_h5r *r, hid_t loc, const char *name, char *buf, size_t len)
{
    char *tmp;
    int rc = sb_h5r_attr_str_alloc(r, loc, name, &tmp);
    if (!rc) snprintf(buf, len, "%s", tmp);
    free(tmp);
    return rc;
}

/* Scalar numeric attribute converted to mtype (HDF5 converts int <-> float). */
int sb_h5r_attr_num(sb_h5r *r, hid_t loc, const char *name, hid_t mtype, void *v)
{
    hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
    if (a < 0) return sb_h5r_fail(r, SB_ERR_INPUT, "missing attribute", name);
    hid_t t = H5Aget_type(a), sp = H5Aget_space(a);
    H5T_class_t c = t < 0 ? H5T_NO_CLASS : H5Tget_class(t);
    int rc = SB_OK;
    if ((c != H5T_INTEGER && c != H5T_FLOAT) || sp < 0 || H5Sget_simple_extent_npoints(sp) != 1)
        rc = sb_h5r_fail(r, SB_ERR_INPUT, "attribute is not a number:", name);
    else if (H5Aread(a, mtype, v) < 0)
        rc = sb_h5r_fail(r, SB_ERR_IO, "cannot read attribute", name);
    if (sp >= 0) H5Sclose(sp);
    if (t >= 0) H5Tclose(t);
    H5Aclose(a);
    return rc;
}

int sb_h5r_attr_int(sb_h5r *r, hid_t loc, const char *name, int *v)
{
    return sb_h5r_attr_num(r, loc, name, H5T_NATIVE_INT, v);
}

int sb_h5r_attr_dbl(sb_h5r *r, hid_t loc, const char *name, double *v)
{
    return sb_h5r_attr_num(r, loc, name, H5T_NATIVE_DOUBLE, v);
}

/* Whole numeric dataset `name` (path relative to loc) of the given rank,
 * converted to mtype (elements of esize bytes) into a new buffer (at least
 * one element allocated, so empty datasets give a valid pointer). */
int sb_h5r_dset(sb_h5r *r, hid_t loc, const char *name, int rank, hid_t mtype, size_t esize,
                     hsize_t *dims, void **out)
{
    *out = NULL;
    if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) {
        /* a digest (sb_record_digest.c) dropped it on purpose: say so */
        hid_t f = H5Iget_file_id(loc);
        const int digest = f >= 0 && H5Aexists(f, "digest") > 0;
        if (f >= 0) H5Fclose(f);
        if (digest) {
            snprintf(r->err, r->errlen, "cannot read %s from %s: the record is a digest (`shellbench digest`), which "
                     "keeps what reports read but not the run's states; run the scene again to draw or inspect it",
                     name, r->path);
            return SB_ERR_INPUT;
        }
        return sb_h5r_fail(r, SB_ERR_INPUT, "missing dataset", name);
    }
    hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
    if (d < 0) return sb_h5r_fail(r, SB_ERR_IO, "cannot open dataset", name);
    hid_t sp = H5Dget_space(d);
    int rc = SB_OK;
    if (sp < 0 || H5Sget_simple_extent_ndims(sp) != rank) {
        rc = sb_h5r_fail(r, SB_ERR_INPUT, "dataset has the wrong rank:", name);
    } else {
        H5Sget_simple_extent_dims(sp, dims, NULL);
        hsize_t n = 1;
        for (int i = 0; i < rank; i++) n *= dims[i];
        if (n > (hsize_t)(SIZE_MAX / esize) - 1) {
            rc = sb_h5r_fail(r, SB_ERR_INPUT, "dataset is implausibly large:", name);
        } else {
            *out = malloc((size_t)(n ? n : 1) * esize);
            if (!*out) rc = SB_ERR_NOMEM, snprintf(r->err, r->errlen, "out of memory reading %s", r->path);
            else if (n > 0 && H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, *out) < 0)
                rc = sb_h5r_fail(r, SB_ERR_IO, "cannot read dataset", name);
        }
    }
    if (sp >= 0) H5Sclose(sp);
    H5Dclose(d);
    if (rc) {
        free(*out);
        *out = NULL;
    }
    return rc;
}

/* Open PATH and check it is a shellbench record of a layout we read. */
/* Silences HDF5's error printing (restored by close_record, which must follow
 * every open_record), checks the path and opens a shellbench record. */
int sb_h5r_open(sb_h5r *r, hid_t *file)
{
    *file = -1;
    H5Eget_auto2(H5E_DEFAULT, &r->old_fn, &r->old_data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    if (!r->path || !r->path[0]) {
        snprintf(r->err, r->errlen, "no record file given");
        return SB_ERR_INPUT;
    }
    struct stat st;
    if (stat(r->path, &st) != 0) {
        snprintf(r->err, r->errlen, "cannot read record %s: %s", r->path, strerror(errno));
        return SB_ERR_IO;
    }
    if (!S_ISREG(st.st_mode)) {
        snprintf(r->err, r->errlen, "cannot read record %s: not a regular file", r->path);
        return SB_ERR_INPUT;
    }
    /* the checksum first, from the raw bytes: HDF5 never parses an altered file (sb_checksum.c) */
    int sealed = 0, vrc = sb_record_verify(r->path, &sealed, r->err, r->errlen);
    if (vrc) return vrc;
    if (H5Fis_hdf5(r->path) <= 0) {
        snprintf(r->err, r->errlen, "%s is not an HDF5 file, so not a shellbench record", r->path);
        return SB_ERR_INPUT;
    }
    /* strong close degree: closing the file closes every object still open
     * in it, so no error path of a reader (nor of HDF5 itself on a corrupt
     * file) can leave a handle behind */
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    if (fapl >= 0 && H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG) < 0) {
        H5Pclose(fapl);
        fapl = -1;
    }
    hid_t f = H5Fopen(r->path, H5F_ACC_RDONLY, fapl >= 0 ? fapl : H5P_DEFAULT);
    if (fapl >= 0) H5Pclose(fapl);
    if (f < 0) {
        snprintf(r->err, r->errlen, "cannot open record %s: HDF5 cannot open it (truncated or corrupt file?)", r->path);
        return SB_ERR_IO;
    }
    char fmt[64] = "";
    int version = 0;
    if (H5Aexists(f, "format") <= 0 || sb_h5r_attr_str(r, f, "format", fmt, sizeof fmt) != SB_OK ||
        strcmp(fmt, SB_RECORD_FORMAT_NAME) != 0) {
        snprintf(r->err, r->errlen, "%s is an HDF5 file but not a shellbench run record (no \"format\" = \"%s\" attribute)",
                 r->path, SB_RECORD_FORMAT_NAME);
        H5Fclose(f);
        return SB_ERR_INPUT;
    }
    int rc = sb_h5r_attr_int(r, f, "format_version", &version);
    if (rc == SB_OK && (version < 1 || version > SB_RECORD_FORMAT_VERSION)) {
        snprintf(r->err, r->errlen, "%s has record format version %d; this build reads versions 1 to %d",
                 r->path, version, SB_RECORD_FORMAT_VERSION);
        rc = SB_ERR_INPUT;
    }
    if (!rc && version >= 2 && !sealed) {
        snprintf(r->err, r->errlen, "cannot read record %s: it has no checksum, which its format version %d requires "
                 "(the file was altered or damaged after it was written)", r->path, version);
        rc = SB_ERR_INPUT;
    }
    if (rc) {
        H5Fclose(f);
        return rc;
    }
    *file = f;
    return SB_OK;
}

void sb_h5r_close(sb_h5r *r, hid_t f)
{
    if (f >= 0) H5Fclose(f);
    H5Eset_auto2(H5E_DEFAULT, r->old_fn, r->old_data);
}
