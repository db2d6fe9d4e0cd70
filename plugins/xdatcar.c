/* xdatcar.c: the VASP 5 XDATCAR plugin (VMD's type VASP_XDATCAR5): the POSCAR header
 * (vasp_util.h) and then frames, each a "Direct configuration= n" line (or Cartesian)
 * followed by one line per atom. A variable-cell run repeats the whole header before each
 * frame: every frame then has its own cell. Atoms are named by their species; the first
 * frame comes with the structure. Files have no extension: XDATCAR* and *.xdatcar name it. */
#include "ms_plugin.h"
#include "plugin_util.h"
#include "vasp_util.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct xdatcar_reader {
    ms_lines in;
    vasp_head hd;
    long frame;        /* frames read so far */
} xdatcar_reader;

static void *xdatcar_open_read(const char *path, long *natoms, ms_perr *err)
{
    xdatcar_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    *natoms = -1;
    return r;
}

static void xdatcar_close_read(void *h)
{
    ms_lines_destroy(h);
}

/* Is the line a frame's "Direct configuration=" (Cartesian, Konfig=) line? *cartesian. */
static int config_line(const char *l, int *cartesian)
{
    l += strspn(l, " \t");
    *cartesian = strncasecmp(l, "cartesian", 9) == 0;
    return *cartesian || strncasecmp(l, "direct", 6) == 0 || strncasecmp(l, "konfig", 6) == 0;
}

/* The header after its comment line (the line just read). */
static int read_header(xdatcar_reader *r, vasp_head *hd, ms_perr *err)
{
    char comment[512];
    snprintf(comment, sizeof comment, "%s", r->in.line);
    memset(hd, 0, sizeof *hd);
    return vasp_read_lattice(&r->in, hd, err) || vasp_read_species(&r->in, hd, comment, err)
               ? MS_PLUGIN_ERROR
               : MS_PLUGIN_OK;
}

/* The configuration line of the next frame (after a repeated header when the cell varies);
 * MS_PLUGIN_EOF when only blank lines remain. */
static int next_config(xdatcar_reader *r, int *cartesian, int *new_cell, ms_perr *err)
{
    ms_lines *in = &r->in;
    const char *l;
    *new_cell = 0;
    while ((l = ms_lines_next(in)) && l[strspn(l, " \t\r")] == '\0') {}
    if (!l) return in->error ? ms_perr_set(err, "read error after line %ld", in->line_no)
                             : MS_PLUGIN_EOF;
    if (config_line(l, cartesian)) return MS_PLUGIN_OK;
    vasp_head hd;
    long at = in->line_no;
    if (read_header(r, &hd, err)) return MS_PLUGIN_ERROR;
    if (hd.natoms != r->hd.natoms)
        return ms_perr_set(err, "line %ld: the header of frame %ld gives %ld atoms, the first "
                           "gave %ld", at, r->frame + 1, hd.natoms, r->hd.natoms);
    r->hd = hd;
    *new_cell = 1;
    if (!vasp_line(in, "configuration line", err)) return MS_PLUGIN_ERROR;
    if (!config_line(in->line, cartesian))
        return ms_perr_set(err, "line %ld: expected 'Direct configuration=', found '%.32s'",
                           in->line_no, in->line);
    return MS_PLUGIN_OK;
}

static int xdatcar_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    xdatcar_reader *r = h;
    ms_lines *in = &r->in;
    if (!ms_lines_next(in))
        return in->error ? ms_perr_set(err, "read error") : ms_perr_set(err, "empty file");
    char comment[512];
    snprintf(comment, sizeof comment, "%s", in->line);
    if (read_header(r, &r->hd, err)) return MS_PLUGIN_ERROR;
    int cartesian, new_cell;
    int rc = next_config(r, &cartesian, &new_cell, err);
    if (rc == MS_PLUGIN_EOF) return ms_perr_set(err, "line %ld: the file has no frame", in->line_no);
    if (rc != MS_PLUGIN_OK) return rc;
    if (ms_check_room(err, (double)r->hd.natoms, 6, ms_lines_left(in), "atoms",
                      "line %ld: the counts give %ld atoms", in->line_no, r->hd.natoms))
        return MS_PLUGIN_ERROR;
    sink->reserve(sink, (size_t)r->hd.natoms);
    for (long k = 0; k < r->hd.natoms; k++) {
        float p[3];
        ms_atom_in a;
        if (vasp_read_atom(in, &r->hd, cartesian, 0, k, p, err)) return MS_PLUGIN_ERROR;
        vasp_atom(&r->hd, k, p, &a);
        if (sink->add_atom(sink, &a))
            return ms_perr_set(err, "out of memory at line %ld", in->line_no);
    }
    float cell[6];
    vasp_cell(&r->hd, cell);
    sink->set_cell(sink, cell);
    if (comment[0] && sink->add_remark(sink, comment)) return ms_perr_set(err, "out of memory");
    r->frame = 1;
    return MS_PLUGIN_OK;
}

static int xdatcar_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    xdatcar_reader *r = h;
    int cartesian, new_cell;
    int rc = next_config(r, &cartesian, &new_cell, err);
    if (rc != MS_PLUGIN_OK) return rc;
    if (natoms != r->hd.natoms)
        return ms_perr_set(err, "the file has %ld atoms, not %ld", r->hd.natoms, natoms);
    for (long k = 0; k < natoms; k++) {
        float p[3];
        if (vasp_read_atom(&r->in, &r->hd, cartesian, 0, k, p, err)) return MS_PLUGIN_ERROR;
        if (fr->pos) memcpy(fr->pos + 3 * k, p, sizeof p);
    }
    vasp_cell(&r->hd, fr->cell);
    fr->has_cell = 1;
    r->frame++;
    return MS_PLUGIN_OK;
}

static const ms_plugin xdatcar_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "VASP_XDATCAR5",
    .description = "VASP 5 XDATCAR trajectory",
    .extensions = "xdatcar XDATCAR*",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES,
    .open_read = xdatcar_open_read,
    .read_structure = xdatcar_read_structure,
    .read_frame = xdatcar_read_frame,
    .close_read = xdatcar_close_read,
};

const ms_plugin *ms_plugin_entry(void) { return &xdatcar_plugin; }
