/* image.h: RGB images and their files. Every image device (snapshot, TachyonInternal, the
 * OpenCL tracer, movies) writes through here: the format follows the file's extension (.png
 * .tga .ppm .bmp .rgb, as VMD picks them), PNG is written with libpng's fast settings (compression
 * level 1 and the UP filter: about 6x faster than the defaults at about the same size), and
 * every file is written to a temporary name and renamed when complete, so a failure (a bad
 * path, a full disk) is an error that leaves no partial file. Readers exist for the tests. */
#ifndef MS_IMAGE_H
#define MS_IMAGE_H

#include <stddef.h>
#include <stdint.h>

#include "base/base.h"

typedef struct ms_image {
    int width, height;
    uint8_t *rgb;        /* 3 * width * height bytes, top row first */
} ms_image;

typedef enum ms_image_format {
    MS_IMG_PNG, MS_IMG_TGA, MS_IMG_PPM, MS_IMG_BMP, MS_IMG_SGI, MS_IMG_UNKNOWN
} ms_image_format;

/* The largest side accepted (a size beyond it is an error, never an allocation attempt). */
#define MS_IMAGE_MAX_SIDE 32768

/* Allocate a black image. 0, or -1 with err set (bad size, no memory). */
int ms_image_alloc(ms_image *img, int width, int height, ms_error *err);
void ms_image_free(ms_image *img);

/* The format a file name asks for, MS_IMG_UNKNOWN when its extension is none of them. */
ms_image_format ms_image_format_of(const char *path);
const char *ms_image_format_name(ms_image_format f);

/* Write by extension (an unknown extension is an error naming the ones known). */
int ms_image_write(const ms_image *img, const char *path, ms_error *err);
/* Write in a given format to a stdio stream (movies pipe frames to an encoder). */
int ms_image_write_stream(const ms_image *img, ms_image_format f, void *stdio_file,
                          ms_error *err);
/* Encode as PNG (libpng's fast settings) in memory: *buf (malloc'd, the caller frees it) of
 * *len bytes. 0, or -1 with err set and nothing allocated. */
int ms_image_png_mem(const ms_image *img, unsigned char **buf, size_t *len, ms_error *err);
/* Read a PNG, TGA (uncompressed or RLE, 24/32 bit), PPM (P6), BMP (24 bit) or SGI (8 bit,
 * verbatim or RLE) file. */
int ms_image_read(const char *path, ms_image *img, ms_error *err);

#endif
