/* rst7.c: AMBER's ASCII restart and input coordinates, VMD's type `rst7` (.rst7 .inpcrd
 * .restrt .rst). A title line; the atom count and, optionally, the time; then the 3N
 * coordinates six a line in 12 columns, optionally the 3N velocities (AMBER's units:
 * Angstrom per 1/20.455 ps, read as Angstrom/ps) and a box line (a b c alpha beta gamma).
 * Which of these follow is told by how many values there are. One frame. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <stdlib.h>
#include <string.h>

#define RST_W 12
#define AMBER_VEL_SCALE 20.455

typedef struct rst7_reader {
    ms_lines in;
    long natoms;
    double time;
    int has_time, done;
} rst7_reader;

static void rst7_close_read(void *h) { ms_lines_destroy(h); }

/* Line 2: the atom count, then the time when there is one. */
static int read_count_line(rst7_reader *r, ms_perr *err)
{
    if (!ms_lines_next(&r->in) || !ms_lines_next(&r->in))
        return ms_perr_set(err, "the file ends before the atom count line (line 2)");
    char buf[256], *tok[4];
    snprintf(buf, sizeof buf, "%s", r->in.line);
    int nt = ms_tokens(buf, tok, 4);
    if (nt < 1 || ms_parse_long(tok[0], strlen(tok[0]), &r->natoms) < 0 || r->natoms < 1)
        return ms_perr_set(err, "line 2: bad atom count '%s' (not an AMBER restart?)",
                           nt ? tok[0] : "");
    if (nt >= 2 && ms_parse_double(tok[1], strlen(tok[1]), &r->time) == 1) r->has_time = 1;
    /* The coordinates take 3 values of 12 columns an atom, at the least. */
    return ms_check_room(err, (double)r->natoms, 3.0 * RST_W, ms_lines_left(&r->in), "atoms",
                         "line 2: the file declares %ld atoms", r->natoms);
}

static void *rst7_open_read(const char *path, long *natoms, ms_perr *err)
{
    rst7_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    if (read_count_line(r, err)) {
        ms_lines_destroy(r);
        return NULL;
    }
    *natoms = r->natoms;
    return r;
}

/* Every value after line 2, up to max; returns the count, or -1 with err set. */
static long read_values(rst7_reader *r, double *v, size_t max, ms_perr *err)
{
    size_t n = 0;
    while (ms_lines_next(&r->in)) {
        size_t len = r->in.line_len;
        while (len && (r->in.line[len - 1] == ' ' || r->in.line[len - 1] == '\r')) len--;
        for (size_t c = 0; c < len; c += RST_W) {
            char tok[RST_W + 1];
            ms_field(r->in.line, len, c, c + RST_W, tok);
            if (n == max)
                return ms_perr_set(err, "line %ld: more values than %ld atoms' coordinates, "
                                        "velocities and box: wrong atom count on line 2",
                                   r->in.line_no, r->natoms);
            if (ms_parse_double(tok, strlen(tok), &v[n]) < 0)
                return ms_perr_set(err, "line %ld: bad number '%s' in columns %zu-%zu",
                                   r->in.line_no, tok, c + 1, c + RST_W);
            n++;
        }
    }
    if (r->in.error) return ms_perr_set(err, "read error after line %ld", r->in.line_no);
    return (long)n;
}

/* Split n values into coordinates, velocities and box by their count. */
static int layout(long n, long natoms, int *vel, int *box)
{
    long c = 3 * natoms;
    static const int kinds[][3] = {{0, 0, 0}, {0, 6, 1}, {0, 3, 1}, {1, 0, 0}, {1, 6, 1},
                                   {1, 3, 1}};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++)
        if (n == c * (1 + kinds[k][0]) + kinds[k][1]) {
            *vel = kinds[k][0];
            *box = kinds[k][2];
            return 0;
        }
    return -1;
}

static int fill_frame(rst7_reader *r, const double *v, long n, ms_frame_out *fr, ms_perr *err)
{
    int vel, box;
    size_t c = 3 * (size_t)r->natoms;
    if (layout(n, r->natoms, &vel, &box))
        return ms_perr_set(err, "%ld values after line 2: %ld atoms need %zu coordinates (and "
                                "as many velocities, and a box line): truncated file or wrong "
                                "atom count", n, r->natoms, c);
    for (size_t i = 0; fr->pos && i < c; i++) fr->pos[i] = (float)v[i];
    if (vel && fr->vel) {
        for (size_t i = 0; i < c; i++) fr->vel[i] = (float)(v[c + i] * AMBER_VEL_SCALE);
        fr->has_vel = 1;
    }
    if (box) {
        const double *b = v + c * (size_t)(1 + vel);
        int six = n - (long)(c * (size_t)(1 + vel)) == 6;
        for (int k = 0; k < 6; k++) fr->cell[k] = k < 3 || six ? (float)b[k] : 90.0f;
        fr->has_cell = 1;
    }
    fr->time = r->time;
    fr->has_time = r->has_time;
    return MS_PLUGIN_OK;
}

static int rst7_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    rst7_reader *r = h;
    if (r->done) return MS_PLUGIN_EOF;
    r->done = 1;
    if (natoms != r->natoms)
        return ms_perr_set(err, "the file has %ld atoms, the structure %ld", r->natoms, natoms);
    size_t max = 6 * (size_t)r->natoms + 6;
    double *v = malloc(max * sizeof *v);
    if (!v) return ms_perr_set(err, "out of memory for %ld atoms", r->natoms);
    long n = read_values(r, v, max, err);
    int rc = n < 0 ? MS_PLUGIN_ERROR : fill_frame(r, v, n, fr, err);
    free(v);
    return rc;
}

static const ms_plugin rst7_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "rst7",
    .description = "AMBER ASCII restart / input coordinates",
    .extensions = "rst7 inpcrd restrt rst",
    .caps = MS_CAN_READ_FRAMES,
    .open_read = rst7_open_read,
    .read_frame = rst7_read_frame,
    .close_read = rst7_close_read,
};

const ms_plugin *ms_plugin_entry(void) { return &rst7_plugin; }
