/* sb_record_xdmf.c — the XDMF sidecar of a run record (lets ParaView open the
 * final and reference surfaces stored in the HDF5 file, and play the run's
 * steps as a time series) and the small file helpers used to replace
 * records atomically.
 *
 * The sidecar holds no numbers: it points at /final/triangles,
 * /final/sample_pos, /final/sample_ref and /final/displacement of the HDF5
 * file next to it (referenced by its base name, so the pair can be moved
 * together).  When the record keeps the time series, a second sidecar
 * RUN.steps.xdmf holds a temporal collection of one grid per step
 * (/steps/sample_pos/NNNNNN, /steps/displacement/NNNNNN, times /steps/t)
 * and, for methods with a triangle surface, RUN.mesh.xdmf the same of the
 * method's own (possibly changing) triangles (/steps/mesh, sb_record_mesh.c):
 * a separate file because ParaView's Xdmf3 readers read no points from a
 * domain that mixes a temporal collection with uniform grids.  XDMF 3 format,
 * https://www.xdmf.org/index.php/XDMF_Model_and_Format.  `make check-paraview`
 * opens it in ParaView (scripts/check_paraview.sh). */
#include "sb_record_io.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

int sb_record_xdmf_path(const char *h5path, char *buf, size_t len)
{
    if (!h5path || !buf || len == 0) return SB_ERR_INPUT;
    size_t n = strlen(h5path);
    int w;
    if (n > 3 && strcmp(h5path + n - 3, ".h5") == 0)
        w = snprintf(buf, len, "%.*s.xdmf", (int)(n - 3), h5path);
    else
        w = snprintf(buf, len, "%s.xdmf", h5path);
    return (w < 0 || (size_t)w >= len) ? SB_ERR_INPUT : SB_OK;
}

const char *sb_record_basename(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

int sb_record_fsync_path(const char *path)
{
    int fd = open(path, O_RDONLY);
    if (fd < 0) return -1;
    int rc = fsync(fd);
    int e = errno;
    close(fd);
    errno = e;
    return rc;
}

void sb_record_fsync_dir(const char *path)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (!slash) snprintf(dir, sizeof dir, ".");
    else if (slash == path) snprintf(dir, sizeof dir, "/");
    else snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    int fd = open(dir, O_RDONLY | O_DIRECTORY);
    if (fd < 0) return;
    (void)fsync(fd);   /* best effort: some file systems refuse directory fsync */
    close(fd);
}

/* Write s with XML special characters escaped. */
static void xml_text(FILE *f, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&apos;", f); break;
        default: fputc(*s, f);
        }
    }
}

static void data_item(FILE *f, const char *h5, const char *dset, long rows, int cols,
                      const char *type, int precision)
{
    fprintf(f, "        <DataItem Dimensions=\"%ld %d\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">",
            rows, cols, type, precision);
    xml_text(f, h5);
    fprintf(f, ":%s</DataItem>\n", dset);
}

/* One surface grid: the shared triangle topology over the sample points,
 * geometry from `geometry_dset`, and the displacement as a node vector. */
static void grid(FILE *f, const sb_run *run, const char *h5, const char *name,
                 const char *geometry_dset)
{
    fprintf(f, "    <Grid Name=\"%s\" GridType=\"Uniform\">\n", name);
    fprintf(f, "      <Topology TopologyType=\"Triangle\" NumberOfElements=\"%d\">\n", run->n_tris);
    data_item(f, h5, "/final/triangles", run->n_tris, 3, "Int", 4);
    fprintf(f, "      </Topology>\n");
    fprintf(f, "      <Geometry GeometryType=\"XYZ\">\n");
    data_item(f, h5, geometry_dset, run->n_samples, 3, "Float", 8);
    fprintf(f, "      </Geometry>\n");
    fprintf(f, "      <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n");
    data_item(f, h5, "/final/displacement", run->n_samples, 3, "Float", 8);
    fprintf(f, "      </Attribute>\n");
    fprintf(f, "    </Grid>\n");
}

int sb_record_steps_xdmf_path(const char *h5path, char *buf, size_t len)
{
    if (!h5path || !buf || len == 0) return SB_ERR_INPUT;
    size_t n = strlen(h5path);
    int w;
    if (n > 3 && strcmp(h5path + n - 3, ".h5") == 0)
        w = snprintf(buf, len, "%.*s.steps.xdmf", (int)(n - 3), h5path);
    else
        w = snprintf(buf, len, "%s.steps.xdmf", h5path);
    return (w < 0 || (size_t)w >= len) ? SB_ERR_INPUT : SB_OK;
}

static int close_fsync(FILE *f, const char *path, char *err, size_t errlen)
{
    int bad = ferror(f) || fflush(f) != 0 || fsync(fileno(f)) != 0;
    int e = errno;
    if (fclose(f) != 0) bad = 1;
    if (bad) {
        snprintf(err, errlen, "cannot write XDMF sidecar %s: %s", path, strerror(e));
        return SB_ERR_IO;
    }
    return SB_OK;
}

static void domain_open(FILE *f, const sb_run *run)
{
    fprintf(f, "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n");
    fprintf(f, "<Xdmf Version=\"3.0\">\n  <Domain Name=\"");
    xml_text(f, run->scene_name);
    fputc('/', f);
    xml_text(f, run->method);
    fputc('/', f);
    xml_text(f, run->solver);
    fprintf(f, "\">\n");
}

