/* sb_record_obstacles.c — the contents of a scene's obstacle meshes as
 * checksums (docs/running.md "Resume", docs/trust.md "Reference files").
 *
 * A mesh obstacle is an OBJ file beside the scene; the scene text names the
 * file, not what is in it, so an edited cube.obj leaves the text unchanged.
 * Each mesh obstacle's parsed contents (vertex count, triangle count, the
 * vertices' bits, the triangles' indices) get a CRC-64 (sb_checksum.c), kept
 * in the record's root attribute "obstacle_meshes" as
 *     "NAME nv NV nt NT crc64 HEX; NAME ..."
 * (absent when the scene has no mesh obstacle).  A checkpoint holds it too,
 * and --resume refuses one whose meshes differ; a reference whose meshes
 * differ from the scene's is refused like a reference of another scene. */
#include "sb_record_io.h"

#include <inttypes.h>
#include <string.h>

void sb_record_mesh_sums(const sb_scene *sc, char *buf, size_t len)
{
    size_t u = 0;
    if (len) buf[0] = 0;
    for (int i = 0; sc && i < sc->n_obstacles; i++) {
        const sb_obstacle_spec *o = &sc->obstacles[i];
        if (o->kind != SB_OBST_MESH) continue;
        uint64_t crc = sb_crc64(0, &o->nv, sizeof o->nv);
        crc = sb_crc64(crc, &o->nt, sizeof o->nt);
        if (o->verts && o->nv > 0) crc = sb_crc64(crc, o->verts, (size_t)o->nv * 3 * sizeof *o->verts);
        if (o->tris && o->nt > 0) crc = sb_crc64(crc, o->tris, (size_t)o->nt * 3 * sizeof *o->tris);
        int w = snprintf(buf + u, len > u ? len - u : 0, "%s%s nv %d nt %d crc64 %016" PRIx64, u ? "; " : "",
                         o->name[0] ? o->name : "(unnamed)", o->nv, o->nt, crc);
        if (w < 0 || (size_t)w >= (len > u ? len - u : 0)) break;   /* truncated: still compared as text */
        u += (size_t)w;
    }
}

int sb_record_read_mesh_sums(const char *path, char *buf, size_t len, char *err, size_t errlen)
{
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    if (len) buf[0] = 0;
    int rc = sb_h5r_open(&r, &f);
    if (!rc && H5Aexists(f, "obstacle_meshes") > 0) rc = sb_h5r_attr_str(&r, f, "obstacle_meshes", buf, len);
    sb_h5r_close(&r, f);
    return rc;
}
