/* dx.c: the OpenDX volume plugin (APBS, VMD's volmap, PyMOL): "object 1 class gridpositions
 * counts nx ny nz", "origin", three "delta" lines, "object 2 class gridconnections", then
 * "object 3 class array ... items N data follows" and N values with z varying fastest.
 * Reads one data set per file (ASCII data); writes the same layout with every float
 * written exactly (9 significant digits). */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct dx_reader {
    ms_lines in;
    ms_volume_meta meta;
    long long data_at;     /* offset of the line after "data follows" */
    long data_line;
    char *rest;            /* values on the "data follows" line itself, if any */
} dx_reader;

static char *ms_strdup_p(const char *s)
{
    size_t n = strlen(s) + 1;
    char *c = malloc(n);
    if (c) memcpy(c, s, n);
    return c;
}

static void dx_close_read(void *h)
{
    dx_reader *r = h;
    free(r->rest);
    ms_lines_destroy(r);
}

/* Parse up to n numbers after `key` in a header line. */
static int header_numbers(const char *line, const char *key, double *v, int n)
{
    const char *p = strstr(line, key);
    if (!p) return 0;
    p += strlen(key);
    char *tok[8], buf[512];
    snprintf(buf, sizeof buf, "%s", p);
    int nt = ms_tokens(buf, tok, 8), got = 0;
    for (int k = 0; k < nt && got < n; k++)
        if (ms_parse_double(tok[k], strlen(tok[k]), &v[got]) == 1) got++;
        else break;
    return got;
}

/* The header, up to the line that says "data follows". */
static int read_header(dx_reader *r, ms_perr *err)
{
    ms_lines *in = &r->in;
    int have_counts = 0, have_origin = 0, ndelta = 0;
    long items = -1, counts_line = 0;
    const char *l;
    while ((l = ms_lines_next(in))) {
        const char *p = l + strspn(l, " \t");
        if (*p == '#' || *p == '\0') continue;
        double v[3];
        if (!strncmp(p, "object", 6) && strstr(p, "gridpositions")) {
            if (header_numbers(p, "counts", v, 3) != 3 || !(v[0] >= 1 && v[0] <= 1e9) ||
                !(v[1] >= 1 && v[1] <= 1e9) || !(v[2] >= 1 && v[2] <= 1e9)) /* NaN too */
                return ms_perr_set(err, "line %ld: bad gridpositions counts", in->line_no);
            for (int d = 0; d < 3; d++) r->meta.n[d] = (long)v[d];
            have_counts = 1;
            counts_line = in->line_no;
        } else if (!strncmp(p, "origin", 6)) {
            if (header_numbers(p, "origin", r->meta.origin, 3) != 3)
                return ms_perr_set(err, "line %ld: bad origin", in->line_no);
            have_origin = 1;
        } else if (!strncmp(p, "delta", 5)) {
            if (ndelta >= 3 || header_numbers(p, "delta", r->meta.delta[ndelta], 3) != 3)
                return ms_perr_set(err, "line %ld: bad delta", in->line_no);
            ndelta++;
        } else if (!strncmp(p, "object", 6) && strstr(p, "class array")) {
            if (strstr(p, "binary") || strstr(p, "data file"))
                return ms_perr_set(err, "line %ld: binary or external DX data is not supported",
                                   in->line_no);
            if (header_numbers(p, "items", v, 1) == 1) {
                if (!(v[0] >= 0 && v[0] <= 1e15)) /* NaN too; no grid holds more */
                    return ms_perr_set(err, "line %ld: bad item count %g", in->line_no, v[0]);
                items = (long)v[0];
            }
            const char *follows = strstr(p, "data follows");
            if (!follows) return ms_perr_set(err, "line %ld: expected 'data follows'", in->line_no);
            const char *after = follows + strlen("data follows");
            if (after[strspn(after, " \t")] && !(r->rest = ms_strdup_p(after)))
                return ms_perr_set(err, "out of memory");
            break;
        }
    }
    if (!l) {
        if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
        return ms_perr_set(err, "line %ld: the file ends before the data (no 'object ... class "
                           "array ... data follows' record)", in->line_no);
    }
    if (!have_counts) return ms_perr_set(err, "no gridpositions record before the data");
    if (!have_origin) return ms_perr_set(err, "no origin record before the data");
    if (ndelta != 3) return ms_perr_set(err, "%d delta records, expected 3", ndelta);
    double total = (double)r->meta.n[0] * (double)r->meta.n[1] * (double)r->meta.n[2];
    if (items >= 0 && (double)items != total)
        return ms_perr_set(err, "line %ld: %ld items, but the grid has %.0f points", in->line_no,
                           items, total);
    /* A value is at least a digit and a separator: the file bounds the grid. */
    long long left = ms_lines_left(in);
    if (left >= 0 && r->rest) left += (long long)strlen(r->rest);
    if (ms_check_room(err, total, 2, left, "values",
                      "line %ld: the header declares %ld x %ld x %ld points", counts_line,
                      r->meta.n[0], r->meta.n[1], r->meta.n[2]))
        return MS_PLUGIN_ERROR;
    r->data_at = ms_lines_tell_next(in);
    r->data_line = in->line_no;
    return MS_PLUGIN_OK;
}

