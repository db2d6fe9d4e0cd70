/* pqr.c: the PQR plugin (APBS, PDB2PQR): PDB-like ATOM/HETATM records read as
 * whitespace-separated fields: serial, name, residue name, optional chain, residue number
 * (an insertion letter may follow it), x y z, charge, radius. Models (MODEL/ENDMDL, END)
 * become frames. Writes the same fields (the chain only when it is not blank). */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

typedef struct pqr_reader {
    ms_lines in;
    long natoms;
    int structure_done;
} pqr_reader;

static int is_atom(const char *l)
{
    return !strncmp(l, "ATOM", 4) || !strncmp(l, "HETATM", 6);
}

static int is_end(const char *l)
{
    return !strncmp(l, "ENDMDL", 6) || (!strncmp(l, "END", 3) && (l[3] == '\0' || isspace((unsigned char)l[3])));
}

static void *pqr_open_read(const char *path, long *natoms, ms_perr *err)
{
    pqr_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    *natoms = -1;
    return r;
}

static void pqr_close_read(void *h)
{
    ms_lines_destroy(h);
}

/* Split an atom line into its fields: 10 without a chain, 11 with one. */
static int split(pqr_reader *r, char *buf, char **tok, ms_perr *err)
{
    const ms_lines *in = &r->in;
    snprintf(buf, 512, "%s", in->line);
    int n = ms_tokens(buf, tok, 12);
    if (n != 10 && n != 11)
        return ms_perr_set(err, "line %ld: %s record has %d fields, expected 10 or 11 (serial "
                           "name resname [chain] resid x y z charge radius)", in->line_no,
                           tok[0], n);
    return n;
}

static int parse_xyzqr(const ms_lines *in, char **t, float v[5], ms_perr *err)
{
    static const char *const what[5] = {"x coordinate", "y coordinate", "z coordinate",
                                        "charge", "radius"};
    for (int k = 0; k < 5; k++)
        if (ms_parse_float(t[k], strlen(t[k]), &v[k]) < 0)
            return ms_perr_set(err, "line %ld: bad %s '%.32s'", in->line_no, what[k], t[k]);
    return MS_PLUGIN_OK;
}

static int pqr_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    pqr_reader *r = h;
    ms_lines *in = &r->in;
    const char *l;
    char buf[512], *tok[12];
    while ((l = ms_lines_next(in))) {
        if (is_end(l) && r->natoms) break;
        if (!is_atom(l)) continue;
        int n = split(r, buf, tok, err);
        if (n < 0) return MS_PLUGIN_ERROR;
        ms_atom_in a;
        memset(&a, 0, sizeof a);
        char **t = tok + n - 8; /* resid x y z q r */
        char *rs = tok[n - 6];
        size_t rl = strlen(rs);
        if (rl > 1 && isalpha((unsigned char)rs[rl - 1])) a.insertion = rs[--rl];
        long resid;
        if (ms_parse_long(rs, rl, &resid) < 0)
            return ms_perr_set(err, "line %ld: bad residue number '%.32s'", in->line_no, rs);
        float v[5];
        if (parse_xyzqr(in, t + 3, v, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
        a.name = a.type = tok[2];
        a.resname = tok[3];
        a.chain = n == 11 ? tok[4] : "";
        a.resid = (int)resid;
        a.x = v[0], a.y = v[1], a.z = v[2], a.charge = v[3], a.radius = v[4];
        a.hetero = l[0] == 'H';
        a.has = MS_HAS_POS | MS_HAS_CHARGE | MS_HAS_RADIUS;
        if (sink->add_atom(sink, &a)) return ms_perr_set(err, "out of memory");
        r->natoms++;
    }
    if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
    if (r->natoms == 0) return ms_perr_set(err, "no ATOM or HETATM records");
    r->structure_done = 1;
    return MS_PLUGIN_OK;
}

static int pqr_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    pqr_reader *r = h;
    ms_lines *in = &r->in;
    if (!r->structure_done) return MS_PLUGIN_EOF;
    long count = 0;
    const char *l;
    char buf[512], *tok[12];
    while ((l = ms_lines_next(in))) {
        if (is_end(l) && count) break;
        if (!is_atom(l)) continue;
        if (count >= natoms)
            return ms_perr_set(err, "line %ld: model has more than %ld atoms", in->line_no, natoms);
        int n = split(r, buf, tok, err);
        float v[5];
        if (n < 0 || parse_xyzqr(in, tok + n - 5, v, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
        if (fr->pos) memcpy(fr->pos + 3 * count, v, 3 * sizeof(float));
        count++;
    }
    if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
    if (count == 0) return MS_PLUGIN_EOF;
    if (count != natoms)
        return ms_perr_set(err, "line %ld: model has %ld atoms, expected %ld", in->line_no, count,
                           natoms);
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

static void *pqr_open_write(const char *path, long natoms, ms_perr *err)
{
    (void)natoms;
    ms_out *o = ms_out_create(sizeof *o, path, err);
    if (!o) return NULL;
    return o;
}

static int pqr_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    ms_out *o = h;
    ms_out_printf(o, "MODEL %d\n", f->index + 1);
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        const float *p = f->pos + 3 * i;
        const char *name = a.name && *a.name ? a.name : "X", *res = a.resname && *a.resname ? a.resname : "UNK";
        char chain[8] = "";
        if (a.chain && a.chain[0] && !isspace((unsigned char)a.chain[0]))
            snprintf(chain, sizeof chain, " %.1s", a.chain);
        ms_out_printf(o, "%-6s%5zu %-4s %-4s%s %5d%c   %9.4f %9.4f %9.4f %8.4f %7.4f\n",
                      a.hetero ? "HETATM" : "ATOM", i + 1, name, res, chain, a.resid,
                      a.insertion && a.insertion != ' ' ? a.insertion : ' ', p[0], p[1], p[2],
                      a.charge, a.radius);
    }
    ms_out_printf(o, "ENDMDL\n");
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int pqr_close_write(void *h, ms_perr *err)
{
    ms_out *o = h;
    ms_out_printf(o, "END\n");
    return ms_out_destroy(o, err);
}

static const ms_plugin pqr_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "pqr",
    .description = "PQR (coordinates, charges and radii)",
    .extensions = "pqr",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = pqr_open_read,
    .read_structure = pqr_read_structure,
    .read_frame = pqr_read_frame,
    .close_read = pqr_close_read,
    .open_write = pqr_open_write,
    .write_frame = pqr_write_frame,
    .close_write = pqr_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &pqr_plugin; }
