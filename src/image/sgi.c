/* sgi.c: the SGI image format (.rgb), as VMD writes it: a 512-byte big-endian header (magic
 * 474, 8 bits a channel, three dimensions, three channels RGB), then the channels one after
 * the other, each bottom row first, stored verbatim. The reader also takes run-length encoded
 * files (storage 1: a table of row offsets and lengths, then runs of at most 127 bytes) and a
 * fourth (alpha) or a single (grey) channel, as other programs write them. */
#include "config.h"
#include "image/image_codecs.h"

#include <stdlib.h>
#include <string.h>

#define SGI_MAGIC 474
#define SGI_HEADER 512

static void be16(uint8_t *p, unsigned v) { p[0] = (uint8_t)(v >> 8); p[1] = (uint8_t)v; }
static void be32(uint8_t *p, uint32_t v)
{
    for (int k = 0; k < 4; k++) p[k] = (uint8_t)(v >> (24 - 8 * k));
}
static unsigned rd16(const uint8_t *p) { return (unsigned)p[0] << 8 | p[1]; }
static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* ---------------------------------------------------------------- writing */

int ms_sgi_write(const ms_image *img, FILE *fp, ms_error *err)
{
    if (img->width > 65535 || img->height > 65535) {
        ms_error_set(err, "SGI: image too large for the format (65535 pixels a side)");
        return -1;
    }
    uint8_t h[SGI_HEADER] = {0};
    be16(h, SGI_MAGIC);
    h[2] = 0;                           /* verbatim */
    h[3] = 1;                           /* bytes per channel */
    be16(h + 4, 3);                     /* dimensions */
    be16(h + 6, (unsigned)img->width);
    be16(h + 8, (unsigned)img->height);
    be16(h + 10, 3);                    /* channels */
    be32(h + 12, 0);                    /* pixmin */
    be32(h + 16, 255);                  /* pixmax */
    memcpy(h + 24, "molscope", 8);      /* image name */
    uint8_t *row = malloc((size_t)img->width);
    if (!row) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    int ok = fwrite(h, 1, sizeof h, fp) == sizeof h;
    for (int c = 0; c < 3 && ok; c++)
        for (int y = img->height - 1; y >= 0 && ok; y--) {
            const uint8_t *src = img->rgb + (size_t)y * (size_t)img->width * 3 + c;
            for (int x = 0; x < img->width; x++) row[x] = src[3 * x];
            ok = fwrite(row, 1, (size_t)img->width, fp) == (size_t)img->width;
        }
    free(row);
    if (!ok) ms_error_set(err, "write failed");
    return ok ? 0 : -1;
}

/* ---------------------------------------------------------------- reading */

typedef struct sgi_file {
    int rle, w, h, nch;
    uint32_t *start, *len;              /* RLE: per row of each channel */
} sgi_file;

/* One run-length encoded row from the file's bytes at off (len of them) into out[w]. */
static int sgi_unpack(FILE *fp, uint32_t off, uint32_t len, uint8_t *out, int w)
{
    if (len > 2u * (uint32_t)w + 16u || fseek(fp, (long)off, SEEK_SET) != 0) return -1;
    uint8_t buf[2 * MS_IMAGE_MAX_SIDE + 16];
    if (fread(buf, 1, len, fp) != len) return -1;
    int x = 0;
    for (uint32_t i = 0; i < len;) {
        int count = buf[i] & 0x7f, literal = buf[i] & 0x80;
        i++;
        if (!count) return x == w ? 0 : -1;
        if (x + count > w || i + (literal ? (uint32_t)count : 1u) > len) return -1;
        if (literal) memcpy(out + x, buf + i, (size_t)count);
        else memset(out + x, buf[i], (size_t)count);
        i += literal ? (uint32_t)count : 1u;
        x += count;
    }
    return x == w ? 0 : -1;
}

/* Row y (from the bottom) of channel c into out[w]. */
static int sgi_row(FILE *fp, const sgi_file *s, int c, int y, uint8_t *out)
{
    if (!s->rle) {
        long off = SGI_HEADER + ((long)c * s->h + y) * (long)s->w;
        if (fseek(fp, off, SEEK_SET) != 0) return -1;
        return fread(out, 1, (size_t)s->w, fp) == (size_t)s->w ? 0 : -1;
    }
    size_t k = (size_t)c * (size_t)s->h + (size_t)y;
    return sgi_unpack(fp, s->start[k], s->len[k], out, s->w);
}

/* The RLE offset and length tables, after the header. */
static int sgi_tables(FILE *fp, sgi_file *s)
{
    size_t n = (size_t)s->h * (size_t)s->nch;
    uint8_t *raw = malloc(8 * n);
    s->start = malloc(n * sizeof *s->start);
    s->len = malloc(n * sizeof *s->len);
    int ok = raw && s->start && s->len && fseek(fp, SGI_HEADER, SEEK_SET) == 0 &&
             fread(raw, 1, 8 * n, fp) == 8 * n;
    for (size_t i = 0; ok && i < n; i++) {
        s->start[i] = rd32(raw + 4 * i);
        s->len[i] = rd32(raw + 4 * (n + i));
    }
    free(raw);
    return ok ? 0 : -1;
}

static int sgi_header(FILE *fp, sgi_file *s, ms_error *err)
{
    uint8_t h[SGI_HEADER];
    if (fread(h, 1, sizeof h, fp) != sizeof h || rd16(h) != SGI_MAGIC) {
        ms_error_set(err, "SGI: not an SGI image (bad or truncated header)");
        return -1;
    }
    unsigned dim = rd16(h + 4);
    s->rle = h[2];
    s->w = (int)rd16(h + 6);
    s->h = dim >= 2 ? (int)rd16(h + 8) : 1;
    s->nch = dim >= 3 ? (int)rd16(h + 10) : 1;
    if (h[3] != 1 || s->rle > 1 || dim < 1 || dim > 3 || s->nch < 1 || s->nch > 4 ||
        s->nch == 2) {
        ms_error_set(err, "SGI: unsupported image (storage %d, %d bytes a channel, %u "
                          "dimensions, %d channels)", h[2], h[3], dim, s->nch);
        return -1;
    }
    return 0;
}

int ms_sgi_read(FILE *fp, ms_image *img, ms_error *err)
{
    sgi_file s = {0};
    img->rgb = NULL;
    if (sgi_header(fp, &s, err) || ms_image_alloc(img, s.w, s.h, err)) return -1;
    int ok = !s.rle || sgi_tables(fp, &s) == 0;
    uint8_t *row = malloc((size_t)s.w);
    ok = ok && row;
    for (int c = 0; c < 3 && ok; c++)
        for (int y = 0; y < s.h && ok; y++) {
            int ch = s.nch >= 3 ? c : 0;
            ok = sgi_row(fp, &s, ch, y, row) == 0;
            uint8_t *d = img->rgb + (size_t)(s.h - 1 - y) * (size_t)s.w * 3 + c;
            for (int x = 0; ok && x < s.w; x++) d[3 * x] = row[x];
        }
    free(row);
    free(s.start);
    free(s.len);
    if (ok) return 0;
    ms_image_free(img);
    ms_error_set(err, "SGI: truncated or corrupt pixel data");
    return -1;
}
