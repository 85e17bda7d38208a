/* sb_sysinfo.h — machine and build facts recorded with every run: CPU model,
 * core count, wall-clock time (UTC) and the build id (git describe). */
#ifndef SB_SYSINFO_H
#define SB_SYSINFO_H

#include <stddef.h>

/* "model name" of the first processor in /proc/cpuinfo ("unknown" when the
 * file or field is missing).  Always NUL-terminates buf. */
void sb_sysinfo_cpu_model(char *buf, size_t len);
/* Online processors (sysconf), at least 1. */
int sb_sysinfo_cores(void);
/* Current UTC time as ISO 8601, "2024-05-01T12:34:56Z". */
void sb_sysinfo_now_iso(char *buf, size_t len);
/* The compile-time SB_BUILD_ID (git describe --always --dirty, passed by the
 * Makefile), or "unknown". */
void sb_sysinfo_build_id(char *buf, size_t len);
/* The BLAS kernel set in use: OpenBLAS's core name (e.g. "Haswell",
 * "SkylakeX", or "Prescott", its generic fallback on CPUs it does not
 * recognize) when the process has loaded OpenBLAS, else "unknown".  The
 * kernel changes round-off and so, on nonconvex scenes, iteration counts
 * (docs/reproducibility.md); records keep it beside the thread count. */
void sb_sysinfo_blas_core(char *buf, size_t len);
/* Host name ("unknown" when unavailable). */
void sb_sysinfo_hostname(char *buf, size_t len);

#endif
