/* cube.c: the Gaussian cube plugin: two comment lines, the atom count and grid origin (and
 * the number of values per point), three lines of point count and step vector (Bohr when
 * the count is positive, Angstrom when negative), one line per atom (atomic number, charge,
 * x y z), with a negative atom count a line of orbital numbers, then the values with z
 * fastest. The atoms become the structure (one frame), each value per point (orbital) a
 * volume set. Lengths are converted to Angstrom. Read only. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BOHR 0.529177210903   /* Angstrom */

typedef struct cube_reader {
    ms_lines in;
    long natoms, nsets;
    int has_mo;
    double unit;           /* length unit of the grid and atoms, in Angstrom */
    ms_volume_meta meta;
    long long atoms_at, data_at;
    long atoms_line, data_line;
    char title[256];
} cube_reader;

static void cube_close_read(void *h)
{
    ms_lines_destroy(h);
}

/* A line of whitespace-separated numbers; returns how many parsed (up to max). */
static int numbers(const char *line, double *v, int max)
{
    char buf[1024], *tok[16];
    snprintf(buf, sizeof buf, "%s", line);
    int nt = ms_tokens(buf, tok, 16), got = 0;
    for (int k = 0; k < nt && got < max; k++) {
        if (ms_parse_double(tok[k], strlen(tok[k]), &v[got]) != 1) break;
        got++;
    }
    return got;
}

static int read_grid_header(cube_reader *r, ms_perr *err)
{
    ms_lines *in = &r->in;
    const char *l;
    double v[5];
    for (int k = 0; k < 2; k++) {
        if (!(l = ms_lines_next(in)))
            return ms_perr_set(err, "line %ld: the file ends in the comment lines", in->line_no);
        if (k == 0) snprintf(r->title, sizeof r->title, "%s", l + strspn(l, " \t"));
    }
    if (!(l = ms_lines_next(in)) || numbers(l, v, 5) < 4)
        return ms_perr_set(err, "line %ld: bad atom count and origin line", in->line_no);
    int nv = numbers(l, v, 5);
    if (v[0] != floor(v[0]) || fabs(v[0]) > 1e8)
        return ms_perr_set(err, "line %ld: bad atom count", in->line_no);
    r->natoms = labs((long)v[0]);
    r->has_mo = v[0] < 0;
    /* Checked as a double first: a cast of an out-of-range value is undefined. */
    if (nv == 5 && !(v[4] >= 1 && v[4] <= 4096 && v[4] == floor(v[4])))
        return ms_perr_set(err, "line %ld: bad number of values per point %g", in->line_no, v[4]);
    r->nsets = nv == 5 ? (long)v[4] : 1;
    if (r->nsets < 1 || r->nsets > 4096)
        return ms_perr_set(err, "line %ld: bad number of values per point", in->line_no);
    double origin[3] = {v[1], v[2], v[3]};
    r->unit = BOHR;
    for (int d = 0; d < 3; d++) {
        if (!(l = ms_lines_next(in)) || numbers(l, v, 4) != 4 || v[0] != floor(v[0]) ||
            v[0] == 0 || fabs(v[0]) > 1e6)
            return ms_perr_set(err, "line %ld: bad grid axis %d line", in->line_no, d + 1);
        if (v[0] < 0) r->unit = 1.0;  /* a negative count: Angstrom */
        r->meta.n[d] = labs((long)v[0]);
        for (int e = 0; e < 3; e++) r->meta.delta[d][e] = v[1 + e];
    }
    for (int d = 0; d < 3; d++) {
        r->meta.origin[d] = origin[d] * r->unit;
        for (int e = 0; e < 3; e++) r->meta.delta[d][e] *= r->unit;
    }
    return MS_PLUGIN_OK;
}

/* Skip the atom lines (read_structure parses them) and the orbital line. */
static int find_data(cube_reader *r, ms_perr *err)
{
    ms_lines *in = &r->in;
    r->atoms_at = ms_lines_tell_next(in);
    r->atoms_line = in->line_no;
    /* An atom line is five numbers: at least 10 bytes. */
    if (ms_check_room(err, (double)r->natoms, 10, ms_lines_left(in), "atoms",
                      "line 3: the header declares %ld atoms", r->natoms))
        return MS_PLUGIN_ERROR;
    for (long i = 0; i < r->natoms; i++)
        if (!ms_lines_next(in))
            return ms_perr_set(err, "line %ld: the file ends after %ld of %ld atoms", in->line_no,
                               i, r->natoms);
    if (r->has_mo) {
        const char *l = ms_lines_next(in);
        double v[2];
        if (!l || numbers(l, v, 1) != 1 || v[0] < 1 || v[0] > 4096)
            return ms_perr_set(err, "line %ld: bad orbital count line", in->line_no);
        r->nsets = (long)v[0];
    }
    r->data_at = ms_lines_tell_next(in);
    r->data_line = in->line_no;
    /* A value is at least a digit and a separator: the file bounds grid times sets. */
    double points = (double)r->meta.n[0] * (double)r->meta.n[1] * (double)r->meta.n[2];
    char sets[48] = "";
    if (r->nsets > 1) snprintf(sets, sizeof sets, " of %ld values each", r->nsets);
    if (ms_check_room(err, points * (double)r->nsets, 2, ms_lines_left(in), "values",
                      "lines 4-6: the header declares %ld x %ld x %ld points%s", r->meta.n[0],
                      r->meta.n[1], r->meta.n[2], sets))
        return MS_PLUGIN_ERROR;
    return MS_PLUGIN_OK;
}

