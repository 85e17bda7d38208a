/* sb_params.c — declared, validated, recorded parameters (see sb_params.h). */
#include "sb_params.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sb_paramset_init(sb_paramset *ps) { memset(ps, 0, sizeof *ps); }

static sb_param_value *find(sb_paramset *ps, const char *key)
{
    for (int i = 0; i < ps->n; i++)
        if (strcmp(ps->v[i].key, key) == 0) return &ps->v[i];
    return NULL;
}

int sb_paramset_add(sb_paramset *ps, const char *prefix, const sb_param_def *defs)
{
    if (!defs) return SB_OK;
    for (const sb_param_def *d = defs; d->name; d++) {
        char key[SB_NAME_LEN];
        if (snprintf(key, sizeof key, "%s.%s", prefix, d->name) >= (int)sizeof key) return SB_ERR_INTERNAL;
        if (find(ps, key)) continue;                      /* shared tables registered twice */
        if (ps->n >= SB_PARAMSET_MAX) return SB_ERR_INTERNAL;
        sb_param_value *v = &ps->v[ps->n++];
        memcpy(v->key, key, sizeof key);
        v->def = d;
        v->value = d->def;
        v->overridden = 0;
    }
    return SB_OK;
}

static void list_keys(const sb_paramset *ps, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = 0;
    for (int i = 0; i < ps->n && used + 2 < len; i++) {
        int w = snprintf(buf + used, len - used, "%s%s", i ? ", " : "", ps->v[i].key);
        if (w < 0) break;
        used += (size_t)w;
    }
}

int sb_paramset_set(sb_paramset *ps, const char *assignment, char *err, size_t errlen)
{
    const char *eq = strchr(assignment, '=');
    if (!eq || eq == assignment) {
        snprintf(err, errlen, "--set %s: expected key=value", assignment);
        return SB_ERR_INPUT;
    }
    char key[SB_NAME_LEN];
    size_t kl = (size_t)(eq - assignment);
    if (kl >= sizeof key) {
        snprintf(err, errlen, "--set %s: key too long", assignment);
        return SB_ERR_INPUT;
    }
    memcpy(key, assignment, kl);
    key[kl] = 0;
    const char *val = eq + 1;
    sb_param_value *v = find(ps, key);
    if (!v) {
        char keys[2048];
        list_keys(ps, keys, sizeof keys);
        snprintf(err, errlen, "--set %s: unknown parameter \"%s\" for this run (known: %s)", assignment, key, keys);
        return SB_ERR_INPUT;
    }
    const sb_param_def *d = v->def;
    if (d->kind == SB_PARAM_CHOICE) {
        for (int i = 0; d->choices && d->choices[i]; i++)
            if (strcmp(d->choices[i], val) == 0) {
                v->value = i;
                v->overridden = 1;
                return SB_OK;
            }
        char opts[512] = "";
        size_t used = 0;
        for (int i = 0; d->choices && d->choices[i] && used < sizeof opts; i++) {
            int w = snprintf(opts + used, sizeof opts - used, "%s%s", i ? ", " : "", d->choices[i]);
            if (w < 0) break;
            used += (size_t)w;
        }
        snprintf(err, errlen, "--set %s: \"%s\" is not one of: %s", assignment, val, opts);
        return SB_ERR_INPUT;
    }
    char *end = NULL;
    errno = 0;
    double x = strtod(val, &end);
    if (end == val || *end != 0 || errno == ERANGE || !isfinite(x)) {
        snprintf(err, errlen, "--set %s: \"%s\" is not a finite number", assignment, val);
        return SB_ERR_INPUT;
    }
    if (d->kind == SB_PARAM_INT && x != floor(x)) {
        snprintf(err, errlen, "--set %s: %s must be an integer", assignment, key);
        return SB_ERR_INPUT;
    }
    if (x < d->lo || x > d->hi) {
        snprintf(err, errlen, "--set %s: %s must be in [%g, %g], got %g", assignment, key, d->lo, d->hi, x);
        return SB_ERR_INPUT;
    }
    v->value = x;
    v->overridden = 1;
    return SB_OK;
}

static const sb_param_value *cfind(const sb_paramset *ps, const char *key)
{
    for (int i = 0; i < ps->n; i++)
        if (strcmp(ps->v[i].key, key) == 0) return &ps->v[i];
    return NULL;
}

double sb_param(const sb_paramset *ps, const char *key)
{
    const sb_param_value *v = cfind(ps, key);
    if (!v) {
        /* a programming error: a component read a parameter it never declared */
        fprintf(stderr, "shellbench: internal error: undeclared parameter %s\n", key);
        return NAN;
    }
    return v->value;
}

int sb_param_int(const sb_paramset *ps, const char *key)
{
    double x = sb_param(ps, key);
    return isfinite(x) ? (int)x : 0;
}

int sb_param_int_or(const sb_paramset *ps, const char *key, int def)
{
    const sb_param_value *v = ps ? cfind(ps, key) : NULL;
    return v && isfinite(v->value) ? (int)v->value : def;
}

const char *sb_param_choice(const sb_paramset *ps, const char *key)
{
    const sb_param_value *v = cfind(ps, key);
    if (!v || v->def->kind != SB_PARAM_CHOICE) return "";
    return v->def->choices[(int)v->value];
}

void sb_param_format(const sb_param_value *pv, char *buf, size_t len)
{
    if (pv->def->kind == SB_PARAM_CHOICE)
        snprintf(buf, len, "%s", pv->def->choices[(int)pv->value]);
    else if (pv->def->kind == SB_PARAM_INT)
        snprintf(buf, len, "%.0f", pv->value);
    else
        snprintf(buf, len, "%.17g", pv->value);
}
