/* h5_read.h — the tests' reading of a record's numeric datasets. */
#ifndef SB_TEST_H5_READ_H
#define SB_TEST_H5_READ_H

#include <hdf5.h>
#include <stddef.h>

/* The dataset at path (rank 1 or 2) as doubles, malloc'd (free it); *n its
 * values, *cols (when given) its second dimension (1 for rank 1).  NULL
 * (and *n = 0) when the file has no such dataset or it cannot be read. */
double *sb_test_h5_doubles(hid_t f, const char *path, size_t *n, size_t *cols);

#endif