int sb_record_write_steps_xdmf(const sb_run *run, const char *path, const char *h5, char *err, size_t errlen)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        snprintf(err, errlen, "cannot create XDMF sidecar %s: %s", path, strerror(errno));
        return SB_ERR_IO;
    }
    const int rows = run->steps_done + 1, n = run->n_samples;
    domain_open(f, run);
    fprintf(f, "    <Grid Name=\"steps\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
    for (int k = 0; k < rows; k++) {
        double t = k;
        if (k > 0 && run->stats && (size_t)k <= run->stats->n_steps && run->stats->steps[k - 1].step == k)
            t = run->stats->steps[k - 1].t;
        char pos[48], disp[48];
        snprintf(pos, sizeof pos, "/steps/sample_pos/%06d", k);
        snprintf(disp, sizeof disp, "/steps/displacement/%06d", k);
        fprintf(f, "    <Grid Name=\"step %d\" GridType=\"Uniform\">\n", k);
        fprintf(f, "      <Time Value=\"%.17g\"/>\n", t);
        fprintf(f, "      <Topology TopologyType=\"Triangle\" NumberOfElements=\"%d\">\n", run->n_tris);
        data_item(f, h5, "/final/triangles", run->n_tris, 3, "Int", 4);
        fprintf(f, "      </Topology>\n      <Geometry GeometryType=\"XYZ\">\n");
        data_item(f, h5, pos, n, 3, "Float", 8);
        fprintf(f, "      </Geometry>\n");
        fprintf(f, "      <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n");
        data_item(f, h5, disp, n, 3, "Float", 8);
        fprintf(f, "      </Attribute>\n    </Grid>\n");
    }
    fprintf(f, "    </Grid>\n  </Domain>\n</Xdmf>\n");
    return close_fsync(f, path, err, errlen);
}

/* RUN.mesh.xdmf: the method's own triangles at every step (/steps/mesh,
 * sb_record_mesh.c), one grid per step whose topology and reference are its
 * version's datasets (stored once per version) and whose geometry is the
 * step's positions: point and cell counts change with an adaptive mesh. */
int sb_record_write_mesh_xdmf(const sb_run *run, const char *path, const char *h5, char *err, size_t errlen)
{
    const sb_mesh_series *s = run->mesh;
    FILE *f = fopen(path, "w");
    if (!f) {
        snprintf(err, errlen, "cannot create XDMF sidecar %s: %s", path, strerror(errno));
        return SB_ERR_IO;
    }
    const int rows = s->rows < run->steps_done + 1 ? s->rows : run->steps_done + 1;
    domain_open(f, run);
    fprintf(f, "    <Grid Name=\"mesh\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
    for (int k = 0; k < rows; k++) {
        double t = k;
        if (k > 0 && run->stats && (size_t)k <= run->stats->n_steps && run->stats->steps[k - 1].step == k)
            t = run->stats->steps[k - 1].t;
        const int v = s->row_topo[k];
        const sb_mesh_topo *tp = &s->topo[v];
        char tri[64], ref[64], pos[48];
        snprintf(tri, sizeof tri, "/steps/mesh/topology/%06d/triangles", v);
        snprintf(ref, sizeof ref, "/steps/mesh/topology/%06d/reference", v);
        snprintf(pos, sizeof pos, "/steps/mesh/pos/%06d", k);
        fprintf(f, "    <Grid Name=\"step %d\" GridType=\"Uniform\">\n", k);
        fprintf(f, "      <Time Value=\"%.17g\"/>\n", t);
        fprintf(f, "      <Topology TopologyType=\"Triangle\" NumberOfElements=\"%d\">\n", tp->nt);
        data_item(f, h5, tri, tp->nt, 3, "Int", 4);
        fprintf(f, "      </Topology>\n      <Geometry GeometryType=\"XYZ\">\n");
        data_item(f, h5, pos, tp->nv, 3, "Float", 8);
        fprintf(f, "      </Geometry>\n");
        fprintf(f, "      <Attribute Name=\"reference\" AttributeType=\"Vector\" Center=\"Node\">\n");
        data_item(f, h5, ref, tp->nv, 3, "Float", 8);
        fprintf(f, "      </Attribute>\n    </Grid>\n");
    }
    fprintf(f, "    </Grid>\n  </Domain>\n</Xdmf>\n");
    return close_fsync(f, path, err, errlen);
}

int sb_record_write_xdmf(const sb_run *run, const char *xdmf_path, const char *h5_name,
                         char *err, size_t errlen)
{
    FILE *f = fopen(xdmf_path, "w");
    if (!f) {
        snprintf(err, errlen, "cannot create XDMF sidecar %s: %s", xdmf_path, strerror(errno));
        return SB_ERR_IO;
    }
    domain_open(f, run);
    grid(f, run, h5_name, "final", "/final/sample_pos");
    grid(f, run, h5_name, "reference", "/final/sample_ref");
    fprintf(f, "  </Domain>\n</Xdmf>\n");
    return close_fsync(f, xdmf_path, err, errlen);
}
