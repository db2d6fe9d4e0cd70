/* frames.c: a movie's frame files: their names, the check that a file is a whole PNG or SGI
 * image of the movie's size that decodes (every row, every checksum), the list of frames
 * still to render, and the clean-up of what a killed job left behind. */
#include "config.h"
#include "movie/movie.h"
#include "base/safewrite.h"
#include "image/image.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

const char *ms_movie_frame_ext(ms_movie_frames format)
{
    return format == MS_FRAMES_RGB ? ".rgb" : ".png";
}

char *ms_movie_frame_path(const char *basename, ms_movie_frames format, long i)
{
    size_t n = strlen(basename) + 48;
    char *p = malloc(n);
    if (p) snprintf(p, n, "%s.%05ld%s", basename, i, ms_movie_frame_ext(format));
    return p;
}

static uint32_t be32(const unsigned char *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

/* Walk the chunks after the signature: 1 when they end with IEND exactly at size and
 * the first is an IHDR of w x h. */
static int png_chunks_ok(FILE *f, long long size, int w, int h)
{
    long long off = 8;
    int idat = 0;
    for (int k = 0;; k++) {
        unsigned char head[8 + 13];
        if (off + 12 > size || fseeko(f, (off_t)off, SEEK_SET) != 0) return 0;
        size_t want = k == 0 ? sizeof head : 8;
        if (fread(head, 1, want, f) != want) return 0;
        uint32_t len = be32(head);
        if (len > 0x7fffffffu) return 0;
        if (k == 0 && (memcmp(head + 4, "IHDR", 4) != 0 || len != 13 ||
                       be32(head + 8) != (uint32_t)w || be32(head + 12) != (uint32_t)h))
            return 0;
        if (!memcmp(head + 4, "IDAT", 4)) idat = 1;
        off += 12 + (long long)len;
        if (!memcmp(head + 4, "IEND", 4)) return len == 0 && off == size && idat;
    }
}

static void decode_error(png_structp png, png_const_charp msg)
{
    (void)msg;
    png_longjmp(png, 1);
}

static void decode_warning(png_structp png, png_const_charp msg) { (void)png, (void)msg; }

/* Decode the whole PNG at the start of f with libpng, every row and the chunks after them,
 * with a CRC error in any chunk an error: 1 when it decodes, 0 when not. A file whose
 * chunks are intact can still hold a damaged byte of pixel data. */
static int png_decodes(FILE *f)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, decode_error,
                                             decode_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    png_bytep row = NULL;
    int ok = 0;
    if (!png || !info) goto done;
    if (setjmp(png_jmpbuf(png))) goto done;
    png_set_crc_action(png, PNG_CRC_ERROR_QUIT, PNG_CRC_ERROR_QUIT);
    rewind(f);
    png_init_io(png, f);
    png_read_info(png, info);
    if (png_get_interlace_type(png, info) != PNG_INTERLACE_NONE) png_set_interlace_handling(png);
    png_read_update_info(png, info);
    png_uint_32 h = png_get_image_height(png, info);
    int passes = png_get_interlace_type(png, info) != PNG_INTERLACE_NONE ? 7 : 1;
    if (!(row = malloc(png_get_rowbytes(png, info)))) goto done;
    for (int pass = 0; pass < passes; pass++)
        for (png_uint_32 y = 0; y < h; y++) png_read_row(png, row, NULL);
    png_read_end(png, NULL);
    ok = 1;
done:
    free(row);
    png_destroy_read_struct(png ? &png : NULL, info ? &info : NULL, NULL);
    return ok;
}

#define SGI_HEADER 512

/* An SGI frame: VMD's header (magic 474, one byte a channel, three dimensions, three or
 * four channels) of width x height, exactly the pixels' length when stored verbatim, and
 * every row of every channel decodes. */
