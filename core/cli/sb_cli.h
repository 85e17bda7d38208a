/* sb_cli.h — the parts of the command line (core/cli/): argument parsing
 * (sb_cli_args.c), help and version (sb_cli_help.c), `list` (sb_cli_list.c)
 * and `sweep` (sb_cli_sweep.c over sb_sweep.h).  main.c dispatches.  The
 * reference is docs/cli.md. */
#ifndef SB_CLI_H
#define SB_CLI_H

#include "sb_run.h"

#include <stdio.h>

/* ---- arguments (sb_cli_args.c) ------------------------------------------- */
/* --res: "N" with 0 <= N <= SB_SCENE_MAX_RESOLUTION (0: the scene's own).
 * SB_OK, or SB_ERR_INPUT with a sentence.  The one place the CLI's limit
 * on a resolution lives. */
int  sb_cli_parse_res(const char *s, int *res, char *err, size_t errlen);
/* A decimal integer in [lo, hi]; 0 or -1. */
int  sb_cli_parse_int(const char *s, long lo, long hi, int *out);
/* Split the comma list s (modified) into at most max items; an empty list
 * or an empty item is an error (-1), as is a list longer than max (-2). */
int  sb_cli_split(char *s, char **items, int max, int *n);

/* The options `run` and `sweep` share, and those of each. */
#define SB_CLI_MAX_SETS 256
typedef struct sb_cli_run {
    sb_run_request req;
    const char *sets[SB_CLI_MAX_SETS];
    const char *scenes, *methods, *solvers, *res_list, *level_list, *dir;   /* sweep */
} sb_cli_run;
/* Parses argv into c (zeroed by the caller); 0, or 2 after a message on stderr. */
int  sb_cli_parse_run(int argc, char **argv, sb_cli_run *c, int sweep);

/* ---- help (sb_cli_help.c) ------------------------------------------------- */
void sb_cli_usage(FILE *f);
/* `help CMD` / `CMD --help`: the command's options; 0, or 2 for an unknown command. */
int  sb_cli_help(const char *cmd, FILE *f);
/* `--version`: build id, record format, BLAS kernel set. */
void sb_cli_version(FILE *f);

/* ---- commands ------------------------------------------------------------ */
int  sb_cli_list(int argc, char **argv);     /* sb_cli_list.c */
int  sb_cli_sweep(int argc, char **argv);    /* sb_cli_sweep.c */
extern const char sb_cli_regress_help[];     /* sb_cli_regress.c */
int  sb_cli_digest(int argc, char **argv);   /* sb_cli_digest.c */
extern const char sb_cli_digest_help[];


#endif
