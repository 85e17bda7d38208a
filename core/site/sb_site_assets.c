/* sb_site_assets.c — the site's own scripts and stylesheet, embedded from
 * core/site/assets/ at build time (scripts/embed_assets.sh), so that the
 * binary writes them into every site without looking for its source tree. */
#include "sb_site.h"

#include "sb_site_assets.h"
