/* mol2.c: the Tripos MOL2 plugin. Reads @<TRIPOS>MOLECULE (name and counts),
 * @<TRIPOS>ATOM (id, name, x y z, SYBYL type, substructure id and name, charge) and
 * @<TRIPOS>BOND (order 1, 2, 3; aromatic "ar" as 1.5; amide, dummy and unknown as 1);
 * further molecules of the same atom count become frames, and the first molecule of
 * another count ends the trajectory. The element is the SYBYL type before its dot. Writes
 * one molecule per frame with the bonds. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

typedef struct mol2_reader {
    ms_lines in;
    long natoms;
    int structure_done;
} mol2_reader;

static void *mol2_open_read(const char *path, long *natoms, ms_perr *err)
{
    mol2_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    *natoms = -1;
    return r;
}

static void mol2_close_read(void *h)
{
    ms_lines_destroy(h);
}

static int is_section(const char *l, const char *name)
{
    return !strncmp(l, "@<TRIPOS>", 9) && !strncmp(l + 9, name, strlen(name));
}

/* Find the next MOLECULE record; read its counts. MS_PLUGIN_EOF when there is none. */
static int read_molecule(mol2_reader *r, long *natoms, long *nbonds, ms_perr *err)
{
    ms_lines *in = &r->in;
    const char *l;
    while ((l = ms_lines_next(in)) && !is_section(l, "MOLECULE")) {}
    if (!l) return in->error ? ms_perr_set(err, "read error after line %ld", in->line_no)
                             : MS_PLUGIN_EOF;
    if (!ms_lines_next(in) || !(l = ms_lines_next(in)))
        return ms_perr_set(err, "line %ld: the file ends in the MOLECULE record", in->line_no);
    char buf[256], *tok[5];
    snprintf(buf, sizeof buf, "%s", l);
    int nt = ms_tokens(buf, tok, 5);
    *nbonds = 0;
    if (nt < 1 || ms_parse_long(tok[0], strlen(tok[0]), natoms) < 0 || *natoms < 1 ||
        (nt > 1 && (ms_parse_long(tok[1], strlen(tok[1]), nbonds) < 0 || *nbonds < 0)))
        return ms_perr_set(err, "line %ld: bad MOLECULE counts line", in->line_no);
    /* An atom line is at least six fields (12 bytes), a bond line four (8 bytes). */
    long long left = ms_lines_left(in);
    if (ms_check_room(err, (double)*natoms, 12, left, "atoms",
                      "line %ld: the MOLECULE record declares %ld atoms", in->line_no, *natoms) ||
        ms_check_room(err, (double)*nbonds, 8, left, "bonds",
                      "line %ld: the MOLECULE record declares %ld bonds", in->line_no, *nbonds))
        return MS_PLUGIN_ERROR;
    while ((l = ms_lines_next(in)) && !is_section(l, "ATOM")) {}
    if (!l) return ms_perr_set(err, "line %ld: no @<TRIPOS>ATOM section", in->line_no);
    return MS_PLUGIN_OK;
}

/* One ATOM line: fields into tok; x y z parsed. */
static int atom_line(ms_lines *in, char *buf, char **tok, int *nt, float xyz[3], ms_perr *err)
{
    const char *l = ms_lines_next(in);
    if (!l) return ms_perr_set(err, "line %ld: the file ends in the ATOM section", in->line_no);
    snprintf(buf, 512, "%s", l);
    *nt = ms_tokens(buf, tok, 10);
    if (*nt < 6) return ms_perr_set(err, "line %ld: ATOM record has %d fields, expected 6 or more",
                                    in->line_no, *nt);
    static const char *const axis[3] = {"x", "y", "z"};
    for (int d = 0; d < 3; d++)
        if (ms_parse_float(tok[2 + d], strlen(tok[2 + d]), &xyz[d]) < 0)
            return ms_perr_set(err, "line %ld: bad %s coordinate '%.32s'", in->line_no, axis[d],
                               tok[2 + d]);
    return MS_PLUGIN_OK;
}

static float bond_order(const char *t)
{
    if (!strcmp(t, "2")) return 2.0f;
    if (!strcmp(t, "3")) return 3.0f;
    if (!strcmp(t, "ar")) return 1.5f;
    return 1.0f;
}

static int read_bonds(mol2_reader *r, long nbonds, ms_struct_sink *sink, ms_perr *err)
{
    ms_lines *in = &r->in;
    const char *l;
    if (nbonds == 0) return MS_PLUGIN_OK;
    while ((l = ms_lines_next(in)) && !is_section(l, "BOND"))
        if (is_section(l, "MOLECULE")) return ms_perr_set(err, "no @<TRIPOS>BOND section");
    if (!l) return ms_perr_set(err, "no @<TRIPOS>BOND section for %ld bonds", nbonds);
    for (long k = 0; k < nbonds; k++) {
        char buf[256], *tok[5];
        if (!(l = ms_lines_next(in)))
            return ms_perr_set(err, "line %ld: the file ends after %ld of %ld bonds", in->line_no,
                               k, nbonds);
        snprintf(buf, sizeof buf, "%s", l);
        long a, b;
        if (ms_tokens(buf, tok, 4) < 4 || ms_parse_long(tok[1], strlen(tok[1]), &a) < 0 ||
            ms_parse_long(tok[2], strlen(tok[2]), &b) < 0 || a < 1 || b < 1 ||
            a > r->natoms || b > r->natoms)
            return ms_perr_set(err, "line %ld: bad BOND record", in->line_no);
        if (sink->add_bond(sink, (size_t)a - 1, (size_t)b - 1, bond_order(tok[3])))
            return ms_perr_set(err, "out of memory");
    }
    sink->bonds_complete(sink);
    return MS_PLUGIN_OK;
}

