/* test_image.c: image files: every format written and read back pixel for pixel, errors for
 * bad paths, unknown extensions and absurd sizes, and no partial file left after a failure. */
#include "config.h"
#include "ms_test.h"
#include "image/image.h"

#include <dirent.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *out_dir(void)
{
    const char *d = getenv("MS_TEST_OUT");
    return d ? d : "/tmp";
}

static int count_files(const char *dir, const char *prefix)
{
    DIR *d = opendir(dir);
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (!strncmp(e->d_name, prefix, strlen(prefix))) n++;
    if (d) closedir(d);
    return n;
}

/* A 3 x 2 RLE SGI file made by hand: red runs, green literals, blue zero; the bottom row
 * first. Read back top row first; then the same file cut short is an error. */
static void sgi_rle(void)
{
    static const uint8_t rows[6][4] = {
        {0x03, 10, 0}, {0x03, 20, 0},                      /* red: bottom 10s, top 20s */
        {0x83, 1, 2, 3}, {0x83, 4, 5, 6},                  /* green: literals */
        {0x03, 0, 0}, {0x03, 0, 0}};                       /* blue */
    static const int len[6] = {3, 3, 4, 4, 3, 3};
    uint8_t f[512 + 48 + 24] = {0x01, 0xda, 1, 1, 0, 3, 0, 3, 0, 2, 0, 3};
    uint32_t off = 512 + 48;
    for (int i = 0; i < 6; i++) {
        for (int k = 0; k < 4; k++) {
            f[512 + 4 * i + k] = (uint8_t)(off >> (24 - 8 * k));
            f[512 + 24 + 4 * i + k] = (uint8_t)((uint32_t)len[i] >> (24 - 8 * k));
        }
        memcpy(f + off, rows[i], (size_t)len[i]);
        off += (uint32_t)len[i];
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/img_rle.rgb", out_dir());
    FILE *fp = fopen(path, "wb");
    fwrite(f, 1, off, fp);
    fclose(fp);
    ms_image back = {0};
    ms_error err = {{0}};
    static const uint8_t want[18] = {20, 4, 0, 20, 5, 0, 20, 6, 0, 10, 1, 0, 10, 2, 0, 10, 3, 0};
    int ok = ms_image_read(path, &back, &err) == 0 && back.width == 3 && back.height == 2 &&
             !memcmp(back.rgb, want, sizeof want);
    t_ok(ok, "an RLE SGI file is read (%s)", ok ? "" : err.msg);
    ms_image_free(&back);
    fp = fopen(path, "wb");
    fwrite(f, 1, off - 4, fp);
    fclose(fp);
    t_ok(ms_image_read(path, &back, &err) == -1 && strstr(err.msg, "SGI: truncated"),
         "a truncated SGI file is an error (%s)", err.msg);
}

int main(void)
{
    t_suite = "image";
    ms_image img;
    ms_error err = {{0}};
    /* 37 x 23: odd sizes exercise BMP row padding. */
    t_ok(ms_image_alloc(&img, 37, 23, &err) == 0, "allocate 37x23");
    for (int y = 0; y < img.height; y++)
        for (int x = 0; x < img.width; x++) {
            uint8_t *p = img.rgb + 3 * (y * img.width + x);
            p[0] = (uint8_t)(x * 7);
            p[1] = (uint8_t)(y * 11);
            p[2] = (uint8_t)(x * y);
        }
    const char *ext[] = {"png", "tga", "ppm", "bmp", "rgb"};
    for (int k = 0; k < 5; k++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/img_rt.%s", out_dir(), ext[k]);
        ms_image back = {0};
        int ok = ms_image_write(&img, path, &err) == 0 && ms_image_read(path, &back, &err) == 0 &&
                 back.width == 37 && back.height == 23 &&
                 memcmp(back.rgb, img.rgb, (size_t)37 * 23 * 3) == 0;
        t_ok(ok, "%s written and read back pixel for pixel (%s)", ext[k], ok ? "" : err.msg);
        ms_image_free(&back);
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/nodir/x.png", out_dir());
    t_ok(ms_image_write(&img, path, &err) == -1 && strstr(err.msg, "No such file"),
         "a bad path is an error (%s)", err.msg);
    snprintf(path, sizeof path, "%s/img.xyz", out_dir());
    t_ok(ms_image_write(&img, path, &err) == -1 && strstr(err.msg, "image format"),
         "an unknown extension is an error (%s)", err.msg);
    t_ok(count_files(out_dir(), "img.xyz") == 0 && count_files(out_dir(), "img_rt.tmp-") == 0,
         "no partial or temporary file is left");
    ms_image bad;
    t_ok(ms_image_alloc(&bad, 0, 10, &err) == -1 && strstr(err.msg, "out of range"),
         "a zero size is an error (%s)", err.msg);
    t_ok(ms_image_alloc(&bad, 100000, 100000, &err) == -1 && strstr(err.msg, "out of range"),
         "an absurd size is an error, not an allocation (%s)", err.msg);
    /* A full disk: /dev/full accepts the open and fails the writes. */
    if (access("/dev/full", W_OK) == 0) {
        ms_image big;
        ms_image_alloc(&big, 512, 512, &err);
        FILE *f = fopen("/dev/full", "wb");
        int rc = ms_image_write_stream(&big, MS_IMG_PPM, f, &err);
        int rc2 = fflush(f);
        fclose(f);
        t_ok(rc != 0 || rc2 != 0, "a full disk is reported");
        ms_image_free(&big);
    }
    ms_image_free(&img);
    sgi_rle();
    return t_done();
}
