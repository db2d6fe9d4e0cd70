/* pdb.c: the PDB plugin. Reads ATOM/HETATM (hybrid-36 serials and resids, altlocs,
 * insertion codes, segment ids, element symbols), CRYST1, HELIX/SHEET, CONECT and REMARKs,
 * and the biological assemblies of REMARK 350 (BIOMOLECULE, APPLY ... TO CHAINS, BIOMT);
 * models (MODEL/ENDMDL, or frames separated by END) become frames. Writes the same. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct pdb_reader {
    ms_lines in;
    long natoms;           /* atoms in the first model */
    long long frame2;      /* offset where the second model's lines start, -1 = none */
    long frame2_line;
    int structure_done;
    int single_model;      /* no frames after the first model */
    int *serial;           /* serial of each atom (for CONECT), -1 when unknown */
    char *chain;           /* chain of each atom (for REMARK 350) */
    size_t serial_cap;
} pdb_reader;

/* REMARK 350: generators (chains and BIOMT operators) of the biomolecules. */
typedef struct biomt_gen {
    char id[16];
    char chains[256];      /* the chain letters it applies to */
    double (*ops)[12];
    size_t nops;
} biomt_gen;

typedef struct biomt {
    biomt_gen *gen;
    size_t ngen;
    char cur[16];
    int failed;
} biomt;

enum rec { R_OTHER, R_ATOM, R_HETATM, R_MODEL, R_ENDMDL, R_END, R_CRYST1, R_HELIX, R_SHEET,
           R_CONECT, R_REMARK };

static enum rec record_type(const char *l, size_t n)
{
    if (n < 3) return R_OTHER;
    switch (l[0]) {
    case 'A':
        return n >= 4 && !strncmp(l, "ATOM", 4) ? R_ATOM : R_OTHER;
    case 'H':
        if (n >= 6 && !strncmp(l, "HETATM", 6)) return R_HETATM;
        if (n >= 5 && !strncmp(l, "HELIX", 5)) return R_HELIX;
        if (n >= 6 && !strncmp(l, "HEADER", 6)) return R_REMARK;
        return R_OTHER;
    case 'M':
        return n >= 5 && !strncmp(l, "MODEL", 5) ? R_MODEL : R_OTHER;
    case 'E':
        if (n >= 6 && !strncmp(l, "ENDMDL", 6)) return R_ENDMDL;
        if (!strncmp(l, "END", 3) && (n == 3 || l[3] == ' ')) return R_END;
        return R_OTHER;
    case 'C':
        if (n >= 6 && !strncmp(l, "CRYST1", 6)) return R_CRYST1;
        if (n >= 6 && !strncmp(l, "CONECT", 6)) return R_CONECT;
        return R_OTHER;
    case 'S':
        return n >= 5 && !strncmp(l, "SHEET", 5) ? R_SHEET : R_OTHER;
    case 'R':
        return n >= 6 && !strncmp(l, "REMARK", 6) ? R_REMARK : R_OTHER;
    case 'T':
        return n >= 5 && !strncmp(l, "TITLE", 5) ? R_REMARK : R_OTHER;
    default:
        return R_OTHER;
    }
}

static void *pdb_open_read(const char *path, long *natoms, ms_perr *err)
{
    pdb_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    r->frame2 = -1;
    *natoms = -1;
    return r;
}

static void pdb_close_read(void *h)
{
    pdb_reader *r = h;
    free(r->serial);
    free(r->chain);
    ms_lines_destroy(r);
}

/* Parse x, y, z of an ATOM/HETATM line; MS_PLUGIN_ERROR with a message naming the line. */
static int parse_xyz(const ms_lines *in, float *x, float *y, float *z, ms_perr *err)
{
    const char *l = in->line;
    size_t n = in->line_len;
    if (n < 54)
        return ms_perr_set(err, "line %ld: %.6s record too short for coordinates (%zu columns)",
                           in->line_no, l, n);
    static const char *axis[3] = {"x", "y", "z"};
    float *v[3] = {x, y, z};
    for (int k = 0; k < 3; k++) {
        int rc = ms_field_float(l, n, 30 + 8 * (size_t)k, 38 + 8 * (size_t)k, v[k]);
        if (rc <= 0) {
            char f[9];
            ms_field(l, n, 30 + 8 * (size_t)k, 38 + 8 * (size_t)k, f);
            return ms_perr_set(err, "line %ld: bad %s coordinate '%s'", in->line_no, axis[k], f);
        }
    }
    return MS_PLUGIN_OK;
}