static int mol2_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    mol2_reader *r = h;
    long n, nb;
    int rc = read_molecule(r, &n, &nb, err);
    if (rc == MS_PLUGIN_EOF) return ms_perr_set(err, "no @<TRIPOS>MOLECULE record");
    if (rc != MS_PLUGIN_OK) return rc;
    if ((double)n > 1e9) return ms_perr_set(err, "bad atom count %ld", n);
    r->natoms = n;
    for (long i = 0; i < n; i++) {
        char buf[512], *tok[10], elem[8];
        int nt;
        ms_atom_in a;
        memset(&a, 0, sizeof a);
        float xyz[3];
        if (atom_line(&r->in, buf, tok, &nt, xyz, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
        a.x = xyz[0], a.y = xyz[1], a.z = xyz[2];
        a.name = tok[1];
        a.type = tok[5];
        snprintf(elem, sizeof elem, "%.*s", (int)strcspn(tok[5], "."), tok[5]);
        a.element = elem;
        a.has = MS_HAS_POS;
        long resid = 0;
        if (nt > 6 && ms_parse_long(tok[6], strlen(tok[6]), &resid) < 0) resid = 0;
        a.resid = (int)resid;
        a.resname = nt > 7 ? tok[7] : "";
        if (nt > 8 && ms_parse_float(tok[8], strlen(tok[8]), &a.charge) == 1) a.has |= MS_HAS_CHARGE;
        if (sink->add_atom(sink, &a)) return ms_perr_set(err, "out of memory");
    }
    if (read_bonds(r, nb, sink, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    r->structure_done = 1;
    return MS_PLUGIN_OK;
}

static int mol2_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    mol2_reader *r = h;
    long n, nb;
    if (!r->structure_done) return MS_PLUGIN_EOF;
    int rc = read_molecule(r, &n, &nb, err);
    if (rc != MS_PLUGIN_OK) return rc;
    if (n != natoms) {
        r->structure_done = 0; /* a different molecule: the trajectory ends */
        return MS_PLUGIN_EOF;
    }
    for (long i = 0; i < n; i++) {
        char buf[512], *tok[10];
        int nt;
        float xyz[3];
        if (atom_line(&r->in, buf, tok, &nt, xyz, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
        if (fr->pos) memcpy(fr->pos + 3 * i, xyz, sizeof xyz);
    }
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

static void *mol2_open_write(const char *path, long natoms, ms_perr *err)
{
    (void)natoms;
    ms_out *o = ms_out_create(sizeof *o, path, err);
    if (!o) return NULL;
    return o;
}

static int mol2_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    ms_out *o = h;
    size_t nb = 0;
    for (size_t i = 0; i < v->natoms; i++) {
        const unsigned *to;
        size_t n = v->get_bonds(v, i, &to);
        for (size_t k = 0; k < n; k++) nb += to[k] > i;
    }
    ms_out_printf(o, "@<TRIPOS>MOLECULE\nmolscope\n%zu %zu 1 0 0\nSMALL\nUSER_CHARGES\n\n"
                     "@<TRIPOS>ATOM\n", v->natoms, nb);
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        const float *p = f->pos + 3 * i;
        const char *type = a.type && *a.type ? a.type : a.element && *a.element ? a.element : "Du";
        ms_out_printf(o, "%7zu %-8s %10.4f %10.4f %10.4f %-8s %5d %-8s %9.4f\n", i + 1,
                      a.name && *a.name ? a.name : "X", p[0], p[1], p[2], type, a.resid,
                      a.resname && *a.resname ? a.resname : "UNK", a.charge);
    }
    ms_out_printf(o, "@<TRIPOS>BOND\n");
    size_t id = 0;
    for (size_t i = 0; i < v->natoms; i++) {
        const unsigned *to;
        size_t n = v->get_bonds(v, i, &to);
        for (size_t k = 0; k < n; k++)
            if (to[k] > i) ms_out_printf(o, "%6zu %6zu %6u 1\n", ++id, i + 1, to[k] + 1);
    }
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int mol2_close_write(void *h, ms_perr *err)
{
    ms_out *o = h;
    return ms_out_destroy(o, err);
}

static const ms_plugin mol2_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "mol2",
    .description = "Tripos MOL2",
    .extensions = "mol2",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = mol2_open_read,
    .read_structure = mol2_read_structure,
    .read_frame = mol2_read_frame,
    .close_read = mol2_close_read,
    .open_write = mol2_open_write,
    .write_frame = mol2_write_frame,
    .close_write = mol2_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &mol2_plugin; }