static void *cube_open_read(const char *path, long *natoms, ms_perr *err)
{
    cube_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    if (read_grid_header(r, err) != MS_PLUGIN_OK || find_data(r, err) != MS_PLUGIN_OK) {
        cube_close_read(r);
        return NULL;
    }
    if (r->natoms == 0) {
        ms_perr_set(err, "the cube file has no atoms");
        cube_close_read(r);
        return NULL;
    }
    *natoms = r->natoms;
    return r;
}

static const char *const symbols[] = {
    "X",  "H",  "He", "Li", "Be", "B",  "C",  "N",  "O",  "F",  "Ne", "Na", "Mg", "Al", "Si",
    "P",  "S",  "Cl", "Ar", "K",  "Ca", "Sc", "Ti", "V",  "Cr", "Mn", "Fe", "Co", "Ni", "Cu",
    "Zn", "Ga", "Ge", "As", "Se", "Br", "Kr", "Rb", "Sr", "Y",  "Zr", "Nb", "Mo", "Tc", "Ru",
    "Rh", "Pd", "Ag", "Cd", "In", "Sn", "Sb", "Te", "I",  "Xe", "Cs", "Ba", "La", "Ce", "Pr",
    "Nd", "Pm", "Sm", "Eu", "Gd", "Tb", "Dy", "Ho", "Er", "Tm", "Yb", "Lu", "Hf", "Ta", "W",
    "Re", "Os", "Ir", "Pt", "Au", "Hg", "Tl", "Pb", "Bi", "Po", "At", "Rn"};

static int cube_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    cube_reader *r = h;
    ms_lines *in = &r->in;
    if (ms_lines_seek(in, r->atoms_at, r->atoms_line) != 0)
        return ms_perr_set(err, "cannot seek to the atoms");
    sink->reserve(sink, (size_t)r->natoms);
    if (r->title[0]) sink->add_remark(sink, r->title);
    for (long i = 0; i < r->natoms; i++) {
        const char *l = ms_lines_next(in);
        double v[5];
        if (!l) return ms_perr_set(err, "line %ld: the file ends in the atoms", in->line_no);
        if (numbers(l, v, 5) != 5 || v[0] < 0 || v[0] > 118 || v[0] != floor(v[0]))
            return ms_perr_set(err, "line %ld: bad atom line", in->line_no);
        int z = (int)v[0];
        ms_atom_in a;
        memset(&a, 0, sizeof a);
        const char *sym = z < (int)(sizeof symbols / sizeof *symbols) ? symbols[z] : "X";
        a.name = a.type = a.element = sym;
        a.resname = "CUB";
        a.atomicnumber = z;
        a.charge = (float)v[1];
        a.x = (float)(v[2] * r->unit);
        a.y = (float)(v[3] * r->unit);
        a.z = (float)(v[4] * r->unit);
        a.has = MS_HAS_POS | MS_HAS_ATOMICNUMBER | MS_HAS_CHARGE;
        if (sink->add_atom(sink, &a)) return ms_perr_set(err, "out of memory");
    }
    return MS_PLUGIN_OK;
}

static int cube_read_frame(void *h, long natoms, ms_frame_out *f, ms_perr *err)
{
    (void)h, (void)natoms, (void)f, (void)err;
    return MS_PLUGIN_EOF;
}

static int cube_read_volume_meta(void *h, int k, ms_volume_meta *meta, ms_perr *err)
{
    (void)err;
    cube_reader *r = h;
    if (k < 0 || k >= r->nsets) return MS_PLUGIN_EOF;
    *meta = r->meta;
    if (r->nsets > 1) snprintf(meta->name, sizeof meta->name, "%.200s [%d]", r->title, k + 1);
    else snprintf(meta->name, sizeof meta->name, "%s", r->title);
    return MS_PLUGIN_OK;
}

static int cube_read_volume_data(void *h, int k, float *data, ms_perr *err)
{
    cube_reader *r = h;
    size_t n = (size_t)r->meta.n[0] * (size_t)r->meta.n[1] * (size_t)r->meta.n[2];
    size_t ns = (size_t)r->nsets, all;
    if (n > ((size_t)1 << 36) / ns) return ms_perr_set(err, "the grid is too large");
    all = n * ns;
    float *tmp = malloc(all * sizeof *tmp);
    if (!tmp) return ms_perr_set(err, "out of memory for %zu values", all);
    if (ms_lines_seek(&r->in, r->data_at, r->data_line) != 0 ||
        ms_read_floats(&r->in, NULL, tmp, all, err) != MS_PLUGIN_OK) {
        if (!err->msg[0]) ms_perr_set(err, "cannot seek to the data");
        free(tmp);
        return MS_PLUGIN_ERROR;
    }
    if (ns > 1)
        for (size_t i = 0; i < n; i++) tmp[i] = tmp[i * ns + (size_t)k];
    ms_grid_zfast_to_xfast(tmp, data, r->meta.n);
    free(tmp);
    return MS_PLUGIN_OK;
}

static const ms_plugin cube_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "cube",
    .description = "Gaussian cube (atoms and volumetric data)",
    .extensions = "cube cub",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_VOLUME,
    .open_read = cube_open_read,
    .read_structure = cube_read_structure,
    .read_frame = cube_read_frame,
    .close_read = cube_close_read,
    .read_volume_meta = cube_read_volume_meta,
    .read_volume_data = cube_read_volume_data,
};

const ms_plugin *ms_plugin_entry(void) { return &cube_plugin; }
