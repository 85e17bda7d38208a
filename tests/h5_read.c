/* h5_read.c — the tests' reading of a record's numeric datasets (h5_read.h). */
#include "h5_read.h"

#include <stdlib.h>

double *sb_test_h5_doubles(hid_t f, const char *path, size_t *n, size_t *cols)
{
    *n = 0;
    if (cols) *cols = 1;
    if (H5Lexists(f, path, H5P_DEFAULT) <= 0) return NULL;
    hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
    if (d < 0) return NULL;
    hid_t s = H5Dget_space(d);
    hsize_t dims[2] = { 0, 1 };
    int rank = H5Sget_simple_extent_dims(s, dims, NULL);
    size_t m = (size_t)dims[0] * (rank > 1 ? (size_t)dims[1] : 1);
    double *b = malloc((m ? m : 1) * sizeof *b);
    if (b && m && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, b) < 0) {
        free(b);
        b = NULL;
    }
    H5Sclose(s);
    H5Dclose(d);
    *n = b ? m : 0;
    if (cols) *cols = rank > 1 ? (size_t)dims[1] : 1;
    return b;
}
