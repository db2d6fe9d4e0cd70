/* image.c: image allocation, format choice by extension, and writing a file through
 * base/safewrite (replaced whole or not at all; devices and FIFOs written in place). */
#include "config.h"
#include "image/image.h"
#include "image/image_codecs.h"
#include "base/safewrite.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

int ms_image_alloc(ms_image *img, int width, int height, ms_error *err)
{
    img->width = img->height = 0;
    img->rgb = NULL;
    if (width < 1 || height < 1 || width > MS_IMAGE_MAX_SIDE || height > MS_IMAGE_MAX_SIDE) {
        ms_error_set(err, "image size %dx%d is out of range (1 to %d pixels a side)", width,
                     height, MS_IMAGE_MAX_SIDE);
        return -1;
    }
    img->rgb = calloc((size_t)width * (size_t)height, 3);
    if (!img->rgb) {
        ms_error_set(err, "out of memory for a %dx%d image", width, height);
        return -1;
    }
    img->width = width;
    img->height = height;
    return 0;
}

void ms_image_free(ms_image *img)
{
    free(img->rgb);
    img->rgb = NULL;
    img->width = img->height = 0;
}

ms_image_format ms_image_format_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    if (!dot) return MS_IMG_UNKNOWN;
    if (!strcasecmp(dot, ".png")) return MS_IMG_PNG;
    if (!strcasecmp(dot, ".tga")) return MS_IMG_TGA;
    if (!strcasecmp(dot, ".ppm")) return MS_IMG_PPM;
    if (!strcasecmp(dot, ".bmp")) return MS_IMG_BMP;
    if (!strcasecmp(dot, ".rgb")) return MS_IMG_SGI;
    return MS_IMG_UNKNOWN;
}

const char *ms_image_format_name(ms_image_format f)
{
    static const char *names[] = {"PNG", "TGA", "PPM", "BMP", "SGI", "unknown"};
    return names[f];
}

int ms_image_write_stream(const ms_image *img, ms_image_format f, void *stdio_file,
                          ms_error *err)
{
    FILE *fp = stdio_file;
    switch (f) {
    case MS_IMG_PNG: return ms_png_write(img, fp, err);
    case MS_IMG_TGA: return ms_tga_write(img, fp, err);
    case MS_IMG_PPM: return ms_ppm_write(img, fp, err);
    case MS_IMG_BMP: return ms_bmp_write(img, fp, err);
    case MS_IMG_SGI: return ms_sgi_write(img, fp, err);
    default: break;
    }
    ms_error_set(err, "unknown image format");
    return -1;
}

int ms_image_write(const ms_image *img, const char *path, ms_error *err)
{
    ms_image_format f = ms_image_format_of(path);
    if (f == MS_IMG_UNKNOWN) {
        ms_error_set(err, "%s: cannot tell the image format from the name (use .png, .tga, "
                          ".ppm, .bmp or .rgb)", path);
        return -1;
    }
    ms_ofile *out;
    FILE *fp = ms_ofile_open_stream(path, &out, err);
    if (!fp) return -1;
    int ok = ms_image_write_stream(img, f, fp, err) == 0;
    /* a failed write's reason (a full disk) says more than the codec's message */
    if (!ok && ms_ofile_check(out, err) == 0) ms_error_prefix(err, "%s", path);
    return ms_ofile_finish(out, ok, err);
}

int ms_image_png_mem(const ms_image *img, unsigned char **buf, size_t *len, ms_error *err)
{
    char *mem = NULL;
    size_t n = 0;
    FILE *fp = open_memstream(&mem, &n);
    if (!fp) {
        ms_error_set(err, "out of memory for the image");
        return -1;
    }
    int rc = ms_image_write_stream(img, MS_IMG_PNG, fp, err);
    if (fclose(fp) != 0 && rc == 0) {
        ms_error_set(err, "out of memory for the image");
        rc = -1;
    }
    if (rc) {
        free(mem);
        return -1;
    }
    *buf = (unsigned char *)mem;
    *len = n;
    return 0;
}

int ms_image_read(const char *path, ms_image *img, ms_error *err)
{
    FILE *fp = fopen(path, "rb");
    if (!fp) {
        ms_error_set(err, "%s: %s", path, strerror(errno));
        return -1;
    }
    unsigned char magic[8] = {0};
    size_t got = fread(magic, 1, sizeof magic, fp);
    rewind(fp);
    int rc;
    if (got >= 8 && !memcmp(magic, "\x89PNG\r\n\x1a\n", 8)) rc = ms_png_read(fp, img, err);
    else if (got >= 2 && magic[0] == 'P' && magic[1] == '6') rc = ms_ppm_read(fp, img, err);
    else if (got >= 2 && magic[0] == 'B' && magic[1] == 'M') rc = ms_bmp_read(fp, img, err);
    else if (got >= 2 && magic[0] == 0x01 && magic[1] == 0xda) rc = ms_sgi_read(fp, img, err);
    else rc = ms_tga_read(fp, img, err);
    fclose(fp);
    if (rc != 0) ms_error_prefix(err, "%s", path);
    return rc;
}
