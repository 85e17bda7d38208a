/* sb_record_h5w.c — small HDF5 writers used by sb_record_write.c.  Each
 * returns 0, or -1 after noting the first object that failed in w->failed
 * (HDF5's own error printing is silenced by the caller).  Strings are
 * fixed-length and NUL-terminated, integers 64-bit (attributes) or 32-bit
 * (index datasets) little-endian, reals IEEE double. */
#include "sb_record_io.h"

#include <stdio.h>
#include <string.h>

/* Notes "<object path>/<name>" (or just name when loc < 0) as the failure. */
int sb_h5w_fail(sb_h5w *w, hid_t loc, const char *name)
{
    if (w->failed[0]) return -1;
    char where[96] = "";
    if (loc >= 0 && H5Iget_name(loc, where, sizeof where) <= 0) where[0] = 0;
    size_t n = strlen(where);
    snprintf(w->failed, sizeof w->failed, "%s%s%s", where, n && where[n - 1] != '/' ? "/" : "", name);
    return -1;
}

static int sb_h5w_attr_raw(sb_h5w *w, hid_t loc, const char *name, hid_t ftype, hid_t mtype,
                           hid_t space, const void *buf)
{
    hid_t a = H5Acreate2(loc, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0) return sb_h5w_fail(w, loc, name);
    herr_t e = H5Awrite(a, mtype, buf);
    H5Aclose(a);
    return e < 0 ? sb_h5w_fail(w, loc, name) : 0;
}

static int sb_h5w_attr_scalar(sb_h5w *w, hid_t loc, const char *name, hid_t ftype, hid_t mtype, const void *v)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    if (sp < 0) return sb_h5w_fail(w, loc, name);
    int rc = sb_h5w_attr_raw(w, loc, name, ftype, mtype, sp, v);
    H5Sclose(sp);
    return rc;
}

int sb_h5w_attr_long(sb_h5w *w, hid_t loc, const char *name, long v)
{
    return sb_h5w_attr_scalar(w, loc, name, H5T_STD_I64LE, H5T_NATIVE_LONG, &v);
}

int sb_h5w_attr_dbl(sb_h5w *w, hid_t loc, const char *name, double v)
{
    return sb_h5w_attr_scalar(w, loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &v);
}

/* Fixed-length, NUL-terminated string sized to its content. */
int sb_h5w_attr_str(sb_h5w *w, hid_t loc, const char *name, const char *s)
{
    if (!s) s = "";
    hid_t t = H5Tcopy(H5T_C_S1);
    if (t < 0 || H5Tset_size(t, strlen(s) + 1) < 0 || H5Tset_strpad(t, H5T_STR_NULLTERM) < 0) {
        if (t >= 0) H5Tclose(t);
        return sb_h5w_fail(w, loc, name);
    }
    int rc = sb_h5w_attr_scalar(w, loc, name, t, t, s);
    H5Tclose(t);
    return rc;
}

/* Array of n fixed-length strings, each `width` bytes in buf. */
hid_t sb_h5w_str_type(size_t width)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    if (t < 0) return t;
    if (H5Tset_size(t, width) < 0 || H5Tset_strpad(t, H5T_STR_NULLTERM) < 0) {
        H5Tclose(t);
        return -1;
    }
    return t;
}

int sb_h5w_attr_str_array(sb_h5w *w, hid_t loc, const char *name, int n, size_t width, const char *buf)
{
    hsize_t d = (hsize_t)n;
    hid_t sp = H5Screate_simple(1, &d, NULL);
    hid_t t = sb_h5w_str_type(width);
    int rc = (sp < 0 || t < 0) ? sb_h5w_fail(w, loc, name) : sb_h5w_attr_raw(w, loc, name, t, t, sp, buf);
    if (t >= 0) H5Tclose(t);
    if (sp >= 0) H5Sclose(sp);
    return rc;
}

/* Dataset of the given shape; zero-sized shapes create an empty dataset. */
static int sb_h5w_dset(sb_h5w *w, hid_t loc, const char *name, hid_t ftype, hid_t mtype,
                int rank, const hsize_t *dims, const void *buf, const char *units)
{
    hsize_t n = 1;
    for (int i = 0; i < rank; i++) n *= dims[i];
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    if (sp < 0) return sb_h5w_fail(w, loc, name);
    hid_t d = H5Dcreate2(loc, name, ftype, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Sclose(sp);
    if (d < 0) return sb_h5w_fail(w, loc, name);
    int rc = 0;
    if (n > 0 && H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) rc = sb_h5w_fail(w, loc, name);
    if (!rc && units && sb_h5w_attr_str(w, d, "units", units)) rc = -1;
    H5Dclose(d);
    return rc;
}

int sb_h5w_dset_dbl(sb_h5w *w, hid_t loc, const char *name, int rank, const hsize_t *dims,
                    const double *buf, const char *units)
{
    return sb_h5w_dset(w, loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, rank, dims, buf, units);
}

int sb_h5w_dset_int(sb_h5w *w, hid_t loc, const char *name, int rank, const hsize_t *dims,
                    const int *buf, const char *units)
{
    return sb_h5w_dset(w, loc, name, H5T_STD_I32LE, H5T_NATIVE_INT, rank, dims, buf, units);
}

int sb_h5w_dset_long(sb_h5w *w, hid_t loc, const char *name, int rank, const hsize_t *dims,
                     const long *buf, const char *units)
{
    return sb_h5w_dset(w, loc, name, H5T_STD_I64LE, H5T_NATIVE_LONG, rank, dims, buf, units);
}

hid_t sb_h5w_group(sb_h5w *w, hid_t file, const char *name)
{
    hid_t g = H5Gcreate2(file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) sb_h5w_fail(w, -1, name);
    return g;
}