static int sgi_frame_ok(const char *path, int width, int height)
{
    FILE *f = fopen(path, "rb");
    unsigned char h[SGI_HEADER];
    struct stat sb;
    int ok = f && fstat(fileno(f), &sb) == 0 && S_ISREG(sb.st_mode) &&
             fread(h, 1, sizeof h, f) == sizeof h;
    if (f) fclose(f);
    unsigned dim = ok ? (unsigned)h[4] << 8 | h[5] : 0, w = ok ? (unsigned)h[6] << 8 | h[7] : 0,
             ht = ok ? (unsigned)h[8] << 8 | h[9] : 0, nch = ok ? (unsigned)h[10] << 8 | h[11] : 0;
    ok = ok && h[0] == 0x01 && h[1] == 0xda && h[2] <= 1 && h[3] == 1 && dim == 3 &&
         (nch == 3 || nch == 4) && w == (unsigned)width && ht == (unsigned)height;
    if (ok && h[2] == 0)
        ok = (long long)sb.st_size == SGI_HEADER + (long long)w * ht * nch;
    ms_image img = {0};
    ms_error err = {{0}};
    ok = ok && ms_image_read(path, &img, &err) == 0;
    ms_image_free(&img);
    return ok;
}

/* The extension of path is .rgb (any case). */
static int is_rgb_name(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && !strcasecmp(path + n - 4, ".rgb");
}

int ms_movie_frame_ok(const char *path, int width, int height)
{
    if (is_rgb_name(path)) return sgi_frame_ok(path, width, height);
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    struct stat sb;
    unsigned char sig[8];
    int ok = fstat(fileno(f), &sb) == 0 && S_ISREG(sb.st_mode) &&
             fread(sig, 1, 8, f) == 8 && !memcmp(sig, "\x89PNG\r\n\x1a\n", 8) &&
             png_chunks_ok(f, (long long)sb.st_size, width, height) && png_decodes(f);
    fclose(f);
    return ok;
}

/* The folder and the file-name prefix "<tail>." of a basename (both malloc'd). */
static int split_base(const char *basename, char **dir, char **prefix)
{
    const char *slash = strrchr(basename, '/');
    *dir = slash ? strndup(basename, (size_t)(slash - basename) + 1) : ms_strdup(".");
    const char *tail = slash ? slash + 1 : basename;
    size_t n = strlen(tail);
    *prefix = malloc(n + 2);
    if (*prefix) {
        memcpy(*prefix, tail, n);
        memcpy(*prefix + n, ".", 2);
    }
    if (*dir && *prefix) return 0;
    free(*dir);
    free(*prefix);
    return -1;
}

/* The frames' file-name prefix "<tail>." and extension ".png", for is_stale. */
typedef struct frame_names {
    const char *prefix, *ext;
} frame_names;

/* Is name a leftover of frame "<prefix><digits><ext>": a temporary file of it (or of a
 * renderer writing that one), or the "<prefix><digits>.part<ext>..." of earlier versions? */
static int is_stale(const char *name, const void *names_arg)
{
    const frame_names *fn = names_arg;
    size_t n = strlen(fn->prefix), e = strlen(fn->ext);
    if (strncmp(name, fn->prefix, n) != 0) return 0;
    const char *p = name + n;
    if (*p < '0' || *p > '9') return 0;
    while (*p >= '0' && *p <= '9') p++;
    if (!strncmp(p, ".part", 5) && !strncmp(p + 5, fn->ext, e)) return 1;
    size_t stem = (size_t)(p - name);
    char *frame = malloc(stem + e + 1);
    if (!frame) return 0;
    memcpy(frame, name, stem);
    memcpy(frame + stem, fn->ext, e + 1);
    int yes = ms_ofile_is_temp(name, frame);
    free(frame);
    return yes;
}

/* Is name a leftover of the video whose base name is video_base: a temporary file of it,
 * or the "<stem>.part<ext>" of earlier versions? */
static int is_stale_video(const char *name, const void *base_arg)
{
    const char *base = base_arg;
    if (ms_ofile_is_temp(name, base)) return 1;
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base) return 0;
    size_t stem = (size_t)(dot - base);
    return !strncmp(name, base, stem) && !strncmp(name + stem, ".part", 5) &&
           !strcmp(name + stem + 5, dot);
}

/* Remove the files of folder dir whose names match; how many were removed. */
static long remove_matching(const char *dir, int (*match)(const char *, const void *),
                            const void *arg)
{
    long removed = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d))) {
        if (!match(e->d_name, arg)) continue;
        size_t n = strlen(dir) + strlen(e->d_name) + 2;
        char *p = malloc(n);
        if (!p) break;
        snprintf(p, n, "%s/%s", dir, e->d_name);
        if (unlink(p) == 0) removed++;
        free(p);
    }
    if (d) closedir(d);
    return removed;
}

