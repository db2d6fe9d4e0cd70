/* rawformats.c: the uncompressed image formats: TGA (VMD's usual output; written as 24-bit,
 * top-left origin; read uncompressed or RLE, 24 or 32 bit, either origin), binary PPM (P6)
 * and BMP (24 bit, bottom-up rows padded to 4 bytes). */
#include "config.h"
#include "image/image_codecs.h"

#include <stdlib.h>
#include <string.h>

static int put(FILE *fp, const void *p, size_t n, ms_error *err)
{
    if (fwrite(p, 1, n, fp) == n) return 0;
    ms_error_set(err, "write failed");
    return -1;
}

static void le16(uint8_t *p, unsigned v) { p[0] = (uint8_t)v; p[1] = (uint8_t)(v >> 8); }
static void le32(uint8_t *p, uint32_t v)
{
    for (int k = 0; k < 4; k++) p[k] = (uint8_t)(v >> (8 * k));
}
static unsigned rd16(const uint8_t *p) { return (unsigned)p[0] | (unsigned)p[1] << 8; }
static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* ---------------------------------------------------------------- TGA */

int ms_tga_write(const ms_image *img, FILE *fp, ms_error *err)
{
    uint8_t h[18] = {0};
    h[2] = 2;                              /* uncompressed true colour */
    le16(h + 12, (unsigned)img->width);
    le16(h + 14, (unsigned)img->height);
    h[16] = 24;
    h[17] = 0x20;                          /* top-left origin */
    if (put(fp, h, sizeof h, err)) return -1;
    size_t row = (size_t)img->width * 3;
    uint8_t *bgr = malloc(row);
    if (!bgr) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    for (int y = 0; y < img->height; y++) {
        const uint8_t *src = img->rgb + (size_t)y * row;
        for (size_t x = 0; x < row; x += 3) {
            bgr[x] = src[x + 2];
            bgr[x + 1] = src[x + 1];
            bgr[x + 2] = src[x];
        }
        if (put(fp, bgr, row, err)) {
            free(bgr);
            return -1;
        }
    }
    free(bgr);
    return 0;
}

int ms_tga_read(FILE *fp, ms_image *img, ms_error *err)
{
    uint8_t h[18];
    img->rgb = NULL;
    if (fread(h, 1, 18, fp) != 18) {
        ms_error_set(err, "TGA: truncated header");
        return -1;
    }
    int type = h[2], bpp = h[16] / 8, rle = type == 10;
    if ((type != 2 && type != 10) || (bpp != 3 && bpp != 4)) {
        ms_error_set(err, "TGA: unsupported image type %d, %d bits", type, h[16]);
        return -1;
    }
    if (fseek(fp, h[0], SEEK_CUR) != 0 ||
        ms_image_alloc(img, (int)rd16(h + 12), (int)rd16(h + 14), err))
        return -1;
    size_t n = (size_t)img->width * (size_t)img->height;
    uint8_t px[4];
    for (size_t i = 0; i < n;) {
        size_t count = 1;
        int repeat = 0;
        if (rle) {
            int c = fgetc(fp);
            if (c == EOF) goto truncated;
            count = (size_t)(c & 0x7f) + 1;
            repeat = c & 0x80;
        }
        for (size_t k = 0; k < count && i < n; k++, i++) {
            if ((k == 0 || !repeat) && fread(px, 1, (size_t)bpp, fp) != (size_t)bpp) goto truncated;
            size_t x = i % (size_t)img->width, y = i / (size_t)img->width;
            if (!(h[17] & 0x20)) y = (size_t)img->height - 1 - y;   /* bottom-left origin */
            uint8_t *d = img->rgb + 3 * (y * (size_t)img->width + x);
            d[0] = px[2];
            d[1] = px[1];
            d[2] = px[0];
        }
    }
    return 0;
truncated:
    ms_image_free(img);
    ms_error_set(err, "TGA: truncated pixel data");
    return -1;
}

/* ---------------------------------------------------------------- PPM */

int ms_ppm_write(const ms_image *img, FILE *fp, ms_error *err)
{
    if (fprintf(fp, "P6\n%d %d\n255\n", img->width, img->height) < 0) {
        ms_error_set(err, "write failed");
        return -1;
    }
    return put(fp, img->rgb, (size_t)img->width * (size_t)img->height * 3, err);
}

