/* poscar.c: the VASP POSCAR/CONTCAR plugin (VMD's type POSCAR). A comment line, the scale
 * factor, three lattice vectors, the species (VASP 5) and counts lines, an optional
 * "Selective dynamics" line, "Direct" or "Cartesian", then one line per atom (see
 * vasp_util.h). Atoms are named by their species; the lattice becomes the unit cell. The
 * rest of a CONTCAR (velocities, predictor-corrector data) is not read.
 * Files have no extension: names POSCAR* and CONTCAR* (or extensions poscar, contcar,
 * vasp) pick this type.
 * Writes VASP 5 files, Cartesian, scale 1, one species entry per run of equal elements
 * (the atoms keep their order), the lattice a along x and b in the xy plane. */
#include "ms_plugin.h"
#include "plugin_util.h"
#include "vasp_util.h"

#include <stdlib.h>
#include <string.h>

typedef struct poscar_reader {
    ms_lines in;
} poscar_reader;

static void *poscar_open_read(const char *path, long *natoms, ms_perr *err)
{
    poscar_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    *natoms = -1;
    return r;
}

static void poscar_close_read(void *h)
{
    ms_lines_destroy(h);
}

/* "Cartesian" or "Kartesisch" (first letter C or K): Cartesian; anything else: Direct. */
static int vasp_is_cartesian(const char *l)
{
    l += strspn(l, " \t");
    return *l == 'C' || *l == 'c' || *l == 'K' || *l == 'k';
}

/* After the counts: the optional selective dynamics line and the coordinate mode line. */
static int read_mode(ms_lines *in, int *selective, int *cartesian, ms_perr *err)
{
    if (!vasp_line(in, "coordinate mode line (Direct or Cartesian)", err)) return MS_PLUGIN_ERROR;
    const char *l = in->line + strspn(in->line, " \t");
    *selective = *l == 'S' || *l == 's';
    if (*selective && !vasp_line(in, "coordinate mode line (Direct or Cartesian)", err))
        return MS_PLUGIN_ERROR;
    l = in->line + strspn(in->line, " \t");
    if (!isalpha((unsigned char)*l))
        return ms_perr_set(err, "line %ld: expected Direct or Cartesian, found '%.32s'",
                           in->line_no, l);
    *cartesian = vasp_is_cartesian(l);
    return MS_PLUGIN_OK;
}

static int poscar_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    poscar_reader *r = h;
    ms_lines *in = &r->in;
    if (!ms_lines_next(in))
        return in->error ? ms_perr_set(err, "read error") : ms_perr_set(err, "empty file");
    char comment[512];
    snprintf(comment, sizeof comment, "%s", in->line);
    vasp_head hd;
    memset(&hd, 0, sizeof hd);
    int selective = 0, cartesian = 0;
    if (vasp_read_lattice(in, &hd, err) || vasp_read_species(in, &hd, comment, err) ||
        read_mode(in, &selective, &cartesian, err))
        return MS_PLUGIN_ERROR;
    /* an atom line ("0 0 0") is at least 6 bytes: the file bounds the count */
    if (ms_check_room(err, (double)hd.natoms, 6, ms_lines_left(in), "atoms",
                      "line %ld: the counts give %ld atoms", in->line_no, hd.natoms))
        return MS_PLUGIN_ERROR;
    sink->reserve(sink, (size_t)hd.natoms);
    for (long k = 0; k < hd.natoms; k++) {
        float p[3];
        ms_atom_in a;
        if (vasp_read_atom(in, &hd, cartesian, selective, k, p, err)) return MS_PLUGIN_ERROR;
        vasp_atom(&hd, k, p, &a);
        if (sink->add_atom(sink, &a))
            return ms_perr_set(err, "out of memory at line %ld", in->line_no);
    }
    float cell[6];
    vasp_cell(&hd, cell);
    sink->set_cell(sink, cell);
    if (comment[0] && sink->add_remark(sink, comment))
        return ms_perr_set(err, "out of memory");
    return MS_PLUGIN_OK;
}

static int poscar_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    (void)h, (void)natoms, (void)fr, (void)err;
    return MS_PLUGIN_EOF; /* one frame, given with the structure */
}

/* ---------------------------------------------------------------- writing */

typedef struct poscar_writer {
    ms_out out;
    int frames;
} poscar_writer;

static void *poscar_open_write(const char *path, long natoms, ms_perr *err)
{
    (void)natoms;
    return ms_out_create(sizeof(poscar_writer), path, err);
}

/* The species of atom i: its element, else its name. */
static const char *species_of(const ms_struct_view *v, size_t i, ms_atom_in *a)
{
    v->get_atom(v, i, a);
    if (a->element && a->element[0] && strcmp(a->element, "X") != 0) return a->element;
    return a->name && a->name[0] ? a->name : "X";
}

/* The species line and the counts line: one entry per run of equal species. */
static void write_species(ms_out *o, const ms_struct_view *v)
{
    ms_atom_in a;
    char prev[64] = "";
    for (size_t i = 0; i < v->natoms; i++) {
        const char *s = species_of(v, i, &a);
        if (i == 0 || strncmp(prev, s, sizeof prev - 1) != 0)
            ms_out_printf(o, " %.15s", s);
        snprintf(prev, sizeof prev, "%s", s);
    }
    ms_out_printf(o, "\n");
    size_t run = 0;
    for (size_t i = 0; i < v->natoms; i++) {
        const char *s = species_of(v, i, &a);
        if (i > 0 && strncmp(prev, s, sizeof prev - 1) != 0) {
            ms_out_printf(o, " %zu", run);
            run = 0;
        }
        snprintf(prev, sizeof prev, "%s", s);
        run++;
    }
    ms_out_printf(o, " %zu\n", run);
}

static int poscar_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f,
                              ms_perr *err)
{
    poscar_writer *w = h;
    ms_out *o = &w->out;
    if (w->frames++) return ms_perr_set(err, "a POSCAR file holds one frame: write one");
    if (!(f->cell[0] > 0 && f->cell[1] > 0 && f->cell[2] > 0))
        return ms_perr_set(err, "a POSCAR file needs a unit cell, and the frame has none "
                           "(set a, b and c with molinfo ... set)");
    if (v->natoms == 0) return ms_perr_set(err, "no atoms to write");
    float box[9];
    ms_gmx_cell_to_box(f->cell, box);
    ms_out_printf(o, "written by molscope\n1.0\n");
    for (int k = 0; k < 3; k++)
        ms_out_printf(o, " %21.16f %21.16f %21.16f\n", 10.0 * box[3 * k], 10.0 * box[3 * k + 1],
                      10.0 * box[3 * k + 2]);
    write_species(o, v);
    ms_out_printf(o, "Cartesian\n");
    for (size_t i = 0; i < v->natoms; i++) {
        const float *p = f->pos + 3 * i;
        ms_out_printf(o, " %16.8f %16.8f %16.8f\n", (double)p[0], (double)p[1], (double)p[2]);
    }
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int poscar_close_write(void *h, ms_perr *err)
{
    return ms_out_destroy(h, err);
}

static const ms_plugin poscar_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "POSCAR",
    .description = "VASP POSCAR/CONTCAR structure",
    .extensions = "poscar contcar vasp POSCAR* CONTCAR*",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = poscar_open_read,
    .read_structure = poscar_read_structure,
    .read_frame = poscar_read_frame,
    .close_read = poscar_close_read,
    .open_write = poscar_open_write,
    .write_frame = poscar_write_frame,
    .close_write = poscar_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &poscar_plugin; }
