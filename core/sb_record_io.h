/* sb_record_io.h — private helpers of the recording module (sb_record_*.c):
 * atomic file replacement, the XDMF sidecar and the report's plot.  Not a
 * public interface. */
#ifndef SB_RECORD_IO_H
#define SB_RECORD_IO_H

#include "sb_record.h"

#include <hdf5.h>

/* fsync a file by path; 0 or -1 with errno set. */
int sb_record_fsync_path(const char *path);
/* fsync the directory containing path (makes a rename durable); best effort. */
void sb_record_fsync_dir(const char *path);
/* Pointer to the last path component. */
const char *sb_record_basename(const char *path);

/* Write the XDMF sidecar for `run` to xdmf_path, referencing the datasets
 * of the HDF5 file `h5_name` (a name relative to the sidecar).  fsyncs the
 * file.  Returns SB_OK or SB_ERR_IO with a message. */
int sb_record_write_xdmf(const sb_run *run, const char *xdmf_path, const char *h5_name,
                         char *err, size_t errlen);

/* ---- HDF5 writers (sb_record_h5w.c): 0, or -1 after noting the object ---- */
typedef struct sb_h5w {
    char failed[160];      /* first object that could not be written */
} sb_h5w;

int   sb_h5w_fail(sb_h5w *w, hid_t loc, const char *name);
int   sb_h5w_attr_long(sb_h5w *w, hid_t loc, const char *name, long v);
int   sb_h5w_attr_dbl(sb_h5w *w, hid_t loc, const char *name, double v);
int   sb_h5w_attr_str(sb_h5w *w, hid_t loc, const char *name, const char *s);
/* n fixed-length strings of `width` bytes each, packed in buf */
int   sb_h5w_attr_str_array(sb_h5w *w, hid_t loc, const char *name, int n, size_t width, const char *buf);
hid_t sb_h5w_str_type(size_t width);
/* Datasets of any shape (zero-sized allowed); units: optional "units" attribute. */
int   sb_h5w_dset_dbl(sb_h5w *w, hid_t loc, const char *name, int rank, const hsize_t *dims,
                      const double *buf, const char *units);
int   sb_h5w_dset_int(sb_h5w *w, hid_t loc, const char *name, int rank, const hsize_t *dims,
                      const int *buf, const char *units);
int   sb_h5w_dset_long(sb_h5w *w, hid_t loc, const char *name, int rank, const hsize_t *dims,
                       const long *buf, const char *units);
hid_t sb_h5w_group(sb_h5w *w, hid_t file, const char *name);

/* Plot log10 ||g|| against cumulative iteration for the n summaries (one
 * line each, titled scene/method/solver) through gnuplot into plot_path
 * (SVG when it ends in ".svg", else PNG), replaced atomically.  gnuplot is
 * the program to run.  Returns SB_OK, or SB_REPORT_WARN_PLOT with a message
 * when gnuplot is missing or fails or there is nothing to plot. */
int sb_report_plot(int n, const sb_record_summary *s, const char *plot_path,
                   const char *gnuplot, char *err, size_t errlen);

#endif
