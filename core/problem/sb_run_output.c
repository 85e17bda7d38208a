/* sb_run_output.c — where a run's record goes, checked and locked before
 * any work (sb_run_state.h): the record, its XDMF sidecar, its checkpoint
 * OUT.partial and that one's sidecar must each be new or a regular file
 * (sb_output.h); /dev/null is --out none; OUT.lock keeps a second run off
 * the same record; the directory is made now, so a run that cannot be
 * recorded fails before it computes anything. */
#include "sb_output.h"
#include "sb_run_state.h"

#include <errno.h>
#include <string.h>
#include <sys/stat.h>

/* the directories above the file PATH (sb_mkdir_p on its parent) */
static int mkdir_parent(const char *path)
{
    char dir[4200];
    const char *slash = strrchr(path, '/');
    if (!slash || slash == path) return 0;
    if ((size_t)(slash - path) >= sizeof dir) {
        errno = ENAMETOOLONG;
        return -1;
    }
    memcpy(dir, path, (size_t)(slash - path));
    dir[slash - path] = 0;
    return sb_mkdir_p(dir);
}

/* Every file the run may write beside the record must be new or regular. */
static int check_paths(run_state *R, const char *out_path)
{
    char xdmf[1200], pxdmf[1300], sxdmf[1200], psxdmf[1300], mxdmf[1200], pmxdmf[1300], msg[1400];
    const char *paths[8] = { out_path, NULL, NULL, R->partial_path, NULL, NULL, NULL, NULL };
    const char *what[8] = { "record", "XDMF sidecar", "XDMF time-series sidecar",
                            "checkpoint", "XDMF sidecar", "XDMF time-series sidecar",
                            "XDMF mesh time-series sidecar", "XDMF mesh time-series sidecar" };
    if (sb_record_xdmf_path(out_path, xdmf, sizeof xdmf) == SB_OK) paths[1] = xdmf;
    if (sb_record_steps_xdmf_path(out_path, sxdmf, sizeof sxdmf) == SB_OK) paths[2] = sxdmf;
    if (sb_record_xdmf_path(R->partial_path, pxdmf, sizeof pxdmf) == SB_OK) paths[4] = pxdmf;
    if (sb_record_steps_xdmf_path(R->partial_path, psxdmf, sizeof psxdmf) == SB_OK) paths[5] = psxdmf;
    if (sb_record_mesh_xdmf_path(out_path, mxdmf, sizeof mxdmf) == SB_OK) paths[6] = mxdmf;
    if (sb_record_mesh_xdmf_path(R->partial_path, pmxdmf, sizeof pmxdmf) == SB_OK) paths[7] = pmxdmf;
    for (int i = 0; i < 8; i++) {
        sb_output_kind kind;
        if (!paths[i]) continue;
        if (sb_output_check(paths[i], what[i], &kind, msg, sizeof msg)) {
            sb_escape_controls(msg, sizeof msg);
            fprintf(R->err, "shellbench: %s\n", msg);
            return SB_EXIT_INPUT;
        }
        if (kind == SB_OUTPUT_DISCARD) {
            fprintf(R->err, "shellbench: will not write %s %s: it is the null device (for no record, give --out none "
                            "or --out /dev/null)\n", what[i], paths[i]);
            return SB_EXIT_INPUT;
        }
    }
    return -1;
}

int sb_run_prepare_output(run_state *R, const sb_run_request *req, int levels, const char **out_path, char *auto_path,
                          size_t len)
{
    FILE *err = R->err;
    const sb_scene *sc = &R->scene;
    *out_path = NULL;
    if (!req->out) {
        char res[32];
        if (R->res_t > 0) snprintf(res, sizeof res, "%dx%d", R->res, R->res_t);
        else snprintf(res, sizeof res, "%d", R->res);
        snprintf(auto_path, len, "results/runs/%s-%s-%s-r%s-l%d.h5", sc->name, R->mt->name, R->stype->name, res,
                 levels);
        *out_path = auto_path;
    } else if (strcmp(req->out, "none") != 0 && !sb_output_is_null(req->out)) {
        *out_path = req->out;
    }
    if (!*out_path && (req->resume || req->stop_after_steps > 0)) {
        fprintf(err, "shellbench: %s needs a record path (--out), not --out %s\n",
                req->resume ? "--resume" : "--stop-after-steps", req->out);
        return SB_EXIT_INPUT;
    }
    if (!*out_path) return -1;
    if (sb_run_partial_path(*out_path, R->partial_path, sizeof R->partial_path)) {
        sb_escape_print(err, "shellbench: output path %s is too long", *out_path);
        return SB_EXIT_INPUT;
    }
    int code = check_paths(R, *out_path);
    if (code >= 0) return code;
    if (mkdir_parent(*out_path)) {
        sb_escape_print(err, "shellbench: cannot create the directory of %s: %s", *out_path, strerror(errno));
        return SB_EXIT_INPUT;
    }
    char msg[8600];
    if (sb_output_lock_take(&R->lock, *out_path, msg, sizeof msg)) {
        sb_escape_controls(msg, sizeof msg);
        fprintf(err, "shellbench: %s\n", msg);
        return SB_EXIT_INPUT;
    }
    R->checkpoint_every = sb_param(&R->ctx.params, "run.checkpoint");
    if (R->checkpoint_every > 0) {
        R->checkpoint_last = sb_now();
        R->checkpoints_on = 1;   /* written by the run's monitor (sb_run_progress.c) */
    }
    return -1;
}
