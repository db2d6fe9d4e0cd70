/* render.c: what the devices share: transactional output files (a temporary name renamed at
 * the end) and images written by their file name. */
#include "config.h"
#include "render/render.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---------------------------------------------------------------- files */

FILE *ms_render_open_tmp(const char *path, char **tmp, ms_error *err)
{
    size_t n = strlen(path);
    char *name = malloc(n + 16);
    if (!name) {
        ms_error_set(err, "%s: out of memory", path);
        return NULL;
    }
    memcpy(name, path, n);
    memcpy(name + n, ".tmp-XXXXXX", 12);
    int fd = mkstemp(name);
    if (fd < 0) {
        ms_error_set(err, "%s: cannot write: %s", path, strerror(errno));
        free(name);
        return NULL;
    }
    FILE *f = fdopen(fd, "w");
    if (!f) {
        ms_error_set(err, "%s: cannot write: %s", path, strerror(errno));
        close(fd);
        unlink(name);
        free(name);
        return NULL;
    }
    /* mkstemp makes the file private; give it the permissions a plain fopen would. */
    mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask);
    setvbuf(f, NULL, _IOFBF, 1 << 16);
    *tmp = name;
    return f;
}

int ms_render_commit(FILE *f, char *tmp, const char *path, int ok, ms_error *err)
{
    int failed = !ok;
    if (ok && ferror(f)) {
        ms_error_set(err, "%s: write error: %s", path, strerror(errno));
        failed = 1;
    }
    if (fclose(f) != 0 && !failed) {
        ms_error_set(err, "%s: write error: %s", path, strerror(errno));
        failed = 1;
    }
    if (!failed && rename(tmp, path) != 0) {
        ms_error_set(err, "%s: cannot write: %s", path, strerror(errno));
        failed = 1;
    }
    if (failed) unlink(tmp);
    free(tmp);
    return failed ? -1 : 0;
}

int ms_render_write_image(const char *path, ms_render_image_fn make, void *user, ms_error *err)
{
    ms_image_format fmt = ms_image_format_of(path);
    if (fmt == MS_IMG_UNKNOWN) fmt = MS_IMG_TGA;
    char *tmp;
    FILE *f = ms_render_open_tmp(path, &tmp, err);
    if (!f) return -1;
    ms_image img;
    int ok = make(user, &img, err) == 0;
    if (ok) {
        if (ms_image_write_stream(&img, fmt, f, err)) {
            ms_error_prefix(err, "%s", path);
            ok = 0;
        }
        ms_image_free(&img);
    }
    return ms_render_commit(f, tmp, path, ok, err);
}

