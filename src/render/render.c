/* render.c: what the devices share: images written by their file name, through
 * base/safewrite (a file replaced whole or not at all). */
#include "config.h"
#include "render/render.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---------------------------------------------------------------- files */

int ms_render_write_image(const char *path, ms_render_image_fn make, void *user, ms_error *err)
{
    ms_image_format fmt = ms_image_format_of(path);
    if (fmt == MS_IMG_UNKNOWN) fmt = MS_IMG_TGA;
    ms_ofile *out;
    FILE *f = ms_ofile_open_stream(path, &out, err);
    if (!f) return -1;
    ms_image img;
    int ok = make(user, &img, err) == 0;
    if (ok) {
        if (ms_image_write_stream(&img, fmt, f, err)) {
            /* a failed write's reason (a full disk) says more than the codec's message */
            if (ms_ofile_check(out, err) == 0) ms_error_prefix(err, "%s", path);
            ok = 0;
        }
        ms_image_free(&img);
    }
    return ms_ofile_finish(out, ok, err);
}

