/* image_codecs.h: the file formats behind image.h, each reading or writing a stdio stream.
 * Internal to the image module. */
#ifndef MS_IMAGE_CODECS_H
#define MS_IMAGE_CODECS_H

#include <stdio.h>

#include "image/image.h"

int ms_png_write(const ms_image *img, FILE *fp, ms_error *err);
int ms_png_read(FILE *fp, ms_image *img, ms_error *err);
int ms_tga_write(const ms_image *img, FILE *fp, ms_error *err);
int ms_tga_read(FILE *fp, ms_image *img, ms_error *err);
int ms_ppm_write(const ms_image *img, FILE *fp, ms_error *err);
int ms_ppm_read(FILE *fp, ms_image *img, ms_error *err);
int ms_bmp_write(const ms_image *img, FILE *fp, ms_error *err);
int ms_bmp_read(FILE *fp, ms_image *img, ms_error *err);
int ms_sgi_write(const ms_image *img, FILE *fp, ms_error *err);
int ms_sgi_read(FILE *fp, ms_image *img, ms_error *err);

#endif
