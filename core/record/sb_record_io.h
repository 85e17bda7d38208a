/* sb_record_io.h — private helpers of the recording module (sb_record_*.c):
 * atomic file replacement, the XDMF sidecar and the report's plot.  Not a
 * public interface. */
#ifndef SB_RECORD_IO_H
#define SB_RECORD_IO_H

#include "sb_record.h"

#include <hdf5.h>
#include <stdint.h>

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

/* The time-series sidecar (RUN.steps.xdmf) of a run that keeps
 * sample_traj: a temporal collection of its steps.  SB_OK or SB_ERR_IO. */
int sb_record_write_steps_xdmf(const sb_run *run, const char *path, const char *h5_name,
                               char *err, size_t errlen);

/* The mesh time-series sidecar (RUN.mesh.xdmf) of a run that keeps its
 * method's triangles (run->mesh).  SB_OK or SB_ERR_IO. */
int sb_record_write_mesh_xdmf(const sb_run *run, const char *path, const char *h5_name,
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

/* The columns of /history/iterations and /history/steps: one struct member
 * each, written as a 1-D dataset (sb_record_write.c) and read back by
 * sb_record_read_resume.  "units" is empty where the unit depends on the
 * method's DOF layout (docs/recorded_figures.md). */
typedef struct sb_record_column {
    const char *name; size_t off; int is_int; const char *units;
    int since_v3;   /* a column of format version 3 (issue 42): absent in older checkpoints, read as 0 */
} sb_record_column;
extern const sb_record_column sb_record_iter_cols[], sb_record_step_cols[];
extern const int sb_record_n_iter_cols, sb_record_n_step_cols;

/* The /resume group of a checkpoint (sb_record_resume.c); 0 or -1. */
int   sb_record_write_resume(sb_h5w *w, hid_t f, const sb_resume_point *rp);
/* /steps: the sample grid of every step (sb_record_steps.c); 0 or -1. */
int   sb_record_write_steps(sb_h5w *w, hid_t f, const sb_run *r);
/* /steps/mesh: the method's triangles of every step (sb_record_mesh.c); 0 or -1. */
int   sb_record_write_mesh(sb_h5w *w, hid_t f, const sb_run *r);
/* The resume log as root attributes (every record). */
int   sb_record_write_resume_log(sb_h5w *w, hid_t f, const sb_resume_log *log);

/* ---- checksums (sb_checksum.c, docs/trust.md) ---------------------------
 * Records begin with a user block of SB_RECORD_USERBLOCK bytes holding the
 * CRC-64 of the rest of the file. */
#define SB_RECORD_USERBLOCK 512
/* CRC-64/XZ of n bytes continuing crc (0 to start) */
uint64_t sb_crc64(uint64_t crc, const void *data, size_t n);
/* Fill the user block of the closed file PATH with the checksum of the rest. */
int  sb_record_seal(const char *path, char *err, size_t errlen);
/* SB_OK with *sealed = 1 when PATH carries a checksum that matches, or with
 * *sealed = 0 when it carries none; SB_ERR_INPUT (mismatch, damaged header)
 * or SB_ERR_IO with a sentence. */
int  sb_record_verify(const char *path, int *sealed, char *err, size_t errlen);

/* ---- HDF5 readers (sb_record_h5r.c): SB_OK, or a status with one sentence
 * in r->err naming the file and the object ---- */
typedef struct sb_h5r {
    const char *path;
    char *err;
    size_t errlen;
    H5E_auto2_t old_fn;      /* the caller's HDF5 error printer, restored by sb_h5r_close */
    void *old_data;
} sb_h5r;

int  sb_h5r_fail(sb_h5r *r, int status, const char *what, const char *name);
/* Silences HDF5's error printing (restored by sb_h5r_close, which must follow
 * every sb_h5r_open), checks the path and opens a shellbench record. */
int  sb_h5r_open(sb_h5r *r, hid_t *file);
void sb_h5r_close(sb_h5r *r, hid_t f);
/* scalar fixed-length string attribute into a new buffer / copied into buf */
int  sb_h5r_attr_str_alloc(sb_h5r *r, hid_t loc, const char *name, char **out);
int  sb_h5r_attr_str(sb_h5r *r, hid_t loc, const char *name, char *buf, size_t len);
/* scalar numeric attribute converted to mtype */
int  sb_h5r_attr_num(sb_h5r *r, hid_t loc, const char *name, hid_t mtype, void *v);
int  sb_h5r_attr_int(sb_h5r *r, hid_t loc, const char *name, int *v);
int  sb_h5r_attr_dbl(sb_h5r *r, hid_t loc, const char *name, double *v);
/* whole numeric dataset of the given rank, converted to mtype (esize bytes),
 * into a new buffer of at least one element; dims receives its shape */
int  sb_h5r_dset(sb_h5r *r, hid_t loc, const char *name, int rank, hid_t mtype, size_t esize,
                 hsize_t *dims, void **out);

/* Plot log10 ||g|| against cumulative iteration for the n summaries (one
 * line each, titled scene/method/solver) through gnuplot into plot_path
 * (SVG when it ends in ".svg", else PNG), replaced atomically.  gnuplot is
 * the program to run.  Returns SB_OK, or SB_REPORT_WARN_PLOT with a message
 * when gnuplot is missing or fails or there is nothing to plot. */
int sb_report_plot(int n, const sb_record_summary *s, const char *plot_path,
                   const char *gnuplot, char *err, size_t errlen);

/* ---- the report (core/report) ------------------------------------------ */
/* "converged (grad_tol)", "not converged (max_iter)", "unfinished (checkpoint)" */
void   sb_report_status_text(const sb_record_summary *s, char *buf, size_t len);
/* The run's error figure (RMS field error or max probe error; *label "rms"
 * or "probe"), NaN when it has none. */
double sb_report_error_value(const sb_record_summary *s, const char **label);
/* The Markdown report of n summaries (sb_report_md.c). */
void   sb_report_markdown(FILE *out, int n, const sb_record_summary *s);

#endif
