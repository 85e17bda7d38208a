/* sb_image.c — the image buffer and a small PNG writer (zlib's deflate;
 * PNG 1.2: IHDR, sRGB, tEXt, IDAT, IEND; filter "Sub" on every row). */
#include "sb_render.h"
#include "sb_common.h"
#include "sb_output.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

int sb_image_alloc(sb_image *im, int w, int h)
{
    im->w = im->h = 0;
    im->rgb = NULL;
    if (w <= 0 || h <= 0 || w > 16384 || h > 16384) return -1;
    im->rgb = calloc((size_t)w * h * 3, sizeof(float));
    if (!im->rgb) return -1;
    im->w = w;
    im->h = h;
    return 0;
}

void sb_image_free(sb_image *im)
{
    free(im->rgb);
    im->rgb = NULL;
    im->w = im->h = 0;
}

/* linear -> sRGB transfer function (IEC 61966-2-1) */
static unsigned char srgb8(float x)
{
    double v = x <= 0 ? 0 : x >= 1 ? 1 : x;
    v = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
    return (unsigned char)lrint(v * 255.0);
}

static void be32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static int chunk(FILE *f, const char *type, const unsigned char *data, size_t n)
{
    unsigned char hdr[8];
    be32(hdr, (uint32_t)n);
    memcpy(hdr + 4, type, 4);
    uLong crc = crc32(0L, Z_NULL, 0);
    crc = crc32(crc, hdr + 4, 4);
    if (n) crc = crc32(crc, data, (uInt)n);
    unsigned char tail[4];
    be32(tail, (uint32_t)crc);
    if (fwrite(hdr, 1, 8, f) != 8) return -1;
    if (n && fwrite(data, 1, n, f) != n) return -1;
    return fwrite(tail, 1, 4, f) == 4 ? 0 : -1;
}

int sb_image_write_png(const sb_image *im, const char *path, int n_text, const char *const *key,
                       const char *const *val, char *err, size_t errlen)
{
    /* only a new path or a regular file is replaced; /dev/null discards;
       a device, FIFO, directory or symbolic link is refused (docs/cli.md
       "Output safety") */
    sb_output_kind kind;
    if (sb_output_check(path, "image", &kind, err, errlen)) return -1;
    if (kind == SB_OUTPUT_DISCARD) return 0;
    const size_t row = (size_t)im->w * 3 + 1, raw_n = row * im->h;
    unsigned char *raw = malloc(raw_n);
    uLongf zn = compressBound((uLong)raw_n);
    unsigned char *z = malloc(zn);
    if (!raw || !z) {
        free(raw);
        free(z);
        snprintf(err, errlen, "out of memory writing %s", path);
        return -1;
    }
    for (int y = 0; y < im->h; y++) {
        unsigned char *r = raw + row * y;
        r[0] = 1;   /* filter type Sub: byte minus the byte one pixel to the left */
        unsigned char prev[3] = { 0, 0, 0 };
        for (int x = 0; x < im->w; x++)
            for (int c = 0; c < 3; c++) {
                const unsigned char b = srgb8(im->rgb[3 * ((size_t)y * im->w + x) + c]);
                r[1 + 3 * x + c] = (unsigned char)(b - prev[c]);
                prev[c] = b;
            }
    }
    int rc = compress2(z, &zn, raw, (uLong)raw_n, 9);
    free(raw);
    if (rc != Z_OK) {
        free(z);
        snprintf(err, errlen, "zlib failed compressing %s", path);
        return -1;
    }
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid());
    /* the temporary file is new and ours: never follow a link planted there */
    const int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
    FILE *f = fd >= 0 ? fdopen(fd, "wb") : NULL;
    if (!f) {
        if (fd >= 0) {
            close(fd);
            remove(tmp);
        }
        free(z);
        snprintf(err, errlen, "cannot create %s: %s", path, strerror(errno));
        return -1;
    }
    static const unsigned char sig[8] = { 137, 80, 78, 71, 13, 10, 26, 10 };
    unsigned char ihdr[13];
    be32(ihdr, (uint32_t)im->w);
    be32(ihdr + 4, (uint32_t)im->h);
    ihdr[8] = 8;    /* bit depth */
    ihdr[9] = 2;    /* colour type RGB */
    ihdr[10] = ihdr[11] = ihdr[12] = 0;
    const unsigned char srgb = 0;   /* rendering intent: perceptual */
    int bad = fwrite(sig, 1, 8, f) != 8 || chunk(f, "IHDR", ihdr, 13) || chunk(f, "sRGB", &srgb, 1);
    for (int i = 0; i < n_text && !bad; i++) {
        char buf[2048];
        size_t kl = strlen(key[i]), vl = strlen(val[i]);
        if (kl < 1 || kl > 79 || kl + 1 + vl > sizeof buf) continue;
        memcpy(buf, key[i], kl);
        buf[kl] = 0;
        memcpy(buf + kl + 1, val[i], vl);
        bad = chunk(f, "tEXt", (const unsigned char *)buf, kl + 1 + vl);
    }
    if (!bad) bad = chunk(f, "IDAT", z, zn) || chunk(f, "IEND", NULL, 0);
    free(z);
    if (fclose(f) != 0) bad = 1;
    if (bad || rename(tmp, path) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        remove(tmp);
        return -1;
    }
    return 0;
}

/* The text of tEXt chunk `key` of the PNG at path (as sb_image_write_png
 * writes them), and the image size: 0, or -1 when the file is not a PNG,
 * cannot be read, or has no such chunk.  Reads chunk headers and skips the
 * image data. */
int sb_image_png_text(const char *path, const char *key, char *val, size_t len, int *w, int *h)
{
    static const unsigned char sig[8] = { 137, 'P', 'N', 'G', 13, 10, 26, 10 };
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    unsigned char head[8];
    int found = -1;
    const size_t klen = strlen(key);
    if (fread(head, 1, 8, f) == 8 && !memcmp(head, sig, 8)) {
        while (found < 0 && fread(head, 1, 8, f) == 8) {
            const uint32_t n = (uint32_t)head[0] << 24 | (uint32_t)head[1] << 16 | (uint32_t)head[2] << 8 | head[3];
            if (n > (1u << 30)) break;
            if (!memcmp(head + 4, "IHDR", 4) || !memcmp(head + 4, "tEXt", 4)) {
                unsigned char *d = malloc(n + 1);
                if (!d || fread(d, 1, n, f) != n) { free(d); break; }
                d[n] = 0;
                if (!memcmp(head + 4, "IHDR", 4) && n >= 8) {
                    *w = (int)((uint32_t)d[0] << 24 | (uint32_t)d[1] << 16 | (uint32_t)d[2] << 8 | d[3]);
                    *h = (int)((uint32_t)d[4] << 24 | (uint32_t)d[5] << 16 | (uint32_t)d[6] << 8 | d[7]);
                } else if (n > klen && !memcmp(d, key, klen) && d[klen] == 0) {
                    snprintf(val, len, "%s", (const char *)d + klen + 1);
                    found = 0;
                }
                free(d);
                if (fseek(f, 4, SEEK_CUR)) break;   /* CRC */
            } else if (fseek(f, (long)n + 4, SEEK_CUR)) {
                break;
            }
        }
    }
    fclose(f);
    return found;
}
