/* sb_font.c — labels on rendered images: a 9x13 monospaced font
 * (sb_font_data.h) blended with its 4-bit coverage, scaled by whole pixels. */
#include "sb_render_world.h"
#include "sb_font_data.h"

#include <string.h>

int sb_font_height(int scale) { return SB_FONT_H * (scale < 1 ? 1 : scale); }

int sb_font_width(const char *text, int scale)
{
    return (int)strlen(text) * SB_FONT_W * (scale < 1 ? 1 : scale);
}

static int hexval(char c) { return c >= 'a' ? c - 'a' + 10 : c - '0'; }

int sb_font_draw(sb_image *im, int x, int y, int scale, const char *text, const float rgb[3])
{
    if (scale < 1) scale = 1;
    int x0 = x;
    for (const char *p = text; *p; p++, x += SB_FONT_W * scale) {
        unsigned char ch = (unsigned char)*p;
        const char *g = sb_font_glyph[(ch >= 32 && ch < 127 ? ch : '?') - 32];
        for (int gy = 0; gy < SB_FONT_H; gy++)
            for (int gx = 0; gx < SB_FONT_W; gx++) {
                const float a = hexval(g[gy * SB_FONT_W + gx]) / 15.0f;
                if (a <= 0) continue;
                for (int sy = 0; sy < scale; sy++)
                    for (int sx = 0; sx < scale; sx++) {
                        const int px = x + gx * scale + sx, py = y + gy * scale + sy;
                        if (px < 0 || py < 0 || px >= im->w || py >= im->h) continue;
                        float *d = im->rgb + 3 * ((size_t)py * im->w + px);
                        for (int c = 0; c < 3; c++) d[c] = (1 - a) * d[c] + a * rgb[c];
                    }
            }
    }
    return x - x0;
}