static int parse_cryst1(const ms_lines *in, float cell[6], ms_perr *err)
{
    static const size_t c[7] = {6, 15, 24, 33, 40, 47, 54};
    for (int k = 0; k < 6; k++) {
        if (ms_field_float(in->line, in->line_len, c[k], c[k + 1], &cell[k]) <= 0)
            return ms_perr_set(err, "line %ld: bad CRYST1 record", in->line_no);
    }
    return MS_PLUGIN_OK;
}

static int parse_atom(pdb_reader *r, ms_struct_sink *sink, int hetero, ms_perr *err)
{
    const ms_lines *in = &r->in;
    const char *l = in->line;
    size_t n = in->line_len;
    char name[5], resname[5], chain[2], segid[5], elem[3], serialf[6], residf[5];
    ms_atom_in a;
    memset(&a, 0, sizeof a);
    if (parse_xyz(in, &a.x, &a.y, &a.z, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    /* parse_xyz checked that the line reaches column 54: every field before it exists. */
    ms_field(l, n, 12, 16, name);
    ms_field(l, n, 17, 21, resname);
    chain[0] = l[21] == ' ' ? '\0' : l[21];
    chain[1] = '\0';
    memcpy(residf, l + 22, 4);
    long resid = 0;
    if (ms_hy36_decode(residf, 4, &resid) < 0) {
        ms_field(l, n, 22, 26, residf);
        return ms_perr_set(err, "line %ld: bad residue number '%s'", in->line_no, residf);
    }
    a.resid = (int)resid;
    a.insertion = l[26];
    a.altloc = l[16];
    if (n > 60) {
        if (ms_field_float(l, n, 54, 60, &a.occupancy) < 0)
            return ms_perr_set(err, "line %ld: bad occupancy", in->line_no);
        if (ms_field_float(l, n, 60, 66, &a.beta) < 0)
            return ms_perr_set(err, "line %ld: bad temperature factor", in->line_no);
    } else if (n > 54 && ms_field_float(l, n, 54, 60, &a.occupancy) < 0) {
        return ms_perr_set(err, "line %ld: bad occupancy", in->line_no);
    }
    a.has = MS_HAS_POS | MS_HAS_OCCUPANCY | MS_HAS_BETA;
    ms_field(l, n, 72, 76, segid);
    /* Columns 77-78: an element symbol. Old files keep line numbers there: ignore anything
     * that is not letters. */
    ms_field(l, n, 76, 78, elem);
    for (char *p = elem; *p; p++)
        if (!((*p >= 'A' && *p <= 'Z') || (*p >= 'a' && *p <= 'z'))) {
            elem[0] = '\0';
            break;
        }
    /* Columns 79-80: formal charge such as "2+" or "1-". */
    if (n >= 80 && l[78] >= '0' && l[78] <= '9' && (l[79] == '+' || l[79] == '-')) {
        a.charge = (float)(l[78] - '0') * (l[79] == '-' ? -1.0f : 1.0f);
        a.has |= MS_HAS_CHARGE;
    }
    a.name = name;
    a.type = name;
    a.resname = resname;
    a.chain = chain;
    a.segname = segid;
    a.element = elem;
    a.hetero = hetero;

    long serial = -1;
    memcpy(serialf, l + 6, 5);
    if (ms_hy36_decode(serialf, 5, &serial) <= 0) serial = -1;
    size_t idx = (size_t)r->natoms;
    if (idx == r->serial_cap) {
        size_t cap = r->serial_cap ? r->serial_cap * 2 : 4096;
        int *ns = realloc(r->serial, cap * sizeof *ns);
        if (ns) r->serial = ns;
        char *nc = ns ? realloc(r->chain, cap) : NULL;
        if (!nc) return ms_perr_set(err, "out of memory");
        r->chain = nc;
        r->serial_cap = cap;
    }
    r->serial[idx] = (int)serial;
    r->chain[idx] = l[21];
    if (sink->add_atom(sink, &a)) return ms_perr_set(err, "out of memory at line %ld", in->line_no);
    r->natoms++;
    return MS_PLUGIN_OK;
}

static int parse_ss(const ms_lines *in, ms_struct_sink *sink, int helix, ms_perr *err)
{
    const char *l = in->line;
    size_t n = in->line_len;
    /* HELIX: chain 20, start 22-25 ins 26, end chain 32, end 34-37 ins 38, class 39-40.
     * SHEET: chain 22, start 23-26 ins 27, end chain 33, end 34-37 ins 38. */
    size_t ch0 = helix ? 19 : 21, s0 = helix ? 21 : 22, i0 = helix ? 25 : 26;
    size_t e0 = 33, ie = 37;
    if (n < 38) return MS_PLUGIN_OK; /* too short to use: ignore, as other readers do */
    int r0, r1, cls = 1;
    if (ms_field_int(l, n, s0, s0 + 4, &r0) <= 0 || ms_field_int(l, n, e0, e0 + 4, &r1) <= 0)
        return ms_perr_set(err, "line %ld: bad %s record residue numbers", in->line_no,
                           helix ? "HELIX" : "SHEET");
    char chain[2] = {l[ch0] == ' ' ? '\0' : l[ch0], '\0'};
    char code = MS_SS_EXTENDED;
    if (helix) {
        if (ms_field_int(l, n, 38, 40, &cls) < 0) cls = 1;
        code = cls == 3 ? MS_SS_PI : cls == 5 ? MS_SS_310 : MS_SS_ALPHA;
    }
    if (sink->add_ss_range(sink, code, chain, r0, l[i0], r1, l[ie]))
        return ms_perr_set(err, "out of memory");
    return MS_PLUGIN_OK;
}

/* Serial -> atom index through a sorted copy, for CONECT records. */
typedef struct serial_ix {
    int serial;
    int index;
} serial_ix;

static int cmp_serial(const void *a, const void *b)
{
    const serial_ix *x = a, *y = b;
    return (x->serial > y->serial) - (x->serial < y->serial);
}

static long find_serial(const serial_ix *ix, long n, int serial)
{
    long lo = 0, hi = n - 1;
    while (lo <= hi) {
        long mid = (lo + hi) / 2;
        if (ix[mid].serial == serial) return ix[mid].index;
        if (ix[mid].serial < serial) lo = mid + 1;
        else hi = mid - 1;
    }
    return -1;
}

typedef struct conect_list {
    int *v;       /* pairs of serials */
    size_t n, cap;
} conect_list;

static int parse_conect(const ms_lines *in, conect_list *c, ms_perr *err)
{
    const char *l = in->line;
    size_t n = in->line_len;
    long from;
    char f[6];
    if (n < 11) return MS_PLUGIN_OK;
    memcpy(f, l + 6, 5);
    if (ms_hy36_decode(f, 5, &from) <= 0)
        return ms_perr_set(err, "line %ld: bad CONECT atom serial", in->line_no);
    for (size_t col = 11; col + 5 <= n && col < 31; col += 5) {
        long to;
        int rc = ms_hy36_decode(l + col, 5, &to);
        if (rc == 0) continue;
        if (rc < 0) return ms_perr_set(err, "line %ld: bad CONECT partner serial", in->line_no);
        if (c->n + 2 > c->cap) {
            size_t nc = c->cap ? 2 * c->cap : 256;
            int *nv = realloc(c->v, nc * sizeof *nv);
            if (!nv) return ms_perr_set(err, "out of memory");
            c->v = nv;
            c->cap = nc;
        }
        c->v[c->n++] = (int)from;
        c->v[c->n++] = (int)to;
    }
    return MS_PLUGIN_OK;
}

static int add_conect_bonds(pdb_reader *r, ms_struct_sink *sink, const conect_list *c,
                            ms_perr *err)
{
    if (c->n == 0 || r->natoms == 0) return MS_PLUGIN_OK;
    serial_ix *ix = malloc((size_t)r->natoms * sizeof *ix);
    if (!ix) return ms_perr_set(err, "out of memory");
    long m = 0;
    for (long i = 0; i < r->natoms; i++)
        if (r->serial[i] >= 0) ix[m++] = (serial_ix){r->serial[i], (int)i};
    qsort(ix, (size_t)m, sizeof *ix, cmp_serial);
    for (size_t k = 0; k < c->n; k += 2) {
        long i = find_serial(ix, m, c->v[k]), j = find_serial(ix, m, c->v[k + 1]);
        if (i < 0 || j < 0) continue; /* CONECT to an atom of another model or a TER */
        if (sink->add_bond(sink, (size_t)i, (size_t)j, 1.0f)) {
            free(ix);
            return ms_perr_set(err, "out of memory");
        }
    }
    free(ix);
    return MS_PLUGIN_OK;
}

static biomt_gen *biomt_new_gen(biomt *b)
{
    biomt_gen *g = realloc(b->gen, (b->ngen + 1) * sizeof *g);
    if (!g) {
        b->failed = 1;
        return NULL;
    }
    b->gen = g;
    g = &b->gen[b->ngen++];
    memset(g, 0, sizeof *g);
    snprintf(g->id, sizeof g->id, "%s", b->cur);
    return g;
}

/* One REMARK 350 line. */
static int parse_remark350(biomt *b, const ms_lines *in, ms_perr *err)
{
    const char *l = in->line + 10;
    if (in->line_len <= 11) return MS_PLUGIN_OK;
    const char *p;
    if ((p = strstr(l, "BIOMOLECULE:"))) {
        char id[16];
        if (sscanf(p + 12, "%15s", id) == 1) snprintf(b->cur, sizeof b->cur, "%s", id);
    } else if ((p = strstr(l, "CHAINS:"))) {
        biomt_gen *g = b->ngen ? &b->gen[b->ngen - 1] : NULL;
        if (!g || g->nops || strcmp(g->id, b->cur) || strstr(l, "APPLY"))
            if (!(g = biomt_new_gen(b))) return ms_perr_set(err, "out of memory");
        for (p += 7; *p; p++)
            if (*p != ',' && *p != ' ' && strlen(g->chains) + 1 < sizeof g->chains)
                strncat(g->chains, p, 1);
    } else if ((p = strstr(l, "BIOMT")) && p[5] >= '1' && p[5] <= '3') {
        int row = p[5] - '1', n;
        double v[4];
        if (sscanf(p + 6, "%d %lf %lf %lf %lf", &n, &v[0], &v[1], &v[2], &v[3]) != 5)
            return ms_perr_set(err, "line %ld: bad REMARK 350 BIOMT record", in->line_no);
        biomt_gen *g = b->ngen ? &b->gen[b->ngen - 1] : NULL;
        if (!g) return ms_perr_set(err, "line %ld: BIOMT before APPLY ... TO CHAINS", in->line_no);
        if (row == 0) {
            double(*ops)[12] = realloc(g->ops, (g->nops + 1) * sizeof *ops);
            if (!ops) return ms_perr_set(err, "out of memory");
            g->ops = ops;
            memset(g->ops[g->nops++], 0, sizeof *ops);
        }
        if (!g->nops) return ms_perr_set(err, "line %ld: BIOMT%d before BIOMT1", in->line_no, row + 1);
        memcpy(&g->ops[g->nops - 1][4 * row], v, sizeof v);
    }
    return MS_PLUGIN_OK;
}

/* Report each generator with the ranges of the first model's atoms in its chains. */
static int report_biomt(pdb_reader *r, biomt *b, ms_struct_sink *sink, ms_perr *err)
{
    for (size_t k = 0; k < b->ngen; k++) {
        biomt_gen *g = &b->gen[k];
        size_t(*rg)[2] = NULL, nr = 0;
        for (long i = 0; i < r->natoms; i++) {
            char c = r->chain[i] == ' ' ? '-' : r->chain[i];
            if (!strchr(g->chains, c) || !c) continue;
            if (nr && rg[nr - 1][1] == (size_t)i) {
                rg[nr - 1][1]++;
                continue;
            }
            size_t(*n2)[2] = realloc(rg, (nr + 1) * sizeof *n2);
            if (!n2) {
                free(rg);
                return ms_perr_set(err, "out of memory");
            }
            rg = n2;
            rg[nr][0] = (size_t)i;
            rg[nr++][1] = (size_t)i + 1;
        }
        int rc = nr && g->nops ? sink->add_assembly(sink, g->id, nr, (const size_t(*)[2])rg,
                                                    g->nops, (const double(*)[12])g->ops) : 0;
        free(rg);
        if (rc) return ms_perr_set(err, "out of memory");
    }
    return MS_PLUGIN_OK;
}

static void biomt_free(biomt *b)
{
    for (size_t k = 0; k < b->ngen; k++) free(b->gen[k].ops);
    free(b->gen);
}

static int pdb_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    pdb_reader *r = h;
    ms_lines *in = &r->in;
    conect_list conect = {0};
    biomt bio = {0};
    int in_first = 1, seen_atoms = 0;
    const char *l;
    /* The file size tells roughly how many atoms: 81 bytes a line. */
    if (fseeko(in->fp, 0, SEEK_END) == 0) {
        long long size = ftello(in->fp);
        rewind(in->fp);
        if (size > 0) sink->reserve(sink, (size_t)(size / 81 + 16));
    }
    while ((l = ms_lines_next(in))) {
        size_t n = in->line_len;
        enum rec t = record_type(l, n);
        if (in_first) {
            switch (t) {
            case R_ATOM:
            case R_HETATM:
                if (parse_atom(r, sink, t == R_HETATM, err) != MS_PLUGIN_OK) goto fail;
                seen_atoms = 1;
                break;
            case R_ENDMDL:
            case R_END:
                if (seen_atoms) {
                    in_first = 0;
                    r->frame2 = ms_lines_tell_next(in);
                    r->frame2_line = in->line_no;
                }
                break;
            case R_CRYST1: {
                float cell[6];
                if (parse_cryst1(in, cell, err) != MS_PLUGIN_OK) goto fail;
                sink->set_cell(sink, cell);
                break;
            }
            case R_HELIX:
            case R_SHEET:
                if (parse_ss(in, sink, t == R_HELIX, err) != MS_PLUGIN_OK) goto fail;
                break;
            case R_REMARK:
                if (sink->add_remark(sink, l)) goto oom;
                if (n > 10 && !strncmp(l, "REMARK 350", 10) &&
                    parse_remark350(&bio, in, err) != MS_PLUGIN_OK)
                    goto fail;
                break;
            default:
                break;
            }
        }
        /* CONECT records usually follow the last model: read them wherever they are. */
        if (t == R_CONECT && parse_conect(in, &conect, err) != MS_PLUGIN_OK) goto fail;
        if (!in_first && (t == R_HELIX || t == R_SHEET) &&
            parse_ss(in, sink, t == R_HELIX, err) != MS_PLUGIN_OK)
            goto fail;
    }
    if (in->error) {
        ms_perr_set(err, "read error after line %ld", in->line_no);
        goto fail;
    }
    if (r->natoms == 0) {
        ms_perr_set(err, "no ATOM or HETATM records");
        goto fail;
    }
    if (add_conect_bonds(r, sink, &conect, err) != MS_PLUGIN_OK) goto fail;
    if (bio.failed) goto oom;
    if (report_biomt(r, &bio, sink, err) != MS_PLUGIN_OK) goto fail;
    biomt_free(&bio);
    free(conect.v);
    free(r->serial); /* only CONECT and REMARK 350 needed them */
    free(r->chain);
    r->chain = NULL;
    r->serial = NULL;
    r->serial_cap = 0;
    r->structure_done = 1;
    /* Position the reader at the second model for read_frame. */
    if (r->frame2 >= 0 && ms_lines_seek(in, r->frame2, r->frame2_line) != 0) {
        ms_perr_set(err, "cannot seek back to the second model");
        return MS_PLUGIN_ERROR;
    }
    r->single_model = r->frame2 < 0;
    return MS_PLUGIN_OK;
oom:
    ms_perr_set(err, "out of memory");
fail:
    free(conect.v);
    biomt_free(&bio);
    return MS_PLUGIN_ERROR;
}

static int pdb_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    pdb_reader *r = h;
    ms_lines *in = &r->in;
    if (!r->structure_done || r->single_model) return MS_PLUGIN_EOF;
    long count = 0;
    const char *l;
    while ((l = ms_lines_next(in))) {
        enum rec t = record_type(l, in->line_len);
        if (t == R_ATOM || t == R_HETATM) {
            if (count >= natoms)
                return ms_perr_set(err, "line %ld: model has more than %ld atoms", in->line_no,
                                   natoms);
            float x, y, z;
            if (parse_xyz(in, &x, &y, &z, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
            if (fr->pos) {
                fr->pos[3 * count] = x;
                fr->pos[3 * count + 1] = y;
                fr->pos[3 * count + 2] = z;
            }
            count++;
        } else if (t == R_CRYST1) {
            if (parse_cryst1(in, fr->cell, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
            fr->has_cell = 1;
        } else if ((t == R_ENDMDL || t == R_END) && count > 0) {
            break;
        }
    }
    if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
    if (count == 0) return MS_PLUGIN_EOF;
    if (count != natoms)
        return ms_perr_set(err, "line %ld: model has %ld atoms, expected %ld", in->line_no,
                           count, natoms);
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

typedef struct pdb_writer {
    ms_out out;
    long natoms;
    int count;       /* frames written */
} pdb_writer;

static void *pdb_open_write(const char *path, long natoms, ms_perr *err)
{
    pdb_writer *w = ms_out_create(sizeof *w, path, err);
    if (!w) return NULL;
    w->natoms = natoms;
    return w;
}

/* Atom names of one-letter elements start in column 14, as the format wants. */
static void format_name(const char *name, const char *elem, char out[5])
{
    size_t len = strlen(name);
    if (len < 4 && strlen(elem) <= 1) snprintf(out, 5, " %-3.3s", name);
    else snprintf(out, 5, "%-4.4s", name);
}

static int pdb_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    pdb_writer *w = h;
    ms_out *o = &w->out;
    if (f->index == 0 && v->remarks) {
        /* Keep the header records the file came with. */
        const char *p = v->remarks;
        while (*p) {
            size_t len = strcspn(p, "\n");
            if (len >= 6 && (!strncmp(p, "REMARK", 6) || !strncmp(p, "HEADER", 6) ||
                             !strncmp(p, "TITLE ", 6)))
                ms_out_printf(o, "%.*s\n", (int)(len > 80 ? 80 : len), p);
            p += len + (p[len] == '\n');
        }
    }
    if (f->cell[0] > 0 && f->cell[1] > 0 && f->cell[2] > 0)
        ms_out_printf(o, "CRYST1%9.3f%9.3f%9.3f%7.2f%7.2f%7.2f P 1           1\n", f->cell[0],
                      f->cell[1], f->cell[2], f->cell[3], f->cell[4], f->cell[5]);
    ms_out_printf(o, "MODEL     %4d\n", f->index + 1);
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        const float *p = f->pos + 3 * i;
        for (int k = 0; k < 3; k++)
            if (!(p[k] > -999.9995f && p[k] < 9999.9995f))
                return ms_perr_set(err, "atom %zu: coordinate %g does not fit PDB's 8.3 field",
                                   i + 1, (double)p[k]);
        char serial[6], resid[5], name[5];
        if (ms_hy36_encode((long)i + 1, 5, serial)) strcpy(serial, "*****");
        if (ms_hy36_encode(a.resid, 4, resid)) strcpy(resid, "****");
        format_name(a.name, a.element ? a.element : "", name);
        char elem[3];
        snprintf(elem, sizeof elem, "%.2s", a.element ? a.element : "");
        if (elem[0] && elem[1]) elem[1] = (char)(elem[1] >= 'a' ? elem[1] - 32 : elem[1]);
        else if (elem[0] && elem[0] >= 'a') elem[0] = (char)(elem[0] - 32);
        ms_out_printf(o, "%-6s%5s %4s%c%-4.4s%c%4s%c   %8.3f%8.3f%8.3f%6.2f%6.2f      %-4.4s%2s\n",
                      a.hetero ? "HETATM" : "ATOM", serial, name, a.altloc ? a.altloc : ' ',
                      a.resname, a.chain && a.chain[0] ? a.chain[0] : ' ', resid,
                      a.insertion ? a.insertion : ' ', p[0], p[1], p[2],
                      a.occupancy > 999.99f ? 999.99f : a.occupancy,
                      a.beta > 999.99f ? 999.99f : a.beta, a.segname, elem);
    }
    ms_out_printf(o, "ENDMDL\n");
    w->count++;
    return w->out.failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int pdb_close_write(void *h, ms_perr *err)
{
    pdb_writer *w = h;
    ms_out_printf(&w->out, "END\n");
    return ms_out_destroy(w, err);
}

static const ms_plugin pdb_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "pdb",
    .description = "Protein Data Bank",
    .extensions = "pdb ent",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = pdb_open_read,
    .read_structure = pdb_read_structure,
    .read_frame = pdb_read_frame,
    .close_read = pdb_close_read,
    .open_write = pdb_open_write,
    .write_frame = pdb_write_frame,
    .close_write = pdb_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &pdb_plugin; }
