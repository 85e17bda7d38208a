/* sb_run_contact.c — what the contact guarantee of a run covered (issue 37;
 * docs/contact.md "What the guarantee covers"): the barrier keeps the
 * sample points outside the obstacles; between them an obstacle can cross
 * the cloth.  Methods that triangulate their sample points have every step
 * end's sample triangles checked against the analytic obstacles
 * (sb_contact_measure); the record and the summary say what was found, or
 * that it was not checked and which obstacles could pass unseen. */
#include "sb_run_state.h"
#include "sb_contact.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void sb_run_contact_between(run_state *R, int step, const sb_contact_report *r, double spacing)
{
    sb_run *rec = &R->rec;
    if (!R->between_init) {   /* first measured step of this process */
        R->between_init = 1;
        rec->has_between = 1;
        rec->contact_steps_between = 0;
        R->between_first_step = 0;
        R->between_obstacle = -1;
    }
    R->contact_spacing = spacing;
    if (r->between < 0) { rec->contact_steps_between = -1; return; }
    if (rec->contact_steps_between < 0) return;
    if (r->between > 0) {
        if (rec->contact_steps_between == 0) {
            R->between_first_step = step;
            R->between_obstacle = r->between_obstacle;
        }
        rec->contact_steps_between++;
    }
}

static const char *kind_name(const sb_obstacle_spec *o)
{
    static const char *const names[] = { "sphere", "plane", "box", "capsule", "mesh" };
    return (int)o->kind >= 0 && (int)o->kind < 5 ? names[o->kind] : "obstacle";
}

void sb_run_contact_coverage(run_state *R)
{
    sb_run *rec = &R->rec;
    const sb_scene *sc = &R->scene;
    char *s = rec->contact_coverage;
    const size_t cap = sizeof rec->contact_coverage;
    s[0] = '\0';
    if (sc->n_obstacles == 0) return;
    size_t k = 0;
#define ADD(...) do { if (k < cap) k += (size_t)snprintf(s + k, cap - k, __VA_ARGS__); } while (0)
    int meshes = 0;
    for (int o = 0; o < sc->n_obstacles; o++) meshes += sc->obstacles[o].kind == SB_OBST_MESH;
    char e[SB_NAME_LEN * 4 + 8];
    if (sc->contact.model == SB_CONTACT_IMPULSE)
        ADD("contact.model impulse: collisions are swept and resolved at the method's own points (bhem: cloth "
            "sample points and mesh vertices against patches; triangle methods: vertices against analytic solids, "
            "vertices and edges against mesh triangles and edges); ");
    else
        ADD("the barrier keeps the sample points outside the obstacles (its guarantee covers the sample points "
            "only); ");
    if (!rec->has_between) {
        ADD("between them nothing was checked (no step was measured)");
        return;
    }
    if (rec->contact_steps_between < 0) {
        /* not checked: name the analytic obstacles a crossing between points
           could come from (a feature narrower than the spacing: spheres and
           capsules thinner than it, every box edge and corner) */
        ADD("between them (spacing about %.3g m) the surface was not checked (method %s does not triangulate its "
            "sample points), so a crossing there cannot be excluded", R->contact_spacing, R->mt->name);
        int n = 0;
        for (int o = 0; o < sc->n_obstacles; o++) {
            const sb_obstacle_spec *ob = &sc->obstacles[o];
            const int narrow = ((ob->kind == SB_OBST_SPHERE || ob->kind == SB_OBST_CAPSULE) &&
                                2 * ob->radius < R->contact_spacing) || ob->kind == SB_OBST_BOX ||
                               ob->kind == SB_OBST_MESH;
            if (!narrow) continue;
            ADD("%s\"%s\" (%s)", n++ ? ", " : ": it is possible for ", sb_escape_copy(ob->name, e, sizeof e),
                kind_name(ob));
        }
        if (!n) ADD(" (no obstacle has a feature narrower than the spacing: the spheres and capsules are wider "
                    "and there are no boxes or meshes)");
        return;
    }
    ADD("between them every step end's sample triangles were checked against the analytic obstacles (an obstacle "
        "reaching deeper than contact.dhat = %g m into one, or a capsule's axis through one, counts): ",
        sc->contact.dhat);
    if (rec->contact_steps_between == 0) ADD("no crossing found");
    else
        ADD("%d step end%s had an obstacle crossing the cloth between sample points, through their flat sample "
            "triangles (first: step %d, obstacle \"%s\" (%s)); %s",
            rec->contact_steps_between, rec->contact_steps_between == 1 ? "" : "s", R->between_first_step,
            sb_escape_copy(sc->obstacles[R->between_obstacle].name, e, sizeof e),
            kind_name(&sc->obstacles[R->between_obstacle]),
            /* the triangle methods' surface is those triangles; the smooth
               methods' is curved between the points, the triangles its chords */
            R->tri_surface ? "the result is not penetration-free (those triangles are the method's surface)"
                           : "the result is not shown penetration-free (those triangles are chords of the method's "
                             "smooth surface, which may pass above an obstacle that crosses a chord, e.g. a cloth "
                             "tented over a needle tip)");
    if (R->resumed) ADD(" (counted over the steps this process ran, after the resume)");
    if (meshes) ADD("; mesh obstacles are not checked between sample points (a mesh vertex or edge can pass between them)");
#undef ADD
}