/* The next header number of a PPM, skipping blanks and comments. */
static int ppm_number(FILE *fp, int *v)
{
    int c;
    for (;;) {
        c = fgetc(fp);
        if (c == '#') {
            while (c != '\n' && c != EOF) c = fgetc(fp);
        } else if (c != ' ' && c != '\t' && c != '\n' && c != '\r') {
            break;
        }
    }
    long val = 0;
    int digits = 0;
    while (c >= '0' && c <= '9' && val < 1000000) {
        val = val * 10 + (c - '0');
        digits++;
        c = fgetc(fp);
    }
    *v = (int)val;
    return digits ? 0 : -1;
}

int ms_ppm_read(FILE *fp, ms_image *img, ms_error *err)
{
    int w, h, maxv;
    img->rgb = NULL;
    if (fgetc(fp) != 'P' || fgetc(fp) != '6' || ppm_number(fp, &w) || ppm_number(fp, &h) ||
        ppm_number(fp, &maxv) || maxv != 255) {
        ms_error_set(err, "PPM: not an 8-bit binary (P6) header");
        return -1;
    }
    if (ms_image_alloc(img, w, h, err)) return -1;
    size_t n = (size_t)w * (size_t)h * 3;
    if (fread(img->rgb, 1, n, fp) != n) {
        ms_image_free(img);
        ms_error_set(err, "PPM: truncated pixel data");
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------- BMP */

int ms_bmp_write(const ms_image *img, FILE *fp, ms_error *err)
{
    size_t row = ((size_t)img->width * 3 + 3) & ~(size_t)3;
    uint64_t size = 54 + (uint64_t)row * (uint64_t)img->height;
    if (size > 0xffffffffu) {
        ms_error_set(err, "BMP: image too large for the format");
        return -1;
    }
    uint8_t h[54] = {'B', 'M'};
    le32(h + 2, (uint32_t)size);
    le32(h + 10, 54);
    le32(h + 14, 40);
    le32(h + 18, (uint32_t)img->width);
    le32(h + 22, (uint32_t)img->height);
    le16(h + 26, 1);
    le16(h + 28, 24);
    le32(h + 34, (uint32_t)(row * (size_t)img->height));
    le32(h + 38, 2835);
    le32(h + 42, 2835);
    if (put(fp, h, sizeof h, err)) return -1;
    uint8_t *buf = calloc(row, 1);
    if (!buf) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    for (int y = img->height - 1; y >= 0; y--) {
        const uint8_t *src = img->rgb + (size_t)y * (size_t)img->width * 3;
        for (int x = 0; x < img->width; x++) {
            buf[3 * x] = src[3 * x + 2];
            buf[3 * x + 1] = src[3 * x + 1];
            buf[3 * x + 2] = src[3 * x];
        }
        if (put(fp, buf, row, err)) {
            free(buf);
            return -1;
        }
    }
    free(buf);
    return 0;
}

int ms_bmp_read(FILE *fp, ms_image *img, ms_error *err)
{
    uint8_t h[54];
    img->rgb = NULL;
    if (fread(h, 1, 54, fp) != 54 || h[0] != 'B' || h[1] != 'M' || rd16(h + 28) != 24 ||
        rd32(h + 30) != 0) {
        ms_error_set(err, "BMP: not an uncompressed 24-bit bitmap");
        return -1;
    }
    int32_t w = (int32_t)rd32(h + 18), hh = (int32_t)rd32(h + 22);
    int topdown = hh < 0;
    if (topdown) hh = -hh;
    if (fseek(fp, (long)rd32(h + 10), SEEK_SET) != 0 || ms_image_alloc(img, w, hh, err)) return -1;
    size_t row = ((size_t)w * 3 + 3) & ~(size_t)3;
    uint8_t *buf = malloc(row);
    if (!buf) {
        ms_image_free(img);
        ms_error_set(err, "out of memory");
        return -1;
    }
    for (int r = 0; r < hh; r++) {
        if (fread(buf, 1, row, fp) != row) {
            free(buf);
            ms_image_free(img);
            ms_error_set(err, "BMP: truncated pixel data");
            return -1;
        }
        int y = topdown ? r : hh - 1 - r;
        uint8_t *d = img->rgb + (size_t)y * (size_t)w * 3;
        for (int x = 0; x < w; x++) {
            d[3 * x] = buf[3 * x + 2];
            d[3 * x + 1] = buf[3 * x + 1];
            d[3 * x + 2] = buf[3 * x];
        }
    }
    free(buf);
    return 0;
}