static void *dx_open_read(const char *path, long *natoms, ms_perr *err)
{
    dx_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    if (read_header(r, err) != MS_PLUGIN_OK) {
        dx_close_read(r);
        return NULL;
    }
    *natoms = 0;
    return r;
}

static int dx_read_volume_meta(void *h, int k, ms_volume_meta *meta, ms_perr *err)
{
    (void)err;
    dx_reader *r = h;
    if (k != 0) return MS_PLUGIN_EOF;
    *meta = r->meta;
    return MS_PLUGIN_OK;
}

static int dx_read_volume_data(void *h, int k, float *data, ms_perr *err)
{
    dx_reader *r = h;
    if (k != 0) return ms_perr_set(err, "no volume set %d", k);
    size_t n = (size_t)r->meta.n[0] * (size_t)r->meta.n[1] * (size_t)r->meta.n[2];
    float *tmp = malloc(n * sizeof *tmp);
    if (!tmp) return ms_perr_set(err, "out of memory for %zu values", n);
    if (ms_lines_seek(&r->in, r->data_at, r->data_line) != 0 ||
        ms_read_floats(&r->in, r->rest, tmp, n, err) != MS_PLUGIN_OK) {
        if (!err->msg[0]) ms_perr_set(err, "cannot seek to the data");
        free(tmp);
        return MS_PLUGIN_ERROR;
    }
    ms_grid_zfast_to_xfast(tmp, data, r->meta.n);
    free(tmp);
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

static void *dx_open_write(const char *path, long natoms, ms_perr *err)
{
    (void)natoms;
    ms_out *o = ms_out_create(sizeof *o, path, err);
    if (!o) return NULL;
    return o;
}

static int dx_write_volume(void *h, const ms_volume_meta *m, const float *data, ms_perr *err)
{
    ms_out *o = h;
    size_t n = (size_t)m->n[0] * (size_t)m->n[1] * (size_t)m->n[2];
    float *z = malloc((n ? n : 1) * sizeof *z);
    if (!z) return ms_perr_set(err, "out of memory");
    ms_grid_xfast_to_zfast(data, z, m->n);
    ms_out_printf(o, "# %s\n# written by molscope\n", m->name[0] ? m->name : "volume");
    ms_out_printf(o, "object 1 class gridpositions counts %ld %ld %ld\n", m->n[0], m->n[1], m->n[2]);
    ms_out_printf(o, "origin %.9g %.9g %.9g\n", m->origin[0], m->origin[1], m->origin[2]);
    for (int d = 0; d < 3; d++)
        ms_out_printf(o, "delta %.9g %.9g %.9g\n", m->delta[d][0], m->delta[d][1], m->delta[d][2]);
    ms_out_printf(o, "object 2 class gridconnections counts %ld %ld %ld\n", m->n[0], m->n[1],
                  m->n[2]);
    ms_out_printf(o, "object 3 class array type double rank 0 items %zu data follows\n", n);
    for (size_t i = 0; i < n; i++)
        ms_out_printf(o, "%.9g%c", (double)z[i], i % 3 == 2 || i + 1 == n ? '\n' : ' ');
    ms_out_printf(o, "attribute \"dep\" string \"positions\"\n");
    ms_out_printf(o, "object \"%s\" class field\n", "regular positions regular connections");
    ms_out_printf(o, "component \"positions\" value 1\ncomponent \"connections\" value 2\n"
                     "component \"data\" value 3\n");
    free(z);
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int dx_close_write(void *h, ms_perr *err)
{
    ms_out *o = h;
    return ms_out_destroy(o, err);
}

static const ms_plugin dx_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "dx",
    .description = "OpenDX volumetric data",
    .extensions = "dx",
    .caps = MS_CAN_READ_VOLUME | MS_CAN_WRITE_VOLUME,
    .open_read = dx_open_read,
    .close_read = dx_close_read,
    .open_write = dx_open_write,
    .close_write = dx_close_write,
    .read_volume_meta = dx_read_volume_meta,
    .read_volume_data = dx_read_volume_data,
    .write_volume = dx_write_volume,
};

const ms_plugin *ms_plugin_entry(void) { return &dx_plugin; }