long ms_movie_remove_stale(const char *basename, ms_movie_frames format)
{
    char *dir, *prefix;
    if (split_base(basename, &dir, &prefix)) return 0;
    frame_names fn = {prefix, ms_movie_frame_ext(format)};
    long removed = remove_matching(dir, is_stale, &fn);
    free(dir);
    free(prefix);
    return removed;
}

long ms_movie_remove_stale_video(const char *video)
{
    const char *slash = strrchr(video, '/');
    char *dir = slash ? strndup(video, (size_t)(slash - video) + 1) : ms_strdup(".");
    if (!dir) return 0;
    long removed = remove_matching(dir, is_stale_video, slash ? slash + 1 : video);
    free(dir);
    return removed;
}

int ms_movie_scan(const char *basename, ms_movie_frames format, long n, int width, int height,
                  long **missing, long *nmissing, ms_error *err)
{
    *missing = NULL;
    *nmissing = 0;
    size_t cap = 0;
    for (long i = 0; i < n; i++) {
        char *p = ms_movie_frame_path(basename, format, i);
        int ok = p && ms_movie_frame_ok(p, width, height);
        free(p);
        if (!p || (!ok && ms_grow((void **)missing, &cap, (size_t)*nmissing + 1,
                                  sizeof **missing))) {
            free(*missing);
            *missing = NULL;
            *nmissing = 0;
            ms_error_set(err, "out of memory");
            return -1;
        }
        if (!ok) (*missing)[(*nmissing)++] = i;
    }
    return 0;
}

/* mkdir -p of dir (which is modified in place and restored). */
static int make_dirs(char *dir)
{
    for (char *p = dir + 1;; p++) {
        if (*p != '/' && *p != '\0') continue;
        char c = *p;
        *p = '\0';
        int rc = mkdir(dir, 0777);
        *p = c;
        if (rc != 0 && errno != EEXIST) return -1;
        if (c == '\0') return 0;
    }
}

int ms_movie_check_dir(const char *path, ms_error *err)
{
    const char *slash = strrchr(path, '/');
    char *dir = slash ? strndup(path, slash == path ? 1 : (size_t)(slash - path))
                      : ms_strdup(".");
    size_t n = dir ? strlen(dir) + 32 : 0;
    char *probe = dir ? malloc(n) : NULL;
    if (!probe) {
        free(dir);
        ms_error_set(err, "out of memory");
        return -1;
    }
    struct stat sb;
    int rc = 0;
    if (stat(dir, &sb) != 0 && make_dirs(dir) != 0) {
        ms_error_set(err, "cannot create the folder %s: %s", dir, strerror(errno));
        rc = -1;
    } else {
        snprintf(probe, n, "%s/.molscope-XXXXXX", dir);
        int fd = mkstemp(probe);
        if (fd < 0) {
            ms_error_set(err, "cannot write in the folder %s: %s", dir, strerror(errno));
            rc = -1;
        } else {
            close(fd);
            unlink(probe);
        }
    }
    free(probe);
    free(dir);
    return rc;
}

double ms_movie_process_start(void)
{
    /* starttime is field 22 of /proc/self/stat, in clock ticks since boot: its age is the
     * boot-time clock now minus that, and the start is that long before the real time. */
    char buf[1024];
    FILE *f = fopen("/proc/self/stat", "r");
    size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    if (f) fclose(f);
    buf[n] = '\0';
    char *p = strrchr(buf, ')');
    unsigned long long ticks = 0;
    for (int field = 2; p && *p; p++)   /* p at ")": field 2 ends here */
        if (*p == ' ' && ++field == 22) {
            ticks = strtoull(p + 1, NULL, 10);
            break;
        }
    long hz = sysconf(_SC_CLK_TCK);
    struct timespec boot, real;
    if (!ticks || hz <= 0 || clock_gettime(CLOCK_BOOTTIME, &boot) != 0 ||
        clock_gettime(CLOCK_REALTIME, &real) != 0)
        return -1;
    double age = (double)boot.tv_sec + boot.tv_nsec * 1e-9 - (double)ticks / (double)hz;
    return (double)real.tv_sec + real.tv_nsec * 1e-9 - age;
}
